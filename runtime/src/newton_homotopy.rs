//! Newton homotopy (the paper's NH): λ goes from 0 to 1 in uniform steps along the straight
//! joint-space segment, each step corrected by Newton's method at fixed λ. A step whose Newton
//! iteration fails is halved. It follows the start's branch while steps are small compared with
//! the distance to a singularity, and it cannot pass a fold.

use crate::newton::{conclude, finish, not_converged, Account};
use crate::{Mechanism, Options, Solution, SolveError, Start, Status};

/// Solves F(v, x*) = 0 by Newton homotopy from the start.
pub fn newton_homotopy<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, target, options)?;
    let mut v = start.v;
    let nominal = 1.0 / options.homotopy_steps as f64;
    let mut step = nominal;
    let mut account = Account {
        lambda: 0.0,
        accepted: 0,
        rejected: 0,
        iterations: 0,
        min_det_ratio: 1.0,
    };
    let at = |l: f64| -> [f64; M] {
        core::array::from_fn(|j| start.x[j] + l * (target[j] - start.x[j]))
    };
    loop {
        let mut failure = None;
        if account.accepted + account.rejected >= options.max_steps {
            failure = Some(not_converged(sys, &v, &at(account.lambda)));
        } else {
            let next = (account.lambda + step).min(1.0);
            let x = at(next);
            let run = crate::correction::newton(sys, v, &x, options);
            account.iterations += run.iterations;
            if run.converged {
                account.accepted += 1;
                v = run.v;
                account.lambda = next;
                account.min_det_ratio = account.min_det_ratio.min((run.det / start.det).abs());
                if next >= 1.0 {
                    return Ok(conclude(sys, start, &run, &x, account));
                }
                step = (step * 2.0).min(nominal);
            } else {
                account.rejected += 1;
                step *= 0.5;
                if step < 1e-6 {
                    let lambda = account.lambda;
                    failure = Some(if run.singular {
                        Status::Singular { lambda }
                    } else {
                        Status::StepTooSmall { lambda }
                    });
                }
            }
        }
        if let Some(status) = failure {
            return Ok(finish(sys, start, v, &at(account.lambda), status, account));
        }
    }
}
