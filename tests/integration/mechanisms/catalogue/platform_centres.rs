//! Pairs to the base at a platform pivot: the platform's own pivot as the centre of an `S` or
//! `U`, or on the axis of an `R`. The base holds that point too, so it stays where the
//! declaration puts it; the model used to leave it free (no equation tied the platform's
//! copy to the base's), and refused these mechanisms as having three freedoms too many. Found
//! by the random-mechanism sweep (seed 1548618553: a platform on one active `S` at its own
//! pivot). And a slide whose axis is the platform's own, on a base that declares no pivot.

use super::{check_inverse, mobility_line, point};
use linkage::{arc_length, pose_from_unknowns, Mechanism, Options, Pose, Status};
use linkage_tests::vec3::matmul;
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// A spherical motor whose centre C is declared on the platform, turned at home.
    pub struct CentredMotor;
    base { }
    platform(home = [0.3, -0.2, 0.1, 10.0, 20.0, 30.0]) {
        C = [0.0, 0.0, 0.0], X = [50.0, 0.0, 0.0], Y = [0.0, 40.0, 10.0],
    }
    chain motor = base - S(C, active yaw pitch roll) - platform;
}

linkage::mechanism! {
    /// A turntable about the platform's own axis A -> B.
    pub struct Turntable;
    base { }
    platform { A = [5.0, -3.0, 0.0], B = [5.0, -3.0, 10.0], P = [55.0, -3.0, 4.0] }
    chain table = base - R(active t, axis = A -> B) - platform;
}

linkage::mechanism! {
    /// A 3-SPS wrist: three legs of active length turn the platform about its pivot O, which
    /// a passive `S` holds to the base.
    pub struct LegWrist;
    base { B1 = [100.0, 40.0, 0.0], B2 = [-84.6, 66.6, 0.0], B3 = [-15.4, -106.6, 0.0] }
    platform {
        O = [0.0, 0.0, 80.0], P1 = [50.0, 0.0, 100.0], P2 = [-25.0, 43.3, 100.0],
        P3 = [-25.0, -43.3, 100.0],
    }
    chain centre = base - S(O) - platform;
    chain leg1 = base - S(B1) - P(active L1) - S(P1) - platform;
    chain leg2 = base - S(B2) - P(active L2) - S(P2) - platform;
    chain leg3 = base - S(B3) - P(active L3) - S(P3) - platform;
}

#[test]
fn a_motor_centred_on_a_platform_pivot_turns_about_it() {
    let motor = CentredMotor::new();
    assert!(mobility_line(CentredMotor::LISTING).contains("M = 9 + 3 − 9 = 3"));
    let start = motor.home_start().unwrap();
    check_jacobians(&motor, start.v(), start.x());
    let home = Pose::from_euler(0.3, -0.2, 0.1, [10.0, 20.0, 30.0]);
    let mut rng = Rng::new(93);
    for _ in 0..40 {
        let x = [0, 1, 2].map(|_| rng.uniform(-1.0, 1.0));
        let sol = arc_length(&motor, &start, &x, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "{x:?}");
        let got = pose_from_unknowns(&motor, &sol.v).unwrap();
        // The inputs turn the platform from its home orientation, about C = (10, 20, 30).
        let turn = Pose::from_euler(x[0], x[1], x[2], [0.0; 3]);
        let want = matmul(&turn.rotation, &home.rotation);
        for i in 0..3 {
            assert!(max_diff(&got.rotation[i], &want[i]) < 1e-12, "{x:?}");
        }
        assert!(max_diff(&got.translation, &[10.0, 20.0, 30.0]) < 1e-10);
        check_inverse(&motor, &sol.v, &x, &x.map(|a| a + 0.05), 1e-9);
    }
}

#[test]
fn a_turntable_on_the_platforms_own_axis_turns_about_it() {
    let table = Turntable::new();
    assert!(mobility_line(Turntable::LISTING).contains("M = 9 + 1 − 9 = 1"));
    let start = table.home_start().unwrap();
    check_jacobians(&table, start.v(), start.x());
    for t in [-2.5, -0.7, 0.0, 0.4, 1.9] {
        let sol = arc_length(&table, &start, &[t], &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "{t}");
        let got = pose_from_unknowns(&table, &sol.v).unwrap();
        let want = Pose::from_euler(t, 0.0, 0.0, [0.0; 3]);
        for i in 0..3 {
            assert!(max_diff(&got.rotation[i], &want.rotation[i]) < 1e-12, "{t}");
        }
        // The axis x = 5, y = -3 stays: the origin turns about it.
        let (c, s) = (t.cos(), t.sin());
        let origin = [5.0 - 5.0 * c - 3.0 * s, -3.0 - 5.0 * s + 3.0 * c, 0.0];
        assert!(max_diff(&got.translation, &origin) < 1e-10, "{t}");
        check_inverse(&table, &sol.v, &[t], &[t + 0.05], 1e-9);
    }
}

