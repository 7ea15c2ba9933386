//! The solvers' x86-64-v3 twin (linkage's run-time dispatch) against the code as built: the
//! same answers, bit for bit, from Newton–Raphson, Newton homotopy, continuation and the
//! tracker, on the Stewart platform (every Table V point), the 3-RPS and the 6-RSS hexapod,
//! and every assembly mode of the 3-RPS (whose sparse LU has a twin).
//! Run by the integration tests and, in a release build where the kernels are inlined into the
//! twins, by `cargo run --release --example twins` in CI.

use crate::{rps, rss_hexapod, stewart};
use linkage::__private::prefer_x86_64_v3;
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage::{
    arc_length, Mechanism, Method, NewtonRaphson, Options, Solution, SolveError, Start, Tracker,
};

/// What [`compare_twins`] compared.
#[derive(Debug)]
pub struct Report {
    /// Answers compared (solves and tracked samples).
    pub answers: usize,
    /// Whether the twin ran: `false` on a CPU without x86-64-v3, where both runs took the
    /// code as built.
    pub twin: bool,
}

/// Solves every case with the twin and as built and compares the answers; the first that
/// differs is the error. Leaves the twin chosen, as it is by default.
pub fn compare_twins() -> Result<Report, String> {
    let twin = prefer_x86_64_v3(true);
    let fast = every_answer();
    prefer_x86_64_v3(false);
    let built = every_answer();
    prefer_x86_64_v3(true);
    if fast.len() != built.len() {
        return Err(format!("{} answers against {}", fast.len(), built.len()));
    }
    match fast.iter().zip(&built).find(|(a, b)| a != b) {
        Some((a, b)) => Err(format!("twin: {a}\nas built: {b}")),
        None => Ok(Report {
            answers: fast.len(),
            twin,
        }),
    }
}

fn every_answer() -> Vec<String> {
    let s = stewart::Stewart::new();
    let home = stewart::home_start(&s).expect("home");
    let mut legs = table_v_legs();
    legs.extend([*home.x(), [1e4; 6], [f64::NAN; 6]]);
    let mut out = answers(&s, &home, &legs);
    out.extend(tracked(&s, &home, &legs[..10]));

    let r = rps::Rps3::new();
    let r_home = rps::home_start(&r).expect("home");
    out.extend(answers(&r, &r_home, &around(r_home.x(), 10.0)));
    out.extend(every_mode(r, &around(r_home.x(), 10.0)[..5]));

    let h = rss_hexapod::RssHexapod::new();
    let h_home = rss_hexapod::home_start(&h).expect("home");
    out.extend(answers(&h, &h_home, &around(h_home.x(), 0.15)));
    out
}

/// Every target by Newton–Raphson (prepared and not), Newton homotopy and, every fourth,
/// continuation: one line per answer, floats as bits.
fn answers<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    targets: &[[f64; M]],
) -> Vec<String> {
    let nr = NewtonRaphson::new(sys.clone(), *start);
    let mut out = Vec::new();
    for (k, x) in targets.iter().enumerate() {
        let tight = &Options::TIGHT;
        out.push(line(S::NAME, k, &nr.solve(x, tight)));
        out.push(line(
            S::NAME,
            k,
            &Method::NewtonRaphson.solve(sys, start, x, tight),
        ));
        out.push(line(
            S::NAME,
            k,
            &Method::NewtonHomotopy.solve(sys, start, x, tight),
        ));
        if k % 4 == 0 {
            out.push(line(S::NAME, k, &arc_length(sys, start, x, tight)));
        }
    }
    out
}

/// Every assembly mode of the 3-RPS at each of `targets`: the endpoints of all 16 paths.
fn every_mode(r: rps::Rps3, targets: &[[f64; 3]]) -> Vec<String> {
    let modes = match AllModes::<_, 9, 3, 32>::new(r, &ModesOptions::default()) {
        Ok(m) => m,
        Err(e) => return vec![format!("3-RPS all modes: {e:?}")],
    };
    let mut roots = Roots::new();
    targets
        .iter()
        .enumerate()
        .map(|(k, x)| match modes.solve(x, &mut roots) {
            // Debug prints each float so that it reads back to the same bits.
            Ok(()) => format!("3-RPS modes {k}: {:?}", roots.endpoints()),
            Err(e) => format!("3-RPS modes {k}: {e:?}"),
        })
        .collect()
}

fn line<const N: usize>(name: &str, k: usize, r: &Result<Solution<N>, SolveError>) -> String {
    match r {
        Ok(s) => format!(
            "{name} target {k}: {:?} {} {} {} {:x?} {:x} {:x} {:x}",
            s.status,
            s.newton_iterations,
            s.steps_accepted,
            s.steps_rejected,
            s.v.map(f64::to_bits),
            s.lambda.to_bits(),
            s.error_estimate.to_bits(),
            s.min_det_ratio.to_bits()
        ),
        Err(e) => format!("{name} target {k}: {e:?}"),
    }
}

/// The tracker along straight joint-space segments from home through `via`, 200 samples each.
fn tracked(s: &stewart::Stewart, home: &Start<18, 6>, via: &[[f64; 6]]) -> Vec<String> {
    let mut tracker = Tracker::new(s.clone(), *home, Options::TIGHT);
    let mut from = *home.x();
    let mut out = Vec::new();
    for to in via {
        for k in 1..=200 {
            let t = k as f64 / 200.0;
            let x: [f64; 6] = core::array::from_fn(|j| from[j] + t * (to[j] - from[j]));
            out.push(match tracker.update(&x) {
                Ok(sample) => format!(
                    "sample {k} to {to:?}: {:x?} {} {:x} {}",
                    sample.v.map(f64::to_bits),
                    sample.newton_iterations,
                    sample.proximity.to_bits(),
                    sample.fell_back
                ),
                Err(e) => format!("sample {k} to {to:?}: {e:?}"),
            });
        }
        from = *to;
    }
    out
}

/// The legs of every Table V point (`examples/data/table_v_points.csv`).
fn table_v_legs() -> Vec<[f64; 6]> {
    include_str!("../data/table_v_points.csv")
        .lines()
        .skip(1)
        .map(|row| {
            let mut cells = row.split(',').skip(1).map(|c| c.parse().expect("a number"));
            core::array::from_fn(|_| cells.next().expect("six legs"))
        })
        .collect()
}

/// 100 inputs within `by` of `home`, spread deterministically (`count` measures NR on them).
pub fn around<const M: usize>(home: &[f64; M], by: f64) -> Vec<[f64; M]> {
    (1..=100)
        .map(|k| core::array::from_fn(|j| home[j] + by * (1.3 * k as f64 + 0.7 * j as f64).sin()))
        .collect()
}
