//! The model's first-order kinematics at its home configuration: v̇ = −B⁻¹ (∂F/∂x) ẋ with
//! B = ∂F/∂v, evaluated where the generated `from_geometry` and `home_start` put the
//! configuration (`model::reference::configuration`).

use crate::generator::V3;
use linkage_codegen::expr::{Expr, Var};
use linkage_codegen::model::{reference, Model};
use nalgebra::{DMatrix, DVector};

pub struct Home {
    pub v: Vec<f64>,
    pub x: Vec<f64>,
    pub c: Vec<f64>,
    /// The largest |F_i(v0, x0)| over the squared length scale of (v0, x0).
    pub residual: f64,
}

pub fn home(model: &Model) -> Result<Home, String> {
    let (v, x, c) = reference::configuration(model, model.home_pose)?;
    let scale = v.iter().chain(&x).fold(1.0f64, |m, a| m.max(a.abs()));
    let residual = model
        .equations
        .iter()
        .map(|f| f.eval(&v, &x, &c).abs())
        .fold(0.0, f64::max)
        / (scale * scale);
    Ok(Home { v, x, c, residual })
}

/// Each platform point of the model: its name, its home position and its velocity for input
/// rates `xdot` (in the model's input order).
pub fn platform_rates(
    model: &Model,
    h: &Home,
    xdot: &[f64],
) -> Result<Vec<(String, V3, V3)>, String> {
    let (n, m) = (model.unknowns.len(), model.inputs.len());
    if model.equations.len() != n {
        return Err(format!(
            "{} equations for {n} unknowns",
            model.equations.len()
        ));
    }
    // ∂F/∂v by central differences of a whole unit: F is of degree ≤ 2 in v, so they are
    // exact up to rounding (and far cheaper than the symbolic derivatives in a debug build);
    // ∂F/∂x symbolically (the inputs enter through sines and cosines).
    let mut b = DMatrix::zeros(n, n);
    let users = unknowns_used(model);
    let mut v = h.v.clone();
    for c in 0..n {
        for &r in &users[c] {
            let f = &model.equations[r];
            v[c] = h.v[c] + 1.0;
            let plus = f.eval(&v, &h.x, &h.c);
            v[c] = h.v[c] - 1.0;
            let minus = f.eval(&v, &h.x, &h.c);
            v[c] = h.v[c];
            b[(r, c)] = (plus - minus) / 2.0;
        }
    }
    let mut fx = DMatrix::zeros(n, m);
    for (r, f) in model.equations.iter().enumerate() {
        for c in 0..m {
            if f.depends_on(Var::Input(c)) {
                fx[(r, c)] = f.derivative(Var::Input(c)).eval(&h.v, &h.x, &h.c);
            }
        }
    }
    let rhs = -(fx * DVector::from_column_slice(xdot));
    let vdot = b.lu().solve(&rhs).ok_or("∂F/∂v is singular at home")?;
    Ok(model
        .points
        .iter()
        .enumerate()
        .map(|(p, pt)| {
            let at = [0, 1, 2].map(|a| h.v[model.unknown(p, a)]);
            let rate = [0, 1, 2].map(|a| vdot[model.unknown(p, a)]);
            (pt.name.clone(), at, rate)
        })
        .collect())
}

/// The model's unknowns at inputs `x` (the model's order), by Newton on F from home along the
/// straight line from home's inputs, following home's branch (`crate::path::follow`).
pub fn solve(model: &Model, h: &Home, x: &[f64]) -> Result<Vec<f64>, crate::path::Stop> {
    let at = |t: f64| -> Vec<f64> { h.x.iter().zip(x).map(|(a, b)| a + t * (b - a)).collect() };
    let users = unknowns_used(model);
    // dv/dt = −B⁻¹ ∂F/∂t, ∂F/∂t by central differences in t (for the prediction only).
    let tangent = |t: f64, v: &[f64]| -> Result<Vec<f64>, String> {
        let e = 1e-6;
        let (plus, minus) = (at(t + e), at(t - e));
        let ft = DVector::from_iterator(
            v.len(),
            model
                .equations
                .iter()
                .map(|f| (f.eval(v, &plus, &h.c) - f.eval(v, &minus, &h.c)) / (2.0 * e)),
        );
        let b = jacobian(model, &users, v, &at(t), &h.c);
        let d = b.lu().solve(&(-ft)).ok_or("∂F/∂v is singular on the way")?;
        Ok(d.iter().copied().collect())
    };
    crate::path::follow(h.v.clone(), tangent, |t, v| newton(model, h, &at(t), v))
}

