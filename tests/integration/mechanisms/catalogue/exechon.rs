//! An Exechon tripod (Neumann's machine tool; Zoppi, Zlatanov and Molfino, "Kinematics
//! analysis of the Exechon tripod", ASME IDETC 2010): two U-P-R legs and one S-P-R leg, each of
//! active length. The two U joints share their base-fixed axis (the base y axis, through A1
//! and A3), and the platform's R joints of those legs share an axis normal to the plane the two
//! legs span, so the legs and the platform move in a plane that turns about the base y axis.
//! The third leg's R joint keeps it normal to the platform's y axis. Three freedoms: the plane's
//! turn α, the platform's turn β about its own x axis in that plane, and a plunge.
//!
//! Against the closed form of its inverse: a pose of that family (the plane turned by α, the
//! platform by β in it, lifted `w` in the plane away from the base y axis, and slid along that
//! axis as far as the third leg's R joint requires) gives the legs' lengths as distances.

use super::{check_inverse, leg_lengths, mobility_line, GENERAL_MODEL};
use linkage::modes::{AllModes, EndpointKind, ModesOptions, Roots};
use linkage::{
    arc_length, pose_from_unknowns, unknowns_from_pose, InverseError, Mechanism, Pose, Status,
    Tracker,
};
use linkage_tests::vec3::{add, dot, matmul};
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// Two U-P-R legs and one S-P-R leg.
    pub struct Exechon;
    base {
        A1 = [0.0, -300.0, 0.0], A1y = [0.0, -299.0, 0.0],
        A3 = [0.0, 300.0, 0.0], A3y = [0.0, 301.0, 0.0],
        A2 = [350.0, 0.0, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 700.0]) {
        B1 = [0.0, -150.0, 0.0], B1x = [1.0, -150.0, 0.0],
        B3 = [0.0, 150.0, 0.0], B3x = [1.0, 150.0, 0.0],
        B2 = [150.0, 0.0, 0.0], B2y = [150.0, 1.0, 0.0],
    }
    // The S-P-R leg's cylinder: its roll about the leg carries the R joint's axis, so it
    // needs a point off the leg.
    link cylinder2 { E2 = [350.0, 100.0, 0.0] }
    chain leg1 = base - U(A1, axis = A1 -> A1y) - P(active L1) - R(passive, axis = B1 -> B1x) - platform;
    chain leg2 = base - S(A2) - cylinder2 - P(active L2) - R(passive, axis = B2 -> B2y) - platform;
    chain leg3 = base - U(A3, axis = A3 -> A3y) - P(active L3) - R(passive, axis = B3 -> B3x) - platform;
}

/// The legs' base and platform pivots, leg by leg (A1, A2, A3 and B1, B2, B3).
const BASE: [[f64; 3]; 3] = [[0.0, -300.0, 0.0], [350.0, 0.0, 0.0], [0.0, 300.0, 0.0]];
const PLATFORM: [[f64; 3]; 3] = [[0.0, -150.0, 0.0], [150.0, 0.0, 0.0], [0.0, 150.0, 0.0]];

/// The legs' plane turned by `alpha` about the base y axis, the platform by `beta` about its
/// own x axis (the plane's normal), lifted `w` in the plane, and slid along the base y axis so
/// that the S-P-R leg stays normal to the platform's y axis (its R joint's axis).
fn exechon_pose(alpha: f64, beta: f64, w: f64) -> Pose {
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let ry = [[ca, 0.0, sa], [0.0, 1.0, 0.0], [-sa, 0.0, ca]];
    let rx = [[1.0, 0.0, 0.0], [0.0, cb, -sb], [0.0, sb, cb]];
    let rotation = matmul(&ry, &rx);
    let y_p = [0, 1, 2].map(|i| rotation[i][1]);
    let lift = [sa, 0.0, ca];
    // (t − A2) · y_p = 0 with t = u ŷ + w·lift (B2 on the platform's x axis: B2 · y_p = t · y_p).
    let u = (dot(BASE[1], y_p) - w * dot(lift, y_p)) / y_p[1];
    let translation = add([0.0, u, 0.0], lift.map(|c| w * c));
    Pose {
        rotation,
        translation,
    }
}

/// The legs' lengths at a pose: the distances from the base pivots.
fn legs(pose: &Pose) -> [f64; 3] {
    leg_lengths(pose, &BASE, &PLATFORM)
}

/// Panics unless `got` is the pose `want`.
fn same_pose(got: &Pose, want: &Pose, what: &str) {
    for i in 0..3 {
        assert!(
            max_diff(&got.rotation[i], &want.rotation[i]) < 1e-9,
            "{what}: {got:?} vs {want:?}"
        );
    }
    assert!(
        max_diff(&got.translation, &want.translation) < 1e-7,
        "{what}: {got:?} vs {want:?}"
    );
}

