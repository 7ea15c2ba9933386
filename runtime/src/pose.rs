//! Poses of the moving platform and their relation to the unknowns v.

use crate::math::{asin, atan2, cos, cross3, dot3, norm3, scale3, sin, sub3};
use crate::mechanism::Mechanism;
use linkage_geometry::least_rotation;

/// A rigid transformation: `p_base = rotation · p_platform + translation`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The platform's axes in the base frame (columns), row-major: `rotation[i][j]` is R_ij.
    pub rotation: [[f64; 3]; 3],
    /// The platform origin in the base frame.
    pub translation: [f64; 3],
}

impl Pose {
    /// `R = Rz(yaw) · Ry(pitch) · Rx(roll)` (the 3–2–1 Euler angles of Appendix B, Eq. A2 as
    /// corrected in ERRATA.md), radians; `translation` the platform origin in the base frame.
    pub fn from_euler(yaw: f64, pitch: f64, roll: f64, translation: [f64; 3]) -> Pose {
        let (cy, sy) = (cos(yaw), sin(yaw));
        let (cp, sp) = (cos(pitch), sin(pitch));
        let (cr, sr) = (cos(roll), sin(roll));
        Pose {
            rotation: [
                [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                [-sp, cp * sr, cp * cr],
            ],
            translation,
        }
    }

    /// `[yaw, pitch, roll]` with pitch in [−π/2, π/2].
    pub fn euler(&self) -> [f64; 3] {
        let r = &self.rotation;
        let pitch = asin((-r[2][0]).clamp(-1.0, 1.0));
        let roll = atan2(r[2][1], r[2][2]);
        let yaw = atan2(r[1][0], r[0][0]);
        [yaw, pitch, roll]
    }

    /// A platform-frame point in the base frame.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let r = &self.rotation;
        let t = self.translation;
        [0, 1, 2].map(|i| r[i][0] * p[0] + r[i][1] * p[1] + r[i][2] * p[2] + t[i])
    }

    /// The rigid motion that takes three non-collinear points from `from` to `to` (exactly for
    /// the first point, the direction to the second and the plane of the third; the best fit
    /// when the points have moved other than rigidly). `None` if either triple is collinear or
    /// not finite.
    ///
    /// ```
    /// use linkage::Pose;
    /// let from = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    /// let motion = Pose::from_euler(0.4, 0.0, 0.0, [5.0, 0.0, 1.0]);
    /// let to = from.map(|p| motion.apply(p));
    /// let back = Pose::between(from, to).unwrap();
    /// assert!((back.euler()[0] - 0.4).abs() < 1e-12 && (back.translation[0] - 5.0).abs() < 1e-12);
    /// ```
    pub fn between(from: [[f64; 3]; 3], to: [[f64; 3]; 3]) -> Option<Pose> {
        let world = triad(to)?;
        let local = triad(from)?;
        // R = W Lᵀ with W, L holding the triads as columns.
        let mut r = [[0.0; 3]; 3];
        for (i, row) in r.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = (0..3).map(|c| world[c][i] * local[c][j]).sum();
            }
        }
        let l0 = from[0];
        let rl = [0, 1, 2].map(|i| r[i][0] * l0[0] + r[i][1] * l0[1] + r[i][2] * l0[2]);
        let pose = Pose {
            rotation: r,
            translation: sub3(to[0], rl),
        };
        pose.translation
            .iter()
            .chain(r.iter().flatten())
            .all(|x| x.is_finite())
            .then_some(pose)
    }

    /// `det R`: +1 for a proper rotation, −1 for a mirror image.
    pub fn handedness(&self) -> f64 {
        let r = &self.rotation;
        dot3(
            r.map(|row| row[0]),
            cross3(r.map(|row| row[1]), r.map(|row| row[2])),
        )
    }
}

