//! The initial configuration every solve starts from, checked once.

use crate::correction::correction;
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

/// Rejects non-finite or out-of-range targets and invalid options before any work.
pub(crate) fn check_target<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    x: &[f64; M],
    options: &crate::Options,
) -> Result<(), SolveError> {
    if !all_finite(x) || !options.is_valid() {
        return Err(SolveError::NonFinite);
    }
    sys.validate_inputs(x)
        .map_err(|input| SolveError::InvalidInput { input })
}

impl<const N: usize, const M: usize> Start<N, M> {
    /// Checks `(v, x)`: finite, valid inputs, F(v, x) ≈ 0 (refined by Newton to full
    /// precision; `v` may be approximate) and B nonsingular.
    pub fn new<S: Mechanism<N, M>>(sys: &S, v: [f64; N], x: [f64; M]) -> Result<Self, SolveError> {
        if !all_finite(&v) || !all_finite(&x) {
            return Err(SolveError::NonFinite);
        }
        sys.validate_inputs(&x)
            .map_err(|input| SolveError::InvalidInput { input })?;
        let scale = norm(&v).max(1.0);
        let given = v;
        let mut v = v;
        for _ in 0..8 {
            let (d, _, _) = correction(sys, &v, &x).ok_or(SolveError::SingularStart)?;
            for i in 0..N {
                v[i] -= d[i];
            }
            if norm(&d) <= 1e-12 * scale {
                break;
            }
        }
        let mut f = [0.0; N];
        sys.residual(&v, &x, &mut f);
        let (d, det, _) = correction(sys, &v, &x).ok_or(SolveError::SingularStart)?;
        // Refinement may polish rounding, not move the start: a large move could land on
        // another assembly mode.
        let mut moved = [0.0; N];
        for i in 0..N {
            moved[i] = v[i] - given[i];
        }
        if norm(&d) > 1e-6 * scale || norm(&moved) > 1e-3 * scale {
            let mut f0 = [0.0; N];
            sys.residual(&given, &x, &mut f0);
            return Err(SolveError::InconsistentStart {
                residual_norm: norm(&f0),
            });
        }
        if det == 0.0 || !det.is_finite() {
            return Err(SolveError::SingularStart);
        }
        Ok(Start { v, x, det })
    }
}
