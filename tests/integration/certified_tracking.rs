//! The tracker with certification (`Tracker::certified`): every accepted sample carries a proof
//! that the step to it kept the branch, a step that cannot be proven is refused, and nothing
//! accepted is ever off the branch — checked against fine continuation along the joint segment.

use linkage::{Options, StepProof, TrackError, Tracker};
use linkage_examples::stewart::{home_start, legs_for_pose, Stewart};
use linkage_tests::{manoeuvre, max_diff, stewart_pose_samples, straight_path_truth};

#[test]
fn every_sample_of_a_1khz_trajectory_is_proven_and_within_its_bound() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT).certified();
    let (mut pieces_total, mut widest) = (0, 0.0f64);
    for k in 1..=2000 {
        let (x, truth) = legs_for_pose(&s, &manoeuvre(k as f64 * 1e-3)).unwrap();
        let sample = tracker
            .update(&x)
            .unwrap_or_else(|e| panic!("sample {k}: {e}"));
        let Some(StepProof::Proven {
            pieces,
            radius,
            error_bound,
        }) = sample.proof
        else {
            panic!("sample {k}: accepted without a proof: {:?}", sample.proof);
        };
        // The proven bound holds the true pivots (themselves rounded from the pose).
        assert!(
            max_diff(&sample.v, &truth) <= error_bound + 1e-9,
            "sample {k}: {} > {error_bound}",
            max_diff(&sample.v, &truth)
        );
        assert!(radius > error_bound);
        pieces_total += pieces;
        widest = widest.max(error_bound);
    }
    println!("2000 samples proven in {pieces_total} pieces, error bounds up to {widest:.2e} mm");
    assert!(pieces_total >= 2000);
}

/// Coarse sampling of fast manoeuvres and straight runs into a fold: whatever the certified
/// tracker accepts is the last accepted sample continued along the joint segment without a
/// sign change of det B, and it refuses (lost or unproven) rather than guess.
#[test]
fn a_certified_tracker_accepts_nothing_off_the_branch() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let (mut accepted, mut unproven, mut lost) = (0, 0, 0);
    // 24 targets (60 with LINKAGE_STRESS set).
    let targets: Vec<[f64; 6]> =
        stewart_pose_samples(2, linkage_tests::sweep(24, 60), 1.2, 150.0, 100)
            .into_iter()
            .map(|p| p.x)
            .collect();
    for (n, target) in targets.iter().enumerate() {
        let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT).certified();
        let mut last = st;
        // 5 to 40 samples along the segment from home: long steps, some behind folds.
        let count = 5 << (n % 4);
        for k in 1..=count {
            let l = k as f64 / count as f64;
            let x: [f64; 6] = std::array::from_fn(|j| st.x()[j] + l * (target[j] - st.x()[j]));
            match tracker.update(&x) {
                Ok(sample) => {
                    assert!(matches!(sample.proof, Some(StepProof::Proven { .. })));
                    let (truth, flips) = straight_path_truth(&s, &last, &x, 1000);
                    assert_eq!(
                        flips, 0,
                        "target {n}, sample {k}: not connected to the last"
                    );
                    assert!(max_diff(&sample.v, &truth) < 1e-6, "target {n}, sample {k}");
                    last = linkage::Start::new(&s, sample.v, x).unwrap();
                    accepted += 1;
                }
                Err(TrackError::Unproven { .. }) => unproven += 1,
                Err(TrackError::Lost(_)) => lost += 1,
                Err(e) => panic!("{e}"),
            }
        }
    }
    println!("{accepted} accepted, {unproven} refused as unproven, {lost} lost");
    assert!(accepted > 100 && lost + unproven > 0);
}

/// A NaN sample is refused without breaking the chain of proofs: the next sample is proven
/// from the last accepted one.
#[test]
fn a_nan_sample_is_refused_and_the_chain_carries_on() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let mut tracker = Tracker::new(s.clone(), st, Options::TIGHT).certified();
    let (x1, _) = legs_for_pose(&s, &manoeuvre(1e-3)).unwrap();
    assert!(tracker.update(&x1).unwrap().proof.unwrap().is_proven());
    let mut bad = x1;
    bad[3] = f64::NAN;
    assert!(matches!(tracker.update(&bad), Err(TrackError::Input(_))));
    bad[3] = f64::INFINITY;
    assert!(tracker.update(&bad).is_err());
    let (x2, truth) = legs_for_pose(&s, &manoeuvre(2e-3)).unwrap();
    let sample = tracker.update(&x2).unwrap();
    assert!(sample.proof.unwrap().is_proven());
    assert!(max_diff(&sample.v, &truth) < 1e-7);
}
