//! A factorisation of B = ∂F/∂v specialised to its sparsity pattern, planned at generation time.
//!
//! Entries of B that are nonzero numbers whatever the pose (the −1 of each rigid-body row in
//! Eq. 19) make perfect pivots. The plan takes as many of them as it can while keeping them
//! independent — no chosen pivot row has an entry in another chosen pivot column — so that
//! eliminating one never changes another, and the elimination is straight-line code with no
//! pivoting decisions. What remains is the Schur complement on the other rows and columns
//! (9×9 for the Stewart platform). Its rows and columns are put in a pivot order chosen here
//! ([`pivot_order`]), and [`Symbolic`] records where its LU factors have nonzeros in
//! that order, fill included, so that the emitted elimination touches only those.
//!
//! With S the chosen pivots (rows r_k, columns c_k, values p_k), R and C the other rows and
//! columns: B permuted to [[D, X], [Y, Z]] with D = diag(p_k), so
//! det B = sign · Π p_k · det(Z − Y D⁻¹ X), and the solve is forward elimination of the static
//! rows, a solve with the complement's factors, and back-substitution of the static unknowns.
//!
//! Before all this, a row whose entries share a numeric factor s (the 2 of a squared distance's
//! derivative) is divided by it: B = diag(s) B', so det B = Π s · det B' and the solve divides
//! that row's right-hand side by s, once, instead of multiplying s into every entry at every
//! factorisation.

pub mod pivot_order;

use crate::expr::Expr;

pub struct Plan {
    pub n: usize,
    /// B's nonzeros as factored: row r of ∂F/∂v divided by `row_scale[r]`.
    pub jac: Vec<(usize, usize, Expr)>,
    /// A numeric factor common to every entry of a row (the 2 of a squared distance's
    /// derivative), taken out so that it is not multiplied in at every iteration; 1 elsewhere.
    pub row_scale: Vec<f64>,
    /// `(row, column, value)` of each static pivot.
    pub statics: Vec<(usize, usize, f64)>,
    /// The Schur complement's rows and columns in pivot order: its k-th pivot is
    /// `(rows[k], cols[k])`.
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    /// Sign of the row and column permutations that bring B to the block form.
    pub sign: f64,
    /// The complement's LU in the pivot order.
    pub lu: Symbolic,
}

/// Structure of the complement and of its LU factors, indices in pivot order.
pub struct Symbolic {
    /// Structural nonzeros of the complement Z − Y D⁻¹ X.
    pub initial: Vec<Vec<bool>>,
    /// Structural nonzeros of L (below the diagonal) and U (on and above it), fill included.
    pub filled: Vec<Vec<bool>>,
}

impl Symbolic {
    pub fn of(initial: Vec<Vec<bool>>) -> Symbolic {
        let k = initial.len();
        let mut filled = initial.clone();
        for p in 0..k {
            // Every pivot is stored, even one that is structurally zero.
            filled[p][p] = true;
            for i in p + 1..k {
                if !filled[i][p] {
                    continue;
                }
                for j in p + 1..k {
                    if filled[p][j] {
                        filled[i][j] = true;
                    }
                }
            }
        }
        Symbolic { initial, filled }
    }

    pub fn size(&self) -> usize {
        self.initial.len()
    }

    /// Rows below pivot `p` with an entry in its column: where multipliers are formed.
    pub fn below(&self, p: usize) -> impl Iterator<Item = usize> + '_ {
        (p + 1..self.size()).filter(move |&i| self.filled[i][p])
    }

    /// Columns right of pivot `p` with an entry in its row: the pivot row's part of U.
    pub fn right(&self, p: usize) -> impl DoubleEndedIterator<Item = usize> + '_ {
        (p + 1..self.size()).filter(move |&j| self.filled[p][j])
    }

    /// `(multiplier-adds, multiplications, divisions)` of the elimination as emitted
    /// (`crate::emit::lu`): a multiplication per multiplier and per entry of U (stored divided
    /// by its pivot), and one more per pivot whose last update is written through its product.
    pub fn operations(&self) -> (usize, usize, usize) {
        let k = self.size();
        let (mut fma, mut mul) = (0, 0);
        for p in 0..k {
            let below = self.below(p).count();
            let right = self.right(p).count();
            mul += below + right;
            fma += below * right;
        }
        let through_product = (0..k)
            .filter(|&i| (0..i).any(|p| self.filled[i][p] && self.filled[p][i]))
            .count();
        (fma, mul + through_product, k)
    }
}

