//! Trajectory mode: 1 kHz samples of smooth pose trajectories, tracked on the start's branch.

use linkage::{Options, Status, TrackError, Tracker};
use linkage_examples::stewart::{home_start, legs_for_pose, Stewart};
use linkage_tests::{manoeuvre, max_diff};

#[test]
fn tracker_follows_a_1khz_trajectory_on_the_branch() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT);
    let mut worst = 0.0f64;
    let mut fallbacks = 0;
    for k in 1..=2000 {
        let (x, truth) = legs_for_pose(&s, &manoeuvre(k as f64 * 1e-3)).unwrap();
        let sample = tracker.update(&x).unwrap();
        worst = worst.max(max_diff(&sample.v, &truth));
        assert!(sample.proximity > 0.0 && sample.proximity.is_finite());
        assert!(
            sample.newton_iterations <= 3,
            "{}",
            sample.newton_iterations
        );
        fallbacks += sample.fell_back as u32;
    }
    assert!(worst < 1e-7, "{worst}");
    assert_eq!(fallbacks, 0);
}

#[test]
fn tracker_refuses_bad_samples_and_stays_usable() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT);
    let (x1, v1) = legs_for_pose(&s, &manoeuvre(0.01)).unwrap();
    tracker.update(&x1).unwrap();
    let mut bad = x1;
    bad[0] = f64::NAN;
    assert!(matches!(tracker.update(&bad), Err(TrackError::Input(_))));
    bad[0] = -1.0;
    assert!(matches!(tracker.update(&bad), Err(TrackError::Input(_))));
    // A jump far outside the workspace: refused, state unchanged.
    let far = [170.0, 170.0, 170.0, 170.0, 170.0, 600.0];
    assert!(matches!(tracker.update(&far), Err(TrackError::Lost(_))));
    assert!(max_diff(tracker.state().0, &v1) < 1e-7);
    let (x2, v2) = legs_for_pose(&s, &manoeuvre(0.011)).unwrap();
    let sample = tracker.update(&x2).unwrap();
    assert!(max_diff(&sample.v, &v2) < 1e-7);
}

#[test]
fn tracker_takes_big_steps_by_continuation() {
    // Samples 50 ms apart: the fast path may refuse, the fallback must stay on the branch.
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT);
    for k in 1..=40 {
        let (x, truth) = legs_for_pose(&s, &manoeuvre(k as f64 * 0.05)).unwrap();
        let sample = tracker.update(&x).unwrap();
        assert!(max_diff(&sample.v, &truth) < 1e-7);
    }
    let _ = Status::Converged;
}

/// Samples walking straight through a fold: the tracker follows the branch up to the fold and
/// refuses what lies beyond; every sample it accepts is confirmed by fine continuation from
/// the previous one, so it never returns a configuration across the singular surface.
#[test]
fn tracker_refuses_to_cross_a_fold() {
    use linkage::{arc_length, Status};
    use linkage_tests::{stewart_pose_samples, straight_path_truth};
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let target = stewart_pose_samples(2, 400, 1.2, 150.0, 100)
        .into_iter()
        .map(|p| p.x)
        .find(|x| {
            matches!(
                arc_length(&s, &st, x, &Options::TIGHT).unwrap().status,
                Status::Fold { .. }
            )
        })
        .expect("the seeded sample holds a target behind a fold");
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT);
    let (mut accepted, mut refused) = (0, 0);
    let mut previous = st;
    for k in 1..=400 {
        let l = k as f64 / 400.0;
        let x: [f64; 6] = std::array::from_fn(|j| st.x()[j] + l * (target[j] - st.x()[j]));
        match tracker.update(&x) {
            Ok(sample) => {
                // Ground truth: fine continuation from the previous accepted sample (after a
                // refusal, the tracker may legitimately reach a later sample another way).
                let (truth, flips) = straight_path_truth(&s, &previous, &x, 200);
                assert_eq!(flips, 0, "accepted a sample across a sign change of det B");
                assert!(max_diff(&sample.v, &truth) < 1e-6);
                assert!(linkage::det_b(&s, &sample.v, &x) * st.det() > 0.0);
                previous = linkage::Start::new(&s, sample.v, x).unwrap();
                accepted += 1;
            }
            Err(TrackError::Lost(_)) => refused += 1,
            Err(e) => panic!("{e}"),
        }
    }
    assert!(
        accepted > 0 && refused > 0,
        "{accepted} accepted, {refused} refused"
    );
}
