//! A linear pentapod (Borràs & Thomas, *Singularity-invariant leg substitutions in pentapods*,
//! IROS 2010; Nawratil & Schicho, *Self-motions of pentapods with linear platform*, Robotica
//! 2017): five U-P-S legs whose platform joints lie on one line, the tool axis of a five-axis
//! machine, whose spin about itself is no freedom of interest. The platform is a line: located
//! by one point and a direction, five freedoms. Base anchors on a circle of radius 250 at
//! different heights; the platform joints at 0, 40, 90, 130 and 200 mm along the tool.
//!
//! Its forward kinematics has at most 8 solutions over ℂ: with p the first joint, u the unit
//! direction, s = p·p and w = p·u, each leg |p + tᵢu − aᵢ|² = Lᵢ² is linear in (s, w, p, u),
//! so the five legs leave a 3-dimensional affine family on which three quadrics (s = p·p,
//! w = p·u, u·u = 1) meet in at most 2³ points. All-modes finds 8 distinct roots, each a
//! configuration.

use super::all_modes::check_count;
use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::velocity::{input_efforts, input_rates, pivot_rates, twist, Twist, Wrench};
use linkage::{arc_length, Pose};
use linkage_tests::vec3::{add, cross, dot, scaled, sub};
use linkage_tests::{check_jacobians, max_diff, Rng};

