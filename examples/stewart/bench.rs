//! `stewart bench`: time per solve over every row of a leg-length CSV, repeated until the
//! timing is stable.

use crate::modes::CAPACITY;
use crate::Method;
use linkage::{CertifiedSteps, Options, Start, TrackError, Tracker};
use linkage_examples::cli::legs_csv::{self, LegRows};
use linkage_examples::cli::stream::{open_input, print};
use linkage_examples::stewart::{home_start, Stewart};
use std::path::Path;
use std::time::{Duration, Instant};

/// Most solves timed in one run: each one's time is kept (8 bytes) for the percentiles, and
/// `--seconds 3600` of sub-microsecond solves would keep about 2e9 of them, 17 GB, until the
/// allocator gave up and the program aborted with no report. 4 Mi times (32 MB) are plenty for
/// a p99; a run that reaches it stops timing there and says so.
const MAX_TIMED: usize = 1 << 22;

/// Whether to time another pass of `per_pass` solves: at least 3 passes, then until `seconds`
/// have passed or another pass would go beyond [`MAX_TIMED`].
fn another_pass(
    repetitions: usize,
    began: Instant,
    seconds: f64,
    timed: usize,
    per_pass: usize,
) -> bool {
    repetitions < 3
        || (began.elapsed() < Duration::from_secs_f64(seconds)
            && timed.saturating_add(per_pass) <= MAX_TIMED)
}

/// Said when the timing stopped at [`MAX_TIMED`] before `--seconds` had passed.
fn say_if_capped(began: Instant, seconds: f64, timed: usize) -> bool {
    let capped = began.elapsed() < Duration::from_secs_f64(seconds);
    if capped {
        eprintln!(
            "bench: stopped after {timed} timed solves ({:.1} s), the most one run keeps, before --seconds {seconds}",
            began.elapsed().as_secs_f64()
        );
    }
    capped
}

