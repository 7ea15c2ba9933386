//! All assembly modes (`linkage::modes`): complete root counts by monodromy and parameter
//! homotopy on random 6-6 platforms, checked against an independent method — Newton's method
//! in real arithmetic from many random poses — and against the pose that generated the legs.

use linkage::lu::Lu;
use linkage::modes::{AllModes, Complex, EndpointKind, ModesError, ModesOptions, Roots};
use linkage::{Mechanism, Pose};
use linkage_examples::rps::Rps3;
use linkage_examples::stewart::{
    legs_for_pose, SixSix, Stewart, StewartGeneral, HOME_LEGS, HOME_POSE,
};
use linkage_tests::{sweep, Rng};

/// A point at radius 0.5…1 × `radius` around the z axis, up to `height` off the plane z = 0.
fn random_point(rng: &mut Rng, radius: f64, height: f64) -> [f64; 3] {
    let r = radius * rng.uniform(0.5, 1.0);
    let t = rng.uniform(0.0, std::f64::consts::TAU);
    [r * t.cos(), r * t.sin(), height * rng.symmetric()]
}

fn random_pose(rng: &mut Rng) -> Pose {
    Pose::from_euler(
        rng.uniform(-0.4, 0.4),
        rng.uniform(-0.3, 0.3),
        rng.uniform(-0.3, 0.3),
        [
            rng.uniform(-30.0, 30.0),
            rng.uniform(-30.0, 30.0),
            rng.uniform(120.0, 200.0),
        ],
    )
}

fn close<const N: usize>(a: &[f64; N], b: &[f64; N], tol: f64) -> bool {
    a.iter()
        .zip(b)
        .all(|(p, q)| (p - q).abs() <= tol * p.abs().max(100.0))
}

/// Distinct nonsingular real roots reached by Newton's method (dense LU, real arithmetic) from
/// `starts` random poses anywhere within `reach` (any orientation, above or below the base).
pub(crate) fn newton_roots<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    x: &[f64; M],
    reach: f64,
    rng: &mut Rng,
    starts: usize,
) -> Vec<[f64; N]> {
    let mut found: Vec<[f64; N]> = Vec::new();
    for _ in 0..starts {
        let pose = Pose::from_euler(
            rng.uniform(-3.2, 3.2),
            rng.uniform(-1.6, 1.6),
            rng.uniform(-3.2, 3.2),
            [
                reach * rng.symmetric(),
                reach * rng.symmetric(),
                reach * rng.symmetric(),
            ],
        );
        let mut v = linkage::unknowns_from_pose(sys, &pose);
        let mut converged = false;
        for _ in 0..60 {
            let mut f = [0.0; N];
            let mut b = [[0.0; N]; N];
            sys.residual(&v, x, &mut f);
            sys.jacobian_dense(&v, x, &mut b);
            let Some(lu) = Lu::new(b) else {
                break;
            };
            lu.solve(&mut f);
            let size = f.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            for i in 0..N {
                v[i] -= f[i];
            }
            if !(size <= 1e6) {
                break;
            }
            if size < 1e-10 {
                converged = true;
                break;
            }
        }
        let mut f = [0.0; N];
        sys.residual(&v, x, &mut f);
        let residual = f.iter().fold(0.0f64, |m, r| m.max(r.abs()));
        if converged
            && residual < 1e-6
            && linkage::det_b(sys, &v, x) != 0.0
            && !found.iter().any(|w| close(w, &v, 1e-6))
        {
            found.push(v);
        }
    }
    found
}

