//! The code generator behind `linkage::mechanism!`: an ordinary library (tokens in, tokens out)
//! so that every phase is testable without rustc.
//!
//! Pipeline, one folder or file per phase, arrows one way:
//! [`front`] (parse; resolve: every check, then names to typed ids in one resolved
//! declaration) → [`mod@model`] (pairs per Table I, rigid links per Eq. 3, closed-form shapes,
//! the general model; every phase's mistakes into one accumulator) → [`simplify`] (duplicates,
//! rank at home) → [`expr`] (the symbolic IR every phase shares) → [`factor`] (the elimination
//! plan for ∂F/∂v, with the pivot order of [`factor::pivot_order`]) → [`emit`] (the Rust: the
//! `Mechanism` impl in [`emit`] itself, one file per further part — [`emit::factor`] with
//! [`emit::lu`], [`emit::inverse`], [`emit::turns`], … — every one writing expressions with
//! [`emit::expr`], which depends on none of them).

pub mod emit;
pub mod expr;
pub mod factor;
pub mod front;
pub mod model;
pub mod simplify;

use proc_macro2::TokenStream;

/// Expands a `mechanism! { ... }` body. Errors become `compile_error!` at the offending tokens.
pub fn expand(input: TokenStream) -> TokenStream {
    let header = fallback_header(&input);
    match try_expand(input) {
        Ok(tokens) => tokens,
        Err(e) => fallback(e, header),
    }
}

/// The errors, and in place of the declared type an alias whose definition is the first of
/// them: an array whose length is `compile_error!`, a type rustc knows to be in error, so the
/// user's other uses of the name (`Name::new()`, `Name::LISTING`, a solver over it) add no
/// errors of their own. (A unit struct in its place left two follow-on errors in a typical
/// program; `compile_error!` alone as the type stands for `()`, which adds them all.)
fn fallback(e: syn::Error, header: Option<(TokenStream, syn::Ident)>) -> TokenStream {
    let Some((vis, name)) = header else {
        return e.to_compile_error();
    };
    let mut errors = e.into_iter();
    let first = errors.next().map(|e| e.to_compile_error());
    let rest = errors.map(|e| e.to_compile_error());
    quote::quote! {
        #[allow(dead_code)]
        #vis type #name = [(); #first];
        #(#rest)*
    }
}

/// The declared type's visibility and name, if the header parses: `attrs vis struct NAME ;`.
fn fallback_header(input: &TokenStream) -> Option<(TokenStream, syn::Ident)> {
    use proc_macro2::{Delimiter, TokenTree};
    let mut vis = TokenStream::new();
    let mut tokens = input.clone().into_iter().peekable();
    while let Some(t) = tokens.next() {
        match &t {
            TokenTree::Ident(i) if i == "struct" => {
                return match tokens.next() {
                    Some(TokenTree::Ident(name)) => Some((vis, name)),
                    _ => None,
                };
            }
            TokenTree::Ident(i) if i == "pub" => {
                vis = TokenStream::from(t.clone());
                let restricted = matches!(
                    tokens.peek(),
                    Some(TokenTree::Group(g)) if g.delimiter() == Delimiter::Parenthesis
                );
                if restricted {
                    vis.extend(tokens.next());
                }
            }
            _ => vis = TokenStream::new(),
        }
    }
    None
}

fn try_expand(input: TokenStream) -> syn::Result<TokenStream> {
    let mech: front::ast::Mechanism = syn::parse2(input)?;
    let mut errors = front::errors::Errors::default();
    let model = mech
        .resolve(&mut errors)
        .and_then(|decl| model::build(&decl, &mut errors).map(|m| (decl, m)));
    let Some((decl, model)) = model else {
        return Err(errors.into_error());
    };
    let home = match (decl.platform.home, &decl.platform.home_inputs) {
        (Some(home), _) => Some(model::reference::check(&model, home)?),
        // The joint values (one per input, by the resolver): forward kinematics from the
        // declared configuration.
        (None, Some((span, target))) => Some(
            model::home_inputs::solve(&model, target).map_err(|msg| syn::Error::new(*span, msg))?,
        ),
        // The general model is always checked at home (identity pose if none is declared).
        (None, None) if model.mobility.is_some() => Some(model::reference::check(
            &model,
            (decl.name.span(), model.home_pose),
        )?),
        (None, None) => None,
    };
    Ok(emit::expand(&mech, &model, home.as_ref()))
}

/// Parses and validates a declaration.
pub fn parse(input: TokenStream) -> syn::Result<front::ast::Mechanism> {
    let mech: front::ast::Mechanism = syn::parse2(input)?;
    mech.validate()?;
    Ok(mech)
}

/// Parses, resolves and models a declaration: the generated system without emitting code.
pub fn model(input: TokenStream) -> syn::Result<model::Model> {
    let mech: front::ast::Mechanism = syn::parse2(input)?;
    let mut errors = front::errors::Errors::default();
    let built = mech
        .resolve(&mut errors)
        .and_then(|decl| model::build(&decl, &mut errors));
    built.ok_or_else(|| errors.into_error())
}
