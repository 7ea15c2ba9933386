//! A planar 3-RRR driven at its middle joints: the actuated revolute pairs join two moving links
//! (the proximal and the distal link of each leg), so the angle they set is relative to a link
//! whose own position is solved for. Against closed-form inverse kinematics (the elbow where
//! two circles meet).

use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::{arc_length, det_b, pose_from_unknowns, Status};
use linkage_tests::straight_path_truth as straight_segment;
use linkage_tests::{check_factorization, check_jacobians, Rng};

/// The planar 3-RRR's geometry, declared once for the two ways of driving it (the chains say
/// which joints are active): base joints at radius rb, elbows at radius re turned by d from
/// them, platform joints at radius rp; every axis vertical.
macro_rules! planar_rrr {
    ($(#[$doc:meta])* $name:ident; $($chains:tt)*) => {
        linkage::mechanism! {
            $(#[$doc])*
            pub struct $name;
            params {
                rb = 200.0, rp = 50.0, re = 130.0, d = 0.4,
                p1 = pi / 2.0, p2 = pi / 2.0 + 2.0 * pi / 3.0, p3 = pi / 2.0 + 4.0 * pi / 3.0,
            }
            base {
                A1 = [rb * cos(p1), rb * sin(p1), 0.0], A1z = [rb * cos(p1), rb * sin(p1), 1.0],
                A2 = [rb * cos(p2), rb * sin(p2), 0.0], A2z = [rb * cos(p2), rb * sin(p2), 1.0],
                A3 = [rb * cos(p3), rb * sin(p3), 0.0], A3z = [rb * cos(p3), rb * sin(p3), 1.0],
            }
            // Turned by 0.5 rad at home: with the platform joints radial, every leg's line A–W would
            // pass through the centre, a singularity of the middle-driven 3-RRR.
            platform(home = [0.5, 0.0, 0.0, 0.0, 0.0, 0.0]) {
                W1 = [rp * cos(p1), rp * sin(p1), 0.0], W1z = [rp * cos(p1), rp * sin(p1), 1.0],
                W2 = [rp * cos(p2), rp * sin(p2), 0.0], W2z = [rp * cos(p2), rp * sin(p2), 1.0],
                W3 = [rp * cos(p3), rp * sin(p3), 0.0], W3z = [rp * cos(p3), rp * sin(p3), 1.0],
            }
            link proximal1 { C1 = [re * cos(p1 + d), re * sin(p1 + d), 0.0], C1z = [re * cos(p1 + d), re * sin(p1 + d), 1.0] }
            link proximal2 { C2 = [re * cos(p2 + d), re * sin(p2 + d), 0.0], C2z = [re * cos(p2 + d), re * sin(p2 + d), 1.0] }
            link proximal3 { C3 = [re * cos(p3 + d), re * sin(p3 + d), 0.0], C3z = [re * cos(p3 + d), re * sin(p3 + d), 1.0] }
            link distal1 { } link distal2 { } link distal3 { }
            $($chains)*
        }
    };
}

planar_rrr! {
    /// A planar 3-RRR driven at its middle joints.
    MiddleRrr;
    chain leg1 = base - R(passive, axis = A1 -> A1z) - proximal1 - R(active q1, axis = C1 -> C1z) - distal1 - R(passive, axis = W1 -> W1z) - platform;
    chain leg2 = base - R(passive, axis = A2 -> A2z) - proximal2 - R(active q2, axis = C2 -> C2z) - distal2 - R(passive, axis = W2 -> W2z) - platform;
    chain leg3 = base - R(passive, axis = A3 -> A3z) - proximal3 - R(active q3, axis = C3 -> C3z) - distal3 - R(passive, axis = W3 -> W3z) - platform;
}

const RB: f64 = 200.0;
const RP: f64 = 50.0;
const RE: f64 = 130.0;
const D: f64 = 0.4;
const YAW: f64 = 0.5;

fn angle(i: usize) -> f64 {
    std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * i as f64 / 3.0
}

fn polar(r: f64, a: f64) -> [f64; 2] {
    [r * a.cos(), r * a.sin()]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

fn heading(a: [f64; 2]) -> f64 {
    a[1].atan2(a[0])
}

fn wrap(t: f64) -> f64 {
    let turn = 2.0 * std::f64::consts::PI;
    (t + std::f64::consts::PI).rem_euclid(turn) - std::f64::consts::PI
}

/// Leg i at a planar pose (φ, x, y): base joint, elbow, platform joint, with the elbow on the
/// side of the line A–W it is on at home (`None` out of reach).
fn leg(i: usize, pose: [f64; 3]) -> Option<[[f64; 2]; 3]> {
    let a = polar(RB, angle(i));
    let c0 = polar(RE, angle(i) + D);
    let w0 = polar(RP, angle(i) + YAW);
    let (l1, l2) = (norm(sub(c0, a)), norm(sub(w0, c0)));
    let side = cross(sub(w0, a), sub(c0, a)).signum();
    let w = {
        let [x, y] = polar(RP, angle(i) + pose[0]);
        [x + pose[1], y + pose[2]]
    };
    // Circles (a, l1) and (w, l2).
    let dv = sub(w, a);
    let dist = norm(dv);
    let along = (l1 * l1 - l2 * l2 + dist * dist) / (2.0 * dist);
    let h2 = l1 * l1 - along * along;
    if h2 < 0.0 {
        return None;
    }
    let (u, n) = ([dv[0] / dist, dv[1] / dist], [-dv[1] / dist, dv[0] / dist]);
    let h = h2.sqrt();
    let elbow = |s: f64| {
        [
            a[0] + along * u[0] + s * h * n[0],
            a[1] + along * u[1] + s * h * n[1],
        ]
    };
    let c = [1.0, -1.0]
        .into_iter()
        .map(elbow)
        .find(|c| cross(dv, sub(*c, a)).signum() == side)?;
    Some([a, c, w])
}

/// The middle joints' angles at a planar pose: the distal link's heading less the proximal
/// link's, from their values at home (positive counterclockwise, about +z).
fn middle_inverse(pose: [f64; 3]) -> Option<[f64; 3]> {
    let mut q = [0.0; 3];
    for (i, qi) in q.iter_mut().enumerate() {
        let [a, c, w] = leg(i, pose)?;
        let [a0, c0, w0] = leg(i, [YAW, 0.0, 0.0])?;
        let relative =
            |a: [f64; 2], c: [f64; 2], w: [f64; 2]| heading(sub(w, c)) - heading(sub(c, a));
        *qi = wrap(relative(a, c, w) - relative(a0, c0, w0));
    }
    Some(q)
}

#[test]
fn middle_rrr_models_with_three_freedoms_and_exact_jacobians() {
    let rrr = MiddleRrr::new();
    assert_eq!(
        mobility_line(MiddleRrr::LISTING),
        "mobility: rank of ∂F/∂(v, x) at home: M = 36 + 3 − 36 = 3 (Grübler–Kutzbach says -3)"
    );
    let start = rrr.home_start().unwrap();
    assert!(linkage_tests::max_diff(start.x(), &[0.0; 3]) < 1e-12);
    check_jacobians(&rrr, start.v(), start.x());
    check_factorization(&rrr, start.v(), start.x());
    // Home: the closed-form inverse reads zero.
    let zero = middle_inverse([YAW, 0.0, 0.0]).unwrap();
    assert!(linkage_tests::max_diff(&zero, &[0.0; 3]) < 1e-12);
}

#[test]
fn middle_rrr_forward_kinematics_against_inverse() {
    let rrr = MiddleRrr::new();
    let start = rrr.home_start().unwrap();
    let det0 = det_b(&rrr, start.v(), start.x());
    let mut rng = Rng::new(71);
    let mut first = true;
    let mut checked = 0;
    while checked < 60 {
        let pose = [
            YAW + rng.uniform(-0.15, 0.15),
            rng.uniform(-20.0, 20.0),
            rng.uniform(-20.0, 20.0),
        ];
        let Some(q) = middle_inverse(pose) else {
            continue;
        };
        let sol = arc_length(&rrr, &start, &q, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{pose:?}: q = {q:?}");
        if first {
            check_jacobians(&rrr, &sol.v, &q);
            first = false;
        }
        let got = pose_from_unknowns(&rrr, &sol.v).unwrap();
        let [yaw, pitch, roll] = got.euler();
        assert!(
            (yaw - pose[0]).abs() < 1e-8,
            "{pose:?}: yaw {yaw}, q = {q:?}"
        );
        assert!(pitch.abs() < 1e-9 && roll.abs() < 1e-9, "stays planar");
        let t = got.translation;
        assert!(
            (t[0] - pose[1]).abs() < 1e-7 && (t[1] - pose[2]).abs() < 1e-7 && t[2].abs() < 1e-9,
            "{pose:?}: {t:?}"
        );
        // The same branch all the way: B keeps its sign.
        assert!(det_b(&rrr, &sol.v, &q) * det0 > 0.0);
        check_inverse(&rrr, &sol.v, &q, &MiddleRrr::HOME_INPUTS, 1e-8);
        checked += 1;
    }
}

#[test]
fn middle_rrr_input_is_the_distal_links_turn_relative_to_the_proximal() {
    // The convention: q_i = 0 at home, positive turning distal link i counterclockwise
    // relative to proximal link i (right-handed about C_i -> C_iz, +z).
    let rrr = MiddleRrr::new();
    let start = rrr.home_start().unwrap();
    let link = |name: &str| MiddleRrr::LINKS.iter().position(|l| *l == name).unwrap();
    let mut rng = Rng::new(72);
    for _ in 0..10 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.1, 0.1));
        let sol = arc_length(&rrr, &start, &q, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged);
        for (i, qi) in q.iter().enumerate() {
            let proximal = rrr
                .link_pose(link(&format!("proximal{}", i + 1)), &sol.v, &q)
                .unwrap();
            let distal = rrr
                .link_pose(link(&format!("distal{}", i + 1)), &sol.v, &q)
                .unwrap();
            let turn = wrap(distal.euler()[0] - proximal.euler()[0]);
            assert!((turn - qi).abs() < 1e-9, "leg {i}: {turn} vs {qi}");
        }
    }
}

planar_rrr! {
    /// The same planar 3-RRR driven at its base joints, as most are built.
    BaseRrr;
    chain leg1 = base - R(active q1, axis = A1 -> A1z) - proximal1 - R(passive, axis = C1 -> C1z) - distal1 - R(passive, axis = W1 -> W1z) - platform;
    chain leg2 = base - R(active q2, axis = A2 -> A2z) - proximal2 - R(passive, axis = C2 -> C2z) - distal2 - R(passive, axis = W2 -> W2z) - platform;
    chain leg3 = base - R(active q3, axis = A3 -> A3z) - proximal3 - R(passive, axis = C3 -> C3z) - distal3 - R(passive, axis = W3 -> W3z) - platform;
}

/// The base joints' angles at a planar pose: each proximal link's heading from its value at
/// home, the elbow on its home side (positive counterclockwise, about +z).
fn base_inverse(pose: [f64; 3]) -> Option<[f64; 3]> {
    let mut q = [0.0; 3];
    for (i, qi) in q.iter_mut().enumerate() {
        let [a, c, _] = leg(i, pose)?;
        let [a0, c0, _] = leg(i, [YAW, 0.0, 0.0])?;
        *qi = wrap(heading(sub(c, a)) - heading(sub(c0, a0)));
    }
    Some(q)
}

/// The elbows where the cranks put them: with the elbows fixed, the platform hangs from them
/// by the three distal links, a 3-RPR of fixed legs.
fn base_rrr_as_rpr(q: [f64; 3]) -> (super::planar_rpr::Rpr, [f64; 3]) {
    let elbow = |i: usize| {
        let a = polar(RB, angle(i));
        let arm = sub(polar(RE, angle(i) + D), a);
        let (s, c) = q[i].sin_cos();
        [
            a[0] + c * arm[0] - s * arm[1],
            a[1] + s * arm[0] + c * arm[1],
        ]
    };
    let distal = |i: usize| norm(sub(polar(RP, angle(i) + YAW), polar(RE, angle(i) + D)));
    (
        super::planar_rpr::Rpr {
            a: [0, 1, 2].map(elbow),
            g: [0, 1, 2].map(|i| polar(RP, angle(i))),
        },
        [0, 1, 2].map(distal),
    )
}

/// Forward kinematics by continuation from home against the closed-form inverse, on the same
/// branch all the way; then every assembly mode at crank angles from random poses: 6 complex
/// roots (the elbows fixed, a 3-RPR's sextic), the real ones exactly those the 3-RPR's scan
/// finds, each with its distal links at their lengths, the generating pose among them.
#[test]
fn base_rrr_forward_kinematics_and_all_modes() {
    use linkage::modes::{AllModes, ModesOptions, Roots};
    let rrr = BaseRrr::new();
    let start = rrr.home_start().unwrap();
    assert!(linkage_tests::max_diff(start.x(), &[0.0; 3]) < 1e-12);
    check_jacobians(&rrr, start.v(), start.x());
    check_factorization(&rrr, start.v(), start.x());
    let det0 = det_b(&rrr, start.v(), start.x());
    let modes = AllModes::<_, 18, 3, 16>::new(rrr.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 6, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<18, 16>::new());
    let mut rng = Rng::new(73);
    let (mut checked, mut real_total, mut other_mode) = (0, 0, 0);
    while checked < 30 {
        let pose = [
            YAW + rng.uniform(-0.15, 0.15),
            rng.uniform(-20.0, 20.0),
            rng.uniform(-20.0, 20.0),
        ];
        let Some(q) = base_inverse(pose) else {
            continue;
        };
        let sol = arc_length(&rrr, &start, &q, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{pose:?}: q = {q:?}");
        // The start's branch along the straight segment, by many small Newton steps: this
        // 3-RRR is cuspidal (two assembly modes with one sign of det B can share the inputs),
        // so the pose the inputs came from need not be the one on the branch from home.
        let (truth, flips) = straight_segment(&rrr, &start, &q, 2000);
        assert_eq!(flips, 0, "{pose:?}: the segment meets a singularity");
        assert!(
            linkage_tests::max_diff(&sol.v, &truth) < 1e-7,
            "{pose:?}: not the start's branch"
        );
        let got = pose_from_unknowns(&rrr, &sol.v).unwrap();
        let [yaw, pitch, roll] = got.euler();
        let t = got.translation;
        assert!(pitch.abs() < 1e-9 && roll.abs() < 1e-9 && t[2].abs() < 1e-9);
        assert!(det_b(&rrr, &sol.v, &q) * det0 > 0.0, "{pose:?}: branch");
        let generating = (yaw - pose[0]).abs() < 1e-7
            && (t[0] - pose[1]).abs() < 1e-6
            && (t[1] - pose[2]).abs() < 1e-6;
        other_mode += usize::from(!generating);
        check_inverse(&rrr, &sol.v, &q, &BaseRrr::HOME_INPUTS, 1e-8);

        modes.solve(&q, &mut roots).unwrap();
        assert!(roots.is_complete(), "{pose:?}");
        let (rpr, distal) = base_rrr_as_rpr(q);
        assert_eq!(
            roots.real().len(),
            rpr.scanned_real_modes(distal),
            "{pose:?}"
        );
        rpr.check_real_roots(roots.real(), distal);
        real_total += roots.real().len();
        assert!(
            roots.real().iter().any(|r| {
                let p = r.pose.unwrap();
                (p.euler()[0] - pose[0]).abs() < 1e-7
                    && (p.translation[0] - pose[1]).abs() < 1e-6
                    && (p.translation[1] - pose[2]).abs() < 1e-6
            }),
            "{pose:?}: the generating pose is not among the real modes"
        );
        checked += 1;
    }
    println!(
        "base-driven 3-RRR: 6 complex roots; 30 random poses, {real_total} real modes, as the 3-RPR scan found; continuation from home on the straight segment's branch every time, {other_mode} of them in another assembly mode than the pose the inputs came from"
    );
}
