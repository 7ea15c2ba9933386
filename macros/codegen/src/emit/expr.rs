//! Expressions as Rust tokens: the leaves every emitter shares ([`emit`](crate::emit) for the
//! `Mechanism` impl, [`factor`](crate::emit::factor) for the factorisation), so that both
//! depend on this module and neither on the other.
//!
//! The model's expressions are trees. Where an active pair turns a link that carries other
//! pivots (a U or S wrist on a delta's carriage), its rotation — Rodrigues' formula of one
//! angle applied to the rotation of the other — enters every coordinate of every pivot the
//! link carries and every derivative of them: written out as trees, one such mechanism came to
//! 5 MB of Rust, most of the integration tests' compile time, and as many sines, cosines and
//! products at run time (the compiler merges repeated arithmetic only after it has
//! type-checked and lowered every copy, and not repeated calls). So the expressions of one
//! function body are emitted through an [`Emitter`]: it hash-conses them into a DAG, and a
//! subexpression that occurs more than once and costs at least [`SHARED_COST`] operations is
//! bound once, to a `let` at the top of the body ([`Emitter::bindings`]), and named where it
//! occurs. In the generic bodies of `residual_in` and `jacobian_in` every repeated operation
//! is bound, down to a constant's conversion ([`Arithmetic::Generic`]), each `let` just before
//! the statement that first needs it ([`Emitter::new_bindings`]).

use crate::expr::Expr;
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};
use std::collections::HashMap;

/// Operations a repeated subexpression must cost to be bound to a name in `f64`: below it (a
/// difference of two coordinates, a square of one) the compiler's own merging does as well, and
/// a binding would only lengthen what is live at a time.
pub const SHARED_COST: usize = 3;

/// What a call of sin or cos counts for against [`SHARED_COST`].
const CALL_COST: usize = 10;

