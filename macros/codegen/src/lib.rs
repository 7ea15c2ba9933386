//! The code generator behind `linkage::mechanism!`: an ordinary library (tokens in, tokens out)
//! so that every phase is testable without rustc.
//!
//! Pipeline: [`ast`] parses the DSL keeping spans, [`check`] validates names and collects every
//! error, [`model`] and [`chain`]/[`rigid`] build the constraint system of Gao & Wu (2015) as
//! symbolic [`expr`]essions, and [`emit`] writes the Rust.

pub mod ast;
pub mod chain;
pub mod check;
pub mod emit;
pub mod expr;
pub mod model;
pub mod rigid;

use proc_macro2::TokenStream;

/// Expands a `mechanism! { ... }` body. Errors become `compile_error!` at the offending tokens.
pub fn expand(input: TokenStream) -> TokenStream {
    match try_expand(input) {
        Ok(tokens) => tokens,
        Err(e) => e.to_compile_error(),
    }
}

fn try_expand(input: TokenStream) -> syn::Result<TokenStream> {
    let mech = parse(input)?;
    let model = model::build(&mech)?;
    Ok(emit::expand(&mech, &model))
}

/// Parses and validates a declaration.
pub fn parse(input: TokenStream) -> syn::Result<ast::Mechanism> {
    let mech: ast::Mechanism = syn::parse2(input)?;
    mech.validate()?;
    Ok(mech)
}

/// Parses, validates and models a declaration: the generated system without emitting code.
pub fn model(input: TokenStream) -> syn::Result<model::Model> {
    model::build(&parse(input)?)
}
