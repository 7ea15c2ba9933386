//! Emission of the factorisation planned in [`crate::factor`]: straight-line elimination of
//! the static pivots, the Schur complement, and the matching solve.

use crate::emit::{lit, tokens};
use crate::expr::Expr;
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
    format!(
        "Generated code: F(v, x) {} additions, {} multiplications, {} sin/cos; ∂F/∂v ({} nonzeros) {} additions, {} multiplications, {} sin/cos; factorisation of ∂F/∂v: {} static pivots eliminated in {} additions and {} multiplications, then a {k}×{k} dense LU with partial pivoting (about {} multiply-adds).",
        f.0,
        f.1,
        f.2,
        jac.len(),
        j.0,
        j.1,
        j.2,
        plan.statics.len(),
        factor.0,
        factor.1,
        k * k * k / 3
    )
}

/// `(type, trait functions, (additions, multiplications))`.
pub fn factor(
    plan: &Plan,
    jac: &[(usize, usize, Expr)],
    m: usize,
) -> (TokenStream, TokenStream, (usize, usize)) {
    let n = plan.n;
    let k = plan.complement();
    let entry = |r: usize, c: usize| jac.iter().position(|(a, b, _)| *a == r && *b == c);
    let e_name = |i: usize| format_ident!("e{}", i);
    let evals = jac.iter().enumerate().map(|(i, (_, _, e))| {
        let name = e_name(i);
        let e = tokens(e);
        quote!(let #name = #e;)
    });
    let (mut adds, mut mults) = (0usize, 0usize);
    // Multipliers l(i, s) for rest rows i with an entry in static column c_s.
    let mut l_index = HashMap::new();
    let mut l_stmts = Vec::new();
    for (s, &(_, c, p)) in plan.statics.iter().enumerate() {
        for &i in &plan.rows {
            if let Some(ei) = entry(i, c) {
                let idx = l_index.len();
                l_index.insert((i, s), idx);
                let e = e_name(ei);
                let inv = lit(1.0 / p);
                l_stmts.push(if p == -1.0 {
                    quote!(f.l[#idx] = -#e;)
                } else {
                    quote!(f.l[#idx] = #e * #inv;)
                });
                mults += usize::from(p != -1.0);
            }
        }
    }
    // The static rows' other entries, kept for back-substitution.
    let mut u_index = HashMap::new();
    let mut u_stmts = Vec::new();
    for (s, &(r, _, _)) in plan.statics.iter().enumerate() {
        for &j in &plan.cols {
            if let Some(ej) = entry(r, j) {
                let idx = u_index.len();
                u_index.insert((s, j), idx);
                let e = e_name(ej);
                u_stmts.push(quote!(f.u[#idx] = #e;));
            }
        }
    }
    // The Schur complement Z − Y D⁻¹ X.
    let mut z_stmts = Vec::new();
    for (ii, &i) in plan.rows.iter().enumerate() {
        for (jj, &j) in plan.cols.iter().enumerate() {
            let mut terms = Vec::new();
            if let Some(e) = entry(i, j) {
                let e = e_name(e);
                terms.push(quote!(#e));
            }
            for s in 0..plan.statics.len() {
                if let (Some(&li), Some(&uj)) = (l_index.get(&(i, s)), u_index.get(&(s, j))) {
                    terms.push(quote!(- f.l[#li] * f.u[#uj]));
                    adds += 1;
                    mults += 1;
                }
            }
            z_stmts.push(if terms.is_empty() {
                quote!(f.z[#ii][#jj] = 0.0;)
            } else {
                quote!(f.z[#ii][#jj] = #(#terms)*;)
            });
        }
    }
    let (nl, nu) = (l_index.len(), u_index.len());
    let scale = plan.sign * plan.statics.iter().map(|s| s.2).product::<f64>();
    let det = match scale {
        1.0 => quote!(piv.det),
        -1.0 => quote!(-piv.det),
        _ => {
            let scale = lit(scale);
            quote!(#scale * piv.det)
        }
    };
    let mut forward = Vec::new();
    for (s, &(r, _, _)) in plan.statics.iter().enumerate() {
        for &i in &plan.rows {
            if let Some(&li) = l_index.get(&(i, s)) {
                forward.push(quote!(b[#i] -= f.l[#li] * b[#r];));
            }
        }
    }
    let gather = plan
        .rows
        .iter()
        .enumerate()
        .map(|(ii, &i)| quote!(y[#ii] = b[#i];));
    let scatter = plan
        .cols
        .iter()
        .enumerate()
        .map(|(jj, &j)| quote!(out[#j] = y[#jj];));
    let back = plan.statics.iter().enumerate().map(|(s, &(r, c, p))| {
        let terms = plan
            .cols
            .iter()
            .filter_map(|&j| u_index.get(&(s, j)).map(|&uj| quote!(- f.u[#uj] * out[#j])));
        if p == -1.0 {
            return quote!(out[#c] = -(b[#r] #(#terms)*););
        }
        let inv = lit(1.0 / p);
        quote!(out[#c] = (b[#r] #(#terms)*) * #inv;)
    });
    let ty = quote!(::linkage::lu::SparseFactor<#k, #nl, #nu>);
    let dense_lu = unrolled_lu(k);
    let dense_solve = unrolled_solve(k);
    let fns = quote! {
        fn new_factor(&self) -> Self::Factor {
            ::linkage::lu::SparseFactor::new()
        }

        #[inline]
        #[allow(unused_variables)]
        fn factor(&self, v: &[f64; #n], x: &[f64; #m], f: &mut Self::Factor) -> ::core::option::Option<::linkage::lu::Factored> {
            let c = &self.constants;
            #(#evals)*
            #(#l_stmts)*
            #(#u_stmts)*
            #(#z_stmts)*
            let piv = { #dense_lu };
            f.piv = piv;
            let det = #det;
            if !det.is_finite() {
                return None;
            }
            Some(::linkage::lu::Factored { det, pivot_ratio: piv.pivot_ratio })
        }

        #[inline]
        fn solve(&self, f: &Self::Factor, b: &mut [f64; #n]) {
            #(#forward)*
            let mut y = [0.0f64; #k];
            #(#gather)*
            #dense_solve
            let mut out = [0.0f64; #n];
            #(#scatter)*
            #(#back)*
            *b = out;
        }
    };
    (ty, fns, (adds, mults + plan.statics.len()))
}

/// LU with partial pivoting of the `k`×`k` block `f.z`, unrolled: every loop bound is a
/// literal, so the compiler schedules the whole elimination as straight-line code. Evaluates
/// to `::linkage::lu::Pivots<k>`; returns `None` from the enclosing function when a column has
/// no usable pivot.
fn unrolled_lu(k: usize) -> TokenStream {
    let steps = (0..k).map(|c| {
        let search =
            (c + 1..k).map(|i| quote!(let a = z[#i][#c].abs(); if a > best { best = a; p = #i; }));
        let rows = (c + 1..k).map(|i| {
            let updates = (c + 1..k).map(|j| quote!(z[#i][#j] -= l * pr[#j];));
            quote!({ let l = z[#i][#c] * inv; z[#i][#c] = l; #(#updates)* })
        });
        quote! {
            let mut p = #c;
            let mut best = z[#c][#c].abs();
            #(#search)*
            if !(best > 0.0) || !best.is_finite() {
                return None;
            }
            swaps[#c] = p;
            if p != #c {
                z.swap(#c, p);
                det = -det;
            }
            let pr = z[#c];
            det *= pr[#c];
            pmin = pmin.min(best);
            pmax = pmax.max(best);
            let inv = 1.0 / pr[#c];
            #(#rows)*
        }
    });
    quote! {
        let z = &mut f.z;
        let mut swaps = [0usize; #k];
        let mut det = 1.0f64;
        let (mut pmin, mut pmax) = (f64::INFINITY, 0.0f64);
        #(#steps)*
        ::linkage::lu::Pivots::from_parts(swaps, det, if #k == 0 { 1.0 } else { pmin / pmax })
    }
}

/// The matching solve on `y`, unrolled.
fn unrolled_solve(k: usize) -> TokenStream {
    let permute = (0..k).map(|c| quote!(let p = swaps[#c]; if p != #c { y.swap(#c, p); }));
    let forward = (1..k).flat_map(|i| (0..i).map(move |j| quote!(y[#i] -= f.z[#i][#j] * y[#j];)));
    let backward = (0..k).rev().map(|i| {
        if i + 1 == k {
            return quote!(y[#i] /= f.z[#i][#i];);
        }
        let terms = (i + 1..k).map(|j| quote!(- f.z[#i][#j] * y[#j]));
        quote!(y[#i] = (y[#i] #(#terms)*) / f.z[#i][#i];)
    });
    quote! {
        let swaps = f.piv.swaps();
        #(#permute)*
        #(#forward)*
        #(#backward)*
    }
}
