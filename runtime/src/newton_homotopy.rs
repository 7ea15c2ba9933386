//! Newton homotopy (the paper's NH): λ goes from 0 to 1 in uniform steps along the straight
//! joint-space segment, each step corrected by Newton's method at fixed λ. A step whose Newton
//! iteration fails is halved. It follows the start's branch while steps are small compared with
//! the distance to a singularity, and it cannot pass a fold — but nothing shows when a step
//! was not small enough (it may jump across a fold to another assembly mode of the same det B
//! sign), so a converged result is [`Status::Unverified`](crate::solution::Status::Unverified), never
//! `Converged`.

use crate::mechanism::Mechanism;
use crate::newton::{Ending, Rule, newton};
use crate::outcome::{Account, conclude, finish, not_converged, unverified};
use crate::solution::{Options, Solution, SolveError, Status};
use crate::start::Start;

/// Solves F(v, x*) = 0 by Newton homotopy from the start.
pub fn newton_homotopy<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, start, target, options)?;
    // Each step corrects toward the homotopy's root from the last: from a start made for
    // another geometry the first would pull wherever Newton leads.
    crate::start::check_consistent(sys, start)?;
    let mut v = *start.v();
    let nominal = 1.0 / options.homotopy_steps as f64;
    let mut step = nominal;
    let mut account = Account::at(0.0);
    // At λ = 1 the target itself: x0 + (x* − x0) may miss x* by an ulp, and near a
    // singularity that ulp moves the root (and the correction measured there) by more than the
    // tolerance.
    let at = |l: f64| -> [f64; M] {
        if l >= 1.0 {
            return *target;
        }
        core::array::from_fn(|j| start.x()[j] + l * (target[j] - start.x()[j]))
    };
    loop {
        let mut failure = None;
        if account.accepted + account.rejected >= options.max_steps {
            failure = Some(not_converged(sys, &v, &at(account.lambda)));
        } else {
            let next = (account.lambda + step).min(1.0);
            let x = at(next);
            // The last step answers, by the final rule; the others only lead there.
            let rule = if next >= 1.0 {
                Rule::Final
            } else {
                Rule::Intermediate
            };
            let run = newton(sys, v, &x, options, rule);
            account.iterations += run.iterations;
            // At the target a stall is the answer (the target itself is near a singularity);
            // a smaller step would not change it.
            if run.ending == Ending::Converged
                || (rule == Rule::Final && run.ending == Ending::Stalled)
            {
                account.accepted += 1;
                account.lambda = next;
                account.min_det_ratio = account.min_det_ratio.min((run.det / start.det()).abs());
                if rule == Rule::Final {
                    return Ok(unverified(conclude(
                        sys,
                        start,
                        &run,
                        &x,
                        options.tolerance,
                        false,
                        account,
                    )));
                }
                v = run.v;
                step = (step * 2.0).min(nominal);
            } else {
                account.rejected += 1;
                step *= 0.5;
                if step < 1e-6 {
                    let lambda = account.lambda;
                    failure = Some(if run.ending == Ending::Singular {
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
