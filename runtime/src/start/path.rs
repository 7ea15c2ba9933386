//! What the two ways of carrying a start to a new geometry share ([`Start::follow`] along the
//! residual, [`Start::follow_geometry`] along the change of geometry itself): their limits,
//! and a corrector trusted only where it contracts and det B keeps the branch's sign.
//!
//! [`Start::follow`]: super::Start::follow
//! [`Start::follow_geometry`]: super::Start::follow_geometry

use super::singular_to_rounding;
use crate::convergence::Contraction;
use crate::math::size;
use crate::mechanism::Mechanism;

/// Attempts (accepted and rejected steps together) before the path is given up.
pub(super) const MAX_STEPS: u32 = 400;
/// The smallest step of the path's parameter; below it the path is given up (a fold: no
/// solution on this branch for the new geometry, or one only across a singularity).
pub(super) const MIN_STEP: f64 = 1e-6;
/// Newton iterations per step.
const MAX_ITERATIONS: u32 = 12;
/// An intermediate point is accepted once its correction is within this share of ‖v‖; the
/// last is refined to full precision by [`Start::new`](super::Start::new).
pub(super) const PATH_TOLERANCE: f64 = 1e-9;

/// Newton's method on F(·, x) − `shift` for `sys` from `predicted`, trusted only while it
/// contracts (its first correction within half the predictor's `length`, each next within a
/// quarter of the one before) and det B keeps the branch's `sign`. The point reached, unless
/// rounding leaves its branch undecided there (no place to go on from).
#[allow(clippy::too_many_arguments)]
pub(super) fn correct<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    x: &[f64; M],
    shift: &[f64; N],
    predicted: [f64; N],
    length: f64,
    sign: f64,
    tolerance: f64,
    fac: &mut S::Factor,
) -> Option<[f64; N]> {
    let mut w = predicted;
    let mut contraction = Contraction::new(length, tolerance);
    for _ in 0..MAX_ITERATIONS {
        let info = sys.factor(&w, x, fac)?;
        if info.det.signum() != sign || !info.det.is_finite() {
            return None;
        }
        let mut delta = [0.0; N];
        sys.residual(&w, x, &mut delta);
        for (d, s) in delta.iter_mut().zip(shift) {
            *d -= s;
        }
        sys.solve(fac, &mut delta);
        let size = size(&delta);
        if !size.is_finite() || !contraction.admits(size) {
            return None;
        }
        for (wi, d) in w.iter_mut().zip(&delta) {
            *wi -= d;
        }
        if size <= tolerance {
            return (!singular_to_rounding(sys, &w, x)).then_some(w);
        }
    }
    None
}
