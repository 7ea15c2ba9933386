//! The homotopy path in `y = (v, μ)`: its points, tangents, and H and its derivatives there.

use crate::math::norm;
use crate::{Linear, Mechanism, Start};

/// The straight joint-space segment from the start to the target, parametrised by
/// μ = λ‖Δv‖ (see the module docs of `arc_length`).
pub(super) struct Path<'a, S, const N: usize, const M: usize> {
    pub sys: &'a S,
    pub start: &'a Start<N, M>,
    /// x* − x0.
    pub dx: [f64; M],
    /// μ at λ = 1.
    pub length: f64,
    /// The corrector's tolerance.
    pub tol: f64,
    pub linear: Linear,
}

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
/// to first order.
pub(super) fn first_order_travel<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    dx: &[f64; M],
) -> Option<f64> {
    let mut fac = sys.new_factor();
    sys.factor(start.v(), start.x(), &mut fac)?;
    let mut y = [0.0; N];
    sys.input_derivative(start.v(), start.x(), dx, &mut y);
    sys.solve(&fac, &mut y);
    let travel = norm(&y);
    (travel.is_finite() && travel > 1e-12 * norm(dx).max(1e-300)).then_some(travel)
}
