//! The constraint Jacobian's entries, differentiated once and evaluated at many
//! configurations: at home by the rank test, along the motion by its check; and the measures
//! both judge rows by (dependence, rounding, the condition of the rows kept).

use super::tape::Tape;
use crate::expr::{Expr, Var};
use nalgebra::DMatrix;

/// Below this fraction of its size off the span of the rows kept, a row is dependent on them.
pub const DEPENDENT: f64 = 1e-8;

/// The smallest singular value of the rows kept over their largest.
pub fn condition(b: &[Vec<f64>], kept: &[usize]) -> f64 {
    if kept.is_empty() || b[0].is_empty() {
        return 0.0;
    }
    let m = DMatrix::from_fn(kept.len(), b[0].len(), |i, j| b[kept[i]][j]);
    let sv = m.singular_values();
    sv.min() / sv.max().max(1e-300)
}

/// Below this σmin/σmax of the rows kept each in its turn, the rank test tries the other
/// choice. Not always: the choice in turn is what the listing promises (the pairs' equations
/// before the links'), and it decides more than the condition at home — on the planar 3-RPR
/// and 3-RRR declared in space, the other choice, though 50× better conditioned there (1e-5
/// against 7e-4), gave a square system of 12 roots for the mechanism's 6.
pub const NEARLY_SINGULAR: f64 = 1e-7;

/// Below this fraction of the rounding scale (an equation's [`Expr::magnitude`] over the
/// length scale), a row is rounding alone: the equation holds identically at home, whatever
/// the unknowns. (A ball joint at a spherical mechanism's centre, held by a link an active R
/// turns about an axis through it: its coefficients off the axes are 1e-16, and scaled up to
/// a row of size 1 they added a random rank, refusing the mechanism as locked.)
pub const ROUNDING: f64 = 1e-12;

/// ∂F/∂v's (or ∂F/∂x's) entries, sparse.
pub struct Derivatives<'a> {
    pub equations: &'a [Expr],
    /// For each equation, the columns of its nonzero derivatives.
    columns_of: Vec<Vec<usize>>,
    /// The nonzero derivatives, row by row.
    tape: Tape,
    pub columns: usize,
}

/// A matrix's rows, sparse: each row's columns and values.
pub type Sparse = Vec<Vec<(usize, f64)>>;

impl<'a> Derivatives<'a> {
    pub fn new(equations: &'a [Expr], vars: &[Var]) -> Self {
        let entries: Vec<Vec<(usize, Expr)>> = equations
            .iter()
            .map(|f| {
                vars.iter()
                    .enumerate()
                    .map(|(k, &var)| (k, f.derivative(var)))
                    .filter(|(_, d)| !d.is_zero())
                    .collect()
            })
            .collect();
        Derivatives {
            equations,
            tape: Tape::new(entries.iter().flatten().map(|(_, d)| d)),
            columns_of: entries
                .iter()
                .map(|row| row.iter().map(|(k, _)| *k).collect())
                .collect(),
            columns: vars.len(),
        }
    }

    /// The operations an evaluation takes.
    pub fn size(&self) -> usize {
        self.tape.len()
    }

    /// The matrix at `(v, x)`.
    pub fn sparse(&self, v: &[f64], x: &[f64], c: &[f64]) -> Sparse {
        let mut values = Vec::new();
        self.tape.eval(v, x, c, &mut values);
        let mut values = values.into_iter();
        self.columns_of
            .iter()
            .map(|row| {
                row.iter()
                    .map(|&k| (k, values.next().unwrap_or(0.0)))
                    .collect()
            })
            .collect()
    }

    /// The rows at `(v, x)`, dense, each scaled to its largest entry: an equation's units (mm
    /// or mm²) must not decide its rank. A row of rounding alone (see [`ROUNDING`]) is zero.
    pub fn rows(&self, v: &[f64], x: &[f64], c: &[f64]) -> Vec<Vec<f64>> {
        Self::side_by_side(&[self], v, x, c)
    }

    /// The rows of the same equations' derivatives by several sets of variables, side by side
    /// (∂F/∂v then ∂F/∂x: ∂F/∂(v, x), each set differentiated once), scaled together as
    /// [`Self::rows`] scales one.
    pub fn side_by_side(parts: &[&Self], v: &[f64], x: &[f64], c: &[f64]) -> Vec<Vec<f64>> {
        let Some(first) = parts.first() else {
            return Vec::new();
        };
        let width = parts.iter().map(|p| p.columns).sum();
        let mut rows = vec![vec![0.0; width]; first.equations.len()];
        let mut offset = 0;
        for part in parts {
            debug_assert_eq!(part.equations.len(), rows.len());
            for (row, entries) in rows.iter_mut().zip(part.sparse(v, x, c)) {
                for (k, d) in entries {
                    row[offset + k] = d;
                }
            }
            offset += part.columns;
        }
        let length = 1.0 + v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        for (f, row) in first.equations.iter().zip(&mut rows) {
            let s = row.iter().fold(0.0f64, |m, a| m.max(a.abs()));
            if s * length <= ROUNDING * f.magnitude(v, x, c) {
                row.fill(0.0);
            } else if s > 0.0 {
                row.iter_mut().for_each(|a| *a /= s);
            }
        }
        rows
    }
}
