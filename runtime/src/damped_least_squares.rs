//! The damped least-squares step of Levenberg–Marquardt, by orthogonal factorisation: the
//! Jacobian's Householder QR once per iteration, then for each damping the diagonal rows
//! folded into R by Givens rotations (Moré's `qrsolv`). Never the normal equations JᵀJ, which
//! square the Jacobian's condition: a SCARA's tool a hundred millimetres down a unit-long
//! quill axis gives J a condition near 1e5, and JᵀJ's 1e10 left the steps too inaccurate to
//! take the inputs within 1e-9 of the scale of a pose the forward solver had placed.

use crate::householder::reflect_column;
use crate::math::sqrt;

/// R and Qᵀb of `a` = QR (a is N × Z; R is Z × Z, its rows past N zero).
pub(crate) struct DampedLeastSquares<const Z: usize> {
    r: [[f64; Z]; Z],
    qtb: [f64; Z],
}

impl<const Z: usize> DampedLeastSquares<Z> {
    /// Factorises `a` (Householder reflections, column by column: [`reflect_column`]) and
    /// applies the same reflections to `b`. A column already zero below its diagonal is left
    /// as it is.
    pub(crate) fn new<const N: usize>(mut a: [[f64; Z]; N], mut b: [f64; N]) -> Self {
        for k in 0..Z.min(N) {
            reflect_column(&mut a, &mut b, k);
        }
        let mut r = [[0.0; Z]; Z];
        let mut qtb = [0.0; Z];
        for k in 0..Z {
            if k >= N {
                break;
            }
            for c in k..Z {
                r[k][c] = a[k][c];
            }
            qtb[k] = b[k];
        }
        DampedLeastSquares { r, qtb }
    }

    /// The d minimising ‖a d − b‖² + Σ (damping_p d_p)²: the rows damping_p e_p appended under
    /// R and rotated into it one by one, then back-substitution. `None` where a diagonal of the
    /// result is zero (no damping on a column a has none of) or d is not finite.
    pub(crate) fn solve(&self, damping: &[f64; Z]) -> Option<[f64; Z]> {
        let (mut r, mut b) = (self.r, self.qtb);
        for j in 0..Z {
            if damping[j] == 0.0 {
                continue;
            }
            let mut row = [0.0; Z];
            row[j] = damping[j];
            let mut beta = 0.0;
            for k in j..Z {
                if row[k] == 0.0 {
                    continue;
                }
                let (c, s) = rotation(r[k][k], row[k]);
                for q in k..Z {
                    let (top, bottom) = (r[k][q], row[q]);
                    r[k][q] = c * top + s * bottom;
                    row[q] = c * bottom - s * top;
                }
                let top = b[k];
                b[k] = c * top + s * beta;
                beta = c * beta - s * top;
            }
        }
        let mut d = [0.0; Z];
        for k in (0..Z).rev() {
            if r[k][k] == 0.0 {
                return None;
            }
            let tail: f64 = (k + 1..Z).map(|q| r[k][q] * d[q]).sum();
            d[k] = (b[k] - tail) / r[k][k];
        }
        d.iter().all(|x| x.is_finite()).then_some(d)
    }
}

/// The Givens rotation (c, s) with −s·a + c·b = 0, computed without overflow.
fn rotation(a: f64, b: f64) -> (f64, f64) {
    if b.abs() > a.abs() {
        let t = a / b;
        let s = 1.0 / sqrt(1.0 + t * t);
        (s * t, s)
    } else {
        let t = b / a;
        let c = 1.0 / sqrt(1.0 + t * t);
        (c, c * t)
    }
}

#[cfg(test)]
mod tests {
    use super::DampedLeastSquares;

    /// Against the damped normal equations written out, on a small well-conditioned problem.
    #[test]
    fn matches_the_damped_normal_equations() {
        let a = [[2.0, -1.0], [0.5, 3.0], [1.0, 1.0], [0.0, -2.0]];
        let b = [1.0, -2.0, 0.5, 4.0];
        let damping = [0.3, 1.7];
        let d = DampedLeastSquares::<2>::new(a, b).solve(&damping).unwrap();
        // (AᵀA + D²) d = Aᵀb, by Cramer's rule.
        let mut h = [[0.0; 2]; 2];
        let mut g = [0.0; 2];
        for r in 0..4 {
            for p in 0..2 {
                g[p] += a[r][p] * b[r];
                for q in 0..2 {
                    h[p][q] += a[r][p] * a[r][q];
                }
            }
        }
        h[0][0] += damping[0] * damping[0];
        h[1][1] += damping[1] * damping[1];
        let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
        let want = [
            (g[0] * h[1][1] - h[0][1] * g[1]) / det,
            (h[0][0] * g[1] - h[1][0] * g[0]) / det,
        ];
        assert!(
            (d[0] - want[0]).abs() < 1e-14 && (d[1] - want[1]).abs() < 1e-14,
            "{d:?} vs {want:?}"
        );
    }

    /// Undamped, on a consistent system whose columns differ by 1e6 in scale: the exact answer
    /// to rounding (the normal equations would lose twelve digits).
    #[test]
    fn solves_an_ill_conditioned_consistent_system_to_rounding() {
        let a = [[1e3, 1e-3], [1e3, 2e-3], [0.0, 1e-3]];
        let x = [0.25, -4.0];
        let b = core::array::from_fn(|r| a[r][0] * x[0] + a[r][1] * x[1]);
        let d = DampedLeastSquares::<2>::new(a, b).solve(&[0.0; 2]).unwrap();
        assert!(
            (d[0] - x[0]).abs() < 1e-14 && (d[1] - x[1]).abs() < 1e-11,
            "{d:?}"
        );
    }

    /// A zero column with no damping has no answer; damped, it gets 0.
    #[test]
    fn a_zero_column_needs_damping() {
        let a = [[1.0, 0.0], [2.0, 0.0], [0.0, 0.0]];
        let b = [1.0, 2.0, 3.0];
        let ls = DampedLeastSquares::<2>::new(a, b);
        assert!(ls.solve(&[0.0; 2]).is_none());
        let d = ls.solve(&[0.0, 1.0]).unwrap();
        assert!((d[0] - 1.0).abs() < 1e-15 && d[1] == 0.0, "{d:?}");
    }
}