/// Checks one solve: every real root (residual, pose, legs by inverse kinematics), the
/// generating configuration `v_true` among them, every root Newton finds among them. Returns
/// (complete, real roots, Newton roots).
fn check_roots<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    sys: &S,
    modes: &AllModes<S, N, M, K>,
    x: &[f64; M],
    v_true: Option<&[f64; N]>,
    reach: f64,
    rng: &mut Rng,
    label: &str,
) -> (bool, usize, usize) {
    let mut roots = Box::new(Roots::<N, K>::new());
    modes.solve(x, &mut roots).unwrap();
    for r in roots.real() {
        assert!(r.residual < 1e-7, "{label}: residual {}", r.residual);
        assert!(r.pose.is_some(), "{label}: no pose");
        let back = sys.inverse(&r.v, x).unwrap();
        assert!(
            back.iter().zip(x).all(|(a, b)| (a - b).abs() < 1e-7),
            "{label}: legs {back:?} vs {x:?}"
        );
        assert!(r.det != 0.0 && r.nearest > 0.0);
    }
    if let Some(v_true) = v_true {
        assert!(
            roots.real().iter().any(|r| close(&r.v, v_true, 1e-7)),
            "{label}: the generating pose is not among the {} real roots",
            roots.real().len()
        );
    }
    let newton = newton_roots(sys, x, reach, rng, 300);
    for w in &newton {
        assert!(
            roots.real().iter().any(|r| close(&r.v, w, 1e-6)),
            "{label}: Newton found a real root the solver missed ({} real, {} by Newton)",
            roots.real().len(),
            newton.len()
        );
    }
    let complete = modes.start_count() == roots.roots() && roots.is_complete();
    if !complete {
        println!(
            "{label}: {} starts ({:?}), {} roots: {} singular, {} diverging, {} duplicate, {} failed",
            modes.start_count(),
            modes.report(),
            roots.roots(),
            roots.count(EndpointKind::Singular),
            roots.count(EndpointKind::Diverging),
            roots.count(EndpointKind::Duplicate),
            roots.count(EndpointKind::Failed)
        );
    }
    (complete, roots.real().len(), newton.len())
}

/// Builds the solver for a 6-6 platform (start set recentred at a level pose 160 mm up) and
/// checks the legs of `pose`; `true` if all 40 roots were found.
fn check_six_six<S: SixSix>(
    sys: S,
    pose: &Pose,
    rng: &mut Rng,
    label: &str,
) -> (bool, usize, usize) {
    let mut modes = AllModes::<S, 18, 6, 64>::new(sys.clone(), &ModesOptions::default())
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let centre = Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 160.0]);
    let (c, _) = legs_for_pose(&sys, &centre).expect("legs of the centre pose");
    modes
        .recenter(&c, 0.1, 7)
        .unwrap_or_else(|e| panic!("{label}: recenter: {e}"));
    let (x, v_true) = legs_for_pose(&sys, pose).expect("legs of the pose");
    let (complete, real, newton) = check_roots(&sys, &modes, &x, Some(&v_true), 300.0, rng, label);
    (complete && modes.start_count() == 40, real, newton)
}

/// At least 99 % complete (with fewer than 100 cases: every one).
fn summary(cases: &[(bool, usize, usize)], label: &str) {
    let complete = cases.iter().filter(|c| c.0).count();
    let real: usize = cases.iter().map(|c| c.1).sum();
    let newton: usize = cases.iter().map(|c| c.2).sum();
    println!(
        "{label}: {complete}/{} cases with all 40 roots; {real} real roots, Newton from 300 random poses per case found {newton}",
        cases.len()
    );
    assert!(
        100 * complete >= 99 * cases.len(),
        "{label}: only {complete} of {} cases complete",
        cases.len()
    );
}

#[test]
fn general_six_six_platforms_have_all_forty_roots() {
    // 4 random platforms (about 3 s on an idle core); 50 with LINKAGE_STRESS set.
    let cases: Vec<_> = (0..sweep(4, 50) as u64)
        .map(|k| {
            let mut rng = Rng::new(6600 + k);
            let base = [0; 6].map(|_| random_point(&mut rng, 150.0, 20.0));
            let platform = [0; 6].map(|_| random_point(&mut rng, 100.0, 20.0));
            let sys = StewartGeneral::with_joints(&base, &platform).unwrap();
            let pose = random_pose(&mut rng);
            check_six_six(sys, &pose, &mut rng, &format!("general {k}"))
        })
        .collect();
    summary(&cases, "general 6-6");
}

