//! Geometry kernels shared by the `mechanism!` generator, which evaluates them at compile time
//! on the declared geometry, and by the `linkage` runtime, which evaluates them whenever the
//! geometry changes. One implementation, so both agree to the last bit.

#![no_std]
#![forbid(unsafe_code)]

pub mod formula;
pub mod math;
pub mod recipe;

use core::f64::consts::PI;
use core::fmt;
use math::{acos, atan2, cross3, dot3, norm3, scale3, sqrt, sub3};

/// A geometry that cannot define the mechanism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeometryError {
    /// A geometry value is NaN or infinite.
    NonFinite { name: &'static str },
    /// No geometry value or pivot has this name.
    UnknownName,
    /// The values are finite, but their squares or constants derived from them (squared
    /// distances) overflow: the geometry is too large to compute with in f64.
    Overflow,
    /// The geometry value `name` (a pivot coordinate or a length) was declared as the
    /// parameter `parameter` and follows it: set the parameter instead.
    FollowsParameter {
        name: &'static str,
        parameter: &'static str,
    },
    /// The platform's three frame pivots are (nearly) collinear.
    CollinearFrame,
    /// A platform pivot left the plane of the frame, but the system was generated in the
    /// coplanar form of Eq. 16; declare the platform with `form = general`.
    NotCoplanar,
    /// A pivot declared on the line of two others (on a prismatic pair's axis, or on a link
    /// whose pivots all lie on one line) left it: the equations place it on that line.
    NotCollinear,
    /// A pair's axis is given by (nearly) coincident points.
    DegenerateAxis,
    /// A link's length is zero or negative.
    NonPositiveLength { name: &'static str },
    /// The parameter `name` is read only at compile time — in `home`, or in another
    /// parameter's value (evaluated where it is declared) — or not at all: nothing the
    /// mechanism evaluates depends on it, so it keeps its declared value.
    CompileTimeOnly { name: &'static str },
    /// The geometry value `name`, declared as arithmetic on the parameters (the first it
    /// reads: `parameter`), is not finite at their values: a square root of a negative, an
    /// `asin` or `acos` out of [−1, 1], a division by zero.
    FormulaNotFinite {
        name: &'static str,
        parameter: &'static str,
    },
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GeometryError::NonFinite { name } => write!(f, "geometry value `{name}` is not finite"),
            GeometryError::UnknownName => write!(f, "no geometry value or pivot has that name"),
            GeometryError::Overflow => write!(
                f,
                "the geometry is too large: its squares or constants derived from it overflow"
            ),
            GeometryError::FollowsParameter { name, parameter } => write!(
                f,
                "{name} follows the parameter {parameter}: set the parameter instead"
            ),
            GeometryError::CollinearFrame => write!(f, "the platform's frame pivots are collinear"),
            GeometryError::NotCoplanar => write!(
                f,
                "a platform pivot is off the frame's plane but the system uses the coplanar form"
            ),
            GeometryError::NotCollinear => write!(
                f,
                "a pivot declared on the line of two others (a prismatic axis) is off it"
            ),
            GeometryError::DegenerateAxis => write!(f, "a pair axis is given by coincident points"),
            GeometryError::CompileTimeOnly { name } => write!(
                f,
                "the parameter `{name}` is used only at compile time (in `home` or another parameter's value) or not at all: changing it would change nothing"
            ),
            GeometryError::FormulaNotFinite { name, parameter } => write!(
                f,
                "{name}, declared from the parameter {parameter}, is not finite at the parameters' values"
            ),
            GeometryError::NonPositiveLength { name } => {
                write!(
                    f,
                    "geometry value `{name}` is a link's length and must be positive"
                )
            }
        }
    }
}

#[cfg(feature = "std")]
extern crate std;

#[cfg(feature = "std")]
impl std::error::Error for GeometryError {}

#[inline(always)]
pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm3(sub3(a, b))
}

