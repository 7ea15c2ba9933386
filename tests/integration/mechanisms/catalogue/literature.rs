//! Mechanisms of the literature no other file declares, each against ground truth written here
//! apart from the library (closed-form inverse and forward kinematics, an orientation scan),
//! and the published number of assembly modes where there is one:
//!
//! - a spherical 5R (two freedoms): two assembly modes at given inputs, the output axis where
//!   two cones about the elbows' axes meet (Ouerfelli & Kumar, "Optimization of a spherical
//!   five-bar parallel drive linkage", J. Mech. Design 116, 1994);
//! - a planar 3-PRR (three slides on the base, rods of fixed length): at given slides, the
//!   3-RPR's direct problem, at most six assembly modes, a sextic (Gosselin, Sefrioui & Richard,
//!   "Polynomial solutions for the direct kinematic problem of planar three-degree-of-freedom
//!   parallel manipulators", Mech. Mach. Theory 27, 1992);
//! - Tsai & Joshi's translational 3-RUU (cranks, rods between U pairs whose outer axes are
//!   parallel to the crank's and whose inner axes are parallel to each other): the platform
//!   translates, its position where three spheres meet (two solutions);
//! - a 6-PUS on parallel rails after the Hexaglide (Honegger, Codourey & Burdet 1997):
//!   sliders on rails, a U at each slider, a rod to a ball on the platform.
//!
//! Not run here: `AllModes` on the 3-RUU (672 complex roots, 80 real at one input, each a
//! placement; 16–28 s to build the start set in the tests' profile).
//!
//! The dimensions are ours.

use super::{check_inverse, point, GENERAL_MODEL};
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage::reference::straight_segment;
use linkage::{
    arc_length, det_b, pose_from_unknowns, Mechanism, Pose, Solution, Start, Status, Tracker,
};
use linkage_tests::vec3::{add, cross, dot, scaled, sub};
use linkage_tests::{check_factorization, check_jacobians, Rng};

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    scaled(a, 1.0 / norm(a))
}

/// `sol`, continuation's answer from `start` to `x`, against the straight input segment's own
/// truth in `steps` fine steps: where the segment meets a sign change of det B, `sol` must not
/// be ok (and `false` says the case has no truth to compare further); else it must have
/// converged onto that truth, to 1e-6.
fn against_the_segment<S: Mechanism<N, M>, const N: usize, const M: usize>(
    m: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    sol: &Solution<N>,
    steps: usize,
    case: &str,
) -> bool {
    let (truth, flips) = straight_segment(m, start, x, steps);
    if flips > 0 {
        assert!(!sol.is_ok(), "{case}: ok across a fold");
        return false;
    }
    assert_eq!(sol.status, Status::Converged, "{case}");
    assert!(linkage_tests::max_diff(&sol.v, &truth) < 1e-6, "{case}");
    true
}

/// Rodrigues: `p` turned by `q` about the unit axis `k` through the origin.
fn turn(p: [f64; 3], k: [f64; 3], q: f64) -> [f64; 3] {
    let (s, c) = q.sin_cos();
    add(
        add(scaled(p, c), scaled(cross(k, p), s)),
        scaled(k, dot(k, p) * (1.0 - c)),
    )
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(sub(a, b))
}

// ---------------------------------------------------------------------------------------------
// Spherical 5R. Five R pairs whose axes meet at the centre O (the origin): base axes u1, u2,
// elbows w1, w2, and the output axis p joining the two distal links (the platform is the
// second distal link). Each axis is declared by its points at r and 2r along it.
const SR: f64 = 100.0;
const U1: [f64; 3] = [-0.5, 0.0, 0.866_025_403_784_438_6];
const U2: [f64; 3] = [0.5, 0.0, 0.866_025_403_784_438_6];

fn w1_home() -> [f64; 3] {
    unit([0.8, 0.7, 0.5])
}
fn w2_home() -> [f64; 3] {
    unit([-0.2, -0.6, 0.8])
}
fn p_home() -> [f64; 3] {
    unit([0.5, -0.5, -0.2])
}

linkage::mechanism! {
    /// A spherical five-bar: two driven R on the base, every axis through the origin.
    pub struct Spherical5R;
    params {
        r = 100.0, s3 = sqrt(3.0) / 2.0,
        n1 = sqrt(0.64 + 0.49 + 0.25), n2 = sqrt(0.04 + 0.36 + 0.64), np = sqrt(0.25 + 0.25 + 0.04),
    }
    base {
        U1 = [-0.5 * r, 0.0, s3 * r], U1f = [-1.0 * r, 0.0, 2.0 * s3 * r],
        U2 = [0.5 * r, 0.0, s3 * r], U2f = [1.0 * r, 0.0, 2.0 * s3 * r],
    }
    platform {
        P = [0.5 * r / np, -0.5 * r / np, -0.2 * r / np], Pf = [1.0 * r / np, -1.0 * r / np, -0.4 * r / np],
        W2 = [-0.2 * r / n2, -0.6 * r / n2, 0.8 * r / n2], W2f = [-0.4 * r / n2, -1.2 * r / n2, 1.6 * r / n2],
    }
    link prox1 { W1 = [0.8 * r / n1, 0.7 * r / n1, 0.5 * r / n1], W1f = [1.6 * r / n1, 1.4 * r / n1, 1.0 * r / n1] }
    link prox2 { }
    link dist1 { }
    chain left = base - R(active q1, axis = U1 -> U1f) - prox1 - R(passive, axis = W1 -> W1f) - dist1 - R(passive, axis = P -> Pf) - platform;
    chain right = base - R(active q2, axis = U2 -> U2f) - prox2 - R(passive, axis = W2 -> W2f) - platform;
}