/// How far from the exact root at `x` a point `v` that Newton on F accepted may be by
/// rounding alone: F's terms are of the squared length scale and round at about 1e-15 of it,
/// and ∂F/∂v's smallest singular value turns that into a distance (a random mechanism's F
/// can be ill-conditioned where its screws are not: σmin/σmax 1.5e-9 at seed 1548621083's
/// step, whose answer the oracle's differs from by 2.7e-6 mm).
pub fn rounding_reach(model: &Model, h: &Home, x: &[f64], v: &[f64]) -> f64 {
    let users = unknowns_used(model);
    let scale = v.iter().chain(x).fold(1.0f64, |m, a| m.max(a.abs()));
    let smallest = jacobian(model, &users, v, x, &h.c).singular_values().min();
    1e-15 * scale * scale / smallest
}

/// ∂F/∂v at (v, x) by central differences of a whole unit: F is of degree ≤ 2 in v, so they are
/// exact up to rounding.
fn jacobian(model: &Model, users: &[Vec<usize>], v: &[f64], x: &[f64], c: &[f64]) -> DMatrix<f64> {
    let n = v.len();
    let mut b = DMatrix::zeros(n, n);
    let mut w = v.to_vec();
    for col in 0..n {
        for &r in &users[col] {
            let e = &model.equations[r];
            w[col] = v[col] + 1.0;
            let plus = e.eval(&w, x, c);
            w[col] = v[col] - 1.0;
            let minus = e.eval(&w, x, c);
            w[col] = v[col];
            b[(r, col)] = (plus - minus) / 2.0;
        }
    }
    b
}

fn newton(model: &Model, h: &Home, x: &[f64], mut v: Vec<f64>) -> Result<Vec<f64>, String> {
    let n = model.unknowns.len();
    let users = unknowns_used(model);
    let scale = v.iter().fold(1.0f64, |m, a| m.max(a.abs()));
    let residual = |v: &[f64]| -> DVector<f64> {
        DVector::from_iterator(n, model.equations.iter().map(|e| e.eval(v, x, &h.c)))
    };
    for _ in 0..60 {
        let f = residual(&v);
        let b = jacobian(model, &users, &v, x, &h.c);
        let step = b.lu().solve(&(-&f)).ok_or("∂F/∂v is singular on the way")?;
        // Converged when the step is negligible, or when F is down to its rounding (F is of
        // degree ≤ 2 in lengths of `scale`: its terms round at about 1e-16·scale²). Where
        // ∂F/∂v is ill-conditioned the step never gets small: it is that rounding times the
        // inverse's norm (seen: |F| ≈ 1e-11 while the step wanders at 1e-7 of a 250 mm
        // scale). The comparison with the oracle's positions after it is what checks the
        // answer.
        let rounded = f.norm() < 1e-14 * scale * scale;
        if step.norm() < 1e-10 * scale || rounded {
            v.iter_mut().zip(step.iter()).for_each(|(a, d)| *a += d);
            return Ok(v);
        }
        // Halved while it does not reduce the residual (an internal link can swing far for a
        // small step of the inputs near a fold of its own).
        let mut t = 1.0;
        let trial = loop {
            let w: Vec<f64> = v.iter().zip(step.iter()).map(|(a, d)| a + t * d).collect();
            if residual(&w).norm() < f.norm() || t < 1e-3 {
                break w;
            }
            t /= 2.0;
        };
        v = trial;
    }
    Err("Newton on F does not converge".into())
}

/// For each unknown, the equations that mention it.
fn unknowns_used(model: &Model) -> Vec<Vec<usize>> {
    fn walk(e: &Expr, out: &mut Vec<usize>) {
        match e {
            Expr::Unknown(i) => out.push(*i),
            Expr::Num(_) | Expr::Input(_) | Expr::Constant(_) => {}
            Expr::Sum(ts) | Expr::Product(ts) => ts.iter().for_each(|t| walk(t, out)),
            Expr::Square(t) | Expr::Sin(t) | Expr::Cos(t) => walk(t, out),
        }
    }
    let mut users = vec![Vec::new(); model.unknowns.len()];
    for (r, f) in model.equations.iter().enumerate() {
        let mut seen = Vec::new();
        walk(f, &mut seen);
        seen.sort_unstable();
        seen.dedup();
        for u in seen {
            users[u].push(r);
        }
    }
    users
}
