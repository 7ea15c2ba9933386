//! Expressions as Rust tokens: the leaves every emitter shares ([`emit`](crate::emit) for the
//! `Mechanism` impl, [`emit_factor`](crate::emit_factor) for the factorisation), so that both
//! depend on this module and neither on the other.

use crate::expr::Expr;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

pub fn lit(x: f64) -> TokenStream {
    let l = Literal::f64_suffixed(x.abs());
    if x.is_sign_negative() {
        quote!((-#l))
    } else {
        quote!(#l)
    }
}

pub fn tokens(e: &Expr) -> TokenStream {
    emit_expr(e, Arithmetic::F64)
}

/// [`tokens`] for the generic scalar `T` of `residual_in` and `jacobian_in`: numbers and
/// constants enter through `T::from_f64`.
pub fn tokens_in(e: &Expr) -> TokenStream {
    emit_expr(e, Arithmetic::Generic)
}

/// The number type an expression is emitted for.
#[derive(Clone, Copy, PartialEq)]
enum Arithmetic {
    F64,
    Generic,
}

fn emit_expr(e: &Expr, a: Arithmetic) -> TokenStream {
    let generic = a == Arithmetic::Generic;
    let call = |f: &str, e: &Expr| {
        let e = emit_expr(e, a);
        let f = format_ident!("{f}");
        if generic {
            quote!(::linkage::Scalar::#f(#e))
        } else {
            quote!(::linkage::__private::#f(#e))
        }
    };
    match e {
        Expr::Num(n) => {
            let n = lit(*n);
            if generic {
                quote!(T::from_f64(#n))
            } else {
                n
            }
        }
        Expr::Unknown(i) => quote!(v[#i]),
        Expr::Input(i) => quote!(x[#i]),
        Expr::Constant(i) if generic => quote!(T::from_f64(c[#i])),
        Expr::Constant(i) => quote!(c[#i]),
        Expr::Sum(ts) => {
            // Negative terms become subtractions: `a - b` rather than `a + (-1.0 * b)`.
            let mut out = TokenStream::new();
            for (k, t) in ts.iter().enumerate() {
                let (negative, magnitude) = split_sign(t);
                let m = emit_expr(&magnitude, a);
                out.extend(match (k, negative) {
                    (0, false) => quote!(#m),
                    (0, true) => quote!(-#m),
                    (_, false) => quote!(+ #m),
                    (_, true) => quote!(- #m),
                });
            }
            quote!((#out))
        }
        Expr::Product(fs) => {
            let (negative, magnitude) = split_sign(e);
            if negative {
                let m = emit_expr(&magnitude, a);
                return quote!((-#m));
            }
            let mut it = fs.iter().map(|f| emit_expr(f, a));
            let first = it.next().unwrap_or_else(|| emit_expr(&Expr::Num(1.0), a));
            let rest = it.map(|f| quote!(* #f));
            quote!((#first #(#rest)*))
        }
        Expr::Square(e) => call("sq", e),
        Expr::Sin(e) => call("sin", e),
        Expr::Cos(e) => call("cos", e),
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
