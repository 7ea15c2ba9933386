//! One Newton correction `Δ = B⁻¹F` and Newton's method at fixed inputs, with the stopping
//! rule every solver shares.

use crate::lu::factor;
use crate::math::norm;
use crate::{Linear, Mechanism, Options};

/// When a Newton iteration has converged: the correction is below the tolerance; or the
/// next one, extrapolated from the contraction so far (θ = ‖Δₖ‖/‖Δₖ₋₁‖ ≤ 0.1), would be; or
/// the correction has stopped decreasing while already below 1e-6 of the scale — the floor that
/// rounding sets near a singularity, where a tighter tolerance cannot be met. Linear
/// convergence (ratio ½, as at a double root) keeps iterating.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Convergence {
    tolerance: f64,
    floor: f64,
    previous: f64,
    /// The estimated distance to the solution after the last correction.
    pub(crate) estimate: f64,
}

impl Convergence {
    pub(crate) fn new(tolerance: f64, v: &[f64]) -> Self {
        Convergence {
            tolerance,
            floor: 1e-6 * norm(v).max(1.0),
            previous: f64::INFINITY,
            estimate: f64::INFINITY,
        }
    }

    pub(crate) fn reached(&mut self, size: f64) -> bool {
        // No contraction is known before the second correction.
        let theta = if self.previous.is_finite() {
            (size / self.previous).min(1.0)
        } else {
            1.0
        };
        let stalled = size <= self.floor && size >= 0.9 * self.previous;
        self.estimate = size * theta;
        self.previous = size;
        size <= self.tolerance || (theta <= 0.1 && self.estimate <= self.tolerance) || stalled
    }
}

/// Newton's method at fixed `x` from `v`.
pub(crate) struct Newton<const N: usize> {
    pub v: [f64; N],
    pub converged: bool,
    /// B was singular at an iterate.
    pub singular: bool,
    pub iterations: u32,
    /// Estimated distance to the solution (see [`Convergence`]).
    pub estimate: f64,
    /// det B at the last iterate factored.
    pub det: f64,
}

pub(crate) fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: [f64; N],
    x: &[f64; M],
    options: &Options,
) -> Newton<N> {
    let mut out = Newton {
        v,
        converged: false,
        singular: false,
        iterations: 0,
        estimate: f64::INFINITY,
        det: 0.0,
    };
    let mut convergence = Convergence::new(options.tolerance, &v);
    let mut fac = sys.new_factor();
    while out.iterations < options.max_iterations {
        let Some((d, det, size)) = correction_in(sys, &out.v, x, options.linear, &mut fac) else {
            out.singular = true;
            break;
        };
        out.iterations += 1;
        out.det = det;
        for i in 0..N {
            out.v[i] -= d[i];
        }
        if convergence.reached(size) {
            out.converged = true;
            break;
        }
    }
    out.estimate = convergence.estimate;
    out
}

/// A Newton correction `Δ = B⁻¹ F` at `(v, x)` with the generated factorisation, and det B;
/// `None` if B is singular.
pub(crate) fn correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<([f64; N], f64, f64)> {
    correction_with(sys, v, x, Linear::Generated)
}

/// [`correction`] with the chosen linear solver.
pub(crate) fn correction_with<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    linear: Linear,
) -> Option<([f64; N], f64, f64)> {
    correction_in(sys, v, x, linear, &mut sys.new_factor())
}

/// [`correction_with`] reusing the factorisation storage of a loop.
pub(crate) fn correction_in<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    linear: Linear,
    fac: &mut S::Factor,
) -> Option<([f64; N], f64, f64)> {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let det = match linear {
        Linear::Generated => {
            let info = sys.factor(v, x, fac)?;
            sys.solve(fac, &mut f);
            info.det
        }
        Linear::Dense => {
            let mut b = [[0.0; N]; N];
            sys.jacobian_dense(v, x, &mut b);
            let piv = crate::lu::factor_dense(&mut b)?;
            crate::lu::solve_dense(&b, &piv, &mut f);
            piv.det
        }
    };
    // One pass gives the size callers need and rejects NaN or infinite corrections.
    let size = norm(&f);
    if !size.is_finite() {
        return None;
    }
    Some((f, det, size))
}

/// `‖B⁻¹ F‖` at `(v, x)`: the size of the next Newton correction, a first-order estimate of the
/// distance to the exact solution (the practical form of Eq. 13). Infinite where B is singular.
pub fn error_estimate<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    correction(sys, v, x).map_or(f64::INFINITY, |(_, _, size)| size)
}

/// det B at `(v, x)`; 0 where B is singular.
pub fn det_b<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    factor::<N, _>(&mut b).map_or(0.0, |p| p.det)
}

#[cfg(test)]
mod tests {
    use super::Convergence;

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

    #[test]
    fn linear_convergence_keeps_going_and_rounding_floors_stop() {
        let mut c = Convergence::new(1e-12, &[100.0]);
        for k in 0..20 {
            assert!(
                !c.reached(0.5f64.powi(k)),
                "ratio ½ must not count as stalled"
            );
        }
        let mut c = Convergence::new(1e-14, &[100.0]);
        assert!(!c.reached(1e-3));
        assert!(!c.reached(2e-8));
        assert!(c.reached(1.9e-8), "stalled below 1e-6 of the scale");
        assert!(c.estimate > 1e-9);
    }
}
