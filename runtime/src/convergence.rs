//! The two rules every iteration here is judged by: when Newton's method has converged
//! ([`Convergence`]), and when a corrector may be trusted to have stayed on its branch
//! ([`Contraction`]).

/// When Newton's method at fixed inputs stops.
///
/// A solve's answer is *converged* only at a point where the Newton correction, measured with
/// B factored at that very point, is at most the tolerance (see `newton::newton`): then the
/// residual, the error estimate and det B all belong to the returned point. (Newton–Raphson
/// may measure it with a chord correction instead, where B was factored so near that it
/// stands for the Newton correction: [`Chords`].)
///
/// For intermediate points (a Newton-homotopy step), [`Self::reached`] also accepts a correction
/// whose successor, extrapolated from the contraction so far (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≤ 0.1), would be
/// below the tolerance. [`Self::stalled`] says that the corrections stopped decreasing while
/// already below 1e-6 of the scale: the floor rounding sets near a singularity, where the
/// tolerance cannot be met — a distinct outcome ([`Status::ToleranceNotMet`](crate::solution::Status)),
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
/// (a chord, or simplified Newton, step) instead of factoring B again, and when such a
/// correction may measure the answer.
///
/// F has degree two in v, so Newton's corrections shrink as ‖Δₖ₊₁‖ ≈ q‖Δₖ‖²; q is estimated
/// from the last pair of corrections. B is affine in v, and over a distance d it changes, relative
/// to itself, by about 2q·d. A chord step from the point after Δₖ, with B factored before Δₖ,
/// shrinks the error by about 2q‖Δₖ‖ instead of squaring it. Where the next Newton correction
/// is predicted above the tolerance but a chord step predicted to bring the error within it,
/// the run takes the chord step ([`Chords::worthwhile`], [`Chords::admits`]): one factorisation
/// instead of two.
///
/// The answer is judged by a correction measured at the returned point: the Newton correction
/// with B factored there, or a chord correction with B factored at a point so near that B
/// differs by at most [`Chords::MEASURES`] (0.1 %) as predicted ([`Chords::vouched`]: the
/// simplified-Newton test of Deuflhard's affine-invariant Newton methods). The two differ by
/// that share: the chord correction, enlarged by four times it, must be within the tolerance,
/// and it is the error estimate reported. det B is then the one at the factored point, of the
/// same sign as at the returned point (B within 0.1 % of it). Wrong predictions cost a
/// correction, never the answer: a chord correction that does not vouch for the tolerance is
/// followed by a Newton correction at the same point, and the stress suite checks every answer
/// called converged against the root found in double-double arithmetic.
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
    /// Largest predicted relative change of B between the point it was factored at and a point
    /// whose chord correction is to stand for its Newton correction.
    const MEASURES: f64 = 1e-3;

    pub(crate) const fn new() -> Self {
        Chords {
            q: f64::NAN,
            newton: f64::NAN,
        }
    }

    /// The relative change of B predicted over a distance `moved` (NaN while q is unknown).
    fn change(&self, moved: f64) -> f64 {
        2.0 * self.q * moved
    }

    /// The Newton correction predicted after one of `size` (NaN while q is unknown).
    pub(crate) fn predicted(&self, size: f64) -> f64 {
        self.q * size * size
    }

    /// The error left by a chord correction of `size` from a point `moved` from where B was
    /// factored, as predicted.
    pub(crate) fn left_by_chord(&self, size: f64, moved: f64) -> f64 {
        self.change(moved) * size
    }

    /// Whether a chord correction at a point `moved` from where B was factored, whose error is
    /// predicted at `error`, is likely to vouch for the tolerance ([`Self::vouched`]): worth
    /// its residual and solve before the Newton correction that would otherwise measure it.
    pub(crate) fn may_finish(&self, error: f64, moved: f64, tolerance: f64) -> bool {
        // False while q is unknown (NaN).
        self.change(moved) <= Self::MEASURES && error <= tolerance
    }

    /// The error estimate a chord correction of `size` measures at a point `moved` from where
    /// B was factored, if it vouches for `tolerance`: B predicted to have changed by at most
    /// [`Self::MEASURES`], and the correction enlarged by four times that change within the
    /// tolerance (the Newton correction there is within the change of it).
    pub(crate) fn vouched(&self, size: f64, moved: f64, tolerance: f64) -> Option<f64> {
        // q as this correction shows it too, after the Newton correction before it: where q was
        // estimated from corrections far from the root, where B was well conditioned, it
        // understates B's change next to a singular root (seen: q = 0.0052 from corrections of
        // 2.97 and 0.046 predicted a change of 5e-4; the chord correction, 1.8e-4, was 16 times
        // the Newton correction q predicted and a tenth of the one at the point, 1.8e-3 above a
        // tolerance of 5e-4: NR answered ok there; stress seed 99999989, case 15039).
        // `max` keeps q where no Newton correction precedes (NaN).
        let change = 2.0 * self.q.max(size / (self.newton * self.newton)) * moved;
        if !(change <= Self::MEASURES) {
            return None;
        }
        let estimate = size / (1.0 - 4.0 * change);
        // NaN sizes are not within it.
        (estimate <= tolerance).then_some(estimate)
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
    /// The shortest predictor step, as a multiple of the error of the point it leaves, whose
    /// corrector can pass the first test: its first correction is about that error, and may be
    /// at most `FIRST` of the step.
    pub(crate) const SHORTEST_STEP_PER_ERROR: f64 = 1.0 / Self::FIRST;

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

    /// Stress seed 99999989, case 15039 (NR, `Linear::Generated`, tolerance 5e-4): Newton
    /// corrections of 2.97 and 0.046 estimate q = 0.0052, and the chord correction of 1.8e-4
    /// after the second vouched for the point, whose Newton correction was 1.8e-3. The chord
    /// correction itself shows q too small: it may not vouch.
    #[test]
    fn a_chord_correction_larger_than_q_predicts_does_not_vouch() {
        let mut c = Chords::new();
        c.newton(2.9737970191792726);
        c.newton(4.606310640184896e-2);
        assert!(
            c.vouched(1.80813716586652e-4, 4.606310640184896e-2, 5e-4)
                .is_none()
        );
        // As q predicts it (the quadratic regime): it vouches, as before.
        let predicted = c.predicted(4.606310640184896e-2);
        assert!(c.vouched(predicted, 4.606310640184896e-2, 5e-4).is_some());
    }

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
    fn a_chord_correction_measures_the_answer_only_where_b_barely_changed() {
        let tol = 1e-9;
        let mut c = Chords::new();
        assert_eq!(c.vouched(1e-12, 1e-5, tol), None, "q is not known yet");
        assert!(!c.may_finish(0.0, 1e-5, tol));
        c.newton(6.7e-2);
        c.newton(9.6e-6);
        // q ≈ 2.1e-3: the next Newton correction is predicted at 2e-13, and B changes by
        // 2q·9.6e-6 ≈ 4e-8 over the step.
        assert!(c.may_finish(c.predicted(9.6e-6), 9.6e-6, tol));
        let estimate = c.vouched(2.6e-13, 9.6e-6, tol).unwrap();
        assert!((2.6e-13..2.61e-13).contains(&estimate), "{estimate}");
        assert_eq!(
            c.vouched(1e-9, 9.6e-6, tol),
            None,
            "enlarged by the change of B, a correction at the tolerance exceeds it"
        );
        assert!(c.vouched(0.999e-9, 9.6e-6, tol).is_some());
        // A point 1 mm from where B was factored: B changed by 0.4 %, too much to stand for
        // the Newton correction there however small the chord correction.
        assert_eq!(c.vouched(1e-15, 1.0, tol), None);
        assert!(!c.may_finish(0.0, 1.0, tol));
        assert!(
            !c.may_finish(c.predicted(6.7e-2), 6.7e-2, tol),
            "predicted above it"
        );
        assert_eq!(c.vouched(f64::NAN, 9.6e-6, tol), None);
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
