//! Emission of the factorisation planned in [`crate::factor`]: straight-line elimination of
//! the static pivots, the Schur complement, its LU ([`crate::emit::lu`]), and the matching
//! solve.
//!
//! The generated `Factor` is a flat `[f64; _]`: entry 0 says which factors of the complement
//! are valid (0: the fixed pivot order, 1: the partial-pivoting fallback), then the static
//! multipliers and static-row entries that depend on (v, x) (those that depend on the geometry
//! alone are read from the constants again in the solve), then the complement's factors.

use crate::emit::expr::{lit, tokens, Arithmetic, Emitter};
use crate::emit::lu::{self as emit_lu, Region};
use crate::expr::{Expr, Var};
use crate::factor::pivot_order::MAX_MULTIPLIER;
use crate::factor::{count_ops, Plan};
use crate::model::Model;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use std::collections::HashMap;

/// Operation counts of the generated code, for the type's documentation.
pub fn operations_doc(
    model: &Model,
    jac: &[(usize, usize, Expr)],
    plan: &Plan,
    factor: (usize, usize),
) -> String {
    let sum = |es: &mut dyn Iterator<Item = &Expr>| {
        es.map(count_ops)
            .fold((0, 0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2))
    };
    let f = sum(&mut model.equations.iter());
    let j = sum(&mut jac.iter().map(|(_, _, e)| e));
    let k = plan.complement();
    let (fma, mul, div) = plan.lu.operations();
    let fill = plan.lu.filled.iter().flatten().filter(|&&x| x).count()
        - plan.lu.initial.iter().flatten().filter(|&&x| x).count();
    format!(
        "Generated code: F(v, x) {} additions, {} multiplications, {} sin/cos; ∂F/∂v ({} nonzeros) {} additions, {} multiplications, {} sin/cos; factorisation of ∂F/∂v ({} rows with a common numeric factor divided out): {} static pivots eliminated in {} additions and {} multiplications, then the {k}×{k} complement factored in a pivot order fixed at generation time for its sparsity ({} nonzeros, {fill} fill-ins; {fma} multiply-adds, {mul} multiplications, {div} reciprocals), redone with partial pivoting when a multiplier exceeds {MAX_MULTIPLIER}.",
        f.0,
        f.1,
        f.2,
        jac.len(),
        j.0,
        j.1,
        j.2,
        plan.row_scale.iter().filter(|&&s| s != 1.0).count(),
        plan.statics.len(),
        factor.0,
        factor.1,
        plan.lu.initial.iter().flatten().filter(|&&x| x).count(),
    )
}

/// Whether an expression is fixed by the geometry alone (no unknown, no input).
fn is_constant(e: &Expr, n: usize, m: usize) -> bool {
    !(0..n).any(|i| e.depends_on(Var::Unknown(i))) && !(0..m).any(|j| e.depends_on(Var::Input(j)))
}

/// A value in emitted code: a number known now, or code. Numbers fold, so that no −1 or 1 is
/// ever multiplied at run time.
#[derive(Clone)]
enum Value {
    Num(f64),
    Code(TokenStream),
}

impl Value {
    /// B's entry `e`, written `code` where it is not a number.
    fn of(e: &Expr, code: TokenStream) -> Value {
        match e {
            Expr::Num(x) => Value::Num(*x),
            _ => Value::Code(code),
        }
    }

