//! Double-double arithmetic: a number as the unevaluated sum of two `f64`s, about 32 significant
//! digits, by Dekker's error-free sums and products (no fused multiply-add: the x86-64
//! baseline has none). One home for it: the all-modes tracker's complex residual far out
//! (`modes::extended`), and the answers near the rounding floor (`crate::floor`), whose
//! generated `residual_in` run on it evaluates F to far below the rounding of its `f64`
//! evaluation. Not for values near overflow: a factor of about 1e300 or a product of about
//! 1e154 may come out infinite or NaN, which the callers treat as "cannot tell".

use core::ops::{Add, Mul, Neg, Sub};

// The sums and products are out of line in builds with debug assertions (the test profile),
// inlined otherwise: written out at every operation of every declared mechanism's generated
// `residual_in`, they made that function in double-double the largest thing in the tests'
// binary (234 k of its 3.58 M lines of optimised IR; `BENCHMARKS.md`, test suite). Release
// builds inline them for speed; the results are the same bit for bit either way.

/// `hi + lo` with `|lo| ≤ ulp(hi) / 2`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct DoubleDouble {
    pub(crate) hi: f64,
    pub(crate) lo: f64,
}

/// `a + b` exactly, as a sum and its rounding error.
#[inline(always)]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a + b` exactly where `|a| ≥ |b|`.
#[inline(always)]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// Dekker's split of a double into two halves of 26 bits.
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    let t = 134_217_729.0 * a; // 2^27 + 1
    let hi = t - (t - a);
    (hi, a - hi)
}

/// `a · b` exactly, as a product and its rounding error (no fused multiply–add needed).
#[inline(always)]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

impl DoubleDouble {
    pub(crate) const fn new(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }

    /// The value rounded to the nearest `f64`.
    pub(crate) fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// `1 / self`: one Newton correction of the f64 quotient.
    pub(crate) fn recip(self) -> Self {
        let q1 = 1.0 / self.hi;
        let r = Self::new(1.0) - self * Self::new(q1);
        let q2 = r.hi / self.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(self, b: Self) -> Self {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DoubleDouble { hi, lo }
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(self, b: Self) -> Self {
        self + -b
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(self, b: Self) -> Self {
        let (p, e) = two_prod(self.hi, b.hi);
        let (hi, lo) = quick_two_sum(p, e + (self.hi * b.lo + self.lo * b.hi));
        DoubleDouble { hi, lo }
    }
}

impl crate::scalar::Scalar for DoubleDouble {
    fn from_f64(x: f64) -> Self {
        Self::new(x)
    }
    fn sq(self) -> Self {
        self * self
    }
    /// The `f64` sine of the leading part: the `f64` residual uses the same rounded value, so
    /// the two evaluate the same equations (sines and cosines enter F only through the inputs,
    /// as coefficients).
    fn sin(self) -> Self {
        Self::new(crate::math::sin(self.hi))
    }
    /// As [`Self::sin`].
    fn cos(self) -> Self {
        Self::new(crate::math::cos(self.hi))
    }
}

#[cfg(test)]
mod tests {
    use super::DoubleDouble;
    use crate::scalar::Scalar;

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
        // 1/3 to about 32 digits: 3 · (1/3) − 1 is below 1e-31.
        let third = dd(3.0).recip();
        assert!((dd(3.0) * third - dd(1.0)).to_f64().abs() < 1e-31);
    }
}
