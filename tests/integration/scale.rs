//! A mechanism smaller than one unit of length: the same machine, the same answers.
//!
//! The relative rules of the solvers (the largest tolerance allowed, when a start is
//! consistent, when a left-out equation still holds, when a path's point is accurate) were
//! relative to max(‖v‖, 1), so below one unit they turned absolute. Table III's platform in
//! micrometres-as-millimetres (every length times 1e-9, 0.2 µm across) with the default
//! tolerance of 1e-9 — five times its own size — came back `Converged` from every solver with
//! the pose of another leg vector: yaw 0.0047316 where it is 0.0047342 (PH), and at 1e-12 the
//! home pose unmoved for a leg 0.6 % longer. A tolerance that does not fit the mechanism is now
//! `InvalidOptions`, and with the tolerance scaled as the mechanism is, the answers are the
//! unscaled ones.

use linkage::{
    arc_length, newton_homotopy, newton_raphson, pose_from_unknowns, Mechanism, Options, Pose,
    SolveError, Start, Status, TrackError, Tracker,
};
use linkage_examples::stewart::{SixSix, Stewart, HOME_LEGS, HOME_POSE};

/// Table III's platform with every length times `k`, and its home start.
fn scaled(k: f64) -> (Stewart, Start<18, 6>) {
    let table = Stewart::new();
    let base = table.base_joints().map(|p| p.map(|c| c * k));
    let platform: [[f64; 3]; 6] = std::array::from_fn(|i| table.point_local(i).map(|c| c * k));
    let sys = Stewart::with_joints(&base, &platform).unwrap();
    let [yaw, pitch, roll, x, y, z] = HOME_POSE;
    let pose = Pose::from_euler(yaw, pitch, roll, [x * k, y * k, z * k]);
    let v = linkage::unknowns_from_pose(&sys, &pose);
    let start = Start::new(&sys, v, HOME_LEGS.map(|l| l * k)).unwrap();
    (sys, start)
}

/// Yaw, pitch, roll and the translation divided by `k`.
fn pose(sys: &Stewart, v: &[f64; 18], k: f64) -> [f64; 6] {
    let p = pose_from_unknowns(sys, v).unwrap();
    let [yaw, pitch, roll] = p.euler();
    let t = p.translation.map(|c| c / k);
    [yaw, pitch, roll, t[0], t[1], t[2]]
}

#[test]
fn a_tolerance_larger_than_the_mechanism_is_refused_not_converged() {
    let legs = [171.0, 170.0, 170.0, 170.0, 170.0, 172.0];
    let (table, table_start) = scaled(1.0);
    let truth = arc_length(&table, &table_start, &legs, &Options::TIGHT).unwrap();
    assert_eq!(truth.status, Status::Converged);
    let truth = pose(&table, &truth.v, 1.0);
    for k in [1e-3, 1e-6, 1e-9, 1e-12] {
        let (sys, start) = scaled(k);
        let x = legs.map(|l| l * k);
        // The default tolerance fits a mechanism down to 1e3 times its size (‖v0‖).
        let size = start.v().iter().map(|c| c * c).sum::<f64>().sqrt();
        let fits = Options::TIGHT.tolerance <= Options::MAX_RELATIVE_TOLERANCE * size;
        let solves = [
            arc_length(&sys, &start, &x, &Options::TIGHT),
            newton_homotopy(&sys, &start, &x, &Options::TIGHT),
            newton_raphson(&sys, &start, &x, &Options::TIGHT),
        ];
        for sol in solves {
            if fits {
                let sol = sol.unwrap();
                assert!(sol.status.meets_tolerance(), "k = {k}: {sol:?}");
            } else {
                assert!(
                    matches!(sol, Err(SolveError::InvalidOptions { .. })),
                    "k = {k}: {sol:?}"
                );
            }
        }
        let mut tracker = Tracker::new(sys.clone(), start, Options::TIGHT);
        let sample = tracker.update(&x);
        if !fits {
            assert!(
                matches!(
                    sample,
                    Err(TrackError::Input(SolveError::InvalidOptions { .. }))
                ),
                "k = {k}: {sample:?}"
            );
        }
        // With the tolerance scaled as the mechanism is: the unscaled answer.
        let options = Options {
            tolerance: Options::TIGHT.tolerance * k,
            ..Options::TIGHT
        };
        let sol = arc_length(&sys, &start, &x, &options).unwrap();
        assert_eq!(sol.status, Status::Converged, "k = {k}");
        let got = pose(&sys, &sol.v, k);
        assert!(
            linkage_tests::max_diff(&got, &truth) < 1e-8,
            "k = {k}: {got:?} vs {truth:?}"
        );
        let mut tracker = Tracker::new(sys.clone(), start, options);
        let sample = tracker.update(&x).unwrap();
        let got = pose(&sys, &sample.v, k);
        assert!(
            linkage_tests::max_diff(&got, &truth) < 1e-8,
            "k = {k}, tracker: {got:?} vs {truth:?}"
        );
    }
}

#[test]
fn a_geometry_at_1e200_or_1e_minus_200_is_not_called_collinear() {
    use linkage::GeometryError;
    use linkage_examples::stewart::Stewart;
    // Every scale whose derived constants fit in f64 is accepted, with the frame's shape
    // (the E_j of Table IV) unchanged; the squared distances at 1e200 overflow, and that is
    // what is said, not that the frame is collinear (it used to be, for both).
    let home = Stewart::new();
    for unit in [1e-200, 1e-150, 1e-100, 1e100, 1e150] {
        let s = Stewart::from_geometry(Stewart::DEFAULT_GEOMETRY.map(|c| c * unit)).unwrap();
        for (k, name) in Stewart::CONSTANT_NAMES.iter().enumerate() {
            if name.len() == 2 {
                // E1..E9: ratios, the same at every scale.
                let (got, want) = (s.constants()[k], home.constants()[k]);
                assert!(
                    (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                    "{unit:e} {name}"
                );
            }
        }
    }
    assert_eq!(
        Stewart::from_geometry(Stewart::DEFAULT_GEOMETRY.map(|c| c * 1e200)),
        Err(GeometryError::Overflow)
    );
}
