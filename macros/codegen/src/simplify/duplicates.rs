//! System-level simplification (Section 2.2): equations that repeat another (or its negation)
//! are removed. Single-unknown equations never survive the chain reductions in `chain`, which
//! solve and substitute them as they combine the pairs.

use crate::expr::Expr;

/// Removes equations structurally equal to an earlier one or to its negation; returns the
/// indices of those kept.
pub fn remove_duplicates(equations: &mut Vec<Expr>) -> Vec<usize> {
    let mut kept: Vec<Expr> = Vec::with_capacity(equations.len());
    let mut indices = Vec::with_capacity(equations.len());
    for (i, e) in equations.drain(..).enumerate() {
        let negated = e.clone().negated();
        if !kept.iter().any(|k| *k == e || *k == negated) {
            kept.push(e);
            indices.push(i);
        }
    }
    *equations = kept;
    indices
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_and_negations_go() {
        let a = Expr::minus(Expr::Unknown(0), Expr::Constant(0));
        let b = Expr::minus(Expr::Unknown(1), Expr::Constant(0));
        let mut eqs = vec![a.clone(), b.clone(), a.clone(), a.clone().negated()];
        assert_eq!(remove_duplicates(&mut eqs), [0, 1]);
        assert_eq!(eqs, vec![a, b]);
    }
}
