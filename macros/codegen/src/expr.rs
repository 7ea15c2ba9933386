//! Symbolic expressions: the intermediate representation between the kinematic model and the
//! emitted Rust. Small on purpose: the constraint systems of lower-pair mechanisms are sums of
//! products and squares of pivot coordinates, with trigonometry only in the joint inputs.

use std::fmt::Write as _;

/// A scalar expression in the unknowns `v`, the inputs `x` and the geometry constants `c`.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Num(f64),
    /// `v[i]`: a pivot coordinate solved for.
    Unknown(usize),
    /// `x[j]`: a joint variable.
    Input(usize),
    /// `c[k]`: a constant derived from the geometry at run time.
    Constant(usize),
    Sum(Vec<Expr>),
    Product(Vec<Expr>),
    Square(Box<Expr>),
    Sin(Box<Expr>),
    Cos(Box<Expr>),
}

/// Which symbol an expression is differentiated by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    Unknown(usize),
    Input(usize),
}

/// How symbols are spelled in listings.
pub struct Names<'a> {
    pub unknowns: &'a [String],
    pub inputs: &'a [String],
    pub constants: &'a [String],
}

impl Expr {
    pub fn zero() -> Expr {
        Expr::Num(0.0)
    }

    pub fn minus(a: Expr, b: Expr) -> Expr {
        Expr::Sum(vec![a, b.negated()]).simplify()
    }

    pub fn plus(a: Expr, b: Expr) -> Expr {
        Expr::Sum(vec![a, b]).simplify()
    }

    pub fn times(a: Expr, b: Expr) -> Expr {
        Expr::Product(vec![a, b]).simplify()
    }

    pub fn negated(self) -> Expr {
        Expr::Product(vec![Expr::Num(-1.0), self]).simplify()
    }

    pub fn square(self) -> Expr {
        Expr::Square(Box::new(self)).simplify()
    }

    pub fn is_zero(&self) -> bool {
        matches!(self, Expr::Num(n) if *n == 0.0)
    }

    /// Polynomial degree in the unknowns (inputs and constants count as coefficients).
    pub fn degree(&self) -> usize {
        match self {
            Expr::Num(_) | Expr::Input(_) | Expr::Constant(_) => 0,
            Expr::Unknown(_) => 1,
            Expr::Sum(ts) => ts.iter().map(Expr::degree).max().unwrap_or(0),
            Expr::Product(fs) => fs.iter().map(Expr::degree).sum(),
            Expr::Square(e) => 2 * e.degree(),
            // Trigonometric terms only ever wrap inputs; a `sin` of an unknown is not polynomial.
            Expr::Sin(e) | Expr::Cos(e) => {
                if e.degree() == 0 {
                    0
                } else {
                    usize::MAX
                }
            }
        }
    }

    /// Whether the expression mentions the symbol at all.
    pub fn depends_on(&self, var: Var) -> bool {
        match (self, var) {
            (Expr::Unknown(i), Var::Unknown(j)) => *i == j,
            (Expr::Input(i), Var::Input(j)) => *i == j,
            (Expr::Num(_) | Expr::Unknown(_) | Expr::Input(_) | Expr::Constant(_), _) => false,
            (Expr::Sum(ts) | Expr::Product(ts), _) => ts.iter().any(|t| t.depends_on(var)),
            (Expr::Square(e) | Expr::Sin(e) | Expr::Cos(e), _) => e.depends_on(var),
        }
    }

    /// Whether `x[input]` enters only as the argument of a sine or cosine, so that the
    /// expression does not change when the input turns by 2π.
    pub fn only_turns(&self, input: usize) -> bool {
        match self {
            Expr::Input(i) => *i != input,
            Expr::Sin(e) | Expr::Cos(e) => {
                matches!(**e, Expr::Input(i) if i == input) || e.only_turns(input)
            }
            Expr::Num(_) | Expr::Unknown(_) | Expr::Constant(_) => true,
            Expr::Sum(ts) | Expr::Product(ts) => ts.iter().all(|t| t.only_turns(input)),
            Expr::Square(e) => e.only_turns(input),
        }
    }

