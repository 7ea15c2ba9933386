//! Emission of the Newton step at lifted points ([`crate::reduce`]): `lift`, which rebuilds
//! the unknowns of the affine static rows from the others so that those rows hold exactly, and
//! `newton_step_lifted`, the Newton correction at such a point.
//!
//! The step is the full one ([`crate::emit_factor`]) without what is known to be zero there:
//! the lifted rows' residuals, the forward elimination of their right-hand sides (and the
//! multipliers stored for it), and their right-hand sides in the back-substitution. Every
//! other operation is the full step's, in the same order, so its correction, determinant and
//! pivot ratio are bit for bit those of `newton_step` at the same point; the lifted unknowns'
//! corrections are still computed, so that the correction's size is that of the full one.

use crate::emit_expr::tokens;
use crate::expr::Expr;
use crate::reduce::Lift;
use proc_macro2::TokenStream;
use quote::quote;

/// What the full factorisation and solve are made of ([`crate::emit_factor::factor`]), with
/// the lifted rows' parts already left out of `stores`, `forward` and `back`.
pub struct Pieces<'a> {
    pub n: usize,
    pub m: usize,
    pub lifts: &'a [Lift],
    pub equations: &'a [Expr],
    pub call_evals: &'a [TokenStream],
    pub sink_check: &'a TokenStream,
    pub fixed: &'a TokenStream,
    pub stores: &'a [TokenStream],
    pub scaled_det: &'a TokenStream,
    pub unscale: &'a [TokenStream],
    pub forward: &'a [TokenStream],
    pub fixed_solve: &'a TokenStream,
    pub scatter: &'a [TokenStream],
    pub back: &'a [TokenStream],
    pub ws: &'a [TokenStream],
}

/// `LIFTS`, `lift` and `newton_step_lifted`; nothing where no row lifts (the trait's defaults:
/// a mechanism without affine rows pays nothing).
pub fn lifted(p: &Pieces) -> TokenStream {
    if p.lifts.is_empty() {
        return quote!();
    }
    let Pieces {
        n,
        m,
        lifts,
        equations,
        call_evals,
        sink_check,
        fixed,
        stores,
        scaled_det,
        unscale,
        forward,
        fixed_solve,
        scatter,
        back,
        ws,
    } = p;
    let lift = lifts.iter().map(|l| {
        let (c, rest) = (l.col, tokens(&l.rest));
        if l.negate {
            quote!(v[#c] = -#rest;)
        } else {
            quote!(v[#c] = #rest;)
        }
    });
    let residual = equations.iter().enumerate().map(|(i, e)| {
        if lifts.iter().any(|l| l.row == i) {
            quote!(delta[#i] = 0.0;)
        } else {
            let e = tokens(e);
            quote!(delta[#i] = #e;)
        }
    });
    quote! {
        const LIFTS: bool = true;

        #[inline]
        #[allow(unused_variables)]
        fn lift(&self, v: &mut [f64; #n], x: &[f64; #m]) {
            let c = &self.constants;
            #(#lift)*
        }

        #[inline]
        #[allow(unused_variables, unused_mut)]
        fn newton_step_lifted(
            &self,
            v: &mut [f64; #n],
            x: &[f64; #m],
            f: &mut Self::Factor,
            delta: &mut [f64; #n],
        ) -> ::core::option::Option<::linkage::lu::Factored> {
            /// A multiplier above the bound, a zero pivot or B not finite: the full
            /// factorisation (with its partial-pivoting fallback) and solve, on right-hand
            /// sides that are 0 in the lifted rows.
            #[cold]
            #[inline(never)]
            fn fallback<S: ::linkage::Mechanism<#n, #m>>(
                sys: &S,
                v: &[f64; #n],
                x: &[f64; #m],
                f: &mut S::Factor,
                delta: &mut [f64; #n],
            ) -> ::core::option::Option<::linkage::lu::Factored> {
                let info = sys.factor(v, x, f)?;
                sys.solve(f, delta);
                ::core::option::Option::Some(info)
            }
            self.lift(v, x);
            let v = &*v;
            let c = &self.constants;
            #(#residual)*
            #(#call_evals)*
            #sink_check
            let ::core::option::Option::Some((det, pivot_ratio)) = (#fixed) else {
                return fallback(self, v, x, f, delta);
            };
            #(#stores)*
            let det = #scaled_det;
            f[0] = 0.0;
            let b = &mut *delta;
            let [#(mut #ws),*] = *b;
            #(#unscale)*
            #(#forward)*
            #fixed_solve
            #(#scatter)*
            #(#back)*
            ::core::option::Option::Some(::linkage::lu::Factored { det, pivot_ratio })
        }
    }
}