/// Plans the factorisation of B, whose nonzeros are `jac`. `sample`, B's values at one
/// configuration in `jac`'s order (the home configuration), lets the pivot order prefer large
/// pivots; without it the order follows the structure alone.
pub fn plan(n: usize, jac: &[(usize, usize, Expr)], sample: Option<&[f64]>) -> Plan {
    let statics = static_pivots(n, jac);
    let static_rows: Vec<usize> = statics.iter().map(|s| s.0).collect();
    let (jac, row_scale) = common_factors(n, jac, &static_rows);
    let sample: Option<Vec<f64>> = sample.map(|s| {
        jac.iter()
            .zip(s)
            .map(|((r, _, _), x)| x / row_scale[*r])
            .collect()
    });
    let sample = sample.as_deref();
    let jac = &jac[..];
    let rows: Vec<usize> = (0..n)
        .filter(|r| !statics.iter().any(|s| s.0 == *r))
        .collect();
    let cols: Vec<usize> = (0..n)
        .filter(|c| !statics.iter().any(|s| s.1 == *c))
        .collect();
    let mut nz = vec![vec![false; n]; n];
    for (r, c, _) in jac {
        nz[*r][*c] = true;
    }
    // The complement's pattern and, with a sample, its values.
    let value = |r: usize, c: usize| -> f64 {
        sample.map_or(0.0, |s| {
            jac.iter()
                .position(|(a, b, _)| *a == r && *b == c)
                .map_or(0.0, |k| s[k])
        })
    };
    let k = rows.len();
    let mut pattern = vec![vec![false; k]; k];
    let mut values = vec![vec![0.0; k]; k];
    for (ii, &i) in rows.iter().enumerate() {
        for (jj, &j) in cols.iter().enumerate() {
            pattern[ii][jj] = nz[i][j];
            values[ii][jj] = value(i, j);
            for &(r, c, p) in &statics {
                if nz[i][c] && nz[r][j] {
                    pattern[ii][jj] = true;
                    values[ii][jj] -= value(i, c) * value(r, j) / p;
                }
            }
        }
    }
    let order = crate::factor::pivot_order::choose(&pattern, sample.map(|_| values.as_slice()));
    let rows: Vec<usize> = order.iter().map(|&(i, _)| rows[i]).collect();
    let cols: Vec<usize> = order.iter().map(|&(_, j)| cols[j]).collect();
    let initial = order
        .iter()
        .map(|&(i, _)| order.iter().map(|&(_, j)| pattern[i][j]).collect())
        .collect();
    let row_order: Vec<usize> = statics
        .iter()
        .map(|s| s.0)
        .chain(rows.iter().copied())
        .collect();
    let col_order: Vec<usize> = statics
        .iter()
        .map(|s| s.1)
        .chain(cols.iter().copied())
        .collect();
    let sign = permutation_sign(&row_order) * permutation_sign(&col_order);
    Plan {
        n,
        jac: jac.to_vec(),
        row_scale,
        statics,
        rows,
        cols,
        sign,
        lu: Symbolic::of(initial),
    }
}

/// The entries that are nonzero numbers whatever the pose and can be pivots at once: no chosen
/// pivot row has an entry in another chosen pivot column.
fn static_pivots(n: usize, jac: &[(usize, usize, Expr)]) -> Vec<(usize, usize, f64)> {
    let mut nz = vec![vec![false; n]; n];
    for (r, c, _) in jac {
        nz[*r][*c] = true;
    }
    let mut statics: Vec<(usize, usize, f64)> = Vec::new();
    for (r, c, e) in jac {
        let Expr::Num(p) = e else { continue };
        if p.abs() < 1e-3 || statics.iter().any(|s| s.0 == *r || s.1 == *c) {
            continue;
        }
        if statics
            .iter()
            .all(|&(r2, c2, _)| !nz[*r][c2] && !nz[r2][*c])
        {
            statics.push((*r, *c, *p));
        }
    }
    statics
}

