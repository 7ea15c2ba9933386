//! A factorisation of B = ∂F/∂v specialised to its sparsity pattern, planned at generation time.
//!
//! Entries of B that are nonzero numbers whatever the pose (the −1 of each rigid-body row in
//! Eq. 19) make perfect pivots. The plan takes as many of them as it can while keeping them
//! independent — no chosen pivot row has an entry in another chosen pivot column — so that
//! eliminating one never changes another, and the elimination is straight-line code with no
//! pivoting decisions. What remains is the Schur complement on the other rows and columns,
//! small and dense (9×9 for the Stewart platform), factored at run time with partial pivoting.
//!
//! With S the chosen pivots (rows r_k, columns c_k, values p_k), R and C the other rows and
//! columns: B permuted to [[D, X], [Y, Z]] with D = diag(p_k), so
//! det B = sign · Π p_k · det(Z − Y D⁻¹ X), and the solve is forward elimination of the static
//! rows, a dense solve on the complement, and back-substitution of the static unknowns.

use crate::expr::Expr;

pub struct Plan {
    pub n: usize,
    /// `(row, column, value)` of each static pivot.
    pub statics: Vec<(usize, usize, f64)>,
    /// The Schur complement's rows and columns, in order.
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    /// Sign of the row and column permutations that bring B to the block form.
    pub sign: f64,
}

pub fn plan(n: usize, jac: &[(usize, usize, Expr)]) -> Plan {
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
    let rows: Vec<usize> = (0..n)
        .filter(|r| !statics.iter().any(|s| s.0 == *r))
        .collect();
    let cols: Vec<usize> = (0..n)
        .filter(|c| !statics.iter().any(|s| s.1 == *c))
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
        statics,
        rows,
        cols,
        sign,
    }
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
        let p = plan(3, &jac);
        assert_eq!(p.statics.len(), 2);
        assert_eq!((p.rows.clone(), p.cols.clone()), (vec![1], vec![1]));
    }
}
