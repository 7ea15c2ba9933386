//! The initial configuration every solve starts from, checked once.

use crate::lu::{factor, solve};
use crate::math::norm;
use crate::{Mechanism, SolveError};

/// A consistent, nonsingular start configuration `(v0, x0)` and the sign of det B there,
/// which marks its branch: det B keeps its sign throughout the valid joint space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start<const N: usize, const M: usize> {
    pub v: [f64; N],
    pub x: [f64; M],
    /// det B at the start.
    pub det: f64,
}

pub(crate) fn all_finite(a: &[f64]) -> bool {
    a.iter().all(|x| x.is_finite())
}

/// A Newton correction `Δ = B⁻¹ F` at `(v, x)`, with det B; `None` if B is singular.
pub(crate) fn correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<([f64; N], f64)> {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let piv = factor::<N, _>(&mut b)?;
    solve(&b, &piv, &mut f);
    if !all_finite(&f) {
        return None;
    }
    Some((f, piv.det))
}

/// det B at `(v, x)`; 0 where B is singular.
pub fn det_b<S: Mechanism<N, M>, const N: usize, const M: usize>(sys: &S, v: &[f64; N], x: &[f64; M]) -> f64 {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    factor::<N, _>(&mut b).map_or(0.0, |p| p.det)
}

impl<const N: usize, const M: usize> Start<N, M> {
    /// Checks `(v, x)`: finite, valid inputs, F(v, x) ≈ 0 (refined by Newton to full
    /// precision; `v` may be approximate) and B nonsingular.
    pub fn new<S: Mechanism<N, M>>(sys: &S, v: [f64; N], x: [f64; M]) -> Result<Self, SolveError> {
        if !all_finite(&v) || !all_finite(&x) {
            return Err(SolveError::NonFinite);
        }
        let scale = norm(&v).max(1.0);
        let mut v = v;
        for _ in 0..8 {
            let (d, _) = correction(sys, &v, &x).ok_or(SolveError::SingularStart)?;
            for i in 0..N {
                v[i] -= d[i];
            }
            if norm(&d) <= 1e-12 * scale {
                break;
            }
        }
        let mut f = [0.0; N];
        sys.residual(&v, &x, &mut f);
        let (d, det) = correction(sys, &v, &x).ok_or(SolveError::SingularStart)?;
        if norm(&d) > 1e-6 * scale {
            return Err(SolveError::InconsistentStart { residual_norm: norm(&f) });
        }
        if det == 0.0 || !det.is_finite() {
            return Err(SolveError::SingularStart);
        }
        Ok(Start { v, x, det })
    }
}
