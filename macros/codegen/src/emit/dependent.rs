//! Emission of `Mechanism::dependent_offset`: how far an answer is from satisfying the
//! equations the rank pass left out as dependent at home ([`crate::simplify::rank`]): the
//! largest |g| / ‖∂g/∂v‖ over them — to first order the distance from v to the surface g = 0
//! at the given inputs. An equation no coordinate enters constrains the inputs alone and is
//! not checked here.
//!
//! Near home they are implied by the kept ones; an over-constrained mechanism's square system
//! can have other components on which they fail (a planar linkage folded out of its plane, a
//! wrist whose platform pivots leave their mutual distances). A solver that lands there has
//! solved the kept equations and still answered wrongly; the runtime refuses such answers.

use crate::emit::expr::{Arithmetic, Emitter};
use crate::expr::{Expr, Var};
use crate::model::Model;
use proc_macro2::TokenStream;
use quote::quote;

/// The method, or nothing (the trait's default, 0) when no equation was left out.
pub fn dependent_offset(model: &Model) -> TokenStream {
    if model.dependent.is_empty() {
        return TokenStream::new();
    }
    let (n, m) = (model.unknowns.len(), model.inputs.len());
    // Each left-out equation with the derivatives of it that are not zero: over the
    // coordinates only, since an angle input's derivative is a crank's length times larger and
    // would make a point far off the surface look close to it.
    let checked: Vec<(&Expr, Vec<Expr>)> = model
        .dependent
        .iter()
        .filter(|g| (0..n).any(|j| g.depends_on(Var::Unknown(j))))
        .map(|g| {
            let derivatives = (0..n)
                .map(|j| g.derivative(Var::Unknown(j)).simplify())
                .filter(|d| !d.is_zero())
                .collect();
            (g, derivatives)
        })
        .collect();
    let mut emitter = Emitter::new(Arithmetic::F64);
    for (g, derivatives) in &checked {
        emitter.count(g);
        derivatives.iter().for_each(|d| emitter.count(d));
    }
    let terms: Vec<TokenStream> = checked
        .iter()
        .map(|(g, derivatives)| {
            let value = emitter.tokens(g);
            let squares: Vec<TokenStream> = derivatives
                .iter()
                .map(|d| {
                    let d = emitter.tokens(d);
                    quote!({ let d = #d; d * d })
                })
                .collect();
            quote! {
                worst = ::linkage::__private::dependent_worst(worst, #value, 0.0 #(+ #squares)*);
            }
        })
        .collect();
    let lets = emitter.bindings();
    quote! {
        #[allow(unused_variables)]
        fn dependent_offset(&self, v: &[f64; #n], x: &[f64; #m]) -> f64 {
            let c = &self.constants;
            #lets
            let mut worst = 0.0f64;
            #(#terms)*
            worst
        }
    }
}
