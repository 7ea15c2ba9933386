//! Newton–Raphson (the paper's NRA): Newton's method on F(v, x*) = 0 from the start's v.
//! Fast, and with no notion of branch: near a singularity it may converge to another
//! assembly mode. The det B sign check catches some of those, not all.

use crate::math::norm;
use crate::start::{all_finite, correction, det_b};
use crate::{Mechanism, Options, Solution, SolveError, Start, Status};

/// Solves F(v, x) = 0 by Newton's method from `start.v`.
///
/// ```
/// # use linkage::{Mechanism, Options, Start, newton_raphson};
/// linkage::mechanism! {
///     /// A point on three legs (a tripod): three S–P–S chains.
///     pub struct Tripod;
///     base { A = [0.0, 0.0, 0.0], B = [100.0, 0.0, 0.0], C = [0.0, 100.0, 0.0] }
///     platform(frame = [P, Q, R]) { P = [0.0, 0.0, 0.0], Q = [1.0, 0.0, 0.0], R = [0.0, 1.0, 0.0] }
///     chain a = base - S(A) - P(active la) - S(P) - platform;
///     chain b = base - S(B) - P(active lb) - S(Q) - platform;
///     chain c = base - S(C) - P(active lc) - S(R) - platform;
/// }
/// # let _ = Tripod::new();
/// ```
pub fn newton_raphson<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, x, options)?;
    let mut v = start.v;
    let mut iterations = 0;
    let status = loop {
        if iterations >= options.max_iterations {
            break not_converged(sys, &v, x);
        }
        let Some((d, _)) = correction(sys, &v, x) else {
            break Status::Singular { lambda: 1.0 };
        };
        iterations += 1;
        for i in 0..N {
            v[i] -= d[i];
        }
        if !all_finite(&v) {
            v = start.v;
            break Status::NotConverged { residual_norm: f64::INFINITY };
        }
        if norm(&d) <= options.tolerance {
            break Status::Converged;
        }
    };
    Ok(finish(sys, start, v, x, status, 1.0, 0, 0, iterations, 1.0))
}

pub(crate) fn not_converged<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Status {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    Status::NotConverged { residual_norm: norm(&f) }
}

/// Fills in the error estimate and checks the branch by the sign of det B.
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    v: [f64; N],
    x: &[f64; M],
    mut status: Status,
    lambda: f64,
    steps_accepted: u32,
    steps_rejected: u32,
    newton_iterations: u32,
    min_det_ratio: f64,
) -> Solution<N> {
    let (error_estimate, det) = match correction(sys, &v, x) {
        Some((d, det)) => (norm(&d), det),
        None => (f64::INFINITY, det_b(sys, &v, x)),
    };
    let ratio = (det / start.det).abs();
    if status == Status::Converged && det * start.det <= 0.0 {
        status = Status::BranchChanged;
    }
    Solution {
        v,
        status,
        lambda,
        steps_accepted,
        steps_rejected,
        newton_iterations,
        error_estimate,
        min_det_ratio: min_det_ratio.min(ratio),
    }
}
