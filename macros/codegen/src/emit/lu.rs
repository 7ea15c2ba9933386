//! Emission of the Schur complement's LU: the fast path unrolled, in the pivot order fixed at
//! generation time ([`crate::factor::pivot_order`]), touching only the nonzeros of [`Symbolic`]; and
//! the dense partial-pivoting fallback it hands over to when a multiplier exceeds
//! [`MAX_MULTIPLIER`] (or a pivot is zero or not finite), a call of the runtime's LU kernel.
//!
//! Both write their factors into the flat `[f64; _]` storage of the generated `Factor` type at
//! the offsets of [`Region`]. The fixed order stores reciprocal pivots and U's rows divided by
//! their pivot (a unit diagonal), so that its solve only multiplies and the back-substitution
//! has one multiplication and one subtraction, not two multiplications, between one unknown and
//! the next.
//!
//! Finiteness: B is not finite when an entry is NaN or infinite. A non-finite value that flows
//! into a later pivot makes the determinant non-finite; one that flows nowhere (a multiplier
//! whose pivot row has no other entry, an entry of U whose column has nothing below) is added
//! to a sum whose finiteness is checked, so that no NaN can hide in the factors.

use crate::factor::pivot_order::MAX_MULTIPLIER;
use crate::factor::Symbolic;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Where the complement's factors live in the storage: the fixed order's values from `fixed`
/// on (one per nonzero of L and U), the fallback's dense `k`×`k` factors from `dense` and its
/// row swaps (as `f64`) after them. The two overlap: only one is valid at a time.
pub struct Region {
    pub fixed: usize,
    pub dense: usize,
}

impl Region {
    /// Storage entries the fixed order needs.
    pub fn fixed_len(lu: &Symbolic) -> usize {
        lu.filled.iter().flatten().filter(|&&f| f).count()
    }

    /// Storage entries the fallback needs.
    pub fn dense_len(k: usize) -> usize {
        k * k + k
    }
}

fn z(i: usize, j: usize) -> proc_macro2::Ident {
    format_ident!("z{}_{}", i, j)
}

/// Offsets of the fixed order's stored values: the multiplier or U entry at `(i, j)`
/// (i ≠ j), the reciprocal pivot at `(p, p)`.
fn fixed_offsets(lu: &Symbolic, base: usize) -> Vec<Vec<Option<usize>>> {
    let k = lu.size();
    let mut at = vec![vec![None; k]; k];
    let mut next = base;
    for (i, row) in lu.filled.iter().enumerate() {
        for (j, &f) in row.iter().enumerate() {
            if f {
                at[i][j] = Some(next);
                next += 1;
            }
        }
    }
    at
}

