//! `stewart solve`: forward kinematics for a CSV of leg lengths, streamed row by row.

use crate::mode_check::ModeCheck;
use crate::{Method, SolveArgs};
use linkage::{CertifiedSteps, Mechanism, Options, Pose, Start, StepProof, Tracker};
use linkage_examples::cli::geometry;
use linkage_examples::cli::legs_csv::{LegRows, Row};
use linkage_examples::cli::results_csv::{self, Record, Via};
use linkage_examples::cli::stream::{open_input, refuse_overwriting, FlushBeforeRead, SharedSink};
use linkage_examples::stewart::{
    find_start, legs_for_pose, platform_is_coplanar, SixSix, Stewart, StewartGeneral, HOME_LEGS,
};

/// Legs longer than this many times the mechanism's size are `invalid_input`: there double
/// precision leaves no room for a useful tolerance, and further on the equations overflow
/// (a 1e308 leg is not a singularity).
pub const MAX_LEG_OVER_SIZE: f64 = 1e6;

/// The status of a row the solver called converged with an error estimate above the
/// tolerance (near a singularity rounding can forbid the tolerance), or whose pose, its leg
/// lengths recomputed, misses the row's legs by more than the tolerance: not `ok`.
const TOLERANCE_NOT_MET: &str = "tolerance_not_met";

/// The status of a row with `--certify --track` whose step from the last row was solved but
/// not proven to keep the branch: refused, not `ok`.
const UNPROVEN: &str = "unproven";

