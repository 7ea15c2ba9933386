//! Inverse kinematics, emitted: in closed form where every chain has one (a leg's length, a
//! crank or slider against the rod it carries), numerically where some chain has none — the
//! closed-form chains' inputs first, then the runtime's `numerical_inverse` (Levenberg–Marquardt
//! from several starts, then along a path from home) for the rest, given what only the model
//! knows: how many coordinates are the platform's, the declared home, which points of the
//! links between a platform point carries, and which inputs turn.

use crate::model::{Inverse, Model};
use proc_macro2::TokenStream;
use quote::quote;

/// The first input of a chain with no closed form, if there is one: then the inverse is
/// numerical (and `home_start` starts from the declared configuration itself).
pub fn numerical_input(model: &Model) -> Option<usize> {
    model.inverses.iter().find_map(|inv| match inv {
        Inverse::None { inputs } => inputs.first().copied(),
        _ => None,
    })
}

/// The body of `Mechanism::inverse`; `pattern` is ∂F/∂v's, in the order of its values.
pub fn body(model: &Model, has_home: bool, pattern: &[(usize, usize)]) -> TokenStream {
    let held = 3 * model.points.len();
    let n = model.unknowns.len();
    let nnz = pattern.len();
    match numerical_input(model) {
        // Every input has a closed form, but links between hold the platform too (a Tricept's
        // passive column): only a search over their points can tell whether they reach the
        // pose, so the numerical inverse, started from the closed forms' inputs, decides.
        None if links_hold_the_platform(model) => numerical_body(model, has_home, 0, pattern),
        // Each closed form reads one point: the others must be where the inputs put them.
        None => {
            let rows = platform_rows(model, pattern, false)
                .into_iter()
                .map(|(r, entries)| quote!((#r, &[#(#entries),*])));
            // Where the platform's own equations do not hold it rigid (a Tricept's platform
            // is rigid through its column's points, which the caller need not give), its
            // distances are checked instead: a platform out of shape has no inputs.
            let distances = (!shape_in_rows(model, pattern)).then(|| {
                quote! {
                    if !::linkage::__private::platform_keeps_its_distances(self, v) {
                        return Err(::linkage::InverseError::Inconsistent);
                    }
                }
            });
            quote! {
            let out = self.closed_form_inputs(v, reference)?;
            #distances
            const ROWS: &[(usize, &[usize])] = &[#(#rows),*];
            let mut f = [0.0; #n];
            self.residual(v, &out, &mut f);
            let mut b = [0.0; #nnz];
            self.jacobian(v, &out, &mut b);
            if !::linkage::__private::closed_form_places(v, #held, &f, &b, ROWS) {
                return Err(::linkage::InverseError::Inconsistent);
            }
            Ok(out)
            }
        }
        Some(first) => numerical_body(model, has_home, first, pattern),
    }
}

/// The equations on the platform's points alone, each with the indices of its values in
/// ∂F/∂v; with `fixed`, only those that read no input either: no inputs and no points of the
/// links between can make them hold, so a platform they fail is unreachable as given.
fn platform_rows(
    model: &Model,
    pattern: &[(usize, usize)],
    fixed: bool,
) -> Vec<(usize, Vec<usize>)> {
    let held = 3 * model.points.len();
    let m = model.inputs.len();
    (0..model.unknowns.len())
        .filter_map(|r| {
            let entries: Vec<usize> = (0..pattern.len()).filter(|&k| pattern[k].0 == r).collect();
            let platform_only = !entries.is_empty() && entries.iter().all(|&k| pattern[k].1 < held);
            let free_of_inputs =
                (0..m).all(|i| !model.equations[r].depends_on(crate::expr::Var::Input(i)));
            (platform_only && (free_of_inputs || !fixed)).then_some((r, entries))
        })
        .collect()
}

/// Whether some equation ties a platform point to an unknown of the links between: a passive
/// chain whose links are solved for holds the platform, beside the chains the closed forms
/// read.
fn links_hold_the_platform(model: &Model) -> bool {
    use crate::expr::Var;
    let held = 3 * model.points.len();
    let n = model.unknowns.len();
    model.equations.iter().any(|f| {
        (0..held).any(|i| f.depends_on(Var::Unknown(i)))
            && (held..n).any(|i| f.depends_on(Var::Unknown(i)))
    })
}

/// Whether the equations on the platform's points alone that read no input hold its shape:
/// as many as a rigid body of its points needs (3k − 6 for k ≥ 3 points, one for two), the
/// rank test having kept them independent.
fn shape_in_rows(model: &Model, pattern: &[(usize, usize)]) -> bool {
    let k = model.points.len();
    let needed = match k {
        0 | 1 => 0,
        2 => 1,
        _ => 3 * k - 6,
    };
    platform_rows(model, pattern, true).len() >= needed
}

/// Where every chain has a closed form: the inherent `closed_form_inputs`, the inputs they
/// give (not checked against the points they do not read: `inverse` does that, while
/// `home_start` leaves a home a calibration moved a little to `Start::new`, which refines it).
pub fn closed_form_method(model: &Model) -> Option<TokenStream> {
    if numerical_input(model).is_some() {
        return None;
    }
    let steps = model.inverses.iter().map(|inv| closed_form(model, inv));
    let (n, m) = (model.unknowns.len(), model.inputs.len());
    // A NaN or infinite coordinate would give a NaN or infinite input (a leg's length is a
    // distance), and so would a finite one far enough out: neither is an answer.
    Some(quote! {
        /// The inputs the chains' closed forms give for the pivots `v` (each reads one
        /// platform point), the nearer branch to `reference`: the first step of `inverse`,
        /// which also checks that they place the points the closed forms do not read.
        fn closed_form_inputs(&self, v: &[f64; #n], reference: &[f64; #m]) -> ::core::result::Result<[f64; #m], ::linkage::InverseError> {
            if !v.iter().chain(reference.iter()).all(|a| a.is_finite()) {
                return Err(::linkage::InverseError::NonFinite);
            }
            let c = &self.constants;
            let mut out = *reference;
            #(#steps)*
            if !out.iter().all(|a| a.is_finite()) {
                return Err(::linkage::InverseError::NonFinite);
            }
            Ok(out)
        }
    })
}

fn numerical_body(
    model: &Model,
    has_home: bool,
    first: usize,
    pattern: &[(usize, usize)],
) -> TokenStream {
    let steps = model.inverses.iter().map(|inv| closed_form(model, inv));
    let n = model.unknowns.len();
    let m = model.inputs.len();
    let held = 3 * model.points.len();
    // A platform out of shape is refused before the search, where some equation can tell.
    let rigid: Vec<TokenStream> = platform_rows(model, pattern, true)
        .into_iter()
        .map(|(r, entries)| quote!((#r, &[#(#entries),*])))
        .collect();
    let nnz = pattern.len();
    let in_shape = (!rigid.is_empty()).then(|| {
        quote! {
            const RIGID: &[(usize, &[usize])] = &[#(#rigid),*];
            let mut f = [0.0; #n];
            self.residual(v, &out, &mut f);
            let mut b = [0.0; #nnz];
            self.jacobian(v, &out, &mut b);
            if !::linkage::__private::platform_in_shape(v, #held, &f, &b, RIGID) {
                return Err(::linkage::InverseError::Unreachable { input: #first });
            }
        }
    });
    // And one whose points are not as far apart as declared, for any model of two points or
    // more (the rows above exist only where the model keeps equations on the platform alone).
    let distances = (model.points.len() >= 2).then(|| {
        quote! {
            if !::linkage::__private::platform_keeps_its_distances(self, v) {
                return Err(::linkage::InverseError::Unreachable { input: #first });
            }
        }
    });
    let z = m + n - held;
    // The points of the links between that a platform point carries: the second guess moves
    // them as far as it has from home.
    let carried = model
        .general_points
        .iter()
        .zip(&model.carried_by)
        .filter_map(|((_, _, first), by)| by.map(|pp| quote!((#first, #pp))));
    // Inputs that turn: F holds them only through sin and cos.
    let turning: Vec<usize> = (0..m)
        .filter(|&i| model.equations.iter().all(|f| f.only_turns(i)))
        .collect();
    let home = if has_home {
        quote!(Some((&Self::HOME_V, &Self::HOME_INPUTS)))
    } else {
        quote!(None)
    };
    quote! {
        if !v.iter().chain(reference.iter()).all(|a| a.is_finite()) {
            return Err(::linkage::InverseError::NonFinite);
        }
        // An angle is returned within half a turn of its reference: past the limit the sum
        // would round the angle found away (a pan-tilt head's angles found at 0 came back as
        // 1e300 for a reference of 1e300, placing nothing where v is). Checked here: in the
        // runtime's solver the same check cost the no-panic proof its link (the optimiser
        // then kept a panic path there it had removed).
        #(
            if !::linkage::__private::turn_reference_ok(reference[#turning]) {
                return Err(::linkage::InverseError::FarReference { input: #turning });
            }
        )*
        #distances
        let c = &self.constants;
        // The chains with a closed form give their inputs; the rest start at the reference.
        let mut out = *reference;
        #(#steps)*
        #in_shape
        let plan = ::linkage::__private::InversePlan {
            held: #held,
            home: #home,
            carried: &[#(#carried),*],
            turning: &[#(#turning),*],
            unsolved: #first,
        };
        ::linkage::__private::numerical_inverse::<Self, #n, #m, #z>(self, v, reference, &out, &plan)
    }
}

fn consts3(s: [usize; 3]) -> TokenStream {
    let [a, b, c] = s;
    quote!([c[#a], c[#b], c[#c]])
}

/// One chain's closed-form inverse, writing `out[input]`.
fn closed_form(model: &Model, inv: &Inverse) -> TokenStream {
    let p = quote!(::linkage::__private);
    let point = |q: usize| {
        let [x, y, z] = [0, 1, 2].map(|a| model.unknown(q, a));
        quote!([v[#x], v[#y], v[#z]])
    };
    match inv {
        Inverse::Distance {
            input,
            point: q,
            anchor,
            offset,
        } => {
            let g = point(*q);
            let a = consts3(*anchor);
            let off = match offset {
                Some(o) => quote!(c[#o]),
                None => quote!(0.0),
            };
            quote!(out[#input] = #p::distance(#g, #a) - #off;)
        }
        Inverse::RevoluteRod {
            input,
            point: q,
            o,
            u,
            w,
            length,
        } => {
            let g = point(*q);
            let (o, u, w) = (consts3(*o), consts3(*u), consts3(*w));
            // An angle is returned within half a turn of its reference: a reference too
            // large for that would round the angle found away.
            quote! {
                if !#p::turn_reference_ok(reference[#input]) {
                    return Err(::linkage::InverseError::FarReference { input: #input });
                }
                out[#input] = #p::revolute_rod_inverse(#g, #o, #u, #w, c[#length], reference[#input])
                    .ok_or(::linkage::InverseError::Unreachable { input: #input })?;
            }
        }
        Inverse::PrismaticRod {
            input,
            point: q,
            c0,
            e,
            length,
            offset,
        } => {
            let g = point(*q);
            let (c0, e) = (consts3(*c0), consts3(*e));
            match offset {
                None => {
                    quote!(out[#input] = #p::prismatic_rod_inverse(#g, #c0, #e, c[#length], reference[#input])
                    .ok_or(::linkage::InverseError::Unreachable { input: #input })?;)
                }
                // The root is a slide; the input reads it plus the offset.
                Some(o) => {
                    quote!(out[#input] = #p::prismatic_rod_inverse(#g, #c0, #e, c[#length], reference[#input] - c[#o])
                    .ok_or(::linkage::InverseError::Unreachable { input: #input })? + c[#o];)
                }
            }
        }
        Inverse::None { .. } => quote!(),
    }
}