#[test]
fn planar_six_six_platforms_have_all_forty_roots() {
    // 5 random platforms; 20 with LINKAGE_STRESS set.
    let cases: Vec<_> = (0..sweep(5, 20) as u64)
        .map(|k| {
            let mut rng = Rng::new(4400 + k);
            let base = [0; 6].map(|_| random_point(&mut rng, 150.0, 0.0));
            let platform = [0; 6].map(|_| random_point(&mut rng, 100.0, 0.0));
            let sys = Stewart::with_joints(&base, &platform).unwrap();
            let pose = random_pose(&mut rng);
            check_six_six(sys, &pose, &mut rng, &format!("planar {k}"))
        })
        .collect();
    summary(&cases, "planar 6-6");
}

/// Dietmaier's 6-6 platform (P. Dietmaier, "The Stewart-Gough platform of general geometry can
/// have 40 real postures", ARK 1998), with the coordinates and leg lengths as published to six
/// digits: all 40 complex roots are real. Every one is checked (residual, legs given back by
/// inverse kinematics, a regular B), the 40 poses are distinct, and every root real Newton's
/// method reaches from random poses is among them.
#[test]
fn dietmaier_platform_has_forty_real_postures() {
    let base = [
        [0.0, 0.0, 0.0],
        [1.107915, 0.0, 0.0],
        [0.549094, 0.756063, 0.0],
        [0.735077, -0.223935, 0.525991],
        [0.514188, -0.526063, -0.368418],
        [0.590473, 0.094733, -0.205018],
    ];
    let platform = [
        [0.0, 0.0, 0.0],
        [0.542805, 0.0, 0.0],
        [0.956919, -0.528915, 0.0],
        [0.665885, -0.353482, 1.402538],
        [0.478359, 1.158742, 0.107672],
        [-0.137087, -0.235121, 0.353913],
    ];
    let legs = [1.0, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071];
    let sys = StewartGeneral::with_joints(&base, &platform).unwrap();
    let modes = AllModes::<_, 18, 6, 64>::new(sys.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 40, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<18, 64>::new());
    modes.solve(&legs, &mut roots).unwrap();
    assert!(
        roots.is_complete(),
        "{:?}",
        roots.endpoints().iter().map(|e| e.kind).collect::<Vec<_>>()
    );
    assert_eq!(roots.real().len(), 40);
    for r in roots.real() {
        assert!(r.residual < 1e-12, "residual {}", r.residual);
        let back = sys.inverse(&r.v, &legs).unwrap();
        assert!(
            back.iter().zip(&legs).all(|(a, b)| (a - b).abs() < 1e-10),
            "{back:?}"
        );
        assert!(r.det != 0.0 && r.nearest_real > 1e-6, "{r:?}");
        assert!(r.pose.is_some());
    }
    let mut rng = Rng::new(1998);
    let newton = newton_roots(&sys, &legs, 2.0, &mut rng, 2000);
    for w in &newton {
        assert!(
            roots
                .real()
                .iter()
                .any(|r| r.v.iter().zip(w).all(|(a, b)| (a - b).abs() < 1e-7)),
            "Newton reached a real root the solver missed"
        );
    }
    println!(
        "Dietmaier: 40 real of 40; Newton from 2000 random poses reached {}",
        newton.len()
    );
}

#[test]
fn table_iii_platform_at_home_legs() {
    let sys = Stewart::new();
    let modes = AllModes::<_, 18, 6, 64>::new(sys.clone(), &ModesOptions::default()).unwrap();
    let [yaw, pitch, roll, x, y, z] = HOME_POSE;
    let home = linkage::unknowns_from_pose(&sys, &Pose::from_euler(yaw, pitch, roll, [x, y, z]));
    // HOME_POSE is rounded to 1 µm: refine it to the root it names.
    let home = *linkage::Start::new(&sys, home, HOME_LEGS).unwrap().v();
    let mut rng = Rng::new(3);
    let (_, real, newton) = check_roots(
        &sys,
        &modes,
        &HOME_LEGS,
        Some(&home),
        300.0,
        &mut rng,
        "Table III",
    );
    let mut roots = Box::new(Roots::<18, 64>::new());
    modes.solve(&HOME_LEGS, &mut roots).unwrap();
    println!(
        "Table III at legs 170 mm: {} starts, {} roots ({} real, Newton found {newton}), {} singular, {} diverging, {} failed",
        modes.start_count(),
        roots.roots(),
        real,
        roots.count(EndpointKind::Singular),
        roots.count(EndpointKind::Diverging),
        roots.count(EndpointKind::Failed)
    );
    // Base and platform are planar: every mode has its mirror image through the base plane.
    for r in roots.real() {
        let mut mirror = r.v;
        for z in &mut mirror[12..] {
            *z = -*z;
        }
        assert!(roots.real().iter().any(|q| close(&q.v, &mirror, 1e-7)));
    }
}