pub fn run(args: &SolveArgs) -> Result<(), String> {
    let mut inputs = vec![args.input.as_path()];
    inputs.extend(args.geometry.as_deref());
    refuse_overwriting(args.output.as_deref(), &inputs)?;
    match &args.geometry {
        None => {
            let check = match args.modes_within {
                Some(within) => Some(ModeCheck::new(
                    crate::modes::table_iii(&[Ok(HOME_LEGS)])?,
                    within,
                )),
                None => None,
            };
            solve_stream(Stewart::new(), HOME_LEGS, None, check, args)
        }
        Some(path) => {
            let g = geometry::load(path)?;
            let pose = g
                .pose
                .map(|[yaw, pitch, roll, x, y, z]| Pose::from_euler(yaw, pitch, roll, [x, y, z]));
            // Coplanar platforms use Eq. 19's form; others the general, mirror-free form.
            if platform_is_coplanar(&g.platform) {
                let sys = Stewart::with_joints(&g.base, &g.platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                check_start_legs(&sys, &g.legs)?;
                let check = mode_check(&sys, g.legs, args)?;
                solve_stream(sys, g.legs, pose, check, args)
            } else {
                let sys = StewartGeneral::with_joints(&g.base, &g.platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                check_start_legs(&sys, &g.legs)?;
                let check = mode_check(&sys, g.legs, args)?;
                solve_stream(sys, g.legs, pose, check, args)
            }
        }
    }
}

/// The rows' bound on the start's legs too: past it the start search met overflow and called
/// the geometry architecture-singular (`[start] legs = [1e300, …]`).
fn check_start_legs<S: SixSix>(sys: &S, legs: &[f64; 6]) -> Result<(), String> {
    let size = mechanism_size(sys);
    match legs.iter().position(|l| *l > MAX_LEG_OVER_SIZE * size) {
        Some(i) => Err(format!(
            "start configuration: start leg L{} = {:e} mm is more than {MAX_LEG_OVER_SIZE:e} times the mechanism's size ({size:e} mm)",
            i + 1,
            legs[i],
        )),
        None => Ok(()),
    }
}

/// `--modes-within` on a geometry from a file: its start set by monodromy, moved near the
/// start's legs.
fn mode_check<S: SixSix>(
    sys: &S,
    legs: [f64; 6],
    args: &SolveArgs,
) -> Result<Option<ModeCheck<S>>, String> {
    let Some(within) = args.modes_within else {
        return Ok(None);
    };
    let modes = crate::modes::solver(sys.clone(), &[Ok(legs)])?;
    Ok(Some(ModeCheck::new(modes, within)))
}

/// Reads a row, solves it, writes its result, and only then reads the next: constant memory,
/// and each result reaches a pipe before the next row is waited for.
fn solve_stream<S: SixSix>(
    sys: S,
    legs: [f64; 6],
    pose: Option<Pose>,
    mut check: Option<ModeCheck<S>>,
    args: &SolveArgs,
) -> Result<(), String> {
    let start = find_start(&sys, legs, pose).map_err(|e| format!("start configuration: {e}"))?;
    let mut solver = RowSolver::new(sys, start, args);
    // Said once, before any row: a tolerance the mechanism is too small for (every solve would
    // refuse it).
    solver.options.check_for(&start).map_err(|e| {
        format!(
            "--tolerance {:e}: {e} (‖v0‖ = {:e} mm)",
            args.tolerance,
            start_size(start.v())
        )
    })?;
    let sink = SharedSink::new(args.output.as_deref());
    let input = FlushBeforeRead::new(open_input(&args.input)?, sink.clone());
    let name = args.input.display();
    let mut rows = LegRows::new(input)
        .map_err(|e| sink.check().err().unwrap_or_else(|| format!("{name}: {e}")))?;
    let mut header = if args.certify {
        results_csv::header_certified()
    } else {
        results_csv::header()
    };
    if check.is_some() {
        header.push_str(ModeCheck::<S>::header());
    }
    sink.write_line(&header)?;
    let mut line = String::new();
    let mut n = 0u64;
    loop {
        let row = match rows.next_row() {
            Ok(Some(row)) => row,
            Ok(None) => break,
            // A failed flush surfaces as a failed read: report the output's error then.
            Err(e) => return Err(sink.check().err().unwrap_or_else(|| format!("{name}: {e}"))),
        };
        n += 1;
        line.clear();
        let record = solver.solve(n, row);
        record.write_to(&mut line);
        if args.certify {
            record.write_certificate(&mut line);
        }
        // Answers: `ok` from PH, `unverified` from NH and NR.
        let answered = record.status == "ok" || record.status == "unverified";
        if let (Some(check), Ok(x)) = (check.as_mut(), row) {
            let v = record.solution.as_ref().map(|(_, v)| v);
            line.push_str(&check.fields(&x, v.filter(|_| answered)));
        } else if check.is_some() {
            line.push_str(",,");
        }
        sink.write_line(&line)?;
    }
    sink.flush()
}

/// Solves one row after another, from the start or (`--track`) from the last solved row.
struct RowSolver<S: SixSix> {
    sys: S,
    start: Start<18, 6>,
    /// Where NH and NR start from: the start, or with `--track` the last row solved to the
    /// tolerance (`unverified`: these methods never establish the branch).
    current: Start<18, 6>,
    tracker: Tracker<S, 18, 6>,
    /// NR from the start, prepared once (B factored there serves every row).
    from_start: linkage::NewtonRaphson<S, 18, 6>,
    options: Options,
    method: Method,
    track: bool,
    max_leg: f64,
    /// `--certify`: each ok answer certified; with `--track`, each step proven (and a row
    /// whose step is not proven is refused).
    certify: bool,
    /// With `--certify --track` and NH or NR: the chain of step proofs from the start.
    chain: CertifiedSteps<18, 6>,
}

impl<S: SixSix> RowSolver<S> {
    fn new(sys: S, start: Start<18, 6>, args: &SolveArgs) -> Self {
        let options = Options {
            tolerance: args.tolerance,
            max_steps: args.max_steps,
            max_iterations: args.max_iterations,
            ..Options::TIGHT
        };
        let size = mechanism_size(&sys);
        let tracker = Tracker::new(sys.clone(), start, options);
        RowSolver {
            from_start: linkage::NewtonRaphson::new(sys.clone(), start),
            tracker: if args.certify {
                tracker.certified()
            } else {
                tracker
            },
            sys,
            start,
            current: start,
            options,
            method: args.method,
            track: args.track,
            max_leg: MAX_LEG_OVER_SIZE * size,
            certify: args.certify,
            chain: CertifiedSteps::new(),
        }
    }

    fn solve(&mut self, n: u64, row: Row) -> Record<'static> {
        let x = match row {
            Ok(x) => x,
            Err(word) => return Record::status_only(n, word),
        };
        if x.iter().any(|l| *l > self.max_leg) {
            return Record::status_only(n, "invalid_input");
        }
        if self.track && matches!(self.method, Method::Ph) {
            return self.track_ph(n, &x);
        }
        // PH goes around a fold when it can (`arc_length_detour`); NH and NR as the paper has
        // them.
        let (result, via) = match self.method {
            Method::Ph => {
                match linkage::arc_length_detour(&self.sys, &self.current, &x, &self.options) {
                    Ok(d) => (
                        Ok(d.solution),
                        if d.via.is_some() {
                            Via::Detour
                        } else {
                            Via::Direct
                        },
                    ),
                    Err(e) => (Err(e), Via::Direct),
                }
            }
            Method::Nh => (
                linkage::newton_homotopy(&self.sys, &self.current, &x, &self.options),
                Via::Direct,
            ),
            Method::Nr if self.current == self.start => {
                (self.from_start.solve(&x, &self.options), Via::Direct)
            }
            Method::Nr => (
                linkage::newton_raphson(&self.sys, &self.current, &x, &self.options),
                Via::Direct,
            ),
        };
        let sol = match result {
            Ok(sol) => sol,
            Err(e) => return Record::status_only(n, e.word()),
        };
        let steps = match self.method {
            Method::Nr => sol.newton_iterations,
            _ => sol.steps_accepted + sol.steps_rejected,
        };
        // Ratios are against the start's det B, also when tracking from another row.
        let min_det_ratio = sol.min_det_ratio * (self.current.det() / self.start.det()).abs();
        let record = Record {
            row: n,
            status: sol.status.word(),
            solution: None,
            error_estimate: Some(sol.error_estimate),
            steps: Some(steps),
            min_det_ratio: Some(min_det_ratio),
            via: Some(via),
            certified: None,
        };
        // `unverified` rows (NH, NR: the tolerance met, the branch not established) carry
        // their pose too, under their own word.
        if !sol.status.meets_tolerance() {
            return record;
        }
        let mut record = with_pose(&self.sys, record, &sol.v, &x, self.options.tolerance);
        if self.certify && record.solution.is_some() {
            if self.track {
                // The step from the last row solved ok: a row it is not proven to reach on
                // that row's branch is refused, and the next row starts from the last one.
                let from = (self.current.v(), self.current.x());
                match self.chain.prove(&self.sys, from, (&sol.v, &x)) {
                    StepProof::Proven {
                        radius,
                        error_bound,
                        ..
                    } => record.certified = Some((radius, error_bound)),
                    StepProof::Unproven { .. } => {
                        return Record {
                            status: UNPROVEN,
                            solution: None,
                            ..record
                        }
                    }
                }
            } else if let Ok(c) = linkage::certify(&self.sys, &sol.v, &x) {
                record.certified = Some((c.radius, c.error_bound));
            }
        }
        if self.track && record.solution.is_some() {
            // A checked start: a row that cannot be one (non-finite, singular) is not taken
            // up, and the next row starts from the last one that can.
            if let Ok(next) = Start::new(&self.sys, sol.v, x) {
                self.current = next;
            }
        }
        record
    }

    /// `--track` with PH: the trajectory tracker, which keeps its last good state when a
    /// sample is refused.
    fn track_ph(&mut self, n: u64, x: &[f64; 6]) -> Record<'static> {
        // The tracker moves on with every sample it accepts; a row this program then refuses
        // (below) must not move it.
        let before = self.tracker.clone();
        match self.tracker.update(x) {
            Ok(sample) => {
                let record = Record {
                    row: n,
                    status: "ok",
                    solution: None,
                    error_estimate: Some(linkage::error_estimate(&self.sys, &sample.v, x)),
                    steps: Some(sample.newton_iterations),
                    // The tracker reports |det B| / |det B0| at the sample itself.
                    min_det_ratio: Some(sample.proximity),
                    via: Some(if sample.fell_back {
                        Via::Fallback
                    } else {
                        Via::Direct
                    }),
                    certified: match sample.proof {
                        Some(StepProof::Proven {
                            radius,
                            error_bound,
                            ..
                        }) => Some((radius, error_bound)),
                        _ => None,
                    },
                };
                let record = with_pose(&self.sys, record, &sample.v, x, self.options.tolerance);
                if record.solution.is_none() {
                    self.tracker = before;
                }
                record
            }
            Err(linkage::TrackError::Input(e)) => Record::status_only(n, e.word()),
            Err(linkage::TrackError::Lost(status)) => Record::status_only(n, status.word()),
            Err(linkage::TrackError::Unproven { .. }) => Record::status_only(n, UNPROVEN),
        }
    }
}