    /// The exact partial derivative, simplified.
    pub fn derivative(&self, var: Var) -> Expr {
        if !self.depends_on(var) {
            return Expr::zero();
        }
        let d = match self {
            Expr::Unknown(_) | Expr::Input(_) => Expr::Num(1.0),
            Expr::Num(_) | Expr::Constant(_) => Expr::zero(),
            Expr::Sum(ts) => Expr::Sum(ts.iter().map(|t| t.derivative(var)).collect()),
            Expr::Product(fs) => Expr::Sum(
                (0..fs.len())
                    .map(|k| {
                        let mut f = fs.clone();
                        f[k] = fs[k].derivative(var);
                        Expr::Product(f)
                    })
                    .collect(),
            ),
            Expr::Square(e) => {
                Expr::Product(vec![Expr::Num(2.0), (**e).clone(), e.derivative(var)])
            }
            Expr::Sin(e) => Expr::Product(vec![Expr::Cos(e.clone()), e.derivative(var)]),
            Expr::Cos(e) => Expr::Product(vec![
                Expr::Num(-1.0),
                Expr::Sin(e.clone()),
                e.derivative(var),
            ]),
        };
        d.simplify()
    }

    /// Numeric value, for tests and compile-time checks.
    pub fn eval(&self, v: &[f64], x: &[f64], c: &[f64]) -> f64 {
        match self {
            Expr::Num(n) => *n,
            Expr::Unknown(i) => v[*i],
            Expr::Input(i) => x[*i],
            Expr::Constant(i) => c[*i],
            Expr::Sum(ts) => ts.iter().map(|t| t.eval(v, x, c)).sum(),
            Expr::Product(fs) => fs.iter().map(|f| f.eval(v, x, c)).product(),
            Expr::Square(e) => {
                let t = e.eval(v, x, c);
                t * t
            }
            Expr::Sin(e) => e.eval(v, x, c).sin(),
            Expr::Cos(e) => e.eval(v, x, c).cos(),
        }
    }

    /// The size rounding is relative to in evaluating the expression: its value with every
    /// term of a sum taken by its size (sines and cosines as 1). An equation whose derivatives
    /// are all rounding-small against it is one that holds identically there.
    pub fn magnitude(&self, v: &[f64], x: &[f64], c: &[f64]) -> f64 {
        match self {
            Expr::Num(n) => n.abs(),
            Expr::Unknown(i) => v[*i].abs(),
            Expr::Input(i) => x[*i].abs(),
            Expr::Constant(i) => c[*i].abs(),
            Expr::Sum(ts) => ts.iter().map(|t| t.magnitude(v, x, c)).sum(),
            Expr::Product(fs) => fs.iter().map(|f| f.magnitude(v, x, c)).product(),
            Expr::Square(e) => e.magnitude(v, x, c).powi(2),
            Expr::Sin(_) | Expr::Cos(_) => 1.0,
        }
    }

    /// Flattens sums and products, folds numbers, drops neutral elements, and writes
    /// `-2*(a - b)` as `2*(b - a)` so that derivatives read like the paper's Table A1.
    pub fn simplify(self) -> Expr {
        match self {
            Expr::Sum(ts) => simplify_sum(ts),
            Expr::Product(fs) => simplify_product(fs),
            Expr::Square(e) => match e.simplify() {
                Expr::Num(n) => Expr::Num(n * n),
                e => Expr::Square(Box::new(e)),
            },
            Expr::Sin(e) => match e.simplify() {
                Expr::Num(n) => Expr::Num(n.sin()),
                e => Expr::Sin(Box::new(e)),
            },
            Expr::Cos(e) => match e.simplify() {
                Expr::Num(n) => Expr::Num(n.cos()),
                e => Expr::Cos(Box::new(e)),
            },
            e => e,
        }
    }

