//! A value and its rate of change along a path, each a [`Ball<1>`]: forward-mode
//! differentiation in rigorous midpoint–radius arithmetic.
//!
//! A [`Slope`] stands for the claim "for every t of the path's parameter interval, the exact
//! value at t lies in `val`, and its derivative with respect to t lies in `d`". The inputs
//! make it true by construction (a joint input moving along a segment is its hull with the
//! segment's half-difference as its rate; an unknown held fixed is a point of rate zero), and
//! every operation keeps it true: the chain rule applied to enclosures of the operands' values
//! and rates over the whole interval encloses the result's rate there, in [`Ball`] arithmetic,
//! whose roundings are bounded.
//!
//! The step certificate uses it for a centred form in the inputs: F(c, x(t)) lies in
//! F(c, x(0)) + t G for |t| ≤ 1, with G the enclosure of dF/dt (the mean value theorem), so
//! that Y F(c, x(t)) is bounded through the signed product Y G, where the entries of Y cancel,
//! instead of |Y| times the spread of F over the inputs' hull.

use crate::ball::Ball;
use crate::scalar::Scalar;
use core::ops::{Add, Mul, Neg, Sub};

/// A value and the rate of change along a path, each enclosed (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Slope {
    /// The values over the path.
    pub val: Ball<1>,
    /// The derivatives along the path, over the path.
    pub d: Ball<1>,
}

impl Slope {
    /// A quantity that does not move along the path.
    #[inline(always)]
    pub fn fixed(val: Ball<1>) -> Self {
        Slope {
            val,
            d: Ball::from_f64(0.0),
        }
    }
}

// Out of line in builds with debug assertions, for the reason the ball arithmetic under it is
// (`ball.rs`): inlined, each product of a generated `residual_in` becomes three ball products
// and a sum written out, for every declared mechanism. The certified tracker's residual in
// slopes was the largest single family of the integration tests' optimisation time (5.5 s of
// 72 s by `-Z llvm-time-trace`); out of line the binary built 2.5 % faster (BENCHMARKS.md).
// Release builds inline it; the results are the same bit for bit.
impl Add for Slope {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(self, o: Self) -> Self {
        Slope {
            val: self.val + o.val,
            d: self.d + o.d,
        }
    }
}

impl Sub for Slope {
    type Output = Self;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(self, o: Self) -> Self {
        Slope {
            val: self.val - o.val,
            d: self.d - o.d,
        }
    }
}

impl Neg for Slope {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Slope {
            val: -self.val,
            d: -self.d,
        }
    }
}

impl Mul for Slope {
    type Output = Self;
    // (a b)′ = a′ b + a b′, with a and b enclosing the values wherever a′ and b′ are taken.
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(self, o: Self) -> Self {
        Slope {
            val: self.val * o.val,
            d: self.d * o.val + self.val * o.d,
        }
    }
}

impl Scalar for Slope {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Slope::fixed(Ball::from_f64(x))
    }

    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sq(self) -> Self {
        // (a²)′ = 2 a a′ (the doubling exact in the ball's midpoint, its rounding bounded).
        let half = self.val * self.d;
        Slope {
            val: self.val.sq(),
            d: half + half,
        }
    }

    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sin(self) -> Self {
        Slope {
            val: self.val.sin(),
            d: self.val.cos() * self.d,
        }
    }

    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn cos(self) -> Self {
        Slope {
            val: self.val.cos(),
            d: -(self.val.sin() * self.d),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `b` holds `x`.
    fn holds(b: &Ball<1>, x: f64) -> bool {
        (x - b.mid).abs() <= b.rad[0]
    }

    /// The path t ↦ 0.4 + 0.3 t, t ∈ [−1, 1]: its hull and its rate.
    fn path() -> Slope {
        Slope {
            val: Ball {
                mid: 0.4,
                rad: [0.3],
            },
            d: Ball::from_f64(0.3),
        }
    }

    #[test]
    fn rates_enclose_the_derivatives_along_the_path() {
        let p = path();
        let k = Slope::from_f64(-1.5);
        // f(t) = sin(p)·p² − cos(p)·k + (p − k)·p, and its derivative in t by hand.
        let f = p.sin() * p.sq() - p.cos() * k + (p - k) * p;
        for i in 0..=40 {
            let t = -1.0 + i as f64 / 20.0;
            let x = 0.4 + 0.3 * t;
            let value = x.sin() * x * x + x.cos() * 1.5 + (x + 1.5) * x;
            let dx = x.cos() * x * x + 2.0 * x * x.sin() - x.sin() * 1.5 + 2.0 * x + 1.5;
            assert!(holds(&f.val, value), "value at t = {t}");
            assert!(holds(&f.d, 0.3 * dx), "rate at t = {t}: {:?}", f.d);
            assert!(holds(&(-p).d, -0.3) && holds(&p.cos().d, -0.3 * x.sin()));
        }
    }

    #[test]
    fn a_fixed_quantity_has_rate_zero() {
        let k = Slope::fixed(Ball::from_f64(2.0));
        let f = k * k - k.sq() + k.sin();
        // Exactly zero but for the bounds' underflow allowance.
        assert!(f.d.mid == 0.0 && f.d.rad[0] < 1e-300, "{:?}", f.d);
    }
}