#[test]
fn a_leg_wrist_turns_about_its_platform_pivot_and_meets_its_leg_lengths() {
    let wrist = LegWrist::new();
    assert!(mobility_line(LegWrist::LISTING).contains("M = 12 + 3 − 12 = 3"));
    let start = wrist.home_start().unwrap();
    check_jacobians(&wrist, start.v(), start.x());
    let at = |v: &[f64; 12], name: &str| point::<LegWrist, 12, 3>(v, name);
    let base = [[100.0, 40.0, 0.0], [-84.6, 66.6, 0.0], [-15.4, -106.6, 0.0]];
    let mut rng = Rng::new(94);
    for _ in 0..40 {
        // Within 3 mm of home: 7 mm shorter on two legs and 2.5 on the third meets a fold.
        let x = start.x().map(|l| l + rng.uniform(-3.0, 3.0));
        let sol = arc_length(&wrist, &start, &x, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "{x:?}");
        assert!(max_diff(&at(&sol.v, "O"), &[0.0, 0.0, 80.0]) < 1e-9);
        for (k, name) in ["P1", "P2", "P3"].iter().enumerate() {
            let p = at(&sol.v, name);
            let leg = (0..3)
                .map(|a| (p[a] - base[k][a]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!((leg - x[k]).abs() < 1e-9, "{name}: {leg} vs {}", x[k]);
        }
        let back = wrist.inverse(&sol.v, start.x()).unwrap();
        assert!(max_diff(&back, &x) < 1e-9, "{back:?} vs {x:?}");
    }
}

linkage::mechanism! {
    /// A gimbal whose centre O is declared on the platform: the first axis G -> Z on the
    /// base, the second Z × X (along +y).
    pub struct CentredGimbal;
    base { G = [0.0, 0.0, 0.0], Z = [0.0, 0.0, 1.0] }
    platform { O = [0.0, 0.0, 0.0], X = [60.0, 0.0, 0.0], W = [0.0, 30.0, 5.0] }
    chain gimbal = base - U(O, axis = G -> Z, active a b) - platform;
}

#[test]
fn a_gimbal_centred_on_a_platform_pivot_turns_about_its_two_axes() {
    let gimbal = CentredGimbal::new();
    assert!(mobility_line(CentredGimbal::LISTING).contains("M = 9 + 2 − 9 = 2"));
    let start = gimbal.home_start().unwrap();
    super::motors::turns_as_a_gimbal(&gimbal, &start, 95);
    let x = [0.4, -0.3];
    let sol = arc_length(&gimbal, &start, &x, &Options::TIGHT).unwrap();
    check_inverse(&gimbal, &sol.v, &x, &x.map(|a| a + 0.05), 1e-9);
}

linkage::mechanism! {
    /// A carriage sliding on a base that declares no pivot: the slide's axis A -> B is the
    /// platform's own, so the base holds no point off it. The model used to ask for one
    /// ("the rail `base` has no point off the axis to carry it: declare one"); the base is
    /// fixed, so it now adds its own. Found by the planar and spherical sweep (seed 202113205:
    /// a planar six-bar whose slides on the base had their axes on the sliders).
    pub struct BareBaseCarriage;
    base { }
    platform(home = [0.5, 0.2, -0.1, 20.0, -10.0, 40.0]) {
        A = [0.0, 0.0, 0.0], B = [0.0, 30.0, 0.0], P = [25.0, 10.0, 5.0],
    }
    chain slide = base - P(active s, axis = A -> B) - platform;
}

#[test]
fn a_carriage_on_a_bare_base_slides_along_its_own_axis_without_turning() {
    let carriage = BareBaseCarriage::new();
    let start = carriage.home_start().unwrap();
    assert_eq!(start.x(), &[0.0]);
    check_jacobians(&carriage, start.v(), start.x());
    let home = Pose::from_euler(0.5, 0.2, -0.1, [20.0, -10.0, 40.0]);
    // The axis A -> B in the base frame: the platform's y turned by its home orientation.
    let axis = [0, 1, 2].map(|i| home.rotation[i][1]);
    for s in [-40.0, -3.5, 0.0, 0.25, 17.0, 120.0] {
        let sol = arc_length(&carriage, &start, &[s], &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "{s}");
        let got = pose_from_unknowns(&carriage, &sol.v).unwrap();
        for i in 0..3 {
            assert!(max_diff(&got.rotation[i], &home.rotation[i]) < 1e-12, "{s}");
        }
        let want = [0, 1, 2].map(|i| home.translation[i] + s * axis[i]);
        assert!(max_diff(&got.translation, &want) < 1e-10, "{s}: {got:?}");
        check_inverse(&carriage, &sol.v, &[s], &[s + 1.0], 1e-9);
    }
}
