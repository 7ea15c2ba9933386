//! The two rules every iteration here is judged by: when Newton's method has converged
//! ([`Convergence`]), and when a corrector may be trusted to have stayed on its branch
//! ([`Contraction`]).

/// When Newton's method at fixed inputs stops.
///
/// A solve's answer is *converged* only at a point where the Newton correction, measured with
/// B factored at that very point, is at most the tolerance (see `newton::newton`): then the
/// residual, the error estimate and det B all belong to the returned point.
///
/// For intermediate points (a Newton-homotopy step), [`Self::reached`] also accepts a correction
/// whose successor, extrapolated from the contraction so far (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≤ 0.1), would be
/// below the tolerance. [`Self::stalled`] says that the corrections stopped decreasing while
/// already below 1e-6 of the scale: the floor rounding sets near a singularity, where the
/// tolerance cannot be met — a distinct outcome ([`Status::ToleranceNotMet`](crate::Status)),
/// never a success. Linear convergence (ratio ½, as at a double root) keeps iterating.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Convergence {
    tolerance: f64,
    floor: f64,
    previous: f64,
    /// The estimated distance to the solution after the last correction.
    pub(crate) estimate: f64,
}

impl Convergence {
    #[cfg(test)]
    pub(crate) fn new<const N: usize>(tolerance: f64, v: &[f64; N]) -> Self {
        Self::with_scale(tolerance, crate::math::size(v))
    }

    /// For iterates of size about `scale` (‖v‖ of the start point).
    pub(crate) fn with_scale(tolerance: f64, scale: f64) -> Self {
        Convergence {
            tolerance,
            floor: 1e-6 * crate::math::scale_or_one(scale),
            previous: f64::INFINITY,
            estimate: f64::INFINITY,
        }
    }

    /// Records a correction of `size`; whether the point after it is within the tolerance as
    /// far as the contraction so far predicts (for intermediate points only).
    pub(crate) fn reached(&mut self, size: f64) -> bool {
        // No contraction is known before the second correction.
        let theta = if self.previous.is_finite() {
            (size / self.previous).min(1.0)
        } else {
            1.0
        };
        self.estimate = size * theta;
        self.previous = size;
        size <= self.tolerance || (theta <= 0.1 && self.estimate <= self.tolerance)
    }

    /// Whether a correction of `size`, following one of `previous`, shows the iteration has
    /// stopped improving at the rounding floor.
    pub(crate) fn stalled(&self, size: f64, previous: f64) -> bool {
        size <= self.floor && size >= 0.9 * previous
    }
}

/// When a Newton run under the final rule may reuse its last factorisation for one correction
/// (a chord, or simplified Newton, step) instead of factoring B again.
///
/// F has degree two in v, so Newton's corrections shrink as ‖Δₖ₊₁‖ ≈ q‖Δₖ‖²; q is estimated
/// from the last pair of corrections. A chord step from the point after Δₖ, with B factored
/// before Δₖ, shrinks the error by about 2q‖Δₖ‖ (B changed by that much, relatively) instead
/// of squaring it. Where the next Newton correction is predicted above the tolerance but a
/// chord step predicted to bring the error within it, the run takes the chord step and then
/// the one Newton correction that measures the returned point: one factorisation instead of
/// two. The answer is still judged by a correction with B factored at the returned point
/// itself; a chord step only moves the point, and only when it contracts strongly
/// ([`Chords::admits`]). Wrong predictions cost a correction, never the answer.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Chords {
    /// The estimate of q (NaN until two corrections are known).
    q: f64,
    /// The size of the last Newton correction, if the step after it was a Newton step.
    newton: f64,
}

impl Chords {
    /// Largest predicted contraction q‖Δ‖ at which a chord step is tried.
    const REGIME: f64 = 0.01;
    /// Largest ratio of a chord correction to the Newton correction before it.
    const RATIO: f64 = 0.25;

    pub(crate) const fn new() -> Self {
        Chords {
            q: f64::NAN,
            newton: f64::NAN,
        }
    }

    /// Records a Newton correction of `size` (the step after it to be taken).
    pub(crate) fn newton(&mut self, size: f64) {
        if self.newton.is_finite() {
            self.q = size / (self.newton * self.newton);
        }
        self.newton = size;
    }

    /// Whether, after the Newton correction of `size` just recorded, a chord step is predicted
    /// to save a factorisation.
    pub(crate) fn worthwhile(&self, size: f64, tolerance: f64) -> bool {
        let contraction = self.q * size;
        let next = contraction * size;
        // False while q is unknown (NaN).
        next > tolerance && contraction <= Self::REGIME && 2.0 * contraction * next <= tolerance
    }

    /// Whether a chord correction of `size` may be applied: it must contract strongly against
    /// the Newton correction before it. If it may, it is recorded (it measures the same error
    /// as a Newton correction would, to first order, so it updates q).
    pub(crate) fn admits(&mut self, size: f64) -> bool {
        if size <= Self::RATIO * self.newton {
            self.q = size / (self.newton * self.newton);
            // The correction after a chord step does not follow a Newton step.
            self.newton = f64::NAN;
            true
        } else {
            false
        }
    }
}