/// The spherical 5R in closed form: the output axis p (unit) at inputs q, on the side
/// `side` of the plane of the two elbows (the sign of det[w1, w2, p]); `None` where the two
/// cones about the elbows do not meet. Both solutions with `side` = ±1.
fn sr_closed_form(q: [f64; 2], side: f64) -> Option<[f64; 3]> {
    let (w10, w20, p0) = (w1_home(), w2_home(), p_home());
    let b1 = turn(w10, U1, q[0]);
    let b2 = turn(w20, U2, q[1]);
    let (c1, c2) = (dot(w10, p0), dot(w20, p0));
    // p = α b1 + β b2 + γ b1×b2 with p·b1 = c1, p·b2 = c2, |p| = 1.
    let g = dot(b1, b2);
    let det = 1.0 - g * g;
    let alpha = (c1 - g * c2) / det;
    let beta = (c2 - g * c1) / det;
    let n = cross(b1, b2);
    let in_plane = add(scaled(b1, alpha), scaled(b2, beta));
    let rest = 1.0 - dot(in_plane, in_plane);
    if !(rest > 0.0) {
        return None;
    }
    let gamma = side * (rest / dot(n, n)).sqrt();
    Some(add(in_plane, scaled(n, gamma)))
}

fn sr_side() -> f64 {
    dot(cross(w1_home(), w2_home()), p_home()).signum()
}

/// The output point P at v against the closed form on the home side, and every axis still
/// through the centre at its declared distance.
fn sr_check<const N: usize>(v: &[f64; N], q: [f64; 2], at: &str) -> f64
where
    Spherical5R: Mechanism<N, 2>,
{
    let truth = scaled(sr_closed_form(q, sr_side()).expect(at), SR);
    let p = point::<Spherical5R, N, 2>(v, "P");
    let pf = point::<Spherical5R, N, 2>(v, "Pf");
    let err = dist(p, truth).max(dist(pf, scaled(truth, 2.0)));
    assert!(err < 1e-7, "{at}: P at {p:?}, closed form {truth:?}");
    err
}

#[test]
fn spherical_5r_against_its_closed_form() {
    let m = Spherical5R::new();
    assert_eq!(Spherical5R::INPUTS, ["q1", "q2"]);
    let line = super::mobility_line(Spherical5R::LISTING);
    assert!(line.contains(" = 2"), "{line}");
    let start = m.home_start().unwrap();
    assert!(dist(sr_closed_form([0.0, 0.0], sr_side()).unwrap(), p_home()) < 1e-12);
    check_jacobians(&m, start.v(), start.x());
    check_factorization(&m, start.v(), start.x());
    let mut rng = Rng::new(5_1994);
    let mut worst: f64 = 0.0;
    let mut converged = 0;
    for case in 0..30 {
        let q = [rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)];
        let sol = arc_length(&m, &start, &q, &GENERAL_MODEL).unwrap();
        if !against_the_segment(&m, &start, &q, &sol, 2000, &format!("case {case} {q:?}")) {
            continue;
        }
        worst = worst.max(sr_check(&sol.v, q, &format!("case {case}")));
        check_jacobians(&m, &sol.v, &q);
        check_inverse(&m, &sol.v, &q, &Spherical5R::HOME_INPUTS, 1e-8);
        converged += 1;
    }
    assert!(converged >= 20, "{converged}");
    // The tracker along a loop.
    let mut tracker = Tracker::new(m.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let t = k as f64 * 0.157;
        let q = [0.4 * t.sin(), 0.3 * (1.3 * t).sin()];
        let s = tracker
            .update(&q)
            .unwrap_or_else(|e| panic!("{q:?}: {e:?}"));
        worst = worst.max(sr_check(&s.v, q, &format!("tracker {q:?}")));
    }
    println!("spherical 5R: {converged} of 30 converged, worst error {worst:.1e} mm");
}

#[test]
fn spherical_5r_has_two_assembly_modes() {
    let m = Spherical5R::new();
    let modes = AllModes::<_, _, 2, 64>::new(m.clone(), &ModesOptions::default()).unwrap();
    let mut roots = Box::new(Roots::new());
    let mut rng = Rng::new(77);
    for _ in 0..5 {
        let q = [rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6)];
        modes.solve(&q, &mut roots).unwrap();
        assert!(roots.is_complete(), "{q:?}");
        let real: Vec<[f64; 3]> = roots
            .real()
            .iter()
            .map(|r| {
                assert!(r.residual < 1e-7);
                unit(point::<Spherical5R, _, 2>(&r.v, "P"))
            })
            .collect();
        let truth: Vec<[f64; 3]> = [1.0, -1.0]
            .iter()
            .filter_map(|s| sr_closed_form(q, *s))
            .collect();
        println!(
            "spherical 5R at {q:?}: {} complex roots, {} real, closed form {}",
            modes.start_count(),
            real.len(),
            truth.len()
        );
        for t in &truth {
            assert!(
                real.iter().any(|p| dist(*p, *t) < 1e-7),
                "{q:?}: {t:?} missed"
            );
        }
        for p in &real {
            assert!(
                truth.iter().any(|t| dist(*p, *t) < 1e-7),
                "{q:?}: {p:?} is no placement"
            );
        }
    }
    assert_eq!(modes.start_count(), 2);
}

// ---------------------------------------------------------------------------------------------
// Planar 3-PRR: three rails along the sides of a triangle on the base, a slider on each with a
// vertical hinge carrying a rod of fixed length to a hinge on the platform.
const PRR_RAIL: [[f64; 2]; 3] = [[-200.0, -100.0], [200.0, -100.0], [0.0, 180.0]];
const PRR_SLIDER: [[f64; 2]; 3] = [[-95.4, -100.0], [137.3, -12.2], [-98.4, 42.2]];
const PRR_PLAT: [[f64; 2]; 3] = [[-30.0, -20.0], [35.0, -15.0], [0.0, 40.0]];
const PRR_HOME: [f64; 3] = [0.2, 10.0, 5.0];

