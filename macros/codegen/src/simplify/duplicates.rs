//! System-level simplification (Section 2.2): equations that repeat another (or its negation)
//! are removed. Single-unknown equations never survive the chain reductions in `chain`, which
//! solve and substitute them as they combine the pairs.

use crate::expr::Expr;

/// Removes equations structurally equal to an earlier one or to its negation; returns how
/// many were removed.
pub fn remove_duplicates(equations: &mut Vec<Expr>) -> usize {
    let before = equations.len();
    let mut kept: Vec<Expr> = Vec::with_capacity(before);
    for e in equations.drain(..) {
        let negated = e.clone().negated();
        if !kept.iter().any(|k| *k == e || *k == negated) {
            kept.push(e);
        }
    }
    *equations = kept;
    before - equations.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_and_negations_go() {
        let a = Expr::minus(Expr::Unknown(0), Expr::Constant(0));
        let b = Expr::minus(Expr::Unknown(1), Expr::Constant(0));
        let mut eqs = vec![a.clone(), b.clone(), a.clone(), a.clone().negated()];
        assert_eq!(remove_duplicates(&mut eqs), 2);
        assert_eq!(eqs, vec![a, b]);
    }
}