#[test]
fn three_rps_has_sixteen_roots() {
    let sys = Rps3::new();
    let modes = AllModes::<_, 9, 3, 32>::new(sys.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 16, "{:?}", modes.report());
    let mut rng = Rng::new(16);
    for k in 0..5 {
        // A level pose (which a 3-RPS reaches) and its legs; then legs near them.
        let pose = Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, rng.uniform(120.0, 180.0)]);
        let v0 = linkage::unknowns_from_pose(&sys, &pose);
        let x0 = sys.inverse(&v0, &[150.0; 3]).unwrap();
        // The declared pivots are rounded to 1 µm: refine to the root the pose names.
        let v0 = *linkage::Start::new(&sys, v0, x0).unwrap().v();
        let label = format!("3-RPS {k}");
        let (complete, _, _) = check_roots(&sys, &modes, &x0, Some(&v0), 300.0, &mut rng, &label);
        assert!(complete, "{label}");
        let x = x0.map(|l| l + rng.uniform(-10.0, 10.0));
        let (complete, _, _) = check_roots(&sys, &modes, &x, None, 300.0, &mut rng, &label);
        assert!(complete, "{label}, moved legs");
    }
}

#[test]
fn degenerate_geometry_and_bad_inputs_are_errors() {
    // Base and platform similar, on circles (conics, projectively related): architecture
    // singular, B is singular in every configuration.
    let circle = |r: f64| {
        core::array::from_fn::<[f64; 3], 6, _>(|i| {
            let t = [0.0, 0.9, 2.1, 3.0, 4.2, 5.1][i];
            [r * f64::cos(t), r * f64::sin(t), 0.0]
        })
    };
    let sys = Stewart::with_joints(&circle(150.0), &circle(80.0)).unwrap();
    let err = AllModes::<_, 18, 6, 64>::new(sys, &ModesOptions::default()).err();
    assert_eq!(err, Some(ModesError::Degenerate));

    let modes = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &ModesOptions::default()).unwrap();
    let mut roots = Box::new(Roots::<9, 32>::new());
    for (x, e) in [
        ([f64::NAN, 150.0, 150.0], ModesError::NonFinite),
        ([150.0, f64::INFINITY, 150.0], ModesError::NonFinite),
        ([150.0, 150.0, -1.0], ModesError::InvalidInput { input: 2 }),
    ] {
        assert_eq!(modes.solve(&x, &mut roots), Err(e));
    }
    // Too small a capacity is an error, not a truncated answer.
    let small = AllModes::<_, 9, 3, 8>::new(Rps3::new(), &ModesOptions::default()).err();
    assert_eq!(small, Some(ModesError::Capacity { capacity: 8 }));
}

#[test]
fn stored_starts_give_the_same_roots() {
    let sys = Rps3::new();
    let modes = AllModes::<_, 9, 3, 32>::new(sys.clone(), &ModesOptions::default()).unwrap();
    let (p0, gamma) = modes.base_point();
    let starts: Vec<[Complex; 9]> = (0..modes.start_count())
        .map(|i| modes.start(i).unwrap())
        .collect();
    let again =
        AllModes::<_, 9, 3, 32>::from_starts(sys, *p0, gamma, &starts, &ModesOptions::default())
            .unwrap();
    let x = [150.0, 160.0, 155.0];
    let (mut a, mut b) = (
        Box::new(Roots::<9, 32>::new()),
        Box::new(Roots::<9, 32>::new()),
    );
    modes.solve(&x, &mut a).unwrap();
    again.solve(&x, &mut b).unwrap();
    assert_eq!(a.real().len(), b.real().len());
    for r in a.real() {
        assert!(b.real().iter().any(|q| close(&q.v, &r.v, 1e-9)));
    }
    // A start given twice is refused.
    let mut bad = starts.clone();
    bad[3] = bad[2];
    let err = AllModes::<_, 9, 3, 32>::from_starts(
        Rps3::new(),
        *p0,
        gamma,
        &bad,
        &ModesOptions::default(),
    )
    .err();
    assert_eq!(err, Some(ModesError::BadStart { index: 3 }));
}

