//! Inverse kinematics, emitted: in closed form where every chain has one (a leg's length, a
//! crank or slider against the rod it carries), numerically where some chain has none.
//!
//! The numerical inverse solves F(v, x) = 0 for the inputs x and the unknowns that are not
//! the platform's (points of the links between, passive slides), with the platform's
//! coordinates held at the given v: N equations in Z = M + (N − 3k) unknowns, Z ≤ N, by
//! Levenberg–Marquardt on the normal equations (Marquardt's diagonal scaling, so that inputs in
//! rad and in mm weigh alike). It starts from the reference inputs (with the closed-form
//! chains' inputs filled in), and from whichever guess for the links between fits better
//! there: the given v's, or the declared home's; then from the other. A result is returned only
//! where the residual vanishes, so any inputs returned do place the platform at v; a pose the
//! mechanism cannot take (off its motion, out of reach) is `Unreachable`.

use crate::model::{Inverse, Model};
use proc_macro2::TokenStream;
use quote::quote;

/// The body of `Mechanism::inverse`.
pub fn body(model: &Model, has_home: bool) -> TokenStream {
    let steps: Vec<TokenStream> = model
        .inverses
        .iter()
        .map(|inv| closed_form(model, inv))
        .collect();
    let numerical = model.inverses.iter().find_map(|inv| match inv {
        Inverse::None { inputs } => inputs.first().copied(),
        _ => None,
    });
    match numerical {
        None => quote! {
            let c = &self.constants;
            let mut out = *reference;
            #(#steps)*
            Ok(out)
        },
        Some(first) => numerical_body(model, has_home, first, &steps),
    }
}

