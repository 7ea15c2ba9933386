//! Emission of `Mechanism::SYMMETRIES` and `Mechanism::symmetry`: the candidate leg spins of
//! [`crate::model::general::universal::spins`], one per chain, each reflecting some unknowns
//! through their centre's coordinates (`v[i] → 2 e − v[i]`). Nothing (the trait's defaults:
//! no candidates) where no chain has one.

use crate::emit::expr::{Arithmetic, Emitter};
use crate::model::Model;
use proc_macro2::TokenStream;
use quote::quote;

pub fn symmetry(model: &Model) -> TokenStream {
    if model.spins.is_empty() {
        return TokenStream::new();
    }
    let (n, m) = (model.unknowns.len(), model.inputs.len());
    let count = model.spins.len();
    let arms = model.spins.iter().enumerate().map(|(k, list)| {
        // A centre is an unknown, a constant or an input's expression: written out whole (no
        // sharing: three coordinates per point, each read once).
        let mut emitter = Emitter::new(Arithmetic::Generic);
        let statements = list.iter().map(|(i, centre)| {
            let c = emitter.tokens(centre);
            quote!(out[#i] = T::from_f64(2.0) * #c - v[#i];)
        });
        quote!(#k => { #(#statements)* })
    });
    quote! {
        const SYMMETRIES: usize = #count;

        #[allow(unused_variables)]
        fn symmetry<T: ::linkage::Scalar>(&self, k: usize, v: &[T; #n], x: &[T; #m], out: &mut [T; #n]) {
            let c = &self.constants;
            *out = *v;
            match k {
                #(#arms)*
                _ => {}
            }
        }
    }
}
