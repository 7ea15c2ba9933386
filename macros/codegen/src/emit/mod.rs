//! Emission: the model as plain, allocation-free, `no_std` Rust implementing
//! `::linkage::Mechanism`. Only absolute paths are named, so the user's imports never matter.

pub mod dependent;
pub mod expr;
pub mod factor;
pub mod inverse;
pub mod lu;
pub mod recipes;
pub mod symmetry;
pub mod turns;

use crate::emit::expr::{lit, tokens, Arithmetic, Emitter};
use crate::expr::{Expr, Var};
use crate::front::ast::Mechanism;
use crate::model::{HomeOf, Inverse, Model, Placed, PointRef};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

pub fn expand(
    mech: &Mechanism,
    model: &Model,
    home: Option<&crate::model::reference::Reference>,
) -> TokenStream {
    let name = &mech.name;
    let vis = &mech.vis;
    let attrs = &mech.attrs;
    let n = model.unknowns.len();
    let m = model.inputs.len();
    let ng = model.slots.len();
    let nc = model.constants.len();
    let jac = model.jacobian();
    let nnz = jac.len();
    let jacobian_uses_inputs = jac
        .iter()
        .any(|(_, _, e)| (0..m).any(|j| e.depends_on(Var::Input(j))));

    let geometry_names = model.slots.iter().map(|s| s.name.as_str());
    // Links' lengths enter the equations squared: a negative one is refused, not taken for
    // its magnitude.
    let positive_checks = model.slots.iter().enumerate().filter(|(_, s)| s.positive).map(|(k, _)| {
        quote! {
            if !(geometry[#k] > 0.0) {
                return Err(::linkage::GeometryError::NonPositiveLength { name: Self::GEOMETRY_NAMES[#k] });
            }
        }
    });
    // Every pair axis given by two points of one link, checked apart as at compile time
    // (`set_pivot` can move one onto the other).
    let axis_checks = (!model.axes.is_empty()).then(|| {
        let each = model
            .axes
            .iter()
            .map(|[a, b]| quote!([[#(#a),*], [#(#b),*]]));
        quote!(::linkage::__private::check_axes(&geometry, &[#(#each),*])?;)
    });
    let defaults = model.slots.iter().map(|s| lit(s.default));
    // Slots declared as formulas of parameters, set from them before anything else (emitted
    // only where there are some).
    let formulas = (!model.formulas.is_empty()).then(|| {
        let each = model.formulas.iter().map(|(slot, ops)| {
            let ops = ops.iter().map(formula_op);
            quote!(f::Formula { slot: #slot, ops: &[#(#ops),*] })
        });
        quote! {
            let mut geometry = geometry;
            use ::linkage::__private::formula as f;
            const FORMULAS: &[f::Formula<'static>] = &[#(#each),*];
            f::apply(FORMULAS, &mut geometry);
        }
    });
    let formulas_doc = (!model.formulas.is_empty()).then(|| {
        quote!(#[doc = " Values declared as arithmetic on parameters are computed from the parameters; what the array holds for them is not read."])
    });
    // Names not to be set by name, so that setting one says which parameter to set.
    let followed = model.followed.iter().map(|(n, p)| quote!((#n, #p)));
    let followed = quote!(&[#(#followed),*]);
    // Parameters only the macro read: a change to one would change nothing, so it is refused.
    let compile_time_check = (!model.compile_time.is_empty()).then(|| {
        let slots = &model.compile_time;
        quote!(::linkage::__private::check_compile_time(&Self::GEOMETRY_NAMES, &[#(#slots),*], &geometry, &Self::DEFAULT_GEOMETRY)?;)
    });
    let constant_names = model.constants.iter().map(|c| c.name.as_str());
    let unknown_names = model.unknowns.iter().map(String::as_str);
    let input_names = model.inputs.iter().map(String::as_str);
    let equation_text: Vec<String> = model.equations.iter().map(|e| model.render(e)).collect();
    let jacobian_text: Vec<String> = jac.iter().map(|(_, _, e)| model.render(e)).collect();
    let pattern = jac.iter().map(|(r, c, _)| quote!((#r, #c)));
    let mobility = model
        .mobility
        .clone()
        .unwrap_or_else(|| model.counted.clone());
    let listing = listing(model, &equation_text, &jac, &jacobian_text).replacen(
        "\nunknowns:",
        &format!("\nmobility: {mobility}\nunknowns:"),
        1,
    );
    let point_names = model.points.iter().map(|p| p.name.as_str());
    let [f0, f1, f2] = model.frame;
    let recipes = crate::emit::recipes::table(model);
    let na = model.auto_points.len();

    let dependent_offset = crate::emit::dependent::dependent_offset(model);
    let symmetry = crate::emit::symmetry::symmetry(model);
    // ∂F/∂x's nonzeros, row by row in column order.
    let input_terms: Vec<Vec<(usize, Expr)>> = model
        .equations
        .iter()
        .map(|f| {
            (0..m)
                .map(|j| (j, f.derivative(Var::Input(j))))
                .filter(|(_, d)| !d.is_zero())
                .collect()
        })
        .collect();
    // Sines and cosines of inputs, where the kernels have any, evaluated once per fixed
    // inputs by `turns` and read from `t` by the residual and the factorisation.
    let turned = crate::emit::turns::turned_inputs(
        m,
        model
            .equations
            .iter()
            .chain(jac.iter().map(|(_, _, e)| e))
            .chain(input_terms.iter().flatten().map(|(_, d)| d)),
    );
    let turns = turned.iter().any(|t| t[0] || t[1]);
    let residual_body = assignments(
        if turns {
            Arithmetic::Turned
        } else {
            Arithmetic::F64
        },
        model
            .equations
            .iter()
            .enumerate()
            .map(|(i, e)| (quote!(f[#i]), e)),
    );
    let jacobian_sparse = assignments(
        Arithmetic::F64,
        jac.iter()
            .enumerate()
            .map(|(k, (_, _, e))| (quote!(values[#k]), e)),
    );
    let residual_in = assignments(
        Arithmetic::Generic,
        model
            .equations
            .iter()
            .enumerate()
            .map(|(i, e)| (quote!(f[#i]), e)),
    );
    let jacobian_in = assignments(
        Arithmetic::Generic,
        jac.iter()
            .enumerate()
            .map(|(k, (_, _, e))| (quote!(values[#k]), e)),
    );
    let jacobian_dense = assignments(
        Arithmetic::F64,
        jac.iter().map(|(r, c, e)| (quote!(b[#r][#c]), e)),
    );
    let input_jacobian = assignments(
        Arithmetic::F64,
        input_terms
            .iter()
            .enumerate()
            .flat_map(|(r, terms)| terms.iter().map(move |(j, d)| (quote!(a[#r][#j]), d))),
    );
    // The same products as `input_jacobian`'s nonzeros, summed per row in column order.
    let input_derivative_body = {
        let mut emitter = Emitter::new(if turns {
            Arithmetic::Turned
        } else {
            Arithmetic::F64
        });
        input_terms
            .iter()
            .flatten()
            .for_each(|(_, d)| emitter.count(d));
        let rows: Vec<TokenStream> = input_terms
            .iter()
            .enumerate()
            .map(|(r, terms)| {
                let terms: Vec<TokenStream> = terms
                    .iter()
                    .map(|(j, d)| {
                        let d = emitter.tokens(d);
                        quote!(#d * dx[#j])
                    })
                    .collect();
                if terms.is_empty() {
                    quote!(out[#r] = 0.0;)
                } else {
                    quote!(out[#r] = #(#terms)+*;)
                }
            })
            .collect();
        let lets = emitter.bindings();
        quote!(#lets #(#rows)*)
    };
    let point_local = model.points.iter().enumerate().map(|(i, p)| {
        let [x, y, z] = p.local;
        quote!(#i => [g[#x], g[#y], g[#z]],)
    });
    // A chain without a closed-form inverse makes the inverse numerical, and `home_start` the
    // declared configuration itself.
    let no_closed_form = crate::emit::inverse::numerical_input(model);
    let pattern_pairs: Vec<(usize, usize)> = jac.iter().map(|(r, c, _)| (*r, *c)).collect();
    let inverse_body = crate::emit::inverse::body(model, home.is_some(), &pattern_pairs);
    let closed_form_method = crate::emit::inverse::closed_form_method(model);
    // A leg's length (input plus offset) must be positive.
    let ranges = model.inverses.iter().filter_map(|inv| match inv {
        Inverse::Distance { input, offset, .. } => {
            let off = match offset {
                Some(o) => quote!(c[#o]),
                None => quote!(0.0),
            };
            Some(quote!(if !(x[#input] + #off > 0.0) { return Err(#input); }))
        }
        _ => None,
    });
    let uses_v = model
        .equations
        .iter()
        .any(|e| (0..n).any(|i| e.depends_on(Var::Unknown(i))));
    let allow = if uses_v {
        quote!()
    } else {
        quote!(#[allow(unused_variables)])
    };
    // The f64 kernels (residual, Jacobians, factorisation and solve) are `#[inline]` where
    // debug assertions are off, as in release builds: inlined into the solvers' loops there.
    // Where they are on (the tests' profile, optimised), an inline function is compiled again
    // in every codegen unit that calls it, for every declared mechanism: without the hint the
    // integration tests' binary rebuilt alone in 89 s instead of 115–118 s, its tests running
    // as fast (39.7 s against 40.5 s; BENCHMARKS.md). The residual, the factorisation and the
    // solve are `#[inline(always)]` there: the runtime's x86-64-v3 twins (`dispatch.rs`) are
    // compiled for AVX only as far as the kernels are inlined into them, and with the plain
    // hint the compiler left the factorisation out of line once it had a few more callers
    // (`count nr-normal`: 615 554 instructions inlined, 666 695 not).
    let residual_fns = if turns {
        let turns_body = crate::emit::turns::turns_body(&turned);
        quote! {
            #[inline]
            fn residual(&self, v: &[f64; #n], x: &[f64; #m], f: &mut [f64; #n]) {
                self.residual_turned(v, x, &self.turns(x), f);
            }

            #[cfg_attr(not(debug_assertions), inline(always))]
            #allow
            fn residual_turned(&self, v: &[f64; #n], x: &[f64; #m], t: &::linkage::Turns<#m>, f: &mut [f64; #n]) {
                let c = &self.constants;
                #residual_body
            }

            #[inline]
            fn turns(&self, x: &[f64; #m]) -> ::linkage::Turns<#m> {
                #turns_body
            }
        }
    } else {
        quote! {
            #[cfg_attr(not(debug_assertions), inline(always))]
            #allow
            fn residual(&self, v: &[f64; #n], x: &[f64; #m], f: &mut [f64; #n]) {
                let c = &self.constants;
                #residual_body
            }
        }
    };
    let input_derivative_fns = if turns {
        quote! {
            #[inline]
            fn input_derivative(&self, v: &[f64; #n], x: &[f64; #m], dx: &[f64; #m], out: &mut [f64; #n]) {
                self.input_derivative_turned(v, x, &self.turns(x), dx, out);
            }

            #[cfg_attr(not(debug_assertions), inline)]
            #[allow(unused_variables)]
            fn input_derivative_turned(&self, v: &[f64; #n], x: &[f64; #m], t: &::linkage::Turns<#m>, dx: &[f64; #m], out: &mut [f64; #n]) {
                let c = &self.constants;
                #input_derivative_body
            }
        }
    } else {
        quote! {
            #[cfg_attr(not(debug_assertions), inline)]
            #[allow(unused_variables)]
            fn input_derivative(&self, v: &[f64; #n], x: &[f64; #m], dx: &[f64; #m], out: &mut [f64; #n]) {
                let c = &self.constants;
                #input_derivative_body
            }
        }
    };
    let priv_ = quote!(::linkage::__private);
    // Without a closed loop the inputs place every link: one configuration at any inputs,
    // which the residual path finds even where the straight path of geometry passes a
    // degenerate one (an axis's second point moved through its first, reversing the axis).
    let carry = if model.open {
        quote!(::linkage::Start::follow(self, v, x))
    } else {
        quote! {
            let (from, to) = (before.geometry, self.geometry);
            ::linkage::Start::follow_geometry(self, v, x, |s| {
                Self::from_geometry(::core::array::from_fn(|i| from[i] + s * (to[i] - from[i]))).ok()
            })
        }
    };
    let home_items = home.map(|r| {
        let pose = r.pose.map(lit);
        let x0 = r.x.iter().map(|x| lit(*x));
        let v0 = r.v.iter().map(|x| lit(*x));
        // Where every chain has a closed form and the pose alone places every unknown (no
        // points of links between), the start is the home pose with the inputs the closed
        // forms give for the current geometry (a delta's cranks: its base set 1 mm wider made
        // the declared configuration inconsistent, and `home_start` refused it). Otherwise it
        // is the declared configuration at the declared inputs, carried to the current
        // geometry along the change of geometry by `follow_from` (the declared configuration
        // itself where the geometry is the declared one).
        let pose_places_all = model.unknowns.len() == 3 * model.points.len();
        let start = if (model.general_home_inputs.is_empty() || pose_places_all)
            && no_closed_form.is_none()
        {
            // Where a calibration took the home pose off the machine's motion (a 3-RPS has
            // three freedoms, and its pose six coordinates), the configuration at the declared
            // inputs instead; the pose's error if that fails too.
            quote! {
                let [yaw, pitch, roll, x, y, z] = Self::HOME;
                let v = ::linkage::unknowns_from_pose(self, &::linkage::Pose::from_euler(yaw, pitch, roll, [x, y, z]));
                let posed = self.closed_form_inputs(&v, &Self::HOME_INPUTS).map_err(|e| match e {
                    ::linkage::InverseError::Unreachable { input } | ::linkage::InverseError::NoClosedForm { input } | ::linkage::InverseError::FarReference { input } => ::linkage::SolveError::InvalidInput { input },
                    ::linkage::InverseError::NonFinite | ::linkage::InverseError::Inconsistent => ::linkage::SolveError::NonFinite,
                }).and_then(|inputs| ::linkage::Start::new(self, v, inputs));
                posed.or_else(|e| self.follow_from(&Self::new(), Self::HOME_V, Self::HOME_INPUTS).map_err(|_| e))
            }
        } else {
            quote!(self.follow_from(&Self::new(), Self::HOME_V, Self::HOME_INPUTS))
        };
        quote! {
            /// The platform's pose `[yaw, pitch, roll, x, y, z]` at home (the declared `home`
            /// pose, or where `home = inputs(...)` puts it), checked at compile time: the
            /// mechanism assembles there and ∂F/∂v is regular.
            pub const HOME: [f64; 6] = [#(#pose),*];
            /// The joint inputs at `HOME` on the declared geometry (from inverse kinematics, or
            /// as `home = inputs(...)` gives them).
            pub const HOME_INPUTS: [f64; #m] = [#(#x0),*];

            /// Every unknown at [`Self::HOME`], on the declared geometry.
            pub const HOME_V: [f64; #n] = [#(#v0),*];

            /// The start configuration at [`Self::HOME`] for the current geometry: the home
            /// pose with the inputs the closed forms give where every chain has one, the pose
            /// places every unknown and the mechanism can take it; otherwise the configuration
            /// at `HOME_INPUTS` on the branch of the declared one, carried to the current
            /// geometry along the change of geometry by [`Self::follow_from`].
            pub fn home_start(&self) -> ::core::result::Result<::linkage::Start<#n, #m>, ::linkage::SolveError> {
                #start
            }
        }
    });
    // Where home is known, `AllModes` seeds from it as well (see the trait's documentation).
    let home_configuration = home.map(|_| {
        quote! {
            fn home_configuration(&self) -> ::core::option::Option<([f64; #n], [f64; #m])> {
                self.home_start().ok().map(|s| (*s.v(), *s.x()))
            }
        }
    });
    let link_names = model.links.iter().map(|l| l.name.as_str());
    let nl = model.links.len();
    let link_arms = model
        .links
        .iter()
        .enumerate()
        .map(|(i, l)| match &l.placed {
            Placed::Unmodelled => quote!(#i => ::core::option::Option::None,),
            Placed::Unknowns => quote!(#i => ::linkage::pose_from_unknowns(self, v),),
            Placed::Frame(frame) => {
                let now = frame.iter().map(|(e, _)| {
                    let [a, b, c] = e.each_ref().map(tokens);
                    quote!([#a, #b, #c])
                });
                let from = frame.iter().map(|(_, h)| match h {
                    HomeOf::Point(p) => point3(model, *p),
                    HomeOf::Constants([a, b, c]) => quote!([c[#a], c[#b], c[#c]]),
                });
                quote!(#i => ::linkage::Pose::between([#(#from),*], [#(#now),*]),)
            }
        });
    // B at home, so that the factorisation's pivot order prefers pivots that are large there.
    let sample: Option<Vec<f64>> = home.and_then(|r| {
        let c = crate::model::reference::constants(model).ok()?;
        Some(jac.iter().map(|(_, _, e)| e.eval(&r.v, &r.x, &c)).collect())
    });
    let plan = crate::factor::plan(n, &jac, sample.as_deref());
    let (factor_type, factor_fns, factor_ops) = crate::emit::factor::factor(&plan, m, nc, turns);
    let ops_doc = crate::emit::factor::operations_doc(model, &jac, &plan, factor_ops);
    let new_doc =
        format!("The mechanism with the geometry declared in `{name}`'s `mechanism!` block.");
    let _ = format_ident!("unused");

    quote! {
        #(#attrs)*
        ///
        #[doc = #ops_doc]
        #[derive(Clone, Debug, PartialEq)]
        #vis struct #name {
            geometry: [f64; #ng],
            constants: [f64; #nc],
        }

        // Declared values can be close to a named constant (a parameter `pi / 4`).
        #[allow(clippy::approx_constant)]
        impl #name {
            /// Names of the run-time geometry values (`link.pivot.axis`, lengths, parameters).
            pub const GEOMETRY_NAMES: [&'static str; #ng] = [#(#geometry_names),*];
            /// The geometry as declared.
            pub const DEFAULT_GEOMETRY: [f64; #ng] = [#(#defaults),*];
            /// Names of the constants the equations use, derived from the geometry.
            pub const CONSTANT_NAMES: [&'static str; #nc] = [#(#constant_names),*];
            /// The generated system, human-readable: equations, then ∂F/∂v entries.
            pub const LISTING: &'static str = #listing;

            #[doc = #new_doc]
            pub fn new() -> Self {
                match Self::from_geometry(Self::DEFAULT_GEOMETRY) {
                    Ok(m) => m,
                    // Unreachable: the macro derived the constants from this geometry at compile time.
                    Err(_) => Self { geometry: Self::DEFAULT_GEOMETRY, constants: [f64::NAN; #nc] },
                }
            }

            /// The mechanism with other dimensions (e.g. from a calibration), in the order of
            /// [`Self::GEOMETRY_NAMES`]. Derived constants are recomputed.
            #formulas_doc
            pub fn from_geometry(geometry: [f64; #ng]) -> ::core::result::Result<Self, ::linkage::GeometryError> {
                #formulas
                // Finite values whose squares are finite, a formula's NaN named with its
                // parameter.
                ::linkage::__private::check_values(&Self::GEOMETRY_NAMES, #followed, &geometry)?;
                #compile_time_check
                #(#positive_checks)*
                #axis_checks
                use ::linkage::__private::recipe;
                const RECIPES: recipe::Recipes<'static> = #recipes;
                let mut auto = [[0.0f64; 3]; #na];
                let mut c = [0.0f64; #nc];
                ::linkage::__private::derive_constants(&RECIPES, &geometry, &mut auto, &mut c)?;
                Ok(Self { geometry, constants: c })
            }

            /// The current geometry values.
            pub fn geometry(&self) -> &[f64; #ng] {
                &self.geometry
            }

            /// The derived constants, in the order of [`Self::CONSTANT_NAMES`].
            pub fn constants(&self) -> &[f64; #nc] {
                &self.constants
            }

            /// Changes one geometry value by name; the mechanism is unchanged on error.
            pub fn set_geometry(&mut self, name: &str, value: f64) -> ::core::result::Result<(), ::linkage::GeometryError> {
                let mut g = self.geometry;
                #priv_::set_named(&Self::GEOMETRY_NAMES, #followed, &mut g, name, value)?;
                *self = Self::from_geometry(g)?;
                Ok(())
            }

            #home_items

            #closed_form_method

            /// The moving links [`Self::link_pose`] reports on: the platform, then the named
            /// links between it and the base.
            pub const LINKS: [&'static str; #nl] = [#(#link_names),*];

            /// The pose of moving link `link` (an index into [`Self::LINKS`]) at `(v, x)`: the
            /// rigid motion from its declared coordinates (the platform's own frame; the base
            /// frame at home for the other links) to where it is. A platform of one pivot or of
            /// pivots on one line has the pose `linkage::pose_from_unknowns` gives it (its spin,
            /// which no pair fixes, by that function's convention). `None` for a rod, whose
            /// spin about its axis is not modelled, or an index out of range.
            #[allow(unused_variables)]
            pub fn link_pose(&self, link: usize, v: &[f64; #n], x: &[f64; #m]) -> ::core::option::Option<::linkage::Pose> {
                let c = &self.constants;
                let g = &self.geometry;
                match link {
                    #(#link_arms)*
                    _ => ::core::option::Option::None,
                }
            }

            /// A configuration `v` of `before` (this mechanism with other dimensions: as
            /// declared, or before a calibration) at inputs `x`, carried to this geometry along
            /// the change: every geometry value moved from `before`'s to this one's together,
            /// and the configuration followed on its branch all along
            /// (`linkage::Start::follow_geometry`). `linkage::Start::new` where the geometry is
            /// the same; `linkage::Start::follow` for a mechanism without a closed loop, whose
            /// inputs place every link.
            pub fn follow_from(&self, before: &Self, v: [f64; #n], x: [f64; #m]) -> ::core::result::Result<::linkage::Start<#n, #m>, ::linkage::SolveError> {
                if self.geometry == before.geometry {
                    return ::linkage::Start::new(self, v, x);
                }
                #carry
            }

            /// Moves pivot `pivot` of link `link` (its own frame); the mechanism is unchanged on error.
            pub fn set_pivot(&mut self, link: &str, pivot: &str, p: [f64; 3]) -> ::core::result::Result<(), ::linkage::GeometryError> {
                let mut g = self.geometry;
                #priv_::set_pivot(&Self::GEOMETRY_NAMES, #followed, &mut g, link, pivot, p)?;
                *self = Self::from_geometry(g)?;
                Ok(())
            }
        }

        impl ::core::default::Default for #name {
            fn default() -> Self {
                Self::new()
            }
        }

        #[allow(clippy::approx_constant)]
        impl ::linkage::Mechanism<#n, #m> for #name {
            const NAME: &'static str = stringify!(#name);
            const UNKNOWNS: [&'static str; #n] = [#(#unknown_names),*];
            const INPUTS: [&'static str; #m] = [#(#input_names),*];
            const EQUATIONS: [&'static str; #n] = [#(#equation_text),*];
            const NNZ: usize = #nnz;
            const PATTERN: &'static [(usize, usize)] = &[#(#pattern),*];
            const JACOBIAN: &'static [&'static str] = &[#(#jacobian_text),*];
            const JACOBIAN_USES_INPUTS: bool = #jacobian_uses_inputs;
            const TURNS: bool = #turns;
            const POINTS: &'static [&'static str] = &[#(#point_names),*];
            const FRAME: [usize; 3] = [#f0, #f1, #f2];

            #residual_fns

            #[cfg_attr(not(debug_assertions), inline)]
            #[allow(unused_variables)]
            fn jacobian(&self, v: &[f64; #n], x: &[f64; #m], values: &mut [f64]) {
                let c = &self.constants;
                let values: &mut [f64; #nnz] = match values.get_mut(..#nnz).and_then(|s| s.try_into().ok()) {
                    Some(s) => s,
                    None => return,
                };
                #jacobian_sparse
            }

            // No `#[inline]` on the scalar-generic kernels and the dense Jacobian: an inline
            // function is compiled again in every codegen unit that calls it, and these are the
            // largest functions emitted, called from every solver. Without it a crate declaring
            // many mechanisms builds faster (the integration tests' binary rebuilt alone: 112 s →
            // 83 s), for 1 % more instructions in PH from home (`count ph-all`), 0.2 % in an
            // all-modes query and none in NR or the tracker (BENCHMARKS.md).
            #allow
            fn residual_in<T: ::linkage::Scalar>(&self, v: &[T; #n], x: &[T; #m], f: &mut [T; #n]) {
                let c = &self.constants;
                #residual_in
            }

            #[allow(unused_variables)]
            fn jacobian_in<T: ::linkage::Scalar>(&self, v: &[T; #n], x: &[T; #m], values: &mut [T]) {
                let c = &self.constants;
                let values: &mut [T; #nnz] = match values.get_mut(..#nnz).and_then(|s| s.try_into().ok()) {
                    Some(s) => s,
                    None => return,
                };
                #jacobian_in
            }

            #[allow(unused_variables)]
            fn jacobian_dense(&self, v: &[f64; #n], x: &[f64; #m], b: &mut [[f64; #n]; #n]) {
                let c = &self.constants;
                *b = [[0.0; #n]; #n];
                #jacobian_dense
            }

            type Factor = #factor_type;

            #factor_fns

            #[cfg_attr(not(debug_assertions), inline)]
            #[allow(unused_variables)]
            fn input_jacobian(&self, v: &[f64; #n], x: &[f64; #m], a: &mut [[f64; #m]; #n]) {
                let c = &self.constants;
                *a = [[0.0; #m]; #n];
                #input_jacobian
            }

            #input_derivative_fns

            #home_configuration

            fn point_local(&self, p: usize) -> [f64; 3] {
                let g = &self.geometry;
                match p {
                    #(#point_local)*
                    _ => [f64::NAN; 3],
                }
            }

            #[allow(unused_variables)]
            fn validate_inputs(&self, x: &[f64; #m]) -> ::core::result::Result<(), usize> {
                let c = &self.constants;
                // x · 0 is 0 for finite x and NaN otherwise: one sum, no branch per input,
                // and the same sum as the solvers' own finiteness check of x, which the
                // compiler then computes once for both. The first bad input only if one is.
                let mut zero = 0.0;
                let mut j = 0;
                while j < #m {
                    zero += x[j] * 0.0;
                    j += 1;
                }
                if zero != 0.0 {
                    let mut j = 0;
                    while j < #m {
                        if !x[j].is_finite() {
                            return Err(j);
                        }
                        j += 1;
                    }
                }
                #(#ranges)*
                Ok(())
            }

            #[allow(unused_variables, unused_mut)]
            fn inverse(&self, v: &[f64; #n], reference: &[f64; #m]) -> ::core::result::Result<[f64; #m], ::linkage::InverseError> {
                #inverse_body
            }

            #dependent_offset

            #symmetry
        }
    }
}

fn listing(
    model: &Model,
    equations: &[String],
    jac: &[(usize, usize, Expr)],
    jtext: &[String],
) -> String {
    let mut s =
        format!(
        "{}: {} equations in {} unknowns, {} inputs\nunknowns: {}\ninputs: {}\nconstants: {}\n\n",
        model.name,
        model.equations.len(),
        model.unknowns.len(),
        model.inputs.len(),
        model.unknowns.join(" "),
        model.inputs.join(" "),
        model.constants.iter().map(|c| c.name.as_str()).collect::<Vec<_>>().join(" ")
    );
    for (i, e) in equations.iter().enumerate() {
        s += &format!("F{} = {e}\n", i + 1);
    }
    if !model.dropped.is_empty() {
        s += "\ndependent at home, implied by the above and left out:\n";
        for e in &model.dropped {
            s += &format!("  {e}\n");
        }
    }
    s += &format!("\n∂F/∂v: {} nonzeros\n", jac.len());
    for ((r, c, _), t) in jac.iter().zip(jtext) {
        s += &format!("J({},{}) = {t}\n", r + 1, c + 1);
    }
    s
}

fn slots3(s: [usize; 3]) -> TokenStream {
    let [a, b, c] = s;
    quote!([g[#a], g[#b], g[#c]])
}

fn point3(model: &Model, p: PointRef) -> TokenStream {
    match p {
        PointRef::Slots(s) => slots3(s),
        PointRef::PlatformHome(s) => {
            let pose = model.home_pose.map(lit);
            let s = slots3(s);
            quote!(::linkage::__private::place([#(#pose),*], #s))
        }
        PointRef::Auto(i) => quote!(auto[#i]),
    }
}

/// The statements `place = expression;` of one function body, after the `let`s of the
/// subexpressions they share ([`Emitter`]).
fn assignments<'e>(
    arithmetic: Arithmetic,
    items: impl Iterator<Item = (TokenStream, &'e Expr)>,
) -> TokenStream {
    let items: Vec<(TokenStream, &Expr)> = items.collect();
    let mut emitter = Emitter::new(arithmetic);
    items.iter().for_each(|(_, e)| emitter.count(e));
    if arithmetic == Arithmetic::Generic {
        // Every repeated operation is bound here: each `let` goes where it is first needed, so
        // that fewer values are live at a time (all at the top, the complex and series
        // residuals took 4 % more instructions in release builds).
        let statements = items.iter().map(|(place, e)| {
            let e = emitter.tokens(e);
            let lets = emitter.new_bindings();
            quote!(#lets #place = #e;)
        });
        return quote!(#(#statements)*);
    }
    let statements: Vec<TokenStream> = items
        .iter()
        .map(|(place, e)| {
            let e = emitter.tokens(e);
            quote!(#place = #e;)
        })
        .collect();
    let lets = emitter.bindings();
    quote!(#lets #(#statements)*)
}

/// One step of a geometry formula, as the runtime's `formula::Op`.
fn formula_op(op: &linkage_geometry::formula::Op) -> TokenStream {
    use linkage_geometry::formula::Op;
    // Within the `use … formula as f` that the emitted `from_geometry` opens.
    let f = quote!(f::Op);
    match *op {
        Op::Num(x) => {
            let x = lit(x);
            quote!(#f::Num(#x))
        }
        Op::Slot(s) => quote!(#f::Slot(#s)),
        Op::Neg => quote!(#f::Neg),
        Op::Add => quote!(#f::Add),
        Op::Sub => quote!(#f::Sub),
        Op::Mul => quote!(#f::Mul),
        Op::Div => quote!(#f::Div),
        Op::Sqrt => quote!(#f::Sqrt),
        Op::Sin => quote!(#f::Sin),
        Op::Cos => quote!(#f::Cos),
        Op::Tan => quote!(#f::Tan),
        Op::Asin => quote!(#f::Asin),
        Op::Acos => quote!(#f::Acos),
        Op::Atan => quote!(#f::Atan),
    }
}
