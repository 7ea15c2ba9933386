//! Truncated Taylor series in one variable over [`Complex`]: evaluating the generated
//! `residual_in` on them gives the Taylor coefficients of `F(v(h), p(h))` along a path, which the
//! predictor needs (Taylor-mode automatic differentiation, as in HomotopyContinuation.jl).

use super::complex::Complex;
use core::ops::{Add, Mul, Neg, Sub};

/// `c[0] + c[1] h + … + c[K−1] h^(K−1)`, arithmetic modulo `h^K`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Series<const K: usize>(pub [Complex; K]);

impl<const K: usize> Series<K> {
    /// The zero series.
    pub const ZERO: Self = Series([Complex::ZERO; K]);

    /// The constant series `c`.
    #[inline(always)]
    pub fn constant(c: Complex) -> Self {
        let mut s = Self::ZERO;
        s.0[0] = c;
        s
    }

    /// Whether every coefficient but the first is zero.
    #[inline(always)]
    pub fn is_constant(&self) -> bool {
        self.0[1..].iter().all(|c| c.re == 0.0 && c.im == 0.0)
    }

    /// `1 / self` (the first coefficient must not be zero).
    pub fn recip(self) -> Self {
        let mut r = Self::ZERO;
        if K == 0 {
            return r;
        }
        let inv = self.0[0].recip();
        r.0[0] = inv;
        for k in 1..K {
            let mut s = Complex::ZERO;
            for j in 1..=k {
                s += self.0[j] * r.0[k - j];
            }
            r.0[k] = -(s * inv);
        }
        r
    }

    /// Every coefficient times `c`.
    #[inline(always)]
    pub fn times(self, c: Complex) -> Self {
        // The generated code's constants are real: half the products.
        if c.im == 0.0 {
            return Series(self.0.map(|x| x.scale(c.re)));
        }
        Series(self.0.map(|x| x * c))
    }
}

// The arithmetic is out of line in builds with debug assertions (the dev and test profiles): a
// generated `residual_in` has hundreds of operations, and each written out (a product's
// constant checks and both products, a sum's K complex additions through memory) made the
// series kernels of every declared mechanism the largest part of a crate's optimised IR (18 %
// of the integration tests', for three orders of series; BENCHMARKS.md). Release builds inline
// it: out of line, an all-modes query of the general 6-6 platform took 11.5 % more
// instructions. The results are the same bit for bit either way.
impl<const K: usize> Add for Series<K> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(self, o: Self) -> Self {
        let mut r = self;
        for k in 0..K {
            r.0[k] += o.0[k];
        }
        r
    }
}

impl<const K: usize> Sub for Series<K> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(self, o: Self) -> Self {
        let mut r = self;
        for k in 0..K {
            r.0[k] -= o.0[k];
        }
        r
    }
}

impl<const K: usize> Neg for Series<K> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn neg(self) -> Self {
        let mut r = self;
        for k in 0..K {
            r.0[k] = -r.0[k];
        }
        r
    }
}

impl<const K: usize> Mul for Series<K> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(self, o: Self) -> Self {
        // The generated code multiplies by many constants: K products instead of K(K+1)/2.
        if o.is_constant() {
            return self.times(o.0[0]);
        }
        if self.is_constant() {
            return o.times(self.0[0]);
        }
        let mut r = Self::ZERO;
        for i in 0..K {
            for j in 0..K - i {
                r.0[i + j] += self.0[i] * o.0[j];
            }
        }
        r
    }
}

impl<const K: usize> crate::scalar::Scalar for Series<K> {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Self::constant(Complex::real(x))
    }

    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sq(self) -> Self {
        if self.is_constant() {
            return Self::constant(self.0[0].sq());
        }
        // Each cross product once, doubled.
        let mut r = Self::ZERO;
        for k in 0..K {
            let mut s = Complex::ZERO;
            for i in 0..k.div_ceil(2) {
                s += self.0[i] * self.0[k - i];
            }
            s = s.scale(2.0);
            if k % 2 == 0 {
                s += self.0[k / 2].sq();
            }
            r.0[k] = s;
        }
        r
    }

    fn sin(self) -> Self {
        sin_cos(self).0
    }

    fn cos(self) -> Self {
        sin_cos(self).1
    }
}

/// sin and cos of a series by the recurrences s' = c·a', c' = −s·a'.
fn sin_cos<const K: usize>(a: Series<K>) -> (Series<K>, Series<K>) {
    let mut s = Series::<K>::ZERO;
    let mut c = Series::<K>::ZERO;
    if K == 0 {
        return (s, c);
    }
    (s.0[0], c.0[0]) = a.0[0].sin_cos();
    for k in 1..K {
        let (mut sk, mut ck) = (Complex::ZERO, Complex::ZERO);
        for j in 1..=k {
            let ja = a.0[j].scale(j as f64);
            sk += ja * c.0[k - j];
            ck -= ja * s.0[k - j];
        }
        s.0[k] = sk.scale(1.0 / k as f64);
        c.0[k] = ck.scale(1.0 / k as f64);
    }
    (s, c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Scalar;

    #[test]
    fn coefficients_of_products_and_sines() {
        // (1 + h)² = 1 + 2h + h².
        let a = Series::<4>([Complex::ONE, Complex::ONE, Complex::ZERO, Complex::ZERO]);
        let p = a.sq();
        assert_eq!(p.0[1], Complex::real(2.0));
        assert_eq!(p.0[2], Complex::ONE);
        assert_eq!(p.0[3], Complex::ZERO);
        // sin(h) = h − h³/6.
        let h = Series::<4>([Complex::ZERO, Complex::ONE, Complex::ZERO, Complex::ZERO]);
        let s = h.sin();
        assert!((s.0[1] - Complex::ONE).abs() < 1e-15);
        assert!((s.0[3] - Complex::real(-1.0 / 6.0)).abs() < 1e-15);
        let c = h.cos();
        assert!((c.0[2] - Complex::real(-0.5)).abs() < 1e-15);
    }
}
