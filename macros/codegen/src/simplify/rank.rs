//! Mobility and redundancy by the rank of the constraint Jacobian at the home configuration.
//!
//! Grübler–Kutzbach counts constraints as if they were independent; over-constrained
//! mechanisms (planar or spherical ones declared in space, parallelograms) have dependent ones,
//! and it undercounts their freedom. At a configuration where the mechanism is assembled, the
//! rank of ∂F/∂(v, x) tells the truth: the mobility is `n + m − rank`, and ∂F/∂v must have full
//! column rank for the inputs to fix the pose. Equations dependent on earlier ones there are
//! dropped (listed as such), which leaves the square system the solvers need; the square
//! system is then checked along the motion from home (`along`), and chosen again
//! where it turns singular there and the mechanism does not.

use super::derivatives::{condition, Derivatives, DEPENDENT, NEARLY_SINGULAR};
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

/// What is left of `row` off the span of `basis` (orthonormal rows), as a fraction of its size,
/// and that part normalised. Gram–Schmidt, twice for stability.
fn off_span(basis: &[Vec<f64>], row: &[f64]) -> (f64, Vec<f64>) {
    let mut r = row.to_vec();
    let size = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..2 {
        for q in basis {
            let d: f64 = r.iter().zip(q).map(|(a, b)| a * b).sum();
            r.iter_mut().zip(q).for_each(|(a, b)| *a -= d * b);
        }
    }
    let left = r.iter().map(|x| x * x).sum::<f64>().sqrt();
    (
        left / size.max(1e-300),
        r.iter().map(|x| x / left.max(1e-300)).collect(),
    )
}

/// Below this fraction of its size off the span of the rows kept (above [`DEPENDENT`]), a row
/// is independent, but barely: kept in its turn, it makes the square system nearly singular at
/// home and singular a small step away (a slide's second placement of the platform held by
/// the x of one point whose x hardly moves for the turn it must stop: 4e-6 off the span, ∂F/∂v
/// singular within 0.08 mm of home, where the mechanism is regular). Such a row may wait until
/// its class's rows that add more are in (see [`at_home`]).
const WEAK: f64 = 1e-3;

fn rank(rows: &[Vec<f64>]) -> usize {
    if rows.is_empty() || rows[0].is_empty() {
        return 0;
    }
    let m = DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j]);
    let sv = m.singular_values();
    let top = sv.max();
    sv.iter().filter(|s| **s > 1e-9 * top).count()
}

/// The rows kept, class by class in order: within a class, rows are taken in order while each
/// adds more than `weak` of its size to the span; then the class's other rows, the one that
/// adds the most first (pivoting), while one adds more than [`DEPENDENT`]. With `weak` at
/// [`DEPENDENT`], every row is taken in its turn unless it depends on those before it; with
/// `weak` infinite, by pivoting alone.
fn select(b: &[Vec<f64>], classes: &[Vec<usize>], weak: f64) -> Vec<usize> {
    let mut kept = Vec::new();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for class in classes {
        let mut waiting = Vec::new();
        for &i in class {
            let Some(row) = b.get(i) else { continue };
            let (left, q) = off_span(&basis, row);
            if left > weak {
                basis.push(q);
                kept.push(i);
            } else if left > DEPENDENT {
                waiting.push(i);
            }
        }
        loop {
            let best = waiting
                .iter()
                .enumerate()
                .map(|(k, &i)| (k, off_span(&basis, &b[i])))
                .max_by(|x, y| x.1 .0.total_cmp(&y.1 .0));
            match best {
                Some((k, (left, q))) if left > DEPENDENT => {
                    basis.push(q);
                    kept.push(waiting.swap_remove(k));
                }
                _ => break,
            }
        }
    }
    kept.sort_unstable();
    kept
}

