//! The initial configuration every solve starts from, checked once.

use crate::correction::{Failure, correction};
use crate::lu::Lu;
use crate::math::{norm, size};
use crate::mechanism::Mechanism;
use crate::solution::{Options, SolveError};

mod follow;
mod geometry;
mod path;

/// Below this reciprocal condition number of the equilibrated B a start is singular to
/// working precision. Near a fold the two roots that meet there lie about `rcond · ‖v‖`
/// apart, while rounding leaves v uncertain by about `ε ‖v‖ / rcond`; the sign of det B — the
/// start's branch — is only meaningful while the first is well above the second, i.e. while
/// rcond is well above √ε ≈ 1.5e-8.
const MIN_RCOND: f64 = 1e-7;

/// A consistent, nonsingular start configuration `(v0, x0)` and the sign of det B there,
/// which marks its branch: det B keeps its sign throughout the valid joint space.
///
/// A start belongs to the mechanism it was checked against, geometry included. Changing the
/// geometry afterwards (`set_geometry`, `set_pivot`) leaves `(v0, x0)` off the new solution
/// set: the solvers that claim the start's branch ([`arc_length`](crate::arc_length),
/// [`arc_length_detour`](crate::detour::arc_length_detour),
/// [`arc_length_certified`](crate::certified_path::arc_length_certified),
/// [`newton_homotopy`](crate::newton_homotopy), [`Tracker`](crate::tracker::Tracker)) measure the
/// start's own Newton correction and refuse such a start with
/// [`SolveError::InconsistentStart`]; make a new start for the new geometry
/// ([`Start::follow_geometry`], and the generated `follow_from`, carry the old one's
/// configuration there along the change of geometry, on its branch).
/// [`newton_raphson`](crate::newton_raphson) and [`NewtonRaphson`](crate::newton_raphson::NewtonRaphson)
/// take `v0` as a guess only and do not check it (their answer is
/// [`Status::Unverified`](crate::solution::Status::Unverified) either way).
///
/// Only checked constructors make one ([`Start::new`]), so every solve can rely on it:
///
/// ```compile_fail
/// let start: linkage::Start<1, 1> = linkage::Start { v: [0.0], x: [1.0], det: 1.0, scale: 0.0 };
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Start<const N: usize, const M: usize> {
    v: [f64; N],
    x: [f64; M],
    det: f64,
    /// ‖v‖ ([`size`]), which every solve from here checks its options against and sets its
    /// rounding floor by: computed once, not per solve.
    scale: f64,
    /// What is known of the rounding floor on this branch (`crate::floor`), from its first
    /// start: a start accepted later on the branch carries it unchanged.
    floor: crate::floor::Floor,
}

/// Whether every entry is finite, without a branch per entry: `x · 0` is 0 for finite x and
/// NaN for an infinite or NaN one, and a sum of zeros cannot overflow.
#[inline]
pub(crate) fn all_finite<const K: usize>(a: &[f64; K]) -> bool {
    let mut zero = 0.0;
    for x in a {
        zero += x * 0.0;
    }
    zero == 0.0
}

/// Rejects invalid options and non-finite, out-of-range or overflowing targets before any
/// work.
pub(crate) fn check_target<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<(), SolveError> {
    check_sample(sys, start, x, options)?;
    // Inputs so large that F overflows at the start (a leg of 1e300 mm) cannot be solved for.
    let mut f = [0.0; N];
    sys.residual(&start.v, x, &mut f);
    if !all_finite(&f) {
        return Err(SolveError::NonFinite);
    }
    Ok(())
}

/// [`check_target`] without evaluating F: for the tracker, whose fast path evaluates it anyway.
pub(crate) fn check_sample<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<(), SolveError> {
    options.check(start.scale)?;
    if !all_finite(x) {
        return Err(SolveError::NonFinite);
    }
    sys.validate_inputs(x)
        .map_err(|input| SolveError::InvalidInput { input })
}

/// How far a start's own Newton correction may be and still count as consistent, relative to
/// ‖v0‖: twice what [`Start::new`] accepts (1e-6 ‖v‖, measured against the given rather
/// than the refined v, which differ by at most 0.1 %), so no start it made is refused here,
/// while one made for another geometry (a link a millimetre longer) is off by far more.
const CONSISTENT: f64 = 2e-6;

/// Refuses a start that is not a solution for `sys` (made for another geometry, before
/// `set_geometry`): its Newton correction ‖B⁻¹F(v0, x0)‖, with B factored at the start in
/// `fac`, must be within [`CONSISTENT`] of ‖v0‖. One residual and one solve.
pub(crate) fn consistent_with<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    fac: &S::Factor,
) -> Result<(), SolveError> {
    let mut f = [0.0; N];
    sys.residual(&start.v, &start.x, &mut f);
    let residual_norm = norm(&f);
    sys.solve(fac, &mut f);
    judge(start, size(&f), residual_norm)
}