/// Row r of `jac` divided by the numeric factor its entries share (other than ±1), except
/// for the rows in `keep`; the factors.
fn common_factors(
    n: usize,
    jac: &[(usize, usize, Expr)],
    keep: &[usize],
) -> (Vec<(usize, usize, Expr)>, Vec<f64>) {
    let coefficient = |e: &Expr| match e {
        Expr::Num(c) => Some((*c, Expr::Num(1.0))),
        Expr::Product(fs) => match fs.first() {
            Some(Expr::Num(c)) => Some((*c, Expr::Product(fs[1..].to_vec()).simplify())),
            _ => None,
        },
        _ => None,
    };
    let mut scale = vec![1.0; n];
    for (r, s) in scale.iter_mut().enumerate() {
        if keep.contains(&r) {
            continue;
        }
        let mut entries = jac.iter().filter(|e| e.0 == r).map(|e| coefficient(&e.2));
        let Some(Some((c, _))) = entries.next() else {
            continue;
        };
        if c.abs() != 1.0
            && c.is_finite()
            && c != 0.0
            && entries.all(|e| e.is_some_and(|e| e.0 == c))
        {
            *s = c;
        }
    }
    let scaled = jac
        .iter()
        .map(|(r, c, e)| {
            let e = match coefficient(e) {
                Some((_, rest)) if scale[*r] != 1.0 => rest,
                _ => e.clone(),
            };
            (*r, *c, e)
        })
        .collect();
    (scaled, scale)
}

fn permutation_sign(p: &[usize]) -> f64 {
    let mut seen = vec![false; p.len()];
    let mut sign = 1.0;
    for start in 0..p.len() {
        if seen[start] {
            continue;
        }
        let mut len = 0;
        let mut i = start;
        while !seen[i] {
            seen[i] = true;
            i = p[i];
            len += 1;
        }
        if len % 2 == 0 {
            sign = -sign;
        }
    }
    sign
}

impl Plan {
    pub fn complement(&self) -> usize {
        self.rows.len()
    }
}

/// Floating-point operations of an expression as emitted: (additions, multiplications, calls).
pub fn count_ops(e: &Expr) -> (usize, usize, usize) {
    match e {
        Expr::Num(_) | Expr::Unknown(_) | Expr::Input(_) | Expr::Constant(_) => (0, 0, 0),
        Expr::Sum(ts) => ts
            .iter()
            .map(count_ops)
            .fold((ts.len().saturating_sub(1), 0, 0), add),
        Expr::Product(fs) => {
            let numeric_minus_one = matches!(fs.first(), Some(Expr::Num(n)) if *n == -1.0);
            let m = fs.len().saturating_sub(1) - usize::from(numeric_minus_one);
            fs.iter().map(count_ops).fold((0, m, 0), add)
        }
        Expr::Square(e) => add(count_ops(e), (0, 1, 0)),
        Expr::Sin(e) | Expr::Cos(e) => add(count_ops(e), (0, 0, 1)),
    }
}

fn add(a: (usize, usize, usize), b: (usize, usize, usize)) -> (usize, usize, usize) {
    (a.0 + b.0, a.1 + b.1, a.2 + b.2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutation_signs() {
        assert_eq!(permutation_sign(&[0, 1, 2]), 1.0);
        assert_eq!(permutation_sign(&[1, 0, 2]), -1.0);
        assert_eq!(permutation_sign(&[1, 2, 0]), 1.0);
    }

    #[test]
    fn static_pivots_are_independent() {
        // [[-1, a, 0], [b, c, d], [0, e, -1]]: both -1 usable (row 0 has no entry in col 2,
        // row 2 none in col 0).
        let jac = vec![
            (0, 0, Expr::Num(-1.0)),
            (0, 1, Expr::Unknown(0)),
            (1, 0, Expr::Unknown(1)),
            (1, 1, Expr::Unknown(2)),
            (1, 2, Expr::Unknown(0)),
            (2, 1, Expr::Unknown(1)),
            (2, 2, Expr::Num(-1.0)),
        ];
        let p = plan(3, &jac, None);
        assert_eq!(p.statics.len(), 2);
        assert_eq!((p.rows.clone(), p.cols.clone()), (vec![1], vec![1]));
    }

    #[test]
    fn fill_follows_the_elimination() {
        // An arrow pointing up-left fills everything; pointing down-right fills nothing.
        let arrow = |head: usize| -> Vec<Vec<bool>> {
            (0..3)
                .map(|i| (0..3).map(|j| i == j || i == head || j == head).collect())
                .collect()
        };
        let s = Symbolic::of(arrow(0));
        assert!(s.filled.iter().flatten().all(|&f| f));
        // 3 multipliers, 3 entries of U divided by their pivot, 2 pivots updated last through
        // their product.
        assert_eq!(s.operations(), (5, 8, 3));
        let s = Symbolic::of(arrow(2));
        assert_eq!(s.filled, s.initial);
        assert_eq!(s.operations(), (2, 5, 3));
    }
}
