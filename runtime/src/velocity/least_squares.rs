//! A small dense least-squares solve (six rows) by Householder reflections.

/// The least-squares solution of `a` y = `b` by Householder reflections (not the normal
/// equations, which would square the condition of a platform Jacobian near a singularity).
/// `None` with more unknowns than rows or a column dependent on the others to rounding.
pub(super) fn least_squares<const M: usize>(
    mut a: [[f64; M]; 6],
    mut b: [f64; 6],
) -> Option<[f64; M]> {
    if M > 6 {
        return None;
    }
    let largest = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for k in 0..M {
        let norm = crate::math::sqrt((k..6).map(|r| a[r][k] * a[r][k]).sum::<f64>());
        if !(norm > 1e-12 * largest) {
            return None;
        }
        let alpha = if a[k][k] > 0.0 { -norm } else { norm };
        // v = x − α e₁, applied as H = I − 2 v vᵀ / (vᵀv).
        let mut h = [0.0; 6];
        for r in k..6 {
            h[r] = a[r][k];
        }
        h[k] -= alpha;
        let hh: f64 = (k..6).map(|r| h[r] * h[r]).sum();
        for c in k..M {
            let s = 2.0 * (k..6).map(|r| h[r] * a[r][c]).sum::<f64>() / hh;
            for r in k..6 {
                a[r][c] -= s * h[r];
            }
        }
        let s = 2.0 * (k..6).map(|r| h[r] * b[r]).sum::<f64>() / hh;
        for r in k..6 {
            b[r] -= s * h[r];
        }
    }
    let mut y = [0.0; M];
    for k in (0..M).rev() {
        let tail: f64 = (k + 1..M).map(|c| a[k][c] * y[c]).sum();
        y[k] = (b[k] - tail) / a[k][k];
    }
    y.iter().all(|c| c.is_finite()).then_some(y)
}