linkage::mechanism! {
    /// A planar 3-PRR: slides along the base triangle's sides driven.
    pub struct PlanarPrr;
    base {
        R1 = [-200.0, -100.0, 0.0], R1e = [200.0, -100.0, 0.0],
        R2 = [200.0, -100.0, 0.0], R2e = [0.0, 180.0, 0.0],
        R3 = [0.0, 180.0, 0.0], R3e = [-200.0, -100.0, 0.0],
    }
    platform(home = [0.2, 0.0, 0.0, 10.0, 5.0, 0.0]) {
        B1 = [-30.0, -20.0, 0.0], B1z = [-30.0, -20.0, 100.0],
        B2 = [35.0, -15.0, 0.0], B2z = [35.0, -15.0, 100.0],
        B3 = [0.0, 40.0, 0.0], B3z = [0.0, 40.0, 100.0],
    }
    link slider1 { S1 = [-95.4, -100.0, 0.0], S1z = [-95.4, -100.0, 100.0] }
    link slider2 { S2 = [137.3, -12.2, 0.0], S2z = [137.3, -12.2, 100.0] }
    link slider3 { S3 = [-98.4, 42.2, 0.0], S3z = [-98.4, 42.2, 100.0] }
    chain leg1 = base - P(active d1, axis = R1 -> R1e) - slider1 - R(passive, axis = S1 -> S1z) - R(passive, axis = B1 -> B1z) - platform;
    chain leg2 = base - P(active d2, axis = R2 -> R2e) - slider2 - R(passive, axis = S2 -> S2z) - R(passive, axis = B2 -> B2z) - platform;
    chain leg3 = base - P(active d3, axis = R3 -> R3e) - slider3 - R(passive, axis = S3 -> S3z) - R(passive, axis = B3 -> B3z) - platform;
}

fn rot2(p: [f64; 2], a: f64) -> [f64; 2] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

fn prr_rail_dir(i: usize) -> [f64; 2] {
    let (a, b) = (PRR_RAIL[i], PRR_RAIL[(i + 1) % 3]);
    let d = [b[0] - a[0], b[1] - a[1]];
    let n = d[0].hypot(d[1]);
    [d[0] / n, d[1] / n]
}

/// The platform hinge i at a planar pose (φ, x, y).
fn prr_hinge(i: usize, pose: [f64; 3]) -> [f64; 2] {
    let b = rot2(PRR_PLAT[i], pose[0]);
    [b[0] + pose[1], b[1] + pose[2]]
}

fn prr_home_hinge(i: usize) -> [f64; 2] {
    prr_hinge(i, PRR_HOME)
}

fn prr_rod(i: usize) -> f64 {
    let (s, b) = (PRR_SLIDER[i], prr_home_hinge(i));
    (b[0] - s[0]).hypot(b[1] - s[1])
}

/// The slider at slide d on rail i.
fn prr_slider(i: usize, d: f64) -> [f64; 2] {
    let e = prr_rail_dir(i);
    [PRR_SLIDER[i][0] + d * e[0], PRR_SLIDER[i][1] + d * e[1]]
}

/// Closed-form inverse kinematics: each slide where the rod reaches the hinge, the root on the
/// side of the hinge's foot on the rail that it has at home (`None` out of reach).
fn prr_inverse(pose: [f64; 3]) -> Option<[f64; 3]> {
    let mut d = [0.0; 3];
    for i in 0..3 {
        let e = prr_rail_dir(i);
        let b = prr_hinge(i, pose);
        let rel = [b[0] - PRR_SLIDER[i][0], b[1] - PRR_SLIDER[i][1]];
        let along = rel[0] * e[0] + rel[1] * e[1];
        let across = rel[0] * e[1] - rel[1] * e[0];
        let h2 = prr_rod(i).powi(2) - across * across;
        if !(h2 > 0.0) {
            return None;
        }
        let home = {
            let b0 = prr_home_hinge(i);
            let r0 = [b0[0] - PRR_SLIDER[i][0], b0[1] - PRR_SLIDER[i][1]];
            (r0[0] * e[0] + r0[1] * e[1]).signum()
        };
        // The slider sits `along − d` behind the hinge's foot: keep that sign as at home.
        d[i] = along - home * h2.sqrt();
    }
    Some(d)
}

/// Every assembly mode of the 3-PRR at slides d by an orientation scan: for each φ, the
/// hinge B1 where its rod's circle meets the circle the rod of leg 2 allows it (both roots),
/// and the third rod's misfit; roots of the misfit refined by bisection.
fn prr_modes_by_scan(d: [f64; 3]) -> Vec<[f64; 3]> {
    let s: [[f64; 2]; 3] = std::array::from_fn(|i| prr_slider(i, d[i]));
    let l: [f64; 3] = std::array::from_fn(prr_rod);
    let place = |phi: f64, branch: f64| -> Option<[f64; 3]> {
        let b12 = {
            let a = rot2(PRR_PLAT[0], phi);
            let b = rot2(PRR_PLAT[1], phi);
            [b[0] - a[0], b[1] - a[1]]
        };
        // B1 on circle (s1, l1) and on circle (s2 − b12, l2).
        let c2 = [s[1][0] - b12[0], s[1][1] - b12[1]];
        let dv = [c2[0] - s[0][0], c2[1] - s[0][1]];
        let dd = dv[0].hypot(dv[1]);
        let along = (l[0] * l[0] - l[1] * l[1] + dd * dd) / (2.0 * dd);
        let h2 = l[0] * l[0] - along * along;
        if !(h2 > 0.0) {
            return None;
        }
        let h = branch * h2.sqrt();
        let b1 = [
            s[0][0] + (along * dv[0] - h * dv[1]) / dd,
            s[0][1] + (along * dv[1] + h * dv[0]) / dd,
        ];
        let a = rot2(PRR_PLAT[0], phi);
        Some([phi, b1[0] - a[0], b1[1] - a[1]])
    };
    let misfit = |phi: f64, branch: f64| -> Option<f64> {
        let pose = place(phi, branch)?;
        let b3 = prr_hinge(2, pose);
        Some((b3[0] - s[2][0]).hypot(b3[1] - s[2][1]) - l[2])
    };
    let mut out = Vec::new();
    let n = 20_000;
    let step = 2.0 * std::f64::consts::PI / n as f64;
    for branch in [1.0, -1.0] {
        for k in 0..n {
            let (a, b) = (-std::f64::consts::PI + k as f64 * step, 0.0);
            let b = a + step + b;
            let (Some(fa), Some(fb)) = (misfit(a, branch), misfit(b, branch)) else {
                continue;
            };
            if fa * fb > 0.0 {
                continue;
            }
            let (mut lo, mut hi, mut flo) = (a, b, fa);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                let Some(fm) = misfit(mid, branch) else { break };
                if fm * flo > 0.0 {
                    (lo, flo) = (mid, fm);
                } else {
                    hi = mid;
                }
            }
            out.push(place(0.5 * (lo + hi), branch).unwrap());
        }
    }
    out
}

