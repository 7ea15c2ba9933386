//! Active S and U pairs from the base: a three-axis spherical motor (Table I's roll–pitch–yaw
//! actuator, "special actuators like the three DOF motor") and a two-axis gimbal, each turning
//! a platform about a fixed centre. The system is linear in the unknowns; against the
//! rotations the conventions promise.

use super::mobility_line;
use linkage::{arc_length, pose_from_unknowns, Mechanism, Options, Pose, Start, Status};
use linkage_tests::{check_jacobians, Rng};

linkage::mechanism! {
    /// A platform on a spherical motor at O: yaw, pitch and roll relative to the base.
    pub struct SphericalMotor;
    base { O = [10.0, 20.0, 30.0] }
    platform(home = [0.0, 0.0, 0.0, 10.0, 20.0, 30.0]) {
        X = [50.0, 0.0, 0.0], Y = [0.0, 40.0, 10.0], Q = [0.0, 0.0, 25.0],
    }
    chain motor = base - S(O, active yaw pitch roll) - platform;
}

linkage::mechanism! {
    /// A gimbal at O: the first axis O -> Z (on the base, up), the second perpendicular to it
    /// and to the line from O to the platform's farthest pivot X at home: Z × X, along +y.
    pub struct Gimbal;
    base { G = [0.0, 0.0, 0.0], Z = [0.0, 0.0, 1.0] }
    platform { X = [60.0, 0.0, 0.0], W = [0.0, 30.0, 5.0], V = [0.0, 0.0, 20.0] }
    chain gimbal = base - U(G, axis = G -> Z, active a b) - platform;
}

#[test]
fn spherical_motor_turns_by_yaw_pitch_roll() {
    let motor = SphericalMotor::new();
    assert_eq!(SphericalMotor::INPUTS, ["yaw", "pitch", "roll"]);
    assert!(mobility_line(SphericalMotor::LISTING).contains("M = 9 + 3 − 9 = 3"));
    let start = motor.home_start().unwrap();
    check_jacobians(&motor, start.v(), start.x());
    let mut rng = Rng::new(91);
    for _ in 0..50 {
        let x = [0, 1, 2].map(|_| rng.uniform(-1.2, 1.2));
        let sol = arc_length(&motor, &start, &x, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged);
        let got = pose_from_unknowns(&motor, &sol.v).unwrap();
        let want = Pose::from_euler(x[0], x[1], x[2], [10.0, 20.0, 30.0]);
        for i in 0..3 {
            assert!(linkage_tests::max_diff(&got.rotation[i], &want.rotation[i]) < 1e-12);
        }
        assert!(linkage_tests::max_diff(&got.translation, &want.translation) < 1e-10);
        // The inverse reads the angles back from a reference near them; from any reference its
        // angles turn the platform the same way (Euler angles repeat: yaw + π, π − pitch,
        // roll + π is the same turn).
        let near = x.map(|a| a + 0.05);
        let back = motor.inverse(&sol.v, &near).unwrap();
        assert!(
            linkage_tests::max_diff(&back, &x) < 1e-9,
            "{back:?} vs {x:?}"
        );
        let any = motor.inverse(&sol.v, &[0.0; 3]).unwrap();
        let same = Pose::from_euler(any[0], any[1], any[2], [0.0; 3]);
        for i in 0..3 {
            assert!(linkage_tests::max_diff(&same.rotation[i], &want.rotation[i]) < 1e-9);
        }
    }
}

#[test]
fn gimbal_turns_about_its_two_axes() {
    let gimbal = Gimbal::new();
    assert!(mobility_line(Gimbal::LISTING).contains("M = 9 + 2 − 9 = 2"));
    turns_as_a_gimbal(&gimbal, &gimbal.home_start().unwrap(), 92);
}

/// A gimbal centred at the origin, its first axis +z on the base and its second +y at home:
/// the inputs (a, b) turn the platform by Rz(a)·Ry(b), a yaw of a, then a pitch of b.
pub(super) fn turns_as_a_gimbal<S: Mechanism<9, 2>>(gimbal: &S, start: &Start<9, 2>, seed: u64) {
    check_jacobians(gimbal, start.v(), start.x());
    let mut rng = Rng::new(seed);
    for _ in 0..50 {
        let x = [0, 1].map(|_| rng.uniform(-1.0, 1.0));
        let sol = arc_length(gimbal, start, &x, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged);
        let got = pose_from_unknowns(gimbal, &sol.v).unwrap();
        let want = Pose::from_euler(x[0], x[1], 0.0, [0.0; 3]);
        for i in 0..3 {
            assert!(
                linkage_tests::max_diff(&got.rotation[i], &want.rotation[i]) < 1e-12,
                "{x:?}: {:?}",
                got.rotation
            );
        }
        assert!(got.translation.iter().all(|t| t.abs() < 1e-10));
    }
}
