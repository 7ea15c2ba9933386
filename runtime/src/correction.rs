//! One Newton correction `Δ = B⁻¹F` at a point, and what factoring B there tells.

use crate::lu::Lu;
use crate::math::norm;
use crate::{Linear, Mechanism};

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
