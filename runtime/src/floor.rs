//! The rounding floor: how far a point may lie from the root of F while F, evaluated in `f64`,
//! cannot tell — and what a solve does where that comes near its tolerance.
//!
//! A Newton correction measured at v is Δ = B⁻¹F̂(v), where F̂ is F as evaluated, off the exact
//! F(v) by the rounding r of its terms. Newton's method stops where F̂ is nearly zero, which is
//! up to ‖B⁻¹r‖ from the root: there the correction is small while the error is not. At regular
//! points of a well-conditioned machine ‖B⁻¹r‖ is far below any tolerance (about 1e-13 mm for
//! the Table III platform); near a singularity it grows as 1/σmin(B), and on a model whose rows
//! sense a motion through a short lever (axes declared by points 1 mm apart) it is about
//! 1e-10 mm at regular points. Measured against the root of the same `f64` equations found in
//! double-double arithmetic, answers labelled converged with a correction within 1e-9 mm were
//! 1.5–2.8e-9 mm off near Stewart-platform singularities (det B at 1e-5 to 1e-6 of home's),
//! and within 1e-11 mm up to 1.4e-10 mm off on a planar 3-RPR.
//!
//! So where the floor may come near what the `f64` correction leaves under the tolerance (a
//! correction just within it leaves little), the answer's correction is measured again with F
//! evaluated in double-double arithmetic ([`vouch`]): to first order that correction is the
//! distance to the root, whatever the `f64` rounding, and steps of it refine the point
//! (Newton's method with an accurate residual, B factored at each point and of the start's
//! sign), each measured again. The answer is converged only if the last measure is within the
//! tolerance. Where is "near" is predicted without that work ([`may_reach`]) from a floor
//! [`estimate`]d once, at the start, grown as |det B| shrinks and as the machine grows; a solve
//! pays for the accurate residual (an evaluation of F in double-double, a factorisation and a
//! solve per measure) only there.

use crate::double_double::DoubleDouble;
use crate::interval::Interval;
use crate::math::size;
use crate::mechanism::Mechanism;
use crate::scalar::Scalar;

/// How close (as a share of the tolerance) the floor predicted from the start's may come
/// before the floor is measured at the answer itself. The prediction scales the start's floor
/// by |det B₀ / det B| (σmin's shrinking near a fold) and by the machine's growth; the margin
/// covers the rest of B⁻¹'s change across a workspace, on top of [`estimate`]'s own (it
/// overstates the floor about tenfold on the Table III platform: 1e-12 against 1e-13 mm).
/// (A hundredfold margin measured at about 15 of the 100 normal Table V points at 1e-9 mm,
/// where the tenfold one measures at none.)
const MARGIN: f64 = 10.0;

/// The rounding floor at `(v, x)`, generously: ‖B⁻¹ (ρ ∘ s)‖ for the rows' rounding bounds ρ
/// (radii of F over the point in interval arithmetic), the largest over three sign patterns s.
/// It only decides where [`vouch`] measures, so it errs high (on the planar 3-RPR 1e-7 mm
/// against the 1.4e-10 mm measured; on the Table III platform at home 1e-12 against 1e-13).
/// Infinite where B cannot be factored or a value is not finite.
pub(crate) fn estimate<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let vi = v.map(Interval::point);
    let xi = x.map(Interval::point);
    let mut fi = [Interval::point(0.0); N];
    sys.residual_in(&vi, &xi, &mut fi);
    let mut radius = [0.0; N];
    for (r, f) in radius.iter_mut().zip(&fi) {
        if !f.is_finite() {
            return f64::INFINITY;
        }
        *r = f.radius();
    }
    let mut fac = sys.new_factor();
    if sys.factor(v, x, &mut fac).is_none() {
        return f64::INFINITY;
    }
    // All of one sign, alternating, and a fixed scramble: rounding has no sign pattern of its
    // own, and one pattern alone can cancel in B⁻¹'s near-null direction.
    let mut floor = 0.0f64;
    for pattern in 0..3 {
        let mut b = radius;
        for (i, r) in b.iter_mut().enumerate() {
            let negative = match pattern {
                0 => false,
                1 => i % 2 == 1,
                _ => (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 63 == 1,
            };
            if negative {
                *r = -*r;
            }
        }
        sys.solve(&fac, &mut b);
        let s = size(&b);
        if !s.is_finite() {
            return f64::INFINITY;
        }
        floor = floor.max(s);
    }
    floor
}

/// What a start knows of the rounding floor on its branch: [`estimate`] at the branch's first
/// start, |det B| and ‖v‖ there. A start accepted later on the branch carries it unchanged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Floor {
    at_start: f64,
    det: f64,
    scale: f64,
}

impl Floor {
    /// The floor of a start at `v` where det B = `det`.
    pub(crate) fn at<S: Mechanism<N, M>, const N: usize, const M: usize>(
        sys: &S,
        v: &[f64; N],
        x: &[f64; M],
        det: f64,
    ) -> Self {
        Floor {
            at_start: estimate(sys, v, x),
            det: det.abs(),
            scale: size(v),
        }
    }

    /// A floor that is always measured: for solvers whose answers cost a path anyway (PH, NH,
    /// the tracker's fallback), and for a run that stalled at the floor.
    pub(crate) const ALWAYS: Floor = Floor {
        at_start: f64::INFINITY,
        det: 1.0,
        scale: 1.0,
    };
}

