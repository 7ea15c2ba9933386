//! Newton's method at fixed inputs, ending by the rule every solver shares ([`newton`]), and
//! Newton–Raphson (the paper's NRA), which is that method on F(v, x*) = 0 from the start's v.
//! Fast, and with no notion of branch: near a singularity it may converge to another
//! assembly mode. The det B sign check catches some of those, not all.

use crate::convergence::Convergence;
use crate::correction::{Correction, Failure};
use crate::math::size;
use crate::outcome::{conclude, Account};
use crate::{Mechanism, Options, Solution, SolveError, Start};

/// Solves F(v, x) = 0 by Newton's method from `start.v`.
///
/// ```
/// use linkage::{newton_raphson, Mechanism, Options, Pose, Start, Status};
///
/// linkage::mechanism! {
///     /// A 3-RPS: three hinged legs of variable length carry a triangular platform.
///     pub struct Rps;
///     base {
///         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
///         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
///         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
///     }
///     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
///     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
///     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
///     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// }
///
/// let rps = Rps::new();
/// // Start: platform level, 150 mm up; its leg lengths from inverse kinematics.
/// let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// let start = Start::new(&rps, v0, x0).unwrap();
/// let sol = newton_raphson(&rps, &start, &[160.0, 155.0, 158.0], &Options::TIGHT).unwrap();
/// assert_eq!(sol.status, Status::Converged);
/// assert!((rps.inverse(&sol.v, &x0).unwrap()[1] - 155.0).abs() < 1e-9);
/// ```
pub fn newton_raphson<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    // F at the start is Newton's first residual: its overflow shows there, not in a check.
    crate::start::check_sample(sys, start, x, options)?;
    let run = newton(sys, *start.v(), x, options, Rule::Final);
    if run.ending == Ending::NonFinite && run.iterations == 0 {
        return Err(SolveError::NonFinite);
    }
    let account = Account {
        iterations: run.iterations,
        ..Account::at(1.0)
    };
    Ok(conclude(sys, start, &run, x, account))
}

/// How a Newton run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ending {
    /// Final rule: the correction measured at the returned point is within the tolerance.
    /// Intermediate rule: the point is within it as far as the contraction predicts.
    Converged,
    /// The corrections stopped decreasing at the rounding floor, above the tolerance.
    Stalled,
    /// B was singular at an iterate.
    Singular,
    /// The iterates overflowed.
    NonFinite,
    /// The iteration limit came first.
    Exhausted,
}

/// Which stopping rule a Newton run follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rule {
    /// For an answer: stop at a point whose own correction is within the tolerance and return
    /// that point, so that its error estimate and det B are measured there, not extrapolated.
    Final,
    /// For a point on the way (a homotopy step): the extrapolated estimate suffices, and a
    /// stall at the rounding floor is good enough to go on from.
    Intermediate,
}

/// Newton's method at fixed `x` from `v`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Newton<const N: usize> {
    /// The point reached: with the final rule, the last point B was factored at (or the best
    /// one, for a stall); never a non-finite point.
    pub v: [f64; N],
    pub ending: Ending,
    pub iterations: u32,
    /// ‖B⁻¹F‖ at `v` (final rule), or its extrapolation (intermediate rule).
    pub estimate: f64,
    /// det B at `v` (final rule), or at the iterate before the last correction (intermediate).
    pub det: f64,
}

/// The smallest correction met so far, at the best point factored so far: what a stall or an
/// exhausted run returns under the final rule.
#[derive(Clone, Copy)]
struct Best {
    estimate: f64,
    det: f64,
}

pub(crate) fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: [f64; N],
    x: &[f64; M],
    options: &Options,
    rule: Rule,
) -> Newton<N> {
    let tolerance = options.tolerance;
    let mut convergence = Convergence::new(tolerance, &v);
    let mut fac = sys.new_factor();
    let mut c = Correction::new();
    let mut current = v;
    let mut best: Option<Best> = None;
    // The best point is `current` itself until the step moves it, then `best_v`: it is copied
    // only as the step is taken, and only while the corrections keep shrinking.
    let mut best_v = v;
    let mut best_here = false;
    let mut iterations = 0;
    let mut previous = f64::INFINITY;
    let ending = loop {
        if iterations >= options.max_iterations {
            break Ending::Exhausted;
        }
        match c.update(sys, &current, x, options.linear, &mut fac) {
            Ok(()) => {}
            Err(Failure::Singular) => {
                return Newton {
                    v: current,
                    ending: Ending::Singular,
                    iterations,
                    estimate: f64::INFINITY,
                    det: 0.0,
                };
            }
            Err(Failure::NonFinite) => break Ending::NonFinite,
        }
        iterations += 1;
        if rule == Rule::Final {
            if c.size <= tolerance {
                return Newton {
                    v: current,
                    ending: Ending::Converged,
                    iterations,
                    estimate: c.size,
                    det: c.det,
                };
            }
            if best.as_ref().is_none_or(|b| c.size < b.estimate) {
                best = Some(Best {
                    estimate: c.size,
                    det: c.det,
                });
                best_here = true;
            }
            if convergence.stalled(c.size, previous) {
                break Ending::Stalled;
            }
        }
        if best_here {
            // One pass copies and steps (clippy sees only the copy).
            #[allow(clippy::manual_memcpy)]
            for i in 0..N {
                best_v[i] = current[i];
                current[i] -= c.delta[i];
            }
            best_here = false;
        } else {
            for i in 0..N {
                current[i] -= c.delta[i];
            }
        }
        if rule == Rule::Intermediate {
            let stalled = convergence.stalled(c.size, previous);
            if convergence.reached(c.size) || stalled {
                return Newton {
                    v: current,
                    ending: Ending::Converged,
                    iterations,
                    estimate: convergence.estimate,
                    det: c.det,
                };
            }
        }
        previous = c.size;
    };
    match best {
        Some(b) => Newton {
            v: if best_here { current } else { best_v },
            ending,
            iterations,
            estimate: b.estimate,
            det: b.det,
        },
        // The last iterate if finite, else the start point.
        None => Newton {
            v: if size(&current).is_finite() {
                current
            } else {
                v
            },
            ending,
            iterations,
            estimate: f64::INFINITY,
            det: 0.0,
        },
    }
}
