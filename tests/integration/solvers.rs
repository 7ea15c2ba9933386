//! The three solvers against ground truth: FK against IK, branch fidelity, folds, bad input.

use linkage::{
    arc_length, newton_homotopy, newton_raphson, pose_from_unknowns, Mechanism, Options,
    SolveError, Start, Status,
};
use linkage_examples::{rps, rss_hexapod, stewart};
use linkage_tests::{max_diff, residual_norm, stewart_pose_samples, straight_path_truth, Rng};

#[test]
fn stewart_home_matches_the_errata_check_value() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let pose = pose_from_unknowns(&s, st.v()).unwrap();
    let e = pose.euler();
    assert!(e.iter().all(|a| a.abs() < 1e-5), "{e:?}");
    let t = pose.translation;
    assert!(
        (t[0] - 58.971).abs() < 2e-3
            && (t[1] + 11.739).abs() < 2e-3
            && (t[2] - 159.011).abs() < 2e-3,
        "{t:?}"
    );
}

#[test]
fn stewart_fk_equals_ik_on_random_poses_for_every_method() {
    let dense = Options {
        linear: linkage::Linear::Dense,
        ..Options::TIGHT
    };
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    for sample in stewart_pose_samples(1, 100, 0.3, 40.0, 200) {
        for (name, sol) in [
            (
                "PH",
                arc_length(&s, &st, &sample.x, &Options::TIGHT).unwrap(),
            ),
            (
                "NH",
                newton_homotopy(&s, &st, &sample.x, &Options::TIGHT).unwrap(),
            ),
            (
                "NR",
                newton_raphson(&s, &st, &sample.x, &Options::TIGHT).unwrap(),
            ),
            (
                "PH, dense LU",
                arc_length(&s, &st, &sample.x, &dense).unwrap(),
            ),
            (
                "NR, dense LU",
                newton_raphson(&s, &st, &sample.x, &dense).unwrap(),
            ),
        ] {
            // NH and NR cannot establish the branch: they say so.
            let expected = if name.starts_with('N') {
                Status::Unverified
            } else {
                Status::Converged
            };
            assert_eq!(sol.status, expected, "{name}");
            assert!(
                max_diff(&sol.v, &sample.v) < 1e-7,
                "{name}: {}",
                max_diff(&sol.v, &sample.v)
            );
            let pose = pose_from_unknowns(&s, &sol.v).unwrap();
            assert!(max_diff(&pose.euler(), &sample.pose.euler()) < 1e-9);
            assert!(max_diff(&pose.translation, &sample.pose.translation) < 1e-7);
            assert!(
                (pose.handedness() - 1.0).abs() < 1e-12,
                "never a mirror image"
            );
            assert!(sol.error_estimate < 1e-9, "{name}: {}", sol.error_estimate);
            let back = s.inverse(&sol.v, st.x()).unwrap();
            assert!(max_diff(&back, &sample.x) < 1e-8);
        }
    }
}

/// The worst defect would be a result across a singularity labelled ok. Over a wide range of
/// targets, every `Converged` from PH must be the start's branch continued along the straight
/// joint-space segment (checked by fine continuation that meets no sign change of det B), and
/// every `Fold` must be real (fine continuation does meet one).
#[test]
fn arc_length_never_crosses_a_singularity_labelled_ok() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let mut folds = 0;
    let mut ok = 0;
    // 160 targets (400 with LINKAGE_STRESS set), each checked by 2 000 steps of continuation.
    let count = linkage_tests::sweep(160, 400);
    for sample in stewart_pose_samples(2, count, 1.2, 150.0, 100) {
        let sol = arc_length(&s, &st, &sample.x, &Options::TIGHT).unwrap();
        let (truth, flips) = straight_path_truth(&s, &st, &sample.x, 2000);
        match sol.status {
            Status::Converged => {
                ok += 1;
                assert_eq!(
                    flips, 0,
                    "ok although the straight path crosses a singularity"
                );
                assert!(
                    max_diff(&sol.v, &truth) < 1e-6,
                    "ok but off the straight path's branch by {}",
                    max_diff(&sol.v, &truth)
                );
            }
            Status::Fold { lambda } => {
                folds += 1;
                assert!(
                    flips > 0,
                    "a fold at λ = {lambda} that fine continuation does not see"
                );
                assert!(lambda > 0.0 && lambda < 1.0);
            }
            other => assert!(!sol.is_ok(), "{other:?}"),
        }
    }
    // Most targets are reachable on the straight segment (over 300 of the 400).
    assert!(4 * ok > 3 * count, "{ok} of {count}");
    assert!(folds > 0, "the sample should contain targets behind a fold");
}