#[test]
fn the_modes_command_needs_no_start_section() {
    use linkage_examples::cli::geometry;
    let joints = "base = [[0,0,0],[1,0,0],[2,0,1],[3,0,0],[4,1,0],[5,0,0]]\nplatform = [[0,0,0],[1,0,0],[2,0,0],[3,1,0],[4,0,0],[5,0,2]]\n";
    let (base, platform) = geometry::parse_joints(joints).unwrap();
    assert_eq!(base[2], [2.0, 0.0, 1.0]);
    assert_eq!(platform[5], [5.0, 0.0, 2.0]);
    // A `[start]` section is allowed (and ignored), as in the files `solve` reads.
    let with_start = format!("{joints}[start]\nlegs = [1,1,1,1,1,1]\n");
    assert!(geometry::parse_joints(&with_start).is_ok());
    assert!(
        geometry::parse(joints).is_err(),
        "`solve` still needs the start"
    );
    let err = geometry::parse_joints(&joints.replace("[5,0,2]", "[5,0,nan]")).unwrap_err();
    assert!(err.contains("finite"), "{err}");
}

/// The committed start sets (`examples/src/start_sets/*_data.rs`) against a fresh run of their
/// generator: the same base point and γ (they depend only on the seeds), and the same roots as
/// sets (to 1e-8 of the scale: the digits may move if the tracker changes, the roots not).
#[test]
fn embedded_start_sets_are_the_generator_output() {
    use linkage_examples::start_sets;
    fn same<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize, const L: usize>(
        stored: &AllModes<S, N, M, K>,
        fresh: &AllModes<S, N, M, L>,
        expected: usize,
        label: &str,
    ) {
        assert_eq!(stored.base_point(), fresh.base_point(), "{label}");
        assert_eq!(fresh.start_count(), expected, "{label}");
        assert_eq!(stored.start_count(), expected, "{label}");
        let near = |a: &[Complex; N], b: &[Complex; N]| {
            (0..N).all(|k| (a[k] - b[k]).abs() <= 1e-8 * stored.scale().max(b[k].abs()))
        };
        for i in 0..expected {
            let s = stored.start(i).unwrap();
            let f = fresh.start(i).unwrap();
            assert!(
                (0..expected).any(|j| near(&s, &fresh.start(j).unwrap())),
                "{label}: stored start {i} is not among the fresh ones: regenerate with `cargo run --release --example start_sets`"
            );
            assert!(
                (0..expected).any(|j| near(&f, &stored.start(j).unwrap())),
                "{label}: fresh start {i} is not stored: regenerate with `cargo run --release --example start_sets`"
            );
        }
    }
    let stored = start_sets::table_iii::<64>().unwrap();
    let fresh =
        start_sets::compute::<_, 18, 6, 64>(Stewart::new(), &start_sets::TABLE_III_CENTRE).unwrap();
    same(&stored, &fresh, 28, "Table III");
    let stored = start_sets::rps3::<32>().unwrap();
    let fresh = start_sets::compute::<_, 9, 3, 32>(Rps3::new(), &start_sets::RPS3_CENTRE).unwrap();
    same(&stored, &fresh, 16, "3-RPS");
    // A tampered start is refused, not tracked.
    let (p0, gamma) = stored.base_point();
    let mut starts: Vec<[Complex; 9]> = (0..16).map(|i| stored.start(i).unwrap()).collect();
    starts[5][4] += Complex::new(1e-3, 0.0);
    let err = AllModes::<_, 9, 3, 32>::from_starts(
        Rps3::new(),
        *p0,
        gamma,
        &starts,
        &ModesOptions::default(),
    )
    .err();
    assert_eq!(err, Some(ModesError::BadStart { index: 5 }));
}

