//! Dense complex Gaussian elimination with partial pivoting, for the small systems solved
//! while seeding (not on the query path).

use super::complex::Complex;

/// Solves `a y = b` in place (`b` becomes y, `a` is destroyed). `false` if `a` is singular to
/// working precision (a pivot below 1e-13 of the largest entry).
pub(crate) fn solve<const N: usize>(a: &mut [[Complex; N]; N], b: &mut [Complex; N]) -> bool {
    let big = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs_max()));
    if !(big > 0.0) || !big.is_finite() {
        return false;
    }
    for k in 0..N {
        // The partial pivot (the last of equal maxima, as `Iterator::max_by`), by a plain
        // loop: `p` in k..N, which the no-panic proof can see.
        let mut p = k;
        for i in k + 1..N {
            if a[i][k].abs_max().total_cmp(&a[p][k].abs_max()).is_ge() {
                p = i;
            }
        }
        if !(a[p][k].abs_max() > 1e-13 * big) {
            return false;
        }
        a.swap(k, p);
        b.swap(k, p);
        let inv = a[k][k].recip();
        for i in k + 1..N {
            let l = a[i][k] * inv;
            if l == Complex::ZERO {
                continue;
            }
            for j in k + 1..N {
                let u = a[k][j];
                a[i][j] -= l * u;
            }
            let bk = b[k];
            b[i] -= l * bk;
        }
    }
    for k in (0..N).rev() {
        let mut s = b[k];
        for j in k + 1..N {
            s -= a[k][j] * b[j];
        }
        b[k] = s / a[k][k];
    }
    true
}
