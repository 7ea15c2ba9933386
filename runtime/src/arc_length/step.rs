//! Step control: how long the next step is, where it is predicted to land, and how its
//! outcome changes the length of the one after.

use super::path::{Point, Tangent};

/// The last accepted point before the current one, for the Hermite predictor.
#[derive(Clone, Copy)]
pub(super) struct Previous<const N: usize> {
    pub point: Point<N>,
    pub tangent: Tangent<N>,
    /// The chord from it to the current point.
    pub chord: f64,
    /// det B at it.
    pub det: f64,
}

/// One step, as predicted.
pub(super) struct Step<const N: usize> {
    /// The step's length along the tangent.
    pub length: f64,
    /// Whether it lands on λ = 1 (then the corrector works at fixed μ).
    pub end: bool,
    /// The length along the tangent to λ = 1 (infinite if the tangent does not head there).
    pub to_end: f64,
    pub predicted: Point<N>,
}

/// The length of the next step, within `[min, max]`.
pub(super) struct StepControl {
    h: f64,
    min: f64,
    max: f64,
    /// The last step was rejected: do not grow straight back into it.
    just_rejected: bool,
}

impl StepControl {
    /// For a path of `length` (μ at λ = 1).
    pub fn new(length: f64) -> Self {
        StepControl {
            h: length / 4.0,
            min: 1e-10 * length,
            max: length / 2.0,
            just_rejected: false,
        }
    }

    /// The next step from `p` along `t`, landing on μ = `length` when that is within reach.
    pub fn next<const N: usize>(
        &self,
        length: f64,
        p: &Point<N>,
        t: &Tangent<N>,
        previous: Option<&Previous<N>>,
    ) -> Step<N> {
        let to_end = if t.mu > 0.0 {
            (length - p.mu) / t.mu
        } else {
            f64::INFINITY
        };
        let end = to_end <= self.h;
        let step = if end { to_end } else { self.h };
        let mut pred = Point {
            v: p.v,
            mu: if end { length } else { p.mu + step * t.mu },
        };
        match previous {
            // Cubic Hermite extrapolation through the last two points and their tangents:
            // third-order accurate where Euler is first-order, so steps near a fold can be
            // longer. Only within one previous chord length, where it is reliable.
            Some(prev) if !end && step <= prev.chord => {
                let (p0, t0, chord) = (&prev.point, &prev.tangent, prev.chord);
                let u = 1.0 + step / chord;
                let (u2, u3) = (u * u, u * u * u);
                let (h00, h10, h01, h11) = (
                    2.0 * u3 - 3.0 * u2 + 1.0,
                    u3 - 2.0 * u2 + u,
                    -2.0 * u3 + 3.0 * u2,
                    u3 - u2,
                );
                for i in 0..N {
                    pred.v[i] =
                        h00 * p0.v[i] + h10 * chord * t0.v[i] + h01 * p.v[i] + h11 * chord * t.v[i];
                }
                pred.mu = h00 * p0.mu + h10 * chord * t0.mu + h01 * p.mu + h11 * chord * t.mu;
            }
            _ => {
                for i in 0..N {
                    pred.v[i] += step * t.v[i];
                }
            }
        }
        Step {
            length: step,
            end,
            to_end,
            predicted: pred,
        }
    }

    /// A step that was not the last ended past λ = 1 (the corrector moves μ too): λ = 1 is
    /// about a step away (this one, plus what the corrector added to μ), the next step lands
    /// on it.
    pub fn overshot<const N: usize>(&mut self, step: &Step<N>, t: &Tangent<N>) {
        self.h = if t.mu > 0.0 {
            step.to_end.max(step.length)
        } else {
            0.5 * step.length
        };
        self.just_rejected = true;
    }

    /// The tangent turned too far over the step.
    pub fn turned<const N: usize>(&mut self, step: &Step<N>) {
        self.h = step.length * 0.5;
        self.just_rejected = true;
    }

    /// The corrector failed.
    pub fn failed<const N: usize>(&mut self, step: &Step<N>) {
        self.h = 0.5 * step.length.min(self.h);
        self.just_rejected = true;
    }

