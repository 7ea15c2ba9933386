//! The derived constants' recipes as a table (`Recipes`), for the generated `from_geometry` to
//! hand to the runtime's one interpreter (`linkage_geometry::recipe`), which the generator's
//! home check runs too.

use crate::emit::expr::lit;
use crate::model::{Auto, Model, PointRef, Recipe};
use proc_macro2::TokenStream;
use quote::quote;

/// A `const` expression of type `linkage::__private::recipe::Recipes<'static>`, with that
/// module in scope as `recipe` (`use ::linkage::__private::recipe;`).
pub fn table(model: &Model) -> TokenStream {
    let home = model.home_pose.map(lit);
    let auto = model.auto_points.iter().map(auto);
    let constants = model.constants.iter().map(|c| recipe(&c.recipe));
    let r = path();
    quote! {
        #r::Recipes {
            home_pose: [#(#home),*],
            auto: &[#(#auto),*],
            constants: &[#(#constants),*],
        }
    }
}

fn path() -> TokenStream {
    quote!(recipe)
}

fn point(p: PointRef) -> TokenStream {
    let r = path();
    match p {
        PointRef::Slots([a, b, c]) => quote!(#r::PointRef::Slots([#a, #b, #c])),
        PointRef::PlatformHome([a, b, c]) => quote!(#r::PointRef::PlatformHome([#a, #b, #c])),
        PointRef::Auto(i) => quote!(#r::PointRef::Auto(#i)),
    }
}

fn auto(a: &Auto) -> TokenStream {
    let r = path();
    match *a {
        Auto::Along { origin, toward } => {
            let (o, t) = (point(origin), point(toward));
            quote!(#r::Auto::Along { origin: #o, toward: #t })
        }
        Auto::Lever {
            origin,
            toward,
            length,
        } => {
            let (o, t) = (point(origin), point(toward));
            quote!(#r::Auto::Lever { origin: #o, toward: #t, length: #length })
        }
        Auto::Normal { origin, a, b } => {
            let o = point(origin);
            let [a0, a1] = a.map(point);
            let [b0, b1] = b.map(point);
            quote!(#r::Auto::Normal { origin: #o, a: [#a0, #a1], b: [#b0, #b1] })
        }
        Auto::Foot { a, b, point: q } => {
            let (a, b, q) = (point(a), point(b), point(q));
            quote!(#r::Auto::Foot { a: #a, b: #b, point: #q })
        }
        Auto::Quarter { a, b, point: q } => {
            let (a, b, q) = (point(a), point(b), point(q));
            quote!(#r::Auto::Quarter { a: #a, b: #b, point: #q })
        }
        Auto::Shift { origin, by } => {
            let o = point(origin);
            let by = by.map(lit);
            quote!(#r::Auto::Shift { origin: #o, by: [#(#by),*] })
        }
    }
}

fn recipe(c: &Recipe) -> TokenStream {
    let r = path();
    match *c {
        Recipe::Slot(s) => quote!(#r::Recipe::Slot(#s)),
        Recipe::Rigid {
            frame,
            point: q,
            index,
            coplanar,
        } => {
            let [f0, f1, f2] = frame.map(point);
            let q = point(q);
            quote!(#r::Recipe::Rigid { frame: [#f0, #f1, #f2], point: #q, index: #index, coplanar: #coplanar })
        }
        Recipe::Collinear {
            line,
            point: q,
            index,
        } => {
            let [l0, l1] = line.map(point);
            let q = point(q);
            quote!(#r::Recipe::Collinear { line: [#l0, #l1], point: #q, index: #index })
        }
        Recipe::Distance { a, b } => {
            let (a, b) = (point(a), point(b));
            quote!(#r::Recipe::Distance { a: #a, b: #b })
        }
        Recipe::InverseDistance { a, b } => {
            let (a, b) = (point(a), point(b));
            quote!(#r::Recipe::InverseDistance { a: #a, b: #b })
        }
        Recipe::Coordinate { point: q, index } => {
            let q = point(q);
            quote!(#r::Recipe::Coordinate { point: #q, index: #index })
        }
        Recipe::Axis {
            a,
            b,
            point: q,
            index,
        } => {
            let (a, b, q) = (point(a), point(b), point(q));
            quote!(#r::Recipe::Axis { a: #a, b: #b, point: #q, index: #index })
        }
    }
}
