//! The `mechanism!` procedural macro. All logic lives in `linkage-codegen`; use it through
//! the `linkage` crate, which re-exports it.

/// Declares a spatial parallel mechanism and generates its constraint system.
/// See the `linkage` crate documentation for the grammar.
#[proc_macro]
pub fn mechanism(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    linkage_codegen::expand(input.into()).into()
}
