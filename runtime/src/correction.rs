//! One Newton correction `Δ = B⁻¹F`, and Newton's method at fixed inputs ending by the rule
//! every solver shares.

use crate::convergence::Convergence;
use crate::lu::Lu;
use crate::math::norm;
use crate::{Linear, Mechanism, Options};

/// A Newton correction at a point, with what factoring B there told.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Correction<const N: usize> {
    /// `Δ = B⁻¹ F`: the point minus Δ is the next Newton iterate.
    pub delta: [f64; N],
    /// det B at the point.
    pub det: f64,
    /// ‖Δ‖, finite.
    pub size: f64,
}

/// Why no correction could be computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Failure {
    /// B is singular (or so near it that Δ overflows) at finite values.
    Singular,
    /// The point, the inputs or F there are not finite: the values have overflowed.
    NonFinite,
}

/// A Newton correction at `(v, x)` with the generated factorisation.
pub(crate) fn correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Result<Correction<N>, Failure> {
    correction_in(sys, v, x, Linear::Generated, &mut sys.new_factor())
}

/// [`correction`] with the chosen linear solver, reusing the factorisation storage of a loop.
pub(crate) fn correction_in<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    linear: Linear,
    fac: &mut S::Factor,
) -> Result<Correction<N>, Failure> {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let factored = match linear {
        Linear::Generated => sys.factor(v, x, fac).map(|info| {
            sys.solve(fac, &mut f);
            info.det
        }),
        Linear::Dense => {
            let mut b = [[0.0; N]; N];
            sys.jacobian_dense(v, x, &mut b);
            Lu::new(b).map(|lu| {
                lu.solve(&mut f);
                lu.det()
            })
        }
    };
    // One pass gives the size callers need and rejects NaN or infinite corrections.
    let size = norm(&f);
    match factored {
        Some(det) if size.is_finite() => Ok(Correction {
            delta: f,
            det,
            size,
        }),
        // Only on failure: tell overflow from singularity.
        _ => Err(failure(sys, v, x)),
    }
}

fn failure<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Failure {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    if norm(v).is_finite() && norm(x).is_finite() && norm(&f).is_finite() {
        Failure::Singular
    } else {
        Failure::NonFinite
    }
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

/// `‖B⁻¹ F‖` at `(v, x)`: the size of the next Newton correction, a first-order estimate of the
/// distance to the exact solution (the practical form of Eq. 13). Infinite where B is singular
/// or the values are not finite.
pub fn error_estimate<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    correction(sys, v, x).map_or(f64::INFINITY, |c| c.size)
}

/// det B at `(v, x)`; 0 where B is singular or not finite.
pub fn det_b<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    Lu::new(b).map_or(0.0, |lu| lu.det())
}
