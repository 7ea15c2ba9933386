//! Helpers the generated code calls. Not public API: names and signatures may change.

use crate::error::GeometryError;

#[inline(always)]
pub fn sq(x: f64) -> f64 {
    x * x
}

pub use crate::dispatch::prefer_x86_64_v3;
pub use crate::inverse::{
    Plan as InversePlan, closed_form_places, platform_in_shape, platform_keeps_its_distances,
    solve as numerical_inverse,
};
pub use crate::lu::{fallback_factor, fallback_solve};
pub use crate::math::{cos, sin};

pub use linkage_geometry::{
    along, axis_frame, collinear_coefficients, distance, normal_point, place,
    prismatic_rod_inverse, revolute_rod_inverse, rigid_coefficients, turn_reference_ok,
};

pub use linkage_geometry::{formula, recipe};

/// The derived constants of a generated `from_geometry`: its recipe table evaluated on the slots
/// `g` (one interpreter for every mechanism, rather than code emitted per constant).
pub fn derive_constants(
    recipes: &recipe::Recipes<'_>,
    g: &[f64],
    auto: &mut [[f64; 3]],
    out: &mut [f64],
) -> Result<(), GeometryError> {
    recipes.derive(g, auto, out).map_err(|e| e.error)?;
    // Finite values whose squares overflow (a platform of 1e200 mm: the squared distances
    // between its pivots): say so rather than build equations of infinities.
    if out.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(GeometryError::Overflow)
    }
}

/// The checks of a generated `from_geometry` on its values `g` (named `names`, the formulas'
/// slots already computed): every value finite — one set directly named first, since a
/// formula of a NaN parameter is NaN too and the parameter is what to set; then a formula's
/// slot, named with the parameter it follows (`sqrt` of a parameter set negative) — and every
/// square finite (the equations are of degree 2 in the geometry as well: a rod of 1e300 was
/// accepted, and every solve from it then failed).
/// Refuses a geometry whose compile-time-only parameters (`slots`) differ from their declared
/// values: nothing reads them, so a calibration of one would be silently ignored.
pub fn check_compile_time(
    names: &[&'static str],
    slots: &[usize],
    g: &[f64],
    declared: &[f64],
) -> Result<(), GeometryError> {
    for &k in slots {
        if g.get(k) != declared.get(k) {
            let name = names.get(k).copied().unwrap_or("");
            return Err(GeometryError::CompileTimeOnly { name });
        }
    }
    Ok(())
}

/// [`linkage_geometry::check_axis`] on every pair axis, given by the geometry slots of its two
/// points.
pub fn check_axes(g: &[f64], axes: &[[[usize; 3]; 2]]) -> Result<(), GeometryError> {
    let point = |s: [usize; 3]| s.map(|k| g.get(k).copied().unwrap_or(f64::NAN));
    axes.iter()
        .try_for_each(|[a, b]| linkage_geometry::check_axis(point(*a), point(*b)))
}

pub fn check_values(
    names: &[&'static str],
    followed: &[(&'static str, &'static str)],
    g: &[f64],
) -> Result<(), GeometryError> {
    let follows = |k: usize| {
        names
            .get(k)
            .and_then(|n| followed.iter().find(|(f, _)| f == n))
    };
    for (k, x) in g.iter().enumerate() {
        if !x.is_finite() && follows(k).is_none() {
            let name = names.get(k).copied().unwrap_or("");
            return Err(GeometryError::NonFinite { name });
        }
    }
    for (k, x) in g.iter().enumerate() {
        if !x.is_finite()
            && let Some(&(name, parameter)) = follows(k)
        {
            return Err(GeometryError::FormulaNotFinite { name, parameter });
        }
    }
    if g.iter().all(|x| (x * x).is_finite()) {
        Ok(())
    } else {
        Err(GeometryError::Overflow)
    }
}

/// Why the name `is` picks out has no geometry slot: it follows a parameter (`followed`:
/// name, parameter), or no such name was declared.
fn missing(followed: &[(&'static str, &'static str)], is: impl Fn(&str) -> bool) -> GeometryError {
    followed
        .iter()
        .find(|(n, _)| is(n))
        .map_or(GeometryError::UnknownName, |&(name, parameter)| {
            GeometryError::FollowsParameter { name, parameter }
        })
}

pub fn set_named(
    names: &[&str],
    followed: &[(&'static str, &'static str)],
    g: &mut [f64],
    name: &str,
    value: f64,
) -> Result<(), GeometryError> {
    // A name that follows a parameter (a formula's slot has a name of its own) is refused
    // first: `from_geometry` would overwrite it.
    if followed.iter().any(|(n, _)| *n == name) {
        return Err(missing(followed, |n| n == name));
    }
    let i = names
        .iter()
        .position(|n| *n == name)
        .ok_or_else(|| missing(followed, |n| n == name))?;
    g[i] = value;
    Ok(())
}

pub fn set_pivot(
    names: &[&str],
    followed: &[(&'static str, &'static str)],
    g: &mut [f64],
    link: &str,
    pivot: &str,
    p: [f64; 3],
) -> Result<(), GeometryError> {
    let named = |n: &str, axis: &str| {
        n.strip_prefix(link)
            .and_then(|r| r.strip_prefix('.'))
            .and_then(|r| r.strip_prefix(pivot))
            .and_then(|r| r.strip_prefix('.'))
            == Some(axis)
    };
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        if followed.iter().any(|(n, _)| named(n, axis)) {
            return Err(missing(followed, |n| named(n, axis)));
        }
        let i = names
            .iter()
            .position(|n| named(n, axis))
            .ok_or_else(|| missing(followed, |n| named(n, axis)))?;
        g[i] = p[k];
    }
    Ok(())
}

/// The larger of `worst` and |g| / ‖∇g‖ (`grad_sq` = ‖∇g‖²): to first order the distance from
/// v to the surface g = 0, a length. NaN, or g ≠ 0 where ∇g = 0, is infinitely far.
pub fn dependent_worst(worst: f64, g: f64, grad_sq: f64) -> f64 {
    let off = if g == 0.0 {
        0.0
    } else {
        g.abs() / crate::math::sqrt(grad_sq)
    };
    if off.is_nan() {
        f64::INFINITY
    } else {
        worst.max(off)
    }
}
