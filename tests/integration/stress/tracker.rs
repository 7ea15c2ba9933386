//! One tracking case: a random trajectory of a random machine, sample by sample through
//! `Tracker::update`, every accepted sample held to the truth.
//!
//! The tracker's last accepted sample (t_a, v_a, x_a) is on the start's branch (checked by
//! induction). A new sample x_k may be accepted as
//! - the pose's pivots at t_k, when v_a was the pose's pivots at t_a and det B keeps the
//!   start's sign on the fine grid between t_a and t_k (the pose path connects them), or
//! - the truth along the straight joint segment from (v_a, x_a) to x_k, when fine continuation
//!   reaches it (the tracker's own fallback path), or, where that segment leaves the branch's
//!   region and comes back too close to its end for continuation to see, along a path through
//!   a waypoint off it ([`reached_via`]): a graze of a fold surface between two samples.
//!   (Beside a fold the branch's point and its mirror across the fold are within the
//!   agreement's rounding allowance of each other; det B's sign, checked at every accepted
//!   sample, tells them apart.)
//!
//! Anything else is another branch labelled ok. A sample refused while the segment from the
//! last accepted one keeps |det B| above 1 % of the start's is a sample wrongly refused; a
//! refused sample must leave the tracker's state as it was.

use super::check::refused_at_rounding_floor;
use super::geometry::{Geometry, Machine};
use super::oracle::{agreement, distance, follow_segment, reached_via, sensitivity, Truth};
use super::run::Tally;
use super::trajectory::{random_trajectory, Grid, Trajectory};
use linkage::{Options, TrackError, Tracker};
use linkage_examples::stewart::SixSix;
use linkage_tests::invariants::point_violation;
use linkage_tests::Rng;

#[derive(Debug)]
#[allow(dead_code)] // read through Debug
struct Inputs<'a> {
    geometry: &'a Geometry,
    start_legs: [f64; 6],
    trajectory: &'a Trajectory,
    options: Options,
}

#[derive(Debug)]
#[allow(dead_code)] // read through Debug
struct AtSample<'a> {
    case: &'a Inputs<'a>,
    sample: usize,
    t: f64,
    legs: [f64; 6],
    last_accepted_t: f64,
    last_accepted_legs: [f64; 6],
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

