//! The Section 5 case study on a reduced protocol: every number Table V reports is measured
//! the same way; here its guarantees are asserted.

use linkage_examples::case_study::sampling::{Protocol, Sampler};
use linkage_examples::case_study::table_v::{run, summarize, to_json};

fn small() -> Protocol {
    Protocol {
        seed: 7,
        normal: 12,
        near_singular: 12,
        mean_samples: 400,
        ..Protocol::default()
    }
}

#[test]
fn test_points_follow_the_protocol() {
    let sampler = Sampler::new(small());
    let (mean, normal, near) = sampler.sample().unwrap();
    assert!(mean > 0.0);
    assert_eq!((normal.len(), near.len()), (12, 12));
    for p in &normal {
        assert!(p.det >= 1e-3 * mean && !p.near_singular);
    }
    for p in &near {
        assert!(p.det < 1e-3 * mean && p.det > 0.0 && p.near_singular);
    }
    // Same seed, same points.
    let (_, again, _) = Sampler::new(small()).sample().unwrap();
    assert_eq!(normal[3].x, again[3].x);
}

#[test]
fn arc_length_never_returns_another_branch_labelled_ok() {
    let report = run(small(), |_| {}).unwrap();
    let n = report.normal.len();
    let json = to_json(&report);
    for name in ["PH", "NH", "NR"] {
        for key in [
            "near_singular_ok_ratio",
            "normal_mean_rel_error",
            "mean_time_s",
            "wrong_branch",
            "fold_reported",
        ] {
            assert!(json["methods"][name][key].is_number(), "{name}.{key}");
            assert!(
                json["methods"][name]["tight"][key].is_number(),
                "{name}.tight.{key}"
            );
        }
    }
    let (_, paper, tight) = &report.outcomes[0];
    for outcomes in [paper, tight] {
        let s = summarize(&outcomes[..n], &outcomes[n..]);
        assert_eq!(s.wrong_branch, 0);
        assert_eq!(s.normal_failures, 0);
    }
    let s = summarize(&tight[..n], &tight[n..]);
    assert!(
        s.normal_mean_rel_error <= 1e-9,
        "{}",
        s.normal_mean_rel_error
    );
    // Every near-singular point whose straight segment stays in the valid joint space is solved.
    let stays = report.near.len() - report.segment_leaves_vjs;
    let solved = paper[n..]
        .iter()
        .filter(|o| o.status == linkage::Status::Converged && o.relative_error < 1e-3)
        .count();
    let second_solutions = paper[n..].iter().filter(|o| o.path_dependent).count();
    assert!(
        solved + second_solutions >= stays,
        "{solved} + {second_solutions} < {stays}"
    );
}