    /// `(coefficient, rest)` with the numeric factor of a product split off.
    fn split_coefficient(&self) -> (f64, Option<Expr>) {
        match self {
            Expr::Num(n) => (*n, None),
            Expr::Product(fs) => match fs.first() {
                Some(Expr::Num(n)) => {
                    let rest = Expr::Product(fs[1..].to_vec()).simplify();
                    (*n, Some(rest))
                }
                _ => (1.0, Some(self.clone())),
            },
            _ => (1.0, Some(self.clone())),
        }
    }

    /// The factors of [`Expr::split_coefficient`]'s rest, borrowed: a product's factors after
    /// its numeric one, or the term itself. Two terms of a simplified sum (no numbers, no
    /// product of one factor) have equal rests exactly where these are equal.
    fn rest_factors(&self) -> &[Expr] {
        match self {
            Expr::Product(fs) => match fs.first() {
                Some(Expr::Num(_)) => &fs[1..],
                _ => fs,
            },
            e => core::slice::from_ref(e),
        }
    }

    /// Human-readable form, in the paper's notation.
    pub fn render(&self, names: &Names) -> String {
        let mut s = String::new();
        self.render_into(&mut s, names);
        s
    }

    fn render_into(&self, s: &mut String, names: &Names) {
        match self {
            Expr::Num(n) => s.push_str(&fmt_num(*n)),
            Expr::Unknown(i) => s.push_str(&names.unknowns[*i]),
            Expr::Input(i) => s.push_str(&names.inputs[*i]),
            Expr::Constant(i) => s.push_str(&names.constants[*i]),
            Expr::Sum(ts) => {
                for (k, t) in ts.iter().enumerate() {
                    let (c, rest) = t.split_coefficient();
                    let negative = c < 0.0;
                    if k == 0 {
                        if negative {
                            s.push('-');
                        }
                    } else {
                        s.push_str(if negative { " - " } else { " + " });
                    }
                    match rest {
                        None => s.push_str(&fmt_num(c.abs())),
                        Some(r) => {
                            if c.abs() != 1.0 {
                                s.push_str(&fmt_num(c.abs()));
                                s.push('*');
                                r.render_factor(s, names);
                            } else if matches!(r, Expr::Sum(_)) {
                                r.render_factor(s, names);
                            } else {
                                r.render_into(s, names);
                            }
                        }
                    }
                }
            }
            Expr::Product(fs) => {
                let mut first = true;
                for (k, f) in fs.iter().enumerate() {
                    if k == 0 && fs.len() > 1 && *f == Expr::Num(-1.0) {
                        s.push('-');
                        continue;
                    }
                    if !first {
                        s.push('*');
                    }
                    first = false;
                    f.render_factor(s, names);
                }
            }
            Expr::Square(e) => {
                e.render_factor(s, names);
                s.push_str("^2");
            }
            Expr::Sin(e) => {
                s.push_str("sin(");
                e.render_into(s, names);
                s.push(')');
            }
            Expr::Cos(e) => {
                s.push_str("cos(");
                e.render_into(s, names);
                s.push(')');
            }
        }
    }

    fn render_factor(&self, s: &mut String, names: &Names) {
        let atomic = matches!(
            self,
            Expr::Unknown(_) | Expr::Input(_) | Expr::Constant(_) | Expr::Sin(_) | Expr::Cos(_)
        ) || matches!(self, Expr::Num(n) if *n >= 0.0);
        if atomic {
            self.render_into(s, names);
        } else {
            s.push('(');
            self.render_into(s, names);
            s.push(')');
        }
    }
}

fn simplify_sum(ts: Vec<Expr>) -> Expr {
    let mut out = Vec::with_capacity(ts.len());
    let mut number = 0.0;
    for t in ts {
        match t.simplify() {
            Expr::Num(n) => number += n,
            Expr::Sum(inner) => {
                for i in inner {
                    match i {
                        Expr::Num(n) => number += n,
                        i => out.push(i),
                    }
                }
            }
            t => out.push(t),
        }
    }
    let mut out = combine_like_terms(out);
    if number != 0.0 {
        out.push(Expr::Num(number));
    }
    match out.len() {
        0 => Expr::zero(),
        1 => out.swap_remove(0),
        _ => Expr::Sum(out),
    }
}

