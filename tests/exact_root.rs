//! The root of a mechanism's `f64` equations to far below `f64` rounding: Newton's method with F
//! evaluated in double-double arithmetic (the generated `residual_in`) and the correction
//! solved in `f64` (iterative refinement). The ground truth against which "within the
//! tolerance" is judged where the `f64` residual's own rounding is near the tolerance. Written
//! here (Dekker's splitting, no fused multiply-add) so that it does not lean on the runtime's
//! own double-double.

use crate::dense::Lu;
use linkage::{Mechanism, Scalar};
use std::ops::{Add, Mul, Neg, Sub};

/// `hi + lo`, about 32 significant digits. Its sums and products are out of line: written out
/// at every operation of every mechanism's `residual_in`, they cost the tests' build more than
/// the calls cost the tests.
#[derive(Clone, Copy, Debug)]
pub struct Dd(f64, f64);

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let v = s - a;
    (s, (a - (s - v)) + (b - v))
}

/// Dekker's split of `a` into two halves of 26 bits each.
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl Add for Dd {
    type Output = Dd;
    #[inline(never)]
    fn add(self, o: Dd) -> Dd {
        let (s, e) = two_sum(self.0, o.0);
        let (h, l) = two_sum(s, e + self.1 + o.1);
        Dd(h, l)
    }
}
impl Neg for Dd {
    type Output = Dd;
    fn neg(self) -> Dd {
        Dd(-self.0, -self.1)
    }
}
impl Sub for Dd {
    type Output = Dd;
    #[inline(never)]
    fn sub(self, o: Dd) -> Dd {
        self + -o
    }
}
impl Mul for Dd {
    type Output = Dd;
    #[inline(never)]
    fn mul(self, o: Dd) -> Dd {
        let (p, e) = two_prod(self.0, o.0);
        let (h, l) = two_sum(p, e + self.0 * o.1 + self.1 * o.0);
        Dd(h, l)
    }
}
impl Scalar for Dd {
    fn from_f64(x: f64) -> Dd {
        Dd(x, 0.0)
    }
    fn sq(self) -> Dd {
        self * self
    }
    // Sines and cosines enter F only through the inputs, as coefficients: the `f64` values
    // are the equations' own.
    fn sin(self) -> Dd {
        Dd(self.0.sin(), 0.0)
    }
    fn cos(self) -> Dd {
        Dd(self.0.cos(), 0.0)
    }
}

/// The root of F(·, x) = 0 (as evaluated with `f64` coefficients) that Newton's method reaches
/// from `v`, near it; `None` if B is singular there or the iteration does not settle.
pub fn exact_root<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<[f64; N]> {
    let mut w: [Dd; N] = std::array::from_fn(|i| Dd(v[i], 0.0));
    let xd: [Dd; M] = std::array::from_fn(|j| Dd(x[j], 0.0));
    for _ in 0..8 {
        let hi: [f64; N] = std::array::from_fn(|i| w[i].0);
        let mut b = [[0.0; N]; N];
        sys.jacobian_dense(&hi, x, &mut b);
        let lu = Lu::new(b)?;
        let mut f = [Dd(0.0, 0.0); N];
        sys.residual_in(&w, &xd, &mut f);
        let mut d: [f64; N] = std::array::from_fn(|i| f[i].0 + f[i].1);
        lu.solve(&mut d);
        for i in 0..N {
            w[i] = w[i] - Dd(d[i], 0.0);
        }
        let scale = hi.iter().fold(1.0f64, |m, c| m.max(c.abs()));
        if d.iter().all(|c| c.abs() <= 1e-28 * scale) {
            break;
        }
    }
    let root: [f64; N] = std::array::from_fn(|i| w[i].0 + w[i].1);
    root.iter().all(|c| c.is_finite()).then_some(root)
}

/// The Newton correction ‖B⁻¹F(v, x)‖ with F evaluated in double-double arithmetic: what the
/// solvers' error estimate stands for (a first-order distance to the root), free of the `f64`
/// residual's rounding. `None` if B is singular at `v` or a value is not finite.
pub fn exact_correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<f64> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let lu = Lu::new(b)?;
    let w: [Dd; N] = std::array::from_fn(|i| Dd(v[i], 0.0));
    let xd: [Dd; M] = std::array::from_fn(|j| Dd(x[j], 0.0));
    let mut f = [Dd(0.0, 0.0); N];
    sys.residual_in(&w, &xd, &mut f);
    let mut d: [f64; N] = std::array::from_fn(|i| f[i].0 + f[i].1);
    lu.solve(&mut d);
    let size = d.iter().map(|c| c * c).sum::<f64>().sqrt();
    size.is_finite().then_some(size)
}
