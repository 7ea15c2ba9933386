//! How every solve's [`Solution`] is assembled, and the one place that may call it
//! [`Status::Converged`]: a final Newton run whose returned point is finite, whose own
//! correction is within the tolerance, where det B has the start's sign, where the equations
//! left out as dependent at home hold, and where rounding lets the correction vouch for the
//! tolerance (`crate::floor`).

use crate::correction::{correction, det_b};
use crate::floor::{Floor, Vouched, vouch};
use crate::math::{norm, size, squares};
use crate::mechanism::Mechanism;
use crate::newton::{Ending, Newton};
use crate::solution::{Solution, Status};
use crate::start::Start;

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
    /// Nothing done yet, at λ.
    pub(crate) fn at(lambda: f64) -> Self {
        Account {
            lambda,
            accepted: 0,
            rejected: 0,
            iterations: 0,
            min_det_ratio: 1.0,
        }
    }

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

/// The solution after a final Newton run (`Rule::Final`) at the target `x`, run to
/// `tolerance`; `predicted`: whether the answer's rounding floor is measured only where
/// predicted near the tolerance (NR, whose whole cost is a few Newton corrections), or always
/// (the solvers whose answers cost a path anyway).
// Inlined into each solver: out of line, every solve paid a call, a frame and a copy of the
// `Solution` through memory (`count nr-normal` 705 305 against 694 997).
#[inline(always)]
pub(crate) fn conclude<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    run: &Newton<N>,
    x: &[f64; M],
    tolerance: f64,
    predicted: bool,
    account: Account,
) -> Solution<N> {
    let lambda = account.lambda;
    let status = match run.ending {
        Ending::Converged | Ending::Stalled => {
            // `run.det` and `run.estimate` were measured at `run.v` itself (or, where a chord
            // correction measured it, with B factored so near that it stands for it).
            // Σv² once, for this check and the floor's prediction; where it overflows, the
            // size (rescaled) tells whether v is finite.
            let squares = squares(&run.v);
            let finite =
                (squares.is_finite() || size(&run.v).is_finite()) && run.estimate.is_finite();
            let stalled = run.ending == Ending::Stalled;
            if !finite {
                not_converged(sys, &run.v, x)
            } else if !(run.det * start.det() > 0.0 && holds_dependent(sys, &run.v, x)) {
                if stalled {
                    Status::ToleranceNotMet {
                        achieved: run.estimate,
                    }
                } else {
                    Status::BranchChanged
                }
            } else {
                // Within the tolerance by its correction, or stalled at the rounding floor
                // above it: near that floor the correction is measured again with an accurate
                // residual (and the point refined by it), which a stall always is.
                let floor = if predicted && !stalled {
                    start.floor()
                } else {
                    &Floor::ALWAYS
                };
                match vouch(
                    sys,
                    floor,
                    (&run.v, x),
                    squares,
                    run.det,
                    run.estimate,
                    tolerance,
                ) {
                    Vouched::Within(_) => Status::Converged,
                    measured => return remeasured(start, run, measured, account),
                }
            }
        }
        Ending::Singular => Status::Singular { lambda },
        Ending::NonFinite | Ending::Exhausted => not_converged(sys, &run.v, x),
    };
    if matches!(run.ending, Ending::Converged | Ending::Stalled) {
        let ratio = (run.det / start.det()).abs();
        return account.into_solution(run.v, status, run.estimate, ratio);
    }
    finish(sys, start, run.v, x, status, account)
}

/// The solution of a final run whose answer [`vouch`] measured with an accurate residual:
/// converged at the refined point, or short of the tolerance by what that measured (by the
/// run's own figure for a stall where nothing could be measured).
#[cold]
fn remeasured<const N: usize, const M: usize>(
    start: &Start<N, M>,
    run: &Newton<N>,
    measured: Vouched<N>,
    account: Account,
) -> Solution<N> {
    let ratio = (run.det / start.det()).abs();
    let (v, status, estimate) = match measured {
        Vouched::Within(e) => (run.v, Status::Converged, e),
        Vouched::Refined(v, e) => (v, Status::Converged, e),
        Vouched::Short(v, achieved) => {
            let achieved = if achieved.is_finite() || run.ending != Ending::Stalled {
                achieved
            } else {
                run.estimate
            };
            (v, Status::ToleranceNotMet { achieved }, achieved)
        }
    };
    account.into_solution(v, status, estimate, ratio)
}

/// Whether the equations left out as dependent at home hold at `v` (see
/// [`Mechanism::dependent_offset`]): within 1e-6 of the configuration's size. A point on the
/// start's branch meets them as closely as it meets the kept ones (to the tolerance, far
/// below); a point on another component of the square system misses them by a fraction of the
/// mechanism's size.
pub(crate) fn holds_dependent<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> bool {
    // 0 exactly where nothing was left out: then no size is computed (this is on the
    // tracker's path at every sample).
    let offset = sys.dependent_offset(v, x);
    offset == 0.0 || offset <= 1e-6 * crate::math::scale_or_one(size(v))
}

/// `sol` from a method that follows no path (NR, NH): [`Status::Converged`] becomes
/// [`Status::Unverified`], since such a method cannot establish the branch.
pub(crate) fn unverified<const N: usize>(mut sol: Solution<N>) -> Solution<N> {
    if sol.status == Status::Converged {
        sol.status = Status::Unverified;
    }
    sol
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

/// A solve that stopped short (`status` is never [`Status::Converged`]: only [`conclude`]
/// grants that): fills in the error estimate and det B at `v`.
pub(crate) fn finish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    v: [f64; N],
    x: &[f64; M],
    status: Status,
    account: Account,
) -> Solution<N> {
    let status = match status {
        Status::Converged => not_converged(sys, &v, x),
        other => other,
    };
    let (error_estimate, det) = match correction(sys, &v, x) {
        Ok(c) => (c.size, c.det),
        Err(_) => (f64::INFINITY, det_b(sys, &v, x)),
    };
    let ratio = (det / start.det()).abs();
    account.into_solution(v, status, error_estimate, ratio)
}
