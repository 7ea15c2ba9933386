//! A fit's inputs polished: Gauss–Newton on the distance from the given platform to where the
//! inputs place it, each placement by Newton on F(·, x) = 0 over every unknown.

use super::levenberg_marquardt::{Solver, off_by};
use crate::damped_least_squares::DampedLeastSquares;
use crate::lu::Lu;
use crate::mechanism::Mechanism;

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize> Solver<'_, S, N, M, Z> {
    /// The unknowns where the inputs `x` place the mechanism: Newton on F(·, x) = 0 over every
    /// unknown from `v`; `None` where B is singular or Newton does not settle.
    fn placed(&self, v: &[f64; N], x: &[f64; M]) -> Option<([f64; N], Lu<N>)> {
        let mut w = *v;
        let mut f = [0.0; N];
        for _ in 0..8 {
            self.sys.residual(&w, x, &mut f);
            let mut b = [[0.0; N]; N];
            self.sys.jacobian_dense(&w, x, &mut b);
            let lu = Lu::<N>::new(b)?;
            let mut d = f;
            lu.solve(&mut d);
            let mut step = 0.0f64;
            for i in 0..N {
                w[i] -= d[i];
                step = step.max(d[i].abs());
            }
            if !step.is_finite() {
                return None;
            }
            if step <= 1e-14 * (1.0 + w.iter().fold(0.0f64, |m, q| m.max(q.abs()))) {
                return Some((w, lu));
            }
        }
        None
    }

    /// How far the platform at v is from where inputs place it, after Gauss–Newton on that
    /// distance from `x` (which it updates to the best inputs found): the largest move of a
    /// platform coordinate from v to where the inputs place it, or what is left of the
    /// equations there if more ([`off_by`]). Infinite where B is singular.
    ///
    /// Where v is off the motion by the forward solver's tolerance, the least-squares fit of
    /// the equations spreads that over the links between and the inputs alike: a SCARA's
    /// tool 6.7e-9 mm off gave inputs that placed it 1.4e-6 mm away, and left the quill's
    /// rigidity (equations left out as dependent) 1.05e-7 mm off. Whether the inputs place the
    /// platform at v is what an answer must hold, and what this measures and minimises.
    pub(super) fn polish(&self, v: &[f64; N], x: &mut [f64; M]) -> f64 {
        let held = self.held.min(N);
        let mut best = f64::INFINITY;
        let mut best_x = *x;
        let mut trial = *x;
        for _ in 0..4 {
            let Some((w, lu)) = self.placed(v, &trial) else {
                break;
            };
            let mut f = [0.0; N];
            self.sys.residual(&w, &trial, &mut f);
            let moved = (0..held).fold(0.0f64, |m, i| m.max((w[i] - v[i]).abs()));
            let off = moved.max(off_by(self.sys, &w, &trial, &f));
            if !(off < best) {
                break;
            }
            (best, best_x) = (off, trial);
            // The platform's motion by the inputs, −B⁻¹ ∂F/∂x, and the inputs' step that
            // moves it onto v in least squares.
            let mut a = [[0.0; M]; N];
            self.sys.input_jacobian(&w, &trial, &mut a);
            let mut s = [[0.0; M]; N];
            for j in 0..M {
                let mut column: [f64; N] = core::array::from_fn(|i| a[i][j]);
                lu.solve(&mut column);
                for i in 0..held {
                    s[i][j] = column[i];
                }
            }
            let mut b = [0.0; N];
            for i in 0..held {
                b[i] = w[i] - v[i];
            }
            let Some(d) = DampedLeastSquares::<M>::new(s, b).solve(&[0.0; M]) else {
                break;
            };
            for j in 0..M {
                trial[j] += d[j];
            }
        }
        *x = best_x;
        best
    }
}