fn prr_pose<const N: usize>(v: &[f64; N]) -> [f64; 3]
where
    PlanarPrr: Mechanism<N, 3>,
{
    let b1 = point::<PlanarPrr, N, 3>(v, "B1");
    let b2 = point::<PlanarPrr, N, 3>(v, "B2");
    let heading = (b2[1] - b1[1]).atan2(b2[0] - b1[0]);
    let local = [
        PRR_PLAT[1][0] - PRR_PLAT[0][0],
        PRR_PLAT[1][1] - PRR_PLAT[0][1],
    ];
    let phi = heading - local[1].atan2(local[0]);
    let a = rot2(PRR_PLAT[0], phi);
    [phi, b1[0] - a[0], b1[1] - a[1]]
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

fn same_planar_pose(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    wrap(a[0] - b[0]).abs() < tol / 100.0 && (a[1] - b[1]).abs() < tol && (a[2] - b[2]).abs() < tol
}

#[test]
fn planar_3prr_against_closed_form_inverse_kinematics() {
    let m = PlanarPrr::new();
    let line = super::mobility_line(PlanarPrr::LISTING);
    assert!(line.contains(" = 3"), "{line}");
    let start = m.home_start().unwrap();
    assert!(linkage_tests::max_diff(&prr_inverse(PRR_HOME).unwrap(), &[0.0; 3]) < 1e-9);
    check_jacobians(&m, start.v(), start.x());
    check_factorization(&m, start.v(), start.x());
    let mut rng = Rng::new(1992);
    let mut worst: f64 = 0.0;
    let mut ok = 0;
    for case in 0..40 {
        let pose = [
            PRR_HOME[0] + rng.uniform(-0.2, 0.2),
            PRR_HOME[1] + rng.uniform(-20.0, 20.0),
            PRR_HOME[2] + rng.uniform(-20.0, 20.0),
        ];
        let Some(d) = prr_inverse(pose) else { continue };
        let sol = arc_length(&m, &start, &d, &GENERAL_MODEL).unwrap();
        if !against_the_segment(&m, &start, &d, &sol, 2000, &format!("case {case} {d:?}")) {
            continue;
        }
        // Every rod at its length, every hinge on its slider, the platform rigid.
        for i in 0..3 {
            let b = point::<PlanarPrr, _, 3>(&sol.v, &format!("B{}", i + 1));
            let s = prr_slider(i, d[i]);
            let rod = (b[0] - s[0]).hypot(b[1] - s[1]);
            worst = worst.max((rod - prr_rod(i)).abs()).max(b[2].abs());
        }
        let got = prr_pose(&sol.v);
        let back = prr_inverse(got).unwrap();
        worst = worst.max(linkage_tests::max_diff(&back, &d));
        check_inverse(&m, &sol.v, &d, &PlanarPrr::HOME_INPUTS, 1e-8);
        // The branch: the pose the slides came from, when the segment is joined to it.
        if same_planar_pose(got, pose, 1e-6) {
            ok += 1;
        }
        check_jacobians(&m, &sol.v, &d);
    }
    assert!(worst < 1e-7, "{worst}");
    assert!(ok >= 20, "{ok}");
    println!(
        "3-PRR: {ok} of 40 back at the pose their slides came from, worst residual {worst:.1e}"
    );
}

#[test]
fn planar_3prr_assembly_modes_against_a_scan() {
    let m = PlanarPrr::new();
    let modes = AllModes::<_, _, 3, 64>::new(m.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 6, "{:?}", modes.report());
    let mut roots = Box::new(Roots::new());
    let mut rng = Rng::new(6);
    for _ in 0..6 {
        let d = [
            rng.uniform(-40.0, 40.0),
            rng.uniform(-40.0, 40.0),
            rng.uniform(-40.0, 40.0),
        ];
        modes.solve(&d, &mut roots).unwrap();
        assert!(roots.is_complete(), "{d:?}");
        let scan = prr_modes_by_scan(d);
        let real: Vec<[f64; 3]> = roots.real().iter().map(|r| prr_pose(&r.v)).collect();
        println!(
            "3-PRR at {d:?}: {} real modes, scan {}",
            real.len(),
            scan.len()
        );
        assert_eq!(real.len(), scan.len(), "{d:?}: {real:?} vs {scan:?}");
        for s in &scan {
            assert!(
                real.iter().any(|r| same_planar_pose(*r, *s, 1e-5)),
                "{d:?}: {s:?} missed"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Tsai & Joshi's translational 3-RUU: cranks on tangential axes (as a delta's), a rod between
// two U pairs whose first axes (on the crank, on the platform) are parallel to the crank's.
linkage::mechanism! {
    /// A translational 3-RUU.
    pub struct TranslationalRuu;
    params {
        rb = 100.0, la = 80.0, rp = 40.0, h = 150.0,
        c = cos(2.0 * pi / 3.0), s = sin(2.0 * pi / 3.0),
    }
    base {
        A1 = [rb, 0.0, 0.0], A1t = [rb, 100.0, 0.0],
        A2 = [rb * c, rb * s, 0.0], A2t = [rb * c - 100.0 * s, rb * s + 100.0 * c, 0.0],
        A3 = [rb * c, -rb * s, 0.0], A3t = [rb * c + 100.0 * s, -rb * s + 100.0 * c, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -h]) {
        F1 = [rp, 0.0, 0.0], F1t = [rp, 100.0, 0.0],
        F2 = [rp * c, rp * s, 0.0], F2t = [rp * c - 100.0 * s, rp * s + 100.0 * c, 0.0],
        F3 = [rp * c, -rp * s, 0.0], F3t = [rp * c + 100.0 * s, -rp * s + 100.0 * c, 0.0],
    }
    link crank1 { E1 = [rb + la, 0.0, 0.0], E1t = [rb + la, 100.0, 0.0] }
    link crank2 { E2 = [(rb + la) * c, (rb + la) * s, 0.0], E2t = [(rb + la) * c - 100.0 * s, (rb + la) * s + 100.0 * c, 0.0] }
    link crank3 { E3 = [(rb + la) * c, -(rb + la) * s, 0.0], E3t = [(rb + la) * c + 100.0 * s, -(rb + la) * s + 100.0 * c, 0.0] }
    chain leg1 = base - R(active q1, axis = A1 -> A1t) - crank1 - U(E1, axis = E1 -> E1t) - U(F1, axis = F1 -> F1t) - platform;
    chain leg2 = base - R(active q2, axis = A2 -> A2t) - crank2 - U(E2, axis = E2 -> E2t) - U(F2, axis = F2 -> F2t) - platform;
    chain leg3 = base - R(active q3, axis = A3 -> A3t) - crank3 - U(E3, axis = E3 -> E3t) - U(F3, axis = F3 -> F3t) - platform;
}

const RUU_RB: f64 = 100.0;
const RUU_LA: f64 = 80.0;
const RUU_RP: f64 = 40.0;
const RUU_H: f64 = 150.0;

fn ruu_dir(i: usize) -> ([f64; 3], [f64; 3]) {
    let a = 2.0 * std::f64::consts::PI * i as f64 / 3.0;
    let radial = [a.cos(), a.sin(), 0.0];
    let tangent = [-a.sin(), a.cos(), 0.0];
    (radial, tangent)
}

fn ruu_rod() -> f64 {
    (RUU_RB + RUU_LA - RUU_RP).hypot(RUU_H)
}

/// The crank tip at angle q: turned right-handed about the tangent (A → A + t).
fn ruu_elbow(i: usize, q: f64) -> [f64; 3] {
    let (radial, tangent) = ruu_dir(i);
    add(
        scaled(radial, RUU_RB),
        turn(scaled(radial, RUU_LA), tangent, q),
    )
}

/// Leg i's crank angles reaching the platform pivot of the platform centre p: the two roots
/// base ± off of a cos q + b sin q = c, as (base, off); `None` out of reach.
fn ruu_leg(i: usize, p: [f64; 3]) -> Option<(f64, f64)> {
    let (radial, tangent) = ruu_dir(i);
    let f = add(p, scaled(radial, RUU_RP));
    // |A + la (cos q r + sin q (t × r)) − f|² = l².
    let rel = sub(f, scaled(radial, RUU_RB));
    let along = cross(tangent, radial);
    let (a, b) = (dot(rel, radial), dot(rel, along));
    let c = (dot(rel, rel) + RUU_LA * RUU_LA - ruu_rod().powi(2)) / (2.0 * RUU_LA);
    let r = a.hypot(b);
    if !(c.abs() < r) {
        return None;
    }
    Some((b.atan2(a), (c / r).acos()))
}

/// Closed-form inverse kinematics at the platform translation p (its centre): each crank where
/// its tip is a rod's length from the platform pivot, on the root it takes at home.
fn ruu_inverse(p: [f64; 3]) -> Option<[f64; 3]> {
    let mut q = [0.0; 3];
    for i in 0..3 {
        let (base0, off0) = ruu_leg(i, [0.0, 0.0, -RUU_H]).unwrap();
        let sign = if wrap(base0 + off0).abs() < wrap(base0 - off0).abs() {
            1.0
        } else {
            -1.0
        };
        let (base, off) = ruu_leg(i, p)?;
        q[i] = wrap(base + sign * off);
    }
    Some(q)
}

/// Closed-form forward kinematics: the platform centre where the three spheres about the crank
/// tips (less the platform pivots' offsets) meet, on the side of their plane it is on at home.
fn ruu_forward(q: [f64; 3]) -> Option<[f64; 3]> {
    let c: [[f64; 3]; 3] =
        std::array::from_fn(|i| sub(ruu_elbow(i, q[i]), scaled(ruu_dir(i).0, RUU_RP)));
    let l = ruu_rod();
    let (e1, e2) = (sub(c[1], c[0]), sub(c[2], c[0]));
    let n = cross(e1, e2);
    // p = c0 + x e1 + y e2 + z n with |p − ci| = l: linear in (x, y) after differences.
    let (g11, g12, g22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
    let (r1, r2) = (0.5 * g11, 0.5 * g22);
    let det = g11 * g22 - g12 * g12;
    let x = (r1 * g22 - r2 * g12) / det;
    let y = (r2 * g11 - r1 * g12) / det;
    let inp = add(scaled(e1, x), scaled(e2, y));
    let z2 = (l * l - dot(inp, inp)) / dot(n, n);
    if !(z2 > 0.0) {
        return None;
    }
    // At home the platform is below the tips' plane: n = e1 × e2 points up (counter-clockwise).
    Some(add(add(c[0], inp), scaled(n, -z2.sqrt() * n[2].signum())))
}

#[test]
fn translational_3ruu_against_closed_forms() {
    let m = TranslationalRuu::new();
    let line = super::mobility_line(TranslationalRuu::LISTING);
    assert!(line.contains(" = 3"), "{line}");
    let start = m.home_start().unwrap();
    let home = [0.0, 0.0, -RUU_H];
    assert!(linkage_tests::max_diff(&ruu_inverse(home).unwrap(), &[0.0; 3]) < 1e-9);
    assert!(dist(ruu_forward([0.0; 3]).unwrap(), home) < 1e-9);
    check_jacobians(&m, start.v(), start.x());
    check_factorization(&m, start.v(), start.x());
    let mut rng = Rng::new(2002);
    let mut worst: f64 = 0.0;
    let mut ok = 0;
    for case in 0..16 {
        let p = [
            rng.uniform(-40.0, 40.0),
            rng.uniform(-40.0, 40.0),
            -RUU_H + rng.uniform(-40.0, 40.0),
        ];
        let Some(q) = ruu_inverse(p) else { continue };
        assert!(dist(ruu_forward(q).unwrap(), p) < 1e-8);
        let sol = arc_length(&m, &start, &q, &GENERAL_MODEL).unwrap();
        if !against_the_segment(&m, &start, &q, &sol, 600, &format!("case {case} {q:?}")) {
            continue;
        }
        let pose = pose_from_unknowns(&m, &sol.v).unwrap();
        super::identity_within(&pose.rotation, 1e-8);
        worst = worst.max(dist(pose.translation, p));
        check_inverse(&m, &sol.v, &q, &TranslationalRuu::HOME_INPUTS, 1e-8);
        if ok < 3 {
            check_jacobians(&m, &sol.v, &q);
        }
        ok += 1;
    }
    assert!(worst < 1e-7, "{worst}");
    assert!(ok >= 10, "{ok}");
    // The tracker along a loop of crank angles.
    let mut tracker = Tracker::new(m.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let t = k as f64 * 0.157;
        let q = [
            0.3 * t.sin(),
            0.25 * (1.3 * t).sin(),
            -0.2 * (0.7 * t).sin(),
        ];
        let s = tracker
            .update(&q)
            .unwrap_or_else(|e| panic!("{q:?}: {e:?}"));
        let pose = pose_from_unknowns(&m, &s.v).unwrap();
        super::identity_within(&pose.rotation, 1e-8);
        let truth = ruu_forward(q).unwrap();
        worst = worst.max(dist(pose.translation, truth));
    }
    assert!(worst < 1e-7, "{worst}");
    println!("3-RUU: {ok} of 16 converged, worst error {worst:.1e} mm");
}

// ---------------------------------------------------------------------------------------------
// 6-PUS on parallel rails: rails along x at y = −150, 0, 150 (the middle one 60 mm higher), two
// sliders on each, a U on each slider (first axis along the rail), a rod to a ball on the
// platform below.
linkage::mechanism! {
    /// A 6-PUS on three parallel rails.
    pub struct Pus;
    params { rp = 60.0, h = 250.0 }
    base {
        R1 = [-200.0, -150.0, 0.0], R1x = [200.0, -150.0, 0.0],
        R2 = [-200.0, 0.0, 60.0], R2x = [200.0, 0.0, 60.0],
        R3 = [-200.0, 150.0, 0.0], R3x = [200.0, 150.0, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -h]) {
        G1 = [rp * cos(-1.4), rp * sin(-1.4), 0.0], G2 = [rp * cos(-1.9), rp * sin(-1.9), 0.0],
        G3 = [rp * cos(0.3), rp * sin(0.3), 0.0], G4 = [rp * cos(2.9), rp * sin(2.9), 0.0],
        G5 = [rp * cos(1.2), rp * sin(1.2), 0.0], G6 = [rp * cos(2.0), rp * sin(2.0), 10.0],
    }
    link s1 { A1 = [160.0, -150.0, 0.0], A1x = [260.0, -150.0, 0.0] }
    link s2 { A2 = [-170.0, -150.0, 0.0], A2x = [-70.0, -150.0, 0.0] }
    link s3 { A3 = [210.0, 0.0, 60.0], A3x = [310.0, 0.0, 60.0] }
    link s4 { A4 = [-210.0, 0.0, 60.0], A4x = [-110.0, 0.0, 60.0] }
    link s5 { A5 = [170.0, 150.0, 0.0], A5x = [270.0, 150.0, 0.0] }
    link s6 { A6 = [-175.0, 150.0, 0.0], A6x = [-75.0, 150.0, 0.0] }
    chain leg1 = base - P(active d1, axis = R1 -> R1x) - s1 - U(A1, axis = A1 -> A1x) - S(G1) - platform;
    chain leg2 = base - P(active d2, axis = R1 -> R1x) - s2 - U(A2, axis = A2 -> A2x) - S(G2) - platform;
    chain leg3 = base - P(active d3, axis = R2 -> R2x) - s3 - U(A3, axis = A3 -> A3x) - S(G3) - platform;
    chain leg4 = base - P(active d4, axis = R2 -> R2x) - s4 - U(A4, axis = A4 -> A4x) - S(G4) - platform;
    chain leg5 = base - P(active d5, axis = R3 -> R3x) - s5 - U(A5, axis = A5 -> A5x) - S(G5) - platform;
    chain leg6 = base - P(active d6, axis = R3 -> R3x) - s6 - U(A6, axis = A6 -> A6x) - S(G6) - platform;
}

const PUS_A: [[f64; 3]; 6] = [
    [160.0, -150.0, 0.0],
    [-170.0, -150.0, 0.0],
    [210.0, 0.0, 60.0],
    [-210.0, 0.0, 60.0],
    [170.0, 150.0, 0.0],
    [-175.0, 150.0, 0.0],
];

fn pus_g() -> [[f64; 3]; 6] {
    let rp = 60.0f64;
    let polar = |a: f64, z: f64| [rp * a.cos(), rp * a.sin(), z];
    [
        polar(-1.4, 0.0),
        polar(-1.9, 0.0),
        polar(0.3, 0.0),
        polar(2.9, 0.0),
        polar(1.2, 0.0),
        polar(2.0, 10.0),
    ]
}

fn pus_home() -> Pose {
    Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, -250.0])
}

fn pus_rods() -> [f64; 6] {
    let g = pus_g();
    std::array::from_fn(|i| dist(pus_home().apply(g[i]), PUS_A[i]))
}

/// Closed-form inverse kinematics: each slide where the rod reaches the ball, on the side of
/// the ball's foot on the rail that the slider has at home.
fn pus_inverse(pose: &Pose) -> Option<[f64; 6]> {
    let g = pus_g();
    let rods = pus_rods();
    let mut d = [0.0; 6];
    for i in 0..6 {
        let rel = sub(pose.apply(g[i]), PUS_A[i]);
        let across2 = rel[1] * rel[1] + rel[2] * rel[2];
        let h2 = rods[i] * rods[i] - across2;
        if !(h2 > 0.0) {
            return None;
        }
        let home = sub(pus_home().apply(g[i]), PUS_A[i])[0].signum();
        d[i] = rel[0] - home * h2.sqrt();
    }
    Some(d)
}

#[test]
fn pus_on_parallel_rails_against_closed_form_inverse() {
    let m = Pus::new();
    let line = super::mobility_line(Pus::LISTING);
    assert!(line.contains(" = 6"), "{line}");
    let start = m.home_start().unwrap();
    assert!(linkage_tests::max_diff(&pus_inverse(&pus_home()).unwrap(), &[0.0; 6]) < 1e-9);
    check_jacobians(&m, start.v(), start.x());
    check_factorization(&m, start.v(), start.x());
    let mut rng = Rng::new(1997);
    let mut worst: f64 = 0.0;
    let mut ok = 0;
    for case in 0..16 {
        let pose = Pose::from_euler(
            rng.uniform(-0.15, 0.15),
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            [
                rng.uniform(-30.0, 30.0),
                rng.uniform(-20.0, 20.0),
                -250.0 + rng.uniform(-20.0, 20.0),
            ],
        );
        let Some(d) = pus_inverse(&pose) else {
            continue;
        };
        let sol = arc_length(&m, &start, &d, &GENERAL_MODEL).unwrap();
        if !against_the_segment(&m, &start, &d, &sol, 600, &format!("case {case} {d:?}")) {
            continue;
        }
        let got = pose_from_unknowns(&m, &sol.v).unwrap();
        // Every rod at its length from its slider.
        let g = pus_g();
        let rods = pus_rods();
        for i in 0..6 {
            let a = add(PUS_A[i], [d[i], 0.0, 0.0]);
            worst = worst.max((dist(got.apply(g[i]), a) - rods[i]).abs());
        }
        let back = pus_inverse(&got).unwrap();
        worst = worst.max(linkage_tests::max_diff(&back, &d));
        check_inverse(&m, &sol.v, &d, &Pus::HOME_INPUTS, 1e-8);
        if dist(got.translation, pose.translation) < 1e-6 {
            ok += 1;
        }
        if case < 3 {
            check_jacobians(&m, &sol.v, &d);
        }
    }
    assert!(worst < 1e-7, "{worst}");
    assert!(ok >= 10, "{ok}");
    println!("6-PUS: {ok} of 16 at the pose their slides came from, worst residual {worst:.1e}");
}

// ---------------------------------------------------------------------------------------------
// Hostile inputs, on each: out of reach (never ok), NaN (an error or not ok), and a start at a
// singular configuration refused.

/// With its rods reduced to their lengths (a U on an unnamed rod to a ball holds only the rod's
/// spin), the 6-PUS is, at fixed slides, a 6-6 platform: 18 unknowns (the type says so) and the
/// 40 complex roots of one. Every real root keeps each rod at its length from its slider, and
/// the home pose is among them. (Before the reduction: 36 unknowns, each rod's second axis a
/// point, and twice as many placements per rod.)
#[test]
fn pus_has_the_forty_assembly_modes_of_a_six_six_platform() {
    let m = Pus::new();
    let modes = AllModes::<_, 18, 6, 64>::new(m.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 40, "{:?}", modes.report());
    let mut roots = Box::new(Roots::new());
    let (g, rods) = (pus_g(), pus_rods());
    let mut rng = Rng::new(40);
    for case in 0..2 {
        let d: [f64; 6] = if case == 0 {
            Pus::HOME_INPUTS
        } else {
            std::array::from_fn(|_| rng.uniform(-20.0, 20.0))
        };
        modes.solve(&d, &mut roots).unwrap();
        assert!(roots.is_complete(), "{d:?}");
        for r in roots.real() {
            let pose = pose_from_unknowns(&m, &r.v).unwrap();
            for i in 0..6 {
                let a = add(PUS_A[i], [d[i], 0.0, 0.0]);
                let off = (dist(pose.apply(g[i]), a) - rods[i]).abs();
                assert!(off < 1e-6 * rods[i], "{d:?}: rod {i} off by {off:e}");
            }
        }
        if case == 0 {
            let home = pus_home();
            assert!(
                roots.real().iter().any(|r| {
                    let p = pose_from_unknowns(&m, &r.v).unwrap();
                    g.iter().all(|&q| dist(p.apply(q), home.apply(q)) < 1e-6)
                }),
                "the home pose is not among the {} real roots",
                roots.real().len()
            );
        }
        println!("6-PUS at {d:?}: {} real modes of 40", roots.real().len());
    }
}

#[test]
fn literature_mechanisms_refuse_hostile_inputs() {
    let sr = Spherical5R::new();
    let s = sr.home_start().unwrap();
    for q in [[3.0, -3.0], [f64::NAN, 0.0], [0.0, f64::INFINITY]] {
        if let Ok(sol) = arc_length(&sr, &s, &q, &GENERAL_MODEL) {
            assert!(
                !sol.is_ok() || sr_closed_form(q, sr_side()).is_some(),
                "{q:?}: {sol:?}"
            );
        }
    }
    // Exactly at a fold: q1 where the two cones about the elbows touch (q2 = 0), the first
    // such angle from home, by bisection on the closed form's discriminant. Ok only with the
    // double root's pose (to the accuracy a double root allows).
    // The cones part first along q = t (−1.4, 1.2), near t = 1 (a scan of the closed form).
    let at = |t: f64| [-1.4 * t, 1.2 * t];
    let (mut lo, mut hi) = (0.0, 0.0);
    while sr_closed_form(at(hi), 1.0).is_some() {
        lo = hi;
        hi += 0.01;
        assert!(hi < 1.5, "no fold along the line");
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if sr_closed_form(at(mid), 1.0).is_some() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    for t in [lo, hi] {
        let q = at(t);
        let sol = arc_length(&sr, &s, &q, &GENERAL_MODEL).unwrap();
        println!("spherical 5R at the fold {q:?}: {:?}", sol.status);
        if sol.is_ok() {
            let p = unit(point::<Spherical5R, _, 2>(&sol.v, "P"));
            let truth = sr_closed_form(at(lo), 1.0).unwrap();
            assert!(
                dist(p, truth) < 1e-4,
                "{q:?}: ok at {p:?}, the fold at {truth:?}"
            );
        }
        assert!(det_b(&sr, &sol.v, &q).is_finite());
    }
    // The tracker: a NaN sample and one out of reach refused, and the tracker still usable.
    let mut tracker = Tracker::new(sr.clone(), s, GENERAL_MODEL);
    assert!(tracker.update(&[f64::NAN, 0.0]).is_err());
    let far = at(hi + 0.3);
    match tracker.update(&far) {
        Ok(sample) => panic!("tracker out of reach at {far:?}: {:?}", sample.v),
        Err(e) => println!("tracker out of reach: {e:?}"),
    }
    let q = [0.05, -0.05];
    let sample = tracker.update(&q).unwrap();
    sr_check(&sample.v, q, "tracker after refusals");
    let prr = PlanarPrr::new();
    let s = prr.home_start().unwrap();
    for d in [
        [400.0, 0.0, 0.0],
        [f64::NAN, 0.0, 0.0],
        [-300.0, 300.0, 0.0],
    ] {
        if let Ok(sol) = arc_length(&prr, &s, &d, &GENERAL_MODEL) {
            assert!(!sol.is_ok(), "{d:?}: {sol:?}");
        }
    }
    let ruu = TranslationalRuu::new();
    let s = ruu.home_start().unwrap();
    for q in [[2.5, 2.5, 2.5], [f64::NAN, 0.0, 0.0], [-1.5, 1.5, 0.0]] {
        if let Ok(sol) = arc_length(&ruu, &s, &q, &GENERAL_MODEL) {
            let reach = ruu_forward(q);
            assert!(!sol.is_ok() || reach.is_some(), "{q:?}: {sol:?}");
            if sol.is_ok() {
                let p = pose_from_unknowns(&ruu, &sol.v).unwrap();
                assert!(dist(p.translation, reach.unwrap()) < 1e-6, "{q:?}");
            }
        }
    }
    let pus = Pus::new();
    let s = pus.home_start().unwrap();
    for d in [[0.0, 0.0, 0.0, 0.0, 0.0, 500.0], [f64::NAN; 6]] {
        if let Ok(sol) = arc_length(&pus, &s, &d, &GENERAL_MODEL) {
            assert!(!sol.is_ok(), "{d:?}: {sol:?}");
        }
    }
}

/// Where the translation crosses a constraint singularity of the 3-RUU (the legs' constraint
/// couples, each leg's direction less its part along the crank axis, in one plane: there the
/// platform can start to turn and a branch of turned placements meets the translations), on
/// straight segments from home along which the three spheres keep meeting regularly (found by
/// a scan of the closed form). No solver may call an answer there ok, nor return a turned
/// platform.
#[test]
fn translational_3ruu_across_a_constraint_singularity() {
    let m = TranslationalRuu::new();
    let start = m.home_start().unwrap();
    for q in [
        [-1.2312138358066331, 1.766594280748162, -1.477312830481009],
        [-1.7703879020447688, 1.4221956888585825, -1.289995932173809],
        [-1.6893839481760327, 1.4324696376402484, -1.3862776141455657],
    ] {
        let truth = ruu_forward(q).unwrap();
        // The fine-stepped reference follows the translation through the singular point,
        // where det B changes sign: no ok answer there is on the start's branch.
        let (v, flips) = straight_segment(&m, &start, &q, 4000);
        let reference = pose_from_unknowns(&m, &v).unwrap();
        assert_eq!(flips, 1, "{q:?}");
        assert!(dist(reference.translation, truth) < 1e-6, "{q:?}");
        let sol = arc_length(&m, &start, &q, &GENERAL_MODEL).unwrap();
        assert!(!sol.is_ok(), "{q:?}: ok across the singularity, {sol:?}");
        let pose = pose_from_unknowns(&m, &sol.v).unwrap();
        super::identity_within(&pose.rotation, 1e-7);
        let mut tracker = Tracker::new(m.clone(), start, GENERAL_MODEL);
        let mut refused = false;
        for k in 1..=50 {
            let qk = q.map(|c| c * k as f64 / 50.0);
            match tracker.update(&qk) {
                Ok(s) => {
                    let pose = pose_from_unknowns(&m, &s.v).unwrap();
                    let turned = pose.euler().iter().fold(0.0f64, |a, b| a.max(b.abs()));
                    assert!(
                        turned < 1e-7,
                        "tracker at {qk:?} (step {k}): turned {:?}",
                        pose.euler()
                    );
                    assert!(dist(pose.translation, ruu_forward(qk).unwrap()) < 1e-6);
                }
                Err(_) => {
                    refused = true;
                    break;
                }
            }
        }
        assert!(refused, "{q:?}: the tracker crossed the singularity");
    }
}
