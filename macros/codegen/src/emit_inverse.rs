//! Inverse kinematics, emitted: in closed form where every chain has one (a leg's length, a
//! crank or slider against the rod it carries), numerically where some chain has none.
//!
//! The numerical inverse solves F(v, x) = 0 for the inputs x and the unknowns that are not
//! the platform's (points of the links between, passive slides), with the platform's
//! coordinates held at the given v: N equations in Z = M + (N − 3k) unknowns, Z ≤ N, by
//! Levenberg–Marquardt on the normal equations (Marquardt's diagonal scaling, so that inputs in
//! rad and in mm weigh alike). It starts from the reference inputs (with the closed-form
//! chains' inputs filled in), and from whichever guess for the links between fits better
//! there: the given v's, or the declared home's; then from the other. Where neither converges
//! (a long way from home, or points of the links between that the equations hold only weakly,
//! such as the two points a unit apart on a cylindrical pair's axis), it follows the platform
//! from home in 16 steps, each solved from the last. A result is returned only where the
//! residual vanishes, so any inputs returned do place the platform at v; a pose the mechanism
//! cannot take (off its motion, out of reach) is `Unreachable`. An input the equations hold
//! only through its sine and cosine (a revolute's angle) is returned within half a turn of the
//! reference: the whole turns Levenberg–Marquardt may have wandered through change nothing.
//! Where all that fails, those inputs are started a quarter, half and three quarters of a turn
//! from the reference.

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
    // From home to v in steps of the platform's pose (Euler angles and translation each
    // interpolated; the coordinates themselves for a platform of one or two points), each
    // step's solution the next one's start, the last step exactly v.
    let homotopy = if has_home {
        quote! {
            let from = ::linkage::pose_from_unknowns(self, &Self::HOME_V);
            let to = ::linkage::pose_from_unknowns(self, v);
            let (mut vv, mut x) = (Self::HOME_V, Self::HOME_INPUTS);
            let mut k = 1;
            while k <= 16 {
                let t = k as f64 / 16.0;
                let at: [f64; #n] = match (&from, &to) {
                    (Some(a), Some(b)) if k < 16 => {
                        let (ea, eb) = (a.euler(), b.euler());
                        let angle = |i: usize| {
                            // The shorter way round.
                            let turn = 2.0 * ::core::f64::consts::PI;
                            let mut d = (eb[i] - ea[i]) % turn;
                            if d > 0.5 * turn {
                                d -= turn;
                            } else if d < -0.5 * turn {
                                d += turn;
                            }
                            ea[i] + t * d
                        };
                        let (ta, tb) = (a.translation, b.translation);
                        let pose = ::linkage::Pose::from_euler(angle(0), angle(1), angle(2), [
                            ta[0] + t * (tb[0] - ta[0]),
                            ta[1] + t * (tb[1] - ta[1]),
                            ta[2] + t * (tb[2] - ta[2]),
                        ]);
                        ::linkage::unknowns_from_pose(self, &pose)
                    }
                    _ => {
                        let mut at = *v;
                        for i in 0..#p {
                            at[i] = Self::HOME_V[i] + t * (v[i] - Self::HOME_V[i]);
                        }
                        at
                    }
                };
                vv[..#p].copy_from_slice(&at[..#p]);
                let left = self.__inverse_newton(&mut vv, &mut x);
                if k == 16 && left <= tolerance {
                    return Ok(nearest(x));
                }
                k += 1;
            }
        }
    } else {
        quote!()
    };
    // Inputs that turn: F holds them only through sin and cos.
    let turning: Vec<usize> = (0..m)
        .filter(|&i| model.equations.iter().all(|f| f.only_turns(i)))
        .collect();
    let nearest = if turning.is_empty() {
        quote!(let nearest = |x: [f64; #m]| x;)
    } else {
        quote! {
        let nearest = |mut x: [f64; #m]| -> [f64; #m] {
            #({
                let turn = 2.0 * ::core::f64::consts::PI;
                let mut d = (x[#turning] - reference[#turning]) % turn;
                if d > 0.5 * turn {
                    d -= turn;
                } else if d < -0.5 * turn {
                    d += turn;
                }
                x[#turning] = reference[#turning] + d;
            })*
            x
        };
        }
    };
    // Last, the turning inputs started a quarter, a half and three quarters of a turn from the
    // reference: a mechanism of few freedoms (a four-bar's coupler point) can be far along its
    // motion from home where neither the reference nor a straight path of the platform leads.
    let turned_starts = if turning.is_empty() {
        quote!()
    } else {
        quote! {
            for k in 1..4 {
                let shift = k as f64 * 0.5 * ::core::f64::consts::PI;
                for mut guess in guesses {
                    let mut x = x0;
                    #(x[#turning] += shift;)*
                    if self.__inverse_newton(&mut guess, &mut x) <= tolerance {
                        return Ok(nearest(x));
                    }
                }
            }
        }
    };
    quote! {
        if !v.iter().chain(reference.iter()).all(|a| a.is_finite()) {
            return Err(::linkage::InverseError::NonFinite);
        }
        #nearest
        let c = &self.constants;
        // The chains with a closed form give their inputs; the rest start at the reference.
        let mut out = *reference;
        #(#steps)*
        let x0 = out;
        #guesses
        let scale = 1.0 + v[..#p].iter().fold(0.0f64, |s, q| s.max(q.abs()));
        let tolerance = 1e-8 * scale * scale;
        for mut guess in guesses {
            let mut x = x0;
            if self.__inverse_newton(&mut guess, &mut x) <= tolerance {
                return Ok(nearest(x));
            }
        }
        #homotopy
        #turned_starts
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
                self.jacobian(v, x, &mut values);
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
    // What the step moved: the inputs, then the unknowns after the platform's (no empty
    // `vt[n..]` where there are none, which clippy refuses in the user's crate).
    let stepped = if p < n {
        quote!(xt.iter().chain(vt[#p..].iter()))
    } else {
        quote!(xt.iter())
    };
    Some(quote! {
        /// Levenberg–Marquardt for [`linkage::Mechanism::inverse`]: the inputs and the
        /// unknowns after the platform's, the platform's held; returns the largest |F| left.
        #[doc(hidden)]
        #[allow(clippy::needless_range_loop)]
        fn __inverse_newton(&self, v: &mut [f64; #n], x: &mut [f64; #m]) -> f64 {
            use ::linkage::Mechanism as _;
            let mut f = [0.0f64; #n];
            self.residual(v, x, &mut f);
            let mut mu = 1e-6f64;
            let mut iteration = 0;
            // Until the step is negligible or none lowers the cost: a residual test alone would
            // stop early on the equations of points a unit apart (an axis tip), whose residuals
            // are small beside the slides that move them.
            while iteration < 100 {
                iteration += 1;
                let mut a = [[0.0f64; #m]; #n];
                self.input_jacobian(v, x, &mut a);
                // J = [∂F/∂x | ∂F/∂v after the platform's].
                let mut j = [[0.0f64; #z]; #n];
                for r in 0..#n {
                    j[r][..#m].copy_from_slice(&a[r]);
                }
                #fill_intermediate
                // Each equation weighed by its row's largest entry, so that equations in mm and
                // in mm², or on points a unit apart and a hundred apart, count alike; one that
                // these unknowns do not move (the platform's own, or one whose terms cancel,
                // down to rounding) not at all.
                let mut w = [0.0f64; #n];
                let mut all = 0.0f64;
                for r in 0..#n {
                    w[r] = j[r].iter().fold(0.0f64, |t, q| t.max(q.abs()));
                    all = all.max(w[r]);
                }
                for r in 0..#n {
                    w[r] = if w[r] > 1e-9 * all { 1.0 / w[r] } else { 0.0 };
                }
                let weighted = |f: &[f64; #n]| -> f64 {
                    let mut c = 0.0f64;
                    for r in 0..#n {
                        c += (w[r] * f[r]) * (w[r] * f[r]);
                    }
                    c
                };
                let cost = weighted(&f);
                if !(cost > 0.0) {
                    break;
                }
                // Weighted JᵀJ and −JᵀF.
                let mut h = [[0.0f64; #z]; #z];
                let mut g = [0.0f64; #z];
                for r in 0..#n {
                    let wr = w[r] * w[r];
                    for p in 0..#z {
                        let jp = j[r][p];
                        if jp != 0.0 {
                            g[p] -= wr * jp * f[r];
                            for q in 0..#z {
                                h[p][q] += wr * jp * j[r][q];
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
                    let Some(lu) = ::linkage::lu::Lu::<#z>::new(damped) else {
                        mu *= 10.0;
                        continue;
                    };
                    let mut d = g;
                    lu.solve(&mut d);
                    let (mut vt, mut xt) = (*v, *x);
                    for p in 0..#m {
                        xt[p] += d[p];
                    }
                    #step_intermediate
                    let mut ft = [0.0f64; #n];
                    self.residual(&vt, &xt, &mut ft);
                    if weighted(&ft) < cost {
                        let negligible = d.iter().zip(#stepped).all(|(s, q)| s.abs() <= 1e-13 * (1.0 + q.abs()));
                        *v = vt;
                        *x = xt;
                        f = ft;
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
            let left = f.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            if left.is_finite() { left } else { f64::INFINITY }
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
