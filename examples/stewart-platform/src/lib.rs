//! The general 6-6 Stewart platform of Gao & Wu (2015), Table III: six S–P–S legs.
//!
//! Shared by the examples, the `stewart` CLI and the C interface (`linkage-ffi`); `no_std`
//! so that the C interface needs nothing beyond the runtime.

#![no_std]

use linkage::{GeometryError, Mechanism, Pose, SolveError, Start};

/// Declares a Stewart platform type with Table III's geometry and the given rigid-body form.
macro_rules! stewart {
    ($(#[$doc:meta])* $name:ident, $form:ident) => {
        linkage::mechanism! {
            $(#[$doc])*
            pub struct $name;

            base {
                D1 = [200.764, 53.795, 0.0],
                D2 = [169.706, 0.0, 0.0],
                D3 = [0.0, 0.0, 0.0],
                D4 = [-31.058, 53.795, 0.0],
                D5 = [53.795, 200.764, 0.0],
                D6 = [115.911, 200.764, 0.0],
            }

            platform(frame = [G1, G3, G5], form = $form, home = [0.0, 0.0, 0.0, 58.971, -11.739, 159.011]) {
                G1 = [122.475, 122.475, 0.0],
                G2 = [51.764, 0.0, 0.0],
                G3 = [0.0, 0.0, 0.0],
                G4 = [-70.711, 122.475, 0.0],
                G5 = [-44.829, 167.303, 0.0],
                G6 = [96.593, 167.303, 0.0],
            }

            chain leg1 = base - S(D1) - P(active L1) - S(G1) - platform;
            chain leg2 = base - S(D2) - P(active L2) - S(G2) - platform;
            chain leg3 = base - S(D3) - P(active L3) - S(G3) - platform;
            chain leg4 = base - S(D4) - P(active L4) - S(G4) - platform;
            chain leg5 = base - S(D5) - P(active L5) - S(G5) - platform;
            chain leg6 = base - S(D6) - P(active L6) - S(G6) - platform;
        }
    };
}

stewart!(
    /// Gao & Wu's Stewart platform (Table III) in the coplanar form of Eq. 16: its system is
    /// Eq. 19, with the distance rows squared (see ERRATA.md).
    Stewart,
    coplanar
);

stewart!(
    /// The same platform in the general (mirror-free) rigid-body form, for 6-6 geometries whose
    /// platform pivots are not coplanar.
    StewartGeneral,
    general
);

/// The paper's initial configuration: all legs 170 mm.
pub const HOME_LEGS: [f64; 6] = [170.0; 6];

/// The home assembly mode: no rotation, platform above the base (see ERRATA.md's check value).
pub const HOME_POSE: [f64; 6] = [0.0, 0.0, 0.0, 58.971, -11.739, 159.011];

/// The start configuration for the home legs, refined from the approximate home pose.
pub fn home_start(sys: &Stewart) -> Result<Start<18, 6>, SolveError> {
    let [yaw, pitch, roll, x, y, z] = HOME_POSE;
    let pose = Pose::from_euler(yaw, pitch, roll, [x, y, z]);
    let v = linkage::unknowns_from_pose(sys, &pose);
    Start::new(sys, v, HOME_LEGS)
}

/// Leg lengths for a platform pose (Appendix B, Eqs. A1–A3), with the pivots v.
pub fn legs_for_pose<S: Mechanism<18, 6>>(sys: &S, pose: &Pose) -> Option<([f64; 6], [f64; 18])> {
    let v = linkage::unknowns_from_pose(sys, pose);
    sys.inverse(&v, &HOME_LEGS).ok().map(|x| (x, v))
}

/// A Stewart platform type whose 6 + 6 joint centres can be set at run time.
pub trait SixSix: Mechanism<18, 6> + Clone + Sized {
    fn with_joints(base: &[[f64; 3]; 6], platform: &[[f64; 3]; 6]) -> Result<Self, GeometryError>;
    /// The base joint centres D1…D6 in the base frame.
    fn base_joints(&self) -> [[f64; 3]; 6];
}

/// A generated geometry name, `link.Pn.axis` (as `base.D3.y`): the link, the pivot's index
/// (n − 1, below 6) and the axis's (0, 1, 2). Total: a name of any other shape is `None`,
/// never a panic (the C interface builds its geometry through this).
fn parse_name(name: &str) -> Option<(&str, usize, usize)> {
    let (link, rest) = split_dot(name)?;
    let (pivot, axis) = split_dot(rest).unwrap_or((rest, ""));
    let i = pivot
        .get(1..)?
        .parse::<usize>()
        .ok()?
        .checked_sub(1)
        .filter(|i| *i < 6)?;
    let a = match axis {
        "x" => 0,
        "y" => 1,
        _ => 2,
    };
    Some((link, i, a))
}

/// `s` split at its first '.', which neither part keeps. By hand: `str::split` keeps a bounds
/// check the optimiser cannot remove, and the no-panic proof links this.
fn split_dot(s: &str) -> Option<(&str, &str)> {
    let at = s.bytes().position(|b| b == b'.')?;
    let (head, tail) = s.split_at_checked(at)?;
    Some((head, tail.get(1..)?))
}

macro_rules! six_six {
    ($name:ident) => {
        impl SixSix for $name {
            fn with_joints(
                base: &[[f64; 3]; 6],
                platform: &[[f64; 3]; 6],
            ) -> Result<Self, GeometryError> {
                let mut g = $name::DEFAULT_GEOMETRY;
                for (value, name) in g.iter_mut().zip($name::GEOMETRY_NAMES) {
                    let joint = match parse_name(name) {
                        Some(("base", i, a)) => base.get(i).and_then(|p| p.get(a)),
                        Some(("platform", i, a)) => platform.get(i).and_then(|p| p.get(a)),
                        _ => None,
                    };
                    *value = *joint.ok_or(GeometryError::UnknownName)?;
                }
                $name::from_geometry(g)
            }

            fn base_joints(&self) -> [[f64; 3]; 6] {
                let mut out = [[0.0; 3]; 6];
                for (value, name) in self.geometry().iter().zip($name::GEOMETRY_NAMES) {
                    if let Some(("base", i, a)) = parse_name(name) {
                        if let Some(slot) = out.get_mut(i).and_then(|p| p.get_mut(a)) {
                            *slot = *value;
                        }
                    }
                }
                out
            }
        }
    };
}

six_six!(Stewart);
six_six!(StewartGeneral);

/// Whether the six platform joint centres lie in one plane, to rounding (1e-13 of the
/// platform's size). The coplanar form places every pivot in the frame's plane: a pivot δ off
/// it is moved by δ, and so are the leg lengths of the poses found, so a platform coplanar only
/// to 1e-9 (1.7e-7 mm for Table III's) gave poses 94 times the default tolerance off their
/// legs. Any platform less flat than rounding takes the general form, exact for every one.
pub fn platform_is_coplanar(platform: &[[f64; 3]; 6]) -> bool {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // The best-conditioned triangle defines the plane (kept with its corner, not the corner's
    // index: the C interface's geometry check is proven not to panic).
    let mut best = (0.0, [0.0; 3], [0.0; 3]);
    for i in 0..6 {
        for j in i + 1..6 {
            for k in j + 1..6 {
                let n = cross(sub(platform[j], platform[i]), sub(platform[k], platform[i]));
                // The squared area: no square root in a no_std crate (`f64::sqrt` is std's).
                let a = dot(n, n);
                if a > best.0 {
                    best = (a, n, platform[i]);
                }
            }
        }
    }
    let (area_sq, n, corner) = best;
    if area_sq == 0.0 {
        return false;
    }
    // The platform's own size, not floored at 1 mm: a platform a micrometre across and 1e-9 mm
    // out of plane is not coplanar.
    let size = platform
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    // |n · (p − corner)| / |n| ≤ 1e-13 size, squared.
    let bound = 1e-13 * size;
    platform.iter().all(|p| {
        let d = dot(n, sub(*p, corner));
        d * d <= bound * bound * area_sq
    })
}

/// Why no start configuration could be found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StartError {
    /// The start legs or pose are invalid.
    Solve(SolveError),
    /// No assembly mode with the platform above the base was found for the start legs.
    NoAssemblyMode,
    /// ∂F/∂v was singular at every configuration tried: the geometry looks
    /// architecture-singular (two legs on the same base and platform joints, for one), so that
    /// no configuration is regular.
    SingularEverywhere,
    /// The given start pose does not satisfy the start legs.
    PoseMismatch,
}

impl core::fmt::Display for StartError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            StartError::Solve(e) => write!(f, "{e}"),
            StartError::NoAssemblyMode => write!(f, "no assembly mode with the platform above the base was found for the start legs"),
            StartError::PoseMismatch => write!(f, "the start pose does not match the start legs (an error above 1 % of the platform size)"),
            StartError::SingularEverywhere => write!(f, "the Jacobian ∂F/∂v is singular at every configuration tried: the geometry looks architecture-singular (two legs on the same base and platform joints, for one)"),
        }
    }
}

