//! Trajectory mode: successive joint vectors (e.g. 1 kHz samples), each solved from the last
//! solution, never leaving the start's branch.

use crate::arc_length::arc_length;
use crate::lu::{factor, solve};
use crate::math::norm;
use crate::start::{all_finite, correction};

use crate::{Mechanism, Options, SolveError, Start, Status};

/// One tracked sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<const N: usize> {
    pub v: [f64; N],
    /// |det B| / |det B at the start|: how far from a direct singularity (0 at one).
    pub proximity: f64,
    /// Newton iterations spent on this sample.
    pub newton_iterations: u32,
    /// Whether the fast path failed and continuation had to take over.
    pub fell_back: bool,
}

/// Why a sample was refused. The tracker keeps its last good state and stays usable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrackError {
    /// The sample itself is invalid.
    Input(SolveError),
    /// The sample cannot be reached on the branch from the last one.
    Lost(Status),
}

impl core::fmt::Display for TrackError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TrackError::Input(e) => write!(f, "{e}"),
            TrackError::Lost(s) => write!(f, "{s}"),
        }
    }
}

/// Follows one branch through a stream of joint vectors.
///
/// Each update predicts with the linearisation `B Δv = −(∂F/∂x) Δx` (Eq. 5), corrects with
/// Newton under the same contraction test as [`arc_length`](crate::arc_length), and falls back
/// to full pseudo-arc-length continuation from the last sample when that test fails.
#[derive(Clone, Debug)]
pub struct Tracker<S, const N: usize, const M: usize> {
    sys: S,
    start: Start<N, M>,
    v: [f64; N],
    x: [f64; M],
    options: Options,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Tracker<S, N, M> {
    pub fn new(sys: S, start: Start<N, M>, options: Options) -> Self {
        Tracker {
            v: start.v,
            x: start.x,
            sys,
            start,
            options,
        }
    }

    /// The last accepted pivot coordinates and joint inputs.
    pub fn state(&self) -> (&[f64; N], &[f64; M]) {
        (&self.v, &self.x)
    }

    pub fn mechanism(&self) -> &S {
        &self.sys
    }

    /// Solves the next sample. On error nothing changes.
    pub fn update(&mut self, x: &[f64; M]) -> Result<Sample<N>, TrackError> {
        crate::start::check_target(&self.sys, x, &self.options).map_err(TrackError::Input)?;
        let scale = norm(&self.v).max(1.0);
        let tol = self.options.tolerance.min(1e-6 * scale);
        let mut iterations = 0;
        if let Some(v) = self.fast(x, tol, &mut iterations) {
            if let Some(sample) = self.accept(v, x, iterations, false) {
                return Ok(sample);
            }
        }
        // Fallback: continuation from the last sample, whose branch is the start's.
        let here = Start {
            v: self.v,
            x: self.x,
            det: self.start.det,
        };
        let sol = arc_length(&self.sys, &here, x, &self.options).map_err(TrackError::Input)?;
        if !sol.is_ok() {
            return Err(TrackError::Lost(sol.status));
        }
        self.accept(sol.v, x, iterations + sol.newton_iterations, true)
            .ok_or(TrackError::Lost(Status::BranchChanged))
    }

    fn fast(&self, x: &[f64; M], tol: f64, iterations: &mut u32) -> Option<[f64; N]> {
        // Predictor: v + Δv with B Δv = −(∂F/∂x)(x − x_prev).
        let mut b = [[0.0; N]; N];
        self.sys.jacobian_dense(&self.v, &self.x, &mut b);
        let piv = factor::<N, _>(&mut b)?;
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(&self.v, &self.x, &mut a);
        let mut dv = [0.0; N];
        for i in 0..N {
            dv[i] = -(0..M).map(|j| a[i][j] * (x[j] - self.x[j])).sum::<f64>();
        }
        solve(&b, &piv, &mut dv);
        let step = norm(&dv);
        let mut v = self.v;
        for i in 0..N {
            v[i] += dv[i];
        }
        let mut prev = f64::INFINITY;
        for k in 0..6 {
            let (d, _) = correction(&self.sys, &v, x)?;
            *iterations += 1;
            for i in 0..N {
                v[i] -= d[i];
            }
            let size = norm(&d);
            if size <= tol {
                return Some(v);
            }
            if (k == 0 && size > 0.5 * step + tol) || (k > 0 && size > 0.25 * prev) {
                return None;
            }
            prev = size;
        }
        None
    }

    fn accept(
        &mut self,
        v: [f64; N],
        x: &[f64; M],
        newton_iterations: u32,
        fell_back: bool,
    ) -> Option<Sample<N>> {
        let det = crate::start::det_b(&self.sys, &v, x);
        if det * self.start.det <= 0.0 || !all_finite(&v) {
            return None;
        }
        self.v = v;
        self.x = *x;
        Some(Sample {
            v,
            proximity: (det / self.start.det).abs(),
            newton_iterations,
            fell_back,
        })
    }
}
