//! Newton's method at fixed inputs, ending by the rule every solver shares ([`newton`]), and
//! Newton–Raphson (the paper's NRA), which is that method on F(v, x*) = 0 from the start's v.
//! Fast, and with no notion of branch: near a singularity it may converge to another
//! assembly mode. The det B sign check catches some of those, not all.

use crate::convergence::Convergence;
use crate::correction::{correction_in, Failure};
use crate::math::norm;
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

pub(crate) fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: [f64; N],
    x: &[f64; M],
    options: &Options,
    rule: Rule,
) -> Newton<N> {
    let mut out = Newton {
        v,
        ending: Ending::Exhausted,
        iterations: 0,
        estimate: f64::INFINITY,
        det: 0.0,
    };
    // With the final rule `out` holds the best point factored so far (smallest correction):
    // what a stall or an exhausted run returns.
    let mut current = v;
    let mut previous = f64::INFINITY;
    let mut convergence = Convergence::new(options.tolerance, &v);
    let mut fac = sys.new_factor();
    while out.iterations < options.max_iterations {
        let c = match correction_in(sys, &current, x, options.linear, &mut fac) {
            Ok(c) => c,
            Err(Failure::Singular) => {
                return Newton {
                    v: current,
                    ending: Ending::Singular,
                    estimate: f64::INFINITY,
                    det: 0.0,
                    ..out
                };
            }
            Err(Failure::NonFinite) => {
                out.ending = Ending::NonFinite;
                break;
            }
        };
        out.iterations += 1;
        match rule {
            Rule::Final => {
                if c.size <= options.tolerance {
                    out.v = current;
                    out.ending = Ending::Converged;
                    out.estimate = c.size;
                    out.det = c.det;
                    return out;
                }
                if c.size < out.estimate {
                    out.v = current;
                    out.estimate = c.size;
                    out.det = c.det;
                }
                if convergence.stalled(c.size, previous) {
                    out.ending = Ending::Stalled;
                    break;
                }
                for i in 0..N {
                    current[i] -= c.delta[i];
                }
            }
            Rule::Intermediate => {
                for i in 0..N {
                    current[i] -= c.delta[i];
                }
                let stalled = convergence.stalled(c.size, previous);
                if convergence.reached(c.size) || stalled {
                    out.v = current;
                    out.det = c.det;
                    out.estimate = convergence.estimate;
                    out.ending = Ending::Converged;
                    return out;
                }
            }
        }
        previous = c.size;
    }
    // Without a best point: the last iterate if finite, else the start point.
    let factored = rule == Rule::Final && out.estimate.is_finite();
    if !factored && norm(&current).is_finite() {
        out.v = current;
    }
    out
}