/// Why [`polish`] failed.
#[derive(Clone, Copy, PartialEq)]
enum Unpolished {
    /// B was singular (or not finite) at an iterate.
    Singular,
    /// The iterates overflowed or did not settle.
    Diverged,
}

/// Polishes a guess `v` for legs `x` by Newton's method (no branch guarantee: a guess, which
/// `Start::new` then checks).
fn polish<S: Mechanism<18, 6>>(
    sys: &S,
    v: [f64; 18],
    x: &[f64; 6],
) -> Result<[f64; 18], Unpolished> {
    let mut v = v;
    // Relative to the configuration's own size (1 only where it is 0).
    let scale = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let mut fac = sys.new_factor();
    for _ in 0..60 {
        let mut f = [0.0; 18];
        sys.residual(&v, x, &mut f);
        sys.factor(&v, x, &mut fac).ok_or(Unpolished::Singular)?;
        sys.solve(&fac, &mut f);
        let size = f.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        if !size.is_finite() {
            return Err(Unpolished::Diverged);
        }
        for i in 0..18 {
            v[i] -= f[i];
        }
        if size <= 1e-12 * scale {
            return Ok(v);
        }
    }
    Err(Unpolished::Diverged)
}

/// The start configuration for legs `x`: at `pose` if given (it must match the legs), else
/// the assembly mode with the platform above the base that is least tilted.
pub fn find_start<S: SixSix>(
    sys: &S,
    x: [f64; 6],
    pose: Option<Pose>,
) -> Result<Start<18, 6>, StartError> {
    sys.validate_inputs(&x)
        .map_err(|input| StartError::Solve(SolveError::InvalidInput { input }))?;
    let scale = (0..6)
        .flat_map(|p| sys.point_local(p))
        .fold(0.0f64, |m, c| m.max(c.abs()));
    if let Some(pose) = pose {
        let guess = linkage::unknowns_from_pose(sys, &pose);
        // The pose as given, if it is (nearly) exact: a singular start is reported as such.
        match Start::new(sys, guess, x) {
            Err(SolveError::InconsistentStart { .. }) => {}
            other => return other.map_err(StartError::Solve),
        }
        let v = polish(sys, guess, &x).map_err(|_| StartError::PoseMismatch)?;
        let moved = v
            .iter()
            .zip(&guess)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        if moved > 0.01 * scale {
            return Err(StartError::PoseMismatch);
        }
        return Start::new(sys, v, x).map_err(StartError::Solve);
    }
    let mean = x.iter().sum::<f64>() / 6.0;
    let base = sys.base_joints();
    let base_c = base.iter().fold([0.0; 3], |a, p| {
        [a[0] + p[0] / 6.0, a[1] + p[1] / 6.0, a[2] + p[2] / 6.0]
    });
    let base_top = base.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p[2]));
    let mut best: Option<([f64; 18], f64)> = None;
    let mut regular_somewhere = false;
    for height in [0.3, 0.5, 0.7, 0.85, 1.0, 1.2] {
        for yaw in [0.0, 0.4, -0.4, 0.8, -0.8, 1.6, -1.6, core::f64::consts::PI] {
            // Centre the platform over the base centroid.
            let local_c = (0..6).map(|p| sys.point_local(p)).fold([0.0; 3], |a, p| {
                [a[0] + p[0] / 6.0, a[1] + p[1] / 6.0, a[2] + p[2] / 6.0]
            });
            let r = Pose::from_euler(yaw, 0.0, 0.0, [0.0; 3]);
            let rc = r.apply(local_c);
            let t = [
                base_c[0] - rc[0],
                base_c[1] - rc[1],
                base_c[2] - rc[2] + height * mean,
            ];
            let guess = linkage::unknowns_from_pose(
                sys,
                &Pose {
                    translation: t,
                    ..r
                },
            );
            let v = match polish(sys, guess, &x) {
                Ok(v) => v,
                Err(why) => {
                    regular_somewhere |= why != Unpolished::Singular;
                    continue;
                }
            };
            regular_somewhere = true;
            let Some(p) = linkage::pose_from_unknowns(sys, &v) else {
                continue;
            };
            let up = p.rotation[2][2];
            let above = (0..6).all(|i| v[12 + i] > base_top);
            if above
                && up > 0.0
                && (p.handedness() - 1.0).abs() < 1e-6
                && best.is_none_or(|(_, u)| up > u + 1e-9)
            {
                best = Some((v, up));
            }
        }
    }
    let (v, _) = best.ok_or(if regular_somewhere {
        StartError::NoAssemblyMode
    } else {
        StartError::SingularEverywhere
    })?;
    Start::new(sys, v, x).map_err(StartError::Solve)
}
