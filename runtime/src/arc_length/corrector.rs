//! The corrector: from a predicted point back onto the path, on `[H; t·(y − y_pred)] = 0`
//! (Keller's constraint, Eq. 8 as corrected in ERRATA.md), or on H at fixed μ for the last
//! step, under the [`Contraction`] test.

use super::bordered::{DenseFrame, Frame};
use super::path::{Path, Point, Tangent, dot};
use crate::convergence::Contraction;
use crate::correction::correction_in;
use crate::lu::Extended;
use crate::mechanism::Mechanism;

/// Most corrections of one step.
const MAX_CORRECTOR: usize = 5;

/// A corrected point and what it took.
pub(super) struct Corrected<const N: usize> {
    pub point: Point<N>,
    pub iterations: u32,
    /// The size of the first correction: the predictor's error, for the step control.
    pub first: f64,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    /// Corrects `pred`, predicted by a step of length `step`, on `[H; t·(y − pred)] = 0` (or on
    /// H at fixed μ), under the [`Contraction`] test. The iteration is the chord method of
    /// Eq. 11: the matrix is the one factored at the last accepted point, by the generated
    /// factorisation (`frame`) or densely (`dense`, the bordered matrix with the row `t`). Full
    /// Newton would contract fast onto a neighbouring sheet of the solution curve from a long
    /// step (seen with `Linear::Dense`: a false fold); the chord's rate grows with the step, so
    /// the contraction test refuses such steps. Only the last step at fixed μ without a frame
    /// is corrected by Newton on B. `Err` holds the iterations spent on a corrector that failed.
    pub fn correct(
        &self,
        pred: &Point<N>,
        t: &Tangent<N>,
        fixed_mu: bool,
        step: f64,
        frame: Option<&Frame<S::Factor, N>>,
        dense: Option<&DenseFrame<N>>,
    ) -> Result<Corrected<N>, u32> {
        let mut p = *pred;
        let tol = self.tolerance(step);
        let mut contraction = Contraction::new(step, tol);
        let mut first = 0.0;
        for k in 0..MAX_CORRECTOR {
            let its = k as u32 + 1;
            let g = dot(&t.v, &p.v) - dot(&t.v, &pred.v) + t.mu * (p.mu - pred.mu);
            let d = match (frame, fixed_mu) {
                (Some(fr), true) => {
                    let mut d = self.residual(&p);
                    self.sys.solve(&fr.factor, &mut d);
                    Some(Extended { head: d, tail: 0.0 })
                }
                (Some(fr), false) => self.border(fr, t, self.residual(&p), g),
                (None, true) => correction_in(
                    self.sys,
                    &p.v,
                    &self.x(p.mu),
                    self.linear,
                    &mut self.sys.new_factor(),
                )
                .ok()
                .map(|c| Extended {
                    head: c.delta,
                    tail: 0.0,
                }),
                (None, false) => dense.map(|lu| {
                    let mut rhs = Extended {
                        head: self.residual(&p),
                        tail: g,
                    };
                    lu.solve(&mut rhs);
                    rhs
                }),
            };
            let Some(d) = d else {
                return Err(its);
            };
            let size = crate::math::sqrt(dot(&d.head, &d.head) + d.tail * d.tail);
            if !size.is_finite() {
                return Err(its);
            }
            for i in 0..N {
                p.v[i] -= d.head[i];
            }
            p.mu -= d.tail;
            if k == 0 {
                first = size;
            }
            // The contraction test before the tolerance: a last correction within the tolerance
            // but barely smaller than the one before leaves the point about as far again from
            // the curve (seen: corrections 0.065, 0.039 under a tolerance of 0.051 left the point
            // 0.087 off; every later step, however short, measured that error against its own
            // length and was refused, and PH ended `StepTooSmall` 2e-6 short of λ = 1). The
            // first correction's bound includes the tolerance, so one within it always passes.
            if !contraction.admits(size) {
                return Err(its);
            }
            if size <= tol {
                return Ok(Corrected {
                    point: p,
                    iterations: its,
                    first,
                });
            }
        }
        Err(MAX_CORRECTOR as u32)
    }
}
