//! Property tests: random geometries, poses, inputs and trajectories.

use linkage::{
    arc_length, newton_homotopy, newton_raphson, Mechanism, Options, Pose, Status, Tracker,
};
use linkage_examples::stewart::{
    find_start, legs_for_pose, SixSix, Stewart, StewartGeneral, HOME_LEGS,
};
use linkage_examples::{rps, rss_hexapod};
use linkage_tests::invariants::{ok_violation, point_violation};
use linkage_tests::{
    check_factorization, check_jacobians, max_diff, near_singularities, straight_path_truth,
    toward_singular,
};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// Cases per property: these are cheap (a few ms each), so more than proptest's default.
fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: n,
        // A fixed seed: every run explores the same cases, and a failure replays as it is
        // (no regression files needed).
        rng_seed: RngSeed::Fixed(0x155E_0009),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Leg lengths a hostile caller might pass: NaN, infinities, signed zeros, subnormals, values
/// whose squares overflow, anything in ±1e300, and a few ulps from the home legs.
fn hostile_leg() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(-0.0),
        Just(5e-324),
        -1e300f64..1e300,
        1e150f64..1e160,
        0.0f64..400.0,
        (-4i64..=4).prop_map(|k| f64::from_bits((170.0f64.to_bits() as i64 + k) as u64)),
    ]
}

/// Table III's joints moved by up to `by` mm in x and y, and `lift` mm in z.
fn geometry(by: f64, lift: f64) -> impl Strategy<Value = ([[f64; 3]; 6], [[f64; 3]; 6])> {
    let g = Stewart::DEFAULT_GEOMETRY;
    (
        prop::array::uniform32(-1.0f64..1.0),
        prop::array::uniform32(-1.0f64..1.0),
    )
        .prop_map(move |(a, b)| {
            let joint = |k: usize, offset: usize, r: &[f64; 32]| -> [f64; 3] {
                let i = offset + 3 * k;
                [
                    g[i] + by * r[3 * k],
                    g[i + 1] + by * r[3 * k + 1],
                    g[i + 2] + lift * r[3 * k + 2],
                ]
            };
            (
                std::array::from_fn(|k| joint(k, 0, &a)),
                std::array::from_fn(|k| joint(k, 18, &b)),
            )
        })
}

fn small_motion() -> impl Strategy<Value = [f64; 6]> {
    prop::array::uniform6(-1.0f64..1.0).prop_map(|u| {
        [
            0.2 * u[0],
            0.2 * u[1],
            0.2 * u[2],
            25.0 * u[3],
            25.0 * u[4],
            25.0 * u[5],
        ]
    })
}

fn fk_of_ik<S: SixSix>(sys: &S, motion: [f64; 6]) -> Result<(), TestCaseError> {
    let Ok(start) = find_start(sys, HOME_LEGS, None) else {
        return Ok(());
    };
    let home = linkage::pose_from_unknowns(sys, start.v()).unwrap();
    let e = home.euler();
    let t = home.translation;
    let pose = Pose::from_euler(
        e[0] + motion[0],
        e[1] + motion[1],
        e[2] + motion[2],
        [t[0] + motion[3], t[1] + motion[4], t[2] + motion[5]],
    );
    let Some((x, v)) = legs_for_pose(sys, &pose) else {
        return Ok(());
    };
    prop_assume!(x.iter().all(|l| *l > 20.0));
    let (_, flips) = straight_path_truth(sys, &start, &x, 400);
    let sol = arc_length(sys, &start, &x, &Options::TIGHT).unwrap();
    if flips == 0 {
        // The pose path may still wind around a cusp; only a straight path free of singularities
        // and a target on the same side are asserted.
        let truth_det = linkage::det_b(sys, &v, &x);
        prop_assume!(truth_det * start.det() > 0.0);
        prop_assert_eq!(sol.status, Status::Converged);
        prop_assert!(max_diff(&sol.v, &v) < 1e-6, "{}", max_diff(&sol.v, &v));
    } else {
        prop_assert!(!sol.is_ok());
    }
    Ok(())
}

// Forward kinematics and tracking: a few ms a case.
proptest! {
    #![proptest_config(cases(192))]

    #[test]
    fn fk_of_ik_returns_the_pose_on_coplanar_geometries((base, platform) in geometry(10.0, 0.0), motion in small_motion()) {
        fk_of_ik(&Stewart::with_joints(&base, &platform).unwrap(), motion)?;
    }

    #[test]
    fn fk_of_ik_returns_the_pose_on_general_geometries((base, platform) in geometry(10.0, 20.0), motion in small_motion()) {
        fk_of_ik(&StewartGeneral::with_joints(&base, &platform).unwrap(), motion)?;
    }

    #[test]
    fn tracker_never_changes_branch_on_smooth_trajectories(amp in prop::array::uniform6(-1.0f64..1.0), freq in 0.2f64..2.0) {
        let s = Stewart::new();
        let start = linkage_examples::stewart::home_start(&s).unwrap();
        let home = linkage::pose_from_unknowns(&s, start.v()).unwrap();
        let t0 = home.translation;
        let at = |t: f64| {
            let w = (2.0 * std::f64::consts::PI * freq * t).sin();
            Pose::from_euler(0.15 * amp[0] * w, 0.15 * amp[1] * w, 0.15 * amp[2] * w, [t0[0] + 20.0 * amp[3] * w, t0[1] + 20.0 * amp[4] * w, t0[2] + 20.0 * amp[5] * w])
        };
        let mut tracker = Tracker::new(s.clone(), start, Options::TIGHT);
        for k in 1..=500 {
            let (x, v) = legs_for_pose(&s, &at(k as f64 * 1e-3)).unwrap();
            // Clear of singularities: the true configuration keeps the start's det B sign.
            prop_assume!(linkage::det_b(&s, &v, &x) * start.det() > 0.0);
            let sample = tracker.update(&x).unwrap();
            prop_assert!(max_diff(&sample.v, &v) < 1e-7);
        }
    }
}