pub fn case<S: SixSix>(tally: &mut Tally, case: u64, rng: &mut Rng, g: Geometry) {
    let Some(m) = Machine::<S>::for_case(&g, tally) else {
        return;
    };
    tally.case();
    let tr = random_trajectory(&m, rng);
    tally.count(format!("trajectory {}", tr.kind));
    let options = if rng.next_u64().is_multiple_of(5) {
        super::fk::random_options(rng)
    } else {
        Options::TIGHT
    };
    let tol = options.tolerance;
    let inputs = Inputs {
        geometry: &g,
        start_legs: m.x0,
        trajectory: &tr,
        options,
    };
    let grid = Grid::new(&m, &tr, (0.25e-3f64).min(0.125 / tr.rate));
    let max_step = 0.003 * sup(&m.x0);
    let mut tracker = Tracker::new(m.sys.clone(), m.start, options);
    // The last accepted sample: time, pivots, legs, and whether it was the pose's pivots.
    let (mut t_a, mut v_a, mut x_a, mut on_pose) = (0.0, m.v0, m.x0, true);
    let mut refused = false;
    for (k, t) in tr.samples().enumerate() {
        tally.count("samples");
        let Some((x, v_pose, ratio)) = m.at(&tr.offset(t), 1.0) else {
            tally.count("samples with a leg too short (not fed)");
            continue;
        };
        let at = AtSample {
            case: &inputs,
            sample: k,
            t,
            legs: x,
            last_accepted_t: t_a,
            last_accepted_legs: x_a,
        };
        let grid_min = grid.min_between(t_a, t).min(ratio);
        let pose_connected = on_pose && grid_min > 0.0;
        let before = (*tracker.state().0, *tracker.state().1);
        let after_refusal = refused;
        match tracker.update(&x) {
            Ok(sample) => {
                tally.count(if sample.fell_back {
                    "accepted (fell back)"
                } else {
                    "accepted"
                });
                if let Some(v) = point_violation(&m.sys, m.det0, &x, &sample.v, tol) {
                    tally.fail(
                        v.kind,
                        case,
                        format!(
                            "Tracker: {} (|det B|/|det0| {:e}, {} Newton iterations{})",
                            v.what,
                            sample.proximity,
                            sample.newton_iterations,
                            if sample.fell_back { ", fell back" } else { "" }
                        ),
                        &at,
                    );
                }
                let near = |truth: &[f64; 18], sens: f64| {
                    distance(&sample.v, truth) <= agreement(tol, sens, sup(&x), sup(truth))
                };
                let as_pose = pose_connected && near(&v_pose, sensitivity(&m.sys, &v_pose, &x));
                if !as_pose {
                    let seg = follow_segment(&m.sys, (&v_a, &x_a), m.det0, &x, max_step);
                    // Or the segment followed backwards from the sample to the last one.
                    let back = || {
                        follow_segment(&m.sys, (&sample.v, &x), m.det0, &x_a, max_step).allows(
                            &v_a,
                            tol,
                            sup(&x_a),
                        )
                    };
                    // Or a path through a waypoint off the segment (drawn from the case and
                    // the sample, so that a replay draws the same).
                    let via = || {
                        let mut draw = Rng::new(case ^ ((k as u64) << 32));
                        let accepts = |truth: &Truth<18>| truth.allows(&sample.v, tol, sup(&x));
                        reached_via(
                            &m.sys,
                            (&v_a, &x_a),
                            m.det0,
                            &x,
                            max_step,
                            (20, &mut draw),
                            accepts,
                        )
                    };
                    let reached = seg.allows(&sample.v, tol, sup(&x)) || back();
                    if !reached && via() {
                        tally.count(
                            "accepted: a path through a waypoint off the joint segment reaches it",
                        );
                    } else if !reached {
                        tally.count("Tracker: WRONG BRANCH ok");
                        tally.fail(
                            "wrong_branch_ok",
                            case,
                            format!(
                                "Tracker accepted a sample{} {:e} from the pose's pivots (pose path from the last accepted sample {}), and {}",
                                if after_refusal { " after refusing the one before" } else { "" },
                                distance(&sample.v, &v_pose),
                                if pose_connected { "nonsingular" } else { "not known nonsingular" },
                                if seg.reached {
                                    format!("{:e} from the joint segment's truth", distance(&sample.v, &seg.v))
                                } else {
                                    format!(
                                        "the joint segment from the last accepted sample meets a singularity at λ = {} ({:e} from the end)",
                                        seg.lambda, seg.remaining
                                    )
                                },
                            ),
                            &at,
                        );
                        // Its state is now off the branch: the rest would only repeat this.
                        break;
                    }
                }
                if after_refusal {
                    tally.count(if as_pose {
                        "accepted after a refusal: the pose's pivots"
                    } else {
                        "accepted after a refusal: the joint segment's truth"
                    });
                }
                (t_a, v_a, x_a, on_pose, refused) = (t, sample.v, x, as_pose, false);
            }
            Err(e) => {
                refused = true;
                if pose_connected {
                    tally.count(
                        "refused although the pose path from the last accepted sample is clear",
                    );
                }
                tally.count(match e {
                    TrackError::Input(e) => format!("refused: input {}", e.word()),
                    TrackError::Lost(s) => format!("refused: {}", s.word()),
                    TrackError::Unproven { .. } => "refused: unproven".to_string(),
                });
                if (*tracker.state().0, *tracker.state().1) != before {
                    tally.fail(
                        "refusal_changed_state",
                        case,
                        "a refused sample changed the tracker's state".into(),
                        &at,
                    );
                }
                let sane = tol >= 1e-10 && options.max_steps >= 500 && options.max_iterations >= 10;
                if pose_connected && grid_min >= 1e-2 && sane {
                    let seg = follow_segment(&m.sys, (&v_a, &x_a), m.det0, &x, max_step);
                    let floor = match e {
                        TrackError::Lost(s) => refused_at_rounding_floor(&m, &s, &seg.v, &x, tol),
                        TrackError::Input(_) | TrackError::Unproven { .. } => None,
                    };
                    if seg.reached && seg.min_ratio >= 1e-2 && floor.is_some() {
                        tally
                            .count("refused: tolerance_not_met at the rounding floor of the truth");
                    } else if seg.reached && seg.min_ratio >= 1e-2 {
                        // What PH itself says from a start rebuilt at the last accepted sample.
                        let ph = |o: &Options| {
                            linkage::Start::new(&m.sys, v_a, x_a).map(|st| {
                                linkage::arc_length(&m.sys, &st, &x, o)
                                    .map(|s| (s.status, distance(&s.v, &seg.v)))
                            })
                        };
                        tally.fail(
                            "tracker_refused_reachable_sample",
                            case,
                            format!(
                                "refused ({e}) although the joint segment from the last accepted sample keeps |det B|/|det0| ≥ {:e}; PH from there (status, distance to the truth): {:?}; with the other linear solver: {:?}",
                                seg.min_ratio,
                                ph(&options),
                                ph(&Options {
                                    linear: super::fk::other_linear(options.linear),
                                    ..options
                                }),
                            ),
                            &at,
                        );
                    }
                }
            }
        }
    }
}