/// `classes`: the equations' indices in the order they are offered to the basis, class by
/// class (a partition of the indices); of dependent ones, the later is left out. Two choices
/// of the rows (see `select`): each in its turn, and with the rows that add less than
/// `WEAK` of themselves waiting for the rest of their class. The first is kept unless it is
/// nearly singular at home (`NEARLY_SINGULAR`) and the second is better conditioned; where
/// both are, a third, by pivoting over all the rows, if it is better conditioned still. Where
/// equations are left out, the choice is followed along the motion and may give way to one
/// that stays regular there (see `along`). `kept` is in the equations' own order.
pub fn at_home(
    equations: &[Expr],
    classes: &[Vec<usize>],
    n: usize,
    m: usize,
    v: &[f64],
    x: &[f64],
    c: &[f64],
) -> Ranked {
    let vars_v: Vec<Var> = (0..n).map(Var::Unknown).collect();
    let vars_x: Vec<Var> = (0..m).map(Var::Input).collect();
    let by_v = Derivatives::new(equations, &vars_v);
    let by_x = Derivatives::new(equations, &vars_x);
    let b = by_v.rows(v, x, c);
    let in_turn = select(&b, classes, DEPENDENT);
    let waiting = select(&b, classes, WEAK);
    let (turn, wait) = (condition(&b, &in_turn), condition(&b, &waiting));
    let (kept, cond) = if waiting.len() > in_turn.len()
        || waiting.len() == in_turn.len() && turn < NEARLY_SINGULAR && wait > turn
    {
        (waiting, wait)
    } else {
        (in_turn, turn)
    };
    // Both nearly singular: the rows chosen by pivoting alone, over every class, the one that
    // adds the most first. (A spherical mechanism with a U whose second turn the loop locks:
    // rows 6e-8 of themselves off the span were kept in their class's turn, 2e-9 ones later
    // left out, and ∂F/∂v had σmin/σmax 1e-10 at home where all the equations give 7e-5.)
    let kept = if cond < NEARLY_SINGULAR {
        let pivoted = select(&b, &[classes.concat()], f64::INFINITY);
        if pivoted.len() >= kept.len() && condition(&b, &pivoted) > cond {
            pivoted
        } else {
            kept
        }
    } else {
        kept
    };
    let full = Derivatives::side_by_side(&[&by_v, &by_x], v, x, c);
    let mobility = (n + m) as i64 - rank(&full) as i64;
    // Equations left out and a square system kept: checked along the motion, where it may
    // turn singular although the mechanism does not.
    let kept = if kept.len() == n && kept.len() < equations.len() && mobility == m as i64 {
        let rays = super::motion::rays(&by_v, &by_x, v, x, c);
        super::along::steady(&by_v, classes, kept, &rays, c)
    } else {
        kept
    };
    Ranked {
        rank_v: kept.len(),
        kept,
        mobility,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cond(equations: &[Expr], kept: &[usize], v: &[f64]) -> f64 {
        let b = Derivatives::new(equations, &[Var::Unknown(0), Var::Unknown(1)]).rows(v, &[], &[]);
        let m = DMatrix::from_fn(kept.len(), 2, |i, j| b[kept[i]][j]);
        let sv = m.singular_values();
        sv.min() / sv.max()
    }

    /// Three equations in two unknowns, one dependent: the second, offered before the third,
    /// adds only 3e-8 of itself to the first. Kept in its turn, it left ∂F/∂v of condition
    /// 1.5e-8 (on a mechanism, singular a small step away); the third, which adds all of
    /// itself, is kept instead.
    #[test]
    fn a_barely_independent_row_gives_way_to_a_better_one_of_its_class() {
        let (x, y) = (Expr::Unknown(0), Expr::Unknown(1));
        let equations = vec![
            x.clone(),
            Expr::plus(x.clone(), Expr::times(Expr::Num(3e-8), y.clone())),
            y.clone(),
        ];
        let v = [0.0, 0.0];
        let ranked = at_home(&equations, &[vec![0], vec![1, 2]], 2, 0, &v, &[], &[]);
        assert_eq!(ranked.kept, [0, 2]);
        assert_eq!(ranked.rank_v, 2);
        assert!(cond(&equations, &ranked.kept, &v) > 0.5);
        // Across classes the order decides both choices: the barely independent row of the
        // first class is kept, the second class's row is then dependent. Both nearly singular,
        // pivoting over every row decides instead.
        let ranked = at_home(&equations, &[vec![0, 1], vec![2]], 2, 0, &v, &[], &[]);
        assert_eq!(ranked.kept, [0, 2]);
        assert!(cond(&equations, &ranked.kept, &v) > 0.5);
    }

    /// An equation that holds identically at home, its coefficients rounding (1e-17, against
    /// terms of 100): its row is zero, not rounding scaled up to a row of size 1, which would
    /// add a rank the mechanism does not have.
    #[test]
    fn a_row_of_rounding_alone_adds_no_rank() {
        let (x, y) = (Expr::Unknown(0), Expr::Unknown(1));
        let equations = vec![
            Expr::minus(Expr::plus(x.clone(), y.clone()), Expr::Num(1.0)),
            Expr::Sum(vec![
                Expr::times(Expr::Num(1e-17), x.clone()),
                Expr::times(Expr::Num(-2e-17), y.clone()),
                Expr::Constant(0),
                Expr::Constant(1).negated(),
            ]),
        ];
        let (v, c) = ([0.25, 0.75], [100.0, 100.0]);
        let ranked = at_home(&equations, &[vec![0, 1]], 2, 0, &v, &[], &c);
        assert_eq!((ranked.kept.as_slice(), ranked.mobility), (&[0][..], 1));
        // The same row with coefficients of its own size is a constraint.
        let mut real = equations.clone();
        real[1] = Expr::minus(x, Expr::times(Expr::Num(2.0), y));
        let ranked = at_home(&real, &[vec![0, 1]], 2, 0, &v, &[], &c);
        assert_eq!((ranked.kept.as_slice(), ranked.mobility), (&[0, 1][..], 0));
    }

    /// On the motion u = t, w = 0 (from home t = 0), the equations u − t, w (1 − u) + (u − t)
    /// and w: the first two, kept at home in their turn, turn singular at u = 1 (their det is
    /// 1 − u), where the mechanism is regular; the first and third do not. The choice along
    /// the motion keeps them. With w (2 + u²) instead, the choice at home stays.
    #[test]
    fn a_choice_that_turns_singular_along_the_motion_gives_way() {
        let (u, w, t) = (Expr::Unknown(0), Expr::Unknown(1), Expr::Input(0));
        let along = Expr::minus(u.clone(), t.clone());
        let equations = |g: Expr| {
            vec![
                along.clone(),
                Expr::plus(Expr::times(w.clone(), g), along.clone()),
                w.clone(),
            ]
        };
        let turning = equations(Expr::minus(Expr::Num(1.0), u.clone()));
        let ranked = at_home(&turning, &[vec![0, 1, 2]], 2, 1, &[0.0, 0.0], &[0.0], &[]);
        assert_eq!((ranked.kept.as_slice(), ranked.mobility), (&[0, 2][..], 1));
        let steady = equations(Expr::plus(Expr::Num(2.0), u.square()));
        let ranked = at_home(&steady, &[vec![0, 1, 2]], 2, 1, &[0.0, 0.0], &[0.0], &[]);
        assert_eq!((ranked.kept.as_slice(), ranked.mobility), (&[0, 1][..], 1));
    }
}
