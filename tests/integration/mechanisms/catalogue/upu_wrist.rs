//! The spherical 3-UPU wrist of Karouia & Hervé (*A three-dof tripod for generating spherical
//! rotation*, ARK 2000; Di Gregorio's 3-UPU wrist, J. Mech. Design 2001): three U-P-U legs
//! whose base U's first axis and platform U's last axis all pass through one point O, so
//! that the platform turns about O. Base pivots at radius 150 mm, 100 below O; platform
//! pivots at radius 60, 50 above O, turned 40° from the base's. Against the closed-form
//! inverse L_i = |R g_i − a_i| with O fixed; and after a calibration of its base's depth,
//! which once sent `home_start` into another operation mode of the 3-UPU (the platform
//! 12.4 mm off O and turned −40°), where forward kinematics then answered `Converged`.

use super::{mobility_line, GENERAL_MODEL};
use linkage::{arc_length, pose_from_unknowns, unknowns_from_pose, Mechanism, Pose};
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// Karouia–Hervé spherical 3-UPU: every base U's first axis and every platform U's last
    /// axis through the centre O (the origin); `kb`, `kp` place each axis' second point 20 mm
    /// nearer O.
    pub struct UpuWrist;
    params {
        rb = 150.0, hb = 100.0, rp = 60.0, hp = 50.0,
        kb = 1.0 - 20.0 / sqrt(rb * rb + hb * hb), kp = 1.0 - 20.0 / sqrt(rp * rp + hp * hp),
    }
    base {
        A1 = [rb * cos(90.0 * pi / 180.0), rb * sin(90.0 * pi / 180.0), -hb], Ao1 = [kb * rb * cos(90.0 * pi / 180.0), kb * rb * sin(90.0 * pi / 180.0), -kb * hb],
        A2 = [rb * cos(210.0 * pi / 180.0), rb * sin(210.0 * pi / 180.0), -hb], Ao2 = [kb * rb * cos(210.0 * pi / 180.0), kb * rb * sin(210.0 * pi / 180.0), -kb * hb],
        A3 = [rb * cos(330.0 * pi / 180.0), rb * sin(330.0 * pi / 180.0), -hb], Ao3 = [kb * rb * cos(330.0 * pi / 180.0), kb * rb * sin(330.0 * pi / 180.0), -kb * hb],
    }
    platform {
        G1 = [rp * cos(130.0 * pi / 180.0), rp * sin(130.0 * pi / 180.0), hp], Go1 = [kp * rp * cos(130.0 * pi / 180.0), kp * rp * sin(130.0 * pi / 180.0), kp * hp],
        G2 = [rp * cos(250.0 * pi / 180.0), rp * sin(250.0 * pi / 180.0), hp], Go2 = [kp * rp * cos(250.0 * pi / 180.0), kp * rp * sin(250.0 * pi / 180.0), kp * hp],
        G3 = [rp * cos(370.0 * pi / 180.0), rp * sin(370.0 * pi / 180.0), hp], Go3 = [kp * rp * cos(370.0 * pi / 180.0), kp * rp * sin(370.0 * pi / 180.0), kp * hp],
    }
    chain leg1 = base - U(A1, axis = A1 -> Ao1) - P(active L1) - U(G1, axis = G1 -> Go1) - platform;
    chain leg2 = base - U(A2, axis = A2 -> Ao2) - P(active L2) - U(G2, axis = G2 -> Go2) - platform;
    chain leg3 = base - U(A3, axis = A3 -> Ao3) - P(active L3) - U(G3, axis = G3 -> Go3) - platform;
}

/// The legs' lengths for a rotation about O, with the base `hb` below it: the inverse
/// kinematics in closed form.
fn legs(pose: &Pose, hb: f64) -> [f64; 3] {
    std::array::from_fn(|i| {
        let (p, q) = (
            (90.0 + 120.0 * i as f64).to_radians(),
            (130.0 + 120.0 * i as f64).to_radians(),
        );
        let a = [150.0 * p.cos(), 150.0 * p.sin(), -hb];
        let g = pose.apply([60.0 * q.cos(), 60.0 * q.sin(), 50.0]);
        (0..3).map(|k| (g[k] - a[k]).powi(2)).sum::<f64>().sqrt()
    })
}

