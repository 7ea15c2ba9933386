//! A 6-PCS: passive cylindrical pairs between moving links (the slide along the axis and the
//! turn about it both free), against inverse kinematics in closed form.

use super::{check_inverse, mobility_line};
use linkage::{arc_length, det_b, pose_from_unknowns, Options, Pose, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// A 6-PCS: six carriages driven up vertical rails, each carrying a leg on a passive
    /// cylindrical pair whose horizontal axis is turned 45° from the radius (one way on
    /// even legs, the other on odd ones: six alike would be singular); a spherical pair
    /// joins each leg to the platform. Each leg holds its platform pivot on a cylinder about
    /// its carriage's axis.
    pub struct Pcs;
    params { rb = 150.0, rp = 80.0, hc = 100.0, da = pi / 4.0 }
    base {
        A1 = [rb * cos(0.0 * pi / 3.0), rb * sin(0.0 * pi / 3.0), 0.0], B1 = [rb * cos(0.0 * pi / 3.0), rb * sin(0.0 * pi / 3.0), 1.0],
        A2 = [rb * cos(1.0 * pi / 3.0), rb * sin(1.0 * pi / 3.0), 0.0], B2 = [rb * cos(1.0 * pi / 3.0), rb * sin(1.0 * pi / 3.0), 1.0],
        A3 = [rb * cos(2.0 * pi / 3.0), rb * sin(2.0 * pi / 3.0), 0.0], B3 = [rb * cos(2.0 * pi / 3.0), rb * sin(2.0 * pi / 3.0), 1.0],
        A4 = [rb * cos(3.0 * pi / 3.0), rb * sin(3.0 * pi / 3.0), 0.0], B4 = [rb * cos(3.0 * pi / 3.0), rb * sin(3.0 * pi / 3.0), 1.0],
        A5 = [rb * cos(4.0 * pi / 3.0), rb * sin(4.0 * pi / 3.0), 0.0], B5 = [rb * cos(4.0 * pi / 3.0), rb * sin(4.0 * pi / 3.0), 1.0],
        A6 = [rb * cos(5.0 * pi / 3.0), rb * sin(5.0 * pi / 3.0), 0.0], B6 = [rb * cos(5.0 * pi / 3.0), rb * sin(5.0 * pi / 3.0), 1.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 200.0]) {
        G1 = [rp * cos(0.0 * pi / 3.0), rp * sin(0.0 * pi / 3.0), 0.0],
        G2 = [rp * cos(1.0 * pi / 3.0), rp * sin(1.0 * pi / 3.0), 0.0],
        G3 = [rp * cos(2.0 * pi / 3.0), rp * sin(2.0 * pi / 3.0), 0.0],
        G4 = [rp * cos(3.0 * pi / 3.0), rp * sin(3.0 * pi / 3.0), 0.0],
        G5 = [rp * cos(4.0 * pi / 3.0), rp * sin(4.0 * pi / 3.0), 0.0],
        G6 = [rp * cos(5.0 * pi / 3.0), rp * sin(5.0 * pi / 3.0), 0.0],
    }
    link carriage1 { C1 = [rb * cos(0.0 * pi / 3.0), rb * sin(0.0 * pi / 3.0), hc], D1 = [rb * cos(0.0 * pi / 3.0) + cos(0.0 * pi / 3.0 + da), rb * sin(0.0 * pi / 3.0) + sin(0.0 * pi / 3.0 + da), hc] }
    link carriage2 { C2 = [rb * cos(1.0 * pi / 3.0), rb * sin(1.0 * pi / 3.0), hc], D2 = [rb * cos(1.0 * pi / 3.0) + cos(1.0 * pi / 3.0 - da), rb * sin(1.0 * pi / 3.0) + sin(1.0 * pi / 3.0 - da), hc] }
    link carriage3 { C3 = [rb * cos(2.0 * pi / 3.0), rb * sin(2.0 * pi / 3.0), hc], D3 = [rb * cos(2.0 * pi / 3.0) + cos(2.0 * pi / 3.0 + da), rb * sin(2.0 * pi / 3.0) + sin(2.0 * pi / 3.0 + da), hc] }
    link carriage4 { C4 = [rb * cos(3.0 * pi / 3.0), rb * sin(3.0 * pi / 3.0), hc], D4 = [rb * cos(3.0 * pi / 3.0) + cos(3.0 * pi / 3.0 - da), rb * sin(3.0 * pi / 3.0) + sin(3.0 * pi / 3.0 - da), hc] }
    link carriage5 { C5 = [rb * cos(4.0 * pi / 3.0), rb * sin(4.0 * pi / 3.0), hc], D5 = [rb * cos(4.0 * pi / 3.0) + cos(4.0 * pi / 3.0 + da), rb * sin(4.0 * pi / 3.0) + sin(4.0 * pi / 3.0 + da), hc] }
    link carriage6 { C6 = [rb * cos(5.0 * pi / 3.0), rb * sin(5.0 * pi / 3.0), hc], D6 = [rb * cos(5.0 * pi / 3.0) + cos(5.0 * pi / 3.0 - da), rb * sin(5.0 * pi / 3.0) + sin(5.0 * pi / 3.0 - da), hc] }
    link leg1 { } link leg2 { } link leg3 { } link leg4 { } link leg5 { } link leg6 { }
    chain leg1 = base - P(active s1, axis = A1 -> B1, offset = hc) - carriage1 - C(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
    chain leg2 = base - P(active s2, axis = A2 -> B2, offset = hc) - carriage2 - C(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
    chain leg3 = base - P(active s3, axis = A3 -> B3, offset = hc) - carriage3 - C(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
    chain leg4 = base - P(active s4, axis = A4 -> B4, offset = hc) - carriage4 - C(passive, axis = C4 -> D4) - leg4 - S(G4) - platform;
    chain leg5 = base - P(active s5, axis = A5 -> B5, offset = hc) - carriage5 - C(passive, axis = C5 -> D5) - leg5 - S(G5) - platform;
    chain leg6 = base - P(active s6, axis = A6 -> B6, offset = hc) - carriage6 - C(passive, axis = C6 -> D6) - leg6 - S(G6) - platform;
}

const RB: f64 = 150.0;
const RP: f64 = 80.0;

/// Each carriage's height for a platform pose: its platform pivot is at the leg's distance r
/// from the carriage's axis, a horizontal line at that height through the rail.
pub(super) fn pcs_inverse(pose: &Pose) -> Option<[f64; 6]> {
    let da = std::f64::consts::FRAC_PI_4;
    // r² at home: 100 mm up, and 70 mm inwards of which the part across the axis counts.
    let r2 = 100.0f64.powi(2) + 70.0f64.powi(2) * (1.0 - da.cos().powi(2));
    let mut s = [0.0; 6];
    for (k, out) in s.iter_mut().enumerate() {
        let phi = k as f64 * std::f64::consts::PI / 3.0;
        let g = pose.apply([RP * phi.cos(), RP * phi.sin(), 0.0]);
        let w = [g[0] - RB * phi.cos(), g[1] - RB * phi.sin()];
        let turn = if k % 2 == 0 { da } else { -da };
        let d = [(phi + turn).cos(), (phi + turn).sin()];
        let along = w[0] * d[0] + w[1] * d[1];
        let across2 = w[0] * w[0] + w[1] * w[1] - along * along;
        if across2 > r2 {
            return None;
        }
        *out = g[2] - (r2 - across2).sqrt();
    }
    Some(s)
}

#[test]
fn pcs_models_with_six_freedoms_and_exact_jacobians() {
    let pcs = Pcs::new();
    let line = mobility_line(Pcs::LISTING);
    assert!(line.ends_with("= 6 (Grübler–Kutzbach says 6)"), "{line}");
    pcs.home_start().unwrap();
    check_jacobians(&pcs, &Pcs::HOME_V, &Pcs::HOME_INPUTS);
    check_factorization(&pcs, &Pcs::HOME_V, &Pcs::HOME_INPUTS);
    assert!(linkage_tests::max_diff(&Pcs::HOME_INPUTS, &[100.0; 6]) < 1e-12);
}

#[test]
fn pcs_forward_kinematics_against_inverse() {
    let pcs = Pcs::new();
    let start = pcs.home_start().unwrap();
    let det0 = det_b(&pcs, &Pcs::HOME_V, &Pcs::HOME_INPUTS);
    let mut rng = Rng::new(71);
    let mut first = true;
    for _ in 0..60 {
        let pose = Pose::from_euler(
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            [
                rng.uniform(-10.0, 10.0),
                rng.uniform(-10.0, 10.0),
                200.0 + rng.uniform(-10.0, 10.0),
            ],
        );
        let s = pcs_inverse(&pose).unwrap();
        let sol = arc_length(&pcs, &start, &s, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "{pose:?}");
        if first {
            // The Jacobians away from home too.
            check_jacobians(&pcs, &sol.v, &s);
            first = false;
        }
        let got = pose_from_unknowns(&pcs, &sol.v).unwrap();
        assert!(linkage_tests::max_diff(&got.translation, &pose.translation) < 1e-7);
        let (a, b) = (got.euler(), pose.euler());
        assert!(linkage_tests::max_diff(&a, &b) < 1e-9, "{a:?} vs {b:?}");
        assert!(det_b(&pcs, &sol.v, &s) * det0 > 0.0);
        check_inverse(&pcs, &sol.v, &s, &Pcs::HOME_INPUTS, 1e-7);
    }
}
