//! A slider-crank (one freedom): the crank driven, the slider (the platform) on a passive
//! prismatic pair from the base. Against the closed form x = r cos φ + √(l² − r² sin² φ).

use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// Crank r = 40 at 60° at home, rod l = 110, the slider's joint C on the x axis.
    pub struct SliderCrank;
    params { r = 40.0, l = 110.0 }
    base { A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 1.0], S0 = [0.0, 0.0, 0.0], S1 = [1.0, 0.0, 0.0] }
    platform {
        C = [r * cos(pi / 3.0) + sqrt(l * l - r * r * sin(pi / 3.0) * sin(pi / 3.0)), 0.0, 0.0],
        Cz = [r * cos(pi / 3.0) + sqrt(l * l - r * r * sin(pi / 3.0) * sin(pi / 3.0)), 0.0, 1.0],
        Cy = [r * cos(pi / 3.0) + sqrt(l * l - r * r * sin(pi / 3.0) * sin(pi / 3.0)), 10.0, 0.0],
    }
    link crank { B = [r * cos(pi / 3.0), r * sin(pi / 3.0), 0.0], Bz = [r * cos(pi / 3.0), r * sin(pi / 3.0), 1.0] }
    link rod { }
    chain driven = base - R(active q, axis = A -> Az) - crank - R(passive, axis = B -> Bz) - rod - R(passive, axis = C -> Cz) - platform;
    chain guide = base - P(passive, axis = S0 -> S1) - platform;
}

/// The slider's joint on the x axis at crank angle φ (from the x axis).
fn slider(phi: f64) -> f64 {
    let (r, l) = (40.0f64, 110.0f64);
    r * phi.cos() + (l * l - r * r * phi.sin() * phi.sin()).sqrt()
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

#[test]
fn slider_crank_has_one_freedom_by_rank_and_exact_jacobians() {
    let sc = SliderCrank::new();
    assert_eq!(SliderCrank::INPUTS, ["q"]);
    let line = super::mobility_line(SliderCrank::LISTING);
    assert!(
        line.contains("rank of ∂F/∂(v, x) at home") && line.contains(" = 1 (Grübler–Kutzbach"),
        "{line}"
    );
    let s = sc.home_start().unwrap();
    check_jacobians(&sc, s.v(), s.x());
    check_factorization(&sc, s.v(), s.x());
}

#[test]
fn slider_crank_against_the_closed_form_through_both_dead_centres() {
    let sc = SliderCrank::new();
    let start = sc.home_start().unwrap();
    let home = slider(std::f64::consts::PI / 3.0);
    let mut rng = Rng::new(43);
    for _ in 0..60 {
        // Crank angles from −π/3 − 2.9 to −π/3 + 2.9 about home: through the top dead centre
        // (φ = 0) and close to the bottom one (φ = π).
        let q = rng.uniform(-2.9, 2.9);
        let sol = arc_length(&sc, &start, &[q], &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        let pose = pose_from_unknowns(&sc, &sol.v).unwrap();
        // The slider only slides: no turn, no leaving the axis.
        assert!(
            pose.euler().iter().all(|a| a.abs() < 1e-9),
            "q = {q}: {:?}",
            pose.euler()
        );
        let truth = slider(std::f64::consts::PI / 3.0 + q) - home;
        let t = pose.translation;
        assert!(
            (t[0] - truth).abs() < 1e-7 && t[1].abs() < 1e-9 && t[2].abs() < 1e-9,
            "q = {q}: slid {t:?}, closed form {truth}"
        );
        assert!(
            det_b(&sc, &sol.v, &[q]) * start.det() > 0.0,
            "q = {q}: another branch"
        );
        // The slider's place fixes the crank only up to its mirror image in the slide's axis
        // (φ or −φ): the numerical inverse returns one of the two, and either puts it back.
        let back = sc.inverse(&sol.v, &SliderCrank::HOME_INPUTS).unwrap();
        let mirror = -q - 2.0 * std::f64::consts::PI / 3.0;
        assert!(
            wrap(back[0] - q).abs() < 1e-8 || wrap(back[0] - mirror).abs() < 1e-8,
            "q = {q}: inverse {back:?}"
        );
        assert!(linkage_tests::residual_norm(&sc, &sol.v, &back) < 1e-8);
    }
}