#[test]
fn newton_raphson_can_land_on_another_branch_and_is_then_not_ok_or_off_truth() {
    // Documented behaviour of the baselines: far targets may converge elsewhere. When det B
    // changed sign, the status says so; otherwise it says the branch is not established.
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let mut unverified = 0;
    for sample in stewart_pose_samples(3, 100, 1.0, 120.0, 100) {
        let sol = newton_raphson(&s, &st, &sample.x, &Options::PAPER).unwrap();
        assert!(!sol.is_ok(), "NR never claims the branch: {:?}", sol.status);
        if sol.status == Status::Unverified {
            unverified += 1;
            assert!(linkage::det_b(&s, &sol.v, &sample.x) * st.det() > 0.0);
        }
    }
    assert!(unverified > 50, "{unverified}");
}

#[test]
fn rss_hexapod_fk_equals_ik_on_random_poses() {
    let h = rss_hexapod::RssHexapod::new();
    let st = rss_hexapod::home_start(&h).unwrap();
    let home = rss_hexapod::home_pose();
    let mut rng = Rng::new(5);
    let mut solved = 0;
    for _ in 0..100 {
        let e: [f64; 3] = std::array::from_fn(|_| rng.uniform(-0.12, 0.12));
        let t: [f64; 3] = std::array::from_fn(|i| home.translation[i] + rng.uniform(-12.0, 12.0));
        let pose = linkage::Pose::from_euler(e[0], e[1], e[2], t);
        let v = linkage::unknowns_from_pose(&h, &pose);
        let Ok(x) = h.inverse(&v, st.x()) else {
            continue;
        };
        assert!(residual_norm(&h, &v, &x) < 1e-8);
        let sol = arc_length(&h, &st, &x, &Options::TIGHT).unwrap();
        let (truth, flips) = straight_path_truth(&h, &st, &x, 2000);
        if flips > 0 {
            assert!(!sol.is_ok());
            continue;
        }
        assert_eq!(sol.status, Status::Converged);
        assert!(max_diff(&sol.v, &truth) < 1e-6);
        assert!(max_diff(&sol.v, &v) < 1e-6, "{}", max_diff(&sol.v, &v));
        let p = pose_from_unknowns(&h, &sol.v).unwrap();
        assert!(max_diff(&p.euler(), &e) < 1e-8);
        solved += 1;
    }
    assert!(solved > 80, "{solved}");
}

#[test]
fn rps_fk_equals_ik_on_random_inputs() {
    let r = rps::Rps3::new();
    let st = rps::home_start(&r).unwrap();
    let mut rng = Rng::new(6);
    for _ in 0..100 {
        let x: [f64; 3] = std::array::from_fn(|i| st.x()[i] + rng.uniform(-20.0, 20.0));
        for sol in [
            arc_length(&r, &st, &x, &Options::TIGHT).unwrap(),
            newton_homotopy(&r, &st, &x, &Options::TIGHT).unwrap(),
            newton_raphson(&r, &st, &x, &Options::TIGHT).unwrap(),
        ] {
            assert!(sol.status.meets_tolerance(), "{:?}", sol.status);
            // ‖F‖ ≤ ‖B‖ ‖Δv‖: a correction within 1e-9 mm, B of a few hundred mm.
            assert!(residual_norm(&r, &sol.v, &x) < 1e-6);
            let back = r.inverse(&sol.v, st.x()).unwrap();
            assert!(max_diff(&back, &x) < 1e-9);
            let (truth, flips) = straight_path_truth(&r, &st, &x, 500);
            assert_eq!(flips, 0);
            assert!(max_diff(&sol.v, &truth) < 1e-7);
        }
    }
}

