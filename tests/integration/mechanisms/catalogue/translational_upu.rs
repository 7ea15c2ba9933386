//! Tsai's translational 3-UPU: against closed-form inverse kinematics; the platform keeps its
//! orientation.

use super::{check_inverse, GENERAL_MODEL};
use linkage::{arc_length, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// Tsai's translational 3-UPU.
    pub struct TranslationalUpu;
    base {
        A1 = [150.0, 0.0, 0.0], A1a = [150.0, 1.0, 0.0],
        A2 = [-75.0, 129.9038105676658, 0.0], A2a = [-75.86602540378444, 129.4038105676658, 0.0],
        A3 = [-75.0, -129.9038105676658, 0.0], A3a = [-74.13397459621556, -130.4038105676658, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 200.0]) {
        G1 = [60.0, 0.0, 0.0], G1a = [60.0, 1.0, 0.0],
        G2 = [-30.0, 51.96152422706632, 0.0], G2a = [-30.86602540378444, 51.46152422706632, 0.0],
        G3 = [-30.0, -51.96152422706632, 0.0], G3a = [-29.13397459621556, -52.46152422706632, 0.0],
    }
    chain leg1 = base - U(A1, axis = A1 -> A1a) - P(active L1) - U(G1, axis = G1 -> G1a) - platform;
    chain leg2 = base - U(A2, axis = A2 -> A2a) - P(active L2) - U(G2, axis = G2 -> G2a) - platform;
    chain leg3 = base - U(A3, axis = A3 -> A3a) - P(active L3) - U(G3, axis = G3 -> G3a) - platform;
}

/// Closed-form inverse kinematics at the translation `t`: base and platform pivots in one
/// plane, each leg the distance from its base pivot to its platform pivot moved by `t`.
pub(super) fn legs_at(t: [f64; 3]) -> [f64; 3] {
    let s = 3f64.sqrt();
    let a = [[150.0, 0.0], [-75.0, 75.0 * s], [-75.0, -75.0 * s]];
    let g = [[60.0, 0.0], [-30.0, 30.0 * s], [-30.0, -30.0 * s]];
    std::array::from_fn(|i| {
        ((t[0] + g[i][0] - a[i][0]).powi(2) + (t[1] + g[i][1] - a[i][1]).powi(2) + t[2].powi(2))
            .sqrt()
    })
}

#[test]
fn translational_upu_keeps_its_orientation() {
    let upu = TranslationalUpu::new();
    let start = upu.home_start().unwrap();
    check_jacobians(&upu, start.v(), start.x());
    check_factorization(&upu, start.v(), start.x());
    let mut rng = Rng::new(6);
    for _ in 0..60 {
        let t = [
            rng.uniform(-40.0, 40.0),
            rng.uniform(-40.0, 40.0),
            200.0 + rng.uniform(-40.0, 40.0),
        ];
        let legs = legs_at(t);
        let sol = arc_length(&upu, &start, &legs, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{t:?}");
        check_inverse(&upu, &sol.v, &legs, &TranslationalUpu::HOME_INPUTS, 1e-8);
        let got = linkage::pose_from_unknowns(&upu, &sol.v).unwrap();
        for (r, row) in got.rotation.iter().enumerate() {
            for (c, x) in row.iter().enumerate() {
                let id = if r == c { 1.0 } else { 0.0 };
                assert!(
                    (x - id).abs() < 1e-8,
                    "the platform turned: {:?}",
                    got.rotation
                );
            }
        }
        for k in 0..3 {
            assert!(
                (got.translation[k] - t[k]).abs() < 1e-7,
                "{:?} vs {t:?}",
                got.translation
            );
        }
    }
}
