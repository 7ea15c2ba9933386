//! A serial pan-tilt head (two freedoms, one chain): a pan R about the base's vertical and a
//! tilt R about a horizontal axis the platform carries. Against the rotation its conventions
//! promise: Rz(pan)·Rx(tilt), the tilt axis turned with the yoke. Declared in
//! `examples/serial-arms`.

use super::check_inverse;
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Pose, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

pub use linkage_serial_arms::PanTilt;

#[test]
fn pan_tilt_has_two_freedoms_by_rank_and_exact_jacobians() {
    let pt = PanTilt::new();
    assert_eq!(PanTilt::INPUTS, ["pan", "tilt"]);
    let line = super::mobility_line(PanTilt::LISTING);
    assert!(
        line.contains("rank of ∂F/∂(v, x) at home") && line.contains(" = 2 (Grübler–Kutzbach"),
        "{line}"
    );
    let s = pt.home_start().unwrap();
    check_jacobians(&pt, s.v(), s.x());
    check_factorization(&pt, s.v(), s.x());
    let sol = arc_length(&pt, &s, &[0.7, -0.4], &super::GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&pt, &sol.v, &[0.7, -0.4]);
}

#[test]
fn pan_tilt_turns_as_its_conventions_promise() {
    let pt = PanTilt::new();
    let start = pt.home_start().unwrap();
    let mut rng = Rng::new(44);
    for _ in 0..60 {
        let x = [rng.uniform(-3.0, 3.0), rng.uniform(-1.4, 1.4)];
        let sol = arc_length(&pt, &start, &x, &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "x = {x:?}");
        // Rz(pan)·Rx(tilt) about T, which lies on the pan axis.
        let r = Pose::from_euler(x[0], 0.0, x[1], [0.0; 3]);
        let t0 = [0.0, 0.0, 50.0];
        let moved = r.apply([0.0, 50.0, 10.0]);
        let truth = [t0[0] + moved[0], t0[1] + moved[1], t0[2] + moved[2]];
        let pose = pose_from_unknowns(&pt, &sol.v).unwrap();
        let q = pose.apply([0.0, 50.0, 60.0]);
        assert!(
            linkage_tests::max_diff(&q, &truth) < 1e-7,
            "x = {x:?}: Q at {q:?}, closed form {truth:?}"
        );
        let [yaw, pitch, roll] = pose.euler();
        assert!(
            (yaw - x[0]).abs() < 1e-9 && pitch.abs() < 1e-9 && (roll - x[1]).abs() < 1e-9,
            "x = {x:?}: {:?}",
            pose.euler()
        );
        assert!(det_b(&pt, &sol.v, &x) * start.det() > 0.0);
        check_inverse(&pt, &sol.v, &x, &PanTilt::HOME_INPUTS, 1e-8);
    }
}
