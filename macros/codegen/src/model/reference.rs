//! The declared `home` pose, checked at compile time: the derived constants evaluated on the
//! declared geometry (with the same kernels the runtime uses), the platform pivots placed by
//! the pose, the joint inputs from inverse kinematics; then F must vanish there (the mechanism
//! can be assembled at home) and B must be regular (no architecture or configuration
//! singularity at the reference configuration).

use crate::expr::Var;
use crate::model::{Inverse, Model, PointRef, Recipes};
use linkage_geometry as geo;
use nalgebra::DMatrix;
use proc_macro2::Span;

/// The home configuration: pose, pivots and joint inputs.
pub struct Reference {
    pub pose: [f64; 6],
    pub v: Vec<f64>,
    pub x: Vec<f64>,
}

fn point(g: &[f64], s: [usize; 3]) -> [f64; 3] {
    s.map(|i| g[i])
}

/// A point's home position in the base frame (or, for `PointRef::Slots` on the platform, in
/// the platform's frame: see [`PointRef`]).
pub fn home_point(model: &Model, g: &[f64], p: PointRef) -> [f64; 3] {
    crate::model::home_of(model.home_pose, &model.auto_points, g, p)
}

/// The constants at the declared geometry, by the interpreter every generated `from_geometry`
/// runs.
pub fn constants(model: &Model) -> Result<Vec<f64>, String> {
    let g = model.default_slots();
    let table = model.recipe_table();
    let recipes = Recipes {
        home_pose: model.home_pose,
        auto: &model.auto_points,
        constants: &table,
    };
    let mut auto = vec![[0.0; 3]; recipes.auto.len()];
    let mut c = vec![0.0; recipes.constants.len()];
    recipes
        .derive(&g, &mut auto, &mut c)
        .map_err(|e| match e.constant {
            Some(i) => format!(
                "constant `{}` cannot be derived from the declared geometry: {}",
                model.constants[i].name, e.error
            ),
            None => format!("a point added to a link cannot be made: {}", e.error),
        })?;
    Ok(c)
}

/// Unknowns, inputs and constants at a configuration.
pub type Configuration = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The home configuration: the platform at `pose`, intermediate points where they are declared,
/// inputs from inverse kinematics (closed-form chains) or their home values (general chains).
pub fn configuration(model: &Model, pose: [f64; 6]) -> Result<Configuration, String> {
    let c = constants(model)?;
    let g = model.default_slots();
    let [yaw, pitch, roll, tx, ty, tz] = pose;
    let r = linkage_geometry::rotation(yaw, pitch, roll);
    let k = model.points.len();
    let mut v = vec![0.0; model.unknowns.len()];
    for (p, pt) in model.points.iter().enumerate() {
        let l = point(&g, pt.local);
        for axis in 0..3 {
            v[model.unknown(p, axis)] =
                r[axis][0] * l[0] + r[axis][1] * l[1] + r[axis][2] * l[2] + [tx, ty, tz][axis];
        }
    }
    for (_, at, first) in &model.general_points {
        let q = home_point(model, &g, *at);
        v[*first..*first + 3].copy_from_slice(&q);
    }
    let at = |p: usize| [v[p], v[k + p], v[2 * k + p]];
    let consts = |s: [usize; 3]| s.map(|i| c[i]);
    let mut x = vec![0.0; model.inputs.len()];
    for &(input, value) in &model.general_home_inputs {
        x[input] = value;
    }
    let general = |i: &usize| model.general_home_inputs.iter().any(|(j, _)| j == i);
    for inv in &model.inverses {
        match inv {
            Inverse::Distance {
                input,
                point: p,
                anchor,
                offset,
            } => {
                x[*input] = geo::distance(at(*p), consts(*anchor)) - offset.map_or(0.0, |o| c[o]);
            }
            Inverse::RevoluteRod {
                input,
                point: p,
                o,
                u,
                w,
                length,
            } => {
                x[*input] = geo::revolute_rod_inverse(
                    at(*p),
                    consts(*o),
                    consts(*u),
                    consts(*w),
                    c[*length],
                    0.0,
                )
                .ok_or_else(|| {
                    format!(
                        "no value of `{}` reaches the `home` pose",
                        model.inputs[*input]
                    )
                })?;
            }
            Inverse::PrismaticRod {
                input,
                point: p,
                c0,
                e,
                length,
                offset,
            } => {
                // The slide nearest the declared configuration's, read with the offset.
                let offset = offset.map_or(0.0, |o| c[o]);
                x[*input] =
                    geo::prismatic_rod_inverse(at(*p), consts(*c0), consts(*e), c[*length], 0.0)
                        .ok_or_else(|| {
                            format!(
                                "no value of `{}` reaches the `home` pose",
                                model.inputs[*input]
                            )
                        })?
                        + offset;
            }
            Inverse::None { inputs } => {
                if let Some(i) = inputs.iter().find(|i| !general(i)) {
                    return Err(format!(
                        "`home` needs inverse kinematics in closed form, which `{}` lacks",
                        model.inputs[*i]
                    ));
                }
            }
        }
    }
    Ok((v, x, c))
}

