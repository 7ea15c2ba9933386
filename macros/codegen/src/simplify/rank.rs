//! Mobility and redundancy by the rank of the constraint Jacobian at the home configuration.
//!
//! Grübler–Kutzbach counts constraints as if they were independent; over-constrained
//! mechanisms (planar or spherical ones declared in space, parallelograms) have dependent ones,
//! and it undercounts their freedom. At a configuration where the mechanism is assembled, the
//! rank of ∂F/∂(v, x) tells the truth: the mobility is `n + m − rank`, and ∂F/∂v must have full
//! column rank for the inputs to fix the pose. Equations dependent on earlier ones there are
//! dropped (listed as such), which leaves the square system the solvers need.

use crate::expr::{Expr, Var};
use nalgebra::DMatrix;

pub struct Ranked {
    /// The indices of the equations kept, in order.
    pub kept: Vec<usize>,
    /// Mobility `n + m − rank ∂F/∂(v, x)`.
    pub mobility: i64,
    /// Rank of ∂F/∂v over all equations.
    pub rank_v: usize,
}

fn independent(rows: &[Vec<f64>], row: &[f64]) -> Option<Vec<f64>> {
    // Gram–Schmidt against the rows kept so far (twice, for stability).
    let mut r = row.to_vec();
    let size = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..2 {
        for q in rows {
            let d: f64 = r.iter().zip(q).map(|(a, b)| a * b).sum();
            r.iter_mut().zip(q).for_each(|(a, b)| *a -= d * b);
        }
    }
    let left = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    (left > 1e-8 * size.max(1e-300)).then(|| r.iter().map(|x| x / left).collect())
}

fn rows(equations: &[Expr], vars: &[Var], v: &[f64], x: &[f64], c: &[f64]) -> Vec<Vec<f64>> {
    equations
        .iter()
        .map(|f| {
            let row: Vec<f64> = vars
                .iter()
                .map(|&var| f.derivative(var).eval(v, x, c))
                .collect();
            // Scale each row: an equation's units (mm or mm²) must not decide its rank.
            let s = row.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            if s > 0.0 {
                row.iter().map(|a| a / s).collect()
            } else {
                row
            }
        })
        .collect()
}

fn rank(rows: &[Vec<f64>]) -> usize {
    if rows.is_empty() || rows[0].is_empty() {
        return 0;
    }
    let m = DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j]);
    let sv = m.singular_values();
    let top = sv.max();
    sv.iter().filter(|s| **s > 1e-9 * top).count()
}

/// `order`: the order in which equations are offered to the basis (a permutation of their
/// indices); of dependent ones, the later is left out. `kept` is in the equations' own order.
pub fn at_home(
    equations: &[Expr],
    order: &[usize],
    n: usize,
    m: usize,
    v: &[f64],
    x: &[f64],
    c: &[f64],
) -> Ranked {
    let vars_v: Vec<Var> = (0..n).map(Var::Unknown).collect();
    let mut vars_all = vars_v.clone();
    vars_all.extend((0..m).map(Var::Input));
    let b = rows(equations, &vars_v, v, x, c);
    let mut kept = Vec::new();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for &i in order {
        if let Some(q) = b.get(i).and_then(|row| independent(&basis, row)) {
            basis.push(q);
            kept.push(i);
        }
    }
    kept.sort_unstable();
    let full = rows(equations, &vars_all, v, x, c);
    Ranked {
        kept,
        mobility: (n + m) as i64 - rank(&full) as i64,
        rank_v: basis.len(),
    }
}
