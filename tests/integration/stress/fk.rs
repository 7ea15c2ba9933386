//! One forward-kinematics case: a random target for a random machine, solved by every solver
//! and held to the truth.
//!
//! Targets are of three kinds: `uniform`, a pose reached from home by a straight pose path that
//! keeps det B's sign at 400 points; `near_singular`, such a pose just short (1e-8 to 1e-2 of
//! the way) of the first singularity along a random ray; `beyond`, a pose past it, whose own
//! pivots are on another branch. The truth for the pose path is the pose's pivots (uniform and
//! near_singular only); the truth for the straight joint segment is [`follow_segment`].
//!
//! An ok from PH must be the straight segment's truth, reached without a singularity (PH claims
//! exactly that). An ok from a detour must be the truth along its polyline. NH and NR follow no
//! path of their own: an ok from them must be one of the truths. And PH must reach a target
//! whose straight segment keeps |det B| above 1 % of the start's (issue 9, defect 3).
//!
//! The oracle gets a second chance before a result is called wrong: the segment followed
//! backwards from the result must then fail to arrive at the start's pivots too. Where it
//! cannot decide (stuck next to a fold, or the end within rounding of one), the pose's pivots
//! are the truth, or, with none, the result is counted as undecided rather than judged.

use super::check::{judge, refused_at_rounding_floor};
use super::geometry::{random_offset, Geometry, Machine};
use super::oracle::{agreement, distance, follow_segment, sensitivity};
use super::run::Tally;
use linkage::{arc_length, arc_length_detour, newton_homotopy, newton_raphson, Linear, Options};
use linkage_examples::stewart::SixSix;
use linkage_tests::Rng;

/// Everything a failure needs to be understood and replayed by hand.
#[derive(Debug)]
#[allow(dead_code)] // read through Debug
struct Inputs<'a> {
    geometry: &'a Geometry,
    start_legs: [f64; 6],
    kind: &'static str,
    /// Pose offset u and how far along it (pose = home ⊕ t u).
    u: [f64; 6],
    t: f64,
    target_legs: [f64; 6],
    options: Options,
}

/// Options as users set them: mostly TIGHT or PAPER, sometimes anything sensible.
pub fn random_options(rng: &mut Rng) -> Options {
    let linear = if rng.next_u64().is_multiple_of(4) {
        Linear::Dense
    } else {
        Linear::Generated
    };
    match rng.next_u64() % 10 {
        0..=4 => Options {
            linear,
            ..Options::TIGHT
        },
        5 | 6 => Options {
            linear,
            ..Options::PAPER
        },
        _ => Options {
            tolerance: 10f64.powf(rng.uniform(-12.0, -3.0)),
            max_iterations: 3 + (rng.next_u64() % 58) as u32,
            max_steps: 20 + (rng.next_u64() % 3000) as u32,
            homotopy_steps: 1 + (rng.next_u64() % 40) as u32,
            linear,
        },
    }
}

/// A target of a random kind: `(kind, u, t)`, or `None` if none was found.
fn target<S: SixSix>(m: &Machine<S>, rng: &mut Rng) -> Option<(&'static str, [f64; 6], f64)> {
    let draw = rng.next_u64() % 20;
    for _ in 0..40 {
        if draw < 12 {
            let (rot, trans) = (rng.uniform(0.05, 0.7), m.size * rng.uniform(0.05, 0.5));
            let u = random_offset(rng, rot, trans);
            if m.path_ratio(&u, (0.0, 1.0), 400) > 0.0 {
                return Some(("uniform", u, 1.0));
            }
            continue;
        }
        let u = random_offset(rng, 0.7, 0.5 * m.size);
        let Some((t_in, t_out)) = m.crossing(&u, 3.0, 200) else {
            continue;
        };
        if draw < 17 {
            let t = t_in * (1.0 - 10f64.powf(rng.uniform(-8.0, -2.0)));
            if m.path_ratio(&u, (0.0, t), 400) > 0.0 {
                return Some(("near_singular", u, t));
            }
        } else {
            let t = t_out * (1.0 + rng.uniform(0.01, 0.5));
            if m.at(&u, t).is_some() {
                return Some(("beyond", u, t));
            }
        }
    }
    None
}

