//! Dense LU with partial pivoting, written here so that the tests' ground truth does not lean
//! on the runtime's own factorisations (nor on the shape of its `lu` module).

/// `P A = L U` of an N×N matrix, and det A.
pub struct Lu<const N: usize> {
    a: [[f64; N]; N],
    swaps: [usize; N],
    pub det: f64,
}

impl<const N: usize> Lu<N> {
    /// Factors `a`; `None` when a pivot is zero or not finite.
    pub fn new(mut a: [[f64; N]; N]) -> Option<Self> {
        let mut swaps = [0; N];
        let mut det = 1.0;
        for k in 0..N {
            let p = (k..N).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
            if !(a[p][k].abs() > 0.0 && a[p][k].is_finite()) {
                return None;
            }
            swaps[k] = p;
            if p != k {
                a.swap(k, p);
                det = -det;
            }
            det *= a[k][k];
            for i in k + 1..N {
                let l = a[i][k] / a[k][k];
                a[i][k] = l;
                for c in k + 1..N {
                    a[i][c] -= l * a[k][c];
                }
            }
        }
        Some(Lu { a, swaps, det })
    }

    /// Solves A y = b in place.
    pub fn solve(&self, b: &mut [f64; N]) {
        for k in 0..N {
            b.swap(k, self.swaps[k]);
        }
        for i in 0..N {
            let s: f64 = (0..i).map(|c| self.a[i][c] * b[c]).sum();
            b[i] -= s;
        }
        for i in (0..N).rev() {
            let s: f64 = (i + 1..N).map(|c| self.a[i][c] * b[c]).sum();
            b[i] = (b[i] - s) / self.a[i][i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Lu;

    #[test]
    fn solves_and_signs_a_permuted_system() {
        let a = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let lu = Lu::new(a).unwrap();
        // det by cofactors: 0·(1) − 2·(1 − 0) + 1·(0 − 3) = −5.
        assert!((lu.det + 5.0).abs() < 1e-12);
        let mut b = [5.0, 3.0, 5.0];
        lu.solve(&mut b);
        for (i, row) in a.iter().enumerate() {
            let back: f64 = row.iter().zip(&b).map(|(x, y)| x * y).sum();
            assert!((back - [5.0, 3.0, 5.0][i]).abs() < 1e-12);
        }
        assert!(Lu::new([[1.0, 2.0], [2.0, 4.0]]).is_none());
    }
}
