//! The residual in double-double complex arithmetic (about 32 significant digits), for roots
//! far out.
//!
//! A delta robot at crank angles close to one another has complex roots 10⁷ times its size
//! away, near points at infinity where the projective Jacobian is nearly singular: Newton's
//! corrections there stall at a rounding floor above what the tracker and `polish` accept,
//! because the residual, a sum of terms |v|² in size that cancel, is evaluated to only 16
//! digits. Evaluated in double-double (Dekker's exact sums and products), with the
//! factorisation and the iterate still in f64 (mixed-precision iterative refinement), the
//! corrections go on contracting far below that floor. Only paths that failed in f64 are
//! tracked or polished so; the angles' sines and cosines are taken in f64 (a fixed function
//! of the parameters, so the equations stay one smooth system).

use super::complex::Complex;
use crate::double_double::DoubleDouble as Dd;
use core::ops::{Add, Mul, Neg, Sub};

/// Beyond this size (in units of the scale) a root that f64 cannot polish is tried in
/// double-double, and so are the corrections of `Settings::FAR` paths: roots 10⁴ times the
/// mechanism's size away still polish in f64.
pub(crate) const WIDE_BEYOND: f64 = 1e4;

/// A complex number in double-double parts: the scalar of [`residual`].
///
/// In builds with debug assertions (the dev and test profiles) its sums and products are out
/// of line, the Dekker arithmetic inside each inlined: written out at every operation of every
/// mechanism's generated `residual_in` it was the largest code a crate declaring many
/// mechanisms compiled (15 % of the integration tests' optimised IR, BENCHMARKS.md). Release
/// builds inline them, for speed. The results are the same bit for bit either way.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Wide {
    re: Dd,
    im: Dd,
}

impl Wide {
    fn from(c: Complex) -> Wide {
        Wide {
            re: Dd::new(c.re),
            im: Dd::new(c.im),
        }
    }

    fn round(self) -> Complex {
        Complex::new(self.re.hi + self.re.lo, self.im.hi + self.im.lo)
    }

    fn recip(self) -> Wide {
        let inv = (self.re * self.re + self.im * self.im).recip();
        Wide {
            re: self.re * inv,
            im: -(self.im * inv),
        }
    }
}

impl Add for Wide {
    type Output = Wide;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn add(self, b: Wide) -> Wide {
        Wide {
            re: self.re + b.re,
            im: self.im + b.im,
        }
    }
}

impl Sub for Wide {
    type Output = Wide;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sub(self, b: Wide) -> Wide {
        Wide {
            re: self.re - b.re,
            im: self.im - b.im,
        }
    }
}

impl Neg for Wide {
    type Output = Wide;
    #[inline(always)]
    fn neg(self) -> Wide {
        Wide {
            re: -self.re,
            im: -self.im,
        }
    }
}

impl Mul for Wide {
    type Output = Wide;
    #[cfg_attr(debug_assertions, inline(never))]
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn mul(self, b: Wide) -> Wide {
        Wide {
            re: self.re * b.re - self.im * b.im,
            im: self.re * b.im + self.im * b.re,
        }
    }
}

impl crate::scalar::Scalar for Wide {
    fn from_f64(x: f64) -> Self {
        Wide::from(Complex::real(x))
    }
    #[cfg_attr(debug_assertions, inline(never))]
    fn sq(self) -> Self {
        self * self
    }
    // The inputs' sines and cosines in f64 (see the module docs).
    fn sin(self) -> Self {
        Wide::from(<Complex as crate::scalar::Scalar>::sin(self.round()))
    }
    fn cos(self) -> Self {
        Wide::from(<Complex as crate::scalar::Scalar>::cos(self.round()))
    }
}

/// The equations in tracking coordinates at (z, p), evaluated in double-double and rounded:
/// F(z, p), or with a projective chart `w^d F(z / w)` with `w = 1 − c·z` (whose cancellation
/// near infinity is exactly what needs the extra digits).
pub(crate) fn residual<S: crate::mechanism::Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    chart: Option<(&[Complex; N], &[u8; N])>,
    z: &[Complex; N],
    p: &[Complex; M],
) -> [Complex; N] {
    let zw = z.map(Wide::from);
    let pw = p.map(Wide::from);
    let mut f = [Wide::default(); N];
    match chart {
        None => sys.residual_in(&zw, &pw, &mut f),
        Some((c, degree)) => {
            let mut w = Wide::from(Complex::ONE);
            for i in 0..N {
                w = w - Wide::from(c[i]) * zw[i];
            }
            let inv = w.recip();
            let v = zw.map(|x| x * inv);
            sys.residual_in(&v, &pw, &mut f);
            for i in 0..N {
                for _ in 0..degree[i] {
                    f[i] = f[i] * w;
                }
            }
        }
    }
    f.map(Wide::round)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_double_keeps_what_f64_rounds_away() {
        // (1 + 2⁻⁶⁰)² − 1 = 2⁻⁵⁹ + 2⁻¹²⁰: zero in f64.
        let e = libm::ldexp(1.0, -60);
        let a = Dd { hi: 1.0, lo: e };
        let d = a * a - Dd::new(1.0);
        assert!(((d.hi + d.lo) - 2.0 * e).abs() <= 1e-30);
        let x = Dd::new(3.0).recip() * Dd::new(3.0) - Dd::new(1.0);
        assert!((x.hi + x.lo).abs() <= 1e-31);
        let z = Wide::from(Complex::new(3.0, -4.0));
        let one = (z * z.recip()).round();
        assert!((one.re - 1.0).abs() < 1e-15 && one.im.abs() < 1e-15);
    }
}