    /// The step was accepted after `iterations` corrections, the first of size `first`.
    pub fn accepted<const N: usize>(&mut self, step: &Step<N>, first: f64, iterations: u32) {
        let step = step.length;
        // The Euler predictor's error grows like h²: aim the next first correction at a
        // twentieth of the step, changing h by at most a factor of two.
        let ideal = if first > 0.0 {
            0.05 * step * step / first
        } else {
            2.0 * step
        };
        // max and min rather than clamp, which panics on a NaN bound.
        self.h = ideal.max(0.5 * step).min(2.0 * step).min(self.max);
        // Right after a rejection, do not grow again: growing straight back into the step that
        // failed makes the step size oscillate.
        if iterations >= 4 || self.just_rejected {
            self.h = self.h.min(step);
        }
        self.just_rejected = false;
    }

    /// Where |det B| fell over the last chord (from `prev` to the current point, where it is
    /// `det`), the next step goes at most twice as far as det B = 0 lies by linear
    /// extrapolation. Two folds close together leave det B of one sign on either side; a step
    /// over both would not see them, and this keeps steps short where det B heads for zero.
    /// Twice, not once: a step must be able to pass a single fold for the sign change to show.
    /// `prev_det` is det B a chord `chord` back.
    pub fn toward_singularity(&mut self, prev_det: f64, chord: f64, det: f64) {
        let fall = prev_det.abs() - det.abs();
        if fall > 0.0 {
            let limit = 2.0 * chord * (det.abs() / fall);
            if limit < self.h {
                self.h = limit.max(self.min);
            }
        }
    }

    /// Whether the step has become too small to go on.
    pub fn too_small(&self) -> bool {
        self.h < self.min
    }
}

/// Whether det B, interpolated by the parabola through its values `d0` at the previous point
/// (a chord `c0` back), `d1` at the current point and `d2` at the corrected point (a chord `c1`
/// ahead), takes the other sign strictly between the current and the corrected point: two
/// folds within one step, which the signs at its ends alone cannot show.
pub(super) fn det_dips(d0: f64, c0: f64, d1: f64, c1: f64, d2: f64) -> bool {
    if !(c0 > 0.0 && c1 > 0.0 && d1 != 0.0) {
        return false;
    }
    // Relative to d1: no overflow in the squares below, whatever the scale of det B.
    let (e0, e2) = (d0 / d1, d2 / d1);
    let a = ((e0 - 1.0) * c1 + (e2 - 1.0) * c0) / (c0 * c1 * (c0 + c1));
    let b = ((e2 - 1.0) - a * c1 * c1) / c1;
    if !(a > 0.0) {
        // Opening away from zero (relative to d1 > 0): its extremum is a maximum.
        return false;
    }
    let s = -b / (2.0 * a);
    s > 0.0 && s < c1 && 1.0 - b * b / (4.0 * a) < 0.0
}

#[cfg(test)]
mod tests {
    use super::det_dips;

    #[test]
    fn a_dip_through_zero_between_the_points_is_seen() {
        // The stress suite's S-shaped segment (case 5441): det B 8.1e19, 7.9e17, 2.8e19 at
        // chords of 33.9: the parabola dips below zero within the step.
        assert!(det_dips(8.095e19, 33.87, 7.933e17, 33.87, 2.850e19));
        // The same values with the dip behind the current point: not within the step.
        assert!(!det_dips(2.850e19, 33.87, 7.933e17, 33.87, 8.095e19 * 10.0));
        // Monotone, or convex but staying positive: nothing.
        assert!(!det_dips(3.0, 1.0, 2.0, 1.0, 1.0));
        assert!(!det_dips(4.0, 1.0, 2.0, 1.0, 3.0));
        // Negative det B throughout, mirrored: the same verdicts.
        assert!(det_dips(-8.095e19, 33.87, -7.933e17, 33.87, -2.850e19));
        assert!(!det_dips(-4.0, 1.0, -2.0, 1.0, -3.0));
        // Huge determinants do not overflow into a false dip.
        assert!(!det_dips(4e300, 1.0, 2e300, 1.0, 3e300));
    }
}
