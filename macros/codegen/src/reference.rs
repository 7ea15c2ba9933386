//! The declared `home` pose, checked at compile time: the derived constants evaluated on the
//! declared geometry (with the same kernels the runtime uses), the platform pivots placed by
//! the pose, the joint inputs from inverse kinematics; then F must vanish there (the mechanism
//! can be assembled at home) and B must be regular (no architecture or configuration
//! singularity at the reference configuration).

use crate::expr::Var;
use crate::model::{Inverse, Model, Recipe};
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

/// The constants at the declared geometry.
pub fn constants(model: &Model) -> Result<Vec<f64>, String> {
    let g = model.default_slots();
    model
        .constants
        .iter()
        .map(|c| {
            let value = match &c.recipe {
                Recipe::Slot(s) => Ok(g[*s]),
                Recipe::Distance { a, b } => Ok(geo::distance(point(&g, *a), point(&g, *b))),
                Recipe::Rigid {
                    frame,
                    point: q,
                    index,
                    coplanar,
                } => geo::rigid_coefficients(frame.map(|f| point(&g, f)), point(&g, *q), *coplanar)
                    .map(|r| r[*index]),
                Recipe::Axis {
                    a,
                    b,
                    point: q,
                    index,
                } => {
                    geo::axis_frame(point(&g, *a), point(&g, *b), point(&g, *q)).map(|r| r[*index])
                }
            };
            value.map_err(|e| {
                format!(
                    "constant `{}` cannot be derived from the declared geometry: {e}",
                    c.name
                )
            })
        })
        .collect()
}

/// Rz(yaw)·Ry(pitch)·Rx(roll), as `linkage::Pose::from_euler`.
fn rotation(yaw: f64, pitch: f64, roll: f64) -> [[f64; 3]; 3] {
    let (cy, sy) = (yaw.cos(), yaw.sin());
    let (cp, sp) = (pitch.cos(), pitch.sin());
    let (cr, sr) = (roll.cos(), roll.sin());
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

pub fn check(model: &Model, (span, pose): (Span, [f64; 6])) -> syn::Result<Reference> {
    let fail = |msg: String| syn::Error::new(span, msg);
    let c = constants(model).map_err(fail)?;
    let g = model.default_slots();
    let [yaw, pitch, roll, tx, ty, tz] = pose;
    let r = rotation(yaw, pitch, roll);
    let k = model.points.len();
    let mut v = vec![0.0; model.unknowns.len()];
    for (p, pt) in model.points.iter().enumerate() {
        let l = point(&g, pt.local);
        for axis in 0..3 {
            v[model.unknown(p, axis)] =
                r[axis][0] * l[0] + r[axis][1] * l[1] + r[axis][2] * l[2] + [tx, ty, tz][axis];
        }
    }
    let at = |p: usize| [v[p], v[k + p], v[2 * k + p]];
    let consts = |s: [usize; 3]| s.map(|i| c[i]);
    let mut x = vec![0.0; model.inputs.len()];
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
                    fail(format!(
                        "no value of `{}` reaches the `home` pose",
                        model.inputs[*input]
                    ))
                })?;
            }
            Inverse::PrismaticRod {
                input,
                point: p,
                c0,
                e,
                length,
            } => {
                x[*input] =
                    geo::prismatic_rod_inverse(at(*p), consts(*c0), consts(*e), c[*length], 0.0)
                        .ok_or_else(|| {
                            fail(format!(
                                "no value of `{}` reaches the `home` pose",
                                model.inputs[*input]
                            ))
                        })?;
            }
            Inverse::None { inputs } if inputs.is_empty() => {}
            Inverse::None { inputs } => {
                return Err(fail(format!(
                    "`home` needs inverse kinematics in closed form, which `{}` lacks",
                    model.inputs[inputs[0]]
                )));
            }
        }
    }
    let scale = v.iter().fold(1.0f64, |m, a| m.max(a.abs()));
    for (i, f) in model.equations.iter().enumerate() {
        let residual = f.eval(&v, &x, &c);
        if !(residual.abs() <= 1e-6 * scale * scale) {
            return Err(fail(format!(
                "the mechanism cannot be assembled at its `home` pose: F{} = {} is {residual:.3e} there",
                i + 1,
                model.render(f)
            )));
        }
    }
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
