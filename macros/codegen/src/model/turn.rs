//! How an active pair that turns moves a point of the link after it (Table I's active column):
//! about the axis by θ, and for a helical pair along it by the lead's share of the turn. One
//! home for the README's conventions, used by the closed-form shapes and the general model.

use crate::expr::{self, Expr, Vec3};

/// `o + u cos θ + w sin θ`: the point turned by θ about the axis, where `o` is its foot on the
/// axis, `u` the point less `o` at home and `w` the axis' unit vector × `u` (right-handed).
pub fn turned(o: &Vec3, u: &Vec3, w: &Vec3, th: &Expr) -> Vec3 {
    let cos = Expr::Cos(Box::new(th.clone()));
    let sin = Expr::Sin(Box::new(th.clone()));
    expr::vadd(
        o,
        &expr::vadd(&expr::vscale(&cos, u), &expr::vscale(&sin, w)),
    )
}

/// The slide of a helical pair of `lead` (per turn) turned by θ: `lead · θ / 2π`.
pub fn helical_rise(lead: Expr, th: Expr) -> Expr {
    Expr::Product(vec![
        Expr::Num(1.0 / (2.0 * std::f64::consts::PI)),
        lead,
        th,
    ])
    .simplify()
}
