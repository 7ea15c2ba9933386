//! A delta robot whose parallelograms turn on universal joints instead of balls (as in many
//! built ones): each rod an R-R pair at either end, the first axis along the crank's hinge (on
//! the crank) and the platform's edge (on the platform). Each rod now holds its spin and the
//! angle between crank and rod, so the machine is overconstrained: Grübler–Kutzbach counts
//! 6(11 − 1 − 15) + 27 = −3 where it moves with three freedoms, and the model's equations are
//! dependent at every configuration. It moves as the ball-jointed delta does (the platform
//! translates only): against `delta::sphere_intersection`.

use super::delta::sphere_intersection;
use super::{check_inverse, identity_within, mobility_line};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// `delta::Delta`'s dimensions, each rod between two U pairs.
    pub struct DeltaUniversal;
    params {
        rb = 100.0, ra = 100.0, rp = 40.0, hw = 30.0,
        c = cos(2.0 * pi / 3.0), s = sin(2.0 * pi / 3.0),
    }
    base {
        A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
        A2 = [rb * c, rb * s, 0.0], B2 = [rb * c - s, rb * s + c, 0.0],
        A3 = [rb * c, -rb * s, 0.0], B3 = [rb * c + s, -rb * s + c, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -200.0]) {
        F11 = [rp, hw, 0.0], F12 = [rp, -hw, 0.0],
        F21 = [rp * c - hw * s, rp * s + hw * c, 0.0], F22 = [rp * c + hw * s, rp * s - hw * c, 0.0],
        F31 = [rp * c + hw * s, -rp * s + hw * c, 0.0], F32 = [rp * c - hw * s, -rp * s - hw * c, 0.0],
    }
    link arm1 { E11 = [rb + ra, hw, 0.0], E12 = [rb + ra, -hw, 0.0] }
    link arm2 {
        E21 = [(rb + ra) * c - hw * s, (rb + ra) * s + hw * c, 0.0],
        E22 = [(rb + ra) * c + hw * s, (rb + ra) * s - hw * c, 0.0],
    }
    link arm3 {
        E31 = [(rb + ra) * c + hw * s, -(rb + ra) * s + hw * c, 0.0],
        E32 = [(rb + ra) * c - hw * s, -(rb + ra) * s - hw * c, 0.0],
    }
    link rod11 { } link rod12 { } link rod21 { } link rod22 { } link rod31 { } link rod32 { }
    chain arm1a = base - R(active q1, axis = A1 -> B1) - arm1 - U(E11, axis = E11 -> E12) - rod11 - U(F11, axis = F11 -> F12) - platform;
    chain arm1b = arm1 - U(E12, axis = E12 -> E11) - rod12 - U(F12, axis = F12 -> F11) - platform;
    chain arm2a = base - R(active q2, axis = A2 -> B2) - arm2 - U(E21, axis = E21 -> E22) - rod21 - U(F21, axis = F21 -> F22) - platform;
    chain arm2b = arm2 - U(E22, axis = E22 -> E21) - rod22 - U(F22, axis = F22 -> F21) - platform;
    chain arm3a = base - R(active q3, axis = A3 -> B3) - arm3 - U(E31, axis = E31 -> E32) - rod31 - U(F31, axis = F31 -> F32) - platform;
    chain arm3b = arm3 - U(E32, axis = E32 -> E31) - rod32 - U(F32, axis = F32 -> F31) - platform;
}

#[test]
fn the_universal_jointed_delta_has_three_freedoms_by_rank_and_exact_jacobians() {
    let delta = DeltaUniversal::new();
    assert_eq!(DeltaUniversal::INPUTS, ["q1", "q2", "q3"]);
    let mobility = mobility_line(DeltaUniversal::LISTING);
    assert!(
        mobility.contains("M = 54 + 3 − 54 = 3") && mobility.contains("Grübler–Kutzbach says -3"),
        "{mobility}"
    );
    assert!(max_diff(&DeltaUniversal::HOME_INPUTS, &[0.0; 3]) < 1e-12);
    delta.home_start().unwrap();
    check_jacobians(
        &delta,
        &DeltaUniversal::HOME_V,
        &DeltaUniversal::HOME_INPUTS,
    );
    check_factorization(
        &delta,
        &DeltaUniversal::HOME_V,
        &DeltaUniversal::HOME_INPUTS,
    );
}

/// Random crank angles, each answer by continuation from home: the platform unturned, where
/// the ball-jointed delta's closed form puts it, on home's branch, and its inputs given back
/// by the inverse.
#[test]
fn the_universal_jointed_delta_moves_as_the_ball_jointed_one() {
    let delta = DeltaUniversal::new();
    let start = delta.home_start().unwrap();
    let (v0, x0) = (DeltaUniversal::HOME_V, DeltaUniversal::HOME_INPUTS);
    let det0 = det_b(&delta, &v0, &x0);
    let mut rng = Rng::new(47);
    for k in 0..40 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.5, 0.5));
        let sol = arc_length(&delta, &start, &q, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q:?}");
        let pose = pose_from_unknowns(&delta, &sol.v).unwrap();
        identity_within(&pose.rotation, 1e-9);
        let [below, _] = sphere_intersection(q).unwrap();
        assert!(
            max_diff(&pose.translation, &below) < 1e-8,
            "q = {q:?}: {:?} vs {below:?}",
            pose.translation
        );
        assert!(det_b(&delta, &sol.v, &q) * det0 > 0.0, "q = {q:?}");
        if k == 0 {
            check_jacobians(&delta, &sol.v, &q);
        }
        check_inverse(&delta, &sol.v, &q, &[0.0; 3], 1e-9);
    }
}
