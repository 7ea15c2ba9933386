//! Newton homotopy (the paper's NH): λ goes from 0 to 1 in uniform steps along the straight
//! joint-space segment, each step corrected by Newton's method at fixed λ. A step whose Newton
//! iteration fails is halved. It follows the start's branch while steps are small compared with
//! the distance to a singularity, and it cannot pass a fold.

use crate::math::norm;
use crate::newton::{finish, not_converged};
use crate::start::all_finite;
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
                sys, start, v, &x, status, lambda, accepted, rejected, iterations, min_ratio,
            ));
        }
        let next = (lambda + step).min(1.0);
        let x = at(next);
        let mut w = v;
        let mut converged = false;
        let mut singular = false;
        let mut det = start.det;
        let mut convergence = crate::start::Convergence::new(options.tolerance, &w);
        for _ in 0..options.max_iterations {
            iterations += 1;
            let Some((d, dt)) = crate::start::correction_with(sys, &w, &x, options.linear) else {
                singular = true;
                break;
            };
            det = dt;
            for i in 0..N {
                w[i] -= d[i];
            }
            if !all_finite(&w) {
                break;
            }
            if convergence.reached(norm(&d)) {
                converged = true;
                break;
            }
        }
        if converged {
            accepted += 1;
            v = w;
            lambda = next;
            min_ratio = min_ratio.min((det / start.det).abs());
            if lambda >= 1.0 {
                return Ok(finish(
                    sys,
                    start,
                    v,
                    &x,
                    Status::Converged,
                    1.0,
                    accepted,
                    rejected,
                    iterations,
                    min_ratio,
                ));
            }
            step = (step * 2.0).min(nominal);
        } else {
            rejected += 1;
            step *= 0.5;
            if step < 1e-6 {
                let status = if singular {
                    Status::Singular { lambda }
                } else {
                    Status::StepTooSmall { lambda }
                };
                let x = at(lambda);
                return Ok(finish(
                    sys, start, v, &x, status, lambda, accepted, rejected, iterations, min_ratio,
                ));
            }
        }
    }
}