#[test]
fn bad_input_gives_typed_errors() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let mut nan = [170.0; 6];
    nan[2] = f64::NAN;
    let mut negative = [170.0; 6];
    negative[4] = -3.0;
    for solve in [
        arc_length::<stewart::Stewart, 18, 6>,
        newton_homotopy,
        newton_raphson,
    ] {
        assert_eq!(
            solve(&s, &st, &nan, &Options::TIGHT),
            Err(SolveError::NonFinite)
        );
        assert_eq!(
            solve(&s, &st, &[f64::INFINITY; 6], &Options::TIGHT),
            Err(SolveError::NonFinite)
        );
        assert_eq!(
            solve(&s, &st, &negative, &Options::TIGHT),
            Err(SolveError::InvalidInput { input: 4 })
        );
        let bad = Options {
            tolerance: f64::NAN,
            ..Options::TIGHT
        };
        assert!(matches!(
            solve(&s, &st, &[170.0; 6], &bad),
            Err(SolveError::InvalidOptions { .. })
        ));
    }
    // A start that is not a solution, and a singular one (platform in the base plane).
    let mut off = *st.v();
    off[0] += 30.0;
    assert!(matches!(
        Start::new(&s, off, *st.x()),
        Err(SolveError::InconsistentStart { .. })
    ));
    let flat = linkage::Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 0.0]);
    let v = linkage::unknowns_from_pose(&s, &flat);
    let x = s.inverse(&v, st.x()).unwrap();
    assert_eq!(Start::new(&s, v, x), Err(SolveError::SingularStart));
    assert_eq!(
        Start::new(&s, [f64::NAN; 18], *st.x()),
        Err(SolveError::NonFinite)
    );
}

#[test]
fn unreachable_legs_end_in_a_typed_outcome() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    // Far beyond the workspace: one leg much longer than the others can follow.
    let x = [170.0, 170.0, 170.0, 170.0, 170.0, 600.0];
    let sol = arc_length(&s, &st, &x, &Options::TIGHT).unwrap();
    assert!(!sol.is_ok(), "{:?}", sol.status);
    assert!(sol.lambda < 1.0);
    // The last point reported lies on the path at λ, to the tracking accuracy (1e-6 of the
    // scale, here about 4e-4 mm).
    let at: [f64; 6] = std::array::from_fn(|j| st.x()[j] + sol.lambda * (x[j] - st.x()[j]));
    assert!(
        linkage::error_estimate(&s, &sol.v, &at) < 1e-3,
        "{}",
        linkage::error_estimate(&s, &sol.v, &at)
    );
}

/// Where the straight segment ends in a fold, `arc_length_detour` may still reach the target;
/// whatever it reaches must be confirmed by fine continuation along the same polyline.
#[test]
fn detours_around_folds_stay_on_the_branch() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let (mut folds, mut reached) = (0, 0);
    for sample in stewart_pose_samples(2, 400, 1.2, 150.0, 100) {
        let r = linkage::arc_length_detour(&s, &st, &sample.x, &Options::TIGHT).unwrap();
        let Some(via) = r.via else {
            assert!(r.left_at.is_none());
            continue;
        };
        folds += 1;
        assert!(
            r.solution.is_ok(),
            "a detour is reported only when it arrived"
        );
        reached += 1;
        let mut here = st;
        for corner in [r.left_at.unwrap(), via, sample.x] {
            let (v, flips) = straight_path_truth(&s, &here, &corner, 3000);
            assert_eq!(flips, 0, "the detour crossed a singularity");
            here = Start::new(&s, v, corner).unwrap();
        }
        assert!(
            max_diff(here.v(), &r.solution.v) < 1e-6,
            "{}",
            max_diff(here.v(), &r.solution.v)
        );
    }
    assert!(
        reached > 0 && folds > 0,
        "the sample should contain folds that a detour passes"
    );
}

