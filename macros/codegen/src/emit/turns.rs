//! Sines and cosines of the inputs, evaluated once per fixed inputs: which inputs the kernels
//! turn by, and the generated `turns`.
//!
//! A rotary mechanism's residual and factorisation evaluate sin xⱼ and cos xⱼ of its crank
//! angles; a Newton run keeps x fixed, so the runtime evaluates them once
//! (`Mechanism::turns`) and passes them to `residual_turned` and `factor_turned`, whose bodies
//! read them from `t` (`Arithmetic::Turned`). Mechanisms that turn by no input keep the plain
//! kernels and the trait's defaults.

use crate::expr::Expr;
use proc_macro2::TokenStream;
use quote::quote;

/// For each input, whether its sine and its cosine occur (as `sin(xⱼ)`, `cos(xⱼ)`) in `exprs`.
pub fn turned_inputs<'e>(m: usize, exprs: impl Iterator<Item = &'e Expr>) -> Vec<[bool; 2]> {
    fn visit(e: &Expr, out: &mut [[bool; 2]]) {
        match e {
            Expr::Sin(a) | Expr::Cos(a) => {
                if let Expr::Input(j) = **a {
                    out[j][usize::from(matches!(e, Expr::Cos(_)))] = true;
                }
                visit(a, out);
            }
            Expr::Sum(ts) | Expr::Product(ts) => ts.iter().for_each(|t| visit(t, out)),
            Expr::Square(a) => visit(a, out),
            Expr::Num(_) | Expr::Unknown(_) | Expr::Input(_) | Expr::Constant(_) => {}
        }
    }
    let mut out = vec![[false; 2]; m];
    exprs.for_each(|e| visit(e, &mut out));
    out
}

/// The body of the generated `turns`: each sine and cosine that occurs, evaluated once; 0 for
/// the others (never read).
pub fn turns_body(turned: &[[bool; 2]]) -> TokenStream {
    let entries = turned.iter().enumerate().map(|(j, &[s, c])| {
        let sin = if s {
            quote!(::linkage::__private::sin(x[#j]))
        } else {
            quote!(0.0)
        };
        let cos = if c {
            quote!(::linkage::__private::cos(x[#j]))
        } else {
            quote!(0.0)
        };
        quote!([#sin, #cos])
    });
    quote!(::linkage::Turns([#(#entries),*]))
}
