//! Following home's solution branch along the finite step, for the model's Newton on F and for
//! the oracle's loop closure alike.
//!
//! Ten fixed steps, each solved from the last, were not enough either way. Near a fold a step
//! can land on another branch: seed 1548616563 (a hexapod) folds at 0.442 of its step, and the
//! oracle's loop closure, stepping from 0.4 to 0.5, closed on another assembly and went on to
//! the end, while Newton on F stopped (and, taken in halves, landed on that same assembly
//! too). Or a step fails to converge on home's own branch: seed 1548616513 folds just beyond
//! its step (3% further), and Newton on F did not converge from 0.9 to 1.0 although the
//! branch is there (in a hundred steps it agrees with the oracle to 1e-8 mm).
//!
//! So each step starts from the first-order prediction (the branch's tangent, from the
//! solver's own Jacobian) and is kept only where the answer is closer to the prediction than
//! half the predicted move: on a branch, the correction shrinks as the square of the step and
//! the move as the step, so some step always passes; a jump to another branch, or a branch
//! about to fold (where the tangent grows without bound), does not pass. A step that does not
//! pass, or whose solve fails, is halved; one that must be shorter than [`SHORTEST`] ends the
//! path with an `Err`: the branch from home folds there (or the solver cannot follow it), for
//! the caller to compare with the other side.
//!
//! "Some step always passes" needs a tangent of some size: where it nearly vanishes (a driven
//! hinge at a dead point of the platform's motion) the move is second order, as the correction
//! is, and the step that passes is shorter than the tangent over the curvature. Two rules
//! cover that: within twice the curvature met so far, where the tangent has shrunk on the way
//! (seed 202152299); and, at the point where no step has passed yet, a correction that is a
//! quarter of the one at twice the step, as a vector (seed 202613499, home itself at the dead
//! point): the answers at both steps lie on one smooth branch through the point, tangent to the
//! prediction. A jump to another branch, at the longer step or at both, does not scale so.

/// The first step's length, as a fraction of the whole: the ten steps the sweep took before.
const FIRST: f64 = 0.1;

/// The shortest step tried (1/640 of the whole: six halvings of [`FIRST`]).
const SHORTEST: f64 = FIRST / 64.0;

/// Below this (radians or millimetres, in the largest coordinate) a correction is rounding,
/// whatever the predicted move.
const ROUNDING: f64 = 1e-9;

/// Where and why a path stopped short of the end.
#[derive(Debug)]
pub struct Stop {
    /// The fraction of the step reached.
    pub at: f64,
    pub why: String,
}

impl std::fmt::Display for Stop {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(
            f,
            "stops at {:.4} of the step ({}): its branch from home folds there, or the solver cannot follow it",
            self.at, self.why
        )
    }
}

fn apart(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
}