pub fn run(
    method: Method,
    track: bool,
    input: &Path,
    json: bool,
    dense: bool,
    certify: bool,
    seconds: f64,
) -> Result<(), String> {
    // The rows are replayed pass after pass, so the valid ones are held in memory (48 bytes
    // each); the others are counted and said.
    let name = input.display();
    let (mut rows, mut skipped) = (Vec::<[f64; 6]>::new(), 0usize);
    for row in LegRows::new(open_input(input)?).map_err(|e| format!("{name}: {e}"))? {
        match row.map_err(|e| format!("{name}: {e}"))? {
            Ok(x) => rows.push(x),
            Err(_) => skipped += 1,
        }
    }
    if rows.is_empty() {
        return Err(format!("{name}: no valid rows"));
    }
    if skipped > 0 {
        eprintln!("bench: {skipped} rows skipped (not six finite numbers)");
    }
    let sys = Stewart::new();
    let start = home_start(&sys).map_err(|e| e.to_string())?;
    let options = Options {
        linear: if dense {
            linkage::Linear::Dense
        } else {
            linkage::Linear::Generated
        },
        ..Options::TIGHT
    };
    let solver = match method {
        Method::Ph => linkage::Method::ArcLength,
        Method::Nh => linkage::Method::NewtonHomotopy,
        Method::Nr => linkage::Method::NewtonRaphson,
    };
    // Newton–Raphson from home, prepared once as a caller solving from a fixed start would:
    // B factored at home serves every row (B does not depend on the leg lengths).
    let from_home = linkage::NewtonRaphson::new(sys.clone(), start);
    let mut times: Vec<f64> = Vec::new();
    // Each row's fastest pass ([`best_of_passes`]).
    let mut best = vec![f64::INFINITY; rows.len()];
    let (mut failures, mut unproven, mut repetitions) = (0usize, 0usize, 0usize);
    let began = Instant::now();
    // At least 3 passes and `seconds` of solving (1 s by default, for stable statistics).
    while another_pass(repetitions, began, seconds, times.len(), rows.len()) {
        repetitions += 1;
        let tracker = Tracker::new(sys.clone(), start, options);
        let mut tracker = if certify {
            tracker.certified()
        } else {
            tracker
        };
        let mut chain = CertifiedSteps::new();
        let mut current = start;
        for (r, x) in rows.iter().enumerate() {
            let t0 = Instant::now();
            // With `--certify`, a solve counts as proven when its certificate (with `--track`:
            // its step's proof, the tracker's own for PH) passes, and is timed with it.
            let (ok, proven, next) = if track && matches!(method, Method::Ph) {
                match tracker.update(x) {
                    Ok(_) => (true, true, None),
                    Err(TrackError::Unproven { .. }) => (true, false, None),
                    Err(_) => (false, false, None),
                }
            } else {
                // An answer, as `solve` counts it: `ok` from PH, `unverified` from NH and NR
                // (the tolerance met; these methods cannot establish the branch).
                let solved = if matches!(method, Method::Nr) && current == start {
                    from_home.solve(x, &options)
                } else {
                    solver.solve(&sys, &current, x, &options)
                };
                match solved {
                    Ok(sol) if sol.status.meets_tolerance() => {
                        let proven = !certify
                            || if track {
                                chain
                                    .prove(&sys, (current.v(), current.x()), (&sol.v, x))
                                    .is_proven()
                            } else {
                                linkage::certify(&sys, &sol.v, x).is_ok()
                            };
                        (true, proven, (track && proven).then_some(sol.v))
                    }
                    _ => (false, false, None),
                }
            };
            let t = t0.elapsed().as_secs_f64() * 1e6;
            times.push(t);
            best[r] = best[r].min(t);
            failures += usize::from(!ok);
            unproven += usize::from(certify && ok && !proven);
            // The next row starts here: a checked start, outside the timed solve.
            if let Some(Ok(s)) = next.map(|v| Start::new(&sys, v, *x)) {
                current = s;
            }
        }
    }
    let capped = say_if_capped(began, seconds, times.len());
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let pick = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize];
    let (best_mean, best_median) = best_of_passes(&mut best);
    let name = match method {
        Method::Ph => "ph",
        Method::Nh => "nh",
        Method::Nr => "nr",
    };
    if json {
        let out = serde_json::json!({
            "method": name, "track": track, "linear": if dense { "dense" } else { "generated" },
            "certify": certify,
            "points": rows.len(), "repetitions": repetitions, "capped": capped, "failures_per_pass": failures / repetitions,
            "unproven_per_pass": certify.then_some(unproven / repetitions),
            "mean_us": mean, "median_us": pick(0.5), "p99_us": pick(0.99),
            "best_of_passes_mean_us": best_mean, "best_of_passes_median_us": best_median,
            // Which of the solvers' twins ran (the answers are the same; the times are not).
            "x86_64_v3": linkage::uses_x86_64_v3(),
        });
        print(&format!("{out}\n"))
    } else {
        print(&format!(
            "{name}{}{}{}{}: {} points × {repetitions} passes, mean {mean:.3} µs, median {:.3} µs, p99 {:.3} µs per solve; each row's fastest pass: mean {best_mean:.3} µs, median {best_median:.3} µs ({} not ok{} per pass)\n",
            if track { " --track" } else { "" },
            if certify { " --certify" } else { "" },
            if dense { " (dense LU)" } else { "" },
            if linkage::uses_x86_64_v3() { " [x86-64-v3]" } else { "" },
            rows.len(),
            pick(0.5),
            pick(0.99),
            failures / repetitions,
            if certify {
                format!(", {} solved but not proven", unproven / repetitions)
            } else {
                String::new()
            }
        ))
    }
}

