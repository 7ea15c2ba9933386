//! Cylindrical pairs with one of their two freedoms driven, declared as their two pairs on one
//! axis with a link between (the README's pair table), each against a closed form.
//!
//! - Only the slide: a 3-CRR translational manipulator (the architecture of Kong & Gosselin,
//!   2002, here with its three cylindrical axes orthogonal), each leg
//!   `P(active d, axis = A -> B) - slider - R(passive, axis = S -> Sx)` then two passive R, all
//!   three axes of a leg parallel. Each leg leaves the platform free to move across its axis
//!   and to turn only about it, so three legs on orthogonal axes translate it by exactly the
//!   three slides.
//! - Only the turn: a table on `R(active θ) - sleeve - P(passive)` about one vertical axis, its
//!   height held by a rod from the base: it turns by θ, at the height where the rod reaches.

use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::{arc_length, det_b, pose_from_unknowns, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// Leg i's cylindrical axis runs along the i-th base axis, 300 mm out; its arm (141 mm)
    /// and forearm (141 mm) turn about parallel axes, the forearm's on the platform.
    pub struct Crr;
    base {
        A1 = [0.0, -300.0, 0.0], B1 = [1.0, -300.0, 0.0],
        A2 = [300.0, 0.0, 0.0], B2 = [300.0, 1.0, 0.0],
        A3 = [0.0, 300.0, 0.0], B3 = [0.0, 300.0, 1.0],
    }
    platform {
        G1 = [0.0, -100.0, 0.0], G1x = [1.0, -100.0, 0.0],
        G2 = [100.0, 0.0, 0.0], G2y = [100.0, 1.0, 0.0],
        G3 = [0.0, 100.0, 0.0], G3z = [0.0, 100.0, 1.0],
    }
    link slider1 { S1 = [0.0, -300.0, 0.0], S1x = [1.0, -300.0, 0.0] }
    link slider2 { S2 = [300.0, 0.0, 0.0], S2y = [300.0, 1.0, 0.0] }
    link slider3 { S3 = [0.0, 300.0, 0.0], S3z = [0.0, 300.0, 1.0] }
    link arm1 { E1 = [0.0, -200.0, 100.0], E1x = [1.0, -200.0, 100.0] }
    link arm2 { E2 = [200.0, 0.0, 100.0], E2y = [200.0, 1.0, 100.0] }
    link arm3 { E3 = [100.0, 200.0, 0.0], E3z = [100.0, 200.0, 1.0] }
    link fore1 { } link fore2 { } link fore3 { }
    chain leg1 = base - P(active d1, axis = A1 -> B1) - slider1 - R(passive, axis = S1 -> S1x)
        - arm1 - R(passive, axis = E1 -> E1x) - fore1 - R(passive, axis = G1 -> G1x) - platform;
    chain leg2 = base - P(active d2, axis = A2 -> B2) - slider2 - R(passive, axis = S2 -> S2y)
        - arm2 - R(passive, axis = E2 -> E2y) - fore2 - R(passive, axis = G2 -> G2y) - platform;
    chain leg3 = base - P(active d3, axis = A3 -> B3) - slider3 - R(passive, axis = S3 -> S3z)
        - arm3 - R(passive, axis = E3 -> E3z) - fore3 - R(passive, axis = G3 -> G3z) - platform;
}