    fn scaled(self, s: f64) -> Value {
        match self {
            Value::Num(x) => Value::Num(x * s),
            Value::Code(t) if s == 1.0 => Value::Code(t),
            Value::Code(t) if s == -1.0 => Value::Code(quote!((-#t))),
            Value::Code(t) => {
                let s = lit(s);
                Value::Code(quote!((#t * #s)))
            }
        }
    }

    fn times(self, other: Value) -> Value {
        match (self, other) {
            (Value::Num(a), Value::Num(b)) => Value::Num(a * b),
            (Value::Num(a), v) | (v, Value::Num(a)) => v.scaled(a),
            (Value::Code(a), Value::Code(b)) => Value::Code(quote!((#a * #b))),
        }
    }

    fn tokens(&self) -> TokenStream {
        match self {
            Value::Num(x) => lit(*x),
            Value::Code(t) => t.clone(),
        }
    }

    /// `self * w` as `(negative, magnitude)`, with the fewest operations.
    fn times_code(&self, w: TokenStream) -> (bool, TokenStream) {
        match self {
            Value::Num(x) if x.abs() == 1.0 => (*x < 0.0, w),
            Value::Num(x) => {
                let m = lit(x.abs());
                (*x < 0.0, quote!(#m * #w))
            }
            Value::Code(t) => (false, quote!(#t * #w)),
        }
    }

    /// `+ self`, or `- |self|` for a negative number.
    fn plus(&self) -> TokenStream {
        match self {
            Value::Num(x) if *x < 0.0 => {
                let m = lit(-x);
                quote!(- #m)
            }
            v => {
                let v = v.tokens();
                quote!(+ #v)
            }
        }
    }
}

/// How a value the solve needs reaches it: stored at an offset of the factor storage by
/// `factor`, or evaluated from the constants in the solve itself.
enum Kept {
    Stored(usize),
    Constant(Value),
}

impl Kept {
    fn value(&self) -> Value {
        match self {
            Kept::Stored(o) => Value::Code(quote!(f[#o])),
            Kept::Constant(v) => v.clone(),
        }
    }
}

/// The static pivots' part of the factors. With g(i, s) = −Y(i, s) / p_s (the negated
/// multiplier of rest row i by static row s) and X(s, j) the static rows' entries, the
/// complement is Z + g X, the solve's forward step adds g times the static rows' right-hand
/// sides, and its back-substitution subtracts X times the complement's solution.
struct Statics<'a> {
    plan: &'a Plan,
    jac: &'a [(usize, usize, Expr)],
    /// `(rest row, static)` → where g lives.
    g: HashMap<(usize, usize), Kept>,
    /// `(static, rest column)` → where X lives.
    x: HashMap<(usize, usize), Kept>,
    /// Storage entries used: entry 0 is the flag, the static values follow.
    len: usize,
}

impl<'a> Statics<'a> {
    fn new(plan: &'a Plan, jac: &'a [(usize, usize, Expr)], m: usize) -> Self {
        let n = plan.n;
        let mut next = 1;
        let mut keep = |e: &Expr, value: Value| {
            if is_constant(e, n, m) {
                Kept::Constant(value)
            } else {
                next += 1;
                Kept::Stored(next - 1)
            }
        };
        let mut g = HashMap::new();
        let mut x = HashMap::new();
        for (s, &(r, c, p)) in plan.statics.iter().enumerate() {
            for &i in &plan.rows {
                if let Some(e) = entry(jac, i, c) {
                    let value = Value::of(&jac[e].2, tokens(&jac[e].2)).scaled(-1.0 / p);
                    g.insert((i, s), keep(&jac[e].2, value));
                }
            }
            for &j in &plan.cols {
                if let Some(e) = entry(jac, r, j) {
                    let value = Value::of(&jac[e].2, tokens(&jac[e].2));
                    x.insert((s, j), keep(&jac[e].2, value));
                }
            }
        }
        Statics {
            plan,
            jac,
            g,
            x,
            len: next,
        }
    }

    /// Stores of the values kept for the solve, B's entries written by `value`, and the
    /// values that feed no entry of the complement (their finiteness is not otherwise seen).
    fn stores(&self, value: &dyn Fn(usize) -> TokenStream) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let (mut stores, mut sinks) = (Vec::new(), Vec::new());
        for (s, &(r, c, p)) in self.plan.statics.iter().enumerate() {
            let row_used = self
                .plan
                .cols
                .iter()
                .any(|&j| entry(self.jac, r, j).is_some());
            let column_used = self
                .plan
                .rows
                .iter()
                .any(|&i| entry(self.jac, i, c).is_some());
            for &i in &self.plan.rows {
                if let (Some(Kept::Stored(o)), Some(e)) =
                    (self.g.get(&(i, s)), entry(self.jac, i, c))
                {
                    let g = Value::of(&self.jac[e].2, value(e))
                        .scaled(-1.0 / p)
                        .tokens();
                    stores.push(quote!(f[#o] = #g;));
                    if !row_used {
                        sinks.push(value(e));
                    }
                }
            }
            for &j in &self.plan.cols {
                if let (Some(Kept::Stored(o)), Some(e)) =
                    (self.x.get(&(s, j)), entry(self.jac, r, j))
                {
                    let x = value(e);
                    stores.push(quote!(f[#o] = #x;));
                    if !column_used {
                        sinks.push(value(e));
                    }
                }
            }
        }
        (stores, sinks)
    }

    /// The complement's entry at rest row `i`, rest column `j`: Z + Σ g X, with B's entries
    /// written by `value`; `None` where it is structurally zero.
    fn complement(
        &self,
        i: usize,
        j: usize,
        value: &dyn Fn(usize) -> TokenStream,
    ) -> Option<TokenStream> {
        let of = |e: usize| Value::of(&self.jac[e].2, value(e));
        let mut terms: Vec<Value> = entry(self.jac, i, j).map(of).into_iter().collect();
        for &(r, c, p) in &self.plan.statics {
            if let (Some(ey), Some(ex)) = (entry(self.jac, i, c), entry(self.jac, r, j)) {
                terms.push(of(ey).scaled(-1.0 / p).times(of(ex)));
            }
        }
        let mut terms = terms.into_iter();
        let first = terms.next()?.tokens();
        let rest = terms.map(|t| t.plus());
        Some(quote!(#first #(#rest)*))
    }

    /// `(additions, multiplications)` of the complement's entries.
    fn operations(&self) -> (usize, usize) {
        let (mut adds, mut mults) = (0, 0);
        for &i in &self.plan.rows {
            for &j in &self.plan.cols {
                let mut terms = usize::from(entry(self.jac, i, j).is_some());
                for &(r, c, p) in &self.plan.statics {
                    if entry(self.jac, i, c).is_some() && entry(self.jac, r, j).is_some() {
                        terms += 1;
                        mults += 1 + usize::from(p != -1.0);
                    }
                }
                adds += terms.saturating_sub(1);
            }
        }
        (adds, mults)
    }
}

/// Whether an expression calls sin or cos.
fn has_call(e: &Expr) -> bool {
    match e {
        Expr::Sin(_) | Expr::Cos(_) => true,
        Expr::Sum(ts) | Expr::Product(ts) => ts.iter().any(has_call),
        Expr::Square(e) => has_call(e),
        Expr::Num(_) | Expr::Unknown(_) | Expr::Input(_) | Expr::Constant(_) => false,
    }
}

fn entry(jac: &[(usize, usize, Expr)], r: usize, c: usize) -> Option<usize> {
    jac.iter().position(|(a, b, _)| *a == r && *b == c)
}

/// `(type, trait functions, (additions, multiplications))`. With `turns`, the fast path reads
/// the inputs' sines and cosines from `t` (`factor_turned`; `factor` evaluates them and calls
/// it); the cold fallback evaluates its own.
pub fn factor(
    plan: &Plan,
    m: usize,
    nc: usize,
    turns: bool,
) -> (TokenStream, TokenStream, (usize, usize)) {
    let n = plan.n;
    let k = plan.complement();
    let jac = &plan.jac[..];
    let statics = Statics::new(plan, jac, m);
    // An entry that is another's negation (2(b − a) beside 2(a − b)) is written as such, so
    // that the compiler folds the sign into the operation that uses it.
    let mut negation_of: Vec<Option<usize>> = vec![None; jac.len()];
    for i in 0..jac.len() {
        let minus = jac[i].2.clone().negated();
        negation_of[i] = (0..i).find(|&j| negation_of[j].is_none() && jac[j].2 == minus);
    }
    // The fallback names every entry of B up front; the fast path writes each where it is
    // used, so that it is computed just before (the compiler merges the repeats) and fewer
    // values are live at a time; entries with sin or cos, which the compiler does not merge,
    // are named in both.
    let name = |i: usize| {
        let e = format_ident!("e{}", i);
        quote!(#e)
    };
    let define = |emitter: &mut Emitter, i: usize| {
        let e = match negation_of[i] {
            Some(j) => {
                let e_j = name(j);
                quote!(-#e_j)
            }
            None => emitter.tokens(&jac[i].2),
        };
        let e_i = name(i);
        quote!(let #e_i = #e;)
    };
    // Each path names its entries through one emitter, which binds what they share (the
    // rotation of an active wrist in every entry of the pivots it carries).
    let define_all = |entries: &[usize], arithmetic: Arithmetic| {
        let mut emitter = Emitter::new(arithmetic);
        for &i in entries.iter().filter(|&&i| negation_of[i].is_none()) {
            emitter.count(&jac[i].2);
        }
        let defined: Vec<TokenStream> = entries.iter().map(|&i| define(&mut emitter, i)).collect();
        let lets = emitter.bindings();
        quote!(#lets #(#defined)*)
    };
    let named = |i: usize| name(i);
    let inline = |i: usize| {
        if has_call(&jac[i].2) {
            return name(i);
        }
        let e = match negation_of[i] {
            Some(j) => {
                let e = tokens(&jac[j].2);
                quote!(-(#e))
            }
            None => tokens(&jac[i].2),
        };
        quote!((#e))
    };
    let evals = define_all(&(0..jac.len()).collect::<Vec<_>>(), Arithmetic::F64);
    let call_evals = define_all(
        &(0..jac.len())
            .filter(|&i| has_call(&jac[i].2))
            .collect::<Vec<_>>(),
        if turns {
            Arithmetic::Turned
        } else {
            Arithmetic::F64
        },
    );
    let (named_stores, named_sinks) = statics.stores(&named);
    let (stores, sinks) = statics.stores(&inline);
    let sink_check = |sinks: &[TokenStream]| {
        if sinks.is_empty() {
            return quote!();
        }
        quote! {
            if !(#(#sinks)+*).is_finite() {
                return ::core::option::Option::None;
            }
        }
    };
    let (named_sink_check, sink_check) = (sink_check(&named_sinks), sink_check(&sinks));
    let base = statics.len;
    let region = Region {
        fixed: base,
        dense: base,
    };
    let size = base + Region::fixed_len(&plan.lu).max(Region::dense_len(k));
    let scale = plan.sign
        * plan.statics.iter().map(|s| s.2).product::<f64>()
        * plan.row_scale.iter().product::<f64>();
    let scaled_det = match scale {
        1.0 => quote!(det),
        -1.0 => quote!(-det),
        _ => {
            let scale = lit(scale);
            quote!(#scale * det)
        }
    };
    let fixed = emit_lu::fixed_factor(&plan.lu, &region, &|i, j| {
        statics
            .complement(plan.rows[i], plan.cols[j], &inline)
            .unwrap_or_else(|| quote!(0.0f64))
    });
    let dense_entries = (0..k).flat_map(|i| {
        let statics = &statics;
        (0..k).filter_map(move |j| {
            statics
                .complement(plan.rows[i], plan.cols[j], &named)
                .map(|e| quote!(z[#i][#j] = #e;))
        })
    });
    let dense = emit_lu::dense_factor(k, &region);

    // The solve: forward elimination of the static rows, the complement, back-substitution,
    // on one local per row (`w3` for row 3), which the compiler keeps in registers where it
    // can; an array would live in memory, its address being given to the fallback.
    let w = |r: usize| {
        let w = format_ident!("w{}", r);
        quote!(#w)
    };
    let mut forward = Vec::new();
    for (s, &(r, _, _)) in plan.statics.iter().enumerate() {
        for &i in &plan.rows {
            if let Some(g) = statics.g.get(&(i, s)) {
                let (wi, wr) = (w(i), w(r));
                forward.push(match g.value().times_code(wr) {
                    (false, t) => quote!(#wi += #t;),
                    (true, t) => quote!(#wi -= #t;),
                });
            }
        }
    }
    // After the complement's solve, w(rows[p]) holds the unknown cols[p].
    let solution_at: HashMap<usize, usize> = plan
        .cols
        .iter()
        .zip(&plan.rows)
        .map(|(&c, &r)| (c, r))
        .collect();
    let back = plan.statics.iter().enumerate().map(|(s, &(r, c, p))| {
        let wr = w(r);
        // x_c = (b_r − Σ X x) / p; for p = −1 written Σ X x − b_r, without a negation, b_r
        // after the first product. The products in the order the complement's back-substitution
        // yields their unknowns (its last pivot first), so that the one solved last is the
        // last operation, not the first of a chain waiting for it.
        let products: Vec<(bool, TokenStream)> = plan
            .cols
            .iter()
            .rev()
            .filter_map(|&j| {
                statics
                    .x
                    .get(&(s, j))
                    .map(|x| x.value().times_code(w(solution_at[&j])))
            })
            .collect();
        if p == -1.0 {
            let sum = products
                .iter()
                .enumerate()
                .map(|(k, (neg, t))| match (k, neg) {
                    (0, false) => quote!(#t - #wr),
                    (0, true) => quote!(-#t - #wr),
                    (_, false) => quote!(+ #t),
                    (_, true) => quote!(- #t),
                });
            return if products.is_empty() {
                quote!(b[#c] = -#wr;)
            } else {
                quote!(b[#c] = #(#sum)*;)
            };
        }
        let terms = products.iter().map(|(neg, t)| match neg {
            false => quote!(- #t),
            true => quote!(+ #t),
        });
        match p {
            1.0 => quote!(b[#c] = #wr #(#terms)*;),
            _ => {
                let inv = lit(1.0 / p);
                quote!(b[#c] = (#wr #(#terms)*) * #inv;)
            }
        }
    });
    let scatter = plan.cols.iter().zip(&plan.rows).map(|(&c, &r)| {
        let wr = w(r);
        quote!(b[#c] = #wr;)
    });
    let fixed_solve = emit_lu::fixed_solve(&plan.lu, &region, &plan.rows, &w);
    // The rows factored with a common factor taken out take it out of the right-hand side.
    let unscale = plan
        .row_scale
        .iter()
        .enumerate()
        .filter(|(_, &s)| s != 1.0)
        .map(|(r, &s)| {
            let (inv, wr) = (lit(1.0 / s), w(r));
            quote!(#wr *= #inv;)
        });
    let dense_solve = emit_lu::dense_solve(k, &region, &plan.rows);
    let ws: Vec<TokenStream> = (0..n).map(w).collect();
    let ty = quote!([f64; #size]);
    let (factor_name, turns_param, factor_wrapper) = if turns {
        (
            format_ident!("factor_turned"),
            quote!(t: &::linkage::Turns<#m>,),
            quote! {
                #[inline]
                fn factor(&self, v: &[f64; #n], x: &[f64; #m], f: &mut Self::Factor) -> ::core::option::Option<::linkage::lu::Factored> {
                    self.factor_turned(v, x, &self.turns(x), f)
                }
            },
        )
    } else {
        (format_ident!("factor"), quote!(), quote!())
    };
    let fns = quote! {
        fn new_factor(&self) -> Self::Factor {
            [0.0; #size]
        }

        #factor_wrapper

        #[cfg_attr(not(debug_assertions), inline(always))]
        #[allow(unused_variables, unused_mut)]
        fn #factor_name(&self, v: &[f64; #n], x: &[f64; #m], #turns_param f: &mut Self::Factor) -> ::core::option::Option<::linkage::lu::Factored> {
            /// The fallback: B again, its complement factored with partial pivoting.
            #[cold]
            #[inline(never)]
            // A system that every row's own unknown solves (a spherical motor) leaves no dense
            // block: its loops run over 0..0.
            #[allow(unused_variables, unused_mut, clippy::reversed_empty_ranges)]
            fn pivoted(c: &[f64; #nc], v: &[f64; #n], x: &[f64; #m], f: &mut [f64; #size]) -> ::core::option::Option<::linkage::lu::Factored> {
                #evals
                #named_sink_check
                #(#named_stores)*
                let mut z = [[0.0f64; #k]; #k];
                #(#dense_entries)*
                let (det, pivot_ratio) = #dense?;
                let det = #scaled_det;
                if !det.is_finite() {
                    return ::core::option::Option::None;
                }
                f[0] = 1.0;
                ::core::option::Option::Some(::linkage::lu::Factored { det, pivot_ratio })
            }
            let c = &self.constants;
            #call_evals
            #sink_check
            let ::core::option::Option::Some((det, pivot_ratio)) = (#fixed) else {
                return pivoted(c, v, x, f);
            };
            #(#stores)*
            let det = #scaled_det;
            f[0] = 0.0;
            ::core::option::Option::Some(::linkage::lu::Factored { det, pivot_ratio })
        }

        #[cfg_attr(not(debug_assertions), inline(always))]
        #[allow(unused_variables, unused_mut)]
        fn solve(&self, f: &Self::Factor, b: &mut [f64; #n]) {
            #[cold]
            #[inline(never)]
            #[allow(clippy::reversed_empty_ranges)]
            fn pivoted(f: &[f64; #size], w: &mut [f64; #n]) {
                #dense_solve
            }
            let c = &self.constants;
            let [#(mut #ws),*] = *b;
            #(#unscale)*
            #(#forward)*
            if f[0] == 0.0 {
                #fixed_solve
            } else {
                let mut w = [#(#ws),*];
                pivoted(f, &mut w);
                [#(#ws),*] = w;
            }
            #(#scatter)*
            #(#back)*
        }
    };
    (ty, fns, statics.operations())
}