/// Terms that differ only in their numeric factor merged into one, in the place of the first
/// (`a − b + c + b` is `a + c`): chains substituted into one another leave such pairs, each an
/// operation per evaluation. A sum without repeats is returned as it was, so the emitted code
/// of such mechanisms does not change.
fn combine_like_terms(terms: Vec<Expr>) -> Vec<Expr> {
    // Most sums have no repeats: look for one by reference first, without building (cloning)
    // each term's rest.
    let rests: Vec<&[Expr]> = terms.iter().map(Expr::rest_factors).collect();
    let repeated = (0..rests.len()).any(|i| (0..i).any(|j| rests[j] == rests[i]));
    if !repeated {
        return terms;
    }
    let split: Vec<(f64, Option<Expr>)> = terms.iter().map(Expr::split_coefficient).collect();
    let mut merged: Vec<(f64, Expr)> = Vec::with_capacity(split.len());
    for (c, rest) in split {
        // `split_coefficient` gives a rest for every non-number term, which is all a sum
        // holds here (its numbers were folded).
        let Some(rest) = rest else { continue };
        match merged.iter_mut().find(|(_, r)| *r == rest) {
            Some((sum, _)) => *sum += c,
            None => merged.push((c, rest)),
        }
    }
    merged
        .into_iter()
        .filter(|&(c, _)| c != 0.0)
        .map(|(c, rest)| match c {
            1.0 => rest,
            _ => Expr::Product(vec![Expr::Num(c), rest]).simplify(),
        })
        .collect()
}

fn simplify_product(fs: Vec<Expr>) -> Expr {
    let mut out = Vec::with_capacity(fs.len());
    let mut number = 1.0;
    for f in fs {
        match f.simplify() {
            Expr::Num(n) => number *= n,
            Expr::Product(inner) => {
                for i in inner {
                    match i {
                        Expr::Num(n) => number *= n,
                        i => out.push(i),
                    }
                }
            }
            f => out.push(f),
        }
    }
    if number == 0.0 {
        return Expr::zero();
    }
    // -k * (a - b)  ==>  k * (b - a): the paper's way of writing J(16,3) = 2(x_G3 - x_G1).
    if number < 0.0 && out.len() == 1 {
        if let Expr::Sum(terms) = &out[0] {
            if terms.len() == 2 {
                let flipped: Vec<Expr> = terms.iter().map(|t| t.clone().negated()).collect();
                let (c0, _) = flipped[0].split_coefficient();
                if c0 > 0.0 {
                    out[0] = Expr::Sum(flipped);
                    number = -number;
                } else {
                    let (c1, _) = flipped[1].split_coefficient();
                    if c1 > 0.0 {
                        out[0] = Expr::Sum(vec![flipped[1].clone(), flipped[0].clone()]);
                        number = -number;
                    }
                }
            }
        }
    }
    if out.is_empty() {
        return Expr::Num(number);
    }
    if number != 1.0 {
        out.insert(0, Expr::Num(number));
    }
    if out.len() == 1 {
        out.swap_remove(0)
    } else {
        Expr::Product(out)
    }
}

fn fmt_num(n: f64) -> String {
    let mut s = String::new();
    if n.fract() == 0.0 && n.abs() < 1e15 {
        let _ = write!(s, "{}", n as i64);
    } else {
        let _ = write!(s, "{n}");
    }
    s
}

/// A 3-vector of expressions: a pivot point's coordinates.
pub type Vec3 = [Expr; 3];

pub fn vsub(a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|k| Expr::minus(a[k].clone(), b[k].clone()))
}

pub fn vadd(a: &Vec3, b: &Vec3) -> Vec3 {
    [0, 1, 2].map(|k| Expr::plus(a[k].clone(), b[k].clone()))
}

pub fn vscale(s: &Expr, a: &Vec3) -> Vec3 {
    [0, 1, 2].map(|k| Expr::times(s.clone(), a[k].clone()))
}

pub fn dot(a: &Vec3, b: &Vec3) -> Expr {
    Expr::Sum(
        (0..3)
            .map(|k| Expr::times(a[k].clone(), b[k].clone()))
            .collect(),
    )
    .simplify()
}

