//! The homotopy path in `y = (v, μ)`: its points, tangents, and H and its derivatives there.

use crate::math::norm;
use crate::mechanism::Mechanism;
use crate::solution::Linear;
use crate::start::Start;

/// The straight joint-space segment from the start to the target, parametrised by
/// μ = λ‖Δv‖ (see the module docs of `arc_length`).
pub(super) struct Path<'a, S, const N: usize, const M: usize> {
    pub sys: &'a S,
    pub start: &'a Start<N, M>,
    /// x* − x0.
    pub dx: [f64; M],
    /// μ at λ = 1.
    pub length: f64,
    /// The corrector's tolerance on a long step: 1e-6 of the larger of |v| and `length`.
    pub tol: f64,
    /// Its least value on a short step: 1e-6 of |v| (see [`Path::tolerance`]).
    pub fine: f64,
    pub linear: Linear,
}

/// The corrector's tolerance as a share of the step (see [`Path::tolerance`]).
const STEP_SHARE: f64 = 1e-2;

/// A point `(v, μ)` of the path.
#[derive(Clone, Copy)]
pub(super) struct Point<const N: usize> {
    pub v: [f64; N],
    pub mu: f64,
}

/// A direction in `(v, μ)`: a unit tangent, or the row bordering B.
#[derive(Clone, Copy)]
pub(super) struct Tangent<const N: usize> {
    pub v: [f64; N],
    pub mu: f64,
}

pub(super) fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p * q).sum()
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    /// The joint inputs at μ.
    pub fn x(&self, mu: f64) -> [f64; M] {
        let l = mu / self.length;
        let mut x = [0.0; M];
        for j in 0..M {
            x[j] = self.start.x()[j] + l * self.dx[j];
        }
        x
    }

    /// The corrector's tolerance for a step of length `step`: at most a hundredth of the step,
    /// and no less than `fine`. A point accepted further from the curve than the step is long
    /// makes the tangent there, and the turn test, meaningless: with `tol` alone (1e-6 of a
    /// first-order travel of 3.5e5 from a nearly singular random start, so 0.35), steps of 0.06
    /// down to 6e-5 were each accepted 0.09 off a sharply bent curve, at a tangent turned 56°
    /// from the last, and refused by the turn test until the step was too small: a reachable
    /// target refused (stress seed 20261201, case 3446). Long steps keep `tol`.
    pub fn tolerance(&self, step: f64) -> f64 {
        self.tol.min(STEP_SHARE * step).max(self.fine)
    }

    /// `λ` at `p`.
    pub fn lambda(&self, p: &Point<N>) -> f64 {
        p.mu / self.length
    }

    /// H at `p`.
    pub fn residual(&self, p: &Point<N>) -> [f64; N] {
        let mut f = [0.0; N];
        self.sys.residual(&p.v, &self.x(p.mu), &mut f);
        f
    }

    /// H_μ at `p`: `(∂F/∂x)(x* − x0) / ‖Δv‖`.
    pub fn column(&self, p: &Point<N>) -> [f64; N] {
        let mut c = [0.0; N];
        self.sys
            .input_derivative(&p.v, &self.x(p.mu), &self.dx, &mut c);
        for c in &mut c {
            *c /= self.length;
        }
        c
    }
}

/// ‖B⁻¹ (∂F/∂x) dx‖ at the start, if B is regular there: how far v moves over the whole path
/// to first order. With `check`, the factorisation also measures the start's own Newton
/// correction ‖B⁻¹ F(v0, x0)‖ first (one residual and one solve more): a start that is not a
/// solution for the mechanism it is given (made before `set_geometry`) is refused with
/// [`SolveError::InconsistentStart`](crate::solution::SolveError::InconsistentStart), as
/// [`crate::start::check_consistent`] says.
pub(super) fn first_order_travel<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    dx: &[f64; M],
    check: bool,
) -> Result<Option<f64>, crate::solution::SolveError> {
    let mut fac = sys.new_factor();
    if sys.factor(start.v(), start.x(), &mut fac).is_none() {
        // B singular here, where `Start::new` found it regular: judged (and refused) as
        // another mechanism's start.
        if check {
            crate::start::check_consistent(sys, start)?;
        }
        return Ok(None);
    }
    if check {
        crate::start::consistent_with(sys, start, &fac)?;
    }
    let mut y = [0.0; N];
    sys.input_derivative(start.v(), start.x(), dx, &mut y);
    sys.solve(&fac, &mut y);
    let travel = norm(&y);
    Ok((travel.is_finite() && travel > 1e-12 * norm(dx).max(1e-300)).then_some(travel))
}
