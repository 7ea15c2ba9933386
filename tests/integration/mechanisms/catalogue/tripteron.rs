//! The Tripteron (Gosselin, Kong, Foucault & Bonev, *A fully decoupled 3-DOF translational
//! parallel mechanism*, PKM 2004): three P-R-R-R legs on orthogonal rails, each leg's three
//! R axes parallel to its rail. A leg leaves its end free to move in the plane square to its
//! rail and to turn about the rail; the three together hold the platform's orientation, and
//! each rail's slide moves the platform along that rail alone: the platform's position is the
//! inputs. Overconstrained (Grübler–Kutzbach counts 0; the rank 3).

use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::{arc_length, pose_from_unknowns, Mechanism, Status};
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// Three P-R-R-R legs; rail i along base axis i, its leg's hinges parallel to it.
    pub struct Tripteron;
    base {
        R1 = [0.0, -300.0, -40.0], R1x = [50.0, -300.0, -40.0],
        R2 = [-300.0, 0.0, -40.0], R2y = [-300.0, 50.0, -40.0],
        R3 = [250.0, 100.0, 40.0], R3z = [250.0, 100.0, 90.0],
    }
    platform {
        T1 = [0.0, -50.0, 0.0], T1x = [30.0, -50.0, 0.0],
        T2 = [-50.0, 0.0, 0.0], T2y = [-50.0, 30.0, 0.0],
        T3 = [40.0, 40.0, 0.0], T3z = [40.0, 40.0, 30.0],
    }
    link carriage1 { K1 = [0.0, -300.0, 0.0], K1x = [30.0, -300.0, 0.0] }
    link arm1 { E1 = [0.0, -150.0, -120.0], E1x = [30.0, -150.0, -120.0] }
    link fore1 { }
    link carriage2 { K2 = [-300.0, 0.0, 0.0], K2y = [-300.0, 30.0, 0.0] }
    link arm2 { E2 = [-150.0, 0.0, -120.0], E2y = [-150.0, 30.0, -120.0] }
    link fore2 { }
    link carriage3 { K3 = [250.0, 100.0, 0.0], K3z = [250.0, 100.0, 30.0] }
    link arm3 { E3 = [150.0, 220.0, 0.0], E3z = [150.0, 220.0, 30.0] }
    link fore3 { }
    chain leg1 = base - P(active q1, axis = R1 -> R1x) - carriage1 - R(passive, axis = K1 -> K1x) - arm1 - R(passive, axis = E1 -> E1x) - fore1 - R(passive, axis = T1 -> T1x) - platform;
    chain leg2 = base - P(active q2, axis = R2 -> R2y) - carriage2 - R(passive, axis = K2 -> K2y) - arm2 - R(passive, axis = E2 -> E2y) - fore2 - R(passive, axis = T2 -> T2y) - platform;
    chain leg3 = base - P(active q3, axis = R3 -> R3z) - carriage3 - R(passive, axis = K3 -> K3z) - arm3 - R(passive, axis = E3 -> E3z) - fore3 - R(passive, axis = T3 -> T3z) - platform;
}

#[test]
fn the_tripteron_has_three_freedoms_by_rank_and_exact_jacobians() {
    let tripteron = Tripteron::new();
    assert_eq!(Tripteron::INPUTS, ["q1", "q2", "q3"]);
    let mobility = mobility_line(Tripteron::LISTING);
    assert!(
        mobility.starts_with("mobility: rank")
            && mobility.contains("= 3 (Grübler–Kutzbach says 0)"),
        "{mobility}"
    );
    let start = tripteron.home_start().unwrap();
    assert_eq!(start.x(), &[0.0; 3]);
    check_jacobians(&tripteron, start.v(), start.x());
}

/// Random slides within ±60 mm: the platform translates by them, without turning.
#[test]
fn the_tripteron_platform_is_where_its_slides_put_it() {
    let tripteron = Tripteron::new();
    let start = tripteron.home_start().unwrap();
    let mut rng = Rng::new(2004);
    for _ in 0..40 {
        let x = [0, 1, 2].map(|_| rng.uniform(-60.0, 60.0));
        let sol = arc_length(&tripteron, &start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{x:?}");
        let got = pose_from_unknowns(&tripteron, &sol.v).unwrap();
        super::identity_within(&got.rotation, 1e-10);
        assert!(max_diff(&got.translation, &x) < 1e-7, "{x:?}: {got:?}");
        check_inverse(&tripteron, &sol.v, &x, &[0.0; 3], 1e-7);
    }
}
