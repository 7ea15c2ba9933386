//! A planar four-bar (one freedom), declared two ways: the coupler as the platform, and the
//! coupler as an intermediate link whose point P is the output (the rocker's chain closes on
//! the coupler). Against the closed form: the crank turned, the rocker's joint where two
//! circles meet, the coupler placed by its two joints.

use super::check_inverse;
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

// Crank 40 (A to B), coupler |BC| = √(100² + 20²), rocker 60 (D to C), frame 100: a Grashof
// crank-rocker (40 + 102 < 100 + 60), so the crank turns all the way round and the mechanism,
// driven at the crank, meets no singularity.
linkage::mechanism! {
    /// The coupler is the platform: it carries B and C (the axes it shares with the crank and
    /// the rocker) and the output point P.
    pub struct FourBar;
    base { A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 1.0], D = [100.0, 0.0, 0.0], Dz = [100.0, 0.0, 1.0] }
    platform {
        B = [0.0, 40.0, 0.0], Bz = [0.0, 40.0, 1.0],
        C = [100.0, 60.0, 0.0], Cz = [100.0, 60.0, 1.0],
        P = [60.0, 80.0, 0.0],
    }
    link crank { }
    link rocker { }
    chain driven = base - R(active q, axis = A -> Az) - crank - R(passive, axis = B -> Bz) - platform;
    chain follower = base - R(passive, axis = D -> Dz) - rocker - R(passive, axis = C -> Cz) - platform;
}

linkage::mechanism! {
    /// The same four-bar with its coupler an intermediate link and the output a point on it:
    /// the rocker's chain ends at the coupler, which the crank's chain passes through.
    pub struct FourBarPoint;
    base { A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 1.0], D = [100.0, 0.0, 0.0], Dz = [100.0, 0.0, 1.0] }
    platform { P = [60.0, 80.0, 0.0] }
    link crank { B = [0.0, 40.0, 0.0], Bz = [0.0, 40.0, 1.0] }
    link rocker { C = [100.0, 60.0, 0.0], Cz = [100.0, 60.0, 1.0] }
    link coupler { }
    chain driven = base - R(active q, axis = A -> Az) - crank - R(passive, axis = B -> Bz) - coupler - S(P) - platform;
    chain follower = base - R(passive, axis = D -> Dz) - rocker - R(passive, axis = C -> Cz) - coupler;
}

/// The coupler's turn from home and its point P at crank angle q (from home), in closed form:
/// B on the crank circle, C where the coupler's circle about B meets the rocker's about D, on
/// the side of BD it is at home (a crank-rocker driven at the crank never changes side).
fn coupler(q: f64) -> (f64, [f64; 2]) {
    let (b0, c0, p0, d) = ([0.0, 40.0], [100.0, 60.0], [60.0, 80.0], [100.0, 0.0]);
    let b = [-40.0 * q.sin(), 40.0 * q.cos()];
    let coupler = f64::hypot(c0[0] - b0[0], c0[1] - b0[1]);
    let rocker = 60.0;
    let bd = f64::hypot(d[0] - b[0], d[1] - b[1]);
    // Distance from B along BD to the chord, and half the chord.
    let a = (coupler * coupler - rocker * rocker + bd * bd) / (2.0 * bd);
    let h = (coupler * coupler - a * a).sqrt();
    let (ex, ey) = ((d[0] - b[0]) / bd, (d[1] - b[1]) / bd);
    // At home C is to the left of B→D (cross product positive).
    let c = [b[0] + a * ex - h * ey, b[1] + a * ey + h * ex];
    let turn = (c[1] - b[1]).atan2(c[0] - b[0]) - (c0[1] - b0[1]).atan2(c0[0] - b0[0]);
    let (s, co) = turn.sin_cos();
    let r = [p0[0] - b0[0], p0[1] - b0[1]];
    (
        turn,
        [b[0] + co * r[0] - s * r[1], b[1] + s * r[0] + co * r[1]],
    )
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

#[test]
fn closed_form_is_the_declared_configuration_at_zero() {
    let (turn, p) = coupler(0.0);
    assert!(turn.abs() < 1e-12 && (p[0] - 60.0).abs() < 1e-12 && (p[1] - 80.0).abs() < 1e-12);
}

#[test]
fn four_bars_have_one_freedom_by_rank_and_exact_jacobians() {
    let (fb, fp) = (FourBar::new(), FourBarPoint::new());
    assert_eq!(FourBar::INPUTS, ["q"]);
    assert_eq!(FourBarPoint::INPUTS, ["q"]);
    for listing in [FourBar::LISTING, FourBarPoint::LISTING] {
        let line = super::mobility_line(listing);
        assert!(
            line.contains("rank of ∂F/∂(v, x) at home") && line.ends_with(")"),
            "{line}"
        );
        assert!(line.contains(" = 1 (Grübler–Kutzbach"), "{line}");
    }
    let s = fb.home_start().unwrap();
    check_jacobians(&fb, s.v(), s.x());
    check_factorization(&fb, s.v(), s.x());
    let s = fp.home_start().unwrap();
    check_jacobians(&fp, s.v(), s.x());
    check_factorization(&fp, s.v(), s.x());
    // And away from home.
    let sol = arc_length(&fb, &fb.home_start().unwrap(), &[1.3], &Options::TIGHT).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&fb, &sol.v, &[1.3]);
}