/// An `ok` record with its pose, or the reason it is not ok after all: never `ok` with a
/// non-finite value, with the error estimate above the tolerance asked for, or with a pose
/// whose leg lengths, recomputed, miss the legs `x` asked for by more than the tolerance (the
/// error estimate measures v against the mechanism's equations, and a pose is read from
/// three of its pivots: only the legs themselves show that the printed pose is the answer).
fn with_pose<'a, S: Mechanism<18, 6>>(
    sys: &S,
    record: Record<'a>,
    v: &[f64; 18],
    x: &[f64; 6],
    tolerance: f64,
) -> Record<'a> {
    let finite = |a: &[f64]| a.iter().all(|c| c.is_finite());
    let error = record.error_estimate.unwrap_or(f64::NAN);
    if !finite(v) || !error.is_finite() {
        return Record {
            status: "non_finite",
            ..record
        };
    }
    if error > tolerance {
        return Record {
            status: TOLERANCE_NOT_MET,
            ..record
        };
    }
    let pose = linkage::pose_from_unknowns(sys, v).map(|p| {
        let [yaw, pitch, roll] = p.euler();
        let t = p.translation;
        [yaw, pitch, roll, t[0], t[1], t[2]]
    });
    let Some(pose) = pose.filter(|p| finite(p)) else {
        return Record {
            status: "degenerate_pose",
            ..record
        };
    };
    let [yaw, pitch, roll, px, py, pz] = pose;
    let reproduced = legs_for_pose(sys, &Pose::from_euler(yaw, pitch, roll, [px, py, pz]))
        .is_some_and(|(legs, _)| {
            legs.iter()
                .zip(x)
                .all(|(got, want)| (got - want).abs() <= tolerance)
        });
    if !reproduced {
        return Record {
            status: TOLERANCE_NOT_MET,
            ..record
        };
    }
    Record {
        solution: Some((pose, *v)),
        ..record
    }
}

/// ‖v‖: the size the solvers measure their tolerance against.
fn start_size(v: &[f64; 18]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// The largest joint coordinate (base or platform): the scale of the mechanism (not floored at
/// 1 mm: a machine a micrometre across is that size).
pub fn mechanism_size<S: SixSix>(sys: &S) -> f64 {
    let base = sys.base_joints().into_iter().flatten();
    let platform = (0..6).flat_map(|p| sys.point_local(p));
    base.chain(platform).fold(0.0f64, |m, c| m.max(c.abs()))
}