/// Coefficients `[a, b, c, d]` with `q = a p1 + b p2 + c p3 + d (p2 − p1) × (p3 − p1)` and
/// `a + b + c = 1` (Eq. 17 for coplanar points, where d = 0).
pub fn rigid_coefficients(
    frame: [[f64; 3]; 3],
    q: [f64; 3],
    coplanar: bool,
) -> Result<[f64; 4], GeometryError> {
    let [p1, p2, p3] = frame;
    // In a unit near the frame's size, so that no product of four coordinates overflows or
    // underflows (a platform of 1e80 mm is not collinear). The unit is a power of two: the
    // scaling is exact, and the results are those of the unscaled computation wherever that
    // one neither overflows nor underflows; a, b and c do not depend on the unit, and d (a
    // length⁻¹) is scaled back at the end.
    // The largest coordinate difference, not a Euclidean length: its squares would overflow
    // at 1e200 and underflow at 1e-200, and a frame of either size is not collinear.
    let size = sub3(p2, p1)
        .into_iter()
        .chain(sub3(p3, p1))
        .fold(0.0f64, |m, c| m.max(c.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return Err(GeometryError::CollinearFrame);
    }
    let exponent = (((size.to_bits() >> 52) & 0x7ff) as i64 - 1023).clamp(-1022, 1022);
    let inverse_unit = f64::from_bits(((1023 - exponent) as u64) << 52);
    let unit = |v: [f64; 3]| scale3(inverse_unit, v);
    let e1 = unit(sub3(p2, p1));
    let e2 = unit(sub3(p3, p1));
    let n = cross3(e1, e2);
    let nn = dot3(n, n);
    let scale = norm3(e1).max(norm3(e2));
    if !(nn > 1e-18 * scale * scale * scale * scale) {
        return Err(GeometryError::CollinearFrame);
    }
    let r = unit(sub3(q, p1));
    let d = dot3(r, n) / nn;
    if coplanar && (d * sqrt(nn)).abs() > 1e-9 * scale.max(norm3(r)) {
        return Err(GeometryError::NotCoplanar);
    }
    let (g11, g12, g22) = (dot3(e1, e1), dot3(e1, e2), dot3(e2, e2));
    let (r1, r2) = (dot3(r, e1), dot3(r, e2));
    // The Gram determinant g11 g22 − g12² equals ‖n‖² (Lagrange's identity).
    let b = (g22 * r1 - g12 * r2) / nn;
    let c = (g11 * r2 - g12 * r1) / nn;
    Ok([
        1.0 - b - c,
        b,
        c,
        if coplanar { 0.0 } else { d * inverse_unit },
    ])
}

/// Coefficients `[a, b]` with `q = a p1 + b p2` and `a + b = 1`: the collinear case of Eq. 3.
/// `q` must lie on the line (relative tolerance 1e-9).
pub fn collinear_coefficients(line: [[f64; 3]; 2], q: [f64; 3]) -> Result<[f64; 2], GeometryError> {
    let [p1, p2] = line;
    let e = sub3(p2, p1);
    let ee = dot3(e, e);
    let r = sub3(q, p1);
    let scale = sqrt(ee).max(norm3(r));
    if !(ee > 1e-24 * scale * scale) {
        return Err(GeometryError::CollinearFrame);
    }
    let b = dot3(r, e) / ee;
    let off = norm3(cross3(r, e)) / sqrt(ee);
    if !(off <= 1e-9 * scale) {
        // Off its line, not off a plane (a SCARA's quill axis tilted by moving one of its
        // points was refused as `NotCoplanar`, which names the platform's plane).
        return Err(GeometryError::NotCollinear);
    }
    Ok([1.0 - b, b])
}

/// Whether the axis `a → b` of a pair is given by (nearly) coincident points: closer than 1e-9
/// of their size (at least one length unit), or not finite. The one rule for a declared axis
/// (at compile time) and a run-time one, and for the axes the closed forms turn about.
pub fn check_axis(a: [f64; 3], b: [f64; 3]) -> Result<(), GeometryError> {
    let len = norm3(sub3(b, a));
    if len > 1e-9 * norm3(a).max(norm3(b)).max(1.0) && len.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::DegenerateAxis)
    }
}

/// `origin + unit(toward − origin)`: a point one length unit along a direction, for the axis of a
/// prismatic pair on a moving link.
pub fn along(origin: [f64; 3], toward: [f64; 3]) -> Result<[f64; 3], GeometryError> {
    lever(origin, toward, 1.0)
}

