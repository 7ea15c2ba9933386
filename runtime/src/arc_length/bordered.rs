//! The bordered systems of Eqs. 9–10, `[[B, H_μ], [rᵀ, d]] [z; ζ] = [f; g]`: solved by
//! bordering on the generated factorisation of B while B is well conditioned, and by a dense
//! LU of the whole bordered matrix near a fold, where B is nearly singular but the bordered
//! matrix stays regular.

use super::path::{Path, Point, Tangent, dot};
use crate::lu::{Bordered, BorderedLu, Extended, Lu};
use crate::math::norm;
use crate::mechanism::Mechanism;
use crate::solution::Linear;

/// Below this pivot ratio the generated factorisation is not trusted for bordering.
const MIN_PIVOT_RATIO: f64 = 1e-10;

/// B and H_μ at an accepted point, factored: what the next corrector and tangent reuse.
pub(super) struct Frame<F, const N: usize> {
    pub factor: F,
    pub det: f64,
    /// B⁻¹ H_μ, with H_μ = (∂F/∂x)(x* − x0)/‖x* − x0‖.
    pub y2: [f64; N],
}

/// The dense bordered matrix `[[B, H_μ], [tᵀ]]` at an accepted point, factored once for every
/// corrector iteration from there (the chord iteration of Eq. 11, as with a [`Frame`]) where
/// the generated factorisation is not used.
pub(super) type DenseFrame<const N: usize> = BorderedLu<N>;

/// The unit tangent at a point, and det B there.
pub(super) struct TangentAt<const N: usize> {
    pub tangent: Tangent<N>,
    pub det: f64,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    /// The generated factorisation at `p`, if it is trustworthy for bordering.
    pub fn frame(&self, p: &Point<N>) -> Option<Frame<S::Factor, N>> {
        if self.linear == Linear::Dense {
            return None;
        }
        let mut factor = self.sys.new_factor();
        let info = self.sys.factor(&p.v, &self.x(p.mu), &mut factor)?;
        if !(info.pivot_ratio > MIN_PIVOT_RATIO) {
            return None;
        }
        let column = self.column(p);
        let mut y2 = column;
        self.sys.solve(&factor, &mut y2);
        Some(Frame {
            factor,
            det: info.det,
            y2,
        })
    }

    /// The [`DenseFrame`] at `p` with the row `t`, when there is no `frame`.
    pub fn dense_frame(
        &self,
        p: &Point<N>,
        t: &Tangent<N>,
        frame: Option<&Frame<S::Factor, N>>,
    ) -> Option<DenseFrame<N>> {
        if frame.is_some() {
            return None;
        }
        BorderedLu::new(self.bordered(p, t).1)
    }

    /// The dense bordered matrix `[[B, H_μ], [rowᵀ]]` at `p`, and H at `p`.
    pub fn bordered(&self, p: &Point<N>, row: &Tangent<N>) -> ([f64; N], Bordered<N>) {
        let x = self.x(p.mu);
        let f = self.residual(p);
        let mut m = Bordered {
            block: [[0.0; N]; N],
            column: self.column(p),
            row: row.v,
            corner: row.mu,
        };
        self.sys.jacobian_dense(&p.v, &x, &mut m.block);
        (f, m)
    }

    /// Solves `[[B, H_μ], [rᵀ, d]] [z; ζ] = [f; g]` by bordering on a frame; `None` where the
    /// bordering is ill-conditioned.
    pub fn border(
        &self,
        frame: &Frame<S::Factor, N>,
        row: &Tangent<N>,
        f: [f64; N],
        g: f64,
    ) -> Option<Extended<N>> {
        let den = row.mu - dot(&row.v, &frame.y2);
        let size = row.mu.abs() + norm(&row.v) * norm(&frame.y2);
        if !(den.abs() > 1e-10 * size) {
            return None;
        }
        let mut y1 = f;
        self.sys.solve(&frame.factor, &mut y1);
        let mu = (g - dot(&row.v, &y1)) / den;
        let mut z = y1;
        for i in 0..N {
            z[i] -= mu * frame.y2[i];
        }
        Some(Extended { head: z, tail: mu })
    }

    /// The unit tangent at `p`, oriented along `prev` (the bordered system of Eq. 9), and
    /// det B there.
    pub fn tangent(
        &self,
        p: &Point<N>,
        prev: &Tangent<N>,
        frame: Option<&Frame<S::Factor, N>>,
    ) -> Option<TangentAt<N>> {
        let (z, det) =
            match frame.and_then(|fr| self.border(fr, prev, [0.0; N], 1.0).map(|z| (z, fr.det))) {
                Some(t) => t,
                None => {
                    let (_, m) = self.bordered(p, prev);
                    let det = Lu::new(m.block).map_or(0.0, |lu| lu.det());
                    let lu = BorderedLu::new(m)?;
                    let mut z = Extended {
                        head: [0.0; N],
                        tail: 1.0,
                    };
                    lu.solve(&mut z);
                    (z, det)
                }
            };
        let nrm = crate::math::sqrt(dot(&z.head, &z.head) + z.tail * z.tail);
        if !(nrm > 0.0) || !nrm.is_finite() {
            return None;
        }
        Some(TangentAt {
            tangent: Tangent {
                v: z.head.map(|zi| zi / nrm),
                mu: z.tail / nrm,
            },
            det,
        })
    }
}
