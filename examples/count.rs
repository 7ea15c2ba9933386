//! Work of the solver kernels, for an instruction counter: every measured piece of work is one
//! `#[inline(never)]` function named `measure_*`, so callgrind's inclusive count of that function
//! is the cost of exactly that work, independent of the machine's load.
//!
//! ```text
//! cargo build --release --example count
//! valgrind --tool=callgrind --callgrind-out-file=cg.out target/release/examples/count nr-normal examples/data/table_v_points.csv
//! callgrind_annotate --inclusive=yes cg.out | grep measure_
//! ```
//!
//! `nr-normal` and `nr-all`: Newton–Raphson on the Stewart platform from home to every normal
//! (every) row of a `stewart table-v --export` CSV, one pass; it prints the number of solves and
//! Newton iterations to divide the count by. `nr-dense`: `nr-normal` with the dense-LU baseline
//! (`Linear::Dense`). `nr-rps`, `nr-rss_hexapod`: the same from the
//! home configurations of the other examples to 100 inputs around it. `ph-all`: pseudo-arc-length
//! continuation from home to every row. `track TRAJECTORY.csv`:
//! the `Tracker` over every sample of a `stewart trajectory` CSV; `track-rss_hexapod` over 2 s
//! at 1 kHz of the 6-RSS hexapod's cranks swinging 0.1 rad about home. `certify`: the Krawczyk
//! certificate of NR's answer from home at every row it solves; `certify-step TRAJECTORY.csv`:
//! `certify_step` between successive tracked samples; `track-certify TRAJECTORY.csv`: the
//! certified `Tracker` (each sample's step proven). `velocity`: 1000 calls each of
//! `velocity::twist` and `velocity::platform_jacobian` on the Stewart platform at home.
//! `stewart`, `rps`, `rss_hexapod`: 1000 calls each of
//! the generated factorisation, solve and residual at the mechanism's home configuration.
//!
//! On an x86-64 CPU with AVX2 the solvers run their x86-64-v3 twin (`linkage::uses_x86_64_v3`);
//! with `COUNT_AS_BUILT=1` in the environment they run the code as built for the plain target,
//! as on a CPU without it.

use linkage::{newton_raphson, Linear, Mechanism, NewtonRaphson, Options, Start};
use linkage_examples::twins::around;
use linkage_examples::{rps, rss_hexapod, stewart};
use std::hint::black_box;

/// Calls of each kernel (factor, solve, residual) per mechanism.
const CALLS: usize = 1000;