/// `origin + length · unit(toward − origin)`: a point `length` along the axis `origin → toward`,
/// for a revolute pair's axis declared by pivots far closer together than the mechanism is large
/// (see the general model's `levers`).
pub fn lever(origin: [f64; 3], toward: [f64; 3], length: f64) -> Result<[f64; 3], GeometryError> {
    check_axis(origin, toward)?;
    let d = sub3(toward, origin);
    let len = norm3(d);
    Ok([0, 1, 2].map(|k| origin[k] + d[k] / len * length))
}

/// `origin + |b1 − b0| unit((a1 − a0) × (b1 − b0))`: a point along the common normal of two
/// directions, as far from `origin` as `b1` is from `b0` (the leg's length), for the second
/// axis of a universal joint. At one length unit (it was) that axis was a lever of 1 mm beside
/// legs of hundreds, and every bound that depends on the unknowns' scale suffered: a 3-PUU's
/// Krawczyk radius at home was 5.5e-5 mm (8.3e-3 with the leg's length), and its certified
/// tracker refused every sample with the rails' axis points 100 mm apart (none refused now).
pub fn normal_point(
    origin: [f64; 3],
    a: [[f64; 3]; 2],
    b: [[f64; 3]; 2],
) -> Result<[f64; 3], GeometryError> {
    let (da, db) = (sub3(a[1], a[0]), sub3(b[1], b[0]));
    let n = cross3(da, db);
    let len = norm3(n);
    if !(len > 1e-9 * norm3(da) * norm3(db)) || !len.is_finite() {
        return Err(GeometryError::DegenerateAxis);
    }
    let lever = norm3(db);
    Ok([0, 1, 2].map(|k| origin[k] + n[k] / len * lever))
}

/// `R p + t` for the pose `[yaw, pitch, roll, x, y, z]`, R = Rz(yaw)·Ry(pitch)·Rx(roll): a
/// platform pivot placed at a declared home pose.
pub fn place(pose: [f64; 6], p: [f64; 3]) -> [f64; 3] {
    let r = rotation(pose[0], pose[1], pose[2]);
    [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + pose[3 + i])
}

