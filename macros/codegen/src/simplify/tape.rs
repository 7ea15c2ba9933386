//! Expressions flattened for evaluation at many configurations: each a sequence of operations
//! on a stack (postfix), evaluated by one loop. Following the motion evaluates the equations
//! and their derivatives thousands of times; walking the trees took 14 ns a node.

use crate::expr::Expr;

#[derive(Clone, Copy)]
enum Op {
    Num(f64),
    Unknown(usize),
    Input(usize),
    Constant(usize),
    /// The sum of the top `k` values.
    Sum(usize),
    Product(usize),
    Square,
    Sin,
    Cos,
}

/// Several expressions, one after the other; `ends[i]` is where the i-th one's ops end.
pub struct Tape {
    ops: Vec<Op>,
    ends: Vec<usize>,
}

fn flatten(e: &Expr, ops: &mut Vec<Op>) {
    match e {
        Expr::Num(a) => ops.push(Op::Num(*a)),
        Expr::Unknown(i) => ops.push(Op::Unknown(*i)),
        Expr::Input(i) => ops.push(Op::Input(*i)),
        Expr::Constant(i) => ops.push(Op::Constant(*i)),
        Expr::Sum(ts) => {
            ts.iter().for_each(|t| flatten(t, ops));
            ops.push(Op::Sum(ts.len()));
        }
        Expr::Product(fs) => {
            fs.iter().for_each(|f| flatten(f, ops));
            ops.push(Op::Product(fs.len()));
        }
        Expr::Square(a) => {
            flatten(a, ops);
            ops.push(Op::Square);
        }
        Expr::Sin(a) => {
            flatten(a, ops);
            ops.push(Op::Sin);
        }
        Expr::Cos(a) => {
            flatten(a, ops);
            ops.push(Op::Cos);
        }
    }
}

impl Tape {
    pub fn new<'a>(exprs: impl IntoIterator<Item = &'a Expr>) -> Tape {
        let mut tape = Tape {
            ops: Vec::new(),
            ends: Vec::new(),
        };
        for e in exprs {
            flatten(e, &mut tape.ops);
            tape.ends.push(tape.ops.len());
        }
        tape
    }

    /// The number of operations: what an evaluation costs.
    pub fn len(&self) -> usize {
        self.ops.len()
    }

    /// Each expression's value at `(v, x)` with constants `c`, in order, into `out`.
    pub fn eval(&self, v: &[f64], x: &[f64], c: &[f64], out: &mut Vec<f64>) {
        out.clear();
        let mut stack: Vec<f64> = Vec::with_capacity(32);
        let mut end = self.ends.iter();
        let mut next = end.next().copied();
        for (k, op) in self.ops.iter().enumerate() {
            match *op {
                Op::Num(a) => stack.push(a),
                Op::Unknown(i) => stack.push(v[i]),
                Op::Input(i) => stack.push(x[i]),
                Op::Constant(i) => stack.push(c[i]),
                Op::Sum(n) => {
                    let at = stack.len() - n;
                    let s = stack[at..].iter().sum();
                    stack.truncate(at);
                    stack.push(s);
                }
                Op::Product(n) => {
                    let at = stack.len() - n;
                    let p = stack[at..].iter().product();
                    stack.truncate(at);
                    stack.push(p);
                }
                Op::Square => {
                    let t = stack.last_mut().expect("an operand");
                    *t *= *t;
                }
                Op::Sin => {
                    let t = stack.last_mut().expect("an operand");
                    *t = t.sin();
                }
                Op::Cos => {
                    let t = stack.last_mut().expect("an operand");
                    *t = t.cos();
                }
            }
            while next == Some(k + 1) {
                out.push(stack.pop().expect("a value"));
                next = end.next().copied();
            }
        }
        // Expressions of no operation (none: every expression has one) would be skipped;
        // every end is met above.
        debug_assert_eq!(out.len(), self.ends.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tape_evaluates_as_the_tree_does() {
        let (v, x, c) = ([0.5, -2.0], [0.3], [4.0]);
        let exprs = [
            Expr::Sum(vec![
                Expr::Product(vec![Expr::Unknown(0), Expr::Constant(0), Expr::Num(3.0)]),
                Expr::Square(Box::new(Expr::Unknown(1))),
                Expr::Sin(Box::new(Expr::Input(0))),
            ]),
            Expr::Num(7.0),
            Expr::Cos(Box::new(Expr::Product(vec![
                Expr::Input(0),
                Expr::Unknown(1),
            ]))),
        ];
        let tape = Tape::new(&exprs);
        let mut out = Vec::new();
        tape.eval(&v, &x, &c, &mut out);
        let want: Vec<f64> = exprs.iter().map(|e| e.eval(&v, &x, &c)).collect();
        assert_eq!(out, want);
        // One operation a node: 9, 1 and 4.
        assert_eq!(tape.len(), 14);
    }
}
