//! Trajectory mode: successive joint vectors (e.g. 1 kHz samples), each solved from the last
//! solution, never leaving the start's branch.

use crate::arc_length::arc_length;
use crate::correction::{correction_in, Convergence};
use crate::math::norm;

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
/// Each update predicts with the linearisation `B Δv = −(∂F/∂x) Δx` (Eq. 5), reusing the
/// factorisation of B kept from the previous update, corrects with Newton under the same
/// contraction test as [`arc_length`](crate::arc_length) (the predictor step counts as the
/// zeroth correction, so a single Newton step can confirm convergence), and falls back to full
/// pseudo-arc-length continuation from the last sample when that test fails. A sample is
/// accepted only if det B keeps the start's sign.
///
/// ```
/// use linkage::{Mechanism, Options, Tracker};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// # let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// # let start = linkage::Start::new(&rps, v0, x0).unwrap();
/// let mut tracker = Tracker::new(rps.clone(), start, Options::TIGHT);
/// for k in 1..=1000 {
///     // 1 kHz samples of a slow heave.
///     let t = k as f64 * 1e-3;
///     let legs = x0.map(|l| l + 10.0 * (2.0 * std::f64::consts::PI * t).sin());
///     let sample = tracker.update(&legs).unwrap();
///     assert!(sample.proximity > 0.1, "far from a singularity");
/// }
/// // A bad sample is refused, and the tracker carries on.
/// assert!(tracker.update(&[f64::NAN; 3]).is_err());
/// assert!(tracker.update(&x0).is_ok());
/// ```
#[derive(Clone, Debug)]
pub struct Tracker<S: Mechanism<N, M>, const N: usize, const M: usize> {
    sys: S,
    start: Start<N, M>,
    v: [f64; N],
    x: [f64; M],
    options: Options,
    /// B factored near (v, x), for the next predictor; `None` until first needed.
    factor: Option<S::Factor>,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Tracker<S, N, M> {
    pub fn new(sys: S, start: Start<N, M>, options: Options) -> Self {
        Tracker {
            v: start.v,
            x: start.x,
            sys,
            start,
            options,
            factor: None,
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
        let mut iterations = 0;
        if let Some((v, det, factor)) = self.fast(x, &mut iterations) {
            if det * self.start.det > 0.0 {
                self.factor = Some(factor);
                return Ok(self.accept(v, x, det, iterations, false));
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
        let det = crate::correction::det_b(&self.sys, &sol.v, x);
        if det * self.start.det <= 0.0 {
            return Err(TrackError::Lost(Status::BranchChanged));
        }
        self.factor = None;
        Ok(self.accept(sol.v, x, det, iterations + sol.newton_iterations, true))
    }

    /// Predictor and Newton corrector; `(v, det B at the last iterate, its factorisation)`.
    fn fast(&mut self, x: &[f64; M], iterations: &mut u32) -> Option<([f64; N], f64, S::Factor)> {
        let mut fac = match self.factor {
            Some(f) => f,
            None => {
                let mut f = self.sys.new_factor();
                self.sys.factor(&self.v, &self.x, &mut f)?;
                f
            }
        };
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(&self.v, &self.x, &mut a);
        let mut dv = [0.0; N];
        for i in 0..N {
            dv[i] = -(0..M).map(|j| a[i][j] * (x[j] - self.x[j])).sum::<f64>();
        }
        self.sys.solve(&fac, &mut dv);
        let step = norm(&dv);
        let mut v = self.v;
        for i in 0..N {
            v[i] += dv[i];
        }
        let mut convergence = Convergence::new(self.options.tolerance, &v);
        // The predictor step is the zeroth correction: it seeds the contraction estimate.
        convergence.reached(step.max(f64::MIN_POSITIVE));
        let mut prev = step;
        for k in 0..6 {
            let (d, det, size) = correction_in(&self.sys, &v, x, self.options.linear, &mut fac)?;
            *iterations += 1;
            for i in 0..N {
                v[i] -= d[i];
            }
            if !size.is_finite()
                || (k == 0 && size > 0.5 * step + self.options.tolerance)
                || (k > 0 && size > 0.25 * prev)
            {
                return None;
            }
            if convergence.reached(size) {
                return Some((v, det, fac));
            }
            prev = size;
        }
        None
    }

    fn accept(
        &mut self,
        v: [f64; N],
        x: &[f64; M],
        det: f64,
        newton_iterations: u32,
        fell_back: bool,
    ) -> Sample<N> {
        self.v = v;
        self.x = *x;
        Sample {
            v,
            proximity: (det / self.start.det).abs(),
            newton_iterations,
            fell_back,
        }
    }
}