/// Forward kinematics by continuation from `start` to the legs of `count` random rotations
/// about O of up to `reach` rad about each axis: every answer `Converged`, the platform turned
/// as asked and its centre still at O.
fn turns_about_its_centre<const N: usize>(
    sys: &UpuWrist,
    start: &linkage::Start<N, 3>,
    hb: f64,
    reach: f64,
    count: usize,
) where
    UpuWrist: Mechanism<N, 3>,
{
    let mut rng = Rng::new(3);
    for _ in 0..count {
        let want = Pose::from_euler(
            rng.uniform(-reach, reach),
            rng.uniform(-reach, reach),
            rng.uniform(-reach, reach),
            [0.0; 3],
        );
        let sol = arc_length(sys, start, &legs(&want, hb), &GENERAL_MODEL).unwrap();
        assert!(sol.is_ok(), "{:?} for {:?}", sol.status, want.euler());
        let got = pose_from_unknowns(sys, &sol.v).unwrap();
        assert!(
            max_diff(&got.translation, &[0.0; 3]) < 1e-6,
            "{:?}",
            got.translation
        );
        assert!(
            max_diff(&got.euler(), &want.euler()) < 1e-8,
            "{:?} vs {:?}",
            got.euler(),
            want.euler()
        );
    }
}

#[test]
fn the_spherical_3_upu_wrist_turns_about_its_centre() {
    let wrist = UpuWrist::new();
    assert!(
        mobility_line(UpuWrist::LISTING).contains("M = 45 + 3 − 45 = 3"),
        "{}",
        mobility_line(UpuWrist::LISTING)
    );
    let start = wrist.home_start().unwrap();
    assert!(
        max_diff(
            start.x(),
            &legs(&Pose::from_euler(0.0, 0.0, 0.0, [0.0; 3]), 100.0)
        ) < 1e-9
    );
    check_jacobians(&wrist, start.v(), start.x());
    let v = unknowns_from_pose(&wrist, &Pose::from_euler(0.2, -0.1, 0.15, [0.0; 3]));
    let x = legs(&Pose::from_euler(0.2, -0.1, 0.15, [0.0; 3]), 100.0);
    let at = arc_length(&wrist, &start, &x, &GENERAL_MODEL).unwrap();
    assert!(at.is_ok());
    check_jacobians(&wrist, &at.v, &x);
    assert!(
        max_diff(
            &pose_from_unknowns(&wrist, &at.v).unwrap().translation,
            &pose_from_unknowns(&wrist, &v).unwrap().translation
        ) < 1e-6
    );
    turns_about_its_centre(&wrist, &start, 100.0, 0.3, 20);
}

/// The base 1 mm deeper: the declared configuration solves nothing there, and at the home
/// legs the wrist stays a wrist — the platform at O, turned about its axis by 0.026 rad. While
/// the model's slide directions and U axes were levers of 1 mm, the residual path from the
/// declared configuration (`Start::follow`, which `home_start` used) ended here in the other
/// operation mode, det B of the other sign; with levers as long as the legs it no longer does
/// (up to 12 mm deeper), so this no longer tells the two paths apart.
#[test]
fn a_calibrated_wrist_starts_in_its_spherical_mode() {
    let declared = UpuWrist::new();
    let home = declared.home_start().unwrap();
    let mut wrist = UpuWrist::new();
    wrist.set_geometry("hb", 101.0).unwrap();
    let start = wrist.home_start().unwrap();
    assert!(start.det() * home.det() > 0.0);
    let pose = pose_from_unknowns(&wrist, start.v()).unwrap();
    assert!(
        max_diff(&pose.translation, &[0.0; 3]) < 1e-6,
        "{:?}",
        pose.translation
    );
    assert!((pose.euler()[0] + 0.026).abs() < 1e-3, "{:?}", pose.euler());
    turns_about_its_centre(&wrist, &start, 101.0, 0.3, 10);
}

/// The certified tracker along a turn of the wrist at 1 kHz: every sample proven and the
/// platform where it was asked to be. With the legs' slide directions and the U joints'
/// second axes as levers of one unit (1 mm) beside legs of 150 mm, as the model made them
/// before, the Krawczyk radius at home was 4.9e-4 mm and the first sample was refused.
#[test]
fn a_turning_wrist_is_tracked_with_a_proof_of_every_sample() {
    let wrist = UpuWrist::new();
    let start = wrist.home_start().unwrap();
    let mut tracker = linkage::Tracker::new(wrist.clone(), start, GENERAL_MODEL).certified();
    for k in 1..=100 {
        let t = k as f64 * 1e-3;
        let want = Pose::from_euler(
            0.3 * (1.3 * t).sin(),
            0.2 * (2.1 * t).sin(),
            0.1 * (0.7 * t).sin(),
            [0.0; 3],
        );
        let sample = tracker
            .update(&legs(&want, 100.0))
            .unwrap_or_else(|e| panic!("sample {k}: {e:?}"));
        assert!(matches!(
            sample.proof,
            Some(linkage::StepProof::Proven { .. })
        ));
        let got = pose_from_unknowns(&wrist, &sample.v).unwrap();
        assert!(max_diff(&got.euler(), &want.euler()) < 1e-8, "sample {k}");
        assert!(max_diff(&got.translation, &[0.0; 3]) < 1e-6, "sample {k}");
    }
}