#[test]
fn four_bar_coupler_against_the_closed_form_all_round() {
    let fb = FourBar::new();
    let start = fb.home_start().unwrap();
    let crank = FourBar::LINKS.iter().position(|l| *l == "crank");
    let mut rng = Rng::new(41);
    let mut solved = 0;
    for _ in 0..60 {
        let q = rng.uniform(-3.0, 3.0);
        let sol = arc_length(&fb, &start, &[q], &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        solved += 1;
        let (turn, p) = coupler(q);
        let pose = pose_from_unknowns(&fb, &sol.v).unwrap();
        let [yaw, pitch, roll] = pose.euler();
        assert!(
            wrap(yaw - turn).abs() < 1e-8,
            "q = {q}: coupler turned {yaw}, closed form {turn}"
        );
        assert!(
            pitch.abs() < 1e-9 && roll.abs() < 1e-9,
            "q = {q}: the coupler left its plane"
        );
        let at = pose.apply([60.0, 80.0, 0.0]);
        assert!(
            (at[0] - p[0]).abs() < 1e-7 && (at[1] - p[1]).abs() < 1e-7 && at[2].abs() < 1e-9,
            "q = {q}: P at {at:?}, closed form {p:?}"
        );
        // The crank (a link the input places, without pivots of its own: it carries the
        // axes it shares) has turned by q.
        if let Some(i) = crank {
            let c = fb
                .link_pose(i, &sol.v, &[q])
                .expect("the crank has its two axes' points");
            assert!(wrap(c.euler()[0] - q).abs() < 1e-9, "{:?}", c.euler());
        }
        assert!(
            det_b(&fb, &sol.v, &[q]) * start.det() > 0.0,
            "q = {q}: another branch"
        );
        check_inverse(&fb, &sol.v, &[q], &FourBar::HOME_INPUTS, 1e-8);
    }
    assert_eq!(solved, 60);
}

#[test]
fn four_bar_point_output_against_the_closed_form_all_round() {
    let fp = FourBarPoint::new();
    let start = fp.home_start().unwrap();
    let mut rng = Rng::new(42);
    for _ in 0..60 {
        let q = rng.uniform(-3.0, 3.0);
        let sol = arc_length(&fp, &start, &[q], &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        let (_, p) = coupler(q);
        // One platform point: v starts with x_P, y_P, z_P.
        assert!(
            (sol.v[0] - p[0]).abs() < 1e-7
                && (sol.v[1] - p[1]).abs() < 1e-7
                && sol.v[2].abs() < 1e-9,
            "q = {q}: P at {:?}, closed form {p:?}",
            &sol.v[..3]
        );
        assert!(
            det_b(&fp, &sol.v, &[q]) * start.det() > 0.0,
            "q = {q}: another branch"
        );
        check_inverse(&fp, &sol.v, &[q], &FourBarPoint::HOME_INPUTS, 1e-8);
    }
}