/// The linear solver other than `l`, to tell a solver's defect from the method's.
pub fn other_linear(l: Linear) -> Linear {
    match l {
        Linear::Dense => Linear::Generated,
        Linear::Generated => Linear::Dense,
    }
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

/// Which solvers a forward-kinematics test runs.
#[derive(Clone, Copy, PartialEq)]
pub enum Solvers {
    /// PH (`arc_length`) and PH with detours (`arc_length_detour`).
    Continuation,
    /// NH (`newton_homotopy`) and NR (`newton_raphson`).
    Newton,
}

pub fn case<S: SixSix>(tally: &mut Tally, case: u64, rng: &mut Rng, g: Geometry, solvers: Solvers) {
    let Some(m) = Machine::<S>::for_case(&g, tally) else {
        return;
    };
    let Some((kind, u, t)) = target(&m, rng) else {
        tally.count("no target found (skipped)");
        return;
    };
    tally.case();
    tally.count(format!("target {kind}"));
    let (x, v_pose, _) = m.at(&u, t).expect("a valid pose");
    let options = random_options(rng);
    let tol = options.tolerance;
    let inputs = Inputs {
        geometry: &g,
        start_legs: m.x0,
        kind,
        u,
        t,
        target_legs: x,
        options,
    };
    let x_size = sup(&x);
    let max_step = 0.003 * sup(&m.x0);
    let seg = follow_segment(&m.sys, (&m.v0, &m.x0), m.det0, &x, max_step);
    let pose_truth = (kind != "beyond").then(|| (v_pose, sensitivity(&m.sys, &v_pose, &x)));
    let on_pose = |v: &[f64; 18]| {
        pose_truth
            .as_ref()
            .is_some_and(|(vp, sens)| distance(v, vp) <= agreement(tol, *sens, x_size, sup(vp)))
    };
    if seg.reached && pose_truth.is_some() && !on_pose(&seg.v) {
        tally.count("straight segment ends in another mode than the pose path (README caveat)");
    }
    if seg.undecided(x_size) {
        tally.count(
            "straight segment undecided (oracle stuck, or the end within rounding of a fold)",
        );
    }
    // What PH claims: the straight segment's truth. Where the segment's end lies within
    // rounding of a fold, also the pose's pivots (the only other truth there is).
    // The same segment followed backwards from a result to the start: where it arrives at the
    // start's pivots, the result is connected to the start along the segment, whatever the
    // forward run said (a second, independent attempt of the oracle).
    let contradicted = std::cell::Cell::new(0);
    let unverified = std::cell::Cell::new(0);
    let backwards = |v: &[f64; 18]| {
        let back = follow_segment(&m.sys, (v, &x), m.det0, &m.x0, max_step);
        let ok = back.allows(&m.v0, tol, sup(&m.x0));
        if ok {
            contradicted.set(contradicted.get() + 1);
        }
        ok
    };
    let on_segment = |v: &[f64; 18]| -> Result<(), String> {
        if seg.allows(v, tol, x_size) || (seg.undecided(x_size) && on_pose(v)) || backwards(v) {
            return Ok(());
        }
        if seg.stuck && !seg.near_end(x_size) {
            // Stuck mid-segment, next to a singular point: not shown wrong, not shown right.
            unverified.set(unverified.get() + 1);
            return Ok(());
        }
        Err(if seg.reached {
            format!(
                "{:e} from the straight segment's truth (allowed {:e})",
                distance(v, &seg.v),
                agreement(tol, seg.sensitivity, x_size, sup(&seg.v))
            )
        } else {
            format!(
                "fine continuation along the straight segment stops at λ = {} ({}, min |det B|/|det0| {:e}){}",
                seg.lambda,
                if seg.stuck { "oracle stuck" } else { "a fold or crossing" },
                seg.min_ratio,
                match &pose_truth {
                    Some((vp, _)) => format!(", and it is {:e} from the pose's pivots", distance(v, vp)),
                    None => String::new(),
                }
            )
        })
    };
    match solvers {
        Solvers::Continuation => {
            let ph = arc_length(&m.sys, &m.start, &x, &options);
            let ph_ok = judge(
                tally,
                case,
                &inputs,
                "PH",
                &m,
                &x,
                &options,
                &ph,
                &on_segment,
            );
            // Issue 9, defect 3: PH must reach what its segment reaches with a margin.
            let sane = options.tolerance >= 1e-10
                && options.max_steps >= 500
                && options.max_iterations >= 10;
            let floor = match &ph {
                Ok(sol) if seg.reached => {
                    refused_at_rounding_floor(&m, &sol.status, &seg.v, &x, options.tolerance)
                }
                _ => None,
            };
            if seg.reached && seg.min_ratio >= 1e-2 && sane && !ph_ok && floor.is_some() {
                tally.count("PH: tolerance_not_met at the rounding floor of the truth");
            } else if seg.reached && seg.min_ratio >= 1e-2 && sane && !ph_ok {
                let other = Options {
                    linear: other_linear(options.linear),
                    ..options
                };
                tally.fail(
                    "ph_refused_reachable_target",
                    case,
                    format!(
                        "PH ended {:?}, but the straight segment keeps |det B|/|det0| ≥ {:e} (PH with the other linear solver: {:?})",
                        ph.map(|s| s.status),
                        seg.min_ratio,
                        arc_length(&m.sys, &m.start, &x, &other).map(|s| s.status),
                    ),
                    &inputs,
                );
            }
            let detour = arc_length_detour(&m.sys, &m.start, &x, &options);
            let polyline = detour.ok().and_then(|d| d.left_at.zip(d.via));
            // The truth along the detour's polyline, corner by corner.
            let along_polyline = |v: &[f64; 18]| -> Result<(), String> {
                let Some((left_at, via)) = polyline else {
                    return on_segment(v);
                };
                let (mut here, mut at) = (m.v0, m.x0);
                for (k, corner) in [left_at, via].into_iter().enumerate() {
                    let leg = follow_segment(&m.sys, (&here, &at), m.det0, &corner, max_step);
                    if leg.reached {
                        (here, at) = (leg.v, corner);
                    } else if leg.near_end(x_size) || (k == 0 && leg.stuck) {
                        // The detour leaves the straight segment at its last point before the
                        // fold: where the oracle stops short of it without meeting the fold,
                        // go on from there (the polyline moves by as little).
                        let stop =
                            std::array::from_fn(|j| at[j] + leg.lambda * (corner[j] - at[j]));
                        (here, at) = (leg.v, stop);
                    } else if leg.stuck {
                        // Next to the fold the oracle may not get going at all: no verdict.
                        unverified.set(unverified.get() + 1);
                        return Ok(());
                    } else {
                        return Err(format!(
                            "the detour's polyline meets a singularity on the way to {corner:?} (λ = {}, {})",
                            leg.lambda,
                            if leg.stuck { "oracle stuck" } else { "a fold or crossing" }
                        ));
                    }
                }
                let last = follow_segment(&m.sys, (&here, &at), m.det0, &x, max_step);
                // As for the straight segment: or followed backwards from the result.
                let back = || {
                    let back = follow_segment(&m.sys, (v, &x), m.det0, &at, max_step);
                    let ok = back.allows(&here, tol, sup(&at));
                    if ok {
                        contradicted.set(contradicted.get() + 1);
                    }
                    ok
                };
                if last.allows(v, tol, x_size) || (last.undecided(x_size) && on_pose(v)) || back() {
                    Ok(())
                } else if last.stuck && !last.near_end(x_size) {
                    unverified.set(unverified.get() + 1);
                    Ok(())
                } else if last.reached {
                    Err(format!(
                        "{:e} from the truth along the detour",
                        distance(v, &last.v)
                    ))
                } else {
                    Err(format!(
                        "the detour's last segment meets a singularity at λ = {} ({})",
                        last.lambda,
                        if last.stuck {
                            "oracle stuck"
                        } else {
                            "a fold or crossing"
                        }
                    ))
                }
            };
            let detour = detour.map(|d| d.solution);
            judge(
                tally,
                case,
                &inputs,
                "PH detour",
                &m,
                &x,
                &options,
                &detour,
                &along_polyline,
            );
        }
        Solvers::Newton => {
            // NH and NR follow no path of their own: an ok must be the pose's pivots or the
            // straight segment's truth. Past a singularity with no segment to the target,
            // nothing is known about the start's branch there: such an ok is counted as
            // unverifiable, not judged.
            let unverifiable = std::cell::Cell::new(0);
            let any_truth = |v: &[f64; 18]| -> Result<(), String> {
                if on_pose(v) {
                    return Ok(());
                }
                if pose_truth.is_none() && !seg.reached && !seg.undecided(x_size) {
                    unverifiable.set(unverifiable.get() + 1);
                    return Ok(());
                }
                on_segment(v)
            };
            let nh = newton_homotopy(&m.sys, &m.start, &x, &options);
            judge(
                tally, case, &inputs, "NH", &m, &x, &options, &nh, &any_truth,
            );
            let nr = newton_raphson(&m.sys, &m.start, &x, &options);
            judge(
                tally, case, &inputs, "NR", &m, &x, &options, &nr, &any_truth,
            );
            for _ in 0..unverifiable.get() {
                tally.count("ok beyond a singularity, no truth known (unverifiable)");
            }
        }
    }
    for _ in 0..unverified.get() {
        tally.count("ok unverified (the oracle stuck next to a singular point, the result not the pose's pivots)");
    }
    for _ in 0..contradicted.get() {
        tally.count("ok confirmed by the segment followed backwards, not forwards");
    }
}
