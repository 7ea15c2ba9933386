//! `stewart solve`: forward kinematics for a CSV of leg lengths.

use crate::{Method, SolveArgs};
use linkage::{Mechanism, Options, Pose, Start, Tracker};
use linkage_examples::cli::geometry;
use linkage_examples::cli::legs_csv::{self, Output};
use linkage_examples::stewart::{
    find_start, platform_is_coplanar, SixSix, Stewart, StewartGeneral, HOME_LEGS,
};

pub fn run(args: &SolveArgs) -> Result<(), String> {
    if !(args.tolerance.is_finite() && args.tolerance > 0.0) {
        return Err("--tolerance must be a positive number".into());
    }
    let rows = legs_csv::read(&args.input)?;
    match &args.geometry {
        None => solve_all(Stewart::new(), HOME_LEGS, None, args, &rows),
        Some(path) => {
            let g = geometry::load(path)?;
            let pose = g
                .pose
                .map(|[yaw, pitch, roll, x, y, z]| Pose::from_euler(yaw, pitch, roll, [x, y, z]));
            // Coplanar platforms use Eq. 19's form; others the general, mirror-free form.
            if platform_is_coplanar(&g.platform) {
                let sys = Stewart::with_joints(&g.base, &g.platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                solve_all(sys, g.legs, pose, args, &rows)
            } else {
                let sys = StewartGeneral::with_joints(&g.base, &g.platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                solve_all(sys, g.legs, pose, args, &rows)
            }
        }
    }
}

fn solve_all<S: SixSix>(
    sys: S,
    legs: [f64; 6],
    pose: Option<Pose>,
    args: &SolveArgs,
    rows: &[legs_csv::Row],
) -> Result<(), String> {
    let start = find_start(&sys, legs, pose).map_err(|e| format!("start configuration: {e}"))?;
    let options = Options {
        tolerance: args.tolerance,
        ..Options::TIGHT
    };
    let method = match args.method {
        Method::Ph => linkage::Method::ArcLength,
        Method::Nh => linkage::Method::NewtonHomotopy,
        Method::Nr => linkage::Method::NewtonRaphson,
    };
    let mut out = Output::new(args.output.as_deref())?;
    let mut tracker = Tracker::new(sys.clone(), start, options);
    let mut current: Start<18, 6> = start;
    for (i, row) in rows.iter().enumerate() {
        let n = i + 1;
        let x = match row {
            Ok(x) => x,
            Err(word) => {
                out.row(n, word, None, None, None)?;
                continue;
            }
        };
        if args.track && matches!(args.method, Method::Ph) {
            match tracker.update(x) {
                Ok(sample) => write_ok(
                    &mut out,
                    &sys,
                    n,
                    &sample.v,
                    x,
                    None,
                    sample.newton_iterations,
                )?,
                Err(linkage::TrackError::Input(e)) => out.row(n, e.word(), None, None, None)?,
                Err(linkage::TrackError::Lost(status)) => {
                    out.row(n, status.word(), None, None, None)?
                }
            }
            continue;
        }
        // PH goes around a fold when it can (`arc_length_detour`); NH and NR as the paper has them.
        let result = match method {
            linkage::Method::ArcLength => {
                linkage::arc_length_detour(&sys, &current, x, &options).map(|d| d.solution)
            }
            _ => method.solve(&sys, &current, x, &options),
        };
        match result {
            Err(e) => out.row(n, e.word(), None, None, None)?,
            Ok(sol) if sol.is_ok() => {
                let steps = match args.method {
                    Method::Nr => sol.newton_iterations,
                    _ => sol.steps_accepted + sol.steps_rejected,
                };
                write_ok(
                    &mut out,
                    &sys,
                    n,
                    &sol.v,
                    x,
                    Some(sol.error_estimate),
                    steps,
                )?;
                if args.track {
                    if let Ok(next) = Start::new(&sys, sol.v, *x) {
                        current = next;
                    }
                }
            }
            Ok(sol) => out.row(
                n,
                sol.status.word(),
                None,
                Some(sol.error_estimate),
                Some(sol.steps_accepted + sol.steps_rejected),
            )?,
        }
    }
    out.finish()
}

fn write_ok<S: Mechanism<18, 6>>(
    out: &mut Output,
    sys: &S,
    n: usize,
    v: &[f64; 18],
    x: &[f64; 6],
    error: Option<f64>,
    steps: u32,
) -> Result<(), String> {
    let error = error.unwrap_or_else(|| linkage::error_estimate(sys, v, x));
    match linkage::pose_from_unknowns(sys, v) {
        Some(p) => {
            let [yaw, pitch, roll] = p.euler();
            let t = p.translation;
            out.row(
                n,
                "ok",
                Some((&[yaw, pitch, roll, t[0], t[1], t[2]], v)),
                Some(error),
                Some(steps),
            )
        }
        None => out.row(n, "degenerate_pose", None, None, None),
    }
}
