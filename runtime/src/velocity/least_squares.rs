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
        if !(crate::householder::reflect_column(&mut a, &mut b, k) > 1e-12 * largest) {
            return None;
        }
    }
    let mut y = [0.0; M];
    for k in (0..M).rev() {
        let tail: f64 = (k + 1..M).map(|c| a[k][c] * y[c]).sum();
        y[k] = (b[k] - tail) / a[k][k];
    }
    y.iter().all(|c| c.is_finite()).then_some(y)
}
