//! The joint inputs of a declaration: each variable an active pair names, in chain order, with
//! the pairs it drives; several only where each declares it `shared`, and measuring the same
//! quantity in each. And `home = inputs(...)` checked against them.

use crate::front::ast::{ChainDecl, ChainItem, PairKind};
use crate::front::errors::Errors;
use proc_macro2::Span;
use syn::Ident;

/// What a joint variable measures.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Quantity {
    /// A rotation (R, H, a C's first variable), radians.
    Angle,
    /// A slide (P, a C's second variable), the base frame's length unit.
    Length,
}

impl Quantity {
    fn describe(self) -> &'static str {
        match self {
            Quantity::Angle => "an angle",
            Quantity::Length => "a length",
        }
    }

    /// What the `k`-th joint variable of an active pair of this kind measures.
    fn of(kind: PairKind, k: usize) -> Quantity {
        match (kind, k) {
            (PairKind::P, _) | (PairKind::C, 1) => Quantity::Length,
            _ => Quantity::Angle,
        }
    }
}

/// A joint input: the pairs it drives (chain name and the variable's token).
pub struct InputSymbol {
    pub name: Ident,
    pub quantity: Quantity,
    pub shared: bool,
    pub uses: Vec<(String, Span)>,
}

/// The inputs in chain order, each with the pairs it drives; a name used by several pairs must
/// be `shared` at each, and mean the same quantity.
pub fn inputs(chains: &[ChainDecl], errors: &mut Errors) -> Vec<InputSymbol> {
    let mut out: Vec<InputSymbol> = Vec::new();
    let mut shared_at: Vec<Vec<bool>> = Vec::new();
    for c in chains {
        for item in &c.items {
            let ChainItem::Pair(p) = item else { continue };
            if p.active.is_none() {
                continue;
            }
            for (k, v) in p.variables.iter().enumerate() {
                let quantity = Quantity::of(p.kind, k);
                let shared = p.shared;
                match out.iter().position(|i| i.name == *v) {
                    None => {
                        out.push(InputSymbol {
                            name: v.clone(),
                            quantity,
                            shared,
                            uses: vec![(c.name.to_string(), v.span())],
                        });
                        shared_at.push(vec![shared]);
                    }
                    Some(i) => {
                        let first = &out[i];
                        let letter = p.kind.letter();
                        if !(shared && first.shared) {
                            errors.push(v.span(), format!(
                                "duplicate joint variable `{v}`: it drives a pair in chain `{}` already; an input that drives several pairs is declared `shared` at each, e.g. `{letter}(active shared {v}, ...)`",
                                first.uses[0].0
                            ));
                        } else if quantity != first.quantity {
                            errors.push(v.span(), format!(
                                "shared input `{v}` is {} in chain `{}` but {} here: an input shared by several pairs measures the same quantity in each",
                                first.quantity.describe(), first.uses[0].0, quantity.describe()
                            ));
                        }
                        out[i].uses.push((c.name.to_string(), v.span()));
                        shared_at[i].push(shared);
                    }
                }
            }
        }
    }
    for i in &out {
        if i.shared && i.uses.len() == 1 {
            errors.push(i.uses[0].1, format!(
                "input `{}` is declared `shared` but drives one pair only: `shared` is for an input that several pairs share (declare it at each of them)",
                i.name
            ));
        }
    }
    out
}

/// `home = inputs(...)` names every input once, and nothing else.
pub fn home_inputs(
    span: Span,
    values: &[(Ident, crate::front::ast::Number)],
    inputs: &[InputSymbol],
    errors: &mut Errors,
) {
    for (k, (name, _)) in values.iter().enumerate() {
        if values[..k].iter().any(|(n, _)| n == name) {
            errors.push(
                name.span(),
                format!("input `{name}` is given twice in `home`"),
            );
        } else if !inputs.iter().any(|i| i.name == *name) {
            let known: Vec<String> = inputs.iter().map(|i| format!("`{}`", i.name)).collect();
            errors.push(
                name.span(),
                format!(
                    "`home` gives a value to `{name}`, which is not an input; the inputs are {}",
                    known.join(", ")
                ),
            );
        }
    }
    let missing: Vec<String> = inputs
        .iter()
        .filter(|i| !values.iter().any(|(n, _)| *n == i.name))
        .map(|i| format!("`{}`", i.name))
        .collect();
    if !missing.is_empty() {
        errors.push(
            span,
            format!(
                "`home = inputs(...)` gives every input its value; missing: {}",
                missing.join(", ")
            ),
        );
    }
}