fn main() -> Result<(), String> {
    if std::env::var_os("COUNT_AS_BUILT").is_some() {
        linkage::__private::prefer_x86_64_v3(false);
    }
    let mut args = std::env::args().skip(1);
    let what = args.next().unwrap_or_default();
    let path = args
        .next()
        .unwrap_or_else(|| "examples/data/table_v_points.csv".into());
    let sys = stewart::Stewart::new();
    let start = stewart::home_start(&sys).map_err(|e| e.to_string())?;
    match what.as_str() {
        "nr-normal" | "nr-all" | "nr-dense" => {
            let (normal, all) = points(&path)?;
            let rows = if what == "nr-all" { all } else { normal };
            let options = if what == "nr-dense" {
                Options {
                    linear: Linear::Dense,
                    ..Options::TIGHT
                }
            } else {
                Options::TIGHT
            };
            let (ok, iterations) = measure_nr(&sys, &start, &rows, &options);
            println!(
                "stewart NR from home ({what}): {} solves, {ok} ok, {iterations} iterations",
                rows.len()
            );
        }
        "nr-rps" => {
            let r = rps::Rps3::new();
            let start = rps::home_start(&r).map_err(|e| e.to_string())?;
            let rows = around(start.x(), 10.0);
            let (ok, iterations) = measure_nr(&r, &start, &rows, &Options::TIGHT);
            println!(
                "rps NR from home, legs within 10 mm of home: {} solves, {ok} ok, {iterations} iterations",
                rows.len()
            );
        }
        "nr-rss_hexapod" => {
            let h = rss_hexapod::RssHexapod::new();
            let start = rss_hexapod::home_start(&h).map_err(|e| e.to_string())?;
            let rows = around(start.x(), 0.15);
            let (ok, iterations) = measure_nr(&h, &start, &rows, &Options::TIGHT);
            println!(
                "rss_hexapod NR from home, cranks within 0.15 rad of home: {} solves, {ok} ok, {iterations} iterations",
                rows.len()
            );
        }
        "ph-all" => {
            let (_, all) = points(&path)?;
            let (ok, steps) = measure_ph(&sys, &start, &all);
            println!(
                "stewart PH (arc length) from home, all points: {} solves, {ok} ok, {steps} steps accepted and rejected",
                all.len()
            );
        }
        "track" => {
            // A `stewart trajectory` CSV: t_s, L1…L6, …
            let rows = legs_after_first_column(&path)?;
            let (ok, samples) = measure_track(&sys, &start, &rows);
            println!("stewart tracker: {samples} samples, {ok} ok");
        }
        "track-rss_hexapod" => {
            // 2 s at 1 kHz: each crank swings 0.1 rad about home at its own slow frequency.
            let h = rss_hexapod::RssHexapod::new();
            let start = rss_hexapod::home_start(&h).map_err(|e| e.to_string())?;
            let rows: Vec<[f64; 6]> = (0..=2000)
                .map(|k| {
                    let t = k as f64 * 1e-3;
                    std::array::from_fn(|j| {
                        let f = 0.5 + 0.1 * j as f64;
                        start.x()[j] + 0.1 * (2.0 * std::f64::consts::PI * f * t).sin()
                    })
                })
                .collect();
            let (ok, samples) = measure_track(&h, &start, &rows);
            println!("rss_hexapod tracker: {samples} samples, {ok} ok");
        }
        "track-certify" => {
            let rows = legs_after_first_column(&path)?;
            let (ok, samples) = measure_track_certified(&sys, &start, &rows);
            println!("stewart certified tracker: {samples} samples, {ok} ok and proven");
        }
        "certify" => {
            // Certificates of NR's answers from home at every row it solves.
            let (_, all) = points(&path)?;
            let sols: Vec<_> = all
                .iter()
                .filter_map(|x| {
                    let sol = newton_raphson(&sys, &start, x, &Options::TIGHT).ok()?;
                    sol.is_ok().then_some((sol.v, *x))
                })
                .collect();
            let proved = measure_certify(&sys, &sols);
            println!("stewart certify: {} solutions, {proved} certified", sols.len());
        }
        "certify-step" => {
            // The tracker's samples, then a certificate of every step between them.
            let rows = legs_after_first_column(&path)?;
            let mut tracker = linkage::Tracker::new(sys.clone(), start, Options::TIGHT);
            let samples: Vec<_> = rows
                .iter()
                .filter_map(|x| Some((tracker.update(x).ok()?.v, *x)))
                .collect();
            let proved = measure_certify_step(&sys, &samples);
            println!(
                "stewart certify_step: {} steps, {proved} certified",
                samples.len().saturating_sub(1)
            );
        }
        "velocity" => {
            // At home: the twist for leg rates, and the 6×6 platform Jacobian.
            let xdot = [1.0, -1.0, 0.5, 0.0, 2.0, -0.5];
            let (twists, jacobians) = measure_velocity(&sys, start.v(), start.x(), &xdot);
            println!("stewart velocity: {CALLS} twists ({twists} ok), {CALLS} platform Jacobians ({jacobians} ok)");
        }
        "stewart" => kernels("stewart", &sys, &start),
        "rps" => {
            let r = rps::Rps3::new();
            kernels("rps", &r, &rps::home_start(&r).map_err(|e| e.to_string())?);
        }
        "rss_hexapod" => {
            let h = rss_hexapod::RssHexapod::new();
            let s = rss_hexapod::home_start(&h).map_err(|e| e.to_string())?;
            kernels("rss_hexapod", &h, &s);
        }
        _ => {
            return Err("usage: count nr-normal|nr-all|nr-dense|nr-rps|nr-rss_hexapod|ph-all|track|track-certify|certify|certify-step|velocity|stewart|rps|rss_hexapod [POINTS.csv]".into())
        }
    }
    Ok(())
}

/// Columns 2 to 7 of every row after the header.
fn legs_after_first_column(path: &str) -> Result<Legs, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    text.lines()
        .skip(1)
        .map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            let mut x = [0.0; 6];
            for (j, v) in x.iter_mut().enumerate() {
                *v = fields
                    .get(j + 1)
                    .and_then(|f| f.trim().parse().ok())
                    .ok_or_else(|| format!("{path}: bad row {line}"))?;
            }
            Ok(x)
        })
        .collect()
}

/// Leg lengths, one row per point.
type Legs = Vec<[f64; 6]>;

/// The leg lengths of the `normal` rows and of all rows of a `stewart table-v --export` CSV.
fn points(path: &str) -> Result<(Legs, Legs), String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let (mut normal, mut all) = (Vec::new(), Vec::new());
    for line in text.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let mut x = [0.0; 6];
        for (j, v) in x.iter_mut().enumerate() {
            *v = fields
                .get(j + 1)
                .and_then(|f| f.trim().parse().ok())
                .ok_or_else(|| format!("{path}: bad row {line}"))?;
        }
        if fields.first() == Some(&"normal") {
            normal.push(x);
        }
        all.push(x);
    }
    Ok((normal, all))
}

