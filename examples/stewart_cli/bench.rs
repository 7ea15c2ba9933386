//! `stewart bench`: time per solve over every row of a leg-length CSV, repeated until the
//! timing is stable.

use crate::Method;
use linkage::{Options, Start, Tracker};
use linkage_examples::cli::legs_csv;
use linkage_examples::stewart::{home_start, Stewart};
use std::path::Path;
use std::time::{Duration, Instant};

pub fn run(
    method: Method,
    track: bool,
    input: &Path,
    json: bool,
    dense: bool,
) -> Result<(), String> {
    let rows: Vec<[f64; 6]> = legs_csv::read(input)?
        .into_iter()
        .filter_map(Result::ok)
        .collect();
    if rows.is_empty() {
        return Err(format!("{}: no valid rows", input.display()));
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
    let mut times: Vec<f64> = Vec::new();
    let (mut failures, mut repetitions) = (0usize, 0usize);
    let began = Instant::now();
    // At least 3 passes and 1 s of solving, so that the per-solve statistics are stable.
    while repetitions < 3 || began.elapsed() < Duration::from_secs(1) {
        repetitions += 1;
        let mut tracker = Tracker::new(sys.clone(), start, options);
        let mut current = start;
        for x in &rows {
            let t0 = Instant::now();
            let ok = if track && matches!(method, Method::Ph) {
                tracker.update(x).is_ok()
            } else {
                match solver.solve(&sys, &current, x, &options) {
                    Ok(sol) if sol.is_ok() => {
                        if track {
                            if let Ok(next) = Start::new(&sys, sol.v, *x) {
                                current = next;
                            }
                        }
                        true
                    }
                    _ => false,
                }
            };
            times.push(t0.elapsed().as_secs_f64() * 1e6);
            failures += usize::from(!ok);
        }
    }
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let pick = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize];
    let name = match method {
        Method::Ph => "ph",
        Method::Nh => "nh",
        Method::Nr => "nr",
    };
    if json {
        let out = serde_json::json!({
            "method": name, "track": track, "linear": if dense { "dense" } else { "generated" },
            "points": rows.len(), "repetitions": repetitions, "failures_per_pass": failures / repetitions,
            "mean_us": mean, "median_us": pick(0.5), "p99_us": pick(0.99),
        });
        println!("{out}");
    } else {
        println!(
            "{name}{}{}: {} points × {repetitions} passes, mean {mean:.3} µs, median {:.3} µs, p99 {:.3} µs per solve ({} not ok per pass)",
            if track { " --track" } else { "" },
            if dense { " (dense LU)" } else { "" },
            rows.len(),
            pick(0.5),
            pick(0.99),
            failures / repetitions
        );
    }
    Ok(())
}
