//! The parameter path of a homotopy: `p(s) = ((1 − s) γ a + s b) / ((1 − s) γ + s)`, from
//! `p(0) = a` to `p(1) = b`.
//!
//! With γ = 1 this is the segment from a to b. A random complex γ (the "γ trick") bends it into
//! another curve of the complex line through a and b; the parameters where the family
//! degenerates (solutions meet or go to infinity) are finitely many points of that line, and
//! for all but finitely many real arguments of γ the path misses them — so a real target b,
//! which may lie on real walls of singular parameters, is still reached from a generic start
//! along a path that touches no singularity before s = 1.

use super::complex::Complex;

#[derive(Clone, Copy, Debug)]
pub(crate) struct ParameterPath<const M: usize> {
    a: [Complex; M],
    b: [Complex; M],
    gamma: Complex,
}

impl<const M: usize> ParameterPath<M> {
    pub(crate) fn new(a: [Complex; M], b: [Complex; M], gamma: Complex) -> Self {
        ParameterPath { a, b, gamma }
    }

    /// The first `K` Taylor coefficients of p at `s`, in powers of the step h.
    pub(crate) fn taylor<const K: usize>(&self, s: f64, out: &mut [[Complex; M]; K]) {
        // n(s) = (1 − s) γ a + s b and d(s) = (1 − s) γ + s are linear in s; 1 / d is a
        // geometric series in h.
        let g = self.gamma;
        let d0 = g.scale(1.0 - s) + Complex::real(s);
        let d1 = Complex::ONE - g;
        let inv = d0.recip();
        let ratio = -(d1 * inv);
        for i in 0..M {
            let n0 = (g * self.a[i]).scale(1.0 - s) + self.b[i].scale(s);
            let n1 = self.b[i] - g * self.a[i];
            // p = (n0 + n1 h) / d0 · Σ (ratio h)^j.
            let mut pow = Complex::ONE; // ratio^j
            let mut prev = Complex::ONE; // ratio^(j−1)
            for (j, row) in out.iter_mut().enumerate() {
                row[i] = if j == 0 {
                    n0 * inv
                } else {
                    (n0 * pow + n1 * prev) * inv
                };
                if j > 0 {
                    prev = pow;
                }
                pow *= ratio;
            }
        }
    }

    /// p(s).
    pub(crate) fn at(&self, s: f64) -> [Complex; M] {
        if s == 1.0 {
            return self.b;
        }
        if s == 0.0 {
            return self.a;
        }
        let mut out = [[Complex::ZERO; M]; 1];
        self.taylor(s, &mut out);
        out[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn taylor_coefficients_match_the_rational_path() {
        let path = ParameterPath::new(
            [Complex::new(1.0, 2.0), Complex::new(-0.5, 0.3)],
            [Complex::real(170.0), Complex::real(-3.0)],
            Complex::new(0.6, -0.8),
        );
        let s = 0.37;
        let mut c = [[Complex::ZERO; 2]; 4];
        path.taylor(s, &mut c);
        for h in [1e-3, -2e-3] {
            let exact = path.at(s + h);
            for i in 0..2 {
                let series =
                    c[0][i] + c[1][i].scale(h) + c[2][i].scale(h * h) + c[3][i].scale(h * h * h);
                assert!((series - exact[i]).abs() < 1e-9 * (1.0 + exact[i].abs()));
            }
        }
        assert_eq!(path.at(0.0)[0], Complex::new(1.0, 2.0));
        assert_eq!(path.at(1.0)[1], Complex::real(-3.0));
    }
}