#[test]
fn the_exechon_has_three_freedoms_and_exact_jacobians() {
    let exechon = Exechon::new();
    assert_eq!(Exechon::INPUTS, ["L1", "L2", "L3"]);
    // Grübler–Kutzbach counts 1: the U-P-R legs' constraints are dependent.
    assert!(
        mobility_line(Exechon::LISTING).contains("M = 36 + 3 − 36 = 3"),
        "{}",
        mobility_line(Exechon::LISTING)
    );
    let start = exechon.home_start().unwrap();
    assert!(max_diff(start.x(), &legs(&exechon_pose(0.0, 0.0, 700.0))) < 1e-9);
    check_jacobians(&exechon, start.v(), start.x());
    let turned = exechon_pose(0.2, -0.15, 680.0);
    let v = unknowns_from_pose(&exechon, &turned);
    let x = exechon.inverse(&v, start.x()).unwrap();
    let sol = arc_length(&exechon, &start, &x, &GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&exechon, &sol.v, &x);
}

/// Random poses of the family (turns within ±0.25 rad, lifts 640–760 mm): their legs'
/// lengths in closed form, solved back to the pose by continuation from home.
#[test]
fn exechon_forward_kinematics_against_its_closed_form_inverse() {
    let exechon = Exechon::new();
    let start = exechon.home_start().unwrap();
    let mut rng = Rng::new(2010);
    for _ in 0..40 {
        let want = exechon_pose(
            rng.uniform(-0.25, 0.25),
            rng.uniform(-0.25, 0.25),
            rng.uniform(640.0, 760.0),
        );
        let x = legs(&want);
        let sol = arc_length(&exechon, &start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{x:?}");
        same_pose(&pose_from_unknowns(&exechon, &sol.v).unwrap(), &want, "PH");
        check_inverse(&exechon, &sol.v, &x, start.x(), 1e-8);
    }
}

/// The tracker at 1 kHz for 3 s along a smooth path of the family: every sample answered, on
/// the closed form's pose.
#[test]
fn exechon_tracked_along_a_pose_path() {
    let exechon = Exechon::new();
    let start = exechon.home_start().unwrap();
    let mut tracker = Tracker::new(exechon.clone(), start, GENERAL_MODEL);
    for k in 0..=3000 {
        let t = k as f64 * 1e-3;
        let want = exechon_pose(
            0.3 * (1.3 * t).sin(),
            0.25 * (2.1 * t).sin() * (0.7 * t).cos(),
            700.0 - 60.0 * (0.9 * t).sin(),
        );
        let sample = tracker
            .update(&legs(&want))
            .unwrap_or_else(|e| panic!("sample {k}: {e:?}"));
        same_pose(
            &pose_from_unknowns(&exechon, &sample.v).unwrap(),
            &want,
            &format!("sample {k}"),
        );
    }
}

/// A rigid pose off the family — the platform turned about the base z axis, or its legs' plane
/// tilted off the base y axis — has no inputs, although each leg's distance is defined.
#[test]
fn a_pose_off_the_exechon_motion_has_no_inputs() {
    let exechon = Exechon::new();
    let start = exechon.home_start().unwrap();
    let on = exechon_pose(0.1, -0.2, 720.0);
    let v = unknowns_from_pose(&exechon, &on);
    let x = exechon.inverse(&v, start.x()).unwrap();
    assert!(max_diff(&x, &legs(&on)) < 1e-8, "{x:?}");
    let (s, c) = 0.05f64.sin_cos();
    let about_z = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
    let twisted = Pose {
        rotation: matmul(&about_z, &on.rotation),
        ..on
    };
    let mut shifted = on;
    shifted.translation[0] += 15.0;
    for off in [twisted, shifted] {
        let r = exechon.inverse(&unknowns_from_pose(&exechon, &off), start.x());
        assert!(
            matches!(r, Err(InverseError::Unreachable { .. })),
            "{off:?}: {r:?}"
        );
    }
}

/// Every assembly mode at home and at two other inputs: every path of the square system ends
/// at a distinct nonsingular root, four of them real roots off the mechanism (`Spurious`: an
/// equation left out as dependent fails there) — which `Roots::is_complete` counts, since no
/// mode is missing for them (it did not before) — and eight assembly modes, each giving its
/// inputs back, home among them. The start set's 48 is monodromy's count for this model, not
/// a published figure: it is the total the endpoints must add up to.
#[test]
fn exechon_has_eight_real_modes_and_every_path_accounted_for() {
    let exechon = Exechon::new();
    let home = exechon_pose(0.0, 0.0, 700.0);
    let poses = [
        home,
        exechon_pose(0.1, -0.05, 690.0),
        exechon_pose(-0.15, 0.1, 715.0),
    ];
    let modes =
        AllModes::<Exechon, 36, 3, 64>::new(exechon.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 48, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<36, 64>::new());
    for (k, pose) in poses.iter().enumerate() {
        let x = legs(pose);
        modes.solve(&x, &mut roots).unwrap();
        assert_eq!(roots.count(EndpointKind::Spurious), 4, "{x:?}");
        assert_eq!(roots.roots() + 4, 48, "{x:?}: a path ended short of a root");
        assert!(roots.is_complete(), "{x:?}");
        assert_eq!(roots.real().len(), 8, "{x:?}");
        let mut found = false;
        for r in roots.real() {
            assert!(r.residual < 1e-7, "{x:?}: residual {}", r.residual);
            let back = exechon.inverse(&r.v, &x).unwrap();
            assert!(max_diff(&back, &x) < 1e-7, "{x:?}: {back:?}");
            let p = pose_from_unknowns(&exechon, &r.v).unwrap();
            found |= max_diff(&p.translation, &pose.translation) < 1e-7;
        }
        assert!(found, "pose {k} is not among the real modes");
    }
}
