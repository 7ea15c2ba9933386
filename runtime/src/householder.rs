//! The Householder reflection of one column, the step both of the runtime's least-squares
//! solves are made of (the platform twist's inverse in `velocity`, the damped steps of the
//! numerical inverse): orthogonal, so the conditioning of the matrix is not squared as it is by
//! the normal equations.

use crate::math::sqrt;

/// Reflects rows `k..N` of `a` (columns `k..Z`) and of `b` so that column `k` becomes zero
/// below its diagonal. Returns the norm of that part of the column as it was; a column whose
/// norm is zero or not finite is left as it is.
#[inline(always)]
pub(crate) fn reflect_column<const Z: usize, const N: usize>(
    a: &mut [[f64; Z]; N],
    b: &mut [f64; N],
    k: usize,
) -> f64 {
    if k >= Z || k >= N {
        return 0.0;
    }
    let norm = sqrt((k..N).map(|r| a[r][k] * a[r][k]).sum::<f64>());
    if !(norm > 0.0) || !norm.is_finite() {
        return norm;
    }
    let alpha = if a[k][k] > 0.0 { -norm } else { norm };
    // h = x − α e₁, applied as I − 2 h hᵀ / (hᵀh); hᵀh = 2 (norm² − α x₁) > 0.
    let mut h = [0.0; N];
    for r in k..N {
        h[r] = a[r][k];
    }
    h[k] -= alpha;
    let hh: f64 = (k..N).map(|r| h[r] * h[r]).sum();
    for c in k..Z {
        let s = 2.0 * (k..N).map(|r| h[r] * a[r][c]).sum::<f64>() / hh;
        for r in k..N {
            a[r][c] -= s * h[r];
        }
    }
    let s = 2.0 * (k..N).map(|r| h[r] * b[r]).sum::<f64>() / hh;
    for r in k..N {
        b[r] -= s * h[r];
    }
    norm
}
