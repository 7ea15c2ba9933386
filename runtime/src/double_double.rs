//! Double-double arithmetic: a number as the unevaluated sum of two `f64`s, about 32 significant
//! digits. The generated `residual_in` run on it evaluates F to far below the rounding of its
//! `f64` evaluation, so that B⁻¹F then measures how far a point is from the root of the `f64`
//! equations, where the `f64` residual shows only its own rounding (`crate::floor`).
//!
//! Error-free transformations: `two_sum` (Knuth) and `two_prod` by Dekker's splitting (no
//! fused multiply-add: the x86-64 baseline has none, and a software one costs more). Not for
//! values near overflow: a factor of about 1e300 or a product of about 1e154 may come out
//! infinite or NaN, which the callers treat as "cannot tell".

use core::ops::{Add, Mul, Neg, Sub};

/// `hi + lo` with |lo| at most half a unit in the last place of `hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DoubleDouble {
    hi: f64,
    lo: f64,
}

/// `a + b = s + e` exactly, `s` the rounded sum.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a = hi + lo` with each half of 26 significant bits (Dekker's splitting), so that
/// products of halves are exact.
#[inline]
fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2²⁷ + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

/// `a · b = p + e` exactly (barring underflow and overflow), `p` the rounded product.
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl DoubleDouble {
    /// The value rounded to the nearest `f64`.
    pub(crate) fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    fn renormalised(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = two_sum(s, e + t);
        Self::renormalised(s, e + f)
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + -o
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        let (p, e) = two_prod(self.hi, o.hi);
        Self::renormalised(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl crate::Scalar for DoubleDouble {
    fn from_f64(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }
    fn sq(self) -> Self {
        self * self
    }
    /// The `f64` sine of the leading part: the `f64` residual uses the same rounded value, so
    /// the two evaluate the same equations (sines and cosines enter F only through the inputs,
    /// as coefficients).
    fn sin(self) -> Self {
        Self::from_f64(crate::math::sin(self.hi))
    }
    /// As [`Self::sin`].
    fn cos(self) -> Self {
        Self::from_f64(crate::math::cos(self.hi))
    }
}

#[cfg(test)]
mod tests {
    use super::DoubleDouble;
    use crate::Scalar;

    fn dd(x: f64) -> DoubleDouble {
        DoubleDouble::from_f64(x)
    }

    #[test]
    fn sums_and_products_keep_what_f64_rounds_away() {
        // (1 + 2⁻⁶⁰) − 1 is 0 in f64 and 2⁻⁶⁰ here.
        let tiny = 2f64.powi(-60);
        assert_eq!(((dd(1.0) + dd(tiny)) - dd(1.0)).to_f64(), tiny);
        // (1 + 2⁻³⁰)² − 1 − 2⁻²⁹ = 2⁻⁶⁰ exactly; f64 loses it.
        let a = 1.0 + 2f64.powi(-30);
        let f64_way = a * a - 1.0 - 2f64.powi(-29);
        assert_eq!(f64_way, 0.0);
        let dd_way = dd(a) * dd(a) - dd(1.0) - dd(2f64.powi(-29));
        assert_eq!(dd_way.to_f64(), tiny);
        assert_eq!((-dd(3.0)).to_f64(), -3.0);
        assert_eq!(dd(0.5).sq().to_f64(), 0.25);
    }
}