/// The largest residual at a configuration, against the squared length scale of `v`.
pub fn assembled(model: &Model, v: &[f64], x: &[f64], c: &[f64]) -> Result<(), String> {
    let scale = v.iter().chain(x).fold(1.0f64, |m, a| m.max(a.abs()));
    for (i, f) in model.equations.iter().enumerate() {
        let residual = f.eval(v, x, c);
        if !(residual.abs() <= 1e-6 * scale * scale) {
            return Err(format!(
                "the mechanism cannot be assembled at its home configuration: F{} = {} is {residual:.3e} there",
                i + 1,
                model.render(f)
            ));
        }
    }
    Ok(())
}

/// For the general model: checks that the declared configuration assembles, decides the mobility
/// by the rank of the Jacobian there, and drops equations that depend on earlier ones.
/// `priority` orders the equations for the rank test (lower first, then in order): of two
/// that depend on each other, the later in that order is left out — unless that leaves ∂F/∂v
/// nearly singular at home, where a row barely independent of those before it may wait for
/// the rest of its priority (see `simplify::rank::at_home`).
pub fn rank_at_home(
    model: &mut Model,
    d: &crate::front::resolved::Decl,
    priority: &[u8],
) -> syn::Result<()> {
    let p = &d.platform;
    let span = p
        .home
        .map(|(s, _)| s)
        .or_else(|| p.home_inputs.as_ref().map(|(s, _)| *s))
        .unwrap_or_else(|| d.name.span());
    let declared = p.home.is_some();
    let by_inputs = p.home_inputs.is_some();
    let fail = |msg: String| {
        let hint = if declared {
            ""
        } else if by_inputs {
            " (with `home = inputs(...)` the declared geometry is still one configuration the mechanism assembles in, with the platform's frame at the base frame: declare the platform's pivots where they are there)"
        } else {
            " (no `home` is declared on the platform, so its pivots were taken at the identity pose: declare `platform(home = [yaw, pitch, roll, x, y, z])` where the mechanism assembles)"
        };
        syn::Error::new(span, format!("{msg}{hint}"))
    };
    let (v, x, c) = configuration(model, model.home_pose).map_err(fail)?;
    assembled(model, &v, &x, &c).map_err(fail)?;
    let (n, inputs) = (model.unknowns.len(), model.inputs.len());
    let class_of = |i: usize| priority.get(i).copied().unwrap_or(u8::MAX);
    let mut order: Vec<usize> = (0..model.equations.len()).collect();
    order.sort_by_key(|&i| (class_of(i), i));
    let classes: Vec<Vec<usize>> = order
        .chunk_by(|&a, &b| class_of(a) == class_of(b))
        .map(<[usize]>::to_vec)
        .collect();
    let ranked = crate::simplify::rank::at_home(&model.equations, &classes, n, inputs, &v, &x, &c);
    let gk = crate::model::mobility::of(d);
    let rule = format!(
        "rank of ∂F/∂(v, x) at home: M = {n} + {inputs} − {} = {} (Grübler–Kutzbach says {})",
        n as i64 + inputs as i64 - ranked.mobility,
        ranked.mobility,
        gk.effective()
    );
    if ranked.mobility != inputs as i64 {
        return Err(crate::model::mobility::mismatch(
            d,
            model,
            ranked.mobility,
            &rule,
        ));
    }
    if ranked.rank_v < n {
        return Err(syn::Error::new(
            d.name.span(),
            format!(
                "∂F/∂v has rank {} for {n} unknown coordinates at home: the home configuration is singular, or the inputs leave a link free to spin or a point that nothing holds",
                ranked.rank_v
            ),
        ));
    }
    let all = std::mem::take(&mut model.equations);
    for (i, e) in all.into_iter().enumerate() {
        if ranked.kept.contains(&i) {
            model.equations.push(e);
        } else {
            let text = model.render(&e);
            model.dropped.push(text);
            model.dependent.push(e);
        }
    }
    model.mobility = Some(rule);
    Ok(())
}

pub fn check(model: &Model, (span, pose): (Span, [f64; 6])) -> syn::Result<Reference> {
    let fail = |msg: String| syn::Error::new(span, msg);
    let (v, x, c) = configuration(model, pose).map_err(fail)?;
    assembled(model, &v, &x, &c)
        .map_err(|e| fail(e.replace("home configuration", "`home` pose")))?;
    let n = v.len();
    let b = DMatrix::from_fn(n, n, |i, j| {
        model.equations[i]
            .derivative(Var::Unknown(j))
            .eval(&v, &x, &c)
    });
    let sv = b.singular_values();
    let (smin, smax) = (sv.min(), sv.max());
    if !(smin > 1e-10 * smax) {
        return Err(fail(format!(
            "the declared geometry is singular at its `home` pose (smallest/largest singular value of ∂F/∂v = {:.1e}): an architecture or configuration singularity",
            smin / smax
        )));
    }
    Ok(Reference { pose, v, x })
}