/// [`consistent_with`] for a caller with no factorisation at hand (the tracker, once; a start
/// where the generated factorisation fails): a Newton correction of its own.
pub(crate) fn check_consistent<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
) -> Result<(), SolveError> {
    let mut f = [0.0; N];
    sys.residual(&start.v, &start.x, &mut f);
    let residual_norm = norm(&f);
    match correction(sys, &start.v, &start.x) {
        Ok(c) => judge(start, c.size, residual_norm),
        // B singular at a start `Start::new` accepted as regular: not this mechanism's start.
        Err(Failure::Singular) => Err(SolveError::SingularStart),
        Err(Failure::NonFinite) => Err(SolveError::InconsistentStart { residual_norm }),
    }
}

fn judge<const N: usize, const M: usize>(
    start: &Start<N, M>,
    correction: f64,
    residual_norm: f64,
) -> Result<(), SolveError> {
    if correction <= CONSISTENT * crate::math::scale_or_one(start.scale) {
        Ok(())
    } else {
        Err(SolveError::InconsistentStart { residual_norm })
    }
}

/// Whether B at (v, x) is singular to working precision, judged without regard to units: the
/// rows and the columns of B are scaled to unit largest entry, then the reciprocal condition
/// number is estimated from an LU factorisation.
pub(crate) fn singular_to_rounding<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> bool {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    for row in b.iter_mut() {
        let m = row.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        if !(m > 0.0) || !m.is_finite() {
            return true;
        }
        row.iter_mut().for_each(|e| *e /= m);
    }
    for j in 0..N {
        let m = b.iter().fold(0.0f64, |m, row| m.max(row[j].abs()));
        if !(m > 0.0) {
            return true;
        }
        b.iter_mut().for_each(|row| row[j] /= m);
    }
    Lu::new(b).is_none_or(|lu| !(lu.reciprocal_condition() >= MIN_RCOND))
}

impl<const N: usize, const M: usize> Start<N, M> {
    /// Checks `(v, x)`: finite, valid inputs, F(v, x) ≈ 0 (refined by Newton to full
    /// precision; `v` may be approximate) and B regular to working precision, judged by a
    /// scale-free condition estimate (a start singular to rounding has no definite branch).
    ///
    /// Errors: [`SolveError::NonFinite`], [`SolveError::InvalidInput`],
    /// [`SolveError::SingularStart`] (B singular to working precision at the given or the
    /// refined point) and [`SolveError::InconsistentStart`] (`v` is not near a solution for `x`).
    ///
    /// ```
    /// use linkage::{Mechanism, Pose, SolveError, Start};
    /// # linkage::mechanism! {
    /// #     pub struct Rps;
    /// #     base {
    /// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
    /// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
    /// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    /// #     }
    /// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    /// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    /// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    /// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
    /// # }
    /// let rps = Rps::new();
    /// let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    /// let x = rps.inverse(&v, &[0.0; 3]).unwrap();
    /// let start = Start::new(&rps, v, x).unwrap();
    /// assert!(start.det() != 0.0 && start.x() == &x);
    /// // The platform in the base plane: B is singular there.
    /// let flat = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 0.0]));
    /// let legs = rps.inverse(&flat, &[0.0; 3]).unwrap();
    /// assert_eq!(Start::new(&rps, flat, legs), Err(SolveError::SingularStart));
    /// ```
    pub fn new<S: Mechanism<N, M>>(sys: &S, v: [f64; N], x: [f64; M]) -> Result<Self, SolveError> {
        if !all_finite(&v) || !all_finite(&x) {
            return Err(SolveError::NonFinite);
        }
        sys.validate_inputs(&x)
            .map_err(|input| SolveError::InvalidInput { input })?;
        let mut f0 = [0.0; N];
        sys.residual(&v, &x, &mut f0);
        if !all_finite(&f0) {
            return Err(SolveError::NonFinite);
        }
        let inconsistent = SolveError::InconsistentStart {
            residual_norm: norm(&f0),
        };
        // B singular to rounding at the given point: Newton cannot be trusted to refine it (it
        // may slide along the near-null direction and look merely inconsistent).
        if singular_to_rounding(sys, &v, &x) {
            return Err(SolveError::SingularStart);
        }
        let scale = crate::math::scale_or_one(norm(&v));
        let given = v;
        let mut v = v;
        // A factorisation that fails where B is regular by its scale-free condition failed on
        // det B alone, which over- or underflows for a machine declared at a scale a double
        // cannot hold its determinant at (a Stewart platform beyond about 1e±30): a value out
        // of range, not a singular start.
        let failed = |v: &[f64; N]| {
            if singular_to_rounding(sys, v, &x) {
                SolveError::SingularStart
            } else {
                SolveError::NonFinite
            }
        };
        let refined = |v: &[f64; N]| match correction(sys, v, &x) {
            Ok(c) => Ok(c),
            Err(Failure::Singular) => Err(failed(v)),
            Err(Failure::NonFinite) => Err(inconsistent),
        };
        let mut c = refined(&v)?;
        for _ in 0..8 {
            if c.size <= 1e-12 * scale {
                break;
            }
            for i in 0..N {
                v[i] -= c.delta[i];
            }
            c = refined(&v)?;
        }
        // Refinement may polish rounding, not move the start: a large move could land on
        // another assembly mode.
        let moved: [f64; N] = core::array::from_fn(|i| v[i] - given[i]);
        if norm(&moved) > 1e-3 * scale {
            return Err(inconsistent);
        }
        if c.det == 0.0 || !c.det.is_finite() || singular_to_rounding(sys, &v, &x) {
            return Err(failed(&v));
        }
        if c.size > 1e-6 * scale {
            return Err(inconsistent);
        }
        // `c` was computed at `v` itself: det B belongs to the stored point.
        let floor = crate::floor::Floor::at(sys, &v, &x, c.det);
        Ok(Start::accepted(v, x, c.det, floor))
    }

