//! The platform's declared `home` pose, in any of three forms, as `[yaw, pitch, roll, x, y, z]`
//! with R = Rz(yaw)·Ry(pitch)·Rx(roll) (Appendix B's 3–2–1 angles):
//!
//! ```text
//! home = [yaw, pitch, roll, x, y, z]
//! home = rotation([[r11, r12, r13], [r21, r22, r23], [r31, r32, r33]], [x, y, z])
//! home = quaternion([w, x, y, z], [x, y, z])
//! home = inputs(q1 = 0.2, q2 = -0.1, ...)
//! ```
//!
//! The last gives the joint values instead: the home configuration is then where forward
//! kinematics puts the mechanism for them, solved at compile time from the declared geometry's
//! own configuration (see `model::home_inputs`).

use crate::front::value::{value, Number, Scope};
use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{bracketed, parenthesized, Ident, Result, Token};

fn list(input: ParseStream, scope: &Scope) -> Result<(Vec<Number>, Span)> {
    let inner;
    let bracket = bracketed!(inner in input);
    let mut out = Vec::new();
    while !inner.is_empty() {
        out.push(value(&inner, scope)?);
        if !inner.is_empty() {
            inner.parse::<Token![,]>()?;
        }
    }
    Ok((out, bracket.span.join()))
}

fn three(input: ParseStream, scope: &Scope, what: &str) -> Result<[f64; 3]> {
    let (v, span) = list(input, scope)?;
    v.iter()
        .map(|n| n.value)
        .collect::<Vec<_>>()
        .try_into()
        .map_err(|_| syn::Error::new(span, format!("{what} has three components, `[x, y, z]`")))
}

/// `[yaw, pitch, roll]` of a proper rotation matrix, checked by rebuilding it.
fn euler(r: [[f64; 3]; 3], span: Span) -> Result<[f64; 3]> {
    let pitch = (-r[2][0]).clamp(-1.0, 1.0).asin();
    let (yaw, roll) = if r[2][0].abs() < 1.0 - 1e-12 {
        (r[1][0].atan2(r[0][0]), r[2][1].atan2(r[2][2]))
    } else {
        // Gimbal lock: only yaw ∓ roll is defined; take roll = 0.
        ((-r[0][1]).atan2(r[1][1]), 0.0)
    };
    let back = linkage_geometry::rotation(yaw, pitch, roll);
    let err = (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| (back[i][j] - r[i][j]).abs())
        .fold(0.0f64, f64::max);
    if !(err <= 1e-6) {
        return Err(syn::Error::new(
            span,
            "`home`'s rotation is not a proper rotation matrix (orthonormal, determinant +1) to 1e-6",
        ));
    }
    Ok([yaw, pitch, roll])
}

/// A declared `home`: a pose, or the joint values.
pub enum Home {
    Pose([f64; 6]),
    /// `inputs(name = value, ...)`, in the order written.
    Inputs(Vec<(Ident, Number)>),
}

pub fn parse(input: ParseStream, scope: &Scope) -> Result<Home> {
    if input.peek(Ident) && input.peek2(syn::token::Paren) {
        let fork = input.fork();
        let form: Ident = fork.parse()?;
        if form == "inputs" {
            input.parse::<Ident>()?;
            let args;
            parenthesized!(args in input);
            let mut values = Vec::new();
            while !args.is_empty() {
                let name: Ident = args.parse()?;
                args.parse::<Token![=]>()?;
                values.push((name, value(&args, scope)?));
                if !args.is_empty() {
                    args.parse::<Token![,]>()?;
                }
            }
            return Ok(Home::Inputs(values));
        }
    }
    pose(input, scope).map(Home::Pose)
}

fn pose(input: ParseStream, scope: &Scope) -> Result<[f64; 6]> {
    if input.peek(syn::token::Bracket) {
        let (v, span) = list(input, scope)?;
        return v
            .iter()
            .map(|n| n.value)
            .collect::<Vec<_>>()
            .try_into()
            .map_err(|_| {
                syn::Error::new(
                    span,
                    "`home` is a pose `[yaw, pitch, roll, x, y, z]` (radians, base-frame units), `rotation([[..], [..], [..]], [x, y, z])`, `quaternion([w, x, y, z], [x, y, z])` or the joint values `inputs(q1 = .., ...)`",
                )
            });
    }
    let form: Ident = input.parse()?;
    let args;
    parenthesized!(args in input);
    let (r, t) = match form.to_string().as_str() {
        "rotation" => {
            let rows;
            let bracket = bracketed!(rows in args);
            let mut r = Vec::new();
            while !rows.is_empty() {
                r.push(three(&rows, scope, "a row of `rotation`")?);
                if !rows.is_empty() {
                    rows.parse::<Token![,]>()?;
                }
            }
            let r: [[f64; 3]; 3] = r.try_into().map_err(|_| {
                syn::Error::new(bracket.span.join(), "`rotation` takes three rows")
            })?;
            args.parse::<Token![,]>()?;
            let t = three(&args, scope, "the translation")?;
            (euler(r, bracket.span.join())?, t)
        }
        "quaternion" => {
            let (q, span) = list(&args, scope)?;
            let [w, x, y, z]: [f64; 4] = q
                .iter()
                .map(|n| n.value)
                .collect::<Vec<_>>()
                .try_into()
                .map_err(|_| syn::Error::new(span, "`quaternion` is `[w, x, y, z]`"))?;
            let norm = (w * w + x * x + y * y + z * z).sqrt();
            if !((norm - 1.0).abs() <= 1e-6) {
                return Err(syn::Error::new(
                    span,
                    format!("`quaternion` is a unit quaternion; this one has norm {norm}"),
                ));
            }
            let r = [
                [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
                [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
                [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
            ];
            args.parse::<Token![,]>()?;
            let t = three(&args, scope, "the translation")?;
            (euler(r, span)?, t)
        }
        other => {
            return Err(syn::Error::new(
                form.span(),
                format!("unknown form of `home`: `{other}`; expected `[yaw, pitch, roll, x, y, z]`, `rotation(...)`, `quaternion(...)` or `inputs(q1 = .., ...)`"),
            ))
        }
    };
    if !args.is_empty() {
        return Err(args.error("unexpected tokens after the translation"));
    }
    Ok([r[0], r[1], r[2], t[0], t[1], t[2]])
}