/// The test a corrector must pass to be trusted: its first correction at most half the
/// predictor step it corrects (plus the tolerance), each next at most a quarter of the one
/// before. A corrector that would slide onto a neighbouring branch converges slowly or not at
/// all from a predicted point far from its own root, and fails it. Pseudo-arc-length
/// continuation and the tracker apply this one rule.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Contraction {
    first_max: f64,
    previous: f64,
}

impl Contraction {
    /// Largest first correction, as a share of the predictor step.
    const FIRST: f64 = 0.5;
    /// Largest ratio of a correction to the one before.
    const RATIO: f64 = 0.25;

    /// For a corrector that starts from a predictor step of length `step`.
    pub(crate) fn new(step: f64, tolerance: f64) -> Self {
        Contraction {
            first_max: Self::FIRST * step.abs() + tolerance,
            previous: f64::INFINITY,
        }
    }

    /// Records the next correction of `size`; false if the corrector is not to be trusted.
    pub(crate) fn admits(&mut self, size: f64) -> bool {
        let ok = if self.previous.is_finite() {
            size <= Self::RATIO * self.previous
        } else {
            size <= self.first_max
        };
        self.previous = size;
        ok
    }
}

#[cfg(test)]
mod tests {
    use super::{Chords, Contraction, Convergence};

    #[test]
    fn a_first_large_correction_never_converges() {
        let mut c = Convergence::new(1e-10, &[100.0]);
        assert!(!c.reached(1e-9), "no contraction is known yet");
        assert!(c.estimate >= 1e-9);
    }

    #[test]
    fn quadratic_convergence_stops_one_step_early() {
        let mut c = Convergence::new(1e-10, &[100.0]);
        for size in [10.0, 1.0, 1e-2] {
            assert!(!c.reached(size));
        }
        assert!(
            c.reached(1e-6),
            "θ = 1e-4 predicts the next correction at 1e-10"
        );
        assert!(c.estimate <= 1e-10);
    }

    /// Defect 10 of issue 9: a correction that stopped decreasing at 2e-8 (above a 1e-14
    /// tolerance) used to count as converged. It is a stall now, never `reached`.
    #[test]
    fn a_stall_above_the_tolerance_is_not_convergence() {
        let mut c = Convergence::new(1e-14, &[100.0]);
        assert!(!c.reached(1e-3));
        assert!(!c.reached(2e-8));
        assert!(!c.reached(1.9e-8), "stalled above the tolerance");
        assert!(c.stalled(1.9e-8, 2e-8));
        assert!(!c.stalled(1e-8, 2e-8), "still halving");
        assert!(!c.stalled(2e-3, 2e-3), "above the rounding floor");
        let mut c = Convergence::new(1e-12, &[100.0]);
        for k in 0..20 {
            let size = 0.5f64.powi(k);
            assert!(!c.reached(size), "ratio ½ must not count as converged");
            assert!(!c.stalled(size, 2.0 * size), "nor as stalled");
        }
    }

    #[test]
    fn a_chord_step_is_taken_where_it_saves_a_factorisation() {
        let tol = 1e-9;
        let mut c = Chords::new();
        c.newton(1.7);
        assert!(
            !c.worthwhile(1.7, tol),
            "q is not known after one correction"
        );
        c.newton(1.2e-2);
        // q ≈ 4.2e-3: the next Newton correction is predicted at 6e-7 (above the tolerance),
        // the error after a chord step at 6e-11 (within it).
        assert!(c.worthwhile(1.2e-2, tol));
        assert!(!c.admits(0.5e-2), "a chord correction must contract by 4");
        assert!(c.admits(6.3e-7));
        assert!(!c.worthwhile(6.3e-7, tol), "no two chord steps in a row");
        c.newton(2e-11);
        assert!(
            !c.worthwhile(2e-11, tol),
            "the next correction is predicted within it"
        );
    }

    #[test]
    fn no_chord_step_outside_the_quadratic_regime() {
        let tol = 1e-9;
        // Linear convergence (ratio ½, a double root): q‖Δ‖ = ½.
        let mut c = Chords::new();
        c.newton(2e-3);
        c.newton(1e-3);
        assert!(!c.worthwhile(1e-3, tol));
        // Quadratic, but a chord step would leave the error above the tolerance.
        // (q ≈ 1.9e-3: the next Newton correction predicted at 8e-6, the error after a
        // chord step at 2e-9.)
        let mut c = Chords::new();
        c.newton(6.0);
        c.newton(6.7e-2);
        assert!(!c.worthwhile(6.7e-2, tol));
        let mut c = Chords::new();
        c.newton(1.0);
        c.newton(1e-2);
        assert!(!c.admits(f64::NAN));
        assert!(!Chords::new().worthwhile(f64::NAN, tol));
    }

    #[test]
    fn contraction_admits_fast_correctors_only() {
        let mut c = Contraction::new(1.0, 1e-10);
        assert!(c.admits(0.4) && c.admits(0.09) && c.admits(0.02));
        assert!(!c.admits(0.01), "ratio ½");
        let mut c = Contraction::new(-1.0, 1e-10);
        assert!(c.admits(0.4), "a step back counts by its length");
        assert!(!Contraction::new(1.0, 0.0).admits(0.6));
        assert!(!Contraction::new(1.0, 0.0).admits(f64::NAN));
    }
}