// Hostile inputs, Jacobians, factorisations: well under a millisecond a case.
proptest! {
    #![proptest_config(cases(512))]

    #[test]
    fn random_inputs_never_panic(x in prop::array::uniform6(hostile_leg()), paper in any::<bool>()) {
        // Issue 9: every ok keeps the invariants (finite, tolerance met as reported and as
        // measured again, det B of the start's sign) — for every solver and the tracker.
        // Fails on today's runtime by defect 1 (NR calls v = NaN converged for legs whose
        // squares overflow, e.g. [1e150, 4e159, 5e-324, …]); its fix is expected to cure it.
        let s = Stewart::new();
        let start = linkage_examples::stewart::home_start(&s).unwrap();
        let options = if paper { Options::PAPER } else { Options::TIGHT };
        let mut tracker = Tracker::new(s.clone(), start, options);
        // The start's pivots, legs and det B, read through the tracker's public state.
        let (v0, x0) = (*tracker.state().0, *tracker.state().1);
        let det0 = linkage::det_b(&s, &v0, &x0);
        let solves = [
            ("PH", arc_length(&s, &start, &x, &options)),
            ("PH detour", linkage::arc_length_detour(&s, &start, &x, &options).map(|d| d.solution)),
            ("NH", newton_homotopy(&s, &start, &x, &options)),
            ("NR", newton_raphson(&s, &start, &x, &options)),
        ];
        for (name, sol) in solves {
            let Ok(sol) = sol else { continue };
            if let Some(v) = ok_violation(&s, det0, &x, &sol, options.tolerance) {
                prop_assert!(false, "{name} at legs {x:?}: {v}");
            }
            if sol.status.meets_tolerance() {
                let mut f = [0.0; 18];
                s.residual(&sol.v, &x, &mut f);
                prop_assert!(f.iter().all(|r| r.is_finite()));
            }
        }
        if let Ok(sample) = tracker.update(&x) {
            if let Some(v) = point_violation(&s, det0, &x, &sample.v, options.tolerance) {
                prop_assert!(false, "Tracker at legs {x:?}: {v}");
            }
        }
        prop_assert!(tracker.update(&HOME_LEGS).is_ok(), "the tracker stays usable");
    }

    #[test]
    fn generated_jacobians_equal_finite_differences(dv in prop::array::uniform32(-40.0f64..40.0), dx in prop::array::uniform6(-15.0f64..15.0)) {
        let s = Stewart::new();
        let st = linkage_examples::stewart::home_start(&s).unwrap();
        check_jacobians(&s, &std::array::from_fn(|i| st.v()[i] + dv[i]), &std::array::from_fn(|j| st.x()[j] + dx[j]));
        let h = rss_hexapod::RssHexapod::new();
        let hs = rss_hexapod::home_start(&h).unwrap();
        check_jacobians(&h, &std::array::from_fn(|i| hs.v()[i] + dv[i]), &std::array::from_fn(|j| hs.x()[j] + dx[j] / 15.0));
        let r = rps::Rps3::new();
        let rs = rps::home_start(&r).unwrap();
        check_jacobians(&r, &std::array::from_fn(|i| rs.v()[i] + dv[i]), &std::array::from_fn(|j| rs.x()[j] + dx[j]));
    }

    #[test]
    fn generated_factorisations_equal_dense_lu_on_random_geometries((base, platform) in geometry(10.0, 20.0), dv in prop::array::uniform32(-30.0f64..30.0)) {
        // The general (non-coplanar) form has its own sparsity pattern and elimination plan.
        let s = StewartGeneral::with_joints(&base, &platform).unwrap();
        let v0 = linkage::unknowns_from_pose(&s, &Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]));
        let v: [f64; 18] = std::array::from_fn(|i| v0[i] + dv[i]);
        check_jacobians(&s, &v, &HOME_LEGS);
        check_factorization(&s, &v, &HOME_LEGS);
        let c = Stewart::with_joints(&base, &platform.map(|p| [p[0], p[1], 0.0])).unwrap();
        check_factorization(&c, &v, &HOME_LEGS);
        // Toward a singularity of B along a random line: the pivots fixed at generation time
        // meet small pivots and large multipliers there, and the fallback takes over.
        let d: [f64; 18] = std::array::from_fn(|i| 4.0 * dv[31 - i]);
        for v in toward_singular(&s, &v, &d, &HOME_LEGS, 48) {
            check_factorization(&s, &v, &HOME_LEGS);
        }
        for v in toward_singular(&c, &v, &d, &HOME_LEGS, 48) {
            check_factorization(&c, &v, &HOME_LEGS);
        }
    }

    #[test]
    fn generated_factorisations_equal_dense_lu_near_singularities_of_every_example(dv in prop::array::uniform32(-1.0f64..1.0)) {
        let s = Stewart::new();
        near_singularities(&s, &s.home_start().unwrap(), &dv, 120.0, 1.0);
        let g = StewartGeneral::new();
        near_singularities(&g, &g.home_start().unwrap(), &dv, 120.0, 1.0);
        let r = rps::Rps3::new();
        near_singularities(&r, &r.home_start().unwrap(), &dv, 60.0, 1.0);
        let h = rss_hexapod::RssHexapod::new();
        near_singularities(&h, &h.home_start().unwrap(), &dv, 150.0, 0.5);
    }
}
