//! Float maths through `libm` (shared with the generator), and the norm of the solvers' hot
//! loops.

pub use linkage_geometry::math::*;

/// Σ vᵢ², unscaled: infinite where it overflows (‖v‖ above about 1e154) as well as where an
/// entry is not finite; finite only where every entry is.
#[inline(always)]
pub(crate) fn squares<const N: usize>(v: &[f64; N]) -> f64 {
    // As in `size`, which keeps its own copy of the loop: written as this function and a
    // root, it cost the Newton loop 72 instructions a solve (`count nr-normal`, BENCHMARKS.md).
    let (mut even, mut odd) = (0.0, 0.0);
    let pairs = v.chunks_exact(2);
    let last = pairs.remainder();
    for p in pairs {
        even += p[0] * p[0];
        odd += p[1] * p[1];
    }
    for x in last {
        even += x * x;
    }
    even + odd
}

/// The Euclidean norm of a fixed-size vector: one sum of squares and one square root, unrolled
/// by the compiler for the mechanism's size. Where that sum is not a normal finite number —
/// NaN, overflowed, or so small it may have underflowed — the rescaling [`norm`] decides, so
/// the result is the same: NaN for any NaN entry, +∞ for an infinite one, never small for a
/// bad vector.
#[inline(always)]
pub(crate) fn size<const N: usize>(v: &[f64; N]) -> f64 {
    // Two partial sums (even and odd entries): the compiler pairs them in one SSE2 register
    // instead of one long chain of scalar additions.
    let (mut even, mut odd) = (0.0, 0.0);
    let pairs = v.chunks_exact(2);
    let last = pairs.remainder();
    for p in pairs {
        even += p[0] * p[0];
        odd += p[1] * p[1];
    }
    for x in last {
        even += x * x;
    }
    let s = even + odd;
    if s.is_finite() && s > 1e-280 {
        sqrt(s)
    } else {
        norm(v)
    }
}

/// The size that the solvers' relative rules measure against: `size` as given, or 1 where it
/// is 0 (a configuration at the origin has no length of its own). Never floored at 1 otherwise:
/// a mechanism 1e-9 across would then be judged in absolute units, its tolerance allowed to
/// exceed the mechanism itself.
#[inline(always)]
pub(crate) fn scale_or_one(size: f64) -> f64 {
    if size > 0.0 { size } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::{norm, size};

    #[test]
    fn size_is_the_norm_and_never_calls_a_bad_vector_small() {
        for v in [
            [3.0, 4.0, 0.0],
            [3e200, 4e200, 0.0],
            [3e-200, 4e-200, 0.0],
            [0.0; 3],
            [1e-150, 1.0, -2.0],
        ] {
            assert_eq!(size(&v), norm(&v), "{v:?}");
        }
        assert!(size(&[1.0, f64::NAN, 1e-300]).is_nan());
        assert!(size(&[f64::NAN; 18]).is_nan());
        assert_eq!(size(&[f64::INFINITY, 1.0]), f64::INFINITY);
        assert_eq!(size(&[1e200, 1e200]), norm(&[1e200, 1e200]));
        assert!(
            size(&[1e200, 1e200]).is_finite(),
            "overflow of the sum is rescaled"
        );
        assert!(!(size(&[f64::NAN; 18]) <= 1e-10));
    }
}
