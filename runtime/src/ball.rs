//! Midpoint–radius ("ball") arithmetic whose radius is a polynomial in the size of a box, with
//! rigorous bounds on every rounding: one evaluation of the generated Jacobian bounds it over
//! every box `c ± ρR`, ρ ∈ [0, 1], at once.
//!
//! A [`Ball<D>`] stands for the claim "for every point of the domain, the exact value lies in
//! `mid ± (rad[0] + rad[1] ρ + … + rad[D−1] ρ^{D−1})`", where the domain is the box of size
//! ρ. The inputs to the generated code make the claim true by construction (an unknown
//! `c_i ± ρR` is `Ball { mid: c_i, rad: [0, R] }`, a joint input `x ± w` is
//! `Ball { mid: x, rad: [w, 0] }`), and every operation keeps it true:
//!
//! - the midpoint is computed in floating point, and its rounding error, at most
//!   `u |exact| < 2u |fl|` (u = 2⁻⁵³) plus an underflow error below [`TINY`], goes into `rad[0]`;
//! - `(a + s)(b + t) − ab = at + bs + st` gives `|a| t + |b| s + s t` for the radius, whose
//!   powers ρ^k with k ≥ D are bounded by ρ^{D−1} (ρ ≤ 1), so the degree stays below D;
//! - sin and cos are 1-Lipschitz: the radius carries over, plus 2⁻⁴⁹ for the library's error
//!   (libm's sin and cos are within an ulp, at most 2⁻⁵³ for values in [−1, 1]);
//! - each radius coefficient is a sum of at most `D (D + 1) / 2 + 3` products of non-negative
//!   floats, which floating point computes to within a factor `(1 − u)^m` (m ≤ 12 roundings
//!   for D ≤ 3) and an underflow error of `η/2 = 2⁻¹⁰⁷⁵` per product: [`up`] turns the computed
//!   value into an upper bound by a factor `1 + 2(m + 2)u` and an added [`TINY`].
//!
//! No rounding mode is changed and nothing is stepped to the next float in the inner loops: the
//! a-priori error bounds (Higham, *Accuracy and Stability of Numerical Algorithms*, 2002, §3.1;
//! Rump, "Fast and parallel interval arithmetic", BIT 1999) are applied once per coefficient.
//! That is what makes this cheap enough for a 1 kHz loop.

use core::ops::{Add, Mul, Neg, Sub};

/// The unit roundoff of `f64`, 2⁻⁵³.
pub(crate) const U: f64 = f64::EPSILON / 2.0;

/// Added to every upper bound: it exceeds the underflow error (at most 2⁻¹⁰⁷⁵ per product) of
/// up to 2⁵¹ products, so bounds need no case for subnormal results.
pub(crate) const TINY: f64 = f64::MIN_POSITIVE;

/// An upper bound on a non-negative real `s` that floating point computed as `x` from
/// non-negative floats by sums and products, each term through at most `m` roundings:
/// `s ≤ x (1 + γ_m) + (underflow)` with γ_m = m u / (1 − m u), and
/// `fl(fl(x · (1 + 2(m + 2)u)) + TINY)` is at least that (the factor is exact in binary for
/// m < 2⁵⁰, and its product and the sum each lose at most a factor 1 − u). NaN stays NaN.
#[inline(always)]
pub(crate) fn up(x: f64, m: u32) -> f64 {
    let grow = 1.0 + (m as f64 + 2.0) * f64::EPSILON;
    x * grow + TINY
}

/// The library's error bound for sin and cos, 2⁻⁴⁹.
const TRIG_ERROR: f64 = 1.7763568394002505e-15;

/// Roundings in one radius coefficient of an operation: a product and up to
/// `D (D + 1) / 2 + 3` additions (bounded here for D ≤ 3).
const ROUNDINGS: u32 = 12;

/// A midpoint and a radius polynomial of degree `D − 1` in the box size ρ ∈ [0, 1]; see the
/// module docs for what it claims.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ball<const D: usize> {
    pub mid: f64,
    pub rad: [f64; D],
}

impl<const D: usize> Ball<D> {
    /// `mid ± rad`, rounding of `mid`'s computation not yet counted.
    #[inline(always)]
    fn finish(mid: f64, mut rad: [f64; D]) -> Self {
        rad[0] += 2.0 * U * mid.abs();
        for r in &mut rad {
            *r = up(*r, ROUNDINGS);
        }
        Ball { mid, rad }
    }
}

// The arithmetic is out of line in builds with debug assertions, as the series and
// double-double arithmetic is (`modes::taylor`): each operation of a generated `residual_in` or
// `jacobian_in` written out (the radius's loops, its rounding bound) for every declared
// mechanism is compiled again for each. Release builds, where the certified tracker runs at
// 1 kHz, inline it. The results are the same bit for bit either way.
impl<const D: usize> Add for Ball<D> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(self, o: Self) -> Self {
        Ball::finish(
            self.mid + o.mid,
            core::array::from_fn(|l| self.rad[l] + o.rad[l]),
        )
    }
}

