//! Geometry values declared as arithmetic on parameters (`A2 = [rb * c2, rb * s2, 0.0]`): the
//! formula, in postfix order over the geometry slots, that the generator writes down once and
//! this one interpreter evaluates — at compile time for the declared value, and in every
//! generated `from_geometry`, so that changing a parameter at run time moves every coordinate
//! declared from it, to the last bit as the generator computed it.

use crate::math::{acos, asin, atan, cos, sin, sqrt, tan};

/// One step of a formula in postfix order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Op {
    /// Push a number.
    Num(f64),
    /// Push a geometry slot's value.
    Slot(usize),
    /// Replace the top `a` with −a.
    Neg,
    /// Replace the top two (`a`, then `b` above it) with a + b, a − b, a · b, a / b.
    Add,
    Sub,
    Mul,
    Div,
    /// Replace the top `a` with f(a).
    Sqrt,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
}

/// The deepest stack a formula may need (the generator refuses deeper ones).
pub const DEPTH: usize = 32;

/// A geometry slot whose value is a formula of other slots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Formula<'a> {
    pub slot: usize,
    pub ops: &'a [Op],
}

/// The value of `ops` on the slots `g`; NaN for a formula that is malformed (a slot out of
/// range, too deep, an operator short of operands, or not exactly one value left).
pub fn evaluate(ops: &[Op], g: &[f64]) -> f64 {
    let mut stack = [0.0f64; DEPTH];
    let mut n = 0usize;
    for op in ops {
        let value = match *op {
            Op::Num(x) => x,
            Op::Slot(s) => match g.get(s) {
                Some(&x) => x,
                None => return f64::NAN,
            },
            Op::Neg | Op::Sqrt | Op::Sin | Op::Cos | Op::Tan | Op::Asin | Op::Acos | Op::Atan => {
                let Some(a) = n.checked_sub(1).and_then(|i| stack.get(i)).copied() else {
                    return f64::NAN;
                };
                n -= 1;
                match *op {
                    Op::Neg => -a,
                    Op::Sqrt => sqrt(a),
                    Op::Sin => sin(a),
                    Op::Cos => cos(a),
                    Op::Tan => tan(a),
                    Op::Asin => asin(a),
                    Op::Acos => acos(a),
                    _ => atan(a),
                }
            }
            Op::Add | Op::Sub | Op::Mul | Op::Div => {
                let (Some(&a), Some(&b)) = (
                    n.checked_sub(2).and_then(|i| stack.get(i)),
                    n.checked_sub(1).and_then(|i| stack.get(i)),
                ) else {
                    return f64::NAN;
                };
                n -= 2;
                match *op {
                    Op::Add => a + b,
                    Op::Sub => a - b,
                    Op::Mul => a * b,
                    _ => a / b,
                }
            }
        };
        match stack.get_mut(n) {
            Some(top) => *top = value,
            None => return f64::NAN,
        }
        n += 1;
    }
    if n == 1 {
        stack[0]
    } else {
        f64::NAN
    }
}

/// Sets every formula's slot in `g` from the others. A formula reads parameter slots only,
/// which no formula sets, so the order does not matter.
pub fn apply(formulas: &[Formula<'_>], g: &mut [f64]) {
    for f in formulas {
        let value = evaluate(f.ops, g);
        if let Some(slot) = g.get_mut(f.slot) {
            *slot = value;
        }
    }
}

/// The stack depth `ops` needs; `None` if it is malformed (an operator short of operands, or
/// not exactly one value left).
pub fn depth(ops: &[Op]) -> Option<usize> {
    let (mut n, mut most) = (0usize, 0usize);
    for op in ops {
        n = match op {
            Op::Num(_) | Op::Slot(_) => n + 1,
            Op::Add | Op::Sub | Op::Mul | Op::Div => n.checked_sub(1).filter(|&k| k >= 1)?,
            _ => n.checked_sub(1).map(|k| k + 1)?,
        };
        most = most.max(n);
    }
    (n == 1).then_some(most)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_formula_reads_its_slots() {
        // (g0 + 2) * -g1, sqrt(g0)
        let f = [
            Op::Slot(0),
            Op::Num(2.0),
            Op::Add,
            Op::Slot(1),
            Op::Neg,
            Op::Mul,
        ];
        assert_eq!(evaluate(&f, &[1.0, 3.0]), -9.0);
        assert_eq!(depth(&f), Some(2));
        let mut g = [4.0, 0.0];
        apply(
            &[Formula {
                slot: 1,
                ops: &[Op::Slot(0), Op::Sqrt],
            }],
            &mut g,
        );
        assert_eq!(g, [4.0, 2.0]);
    }

    #[test]
    fn a_malformed_formula_is_nan_not_a_panic() {
        for f in [
            &[Op::Add][..],
            &[Op::Num(1.0), Op::Num(2.0)],
            &[Op::Slot(7)],
            &[Op::Sin],
            &[],
        ] {
            assert!(evaluate(f, &[1.0]).is_nan(), "{f:?}");
        }
        assert_eq!(depth(&[Op::Add]), None);
        let deep = [Op::Num(1.0); DEPTH + 1];
        assert!(evaluate(&deep, &[]).is_nan());
    }
}
