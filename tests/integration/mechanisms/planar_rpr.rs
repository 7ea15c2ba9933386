//! A planar 3-RPR with true R–P–R legs: against closed-form inverse kinematics.

use super::{check_inverse, GENERAL_MODEL};
use linkage::{arc_length, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// A planar 3-RPR with true R–P–R legs: vertical revolute axes at the base and on the
    /// platform, leg lengths driven.
    pub struct PlanarRpr;
    base {
        A1 = [200.0, 0.0, 0.0], A1z = [200.0, 0.0, 1.0],
        A2 = [-100.0, 173.20508075688772, 0.0], A2z = [-100.0, 173.20508075688772, 1.0],
        A3 = [-100.0, -173.20508075688772, 0.0], A3z = [-100.0, -173.20508075688772, 1.0],
    }
    platform(home = [0.3, 0.0, 0.0, 10.0, 5.0, 0.0]) {
        G1 = [60.0, 0.0, 0.0], G1z = [60.0, 0.0, 1.0],
        G2 = [-30.0, 51.96152422706632, 0.0], G2z = [-30.0, 51.96152422706632, 1.0],
        G3 = [-30.0, -51.96152422706632, 0.0], G3z = [-30.0, -51.96152422706632, 1.0],
    }
    chain leg1 = base - R(passive, axis = A1 -> A1z) - P(active L1) - R(passive, axis = G1 -> G1z) - platform;
    chain leg2 = base - R(passive, axis = A2 -> A2z) - P(active L2) - R(passive, axis = G2 -> G2z) - platform;
    chain leg3 = base - R(passive, axis = A3 -> A3z) - P(active L3) - R(passive, axis = G3 -> G3z) - platform;
}

/// Leg lengths of the 3-RPR at a planar pose (φ, x, y): |R(φ) g + t − a|.
fn rpr_legs(pose: [f64; 3]) -> [f64; 3] {
    let s3 = 3f64.sqrt();
    let a = [[200.0, 0.0], [-100.0, 100.0 * s3], [-100.0, -100.0 * s3]];
    let g = [[60.0, 0.0], [-30.0, 30.0 * s3], [-30.0, -30.0 * s3]];
    let (c, s) = (pose[0].cos(), pose[0].sin());
    std::array::from_fn(|i| {
        let p = [
            c * g[i][0] - s * g[i][1] + pose[1],
            s * g[i][0] + c * g[i][1] + pose[2],
        ];
        ((p[0] - a[i][0]).powi(2) + (p[1] - a[i][1]).powi(2)).sqrt()
    })
}

#[test]
fn planar_rpr_forward_kinematics_against_inverse() {
    let rpr = PlanarRpr::new();
    let start = rpr.home_start().unwrap();
    for (i, l) in rpr_legs([0.3, 10.0, 5.0]).iter().enumerate() {
        assert!(
            (start.x()[i] - l).abs() < 1e-9,
            "home legs: {:?}",
            *start.x()
        );
    }
    check_jacobians(&rpr, start.v(), start.x());
    check_factorization(&rpr, start.v(), start.x());
    let mut rng = Rng::new(5);
    for _ in 0..60 {
        let pose = [
            0.3 + rng.uniform(-0.2, 0.2),
            10.0 + rng.uniform(-30.0, 30.0),
            5.0 + rng.uniform(-30.0, 30.0),
        ];
        let legs = rpr_legs(pose);
        let sol = arc_length(&rpr, &start, &legs, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{pose:?}");
        check_inverse(&rpr, &sol.v, &legs, &PlanarRpr::HOME_INPUTS, 1e-8);
        let got = linkage::pose_from_unknowns(&rpr, &sol.v).unwrap();
        let platform = rpr.link_pose(0, &sol.v, &legs).unwrap();
        assert_eq!(PlanarRpr::LINKS[0], "platform");
        assert!(linkage_tests::max_diff(&platform.translation, &got.translation) < 1e-9);
        let [yaw, pitch, roll] = got.euler();
        assert!((yaw - pose[0]).abs() < 1e-8, "{yaw} vs {}", pose[0]);
        assert!(pitch.abs() < 1e-9 && roll.abs() < 1e-9, "stays planar");
        let t = got.translation;
        assert!(
            (t[0] - pose[1]).abs() < 1e-7 && (t[1] - pose[2]).abs() < 1e-7 && t[2].abs() < 1e-9
        );
    }
}
