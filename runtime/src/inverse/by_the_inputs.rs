//! The inverse as a search over the inputs alone: Levenberg–Marquardt on the distance from v
//! to where the inputs place the platform, each iterate's configuration by continuation from
//! the last one's (the forward kinematics, `arc_length`), from the declared home. For a
//! platform given by its points alone, where the links' points must otherwise be guessed:
//! every iterate is a configuration of the mechanism, so none can be a compromise between
//! equations, and no path of the platform's pose has to stay inside the workspace (a straight
//! one from a SCARA's home, at the edge of its reach, leaves it at once).

use super::levenberg_marquardt::{ACCEPT, STALL, STALLED, Solver, Work, off_by};
use crate::arc_length::arc_length;
use crate::damped_least_squares::DampedLeastSquares;
use crate::lu::Lu;
use crate::math::sqrt;
use crate::mechanism::Mechanism;
use crate::solution::{Options, Status};
use crate::start::Start;

/// Iterations over the inputs (each a forward solve).
const ITERATIONS: usize = 60;

/// Inputs placing the platform at `v`, searched from `x0` with the mechanism placed there by
/// continuation from home; `None` where the search ends short of [`ACCEPT`] of `scale`.
pub(super) fn by_the_inputs<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    solver: &Solver<'_, S, N, M, Z>,
    v: &[f64; N],
    home: (&[f64; N], &[f64; M]),
    x0: &[f64; M],
    scale: f64,
) -> Option<[f64; M]> {
    Work::add(&solver.work.runs);
    let sys = solver.sys;
    let held = solver.held.min(N);
    let options = Options::TIGHT;
    let start = Start::new(sys, *home.0, *home.1).ok()?;
    let placed = |start: &Start<N, M>, x: &[f64; M]| -> Option<[f64; N]> {
        let sol = arc_length(sys, start, x, &options).ok()?;
        (sol.status == Status::Converged).then_some(sol.v)
    };
    let mut x = *x0;
    let mut w = placed(&start, &x)?;
    let cost = |w: &[f64; N]| -> f64 { (0..held).map(|i| (v[i] - w[i]) * (v[i] - w[i])).sum() };
    let mut c = cost(&w);
    let mut mu = 1e-6f64;
    let mut before = f64::INFINITY;
    for k in 0..ITERATIONS {
        Work::add(&solver.work.iterations);
        // Placed within the acceptance, and its equations hold: the inputs are the answer.
        let moved = (0..held).fold(0.0f64, |m, i| m.max((w[i] - v[i]).abs()));
        let mut f = [0.0; N];
        sys.residual(&w, &x, &mut f);
        if moved.max(off_by(sys, &w, &x, &f)) <= ACCEPT * scale {
            return Some(x);
        }
        // Stalled short of it (the rule of the other runs, [`STALLED`]).
        if k % STALL == 0 {
            if c > STALLED * before {
                return None;
            }
            before = c;
        }
        // The platform's motion by the inputs, −B⁻¹ ∂F/∂x, and the damped step towards v.
        let mut b = [[0.0; N]; N];
        sys.jacobian_dense(&w, &x, &mut b);
        let lu = Lu::<N>::new(b)?;
        let mut a = [[0.0; M]; N];
        sys.input_jacobian(&w, &x, &mut a);
        let mut s = [[0.0; M]; N];
        for j in 0..M {
            let mut column: [f64; N] = core::array::from_fn(|i| a[i][j]);
            lu.solve(&mut column);
            for i in 0..held {
                s[i][j] = -column[i];
            }
        }
        let mut r = [0.0; N];
        for i in 0..held {
            r[i] = v[i] - w[i];
        }
        let mut size = [0.0; M];
        for row in &s {
            for j in 0..M {
                size[j] += row[j] * row[j];
            }
        }
        let least_squares = DampedLeastSquares::<M>::new(s, r);
        let here = Start::new(sys, w, x).ok()?;
        let mut accepted = false;
        while mu <= 1e12 {
            let damping = size.map(|q| sqrt(mu * (q + 1e-300)));
            Work::add(&solver.work.damped_solves);
            let Some(d) = least_squares.solve(&damping) else {
                mu *= 4.0;
                continue;
            };
            let xt: [f64; M] = core::array::from_fn(|j| x[j] + d[j]);
            if let Some(wt) = placed(&here, &xt) {
                let ct = cost(&wt);
                if ct < c {
                    (x, w, c) = (xt, wt, ct);
                    mu = (mu * 0.25).max(1e-15);
                    accepted = true;
                    break;
                }
            }
            mu *= 4.0;
        }
        if !accepted {
            return None;
        }
    }
    None
}
