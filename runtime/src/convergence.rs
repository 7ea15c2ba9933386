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
            floor: 1e-6 * scale.max(1.0),
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
    use super::{Contraction, Convergence};

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
