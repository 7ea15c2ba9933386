//! Which static pivots' unknowns are affine functions of the others: the rows a Newton
//! iteration can satisfy exactly by construction instead of carrying them as equations.
//!
//! A static row (see [`crate::factor`]) whose entries of ∂F/∂v do not depend on v is affine
//! in v: F_r = S(v_kept, x) ± v_c, with S the row's other terms. Setting v_c = ∓S — the
//! "lift" — makes F_r exactly 0 in floating point, not merely to rounding, when S is
//! evaluated with the same operations in the same order as the residual evaluates it: the
//! residual is then S − S (or S + (−S)). The pass therefore accepts a row only in the form the
//! residual emits as `S − v_c` or `S + v_c`: a sum whose last term is ±v_c, with pivot ±1, and
//! v_c in no other term. For the Stewart platform these are the nine rigid-body rows of
//! Eq. 19 (x_G2 = E1 x_G1 + E2 x_G3 + E3 x_G5, …).
//!
//! At a lifted point the static rows' right-hand sides are exactly zero, so the Newton
//! correction needs neither those rows' residuals nor the forward elimination of their
//! right-hand sides: [`crate::emit_reduced`] emits that step, whose result is bit for bit the
//! full step's at such a point.

use crate::expr::{Expr, Var};
use crate::factor::Plan;

/// A static pivot's unknown written as a function of the kept unknowns.
#[derive(Clone, Debug, PartialEq)]
pub struct Lift {
    /// Index into [`Plan::statics`].
    pub statics: usize,
    /// The row and the unknown it determines.
    pub row: usize,
    pub col: usize,
    /// The row's other terms S, in the residual's order.
    pub rest: Expr,
    /// Whether v_c = −S (the row is S + v_c) rather than S (the row is S − v_c).
    pub negate: bool,
}

/// The lifts of the plan's static rows that qualify (see the module documentation), in
/// [`Plan::statics`] order.
pub fn lifts(plan: &Plan, equations: &[Expr]) -> Vec<Lift> {
    let n = plan.n;
    plan.statics
        .iter()
        .enumerate()
        .filter_map(|(s, &(r, c, p))| {
            // Affine in v: no entry of the row depends on an unknown.
            let affine = plan
                .jac
                .iter()
                .filter(|e| e.0 == r)
                .all(|e| (0..n).all(|i| !e.2.depends_on(Var::Unknown(i))));
            if !affine || (p != 1.0 && p != -1.0) {
                return None;
            }
            let Expr::Sum(ts) = equations.get(r)? else {
                return None;
            };
            let (last, rest) = ts.split_last()?;
            let pivot_term = if p == 1.0 {
                Expr::Unknown(c)
            } else {
                Expr::Unknown(c).negated()
            };
            if *last != pivot_term
                || rest.is_empty()
                || rest.iter().any(|t| t.depends_on(Var::Unknown(c)))
            {
                return None;
            }
            let rest = match rest {
                [one] => one.clone(),
                _ => Expr::Sum(rest.to_vec()),
            };
            Some(Lift {
                statics: s,
                row: r,
                col: c,
                rest,
                negate: p == 1.0,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn jac_of(rows: &[Expr], n: usize) -> Vec<(usize, usize, Expr)> {
        let mut jac = Vec::new();
        for (r, e) in rows.iter().enumerate() {
            for c in 0..n {
                let d = e.derivative(Var::Unknown(c));
                if !d.is_zero() {
                    jac.push((r, c, d));
                }
            }
        }
        jac
    }

    #[test]
    fn affine_rows_lift_and_others_do_not() {
        // F0 = v0² + v1² − x0² (not affine), F1 = c0 v0 − v1 (affine, liftable),
        // F2 = v2 − c1 v0 (affine, pivot +1 but not last: not lifted).
        let u = Expr::Unknown;
        let rows = vec![
            Expr::Sum(vec![
                u(0).square(),
                u(1).square(),
                Expr::Input(0).square().negated(),
            ]),
            Expr::Sum(vec![Expr::times(Expr::Constant(0), u(0)), u(1).negated()]),
            Expr::Sum(vec![u(2), Expr::times(Expr::Constant(1), u(0)).negated()]),
        ];
        let jac = jac_of(&rows, 3);
        let plan = crate::factor::plan(3, &jac, None);
        let lifts = lifts(&plan, &rows);
        assert_eq!(lifts.len(), 1, "{lifts:?}");
        assert_eq!((lifts[0].row, lifts[0].col, lifts[0].negate), (1, 1, false));
        assert_eq!(lifts[0].rest, Expr::times(Expr::Constant(0), u(0)));
    }

    #[test]
    fn a_system_without_affine_rows_has_no_lifts() {
        let u = Expr::Unknown;
        let rows = vec![
            Expr::Sum(vec![u(0).square(), u(1), Expr::Input(0).negated()]),
            Expr::Sum(vec![Expr::times(u(0), u(1)), Expr::Input(1).negated()]),
        ];
        let jac = jac_of(&rows, 2);
        let plan = crate::factor::plan(2, &jac, None);
        assert!(lifts(&plan, &rows).is_empty());
    }
}