    /// A point the crate has itself accepted on a start's branch (a tracked sample, a
    /// converged solve, a point of a continuation path): consistent and regular as far as
    /// that acceptance showed, with det B measured at `v`, and the `floor` of the start of the
    /// branch ([`Self::floor`]). Not for unchecked input.
    pub(crate) fn accepted(v: [f64; N], x: [f64; M], det: f64, floor: crate::floor::Floor) -> Self {
        Start {
            v,
            x,
            det,
            scale: size(&v),
            floor,
        }
    }

    /// What is known of the rounding floor on the start's branch (`crate::floor`).
    pub(crate) fn floor(&self) -> &crate::floor::Floor {
        &self.floor
    }

    /// ‖v0‖.
    pub(crate) fn scale(&self) -> f64 {
        self.scale
    }

    /// The pivot coordinates v0, refined to full precision.
    pub fn v(&self) -> &[f64; N] {
        &self.v
    }

    /// The joint inputs x0.
    pub fn x(&self) -> &[f64; M] {
        &self.x
    }

    /// det B at `(v0, x0)`: its sign marks the start's branch.
    pub fn det(&self) -> f64 {
        self.det
    }
}

/// Options are checked against a start's scale, so the check that takes a start lives beside
/// it (options are a lower layer than the start, which reads them).
impl Options {
    /// Whether these options can be used from `start` (every solver and the tracker checks
    /// them so, and refuses with this error): a positive tolerance within
    /// [`MAX_RELATIVE_TOLERANCE`](Self::MAX_RELATIVE_TOLERANCE) of the start's size, and
    /// positive iteration and step counts. For a program that would rather say so once than
    /// for every solve.
    ///
    /// ```
    /// use linkage::{Options, SolveError, Start};
    /// # linkage::mechanism! {
    /// #     pub struct Rps;
    /// #     base {
    /// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
    /// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
    /// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    /// #     }
    /// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    /// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    /// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    /// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
    /// # }
    /// # use linkage::Mechanism;
    /// let rps = Rps::new();
    /// let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    /// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
    /// let start = Start::new(&rps, v0, x0).unwrap();
    /// assert_eq!(Options::TIGHT.check_for(&start), Ok(()));
    /// // A tolerance of 1 m on a platform 200 mm across would call anything converged.
    /// let loose = Options { tolerance: 1000.0, ..Options::TIGHT };
    /// assert!(matches!(loose.check_for(&start), Err(SolveError::InvalidOptions { .. })));
    /// ```
    pub fn check_for<const N: usize, const M: usize>(
        &self,
        start: &Start<N, M>,
    ) -> Result<(), SolveError> {
        self.check(start.scale())
    }
}

#[cfg(test)]
mod tests {
    use super::all_finite;

    #[test]
    fn all_finite_rejects_any_infinite_or_nan_entry() {
        assert!(all_finite(&[0.0, -1.0, 1e308, -1e308, 5e-324, -0.0]));
        assert!(all_finite::<0>(&[]));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..6 {
                let mut a = [1e308; 6];
                a[i] = bad;
                assert!(!all_finite(&a), "{a:?}");
            }
        }
    }
}
