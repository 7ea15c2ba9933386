//! A small complex number type for the homotopy: the generated `residual_in` and
//! `jacobian_in` evaluate F and ∂F/∂v in it through [`Scalar`](crate::scalar::Scalar).

use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// `re + i·im`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Complex {
    /// The real part.
    pub re: f64,
    /// The imaginary part.
    pub im: f64,
}

impl Complex {
    /// 0.
    pub const ZERO: Complex = Complex { re: 0.0, im: 0.0 };
    /// 1.
    pub const ONE: Complex = Complex { re: 1.0, im: 0.0 };
    /// The imaginary unit.
    pub const I: Complex = Complex { re: 0.0, im: 1.0 };

    /// `re + i·im`.
    #[inline(always)]
    pub const fn new(re: f64, im: f64) -> Self {
        Complex { re, im }
    }

    /// The real number `re`.
    #[inline(always)]
    pub const fn real(re: f64) -> Self {
        Complex { re, im: 0.0 }
    }

    /// The complex conjugate.
    #[inline(always)]
    pub fn conj(self) -> Self {
        Complex::new(self.re, -self.im)
    }

    /// `|z|²`.
    #[inline(always)]
    pub fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// `|z|`, without overflow for large parts.
    #[inline]
    pub fn abs(self) -> f64 {
        libm::hypot(self.re, self.im)
    }

    /// `max(|re|, |im|)`: within a factor √2 of `|z|` and cheaper; enough for norms that only
    /// steer step sizes and tolerances.
    #[inline(always)]
    pub fn abs_max(self) -> f64 {
        self.re.abs().max(self.im.abs())
    }

    /// `s · z` for a real `s`.
    #[inline(always)]
    pub fn scale(self, s: f64) -> Self {
        Complex::new(self.re * s, self.im * s)
    }

    /// `1 / z` (scaled so that neither part of |z|² overflows or underflows needlessly).
    #[inline]
    pub fn recip(self) -> Self {
        let m = self.abs_max();
        if m == 0.0 || !m.is_finite() {
            let d = self.norm_sqr();
            return Complex::new(self.re / d, -self.im / d);
        }
        let (a, b) = (self.re / m, self.im / m);
        let d = (a * a + b * b) * m;
        Complex::new(a / d, -b / d)
    }

    /// Whether both parts are finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }

    /// The principal square root.
    pub fn sqrt(self) -> Self {
        let r = self.abs();
        if r == 0.0 {
            return Complex::ZERO;
        }
        let t = crate::math::sqrt(0.5 * (r + self.re.abs()));
        if self.re >= 0.0 {
            Complex::new(t, 0.5 * self.im / t)
        } else {
            Complex::new(0.5 * self.im.abs() / t, libm::copysign(t, self.im))
        }
    }

    /// `(sin z, cos z)`.
    pub fn sin_cos(self) -> (Self, Self) {
        let (s, c) = (libm::sin(self.re), libm::cos(self.re));
        let (sh, ch) = (libm::sinh(self.im), libm::cosh(self.im));
        (Complex::new(s * ch, c * sh), Complex::new(c * ch, -s * sh))
    }
}

impl Add for Complex {
    type Output = Complex;
    #[inline(always)]
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
}

impl Sub for Complex {
    type Output = Complex;
    #[inline(always)]
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
}

impl Mul for Complex {
    type Output = Complex;
    #[inline(always)]
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

impl Div for Complex {
    type Output = Complex;
    #[inline]
    fn div(self, o: Complex) -> Complex {
        let r = o.recip();
        Complex::new(
            self.re * r.re - self.im * r.im,
            self.re * r.im + self.im * r.re,
        )
    }
}

impl Neg for Complex {
    type Output = Complex;
    #[inline(always)]
    fn neg(self) -> Complex {
        Complex::new(-self.re, -self.im)
    }
}

impl AddAssign for Complex {
    #[inline(always)]
    fn add_assign(&mut self, o: Complex) {
        self.re += o.re;
        self.im += o.im;
    }
}

impl SubAssign for Complex {
    #[inline(always)]
    fn sub_assign(&mut self, o: Complex) {
        self.re -= o.re;
        self.im -= o.im;
    }
}

impl MulAssign for Complex {
    #[inline(always)]
    fn mul_assign(&mut self, o: Complex) {
        *self = *self * o;
    }
}

impl crate::scalar::Scalar for Complex {
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Complex::real(x)
    }
    #[inline(always)]
    fn sq(self) -> Self {
        Complex::new(
            self.re * self.re - self.im * self.im,
            2.0 * self.re * self.im,
        )
    }
    #[inline]
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    #[inline]
    fn cos(self) -> Self {
        self.sin_cos().1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_and_functions() {
        let a = Complex::new(1.5, -2.0);
        let b = Complex::new(-0.25, 3.0);
        let q = a / b;
        let back = q * b;
        assert!((back - a).abs() < 1e-14);
        let r = Complex::new(-4.0, 1e-3).sqrt();
        assert!((r * r - Complex::new(-4.0, 1e-3)).abs() < 1e-14 && r.im > 0.0);
        let (s, c) = a.sin_cos();
        // sin² + cos² = 1 holds for complex arguments too.
        assert!((s * s + c * c - Complex::ONE).abs() < 1e-12);
        assert_eq!(Complex::real(2.0).recip(), Complex::real(0.5));
    }
}
