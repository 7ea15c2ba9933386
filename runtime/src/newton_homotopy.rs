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
    let mut lambda = 0.0;
    let nominal = 1.0 / options.homotopy_steps as f64;
    let mut step = nominal;
    let (mut accepted, mut rejected, mut iterations) = (0u32, 0u32, 0u32);
    let mut min_ratio = 1.0f64;
    let at = |l: f64| -> [f64; M] {
        let mut x = [0.0; M];
        for j in 0..M {
            x[j] = start.x[j] + l * (target[j] - start.x[j]);
        }
        x
    };
    loop {
        if accepted + rejected >= options.max_steps {
            let x = at(lambda);
            let status = not_converged(sys, &v, &x);
            return Ok(finish(
                sys,
                start,
                v,
                &x,
                status,
                Account {
                    lambda,
                    accepted,
                    rejected,
                    iterations,
                    min_det_ratio: min_ratio,
                },
            ));
        }
        let next = (lambda + step).min(1.0);
        let x = at(next);
        let run = crate::start::newton(sys, v, &x, options);
        iterations += run.iterations;
        if run.converged {
            accepted += 1;
            v = run.v;
            lambda = next;
            min_ratio = min_ratio.min((run.det / start.det).abs());
            if lambda >= 1.0 {
                return Ok(conclude(
                    sys,
                    start,
                    &run,
                    &x,
                    Account {
                        lambda: 1.0,
                        accepted,
                        rejected,
                        iterations,
                        min_det_ratio: min_ratio,
                    },
                ));
            }
            step = (step * 2.0).min(nominal);
        } else {
            rejected += 1;
            step *= 0.5;
            if step < 1e-6 {
                let status = if run.singular {
                    Status::Singular { lambda }
                } else {
                    Status::StepTooSmall { lambda }
                };
                let x = at(lambda);
                return Ok(finish(
                    sys,
                    start,
                    v,
                    &x,
                    status,
                    Account {
                        lambda,
                        accepted,
                        rejected,
                        iterations,
                        min_det_ratio: min_ratio,
                    },
                ));
            }
        }
    }
}