fn numerical_body(
    model: &Model,
    has_home: bool,
    first: usize,
    steps: &[TokenStream],
) -> TokenStream {
    let n = model.unknowns.len();
    let m = model.inputs.len();
    let p = 3 * model.points.len();
    // The second guess for the links between: the declared home's, with the points nearest a
    // platform pivot moved as far as it has.
    let k = model.points.len();
    let carried = model
        .general_points
        .iter()
        .zip(&model.carried_by)
        .filter_map(|((_, _, first), by)| by.map(|pp| (*first, pp)))
        .map(|(first, pp)| {
            let moves = (0..3).map(|a| {
                let (q, c) = (first + a, a * k + pp);
                quote!(other[#q] += v[#c] - Self::HOME_V[#c];)
            });
            quote!(#(#moves)*)
        });
    // Where there is no second guess (no link between has unknowns, or no declared home), one
    // attempt from the given v.
    let guesses = if has_home && p < n {
        quote! {
            let cost = |vv: &[f64; #n], xx: &[f64; #m]| -> f64 {
                let mut f = [0.0f64; #n];
                <Self as ::linkage::Mechanism<#n, #m>>::residual(self, vv, xx, &mut f);
                let s: f64 = f.iter().map(|r| r * r).sum();
                if s.is_finite() { s } else { f64::INFINITY }
            };
            let mut other = *v;
            other[#p..].copy_from_slice(&Self::HOME_V[#p..]);
            #(#carried)*
            let guesses = if cost(v, &x0) <= cost(&other, &x0) { [*v, other] } else { [other, *v] };
        }
    } else {
        quote!(let guesses = [*v];)
    };
    quote! {
        if !v.iter().chain(reference.iter()).all(|a| a.is_finite()) {
            return Err(::linkage::InverseError::NonFinite);
        }
        let c = &self.constants;
        // The chains with a closed form give their inputs; the rest start at the reference.
        let mut out = *reference;
        #(#steps)*
        let x0 = out;
        #guesses
        let scale = 1.0 + v[..#p].iter().fold(0.0f64, |s, q| s.max(q.abs()));
        let tolerance = 1e-8 * scale * scale;
        for guess in guesses {
            if let Some(x) = self.__inverse_newton(guess, x0, tolerance) {
                return Ok(x);
            }
        }
        Err(::linkage::InverseError::Unreachable { input: #first })
    }
}

/// The Levenberg–Marquardt iteration of the numerical inverse, as an inherent method (`None`
/// for the closed-form mechanisms).
pub fn newton_method(model: &Model) -> Option<TokenStream> {
    let numerical = model
        .inverses
        .iter()
        .any(|inv| matches!(inv, Inverse::None { inputs } if !inputs.is_empty()));
    if !numerical {
        return None;
    }
    let n = model.unknowns.len();
    let m = model.inputs.len();
    let nnz = model.jacobian().len();
    let p = 3 * model.points.len();
    let z = m + n - p;
    // The columns and steps of the unknowns after the platform's, if there are any.
    let (fill_intermediate, step_intermediate) = if p < n {
        (
            quote! {
                let mut values = [0.0f64; #nnz];
                self.jacobian(&v, &x, &mut values);
                for (k, &(r, col)) in <Self as ::linkage::Mechanism<#n, #m>>::PATTERN.iter().enumerate() {
                    if (#p..#n).contains(&col) && r < #n {
                        j[r][#m + col - #p] = values[k];
                    }
                }
            },
            quote! {
                for p in #m..#z {
                    vt[#p + p - #m] += d[p];
                }
            },
        )
    } else {
        (quote!(), quote!())
    };
    Some(quote! {
        /// Levenberg–Marquardt for [`linkage::Mechanism::inverse`]: the inputs and the
        /// unknowns after the platform's, the platform's held; `None` unless F vanishes (to
        /// `tolerance`) at the end.
        #[doc(hidden)]
        #[allow(clippy::needless_range_loop)]
        fn __inverse_newton(&self, mut v: [f64; #n], mut x: [f64; #m], tolerance: f64) -> ::core::option::Option<[f64; #m]> {
            use ::linkage::Mechanism as _;
            let mut f = [0.0f64; #n];
            self.residual(&v, &x, &mut f);
            let mut cost: f64 = f.iter().map(|r| r * r).sum();
            let mut mu = 1e-3f64;
            let mut iteration = 0;
            // Until the step is negligible or none lowers the cost: a residual test alone would stop
            // early on the equations of unit-length points (an axis tip), whose residuals are
            // small beside the slides that move them.
            while iteration < 100 && cost.is_finite() && cost > 0.0 {
                iteration += 1;
                let mut a = [[0.0f64; #m]; #n];
                self.input_jacobian(&v, &x, &mut a);
                // J = [∂F/∂x | ∂F/∂v after the platform's], then JᵀJ and −JᵀF.
                let mut j = [[0.0f64; #z]; #n];
                for r in 0..#n {
                    j[r][..#m].copy_from_slice(&a[r]);
                }
                #fill_intermediate
                let mut h = [[0.0f64; #z]; #z];
                let mut g = [0.0f64; #z];
                for r in 0..#n {
                    for p in 0..#z {
                        let jp = j[r][p];
                        if jp != 0.0 {
                            g[p] -= jp * f[r];
                            for q in 0..#z {
                                h[p][q] += jp * j[r][q];
                            }
                        }
                    }
                }
                // Damped steps until one lowers the cost.
                let mut accepted = false;
                while mu <= 1e12 {
                    let mut damped = h;
                    for p in 0..#z {
                        damped[p][p] += mu * (h[p][p] + 1e-300);
                    }
                    let Some(piv) = ::linkage::lu::factor_dense::<#z>(&mut damped) else {
                        mu *= 10.0;
                        continue;
                    };
                    let mut d = g;
                    ::linkage::lu::solve_dense::<#z>(&damped, &piv, &mut d);
                    let (mut vt, mut xt) = (v, x);
                    for p in 0..#m {
                        xt[p] += d[p];
                    }
                    #step_intermediate
                    let mut ft = [0.0f64; #n];
                    self.residual(&vt, &xt, &mut ft);
                    let trial: f64 = ft.iter().map(|r| r * r).sum();
                    if trial < cost {
                        let negligible = d.iter().zip(xt.iter().chain(vt[#p..].iter())).all(|(s, q)| s.abs() <= 1e-13 * (1.0 + q.abs()));
                        v = vt;
                        x = xt;
                        f = ft;
                        cost = trial;
                        mu = (mu * 0.1).max(1e-15);
                        accepted = !negligible;
                        break;
                    }
                    mu *= 10.0;
                }
                if !accepted {
                    break;
                }
            }
            (f.iter().all(|r| r.abs() <= tolerance)).then_some(x)
        }
    })
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
            quote!(out[#input] = #p::revolute_rod_inverse(#g, #o, #u, #w, c[#length], reference[#input])
                .ok_or(::linkage::InverseError::Unreachable { input: #input })?;)
        }
        Inverse::PrismaticRod {
            input,
            point: q,
            c0,
            e,
            length,
        } => {
            let g = point(*q);
            let (c0, e) = (consts3(*c0), consts3(*e));
            quote!(out[#input] = #p::prismatic_rod_inverse(#g, #c0, #e, c[#length], reference[#input])
                .ok_or(::linkage::InverseError::Unreachable { input: #input })?;)
        }
        Inverse::None { .. } => quote!(),
    }
}
