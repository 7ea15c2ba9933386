//! What `AllModes::new` says about its start set (`StartReport`): how monodromy ended and how
//! late its last new root came, checked where the root count is known.

use linkage::modes::{AllModes, Complex, Ended, ModesError, ModesOptions, Roots, StartReport};
use linkage_examples::rps::Rps3;
use linkage_examples::stewart::{SixSix, StewartGeneral};
use linkage_tests::Rng;

/// A general 6-6 platform: joint centres at random around the z axis, up to 20 mm off their
/// planes (the declared `StewartGeneral::new()` is Table III's, with 28 roots).
fn general_six_six() -> StewartGeneral {
    let mut rng = Rng::new(6601);
    let mut point = |radius: f64| {
        let r = radius * rng.uniform(0.5, 1.0);
        let t = rng.uniform(0.0, std::f64::consts::TAU);
        [r * t.cos(), r * t.sin(), 20.0 * rng.symmetric()]
    };
    let base = [0; 6].map(|_| point(150.0));
    let platform = [0; 6].map(|_| point(100.0));
    StewartGeneral::with_joints(&base, &platform).unwrap()
}

/// The fields of a count-stable stop agree with the stopping rule of `options`.
fn check_stable(report: &StartReport, count: usize, options: &ModesOptions, label: &str) {
    assert_eq!(report.ended, Ended::Stable, "{label}: {report:?}");
    // The last loops brought nothing: at least `stable_loops` of them in a row.
    assert!(
        report.loops_since_new >= options.stable_loops,
        "{label}: {report:?}"
    );
    // The seeds' rule: max(stable_seeds, ⌈confidence · count / smallest find⌉), and at least
    // that many fruitless seeds since the last new root (one more where the home was tried).
    assert!(
        report.smallest_find >= 1 && report.smallest_find <= count,
        "{label}: {report:?}"
    );
    let rule = (options.confidence * count as f64 / report.smallest_find as f64).ceil() as usize;
    assert_eq!(
        report.seeds_needed,
        options.stable_seeds.max(rule),
        "{label}: {report:?}"
    );
    assert!(
        report.seeds_since_new >= report.seeds_needed
            && report.seeds_since_new <= report.seeds_needed + 1,
        "{label}: {report:?}"
    );
    assert!(
        report.first_settled >= 1 && report.first_settled <= count,
        "{label}: {report:?}"
    );
    assert!(report.seeds > report.seeds_since_new, "{label}: {report:?}");
}

/// The 3-RPS (16 roots, two components of eight) and a general 6-6 platform (40): count
/// stability ends both, and the report's fields agree with the rule. The 3-RPS's loops settle
/// at one component of eight, and a random seed finds the other.
#[test]
fn start_report_of_a_count_stable_run() {
    let options = ModesOptions::default();
    let rps = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &options).unwrap();
    assert_eq!(rps.start_count(), 16, "{:?}", rps.report());
    check_stable(&rps.report(), 16, &options, "3-RPS");
    assert_eq!(rps.report().first_settled, 8, "{:?}", rps.report());
    assert_eq!(rps.report().smallest_find, 8, "{:?}", rps.report());
    assert!(rps.report().seed_finds >= 1, "{:?}", rps.report());
    let six = AllModes::<_, 18, 6, 64>::new(general_six_six(), &options).unwrap();
    assert_eq!(six.start_count(), 40, "{:?}", six.report());
    check_stable(&six.report(), 40, &options, "6-6");
    // All 40 on the first seed's component: the loops alone found them.
    assert_eq!(six.report().first_settled, 40, "{:?}", six.report());
    assert_eq!(six.report().smallest_find, 40, "{:?}", six.report());
    assert!(!six.report().last_after_seed, "{:?}", six.report());
    println!("3-RPS: {:?}\n6-6: {:?}", rps.report(), six.report());
}

/// A run stopped by a tiny loop cap says so; one stopped at the expected count says that; a start set given is not monodromy's.
#[test]
fn start_report_of_capped_and_given_runs() {
    let capped = ModesOptions {
        max_loops: 2,
        ..ModesOptions::default()
    };
    let six = AllModes::<_, 18, 6, 64>::new(general_six_six(), &capped).unwrap();
    let report = six.report();
    assert_eq!(report.ended, Ended::LoopCap, "{report:?}");
    assert_eq!(report.loops, 2, "{report:?}");
    assert_eq!(report.seeds_needed, 0, "{report:?}");
    // Short of the 40 (14 measured: a loop also carries the roots it finds).
    assert!(six.start_count() < 40, "{report:?}");
    // And no list tracked from it calls itself complete.
    let mut roots = Box::new(Roots::<18, 64>::new());
    six.solve(&[200.0; 6], &mut roots).unwrap();
    assert!(roots.start_set_capped() && !roots.is_complete());

    let expected = ModesOptions {
        expected: Some(16),
        ..ModesOptions::default()
    };
    let rps = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &expected).unwrap();
    assert_eq!(rps.report().ended, Ended::Expected, "{:?}", rps.report());
    assert_eq!(rps.start_count(), 16);

    let (p0, gamma) = rps.base_point();
    let starts: Vec<[Complex; 9]> = (0..16).map(|i| rps.start(i).unwrap()).collect();
    let given =
        AllModes::<_, 9, 3, 32>::from_starts(Rps3::new(), *p0, gamma, &starts, &expected).unwrap();
    assert_eq!(given.report().ended, Ended::Given);
    assert_eq!(given.report().loops, 0);
    let mut roots = Roots::<9, 32>::new();
    given.solve(&Rps3::HOME_INPUTS, &mut roots).unwrap();
    assert!(!roots.start_set_capped() && roots.is_complete());

    // A confidence that is not a finite non-negative number is an error, not a panic.
    for confidence in [f64::NAN, -1.0, f64::INFINITY] {
        let bad = ModesOptions {
            confidence,
            ..ModesOptions::default()
        };
        let err = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &bad).err();
        assert_eq!(err, Some(ModesError::NonFinite), "{confidence}");
    }
}
