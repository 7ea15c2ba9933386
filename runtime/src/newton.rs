//! Newton–Raphson (the paper's NRA): Newton's method on F(v, x*) = 0 from the start's v.
//! Fast, and with no notion of branch: near a singularity it may converge to another
//! assembly mode. The det B sign check catches some of those, not all.

use crate::correction::{correction, det_b};
use crate::math::norm;
use crate::start::all_finite;
use crate::{Mechanism, Options, Solution, SolveError, Start, Status};

/// Solves F(v, x) = 0 by Newton's method from `start.v`.
///
/// ```
/// use linkage::{newton_raphson, Mechanism, Options, Pose, Start, Status};
///
/// linkage::mechanism! {
///     /// A 3-RPS: three hinged legs of variable length carry a triangular platform.
///     pub struct Rps;
///     base {
///         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
///         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
///         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
///     }
///     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
///     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
///     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
///     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// }
///
/// let rps = Rps::new();
/// // Start: platform level, 150 mm up; its leg lengths from inverse kinematics.
/// let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// let start = Start::new(&rps, v0, x0).unwrap();
/// let sol = newton_raphson(&rps, &start, &[160.0, 155.0, 158.0], &Options::TIGHT).unwrap();
/// assert_eq!(sol.status, Status::Converged);
/// assert!((rps.inverse(&sol.v, &x0).unwrap()[1] - 155.0).abs() < 1e-9);
/// ```
pub fn newton_raphson<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, x, options)?;
    let run = crate::correction::newton(sys, start.v, x, options);
    Ok(conclude(
        sys,
        start,
        &run,
        x,
        Account {
            lambda: 1.0,
            accepted: 0,
            rejected: 0,
            iterations: run.iterations,
            min_det_ratio: 1.0,
        },
    ))
}

/// What a solve met on its way, for its [`Solution`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Account {
    pub lambda: f64,
    pub accepted: u32,
    pub rejected: u32,
    pub iterations: u32,
    pub min_det_ratio: f64,
}

impl Account {
    fn into_solution<const N: usize>(
        self,
        v: [f64; N],
        status: Status,
        error_estimate: f64,
        det_ratio: f64,
    ) -> Solution<N> {
        Solution {
            v,
            status,
            lambda: self.lambda,
            steps_accepted: self.accepted,
            steps_rejected: self.rejected,
            newton_iterations: self.iterations,
            error_estimate,
            min_det_ratio: self.min_det_ratio.min(det_ratio),
        }
    }
}

/// The solution after a final Newton run: its own estimate and det B when it converged,
/// re-evaluated otherwise.
pub(crate) fn conclude<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    run: &crate::correction::Newton<N>,
    x: &[f64; M],
    account: Account,
) -> Solution<N> {
    let lambda = account.lambda;
    if !run.converged {
        let status = if run.singular {
            Status::Singular { lambda }
        } else {
            not_converged(sys, &run.v, x)
        };
        let v = if all_finite(&run.v) { run.v } else { start.v };
        return finish(sys, start, v, x, status, account);
    }
    // The last factorisation was at the iterate before the last (small) correction; det B
    // cannot change sign over it unless B is singular to rounding there.
    let ratio = (run.det / start.det).abs();
    let status = if run.det * start.det > 0.0 {
        Status::Converged
    } else {
        Status::BranchChanged
    };
    account.into_solution(run.v, status, run.estimate, ratio)
}

pub(crate) fn not_converged<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Status {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    Status::NotConverged {
        residual_norm: norm(&f),
    }
}

/// Fills in the error estimate and checks the branch by the sign of det B.
pub(crate) fn finish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    v: [f64; N],
    x: &[f64; M],
    mut status: Status,
    account: Account,
) -> Solution<N> {
    let (error_estimate, det) = match correction(sys, &v, x) {
        Some((_, det, size)) => (size, det),
        None => (f64::INFINITY, det_b(sys, &v, x)),
    };
    let ratio = (det / start.det).abs();
    if status == Status::Converged && det * start.det <= 0.0 {
        status = Status::BranchChanged;
    }
    account.into_solution(v, status, error_estimate, ratio)
}