impl<const D: usize> Sub for Ball<D> {
    type Output = Self;
    // The radii of a difference add, as those of a sum do.
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(self, o: Self) -> Self {
        Ball::finish(
            self.mid - o.mid,
            core::array::from_fn(|l| self.rad[l] + o.rad[l]),
        )
    }
}

impl<const D: usize> Neg for Ball<D> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Ball {
            mid: -self.mid,
            rad: self.rad,
        }
    }
}

impl<const D: usize> Mul for Ball<D> {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(self, o: Self) -> Self {
        let (a, b) = (self.mid.abs(), o.mid.abs());
        let mut rad: [f64; D] = core::array::from_fn(|l| a * o.rad[l] + b * self.rad[l]);
        for i in 0..D {
            for j in 0..D {
                // ρ^{i+j} ≤ ρ^{D−1} once i + j ≥ D − 1, for ρ ≤ 1.
                rad[(i + j).min(D - 1)] += self.rad[i] * o.rad[j];
            }
        }
        Ball::finish(self.mid * o.mid, rad)
    }
}

impl<const D: usize> crate::scalar::Scalar for Ball<D> {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Ball {
            mid: x,
            rad: [0.0; D],
        }
    }

    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sq(self) -> Self {
        // (a + s)² − a² = 2 a s + s².
        let a = self.mid.abs();
        let mut rad: [f64; D] = core::array::from_fn(|l| 2.0 * a * self.rad[l]);
        for i in 0..D {
            for j in 0..D {
                rad[(i + j).min(D - 1)] += self.rad[i] * self.rad[j];
            }
        }
        Ball::finish(self.mid * self.mid, rad)
    }

    fn sin(self) -> Self {
        let mut rad = self.rad;
        rad[0] += TRIG_ERROR;
        Ball::finish(crate::math::sin(self.mid), rad)
    }

    fn cos(self) -> Self {
        let mut rad = self.rad;
        rad[0] += TRIG_ERROR;
        Ball::finish(crate::math::cos(self.mid), rad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Scalar;

    /// Whether `b` at box size ρ holds `x`.
    fn holds<const D: usize>(b: &Ball<D>, rho: f64, x: f64) -> bool {
        let r: f64 = (0..D).map(|l| b.rad[l] * rho.powi(l as i32)).sum();
        (x - b.mid).abs() <= r
    }

    #[test]
    fn operations_hold_every_value_of_their_operands() {
        // u ± ρ·2 and w ± (0.1 + ρ): values at a few points of the box, exactly representable.
        let big = 2.0;
        let u = Ball::<2> {
            mid: 0.3,
            rad: [0.0, big],
        };
        let w = Ball::<2> {
            mid: -1.7,
            rad: [0.1, 1.0],
        };
        for rho in [0.0, 0.25, 0.5, 1.0] {
            for s in [-1.0, -0.5, 0.0, 0.5, 1.0] {
                for t in [-1.0, 0.0, 1.0] {
                    let a = 0.3 + s * big * rho;
                    let b = -1.7 + t * (0.1 + rho);
                    assert!(holds(&(u + w), rho, a + b));
                    assert!(holds(&(u - w), rho, a - b));
                    assert!(holds(&(u * w), rho, a * b));
                    assert!(holds(&(-u), rho, -a));
                    assert!(holds(&u.sq(), rho, a * a));
                    assert!(holds(&Scalar::sin(w), rho, libm::sin(b)));
                    assert!(holds(&Scalar::cos(u * w), rho, libm::cos(a * b)));
                }
            }
        }
    }

    #[test]
    fn the_rounding_of_the_midpoint_is_counted() {
        // 0.1 + 0.2 ≠ 0.3 in floating point: the ball must hold the exact sum of the two
        // floats, which differs from the computed midpoint.
        let s = Ball::<1>::from_f64(0.1) + Ball::<1>::from_f64(0.2);
        assert!(s.rad[0] > 0.0 && s.rad[0] < 1e-15);
        let third = Ball::<1>::from_f64(1.0 / 3.0) * Ball::<1>::from_f64(3.0);
        assert!(third.rad[0] >= (third.mid - 1.0).abs());
        // Bounds stay positive through underflow.
        let tiny = Ball::<1>::from_f64(1e-200) * Ball::<1>::from_f64(1e-200);
        assert!(tiny.rad[0] >= TINY);
        assert!(up(1.0, 3) > 1.0 && up(0.0, 3) > 0.0 && up(f64::NAN, 3).is_nan());
    }
}