/// The fixed-order factorisation as a block that evaluates to `Some((det Z, pivot ratio))`, or
/// `None` when the order is not good enough here. `entry(i, j)` is the complement's entry at a
/// structural nonzero `(i, j)` of `lu.initial`, in pivot order.
pub fn fixed_factor(
    lu: &Symbolic,
    region: &Region,
    entry: &dyn Fn(usize, usize) -> TokenStream,
) -> TokenStream {
    let k = lu.size();
    if k == 0 {
        return quote!(::core::option::Option::Some((1.0f64, 1.0f64)));
    }
    let at = fixed_offsets(lu, region.fixed);
    // Row by row (Doolittle's order): row i takes the multipliers of the rows above it, then
    // yields its part of U. Only the current row and the finished rows of U that are still
    // needed are live, which keeps the registers from spilling much.
    let mut body = Vec::new();
    let mut sinks = Vec::new();
    let mut pivots = Vec::new();
    let mut assigned = lu.initial.clone();
    for i in 0..k {
        for j in 0..k {
            let name = z(i, j);
            if lu.initial[i][j] {
                let e = entry(i, j);
                body.push(quote!(let mut #name = #e;));
            } else if i == j {
                // A pivot that is not a nonzero of the complement (it may fill in).
                body.push(quote!(let mut #name = 0.0f64;));
                assigned[i][i] = true;
            }
        }
        // The pivot's last update, from the row whose pivot comes last, is written
        // `(z_ip * z_pi) * r_p` rather than `m_ip * z_pi`: the product is ready before the
        // reciprocal is, so that one multiplication and one subtraction, not two
        // multiplications, lie between one pivot's reciprocal and the next pivot on the
        // factorisation's critical path (the multiplier is still computed beside it, for the
        // check and the solve). One multiplication more per pivot.
        let last = (0..i).rev().find(|&p| lu.filled[i][p] && lu.filled[p][i]);
        for p in (0..i).filter(|&p| lu.filled[i][p]) {
            let recip = format_ident!("r{}", p);
            let m = format_ident!("m{}_{}", i, p);
            let source = z(i, p);
            let o = at[i][p].unwrap_or(0);
            // The largest and smallest multiplier rather than the largest |multiplier|: no
            // copy for the absolute value (two-operand SSE2), one maxsd and one minsd, written
            // so that the accumulator is their destination. A NaN multiplier is not caught
            // here (the next one replaces a NaN accumulator): it comes from a NaN entry or
            // pivot, which reaches det Z or the sink (see the module documentation).
            body.push(quote! {
                let #m = #source * #recip;
                f[#o] = #m;
                high = if high > #m { high } else { #m };
                low = if low < #m { low } else { #m };
            });
            let right: Vec<usize> = lu.right(p).collect();
            if right.is_empty() {
                sinks.push(quote!(#m));
            }
            for j in right {
                let target = z(i, j);
                let u = z(p, j);
                if j == i && last == Some(p) {
                    body.push(if assigned[i][j] {
                        quote!(#target -= (#source * #u) * #recip;)
                    } else {
                        quote!(let mut #target = -((#source * #u) * #recip);)
                    });
                    assigned[i][j] = true;
                } else if assigned[i][j] {
                    body.push(quote!(#target -= #m * #u;));
                } else {
                    assigned[i][j] = true;
                    body.push(quote!(let mut #target = -(#m * #u);));
                }
            }
        }
        let pivot = z(i, i);
        let recip = format_ident!("r{}", i);
        let ri = at[i][i].unwrap_or(0);
        body.push(quote!(let #recip = 1.0 / #pivot; f[#ri] = #recip;));
        pivots.push(pivot);
        let below_empty = lu.below(i).next().is_none();
        for j in lu.right(i) {
            let u = z(i, j);
            let o = at[i][j].unwrap_or(0);
            // Stored divided by the pivot (U with a unit diagonal): the solve's
            // back-substitution then needs no multiplication after its subtractions.
            body.push(quote!(f[#o] = #u * #recip;));
            if below_empty {
                sinks.push(quote!(#u));
            }
        }
    }
    let max = MAX_MULTIPLIER;
    let sink = if sinks.is_empty() {
        quote!(0.0f64)
    } else {
        quote!(#(#sinks)+*)
    };
    let abs_pivots = pivots.iter().map(|p| quote!(#p.abs()));
    let det = pivots
        .iter()
        .map(|p| quote!(#p))
        .reduce(|a, b| quote!(#a * #b))
        .unwrap_or_else(|| quote!(1.0f64));
    quote! {{
        let (mut high, mut low) = (0.0f64, 0.0f64);
        #(#body)*
        let det = #det;
        let sink: f64 = #sink;
        if high <= #max && low >= -#max && det.is_finite() && det != 0.0 && sink.is_finite() {
            let (mut pmin, mut pmax) = (f64::INFINITY, 0.0f64);
            for a in [#(#abs_pivots),*] {
                pmin = if a < pmin { a } else { pmin };
                pmax = if a > pmax { a } else { pmax };
            }
            ::core::option::Option::Some((det, pmin / pmax))
        } else {
            ::core::option::Option::None
        }
    }}
}

/// The solve with the fixed-order factors on the complement's right-hand side, in place in
/// the locals `w(r)`: `w(rows[p])` holds the right-hand side of the p-th pivot row, and
/// afterwards the solution for the p-th pivot column.
pub fn fixed_solve(
    lu: &Symbolic,
    region: &Region,
    rows: &[usize],
    w: &dyn Fn(usize) -> TokenStream,
) -> TokenStream {
    let k = lu.size();
    let at = fixed_offsets(lu, region.fixed);
    let mut body = Vec::new();
    for p in 0..k {
        let wp = w(rows[p]);
        for i in lu.below(p) {
            let wi = w(rows[i]);
            let o = at[i][p].unwrap_or(0);
            body.push(quote!(#wi -= f[#o] * #wp;));
        }
    }
    // Back-substitution solves the last pivot first: `x_p = w_p r_p − Σ ũ_pj x_j` with U's
    // rows stored divided by their pivot (ũ), each row's terms subtracted in the order their
    // unknowns are solved (the highest pivot first), so that the unknown solved just before is
    // the last operation, not the first of a chain of subtractions that waits for it.
    for p in (0..k).rev() {
        let wp = w(rows[p]);
        let terms: Vec<TokenStream> = lu
            .right(p)
            .rev()
            .map(|j| {
                let wj = w(rows[j]);
                let o = at[p][j].unwrap_or(0);
                quote!(- f[#o] * #wj)
            })
            .collect();
        let o = at[p][p].unwrap_or(0);
        body.push(if terms.is_empty() {
            quote!(#wp *= f[#o];)
        } else {
            quote!(#wp = #wp * f[#o] #(#terms)*;)
        });
    }
    quote!(#(#body)*)
}

/// LU with partial pivoting of the dense `k`×`k` local `z` by the runtime's kernel
/// (`linkage::lu::fallback_factor`, shared by every mechanism with a block of this size: the
/// fallback is cold). Stores the factors and row swaps at `region.dense`; evaluates to
/// `Some((det Z, pivot ratio))`, or `None` when a column has no usable pivot.
pub fn dense_factor(k: usize, region: &Region) -> TokenStream {
    let (base, end) = (region.dense, region.dense + Region::dense_len(k));
    quote!(::linkage::__private::fallback_factor::<#k>(z, &mut f[#base..#end]))
}

/// The solve with the fallback's dense factors, in place in `w` as [`fixed_solve`].
pub fn dense_solve(k: usize, region: &Region, rows: &[usize]) -> TokenStream {
    let (base, end) = (region.dense, region.dense + Region::dense_len(k));
    let gather = rows
        .iter()
        .enumerate()
        .map(|(p, &r)| quote!(y[#p] = w[#r];));
    let scatter = rows
        .iter()
        .enumerate()
        .map(|(p, &r)| quote!(w[#r] = y[#p];));
    quote! {
        let mut y = [0.0f64; #k];
        #(#gather)*
        ::linkage::__private::fallback_solve::<#k>(&f[#base..#end], &mut y);
        #(#scatter)*
    }
}