pub fn lit(x: f64) -> TokenStream {
    let l = Literal::f64_suffixed(x.abs());
    if x.is_sign_negative() {
        quote!((-#l))
    } else {
        quote!(#l)
    }
}

/// One expression in `f64`, nothing shared.
pub fn tokens(e: &Expr) -> TokenStream {
    Emitter::new(Arithmetic::F64).tokens(e)
}

/// The number type an expression is emitted for.
#[derive(Clone, Copy, PartialEq)]
pub enum Arithmetic {
    F64,
    /// `f64`, with the sine and cosine of an input read from the caller's `t: &Turns<M>`
    /// (`t.0[j] = [sin xⱼ, cos xⱼ]`) instead of evaluated: the kernels of a Newton run at
    /// fixed inputs.
    Turned,
    /// The generic scalar `T` of `residual_in` and `jacobian_in`: numbers and constants enter
    /// through `T::from_f64`. Every repeated operation is bound to a name, a conversion too:
    /// an operation on series, balls or double-doubles is a call the compiler does not merge
    /// (out of line in builds with debug assertions, loops over coefficients otherwise), and
    /// each copy is one more to compile for every declared mechanism and every scalar type.
    Generic,
}

/// A node of the DAG: children by index.
#[derive(Clone, PartialEq, Eq, Hash)]
enum Node {
    /// The number's bits.
    Num(u64),
    Unknown(usize),
    Input(usize),
    Constant(usize),
    /// Terms with their sign, so that `a - b` is written rather than `a + (-1.0 * b)`.
    Sum(Vec<(bool, usize)>),
    Product(Vec<usize>),
    Neg(usize),
    Square(usize),
    Sin(usize),
    Cos(usize),
}

/// Emits the expressions of one function body, binding their shared subexpressions.
///
/// Use: [`Emitter::count`] every expression the body will contain, then [`Emitter::tokens`]
/// each where it goes, then put [`Emitter::bindings`] at the top of the body (they read only
/// `v`, `x` and `c`). Without `count`, nothing is shared and `tokens` writes trees.
pub struct Emitter {
    arithmetic: Arithmetic,
    nodes: Vec<Node>,
    index: HashMap<Node, usize>,
    /// Occurrences in the counted trees.
    uses: Vec<usize>,
    /// Operations of the subtree, calls weighted.
    cost: Vec<usize>,
    name: Vec<Option<Ident>>,
    lets: Vec<TokenStream>,
    /// How many of `lets` [`Emitter::new_bindings`] has handed out.
    handed: usize,
}

impl Emitter {
    pub fn new(arithmetic: Arithmetic) -> Emitter {
        Emitter {
            arithmetic,
            nodes: Vec::new(),
            index: HashMap::new(),
            uses: Vec::new(),
            cost: Vec::new(),
            name: Vec::new(),
            lets: Vec::new(),
            handed: 0,
        }
    }

    /// Records one occurrence of `e` (and of each of its subexpressions).
    pub fn count(&mut self, e: &Expr) {
        self.intern(e, true);
    }

    /// `e` as tokens, with every shared subexpression named.
    pub fn tokens(&mut self, e: &Expr) -> TokenStream {
        let id = self.intern(e, false);
        self.emit(id)
    }

    /// The `let` of every subexpression [`Emitter::tokens`] has named so far, in order.
    pub fn bindings(&self) -> TokenStream {
        let lets = &self.lets;
        quote!(#(#lets)*)
    }

    /// The `let`s named since the last call: put before the statement just emitted, each
    /// binding is computed where it is first needed rather than all at the top of the body.
    pub fn new_bindings(&mut self) -> TokenStream {
        let lets = &self.lets[self.handed..];
        self.handed = self.lets.len();
        quote!(#(#lets)*)
    }

    fn intern(&mut self, e: &Expr, count: bool) -> usize {
        let node = match e {
            Expr::Num(n) => Node::Num(n.to_bits()),
            Expr::Unknown(i) => Node::Unknown(*i),
            Expr::Input(i) => Node::Input(*i),
            Expr::Constant(i) => Node::Constant(*i),
            Expr::Sum(ts) => Node::Sum(
                ts.iter()
                    .map(|t| {
                        let (negative, magnitude) = split_sign(t);
                        (negative, self.intern(&magnitude, count))
                    })
                    .collect(),
            ),
            Expr::Product(fs) => match split_sign(e) {
                (true, magnitude) => Node::Neg(self.intern(&magnitude, count)),
                (false, _) if fs.is_empty() => Node::Num(1f64.to_bits()),
                (false, _) => Node::Product(fs.iter().map(|f| self.intern(f, count)).collect()),
            },
            Expr::Square(e) => Node::Square(self.intern(e, count)),
            Expr::Sin(e) => Node::Sin(self.intern(e, count)),
            Expr::Cos(e) => Node::Cos(self.intern(e, count)),
        };
        let id = match self.index.get(&node) {
            Some(&id) => id,
            None => {
                let generic = self.arithmetic == Arithmetic::Generic;
                let cost = match &node {
                    Node::Num(_) | Node::Constant(_) if generic => 1,
                    Node::Num(_) | Node::Unknown(_) | Node::Input(_) | Node::Constant(_) => 0,
                    Node::Sum(ts) => {
                        ts.len() - 1 + ts.iter().map(|t| self.cost[t.1]).sum::<usize>()
                    }
                    Node::Product(fs) => {
                        fs.len() - 1 + fs.iter().map(|&f| self.cost[f]).sum::<usize>()
                    }
                    Node::Neg(a) => self.cost[*a],
                    Node::Square(a) => 1 + self.cost[*a],
                    Node::Sin(a) | Node::Cos(a) if self.turned(*a).is_some() => 0,
                    Node::Sin(a) | Node::Cos(a) => CALL_COST + self.cost[*a],
                };
                self.nodes.push(node.clone());
                self.index.insert(node, self.nodes.len() - 1);
                self.uses.push(0);
                self.cost.push(cost);
                self.name.push(None);
                self.nodes.len() - 1
            }
        };
        if count {
            self.uses[id] += 1;
        }
        id
    }

    /// The input `j` whose sine or cosine node `argument` is the argument of, where those are
    /// read from `t` rather than evaluated.
    fn turned(&self, argument: usize) -> Option<usize> {
        match (&self.nodes[argument], self.arithmetic) {
            (Node::Input(j), Arithmetic::Turned) => Some(*j),
            _ => None,
        }
    }

    fn emit(&mut self, id: usize) -> TokenStream {
        if let Some(name) = &self.name[id] {
            return quote!(#name);
        }
        let generic = self.arithmetic == Arithmetic::Generic;
        let call = |f: &str, e: TokenStream| {
            let f = format_ident!("{f}");
            if generic {
                quote!(::linkage::Scalar::#f(#e))
            } else {
                quote!(::linkage::__private::#f(#e))
            }
        };
        let code = match self.nodes[id].clone() {
            Node::Num(bits) => {
                let n = lit(f64::from_bits(bits));
                if generic {
                    quote!(T::from_f64(#n))
                } else {
                    n
                }
            }
            Node::Unknown(i) => quote!(v[#i]),
            Node::Input(i) => quote!(x[#i]),
            Node::Constant(i) if generic => quote!(T::from_f64(c[#i])),
            Node::Constant(i) => quote!(c[#i]),
            Node::Sum(ts) => {
                let mut out = TokenStream::new();
                for (k, (negative, t)) in ts.into_iter().enumerate() {
                    let m = self.emit(t);
                    out.extend(match (k, negative) {
                        (0, false) => quote!(#m),
                        (0, true) => quote!(-#m),
                        (_, false) => quote!(+ #m),
                        (_, true) => quote!(- #m),
                    });
                }
                quote!((#out))
            }
            Node::Product(fs) => {
                let fs: Vec<TokenStream> = fs.into_iter().map(|f| self.emit(f)).collect();
                let (first, rest) = (&fs[0], &fs[1..]);
                quote!((#first #(* #rest)*))
            }
            Node::Neg(a) => {
                let m = self.emit(a);
                quote!((-#m))
            }
            Node::Square(a) => call("sq", self.emit(a)),
            Node::Sin(a) => match self.turned(a) {
                Some(j) => quote!(t.0[#j][0]),
                None => call("sin", self.emit(a)),
            },
            Node::Cos(a) => match self.turned(a) {
                Some(j) => quote!(t.0[#j][1]),
                None => call("cos", self.emit(a)),
            },
        };
        let shared_cost = if generic { 1 } else { SHARED_COST };
        if self.uses[id] < 2 || self.cost[id] < shared_cost {
            return code;
        }
        let name = format_ident!("cse{}", self.lets.len());
        self.lets.push(quote!(let #name = #code;));
        self.name[id] = Some(name.clone());
        quote!(#name)
    }
}

/// `(true, -e)` for a term with a negative numeric factor, else `(false, e)`.
fn split_sign(e: &Expr) -> (bool, Expr) {
    match e {
        Expr::Num(n) if *n < 0.0 => (true, Expr::Num(-n)),
        Expr::Product(fs) => match fs.first() {
            Some(Expr::Num(n)) if *n < 0.0 => {
                let mut rest = fs.clone();
                rest[0] = Expr::Num(-n);
                (true, Expr::Product(rest).simplify())
            }
            _ => (false, e.clone()),
        },
        _ => (false, e.clone()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cos_x0() -> Expr {
        Expr::Cos(Box::new(Expr::Input(0)))
    }

    #[test]
    fn a_repeated_call_is_bound_once_and_named_where_it_occurs() {
        let a = Expr::times(cos_x0(), Expr::Unknown(0));
        let b = Expr::times(cos_x0(), Expr::Unknown(1));
        let mut emitter = Emitter::new(Arithmetic::F64);
        emitter.count(&a);
        emitter.count(&b);
        let (ta, tb) = (
            emitter.tokens(&a).to_string(),
            emitter.tokens(&b).to_string(),
        );
        let lets = emitter.bindings().to_string();
        assert_eq!(
            lets,
            "let cse0 = :: linkage :: __private :: cos (x [0usize]) ;"
        );
        assert_eq!(ta, "(cse0 * v [0usize])");
        assert_eq!(tb, "(cse0 * v [1usize])");
    }

    #[test]
    fn cheap_or_single_subexpressions_are_written_out() {
        // v0 - c0 twice: one operation, left to the compiler; cos(x0) once: nothing to share.
        let d = Expr::minus(Expr::Unknown(0), Expr::Constant(0));
        let a = Expr::times(d.clone(), cos_x0());
        let b = Expr::times(d, Expr::Unknown(2));
        let mut emitter = Emitter::new(Arithmetic::F64);
        emitter.count(&a);
        emitter.count(&b);
        let _ = (emitter.tokens(&a), emitter.tokens(&b));
        assert!(emitter.bindings().is_empty());
    }

    #[test]
    fn generic_bodies_bind_every_repeated_operation_and_conversion() {
        // The same v0 - c0 twice: in `f64` left to the compiler, for a generic scalar bound
        // once, with the conversion of c0 it reads.
        let d = Expr::minus(Expr::Unknown(0), Expr::Constant(0));
        let a = Expr::times(d.clone(), Expr::Unknown(1));
        let b = Expr::Square(Box::new(d));
        let mut emitter = Emitter::new(Arithmetic::Generic);
        emitter.count(&a);
        emitter.count(&b);
        let (ta, tb) = (
            emitter.tokens(&a).to_string(),
            emitter.tokens(&b).to_string(),
        );
        assert_eq!(
            emitter.bindings().to_string(),
            "let cse0 = T :: from_f64 (c [0usize]) ; let cse1 = (v [0usize] - cse0) ;"
        );
        assert_eq!(ta, "(cse1 * v [1usize])");
        assert_eq!(tb, ":: linkage :: Scalar :: sq (cse1)");
    }

    #[test]
    fn without_counts_the_tree_is_written_as_before() {
        let e = Expr::minus(
            Expr::times(Expr::Num(2.0), Expr::Unknown(0)),
            Expr::times(cos_x0(), Expr::Constant(1)),
        );
        assert_eq!(
            tokens(&e).to_string(),
            "((2f64 * v [0usize]) - (:: linkage :: __private :: cos (x [0usize]) * c [1usize]))"
        );
    }
}
