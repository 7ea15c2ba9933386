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
        self.h = ideal.clamp(0.5 * step, 2.0 * step).min(self.max);
        // Right after a rejection, do not grow again: growing straight back into the step that
        // failed makes the step size oscillate.
        if iterations >= 4 || self.just_rejected {
            self.h = self.h.min(step);
        }
        self.just_rejected = false;
    }

    /// Whether the step has become too small to go on.
    pub fn too_small(&self) -> bool {
        self.h < self.min
    }
}
