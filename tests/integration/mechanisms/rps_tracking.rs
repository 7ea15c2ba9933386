//! The trajectory tracker on the 3-RPS (16 assembly modes in the complex) over random smooth
//! leg-length curves, every accepted sample held to a finely stepped continuation along the
//! curve itself.
//!
//! The reference follows the curve in 16 Newton-corrected steps per sample and watches det B
//! between them: while its sign has not changed it is the start's branch, and an accepted
//! sample must be it. Once the curve has met a singularity the branch beyond it is no longer
//! defined by the curve; an accepted sample must then be what fine continuation along the
//! straight joint segment from the last accepted sample reaches without a sign change of
//! det B (the tracker's own fallback path, and the only connection it can claim).

use linkage::reference::straight_segment_from;
use linkage::{det_b, Mechanism, Options, Tracker};
use linkage_examples::rps::Rps3;
use linkage_tests::Rng;
use std::f64::consts::TAU;

/// Leg lengths from the home legs: per leg a sine and a 1 − cos term, sampled at `rate`.
struct Curve {
    home: [f64; 3],
    amp: [[f64; 3]; 2],
    phase: [f64; 3],
    freq: [f64; 2],
    rate: f64,
}

impl Curve {
    fn at(&self, t: f64) -> [f64; 3] {
        std::array::from_fn(|i| {
            let p = self.phase[i];
            self.home[i]
                + self.amp[0][i] * ((TAU * self.freq[0] * t + p).sin() - p.sin())
                + self.amp[1][i] * (1.0 - (TAU * self.freq[1] * t).cos())
        })
    }
}

/// Newton from `v` at inputs `x` (dense LU, as the reference module does); `None` if it does
/// not settle to rounding.
fn newton(sys: &Rps3, mut v: [f64; 9], x: &[f64; 3]) -> Option<[f64; 9]> {
    for _ in 0..30 {
        let mut f = [0.0; 9];
        sys.residual(&v, x, &mut f);
        let mut b = [[0.0; 9]; 9];
        sys.jacobian_dense(&v, x, &mut b);
        let mut d = f;
        linkage_tests::dense::Lu::new(b)?.solve(&mut d);
        let size = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        let step = d.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        for i in 0..9 {
            v[i] -= d[i];
        }
        if step <= 1e-13 * size {
            return Some(v);
        }
        if !step.is_finite() {
            return None;
        }
    }
    None
}

#[derive(Default, Debug)]
struct Tally {
    accepted: usize,
    /// Accepted while the curve's reference was intact, and matched it.
    on_curve: usize,
    /// Accepted after the curve met a singularity, matched by the straight joint segment.
    on_segment: usize,
    refused: usize,
    /// Refused while the curve's reference stayed above 5 % of the start's |det B| since the
    /// last accepted sample.
    refused_clear: usize,
    curves_through_singularities: usize,
}

fn track(sys: &Rps3, curve: &Curve, tally: &mut Tally, case: usize) {
    let start = sys.home_start().unwrap();
    let det0 = start.det();
    let tol = Options::TIGHT.tolerance;
    let mut tracker = Tracker::new(sys.clone(), start, Options::TIGHT);
    // The reference along the curve, while intact.
    let mut reference = Some(*start.v());
    // The smallest det B / det0 the reference met since the last accepted sample.
    let mut low = f64::INFINITY;
    const SUB: usize = 16;
    for k in 1..=curve.rate as usize {
        let t = k as f64 / curve.rate;
        let x = curve.at(t);
        if let Some(mut v) = reference {
            let mut intact = true;
            for s in 1..=SUB {
                let ts = (k - 1) as f64 / curve.rate + s as f64 / (SUB as f64 * curve.rate);
                let xs = curve.at(ts);
                match newton(sys, v, &xs) {
                    Some(next) => {
                        let ratio = det_b(sys, &next, &xs) / det0;
                        low = low.min(ratio);
                        v = next;
                        intact &= ratio > 0.0;
                    }
                    None => intact = false,
                }
                if !intact {
                    break;
                }
            }
            reference = intact.then_some(v);
            if !intact {
                tally.curves_through_singularities += 1;
            }
        }
        let at = format!("case {case}, sample {k} (t = {t}), legs {x:?}");
        let (v_a, x_a) = (*tracker.state().0, *tracker.state().1);
        match tracker.update(&x) {
            Ok(sample) => {
                tally.accepted += 1;
                low = f64::INFINITY;
                let near = |truth: &[f64; 9]| {
                    linkage_tests::max_diff(&sample.v, truth)
                        <= 10.0 * tol / sample.proximity.min(1.0) + 1e-9
                };
                if reference.as_ref().is_some_and(near) {
                    tally.on_curve += 1;
                    continue;
                }
                assert!(
                    reference.is_none(),
                    "{at}: accepted {:?}, {:e} from the curve's own branch {:?} (proximity {:e})",
                    sample.v,
                    linkage_tests::max_diff(&sample.v, reference.as_ref().unwrap()),
                    reference,
                    sample.proximity
                );
                let (seg, flips) = straight_segment_from(sys, (&v_a, &x_a), det0, &x, 1000);
                assert!(
                    flips == 0 && near(&seg),
                    "{at}: accepted after the curve met a singularity, but the joint segment from the last accepted sample {} ({:e} from its end)",
                    if flips == 0 { "does not reach it" } else { "meets a singularity" },
                    linkage_tests::max_diff(&sample.v, &seg)
                );
                tally.on_segment += 1;
            }
            Err(_) => {
                tally.refused += 1;
                assert_eq!((*tracker.state().0, *tracker.state().1), (v_a, x_a), "{at}");
                if reference.is_some() && low > 0.05 {
                    tally.refused_clear += 1;
                    eprintln!("{at}: refused on a stretch of the curve clear of singularities (det B ≥ {low:e} of the start's)");
                }
            }
        }
    }
}

#[test]
fn rps_tracker_stays_on_the_curves_branch() {
    let sys = Rps3::new();
    let home = Rps3::HOME_INPUTS;
    let mut tally = Tally::default();
    let mut rng = Rng::new(0x3295);
    for case in 0..linkage_tests::sweep(4, 150) {
        // Up to 90 mm on legs of 158 mm: into the singular configurations and out of reach.
        let reach = rng.uniform(5.0, 90.0);
        let curve = Curve {
            home,
            amp: [0, 1].map(|_| [0, 1, 2].map(|_| reach * rng.symmetric() / 2.0)),
            phase: [0, 1, 2].map(|_| rng.uniform(0.0, TAU)),
            freq: [rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0)],
            rate: [25.0, 100.0, 1000.0][(rng.next_u64() % 3) as usize],
        };
        track(&sys, &curve, &mut tally, case);
    }
    eprintln!("3-RPS tracker: {tally:?}");
    assert!(tally.on_curve > 0, "{tally:?}");
    assert_eq!(tally.refused_clear, 0, "{tally:?}");
}