#[inline(never)]
fn measure_nr<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    rows: &[[f64; M]],
    options: &Options,
) -> (usize, u64) {
    let (mut ok, mut iterations) = (0, 0);
    // Prepared once, as a caller solving from one start would (B factored at the start where
    // it serves every target); counted with the solves.
    let nr = NewtonRaphson::new(sys.clone(), *start);
    for x in rows {
        if let Ok(sol) = nr.solve(black_box(x), options) {
            // NR's converged results are `unverified`: it cannot establish the branch.
            ok += usize::from(sol.status.meets_tolerance());
            iterations += u64::from(sol.newton_iterations);
        }
    }
    (ok, iterations)
}

#[inline(never)]
fn measure_ph(sys: &stewart::Stewart, start: &Start<18, 6>, rows: &[[f64; 6]]) -> (usize, u64) {
    let (mut ok, mut steps) = (0, 0);
    for x in rows {
        if let Ok(sol) = linkage::arc_length(sys, start, black_box(x), &Options::TIGHT) {
            ok += usize::from(sol.is_ok());
            steps += u64::from(sol.steps_accepted + sol.steps_rejected);
        }
    }
    (ok, steps)
}

#[inline(never)]
fn measure_track<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    rows: &[[f64; M]],
) -> (usize, usize) {
    let mut tracker = linkage::Tracker::new(sys.clone(), *start, Options::TIGHT);
    let ok = rows
        .iter()
        .filter(|x| tracker.update(black_box(x)).is_ok())
        .count();
    (ok, rows.len())
}

#[inline(never)]
fn measure_track_certified(
    sys: &stewart::Stewart,
    start: &Start<18, 6>,
    rows: &[[f64; 6]],
) -> (usize, usize) {
    let mut tracker = linkage::Tracker::new(sys.clone(), *start, Options::TIGHT).certified();
    let ok = rows
        .iter()
        .filter(|x| tracker.update(black_box(x)).is_ok())
        .count();
    (ok, rows.len())
}

#[inline(never)]
fn measure_certify(sys: &stewart::Stewart, sols: &[([f64; 18], [f64; 6])]) -> usize {
    sols.iter()
        .filter(|(v, x)| linkage::certify(sys, black_box(v), black_box(x)).is_ok())
        .count()
}

#[inline(never)]
fn measure_certify_step(sys: &stewart::Stewart, samples: &[([f64; 18], [f64; 6])]) -> usize {
    samples
        .windows(2)
        .filter(|w| {
            linkage::certify_step(sys, black_box((&w[0].0, &w[0].1)), (&w[1].0, &w[1].1)).is_ok()
        })
        .count()
}

fn kernels<S: Mechanism<N, M>, const N: usize, const M: usize>(
    name: &str,
    sys: &S,
    start: &Start<N, M>,
) {
    let mut fac = sys.new_factor();
    let singular = measure_factor(sys, start, &mut fac);
    let y = measure_solve(sys, &fac, start.v());
    let f = measure_residual(sys, start);
    println!(
        "{name}: {CALLS} factorisations ({singular} singular), solves and residuals (checksums {:.3e} {:.3e})",
        y.iter().sum::<f64>(),
        f.iter().sum::<f64>()
    );
}

#[inline(never)]
fn measure_factor<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    fac: &mut S::Factor,
) -> usize {
    (0..CALLS)
        .filter(|_| {
            sys.factor(black_box(start.v()), black_box(start.x()), fac)
                .is_none()
        })
        .count()
}

#[inline(never)]
fn measure_solve<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    fac: &S::Factor,
    b: &[f64; N],
) -> [f64; N] {
    let mut out = [0.0; N];
    for _ in 0..CALLS {
        let mut y = black_box(*b);
        sys.solve(black_box(fac), &mut y);
        out = y;
    }
    out
}

#[inline(never)]
fn measure_residual<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
) -> [f64; N] {
    let mut f = [0.0; N];
    for _ in 0..CALLS {
        sys.residual(black_box(start.v()), black_box(start.x()), &mut f);
        black_box(&mut f);
    }
    f
}

#[inline(never)]
fn measure_velocity<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    xdot: &[f64; M],
) -> (usize, usize) {
    let twists = (0..CALLS)
        .filter(|_| linkage::velocity::twist(sys, black_box(v), x, xdot).is_ok())
        .count();
    let jacobians = (0..CALLS)
        .filter(|_| linkage::velocity::platform_jacobian(sys, black_box(v), x).is_ok())
        .count();
    (twists, jacobians)
}