/// Follows the branch from `start`, the solution at t = 0, to t = 1. `tangent(t, s)`: the
/// branch's derivative in t at the solution `s`; `solve(t, from)`: the solution at `t` by a
/// local method started at `from`.
pub fn follow(
    start: Vec<f64>,
    tangent: impl Fn(f64, &[f64]) -> Result<Vec<f64>, String>,
    mut solve: impl FnMut(f64, Vec<f64>) -> Result<Vec<f64>, String>,
) -> Result<Vec<f64>, Stop> {
    let (mut t, mut s, mut h) = (0.0f64, start, FIRST);
    // The largest correction over the square of its step among the steps kept by the
    // prediction (the path's curvature as met so far), and the tangent's size at the start.
    let mut curvature: Option<f64> = None;
    let mut speed: Option<f64> = None;
    // The correction (answer less prediction) of the step tried last from this t, refused, if
    // its solve converged: the next try is at half that step.
    let mut longer: Option<Vec<f64>> = None;
    while t < 1.0 {
        let step = h.min(1.0 - t);
        let slope = tangent(t, &s).map_err(|why| Stop { at: t, why })?;
        let predicted: Vec<f64> = s.iter().zip(&slope).map(|(a, d)| a + step * d).collect();
        let why = match solve(t + step, predicted.clone()) {
            Ok(next) => {
                let (moved, corrected) = (apart(&predicted, &s), apart(&next, &predicted));
                let correction: Vec<f64> =
                    next.iter().zip(&predicted).map(|(a, p)| a - p).collect();
                let start_speed = *speed.get_or_insert(moved / step);
                // Or, where the tangent has shrunk to less than half its size at the start,
                // within twice what the curvature met so far predicts: where the path's
                // tangent vanishes (a driven hinge near a dead point moves the rest to second
                // order only: seed 202152299), the move shrinks and the correction does not,
                // and no step would pass. Not where the tangent grows (a fold, across which a
                // step would close on another assembly: seed 1548616563), nor by more than
                // the curvature allows (a jump to another branch, a distance of its own).
                let fits = corrected <= 0.5 * moved + ROUNDING;
                let curved = moved / step < 0.5 * start_speed
                    && curvature.is_some_and(|c| corrected <= 2.0 * c * step * step);
                // Or, at the point where no step has passed yet (so no curvature is known),
                // where the tangent nearly vanishes: the correction, second order in the step,
                // is a quarter of the one at twice the step, to within a quarter of that (the
                // third-order terms), and the curvature they show is the path's. A Sarrus
                // linkage whose driven hinge is at a dead point at home (seed 202613499: the
                // model's unknowns move 0.026 mm to first order over the whole step, the
                // corrections are 0.11 mm at a tenth of it and fall by 3.6 to 3.98 per halving)
                // passed no step by the other rules, where the oracle's joint values, moving to
                // first order, went on.
                let quarter = curvature.is_none()
                    && longer.as_ref().is_some_and(|d| {
                        let four: Vec<f64> = correction.iter().map(|c| 4.0 * c).collect();
                        apart(d, &four) <= 0.25 * d.iter().fold(0.0f64, |m, c| m.max(c.abs()))
                    });
                if fits || curved || quarter {
                    if fits || quarter {
                        let c = corrected / (step * step);
                        curvature = Some(curvature.map_or(c, |k| k.max(c)));
                    }
                    longer = None;
                    s = next;
                    t = if 1.0 - (t + step) < 1e-12 {
                        1.0
                    } else {
                        t + step
                    };
                    h = (2.0 * h).min(FIRST);
                    continue;
                }
                longer = Some(correction);
                format!(
                    "the answer is {corrected:.1e} from the prediction, which moved {moved:.1e}"
                )
            }
            Err(e) => {
                longer = None;
                e
            }
        };
        if step <= SHORTEST * (1.0 + 1e-9) {
            return Err(Stop { at: t, why });
        }
        h = step / 2.0;
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Newton on x² = c from `from`.
    fn root(c: f64, from: f64) -> Result<f64, String> {
        let mut x = from;
        for _ in 0..60 {
            let f = x * x - c;
            if f.abs() < 1e-15 {
                return Ok(x);
            }
            x -= f / (2.0 * x);
        }
        Err("no convergence".into())
    }

    /// x² = 1 − 2t from x = 1 folds at t = 1/2: the path stops just short of it. x² = 1 + t
    /// is followed to the end, on its positive branch.
    #[test]
    fn a_fold_stops_the_path_and_a_regular_branch_is_followed() {
        let e = follow(
            vec![1.0],
            |_, s| Ok(vec![-1.0 / s[0]]),
            |t, from| root(1.0 - 2.0 * t, from[0]).map(|x| vec![x]),
        )
        .expect_err("the branch ends at t = 1/2");
        assert!((0.48..0.5).contains(&e.at), "{e}");
        let x = follow(
            vec![1.0],
            |_, s| Ok(vec![0.5 / s[0]]),
            |t, from| root(1.0 + t, from[0]).map(|x| vec![x]),
        )
        .unwrap();
        assert!((x[0] - 2f64.sqrt()).abs() < 1e-15);
    }

    /// x = 1 + 1e-4 t + 10 t² (a tangent of 1e-4 at the start, a curvature of 10): no step
    /// down to the shortest passes by its prediction (the correction 10 h² against half the
    /// move, 5e-5 h), but each correction is a quarter of the one at twice the step, and the
    /// path goes on to the end. With the solver jumping to x + 1 from the start at steps longer
    /// than 0.02, the first step kept is shorter than that.
    #[test]
    fn a_vanishing_tangent_at_the_start_is_followed() {
        let x = |t: f64| 1.0 + 1e-4 * t + 10.0 * t * t;
        let end = follow(
            vec![1.0],
            |t, _| Ok(vec![1e-4 + 20.0 * t]),
            |t, _| Ok(vec![x(t)]),
        )
        .unwrap();
        assert!((end[0] - x(1.0)).abs() < 1e-12, "{end:?}");
        // The points steps were tried from, in order (the tangent is asked for at each try).
        let passed = std::cell::RefCell::new(Vec::new());
        let mut from_start = true;
        let end = follow(
            vec![1.0],
            |t, _| {
                passed.borrow_mut().push(t);
                Ok(vec![1e-4 + 20.0 * t])
            },
            |t, _| {
                from_start &= passed.borrow().iter().all(|&p| p == 0.0);
                let jump = if from_start && t > 0.02 { 1.0 } else { 0.0 };
                Ok(vec![x(t) + jump])
            },
        )
        .unwrap();
        assert!((end[0] - x(1.0)).abs() < 1e-12, "{end:?}");
        let passed = passed.into_inner();
        let first = passed.iter().find(|&&p| p > 0.0);
        assert!(first.is_some_and(|&p| p < 0.02), "{passed:?}");
    }

    /// A solver that jumps to another branch (here the negative root, as if from far off) is
    /// caught by the prediction, not followed.
    #[test]
    fn a_jump_to_another_branch_is_not_followed() {
        let e = follow(
            vec![1.0],
            |_, s| Ok(vec![0.5 / s[0]]),
            |t, from| {
                let x = root(1.0 + t, from[0])?;
                Ok(vec![if t > 0.3 { -x } else { x }])
            },
        )
        .expect_err("the jump at 0.3 is refused");
        assert!(e.why.contains("from the prediction"), "{e}");
        assert!((0.2..=0.3).contains(&e.at), "{e}");
    }
}