/// Every Table V test point (seed 2015), normal and near-singular, has its true pose — the
/// pose its legs were computed from — among the real modes found from the stored start set.
/// Near a fold the true root has a twin within micrometres; real Newton there stops at a
/// rounding floor above 1e-14, which once hid the true root (point 13 of the near-singular
/// ones).
#[test]
fn every_table_v_point_has_its_true_pose_among_the_real_modes() {
    use linkage_examples::case_study::sampling::{Protocol, Sampler};
    let sampler = Sampler::new(Protocol::default());
    let (_, normal, near) = sampler.sample().unwrap();
    let modes = linkage_examples::start_sets::table_iii::<64>().unwrap();
    let mut roots = Box::new(Roots::<18, 64>::new());
    let mut missed = Vec::new();
    for (k, p) in normal.iter().chain(&near).enumerate() {
        modes.solve(&p.x, &mut roots).unwrap();
        assert!(roots.is_complete(), "point {k}");
        let size = p.v.iter().map(|c| c * c).sum::<f64>().sqrt();
        let found = roots.real().iter().any(|r| {
            let d =
                r.v.iter()
                    .zip(&p.v)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>();
            d.sqrt() < 1e-6 * size
        });
        if !found {
            missed.push(k);
        }
    }
    assert!(
        missed.is_empty(),
        "true pose not among the real modes: {missed:?}"
    );
}

/// `stewart table-v`'s path dependence, checked independently: for near-singular targets it
/// names, the runtime's `Tracker` (real arithmetic, continuation) driven along the legs of the
/// straight pose path from home to the other root ends at that root — not at the true pose,
/// which the sampled pose path reaches — without a sign change of det B.
#[test]
fn path_dependent_table_v_targets_are_reached_by_the_tracker() {
    use linkage::{Options, Tracker};
    use linkage_examples::case_study::path_dependence::{examine, offset_to};
    use linkage_examples::case_study::sampling::{Protocol, Sampler};
    let sampler = Sampler::new(Protocol::default());
    let (_, _, near) = sampler.sample().unwrap();
    // No joint-space segments here (flips = 1: none counts): the pose paths alone.
    let segments = vec![([0.0; 18], 1); near.len()];
    let found = examine(&sampler, &near, &segments, 2000).unwrap();
    println!("{found:?}");
    assert_eq!(found.truth_found, near.len());
    assert!(found.path_dependent_targets > 0);
    let modes = linkage_examples::start_sets::table_iii::<64>().unwrap();
    let mut roots = Box::new(Roots::<18, 64>::new());
    let rel = |a: &[f64; 18], b: &[f64; 18]| {
        let d: f64 = a.iter().zip(b).map(|(p, q)| (p - q) * (p - q)).sum();
        (d / b.iter().map(|q| q * q).sum::<f64>()).sqrt()
    };
    let sign = sampler.start.det();
    let mut confirmed = 0;
    for &i in found.which.iter().take(5) {
        let p = &near[i - 1];
        modes.solve(&p.x, &mut roots).unwrap();
        for r in roots.real() {
            if rel(&r.v, &p.v) < 1e-6 || r.det * sign <= 0.0 {
                continue;
            }
            let Some(u) = r.pose.and_then(|pose| offset_to(&sampler, &pose)) else {
                continue;
            };
            if !sampler.nonsingular(&u, 1.0) {
                continue;
            }
            let mut tracker = Tracker::new(sampler.sys.clone(), sampler.start, Options::TIGHT);
            let samples = 2000;
            let mut last = None;
            for k in 1..=samples {
                let pose = sampler.pose(&u, k as f64 / samples as f64);
                let (x, _) = legs_for_pose(&sampler.sys, &pose).unwrap();
                let sample = tracker.update(&x).unwrap_or_else(|e| {
                    panic!("target {i}: the tracker stopped at sample {k}: {e:?}")
                });
                assert!(sample.proximity > 0.0);
                last = Some(sample.v);
            }
            let v = last.unwrap();
            assert!(
                rel(&v, &r.v) < 1e-6,
                "target {i}: the tracker ended elsewhere"
            );
            assert!(
                rel(&v, &p.v) > 1e-3,
                "target {i}: the tracker ended at the true pose"
            );
            confirmed += 1;
        }
    }
    assert!(confirmed > 0);
    println!("{confirmed} second modes confirmed by the tracker");
}
