//! Float maths through `libm`, so that nothing needs `std`.

/// √x, correctly rounded either way. With `std`, the compiler's own: one instruction, encoded
/// for the target features of the function it is inlined into. `libm`'s, on x86, is inline
/// assembly in the SSE encoding, which in the runtime's AVX twin (`linkage::uses_x86_64_v3`)
/// stalled on the registers' upper halves: the tracker's median sample took 0.62 µs instead
/// of 0.45 (BENCHMARKS.md, Instruction counts).
#[inline]
pub fn sqrt(x: f64) -> f64 {
    #[cfg(feature = "std")]
    return x.sqrt();
    #[cfg(not(feature = "std"))]
    libm::sqrt(x)
}

#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

#[inline]
pub fn asin(x: f64) -> f64 {
    libm::asin(x)
}

#[inline]
pub fn tan(x: f64) -> f64 {
    libm::tan(x)
}

#[inline]
pub fn atan(x: f64) -> f64 {
    libm::atan(x)
}

pub fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub fn sub3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub fn scale3(s: f64, a: [f64; 3]) -> [f64; 3] {
    [s * a[0], s * a[1], s * a[2]]
}

pub fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub fn norm3(a: [f64; 3]) -> f64 {
    sqrt(dot3(a, a))
}

/// Euclidean norm of a slice; rescaled only when the plain sum of squares over- or underflows.
/// NaN if any entry is NaN, +∞ if any is infinite: a norm must never call a bad vector small
/// (`f64::max` skips NaN, so the rescaling below must not see one).
pub fn norm(v: &[f64]) -> f64 {
    let s: f64 = v.iter().map(|x| x * x).sum();
    if s.is_finite() && s > 1e-280 {
        return sqrt(s);
    }
    if s.is_nan() {
        return f64::NAN;
    }
    let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    let s: f64 = v.iter().map(|x| (x / scale) * (x / scale)).sum();
    scale * sqrt(s)
}

#[cfg(test)]
mod tests {
    use super::norm;

    #[test]
    fn a_norm_never_calls_nan_or_infinity_small() {
        assert!(norm(&[f64::NAN; 4]).is_nan());
        assert!(norm(&[0.0, f64::NAN, 1.0]).is_nan());
        assert!(norm(&[1e-200, f64::NAN]).is_nan());
        assert_eq!(norm(&[f64::INFINITY, 1.0]), f64::INFINITY);
        assert!(norm(&[f64::NEG_INFINITY, f64::NAN]).is_nan());
        // Still accurate where the plain sum over- or underflows.
        assert!((norm(&[3e200, 4e200]) / 5e200 - 1.0).abs() < 1e-15);
        assert!((norm(&[3e-200, 4e-200]) / 5e-200 - 1.0).abs() < 1e-15);
        assert_eq!(norm(&[]), 0.0);
        // Every caller's `norm(d) <= tol` must reject a NaN correction.
        assert!(!(norm(&[f64::NAN; 18]) <= 1e-10));
    }
}
