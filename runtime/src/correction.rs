//! One Newton correction `Δ = B⁻¹F` at a point, and what factoring B there tells.

use crate::lu::Lu;
use crate::math::{norm, size};
use crate::mechanism::Mechanism;
use crate::solution::Linear;
use crate::turns::Turns;

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

impl<const N: usize> Correction<N> {
    /// Storage for [`Self::update`].
    pub(crate) const fn new() -> Self {
        Correction {
            delta: [0.0; N],
            det: 0.0,
            size: f64::INFINITY,
        }
    }

    /// The correction at `(v, x)`, computed in place with the chosen linear solver and the
    /// factorisation storage of a loop; `t` = `sys.turns(x)`. On failure the fields are
    /// unspecified.
    #[inline(always)]
    pub(crate) fn update<S: Mechanism<N, M>, const M: usize>(
        &mut self,
        sys: &S,
        v: &[f64; N],
        x: &[f64; M],
        t: &Turns<M>,
        linear: Linear,
        fac: &mut S::Factor,
    ) -> Result<(), Failure> {
        let det = match linear {
            Linear::Generated => sys
                .newton_step(v, x, t, fac, &mut self.delta)
                .map(|i| i.det),
            Linear::Dense => dense_step(sys, v, x, &mut self.delta),
        };
        // One pass gives the size callers need and rejects NaN or infinite corrections.
        self.size = size(&self.delta);
        match det {
            Some(det) if self.size.is_finite() => {
                self.det = det;
                Ok(())
            }
            // Only on failure: tell overflow from singularity.
            _ => Err(failure(sys, v, x)),
        }
    }

    /// The simplified (chord) correction at `(v, x)`: `B₀⁻¹ F(v)` with B₀ the factorisation
    /// already in `fac` (of a point one correction away). It costs a residual and a solve, no
    /// factorisation; `det` is left as it was (B₀'s). On failure the fields are unspecified.
    // Out of line: inlined into the Newton loop beside the Newton correction's kernels, it made
    // the loop's code worse than the call costs (`count nr-normal` 785 539 against 746 200).
    #[inline(never)]
    pub(crate) fn chord<S: Mechanism<N, M>, const M: usize>(
        &mut self,
        sys: &S,
        v: &[f64; N],
        x: &[f64; M],
        t: &Turns<M>,
        fac: &S::Factor,
    ) -> Result<(), Failure> {
        let delta = &mut self.delta;
        crate::dispatch::fastest(|| sys.residual_turned(v, x, t, delta));
        crate::dispatch::fastest(|| sys.solve(fac, delta));
        self.size = size(&self.delta);
        if self.size.is_finite() {
            Ok(())
        } else {
            Err(failure(sys, v, x))
        }
    }
}

/// [`Mechanism::newton_step`] with dense LU on the assembled B (the baseline).
#[inline(never)]
fn dense_step<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    delta: &mut [f64; N],
) -> Option<f64> {
    sys.residual(v, x, delta);
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let lu = Lu::new(b)?;
    lu.solve(delta);
    Some(lu.det())
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
    let mut c = Correction::new();
    let mut turned = Turns::NONE;
    c.update(sys, v, x, Turns::of(sys, x, &mut turned), linear, fac)?;
    Ok(c)
}

#[cold]
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
    dense_b(sys, v, x).map_or(0.0, |lu| lu.det())
}

/// B at `(v, x)` as a dense matrix, factored with partial pivoting (`None` where it is
/// singular): the baseline `det_b` and the reference path measure with.
pub(crate) fn dense_b<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<Lu<N>> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    Lu::new(b)
}