/// Rz(yaw)·Ry(pitch)·Rx(roll) (the 3–2–1 Euler angles of Appendix B).
pub fn rotation(yaw: f64, pitch: f64, roll: f64) -> [[f64; 3]; 3] {
    let (cy, sy) = (math::cos(yaw), math::sin(yaw));
    let (cp, sp) = (math::cos(pitch), math::sin(pitch));
    let (cr, sr) = (math::cos(roll), math::sin(roll));
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// Of `count` points (`point(i)` the i-th), the index of the one farthest from the first (the
/// last of equals): with the first, the best-conditioned pair to take a line's direction from
/// (0 if they all coincide, or there are fewer than two). The generator's collinear pivots, a
/// line platform's pose at compile time and at run time all take it.
pub fn farthest_from_first(count: usize, point: impl Fn(usize) -> [f64; 3]) -> usize {
    if count == 0 {
        return 0;
    }
    let first = point(0);
    let from_first = |p: usize| norm3(sub3(point(p), first));
    (1..count).fold(0, |best, p| {
        let d = from_first(p);
        if d >= from_first(best) && d > 0.0 {
            p
        } else {
            best
        }
    })
}

/// The rotation of least angle that turns the direction `from` into the direction `to` (neither
/// need be a unit vector): about `from × to`, or a half turn about an axis square to `from`
/// where the two are opposite. The convention that places a line platform, whose spin about
/// itself no pair fixes, at compile time and at run time alike. The identity if either is zero
/// or not finite.
///
/// ```
/// let r = linkage_geometry::least_rotation([2.0, 0.0, 0.0], [0.0, 0.0, 3.0]);
/// let turned = [0, 1, 2].map(|i| r[i][0]);
/// assert!((turned[2] - 1.0).abs() < 1e-15 && r[1][1] == 1.0);
/// ```
pub fn least_rotation(from: [f64; 3], to: [f64; 3]) -> [[f64; 3]; 3] {
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (na, nb) = (norm3(from), norm3(to));
    if !(na > 0.0 && nb > 0.0 && na.is_finite() && nb.is_finite()) {
        return identity;
    }
    let (a, b) = (scale3(1.0 / na, from), scale3(1.0 / nb, to));
    // The axis from a × b = a × (a + b): where b is nearly −a, a + b is exact (each component
    // a difference within a factor of two) and so is the axis to full relative accuracy, which
    // a · b and a × b alone lose as the turn nears π (Rodrigues' 1 / (1 + cos θ) put a turn of
    // π − 1e-6 4e-10 off its target, and one of π − 1e-12 off a rotation altogether).
    let w = cross3(a, [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
    let (sin, cos) = (norm3(w), dot3(a, b));
    let r = sqrt(sin * sin + cos * cos);
    let n = if sin > 0.0 {
        scale3(1.0 / sin, w)
    } else if cos > 0.0 {
        return identity;
    } else {
        // Opposite: a half turn about the unit axis square to `a` made with the coordinate
        // axis least along it.
        let k = (0..3).fold(0, |k, i| if a[i].abs() < a[k].abs() { i } else { k });
        let mut e = [0.0; 3];
        e[k] = 1.0;
        let n = cross3(a, e);
        scale3(1.0 / norm3(n), n)
    };
    // R = cos θ I + sin θ [n]× + (1 − cos θ) n nᵀ, with cos² θ + sin² θ = 1 to rounding.
    let (c, s) = (cos / r, sin / r);
    let nx = [[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]];
    [0, 1, 2]
        .map(|i| [0, 1, 2].map(|j| c * identity[i][j] + s * nx[i][j] + (1.0 - c) * n[i] * n[j]))
}

/// `[e, o, u, w]` for rotating `q` about the axis `a → b`: e the unit axis, o the foot of q on
/// the axis, u = q − o the arm and w = e × u, so that Eq. 2 gives `o + u cos θ + w sin θ`.
pub fn axis_frame(a: [f64; 3], b: [f64; 3], q: [f64; 3]) -> Result<[f64; 12], GeometryError> {
    check_axis(a, b)?;
    let d = sub3(b, a);
    let len = norm3(d);
    let e = [d[0] / len, d[1] / len, d[2] / len];
    let r = sub3(q, a);
    let t = dot3(e, r);
    let o = [a[0] + t * e[0], a[1] + t * e[1], a[2] + t * e[2]];
    let u = sub3(q, o);
    let w = cross3(e, u);
    Ok([
        e[0], e[1], e[2], o[0], o[1], o[2], u[0], u[1], u[2], w[0], w[1], w[2],
    ])
}

/// The largest reference, in magnitude, near which an angle is returned within half a turn
/// (2¹⁶ rad, about 10 400 turns): there a double still holds an angle to 1.5e-11 rad, a
/// thousandth of the inverse's acceptance at a lever arm of the mechanism's scale. Past it the
/// sum `reference + d` rounds the angle away (at 1e17 rad to a multiple of 16 rad), so that an
/// input "near the reference" would no longer be the angle found.
pub const TURN_REFERENCE_LIMIT: f64 = 65536.0;

/// Whether an angle within half a turn of `reference` is still the angle found (finite and
/// within [`TURN_REFERENCE_LIMIT`]).
pub fn turn_reference_ok(reference: f64) -> bool {
    reference.abs() <= TURN_REFERENCE_LIMIT
}

/// The angle θ nearest `reference` with `‖g − (o + u cos θ + w sin θ)‖ = length`, within half
/// a turn of it (exactly so only for a reference that [`turn_reference_ok`] accepts).
pub fn revolute_rod_inverse(
    g: [f64; 3],
    o: [f64; 3],
    u: [f64; 3],
    w: [f64; 3],
    length: f64,
    reference: f64,
) -> Option<f64> {
    let h = sub3(g, o);
    let a = 2.0 * dot3(h, u);
    let b = 2.0 * dot3(h, w);
    let c = dot3(h, h) + dot3(u, u) - length * length;
    let r = sqrt(a * a + b * b);
    if !(r > 0.0) || !c.is_finite() || c.abs() > r * (1.0 + 1e-12) {
        return None;
    }
    let phi = atan2(b, a);
    let delta = acos((c / r).clamp(-1.0, 1.0));
    let near = |t: f64| {
        let mut d = (t - reference) % (2.0 * PI);
        if d > PI {
            d -= 2.0 * PI;
        } else if d <= -PI {
            d += 2.0 * PI;
        }
        reference + d
    };
    let (t1, t2) = (near(phi + delta), near(phi - delta));
    Some(if (t1 - reference).abs() <= (t2 - reference).abs() {
        t1
    } else {
        t2
    })
}

/// The slide s nearest `reference` with `‖g − (c0 + s e)‖ = length`.
pub fn prismatic_rod_inverse(
    g: [f64; 3],
    c0: [f64; 3],
    e: [f64; 3],
    length: f64,
    reference: f64,
) -> Option<f64> {
    let h = sub3(g, c0);
    let t = dot3(e, h);
    let disc = t * t - dot3(h, h) + length * length;
    if !(disc >= 0.0) {
        return None;
    }
    let (s1, s2) = (t + sqrt(disc), t - sqrt(disc));
    Some(if (s1 - reference).abs() <= (s2 - reference).abs() {
        s1
    } else {
        s2
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use math::{cos, sin};

    /// A proper rotation that takes `a`'s direction to `b`'s, by their angle.
    fn assert_least(a: [f64; 3], b: [f64; 3]) {
        let r = least_rotation(a, b);
        let turned = [0, 1, 2].map(|i| dot3(r[i], a));
        let (ua, ub) = (scale3(1.0 / norm3(a), a), scale3(1.0 / norm3(b), b));
        let gap = norm3(sub3(scale3(1.0 / norm3(turned), turned), ub));
        assert!(gap < 1e-12, "{a:?} -> {b:?}: {gap:e}");
        for i in 0..3 {
            for j in 0..3 {
                let rrt = dot3(r[i], r[j]);
                assert!(
                    (rrt - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12,
                    "{a:?} -> {b:?}: {rrt}"
                );
            }
        }
        let det = dot3(r[0], cross3(r[1], r[2]));
        assert!((det - 1.0).abs() < 1e-12);
        // trace R = 1 + 2 cos θ: no more turn than the angle between them.
        let trace = r[0][0] + r[1][1] + r[2][2];
        assert!((trace - 1.0 - 2.0 * dot3(ua, ub)).abs() < 1e-9, "{trace}");
    }

    /// One rule for every axis: points closer than 1e-9 of their size (at least one unit), or
    /// not finite, give no axis.
    #[test]
    fn an_axis_needs_two_points_apart() {
        let a = [200.0, 0.0, 0.0];
        assert!(check_axis(a, [200.0, 0.0, 1.0]).is_ok());
        assert!(check_axis(a, [200.0, 0.0, 1e-6]).is_ok());
        assert_eq!(
            check_axis(a, [200.0, 0.0, 1e-8]),
            Err(GeometryError::DegenerateAxis)
        );
        assert_eq!(check_axis(a, a), Err(GeometryError::DegenerateAxis));
        // Small mechanisms: at least one unit of size, so 1e-9 apart is always too close.
        assert!(check_axis([0.0; 3], [0.0, 0.0, 1e-9]).is_err());
        assert!(check_axis([0.0; 3], [0.0, 0.0, 2e-9]).is_ok());
        assert!(check_axis(a, [f64::NAN, 0.0, 0.0]).is_err());
        assert!(check_axis(a, [f64::INFINITY, 0.0, 0.0]).is_err());
    }

    /// A lever is `length` along the axis whatever the declared points' spacing, `along` one
    /// unit; both refuse what `check_axis` refuses.
    #[test]
    fn a_lever_is_its_length_along_the_axis() {
        let a = [200.0, 0.0, 0.0];
        let p = lever(a, [200.0, 0.0, 1.0], 346.0).unwrap();
        assert_eq!(p, [200.0, 0.0, 346.0]);
        let q = lever(a, [201.0, 1.0, 0.0], 10.0).unwrap();
        assert!((norm3(sub3(q, a)) - 10.0).abs() < 1e-12 && (q[0] - q[1] - 200.0).abs() < 1e-12);
        assert_eq!(along(a, [200.0, 0.0, 5.0]).unwrap(), [200.0, 0.0, 1.0]);
        assert_eq!(lever(a, a, 10.0), Err(GeometryError::DegenerateAxis));
        assert_eq!(
            along(a, [200.0, 0.0, 1e-8]),
            Err(GeometryError::DegenerateAxis)
        );
    }

    #[test]
    fn least_rotation_turns_by_the_angle_between_and_no_more() {
        let dirs = [
            [1.0, 0.0, 0.0],
            [0.3, -2.0, 0.7],
            [-1e-3, 5.0, 1e3],
            [0.0, 0.0, -4.0],
        ];
        for a in dirs {
            for b in dirs {
                assert_least(a, b);
            }
            // Opposite, and all but opposite.
            assert_least(a, scale3(-1.0, a));
            for d in [1e-6, 1e-12] {
                assert_least(a, [-a[0] + d * norm3(a), -a[1], -a[2]]);
            }
        }
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(least_rotation([0.0; 3], [1.0, 0.0, 0.0]), identity);
        assert_eq!(
            least_rotation([1.0, 0.0, 0.0], [f64::NAN, 0.0, 0.0]),
            identity
        );
    }

    #[test]
    fn rigid_coefficients_reproduce_the_point_and_reject_mirrors() {
        let frame = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 3.0, 0.0]];
        let q = [0.5, 1.0, 2.0];
        let [a, b, c, d] = rigid_coefficients(frame, q, false).unwrap();
        let n = cross3(sub3(frame[1], frame[0]), sub3(frame[2], frame[0]));
        for k in 0..3 {
            let rebuilt = a * frame[0][k] + b * frame[1][k] + c * frame[2][k] + d * n[k];
            assert!((rebuilt - q[k]).abs() < 1e-12);
        }
        assert_eq!(
            rigid_coefficients(frame, q, true),
            Err(GeometryError::NotCoplanar)
        );
        let line = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert_eq!(
            rigid_coefficients(line, q, false),
            Err(GeometryError::CollinearFrame)
        );
    }

    #[test]
    fn rigid_coefficients_do_not_depend_on_the_unit() {
        // The same frame and point from 1e-100 to 1e100: a, b, c the same, d scaled by the
        // unit's inverse (a frame of 1e80 mm was once called collinear: ‖n‖² overflowed).
        let frame = [[1.0, -2.0, 0.5], [3.0, 0.0, 0.0], [0.0, 3.5, 1.0]];
        let q = [0.5, 1.0, 2.0];
        let base = rigid_coefficients(frame, q, false).unwrap();
        for unit in [1e-100, 1e-60, 1e60, 1e80, 1e100] {
            let f = frame.map(|p| scale3(unit, p));
            let [a, b, c, d] = rigid_coefficients(f, scale3(unit, q), false).unwrap();
            for (got, want) in [a, b, c].iter().zip(&base) {
                assert!((got - want).abs() < 1e-12, "{unit:e}");
            }
            assert!((d * unit / base[3] - 1.0).abs() < 1e-12, "{unit:e}");
        }
        let coincident = [[1e80; 3]; 3];
        assert_eq!(
            rigid_coefficients(coincident, q, false),
            Err(GeometryError::CollinearFrame)
        );
    }

    #[test]
    fn revolute_inverse_round_trips() {
        let f = axis_frame([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [30.0, 0.0, 5.0]).unwrap();
        let (o, u, w) = ([f[3], f[4], f[5]], [f[6], f[7], f[8]], [f[9], f[10], f[11]]);
        let th = 0.3;
        let tip = [
            o[0] + u[0] * cos(th) + w[0] * sin(th),
            o[1] + u[1] * cos(th) + w[1] * sin(th),
            o[2] + u[2] * cos(th) + w[2] * sin(th),
        ];
        let g = [tip[0] + 10.0, tip[1] + 40.0, tip[2] + 80.0];
        let l = distance(g, tip);
        let back = revolute_rod_inverse(g, o, u, w, l, 0.25).unwrap();
        assert!((back - th).abs() < 1e-9, "{back}");
    }
}
