//! Random pose trajectories from home, and det B along them on a fine grid: the oracle for the
//! tracker (a sample is connected to an earlier one without a singularity when det B keeps the
//! start's sign at every grid point between them).
//!
//! A trajectory is home ⊕ s·(a₁ sin 2πf₁t + a₂ (1 − cos 2πf₂t)), sampled at `rate` Hz. Its
//! kind sets the scale s against s*, the largest scale whose trajectory stays clear of
//! singularities (bisection on a coarse grid): `clear` (s* · 0.3–0.9), `graze` (just below s*),
//! `cross` (above s*: the pose meets a singular surface, and may come back), `fast` (fast
//! motion, 2–8 Hz, at 10–40 Hz sampling, below s*: the case of issue 9's defect 2).

use super::geometry::{random_offset, Machine};
use linkage_examples::stewart::SixSix;
use linkage_tests::Rng;
use std::f64::consts::TAU;

#[derive(Clone, Debug)]
pub struct Trajectory {
    pub kind: &'static str,
    pub amp: [[f64; 6]; 2],
    pub freq: [f64; 2],
    pub scale: f64,
    pub duration: f64,
    pub rate: f64,
}

impl Trajectory {
    /// The offset from home at time t.
    pub fn offset(&self, t: f64) -> [f64; 6] {
        let (a, b) = (
            (TAU * self.freq[0] * t).sin(),
            1.0 - (TAU * self.freq[1] * t).cos(),
        );
        std::array::from_fn(|i| self.scale * (self.amp[0][i] * a + self.amp[1][i] * b))
    }

    /// Sample times: k / rate for k = 1 … rate · duration.
    pub fn samples(&self) -> impl Iterator<Item = f64> + '_ {
        (1..=(self.rate * self.duration) as u64).map(|k| k as f64 / self.rate)
    }
}

/// det B / det0 along the trajectory at grid points `step` apart (−1 where the pose is not a
/// valid configuration).
pub struct Grid {
    pub step: f64,
    pub ratio: Vec<f64>,
}

impl Grid {
    pub fn new<S: SixSix>(m: &Machine<S>, tr: &Trajectory, step: f64) -> Grid {
        let n = (tr.duration / step).ceil() as usize;
        let ratio = (0..=n)
            .map(|i| {
                m.at(&tr.offset(i as f64 * step), 1.0)
                    .map_or(-1.0, |(_, _, r)| r)
            })
            .collect();
        Grid { step, ratio }
    }

    /// The smallest det B / det0 at the grid points in [t0, t1].
    pub fn min_between(&self, t0: f64, t1: f64) -> f64 {
        let i0 = (t0 / self.step).ceil() as usize;
        let i1 = ((t1 / self.step).floor() as usize).min(self.ratio.len() - 1);
        self.ratio
            .get(i0..=i1)
            .unwrap_or(&[])
            .iter()
            .fold(f64::INFINITY, |m, r| m.min(*r))
    }
}

fn clear_at<S: SixSix>(m: &Machine<S>, tr: &Trajectory, scale: f64) -> bool {
    let tr = Trajectory {
        scale,
        ..tr.clone()
    };
    (0..=300).all(|k| {
        let t = tr.duration * k as f64 / 300.0;
        m.at(&tr.offset(t), 1.0).is_some_and(|(_, _, r)| r > 0.0)
    })
}

/// A random trajectory of a random kind for the machine `m`.
pub fn random_trajectory<S: SixSix>(m: &Machine<S>, rng: &mut Rng) -> Trajectory {
    // Crossing trajectories weigh most: after a crossing the tracker must refuse until the
    // pose comes back, and then take up only what it can show is connected (defect 2).
    let kind = [
        "clear", "graze", "graze", "cross", "cross", "cross", "fast", "fast",
    ][(rng.next_u64() % 8) as usize];
    let fast = kind == "fast";
    let (f_lo, f_hi) = if fast { (2.0, 8.0) } else { (0.2, 3.0) };
    let rate = if fast {
        rng.uniform(10.0, 40.0)
    } else {
        match rng.next_u64() % 5 {
            0 => 1000.0,
            1 => 10.0,
            _ => 10f64.powf(rng.uniform(1.0, 3.0)),
        }
    };
    let mut tr = Trajectory {
        kind,
        amp: [
            random_offset(rng, 0.3, 0.3 * m.size),
            random_offset(rng, 0.3, 0.3 * m.size),
        ],
        freq: [rng.uniform(f_lo, f_hi), rng.uniform(f_lo, f_hi)],
        scale: 1.0,
        duration: rng.uniform(0.5, 2.0),
        rate,
    };
    // s*: the largest scale (up to 16) clear of singularities on the coarse grid.
    let (mut lo, mut hi) = (0.0, 1.0);
    while clear_at(m, &tr, hi) && hi < 16.0 {
        (lo, hi) = (hi, 2.0 * hi);
    }
    for _ in 0..16 {
        let mid = 0.5 * (lo + hi);
        if clear_at(m, &tr, mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    tr.scale = lo
        * match kind {
            "clear" => rng.uniform(0.3, 0.9),
            "graze" => 1.0 - 10f64.powf(rng.uniform(-6.0, -2.0)),
            "cross" => 1.0 + rng.uniform(0.02, 0.5),
            _ => rng.uniform(0.5, 0.99),
        };
    tr
}
