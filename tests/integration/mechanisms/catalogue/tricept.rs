//! A Tricept (Neumann's machine; Siciliano, *The Tricept robot*, Robotica 17, 1999): three
//! U-P-S legs of active length, and a passive central column — a U at the base centre, then a
//! slide whose slider is the platform — that lets the platform turn only as the column does
//! and move only along it: three freedoms, two turns and a plunge. Against the closed form of
//! its inverse: a pose of the column's (turned about the base x axis, then about its own y,
//! and slid) gives the legs' lengths as distances.

use super::{check_inverse, leg_lengths, mobility_line, GENERAL_MODEL};
use linkage::{
    arc_length, pose_from_unknowns, unknowns_from_pose, InverseError, Mechanism, Pose, Status,
};
use linkage_tests::vec3::matmul;
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// Three U-P-S legs and a passive U-P column.
    pub struct Tricept;
    base {
        O = [0.0, 0.0, 0.0], Ox = [1.0, 0.0, 0.0],
        A1 = [0.0, 300.0, 0.0], A1t = [-1.0, 300.0, 0.0],
        A2 = [-259.8076211353316, -150.0, 0.0], A2t = [-259.3076211353316, -150.8660254037844, 0.0],
        A3 = [259.8076211353316, -150.0, 0.0], A3t = [259.3076211353316, -149.1339745962156, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 600.0]) {
        C = [0.0, 0.0, 0.0],
        P1 = [0.0, 150.0, 0.0],
        P2 = [-129.9038105676658, -75.0, 0.0],
        P3 = [129.9038105676658, -75.0, 0.0],
    }
    link column { T = [0.0, 0.0, 200.0] }
    chain centre = base - U(O, axis = O -> Ox) - column - P(passive, axis = O -> C) - platform;
    chain leg1 = base - U(A1, axis = A1 -> A1t) - P(active L1) - S(P1) - platform;
    chain leg2 = base - U(A2, axis = A2 -> A2t) - P(active L2) - S(P2) - platform;
    chain leg3 = base - U(A3, axis = A3 -> A3t) - P(active L3) - S(P3) - platform;
}

const BASE: [[f64; 3]; 3] = [
    [0.0, 300.0, 0.0],
    [-259.8076211353316, -150.0, 0.0],
    [259.8076211353316, -150.0, 0.0],
];
const PLATFORM: [[f64; 3]; 3] = [
    [0.0, 150.0, 0.0],
    [-129.9038105676658, -75.0, 0.0],
    [129.9038105676658, -75.0, 0.0],
];

/// The column turned by `a` about the base x axis, then by `b` about its own y, and the
/// platform slid `s` along it from home (600 above the base centre).
fn column_pose(a: f64, b: f64, s: f64) -> Pose {
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let rx = [[1.0, 0.0, 0.0], [0.0, ca, -sa], [0.0, sa, ca]];
    let ry = [[cb, 0.0, sb], [0.0, 1.0, 0.0], [-sb, 0.0, cb]];
    let rotation = matmul(&rx, &ry);
    let translation = [0, 1, 2].map(|i| rotation[i][2] * (600.0 + s));
    Pose {
        rotation,
        translation,
    }
}

/// The legs' lengths at a pose: the inverse kinematics in closed form.
fn legs(pose: &Pose) -> [f64; 3] {
    leg_lengths(pose, &BASE, &PLATFORM)
}

#[test]
fn the_tricept_has_three_freedoms_and_exact_jacobians() {
    let tricept = Tricept::new();
    assert_eq!(Tricept::INPUTS, ["L1", "L2", "L3"]);
    assert!(
        mobility_line(Tricept::LISTING).contains("M = 22 + 3 − 22 = 3"),
        "{}",
        mobility_line(Tricept::LISTING)
    );
    let start = tricept.home_start().unwrap();
    assert!(max_diff(start.x(), &legs(&column_pose(0.0, 0.0, 0.0))) < 1e-9);
    check_jacobians(&tricept, start.v(), start.x());
}

/// Random poses of the column (turns within ±0.3 rad, plunges within ±80 mm): their legs'
/// lengths in closed form, solved back to the pose by continuation from home.
#[test]
fn tricept_forward_kinematics_against_its_closed_form_inverse() {
    let tricept = Tricept::new();
    let start = tricept.home_start().unwrap();
    let mut rng = Rng::new(1999);
    for _ in 0..40 {
        let want = column_pose(
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.3, 0.3),
            rng.uniform(-80.0, 80.0),
        );
        let x = legs(&want);
        let sol = arc_length(&tricept, &start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{x:?}");
        let got = pose_from_unknowns(&tricept, &sol.v).unwrap();
        for i in 0..3 {
            assert!(
                max_diff(&got.rotation[i], &want.rotation[i]) < 1e-9,
                "{x:?}: {got:?} vs {want:?}"
            );
        }
        assert!(
            max_diff(&got.translation, &want.translation) < 1e-7,
            "{x:?}: {got:?} vs {want:?}"
        );
        check_inverse(&tricept, &sol.v, &x, start.x(), 1e-8);
    }
}

/// A rigid pose the column cannot take — the platform shifted 20 mm sideways, or turned about
/// its own axis — has no inputs, although each leg's closed form gives a length for it: the
/// legs' closed forms alone returned those lengths, from which the forward kinematics finds
/// another pose. The column's points are solved for (the numerical inverse, started from the
/// legs' lengths), and the pose refused; a pose the column takes is not.
#[test]
fn a_pose_off_the_columns_motion_has_no_inputs() {
    let tricept = Tricept::new();
    let start = tricept.home_start().unwrap();
    let on = column_pose(0.2, -0.1, 30.0);
    let v = unknowns_from_pose(&tricept, &on);
    let x = tricept.inverse(&v, start.x()).unwrap();
    assert!(max_diff(&x, &legs(&on)) < 1e-8, "{x:?}");
    let mut shifted = on;
    shifted.translation[0] += 20.0;
    let twisted = Pose {
        rotation: matmul(
            &on.rotation,
            &[[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        ),
        ..on
    };
    for off in [shifted, twisted] {
        let r = tricept.inverse(&unknowns_from_pose(&tricept, &off), start.x());
        assert!(
            matches!(r, Err(InverseError::Unreachable { .. })),
            "{off:?}: {r:?}"
        );
    }
}