pub fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [(1, 2), (2, 0), (0, 1)].map(|(i, j)| {
        Expr::minus(
            Expr::times(a[i].clone(), b[j].clone()),
            Expr::times(a[j].clone(), b[i].clone()),
        )
    })
}

/// `‖a − b‖²` written as a sum of squares, the form of Eq. 15 and Eq. 19.
pub fn squared_distance(a: &Vec3, b: &Vec3) -> Expr {
    Expr::Sum(
        (0..3)
            .map(|k| Expr::minus(a[k].clone(), b[k].clone()).square())
            .collect(),
    )
    .simplify()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> (Vec<String>, Vec<String>, Vec<String>) {
        (
            vec!["a".into(), "b".into()],
            vec!["L".into()],
            vec!["E".into()],
        )
    }

    #[test]
    fn derivative_of_a_square_reads_like_table_a1() {
        let (u, i, c) = names();
        let names = Names {
            unknowns: &u,
            inputs: &i,
            constants: &c,
        };
        let e = Expr::minus(Expr::Unknown(0), Expr::Unknown(1)).square();
        assert_eq!(e.render(&names), "(a - b)^2");
        assert_eq!(e.derivative(Var::Unknown(0)).render(&names), "2*(a - b)");
        assert_eq!(e.derivative(Var::Unknown(1)).render(&names), "2*(b - a)");
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let e = Expr::Sum(vec![
            Expr::Product(vec![Expr::Constant(0), Expr::Unknown(0), Expr::Unknown(1)]),
            Expr::Sub2(),
            Expr::Cos(Box::new(Expr::Input(0))),
        ])
        .simplify();
        let (v, x, c) = ([1.3, -0.7], [0.4], [2.5]);
        for var in [Var::Unknown(0), Var::Unknown(1), Var::Input(0)] {
            let h = 1e-6;
            let bump = |s: f64| {
                let (mut v2, mut x2) = (v, x);
                match var {
                    Var::Unknown(i) => v2[i] += s,
                    Var::Input(i) => x2[i] += s,
                }
                e.eval(&v2, &x2, &c)
            };
            let fd = (bump(h) - bump(-h)) / (2.0 * h);
            let exact = e.derivative(var).eval(&v, &x, &c);
            assert!((fd - exact).abs() < 1e-6, "{var:?}: {fd} vs {exact}");
        }
    }

    impl Expr {
        #[allow(non_snake_case)]
        fn Sub2() -> Expr {
            Expr::minus(Expr::Unknown(1), Expr::Input(0)).square()
        }
    }

    #[test]
    fn like_terms_merge_and_cancelling_pairs_vanish() {
        let (u, i, c) = names();
        let names = Names {
            unknowns: &u,
            inputs: &i,
            constants: &c,
        };
        let (a, b, l) = (Expr::Unknown(0), Expr::Unknown(1), Expr::Input(0));
        // c·(a − b + L + b) as substitution leaves it: c·(a + L).
        let inner = Expr::plus(
            Expr::minus(a.clone(), b.clone()),
            Expr::plus(l.clone(), b.clone()),
        );
        let e = Expr::times(Expr::Constant(0), inner);
        assert_eq!(e.render(&names), "E*(a + L)");
        // Coefficients add: 2a − b + a is 3a − b; a sum without repeats keeps its order.
        let e = Expr::plus(
            Expr::minus(Expr::times(Expr::Num(2.0), a.clone()), b.clone()),
            a.clone(),
        );
        assert_eq!(e.render(&names), "3*a - b");
        assert_eq!(Expr::minus(b.clone(), a.clone()).render(&names), "b - a");
        assert!(Expr::minus(Expr::plus(a.clone(), l), a).render(&names) == "L");
    }

    #[test]
    fn degree_counts_unknowns_only() {
        let e = Expr::times(Expr::Input(0), Expr::Unknown(0).square());
        assert_eq!(e.degree(), 2);
        assert_eq!(Expr::Cos(Box::new(Expr::Input(0))).degree(), 0);
    }
}
