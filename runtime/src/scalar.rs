//! The arithmetic the generated residual and Jacobian can be evaluated in: `f64`, and
//! [`Interval`] for certification.

use crate::interval::Interval;
use core::ops::{Add, Mul, Neg, Sub};

/// A number type the generated `residual_in` and `jacobian_in` run on.
pub trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// The number `x` (for an interval, the point `[x, x]`).
    fn from_f64(x: f64) -> Self;
    /// `self²` (for an interval, of one variable: never negative).
    fn sq(self) -> Self;
    /// The sine (for an interval, an enclosure of the sines over it).
    fn sin(self) -> Self;
    /// The cosine (as [`Scalar::sin`]).
    fn cos(self) -> Self;
}

impl Scalar for f64 {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sq(self) -> Self {
        self * self
    }
    #[inline(always)]
    fn sin(self) -> Self {
        crate::math::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        crate::math::cos(self)
    }
}

impl Scalar for Interval {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Interval::point(x)
    }
    #[inline(always)]
    fn sq(self) -> Self {
        Interval::sq(self)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        Interval::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        Interval::cos(self)
    }
}