/// `stewart bench --method all`: time per row to find every assembly mode (all complex roots,
/// `linkage::modes`), after the start set is built once (its time reported apart).
pub fn run_all(
    geometry: Option<&Path>,
    input: &Path,
    json: bool,
    seconds: f64,
) -> Result<(), String> {
    use linkage_examples::cli::geometry;
    use linkage_examples::stewart::{platform_is_coplanar, SixSix, StewartGeneral};
    let rows = legs_csv::read(input)?;
    match geometry {
        None => time_all(
            || crate::modes::table_iii(&rows),
            &rows,
            input,
            json,
            seconds,
        ),
        Some(path) => {
            let (base, platform) = geometry::load_joints(path)?;
            if platform_is_coplanar(&platform) {
                let sys = Stewart::with_joints(&base, &platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                time_all(
                    || crate::modes::solver(sys, &rows),
                    &rows,
                    input,
                    json,
                    seconds,
                )
            } else {
                let sys = StewartGeneral::with_joints(&base, &platform)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
                time_all(
                    || crate::modes::solver(sys, &rows),
                    &rows,
                    input,
                    json,
                    seconds,
                )
            }
        }
    }
}

fn time_all<S: linkage_examples::stewart::SixSix>(
    setup: impl FnOnce() -> Result<Box<linkage::modes::AllModes<S, 18, 6, CAPACITY>>, String>,
    rows: &[legs_csv::Row],
    input: &Path,
    json: bool,
    seconds: f64,
) -> Result<(), String> {
    use linkage::modes::Roots;
    let points: Vec<[f64; 6]> = rows
        .iter()
        .filter_map(|r| r.as_ref().ok().copied())
        .collect();
    if points.is_empty() {
        return Err(format!("{}: no valid rows", input.display()));
    }
    let began = Instant::now();
    let modes = setup()?;
    let setup = began.elapsed().as_secs_f64();
    let mut roots = Box::new(Roots::<18, CAPACITY>::new());
    let mut times: Vec<f64> = Vec::new();
    // Each row's fastest pass ([`best_of_passes`]).
    let mut best = vec![f64::INFINITY; points.len()];
    let (mut incomplete, mut steps, mut real, mut repetitions) = (0usize, 0usize, 0usize, 0usize);
    let began = Instant::now();
    while another_pass(repetitions, began, seconds, times.len(), points.len()) {
        repetitions += 1;
        for (r, x) in points.iter().enumerate() {
            let t0 = Instant::now();
            let ok = modes.solve(x, &mut roots).is_ok();
            let t = t0.elapsed().as_secs_f64() * 1e6;
            times.push(t);
            best[r] = best[r].min(t);
            incomplete += usize::from(!ok || !roots.is_complete());
            steps += roots.endpoints().iter().map(|e| e.steps).sum::<usize>();
            real += roots.real().len();
        }
    }
    let capped = say_if_capped(began, seconds, times.len());
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let pick = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize];
    let (best_mean, best_median) = best_of_passes(&mut best);
    let paths = modes.start_count();
    let solves = times.len() as f64;
    let steps_per_path = steps as f64 / (solves * paths as f64);
    if json {
        let out = serde_json::json!({
            "method": "all", "points": points.len(), "repetitions": repetitions, "capped": capped,
            "paths": paths, "setup_ms": setup * 1e3,
            "incomplete_per_pass": incomplete / repetitions,
            "real_per_point": real as f64 / solves, "steps_per_path": steps_per_path,
            "mean_us": mean, "median_us": pick(0.5), "p99_us": pick(0.99),
            "mean_us_per_path": mean / paths as f64,
            "best_of_passes_mean_us": best_mean, "best_of_passes_median_us": best_median,
        });
        print(&format!("{out}\n"))
    } else {
        print(&format!(
            "all modes: {} points × {repetitions} passes, {paths} paths (start set {:.0} ms), mean {mean:.1} µs, median {:.1} µs, p99 {:.1} µs per point ({:.2} µs per path, {steps_per_path:.1} steps per path); each row's fastest pass: mean {best_mean:.1} µs, median {best_median:.1} µs; {} incomplete per pass",
            points.len(),
            setup * 1e3,
            pick(0.5),
            pick(0.99),
            mean / paths as f64,
            incomplete / repetitions
        ))
    }
}

/// The mean and median over the rows of each row's fastest pass (`best`, sorted here):
/// preemption on a shared machine only ever adds time, so a row's minimum over passes is its
/// own cost, and these are steadier than the figures over every solve when the machine is busy.
fn best_of_passes(best: &mut [f64]) -> (f64, f64) {
    best.sort_by(f64::total_cmp);
    let mean = best.iter().sum::<f64>() / best.len() as f64;
    (mean, best[(best.len() - 1) / 2])
}
