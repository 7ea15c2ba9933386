//! Interval arithmetic with outward rounding: every operation's result contains the exact result
//! for every pair of reals in its operands. Rounding is made outward by stepping each bound one
//! unit in the last place away (`next_down`, `next_up`), which contains the correctly rounded
//! result of IEEE 754 arithmetic (the library functions `sin` and `cos` are widened by a bound
//! on their error instead; see there).

use core::ops::{Add, Mul, Neg, Sub};

/// A closed interval `[lo, hi]` of reals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// The lower bound.
    pub lo: f64,
    /// The upper bound.
    pub hi: f64,
}

impl Interval {
    /// `[x, x]`.
    pub const fn point(x: f64) -> Self {
        Interval { lo: x, hi: x }
    }

    /// `[lo, hi]`; NaN bounds make an interval that contains nothing useful: check
    /// [`Interval::is_finite`].
    pub const fn new(lo: f64, hi: f64) -> Self {
        Interval { lo, hi }
    }

    /// `[c − r, c + r]`, rounded outward.
    pub fn around(c: f64, r: f64) -> Self {
        Interval {
            lo: (c - r).next_down(),
            hi: (c + r).next_up(),
        }
    }

    /// Whether both bounds are finite and in order (`lo ≤ hi`): an interval that means
    /// something.
    pub fn is_finite(&self) -> bool {
        self.lo.is_finite() && self.hi.is_finite() && self.lo <= self.hi
    }

    /// The midpoint, rounded (halves summed, so that it cannot overflow).
    pub fn mid(&self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }

    /// A radius about [`Interval::mid`], rounded up: `[mid − radius, mid + radius]` contains
    /// the interval even though the midpoint itself is rounded.
    pub fn radius(&self) -> f64 {
        let m = self.mid();
        (self.hi - m).max(m - self.lo).next_up()
    }

    /// The largest |x| for x in the interval.
    pub fn mag(&self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }

    /// `y · self` for a point `y`: two products instead of four.
    #[inline]
    pub fn scale(self, y: f64) -> Self {
        let (a, b) = (y * self.lo, y * self.hi);
        if y >= 0.0 {
            Interval::new(a.next_down(), b.next_up())
        } else {
            Interval::new(b.next_down(), a.next_up())
        }
    }

    /// Whether `other` lies in the interior of `self`.
    pub fn contains_strictly(&self, other: &Interval) -> bool {
        self.lo < other.lo && other.hi < self.hi
    }

    /// Whether `x` lies in the interval, bounds included.
    pub fn contains(&self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }

    /// `{x² : x ∈ self}`, rounded outward: tighter than `self * self`, which does not know
    /// both factors are the same x (for `[−1, 2]`, `[0, 4]` instead of `[−2, 4]`).
    pub fn sq(self) -> Self {
        let (a, b) = (self.lo * self.lo, self.hi * self.hi);
        if self.lo <= 0.0 && self.hi >= 0.0 {
            Interval::new(0.0, a.max(b).next_up())
        } else {
            Interval::new(a.min(b).next_down().max(0.0), a.max(b).next_up())
        }
    }

    /// sin over the interval: the midpoint's value widened by the half-width (|sin'| ≤ 1) and by
    /// 2⁻⁴⁹ for the library's error (libm's sin is within 1 ulp, far below this), clipped to
    /// [−1, 1].
    pub fn sin(self) -> Self {
        Self::lipschitz(self, crate::math::sin)
    }

    /// cos over the interval; as [`Interval::sin`].
    pub fn cos(self) -> Self {
        Self::lipschitz(self, crate::math::cos)
    }

    fn lipschitz(self, f: fn(f64) -> f64) -> Self {
        if !self.is_finite() {
            return Interval::new(f64::NAN, f64::NAN);
        }
        let m = self.mid();
        let r = (self.hi - m).max(m - self.lo).next_up();
        let y = f(m);
        // 2⁻⁴⁹ ≈ 1.8e-15.
        let slack = (r + 1.7763568394002505e-15).next_up();
        Interval::new(
            (y - slack).next_down().max(-1.0),
            (y + slack).next_up().min(1.0),
        )
    }
}

impl Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::new((self.lo + o.lo).next_down(), (self.hi + o.hi).next_up())
    }
}

impl Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        Interval::new((self.lo - o.hi).next_down(), (self.hi - o.lo).next_up())
    }
}

impl Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let p = [
            self.lo * o.lo,
            self.lo * o.hi,
            self.hi * o.lo,
            self.hi * o.hi,
        ];
        if p.iter().any(|x| x.is_nan()) {
            // 0 × ∞ in a bound: give up on this product rather than guess.
            return Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        }
        let lo = p.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        let hi = p.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        Interval::new(lo.next_down(), hi.next_up())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operations_contain_the_exact_results() {
        let a = Interval::new(0.1, 0.3);
        let b = Interval::new(-0.2, 0.7);
        for x in [0.1, 0.2, 0.3] {
            for y in [-0.2, 0.0, 0.5, 0.7] {
                assert!((a + b).contains(x + y));
                assert!((a - b).contains(x - y));
                assert!((a * b).contains(x * y));
                assert!(b.sq().contains(y * y));
                assert!(b.sin().contains(libm::sin(y)));
                assert!(a.cos().contains(libm::cos(x)));
            }
        }
        // 0.1 + 0.2 is not 0.3 in floating point: the enclosure of the point sum holds both.
        let s = Interval::point(0.1) + Interval::point(0.2);
        assert!(s.contains(0.1 + 0.2) && s.lo < s.hi);
        assert_eq!(Interval::new(-1.0, 2.0).sq().lo, 0.0);
        // Midpoint and radius cover the interval when the midpoint is not representable.
        let narrow = Interval::new(100.0, 100.0f64.next_up());
        let (m, r) = (narrow.mid(), narrow.radius());
        assert!(m - r <= narrow.lo && narrow.hi <= m + r);
    }
}