/// An orthonormal frame from three non-collinear points: columns e1 along p1→p2, e3 normal.
fn triad(p: [[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let a = sub3(p[1], p[0]);
    let na = norm3(a);
    let n = cross3(a, sub3(p[2], p[0]));
    let nn = norm3(n);
    if !(na > 0.0 && nn > 0.0) {
        return None;
    }
    let e1 = scale3(1.0 / na, a);
    let e3 = scale3(1.0 / nn, n);
    let e2 = cross3(e3, e1);
    Some([e1, e2, e3])
}

fn point<const N: usize>(v: &[f64; N], points: usize, p: usize) -> [f64; 3] {
    [v[p], v[points + p], v[2 * points + p]]
}

/// The platform pivots that place the platform (indices into [`Mechanism::POINTS`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PlatformPivots {
    /// Three non-collinear pivots ([`Mechanism::FRAME`]).
    Frame([usize; 3]),
    /// A line through the first pivot and this one, the farthest from it in the platform's
    /// frame (the best-conditioned direction; every other pivot is on the line).
    Line(usize),
    /// One point (the first pivot; any others coincide with it).
    Point,
}

/// How the platform is placed: the generator gives a platform without a frame of three
/// non-collinear pivots one pivot three times over.
pub(crate) fn platform_pivots<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
) -> PlatformPivots {
    let f = S::FRAME;
    if f[0] != f[1] {
        return PlatformPivots::Frame(f);
    }
    let far = linkage_geometry::farthest_from_first(S::POINTS.len(), |p| sys.point_local(p));
    if far == 0 {
        PlatformPivots::Point
    } else {
        PlatformPivots::Line(far)
    }
}

/// The platform pose that places its frame pivots where `v` has them. `None` if they are
/// collinear or not finite.
///
/// A platform of one pivot (a five-bar's output) or of pivots on one line (a linear
/// pentapod's tool axis) has no frame: nothing fixes its spin about the line. Its pose is the
/// one that puts its first pivot where `v` has it and turns the line from its direction in the
/// platform's frame to its direction in `v` by the least rotation
/// ([`linkage_geometry::least_rotation`], a half turn where the two are opposite; the identity
/// for a point): the rotation's spin about the line is this convention's, not the machine's,
/// while every pivot of the platform lands where `v` has it. The declared `home` pose of such a
/// platform is read the same way.
///
/// ```
/// use linkage::{pose_from_unknowns, unknowns_from_pose, Pose};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// let pose = Pose::from_euler(0.1, -0.05, 0.02, [1.0, 2.0, 140.0]);
/// let v = unknowns_from_pose(&rps, &pose);
/// let back = pose_from_unknowns(&rps, &v).unwrap();
/// assert!((back.euler()[0] - 0.1).abs() < 1e-12 && (back.translation[2] - 140.0).abs() < 1e-12);
/// ```
pub fn pose_from_unknowns<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
) -> Option<Pose> {
    let k = S::POINTS.len();
    let far = match platform_pivots(sys) {
        PlatformPivots::Frame(f) => {
            return Pose::between(f.map(|i| sys.point_local(i)), f.map(|i| point(v, k, i)));
        }
        PlatformPivots::Line(far) => far,
        PlatformPivots::Point => 0,
    };
    let local = |p: usize| sys.point_local(p);
    let (along, placed) = (
        sub3(local(far), local(0)),
        sub3(point(v, k, far), point(v, k, 0)),
    );
    // A line whose pivots `v` puts on one point (or nowhere) has no direction to turn to.
    let length = norm3(placed);
    if norm3(along) > 0.0 && !(length > 0.0 && length.is_finite()) {
        return None;
    }
    let rotation = least_rotation(along, placed);
    let turned = Pose {
        rotation,
        translation: [0.0; 3],
    }
    .apply(local(0));
    let pose = Pose {
        rotation,
        translation: sub3(point(v, k, 0), turned),
    };
    pose.translation
        .iter()
        .chain(rotation.iter().flatten())
        .all(|x| x.is_finite())
        .then_some(pose)
}

/// The unknowns v of the platform at `pose` (Eq. A1).
pub fn unknowns_from_pose<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    pose: &Pose,
) -> [f64; N] {
    let k = S::POINTS.len();
    let mut v = [0.0; N];
    for p in 0..k {
        let q = pose.apply(sys.point_local(p));
        for (axis, value) in q.iter().enumerate() {
            if axis * k + p < N {
                v[axis * k + p] = *value;
            }
        }
    }
    v
}