#[test]
fn crr_translates_by_its_three_slides() {
    // Overconstrained (Grübler–Kutzbach counts 0): the rank at home decides.
    let line = mobility_line(Crr::LISTING);
    assert!(line.contains("rank of ∂F/∂(v, x) at home"), "{line}");
    assert!(line.contains(" = 3 (Grübler–Kutzbach says 0)"), "{line}");
    let crr = Crr::new();
    let start = crr.home_start().unwrap();
    check_jacobians(&crr, &Crr::HOME_V, &Crr::HOME_INPUTS);
    check_factorization(&crr, &Crr::HOME_V, &Crr::HOME_INPUTS);
    let det0 = start.det();
    let mut rng = Rng::new(2002);
    for _ in 0..linkage_tests::sweep(20, 200) {
        // Within reach: each leg's platform point stays 200 mm across its axis at most 80 mm
        // off, well inside the arm and forearm's 282 mm.
        let d = [
            rng.uniform(-60.0, 60.0),
            rng.uniform(-60.0, 60.0),
            rng.uniform(-60.0, 60.0),
        ];
        let s = arc_length(&crr, &start, &d, &GENERAL_MODEL).unwrap();
        assert_eq!(s.status, Status::Converged, "at {d:?}");
        let pose = pose_from_unknowns(&crr, &s.v).unwrap();
        assert!(
            max_diff(&pose.translation, &d) < 1e-7,
            "at {d:?}: the platform at {:?}",
            pose.translation
        );
        assert!(
            pose.euler().iter().all(|a| a.abs() < 1e-9),
            "at {d:?}: the platform turned {:?}",
            pose.euler()
        );
        assert!(
            det_b(&crr, &s.v, &d) * det0 > 0.0,
            "at {d:?}: det B changed sign"
        );
        check_jacobians(&crr, &s.v, &d);
        check_inverse(&crr, &s.v, &d, &[0.0; 3], 1e-6);
    }
}

linkage::mechanism! {
    /// A table on a cylindrical pair about the base's z axis, driven only in its turn (the
    /// sleeve's pivot K off the axis defines the sleeve's turn); a rod of √5000 mm from A on
    /// the base to G on the table holds its height.
    pub struct Turntable;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0], A = [100.0, 0.0, 0.0] }
    platform { T = [0.0, 0.0, 50.0], Tz = [0.0, 0.0, 51.0], G = [50.0, 0.0, 50.0] }
    link sleeve { K = [10.0, 0.0, 0.0], S0 = [0.0, 0.0, 5.0], Sz = [0.0, 0.0, 10.0] }
    link rod { }
    chain drive = base - R(active th, axis = O -> Oz) - sleeve - P(passive, axis = S0 -> Sz) - platform;
    chain hold = base - S(A) - rod - S(G) - platform;
}

#[test]
fn a_table_turned_on_its_cylinder_rises_where_the_rod_reaches() {
    let line = mobility_line(Turntable::LISTING);
    assert!(line.contains(" = 1 (Grübler–Kutzbach says 1)"), "{line}");
    let table = Turntable::new();
    let start = table.home_start().unwrap();
    check_jacobians(&table, &Turntable::HOME_V, &Turntable::HOME_INPUTS);
    check_factorization(&table, &Turntable::HOME_V, &Turntable::HOME_INPUTS);
    for th in [0.3f64, -0.5, 0.7, -0.7] {
        let s = arc_length(&table, &start, &[th], &Options::default()).unwrap();
        assert_eq!(s.status, Status::Converged, "at {th}");
        let pose = pose_from_unknowns(&table, &s.v).unwrap();
        // G turned to (50 cos θ, 50 sin θ) at height h, √5000 from A = (100, 0, 0).
        let (dx, dy) = (50.0 * th.cos() - 100.0, 50.0 * th.sin());
        let h = (5000.0 - dx * dx - dy * dy).sqrt();
        let e = pose.euler();
        assert!(
            (e[0] - th).abs() < 1e-9 && e[1].abs() < 1e-9 && e[2].abs() < 1e-9,
            "at {th}: {e:?}"
        );
        assert!(
            max_diff(&pose.translation, &[0.0, 0.0, h - 50.0]) < 1e-7,
            "at {th}: the table at {:?}, not at height {h}",
            pose.translation
        );
        check_jacobians(&table, &s.v, &[th]);
    }
    // Turned 1 rad the rod cannot reach: never an ok answer.
    let s = arc_length(&table, &start, &[1.0], &Options::default()).unwrap();
    assert_ne!(s.status, Status::Converged);
}