/// Whether the floor at a point `v` where det B = `det` may come within [`MARGIN`] of `room`
/// (what the correction measured in `f64` leaves under the tolerance), predicted from the
/// branch's [`Floor`]: the floor grows as 1/σmin, and |det B|
/// shrinks with σmin (none is credited for |det B| above the start's); and it grows with the
/// size of F's terms, about ‖v‖² (legs so long that the machine is 1e8 mm across put it at
/// 1e-2 mm). A configuration r = ‖v‖/‖v₀‖ > 1 times the start's also multiplies det B by up
/// to rᴺ without bringing B any nearer singular: that growth is taken out first. Cheap enough
/// for every solve and tracked sample; a prediction, which the stress suite's random
/// geometries showed can fall short twentyfold near singularities, so the solvers whose
/// answers cost a path anyway measure every answer ([`Floor::ALWAYS`]).
#[inline(always)]
pub(crate) fn may_reach<const N: usize>(
    floor: &Floor,
    (squares, det): (f64, f64),
    room: f64,
) -> bool {
    // r² without a square root, from Σv² (`squares`, which the caller has: see [`vouch`]);
    // rᴺ as (r²)^⌈N/2⌉ by squaring (an overestimate for odd N, which only measures more
    // often).
    let r2 = (squares / (floor.scale * floor.scale)).max(1.0);
    let mut growth = 1.0;
    if r2 > 1.0 {
        let (mut base, mut e) = (r2, N.div_ceil(2));
        while e > 0 {
            if e & 1 == 1 {
                growth *= base;
            }
            base *= base;
            e >>= 1;
        }
    }
    let det = (det.abs() / growth).min(floor.det);
    // NaN, infinite or zero values count as near: measure.
    !(MARGIN * floor.at_start * floor.det * r2 < room * det)
}

/// The Newton correction at `v` with F evaluated in double-double arithmetic and B factored
/// in `fac` (at `v`, or a point within rounding of it): B⁻¹F to first order is the distance to
/// the root of the `f64` equations, whatever the `f64` residual's rounding. `None` where a value
/// is not finite.
fn accurate_correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    fac: &S::Factor,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<[f64; N]> {
    let vd = v.map(DoubleDouble::from_f64);
    let xd = x.map(DoubleDouble::from_f64);
    let mut fd = [DoubleDouble::from_f64(0.0); N];
    sys.residual_in(&vd, &xd, &mut fd);
    let mut delta = fd.map(DoubleDouble::to_f64);
    sys.solve(fac, &mut delta);
    size(&delta).is_finite().then_some(delta)
}

/// What [`vouch`] found.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Vouched<const N: usize> {
    /// The correction found vouches for the tolerance, at the point as it is: the error
    /// estimate to report.
    Within(f64),
    /// A refined point, whose correction (F in double-double arithmetic) is within the
    /// tolerance: the point and that correction's size.
    Refined([f64; N], f64),
    /// Not within the tolerance: the point last measured and the smallest correction reached
    /// (infinite if none could be measured; then the point is the one given).
    Short([f64; N], f64),
}

/// Whether the correction of `size` that a Newton run found within `tolerance` at `v` (where
/// det B = `det` and Σv² = `squares`: [`crate::math::squares`], which `conclude` has computed
/// anyway, to check that v is finite) vouches for it. The correction is off the accurate one
/// by up to the floor, so where the floor may reach the room left between `size` and the
/// tolerance ([`may_reach`] from the branch's `floor`; a correction just within the tolerance
/// leaves little), the correction is measured again with F in
/// double-double arithmetic and B factored at the point, and the point refined by such
/// corrections while they shrink, up to three times (Newton's method with an accurate
/// residual, which goes below the `f64` floor).
// Inlined: on every solve's and tracked sample's path, where the prediction almost always
// says the floor is far; the measurement is out of line.
#[inline(always)]
pub(crate) fn vouch<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    floor: &Floor,
    (v, x): (&[f64; N], &[f64; M]),
    squares: f64,
    det: f64,
    size: f64,
    tolerance: f64,
) -> Vouched<N> {
    // Not the tolerance alone: a correction of 0.94e-9 mm measured in `f64` where the floor
    // was predicted at 6e-11 mm was 1.03e-9 mm in double-double (the stress suite's random
    // 6-6 trajectories, LINKAGE_STRESS_SEED=20261129, case 211).
    if !may_reach::<N>(floor, (squares, det), tolerance - size) {
        return Vouched::Within(size);
    }
    measure_and_refine(sys, (v, x), det, tolerance)
}

/// [`vouch`] where the floor may reach the tolerance.
#[cold]
#[inline(never)]
fn measure_and_refine<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (v, x): (&[f64; N], &[f64; M]),
    det: f64,
    tolerance: f64,
) -> Vouched<N> {
    let mut fac = sys.new_factor();
    let measure = |w: &[f64; N], fac: &mut S::Factor| {
        // B of the start's sign at every point measured: refinement stays on the branch.
        let info = sys.factor(w, x, fac)?;
        if !(info.det * det > 0.0) {
            return None;
        }
        accurate_correction(sys, fac, w, x)
    };
    let Some(mut delta) = measure(v, &mut fac) else {
        return Vouched::Short(*v, f64::INFINITY);
    };
    let mut point = *v;
    let mut achieved = crate::math::size(&delta);
    for _ in 0..REFINEMENTS {
        if achieved <= tolerance {
            break;
        }
        let mut next = point;
        for (w, d) in next.iter_mut().zip(&delta) {
            *w -= d;
        }
        match measure(&next, &mut fac) {
            Some(d) if crate::math::size(&d) < achieved => {
                achieved = crate::math::size(&d);
                delta = d;
                point = next;
            }
            _ => break,
        }
    }
    if achieved <= tolerance {
        Vouched::Refined(point, achieved)
    } else {
        Vouched::Short(point, achieved)
    }
}

/// Refinement steps [`vouch`] takes at most: from an answer at the `f64` floor, one brings the
/// correction to the double-double floor; more help where B is so nearly singular that a
/// step's own second-order term shows.
const REFINEMENTS: usize = 3;