/// `NewtonRaphson` factors B at its start once where B does not depend on the inputs: its
/// solves must be `newton_raphson`'s, bit for bit (the same iterates, statuses and
/// estimates), over every Table V point (near-singular ones included), with both options
/// sets, for the Stewart platform, the 3-RPS (both reuse the factorisation) and the 6-RSS
/// hexapod (B moves with its cranks: nothing is reused).
#[test]
fn prepared_newton_raphson_is_newton_raphson() {
    use linkage::NewtonRaphson;
    fn same<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
        sys: &S,
        start: &linkage::Start<N, M>,
        targets: &[[f64; M]],
    ) {
        let nr = NewtonRaphson::new(sys.clone(), *start);
        for x in targets {
            for options in [Options::TIGHT, Options::PAPER] {
                let once = newton_raphson(sys, start, x, &options);
                assert_eq!(nr.solve(x, &options), once, "{} at {x:?}", S::NAME);
            }
        }
    }
    const {
        assert!(!stewart::Stewart::JACOBIAN_USES_INPUTS && !rps::Rps3::JACOBIAN_USES_INPUTS);
        assert!(rss_hexapod::RssHexapod::JACOBIAN_USES_INPUTS);
    }

    let s = stewart::Stewart::new();
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/data/table_v_points.csv"
    ))
    .unwrap();
    let mut legs: Vec<[f64; 6]> = text
        .lines()
        .skip(1)
        .map(|line| {
            let f: Vec<f64> = line
                .split(',')
                .skip(1)
                .take(6)
                .map(|t| t.parse().unwrap())
                .collect();
            std::array::from_fn(|j| f[j])
        })
        .collect();
    assert_eq!(legs.len(), 200);
    // Home itself (the first correction is the answer) and a target no leg can reach.
    let home = stewart::home_start(&s).unwrap();
    legs.extend([*home.x(), [1e4; 6]]);
    same(&s, &home, &legs);

    let mut rng = Rng::new(11);
    let r = rps::Rps3::new();
    let st = rps::home_start(&r).unwrap();
    let targets: Vec<[f64; 3]> = (0..50)
        .map(|_| std::array::from_fn(|i| st.x()[i] + rng.uniform(-40.0, 40.0)))
        .collect();
    same(&r, &st, &targets);

    let h = rss_hexapod::RssHexapod::new();
    let st = rss_hexapod::home_start(&h).unwrap();
    let targets: Vec<[f64; 6]> = (0..20)
        .map(|_| std::array::from_fn(|i| st.x()[i] + rng.uniform(-0.3, 0.3)))
        .collect();
    same(&h, &st, &targets);
}

/// Newton–Raphson's answers hold to the exact Newton correction at the returned point (F in
/// double-double arithmetic, B factored there) and to det B's sign there, however the run
/// measured them: by a Newton correction, or by a chord correction with B factored one
/// correction before, where B is predicted to differ by at most 0.1 % (the chord's size,
/// enlarged by four times that, is then the error estimate). From home to 100 targets around
/// it on the 3-RPS, the 6-RSS hexapod and the Stewart platform, at tolerances from loose to
/// the rounding floor.
#[test]
fn nr_answers_hold_to_the_exact_correction_however_measured() {
    use linkage::NewtonRaphson;
    use linkage_examples::twins::around;
    use linkage_tests::invariants::ok_violation;

    fn check<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
        name: &str,
        sys: &S,
        start: &Start<N, M>,
        by: f64,
    ) {
        let nr = NewtonRaphson::new(sys.clone(), *start);
        for tolerance in [1e-4, 1e-7, 1e-9, 1e-11] {
            let options = Options {
                tolerance,
                ..Options::TIGHT
            };
            let mut met = 0;
            for x in around(start.x(), by) {
                let sol = nr.solve(&x, &options).unwrap();
                if let Some(v) = ok_violation(sys, start.det(), &x, &sol, tolerance) {
                    panic!("{name}, tolerance {tolerance:e}, x = {x:?}: {}", v.what);
                }
                met += usize::from(sol.status.meets_tolerance());
            }
            // Near home every target is regular: all of them meet a tolerance above the
            // rounding floor.
            if tolerance >= 1e-9 {
                assert_eq!(met, 100, "{name}, tolerance {tolerance:e}");
            }
        }
    }
    let r = rps::Rps3::new();
    check("3-RPS", &r, &rps::home_start(&r).unwrap(), 10.0);
    let h = rss_hexapod::RssHexapod::new();
    check("6-RSS", &h, &rss_hexapod::home_start(&h).unwrap(), 0.15);
    let s = stewart::Stewart::new();
    check("Stewart", &s, &stewart::home_start(&s).unwrap(), 10.0);
}