/// A linear pentapod on the bases and legs below, with the platform (and its doc) given.
macro_rules! pentapod {
    ($(#[$doc:meta])* $name:ident, $($platform:tt)*) => {
        linkage::mechanism! {
            $(#[$doc])*
            pub struct $name;
            base {
                A1 = [250.0, 0.0, 0.0], A1t = [250.0, 1.0, 0.0],
                A2 = [77.25424859373686, 237.76412907378838, 20.0], A2t = [76.30318, 238.07314, 20.0],
                A3 = [-202.25424859373686, 146.9463130731183, -10.0], A3t = [-202.84203, 146.13729, -10.0],
                A4 = [-202.25424859373686, -146.9463130731183, 30.0], A4t = [-201.66646, -147.75533, 30.0],
                A5 = [77.25424859373686, -237.76412907378838, 5.0], A5t = [78.2053, -237.45511, 5.0],
            }
            $($platform)*
            chain leg1 = base - U(A1, axis = A1 -> A1t) - P(active L1) - S(G1) - platform;
            chain leg2 = base - U(A2, axis = A2 -> A2t) - P(active L2) - S(G2) - platform;
            chain leg3 = base - U(A3, axis = A3 -> A3t) - P(active L3) - S(G3) - platform;
            chain leg4 = base - U(A4, axis = A4 -> A4t) - P(active L4) - S(G4) - platform;
            chain leg5 = base - U(A5, axis = A5 -> A5t) - P(active L5) - S(G5) - platform;
        }
    };
}

pentapod! {
    /// Linear pentapod: a line platform on five U-P-S legs.
    LinearPentapod,
    platform(home = [0.3, -1.2, 0.0, 0.0, 0.0, 300.0]) {
        G1 = [0.0, 0.0, 0.0], G2 = [40.0, 0.0, 0.0], G3 = [90.0, 0.0, 0.0],
        G4 = [130.0, 0.0, 0.0], G5 = [200.0, 0.0, 0.0],
    }
}

const ANCHORS: [[f64; 3]; 5] = [
    [250.0, 0.0, 0.0],
    [77.25424859373686, 237.76412907378838, 20.0],
    [-202.25424859373686, 146.9463130731183, -10.0],
    [-202.25424859373686, -146.9463130731183, 30.0],
    [77.25424859373686, -237.76412907378838, 5.0],
];
/// Where each platform joint is along the tool, from the first.
const ALONG: [f64; 5] = [0.0, 40.0, 90.0, 130.0, 200.0];
const HOME_POINT: [f64; 3] = [0.0, 0.0, 300.0];

/// The tool's direction at home: the platform's x axis turned by the declared home pose.
fn home_direction() -> [f64; 3] {
    Pose::from_euler(0.3, -1.2, 0.0, [0.0; 3]).apply([1.0, 0.0, 0.0])
}

fn unit(d: [f64; 3]) -> [f64; 3] {
    scaled(d, 1.0 / dot(d, d).sqrt())
}

/// The legs' lengths for the tool through `p` along the unit `u`: the inverse kinematics in
/// closed form.
fn legs(p: [f64; 3], u: [f64; 3]) -> [f64; 5] {
    std::array::from_fn(|i| {
        let d = sub(add(p, scaled(u, ALONG[i])), ANCHORS[i]);
        dot(d, d).sqrt()
    })
}

/// Platform joint `i` in the unknowns (stored by axis).
fn joint(v: &[f64; 15], i: usize) -> [f64; 3] {
    [v[i], v[5 + i], v[10 + i]]
}

/// The tool's line in the unknowns: its first joint and its unit direction.
fn line(v: &[f64; 15]) -> ([f64; 3], [f64; 3]) {
    let p = joint(v, 0);
    (p, scaled(sub(joint(v, 4), p), 1.0 / ALONG[4]))
}

/// Every joint where the line puts it and every leg at its length.
fn assert_configuration(v: &[f64; 15], x: &[f64; 5]) {
    let (p, u) = line(v);
    assert!((dot(u, u) - 1.0).abs() < 1e-9, "direction {u:?}");
    for i in 0..5 {
        let g = joint(v, i);
        assert!(
            max_diff(&g, &add(p, scaled(u, ALONG[i]))) < 1e-7,
            "joint {i} off the line"
        );
        let d = sub(g, ANCHORS[i]);
        assert!((dot(d, d).sqrt() - x[i]).abs() < 1e-7, "leg {i}");
    }
}

/// `pose` places every joint where `v` has it, and turns the tool's x axis onto the line by
/// the least rotation: by the angle between them, about an axis square to both.
fn assert_least_turn(pose: &Pose, v: &[f64; 15]) {
    for i in 0..5 {
        let placed = pose.apply([ALONG[i], 0.0, 0.0]);
        assert!(
            max_diff(&placed, &joint(v, i)) < 1e-9,
            "joint {i}: {placed:?}"
        );
    }
    let (_, u) = line(v);
    let r = pose.rotation;
    assert!((pose.handedness() - 1.0).abs() < 1e-12);
    // trace R = 1 + 2 cos θ, and cos θ = x·u for the least rotation.
    let trace = r[0][0] + r[1][1] + r[2][2];
    assert!(
        (trace - (1.0 + 2.0 * u[0])).abs() < 1e-12,
        "{trace} for {u:?}"
    );
    let back = linkage::unknowns_from_pose(&LinearPentapod::new(), pose);
    assert!(max_diff(&back, v) < 1e-9);
}

#[test]
fn a_linear_pentapod_places_its_tool_line() {
    let sys = LinearPentapod::new();
    assert!(
        mobility_line(LinearPentapod::LISTING).contains("M = 15 + 5 − 15 = 5"),
        "{}",
        mobility_line(LinearPentapod::LISTING)
    );
    let start = sys.home_start().unwrap();
    assert!(max_diff(start.x(), &legs(HOME_POINT, home_direction())) < 1e-9);
    check_jacobians(&sys, start.v(), start.x());
    // A line has no frame, only a place and a direction: its pose turns it there by the
    // least rotation, with the spin that convention gives.
    let pose = linkage::pose_from_unknowns(&sys, start.v()).unwrap();
    assert_least_turn(&pose, start.v());
    let mut rng = Rng::new(2010);
    for case in 0..30 {
        let p = add(HOME_POINT, [0.0; 3].map(|_| rng.uniform(-30.0, 30.0)));
        let u = unit(add(
            home_direction(),
            [0.0; 3].map(|_| rng.uniform(-0.2, 0.2)),
        ));
        let x = legs(p, u);
        let sol = arc_length(&sys, &start, &x, &GENERAL_MODEL).unwrap();
        assert!(sol.is_ok(), "case {case}: {:?}", sol.status);
        assert_configuration(&sol.v, &x);
        let (q, e) = line(&sol.v);
        assert!(max_diff(&q, &p) < 1e-6, "case {case}: {q:?} vs {p:?}");
        assert!(max_diff(&e, &u) < 1e-8, "case {case}: {e:?} vs {u:?}");
        let pose = linkage::pose_from_unknowns(&sys, &sol.v).unwrap();
        assert_least_turn(&pose, &sol.v);
        // The tool line is a link `link_pose` reports on, with the same pose.
        let i = LinearPentapod::LINKS
            .iter()
            .position(|l| *l == "platform")
            .unwrap();
        assert_eq!(sys.link_pose(i, &sol.v, &x), Some(pose));
        if case < 3 {
            check_jacobians(&sys, &sol.v, &x);
            check_inverse(&sys, &sol.v, &x, start.x(), 1e-7);
        }
    }
}

/// The tool line's velocity: ω square to the line (its spin is no freedom), every joint's
/// velocity what the twist gives it, the line's direction moving as ω × u (finite differences
/// of forward kinematics), the input rates back from the twist, and a spin about the line left
/// over by the inputs and felt by no actuator.
#[test]
fn a_linear_pentapod_has_the_velocity_of_its_tool_line() {
    let sys = LinearPentapod::new();
    let start = sys.home_start().unwrap();
    let (v, x) = (*start.v(), *start.x());
    let origin = linkage::pose_from_unknowns(&sys, &v).unwrap().translation;
    let (_, u) = line(&v);
    let mut rng = Rng::new(2017);
    for case in 0..10 {
        let xdot: [f64; 5] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let t = twist(&sys, &v, &x, &xdot).unwrap();
        let vdot = pivot_rates(&sys, &v, &x, &xdot).unwrap();
        let w = t.angular;
        assert!(
            dot(w, u).abs() < 1e-12 * dot(w, w).sqrt(),
            "case {case}: spin {w:?}"
        );
        for i in 0..5 {
            let (made, want) = (t.at(origin, joint(&v, i)), joint(&vdot, i));
            assert!(
                max_diff(&made, &want) < 1e-9 * (1.0 + dot(want, want).sqrt()),
                "case {case}, joint {i}"
            );
        }
        // The direction's rate by central differences of forward kinematics along ±h ẋ.
        let h = 1e-4;
        let at = |s: f64| {
            let target: [f64; 5] = std::array::from_fn(|j| x[j] + s * h * xdot[j]);
            let sol = arc_length(&sys, &start, &target, &GENERAL_MODEL).unwrap();
            assert!(sol.is_ok());
            line(&sol.v).1
        };
        let du = scaled(sub(at(1.0), at(-1.0)), 0.5 / h);
        assert!(
            max_diff(&du, &cross(w, u)) < 1e-6,
            "case {case}: {du:?} vs {:?}",
            cross(w, u)
        );
        let back = input_rates(&sys, &v, &x, &t).unwrap();
        assert!(
            max_diff(&back.rates, &xdot) < 1e-9,
            "case {case}: {:?}",
            back.rates
        );
        let left = back.left_over;
        assert!(
            max_diff(&left.angular, &[0.0; 3]) < 1e-9 && max_diff(&left.linear, &[0.0; 3]) < 1e-9
        );
        // A spin about the line (through the origin, on it) asked for besides: the same rates,
        // the spin left over.
        let spun = Twist {
            angular: add(w, scaled(u, 0.3)),
            linear: t.linear,
        };
        let back = input_rates(&sys, &v, &x, &spun).unwrap();
        assert!(
            max_diff(&back.rates, &xdot) < 1e-9,
            "case {case}: {:?}",
            back.rates
        );
        assert!(max_diff(&back.left_over.angular, &scaled(u, -0.3)) < 1e-9);
        assert!(max_diff(&back.left_over.linear, &[0.0; 3]) < 1e-9);
    }
    // Hostile configurations: not finite, or the line's joints on one point.
    let mut bad = v;
    bad[4] = f64::NAN;
    assert!(linkage::pose_from_unknowns(&sys, &bad).is_none());
    assert_eq!(
        twist(&sys, &bad, &x, &[1.0; 5]),
        Err(linkage::velocity::VelocityError::NonFinite)
    );
    let mut collapsed = v;
    for axis in 0..3 {
        collapsed[axis * 5 + 4] = collapsed[axis * 5];
    }
    assert!(linkage::pose_from_unknowns(&sys, &collapsed).is_none());
    assert_eq!(
        twist(&sys, &collapsed, &x, &[1.0; 5]),
        Err(linkage::velocity::VelocityError::NoFrame)
    );
    // A moment about the tool axis turns the tool, not the legs.
    let about_line = Wrench {
        moment: scaled(u, 5.0),
        force: [0.0; 3],
    };
    let efforts = input_efforts(&sys, &v, &x, &about_line).unwrap();
    assert!(max_diff(&efforts, &[0.0; 5]) < 1e-12, "{efforts:?}");
}

#[test]
fn a_linear_pentapod_has_eight_assembly_modes() {
    let sys = LinearPentapod::new();
    let at = legs(
        add(HOME_POINT, [10.0, -5.0, 20.0]),
        unit(add(home_direction(), [0.1, 0.0, -0.1])),
    );
    let (count, most) = check_count(
        "linear pentapod",
        sys,
        &[LinearPentapod::HOME_INPUTS, at],
        400.0,
        |_| false,
    );
    assert_eq!(count, 8);
    assert!(most <= 8);
    let modes = linkage::modes::AllModes::<_, 15, 5, 64>::new(
        LinearPentapod::new(),
        &linkage::modes::ModesOptions::default(),
    )
    .unwrap();
    let mut roots = Box::new(linkage::modes::Roots::<15, 64>::new());
    for x in [LinearPentapod::HOME_INPUTS, at] {
        modes.solve(&x, &mut roots).unwrap();
        assert_eq!(roots.roots(), 8);
        assert!(!roots.real().is_empty());
        for r in roots.real() {
            assert_configuration(&r.v, &x);
        }
    }
}

pentapod! {
    /// The linear pentapod declared with its tool along the base's x axis at 300 mm and its
    /// home given by the legs' lengths of another line (turned 0.25 rad in yaw and 0.15 in
    /// pitch, its first joint at [10, −5, 310] − 100 u).
    PentapodHomeByInputs,
    platform(home = inputs(L1 = 468.209733, L2 = 413.782771, L3 = 410.210217, L4 = 395.315412, L5 = 388.732841)) {
        G1 = [-100.0, 0.0, 300.0], G2 = [-60.0, 0.0, 300.0], G3 = [-10.0, 0.0, 300.0],
        G4 = [30.0, 0.0, 300.0], G5 = [100.0, 0.0, 300.0],
    }
}

/// `home = inputs(...)` on a line platform of five joints: the start is the configuration at
/// the declared legs, on the turned line. The home pose was once computed with the line
/// unturned wherever more than two joints were on it: `home_start` then put the tool along
/// the base's x axis through the right first joint, at legs 10–21 mm off the declared ones.
#[test]
fn a_linear_pentapod_starts_at_its_declared_legs() {
    let declared = [468.209733, 413.782771, 410.210217, 395.315412, 388.732841];
    let sys = PentapodHomeByInputs::new();
    let start = sys.home_start().unwrap();
    assert!(max_diff(start.x(), &declared) < 1e-9, "{:?}", start.x());
    assert!(max_diff(start.v(), &PentapodHomeByInputs::HOME_V) < 1e-9);
    let (yaw, pitch) = (0.25f64, 0.15f64);
    let u = [
        yaw.cos() * pitch.cos(),
        yaw.sin() * pitch.cos(),
        -pitch.sin(),
    ];
    let first = [start.v()[0], start.v()[5], start.v()[10]];
    let last = [start.v()[4], start.v()[9], start.v()[14]];
    assert!(max_diff(&scaled(sub(last, first), 1.0 / 200.0), &u) < 1e-7);
    assert!(max_diff(&add(first, scaled(u, 100.0)), &[10.0, -5.0, 310.0]) < 1e-5);
}
