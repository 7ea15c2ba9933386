//! Mechanisms the general model declares, one file each, checked end to end: the generated
//! Jacobians against finite differences, forward kinematics (by continuation from home)
//! against an independent inverse or forward kinematics in closed form, the mobility and the
//! rule that decided it, each mechanism's invariant, and distinct assembly modes reached from
//! different declared homes of the same machine.

// The core: the mechanisms the library is introduced with (the delta robot, the 3-PRS head, the
// planar 3-RPR, the five-bar, the spherical wrist; the Stewart platform and the rotary hexapod
// are the examples' own) and one declaration with each rarer pair (C, H, U). A plain
// `cargo test` builds these.
pub mod delta;
mod delta_tools;
mod five_bar;
mod planar_rpr;
mod prs;
mod spherical_wrist;

// The catalogue: the published mechanisms beyond those, the branch and geometry hunts across
// them, calibrated homes, every declared mechanism's generic root count. Each declaration
// instantiates the solvers for its own type, and together they were most of the integration
// binary's build (about 100 s of 125 s alone on 2 cores; BENCHMARKS.md, forty-fifth session),
// so they build with `--features linkage-tests/catalogue`, as `.ci/run` does.
#[cfg(feature = "catalogue")]
mod all_modes;
#[cfg(feature = "catalogue")]
mod bennett;
#[cfg(feature = "catalogue")]
mod branch_hunt;
#[cfg(feature = "catalogue")]
mod calibrated_home;
#[cfg(feature = "catalogue")]
mod delta_tracking;
#[cfg(feature = "catalogue")]
mod delta_universal;
#[cfg(feature = "catalogue")]
mod exechon;
#[cfg(feature = "catalogue")]
mod four_bar;
#[cfg(feature = "catalogue")]
mod geometry_hunt;
#[cfg(feature = "catalogue")]
mod goldberg;
#[cfg(feature = "catalogue")]
mod h4;
#[cfg(feature = "catalogue")]
mod home_by_inputs;
#[cfg(feature = "catalogue")]
mod jansen;
#[cfg(feature = "catalogue")]
mod linear_delta;
#[cfg(feature = "catalogue")]
mod linear_pentapod;
#[cfg(feature = "catalogue")]
mod literature;
#[cfg(feature = "catalogue")]
mod literature_more;
#[cfg(feature = "catalogue")]
mod motors;
#[cfg(feature = "catalogue")]
mod numerical_inverse;
#[cfg(feature = "catalogue")]
mod orthoglide;
#[cfg(feature = "catalogue")]
mod pan_tilt;
#[cfg(feature = "catalogue")]
mod partly_driven_cylinders;
#[cfg(feature = "catalogue")]
mod pcs;
#[cfg(feature = "catalogue")]
mod peaucellier;
#[cfg(feature = "catalogue")]
mod planar_rrr;
#[cfg(feature = "catalogue")]
mod platform_centres;
#[cfg(feature = "catalogue")]
mod published;
#[cfg(feature = "catalogue")]
mod puu;
#[cfg(feature = "catalogue")]
mod rrs;
#[cfg(feature = "catalogue")]
mod scara;
#[cfg(feature = "catalogue")]
mod slider_crank;
#[cfg(feature = "catalogue")]
mod translational_upu;
#[cfg(feature = "catalogue")]
mod triangle_platforms;
#[cfg(feature = "catalogue")]
mod tricept;
#[cfg(feature = "catalogue")]
mod tripteron;
#[cfg(feature = "catalogue")]
mod upu_modes;
#[cfg(feature = "catalogue")]
mod upu_wrist;

use linkage::{Mechanism, Options};

/// The general model's rows (unit axis vectors beside 200 mm coordinates) can leave a rounding
/// floor of 1e-10 to 2e-9 mm on the Newton correction even at regular points: below it a solve
/// ends `ToleranceNotMet`, so tests that need every solve to converge ask for a tolerance above it.
pub const GENERAL_MODEL: Options = Options {
    tolerance: 1e-8,
    ..Options::TIGHT
};

/// The inverse kinematics gives `x` back (to `tol`, from `reference`): from the solved unknowns,
/// and from the platform's points alone (the unknowns of the links between zeroed, as
/// `unknowns_from_pose` leaves them).
pub fn check_inverse<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    reference: &[f64; M],
    tol: f64,
) {
    let back = sys.inverse(v, reference).unwrap();
    assert!(
        linkage_tests::max_diff(&back, x) < tol,
        "{}: {back:?} vs {x:?}",
        S::NAME
    );
    let mut platform_only = *v;
    for q in platform_only[3 * S::POINTS.len()..].iter_mut() {
        *q = 0.0;
    }
    let back = sys.inverse(&platform_only, reference).unwrap();
    assert!(
        linkage_tests::max_diff(&back, x) < tol,
        "{} from the platform alone: {back:?} vs {x:?}",
        S::NAME
    );
    // The platform's coordinates NaN, infinite, or so far out that the inputs overflow, and a
    // NaN reference: an error, never inputs (a closed form gave a leg of NaN or ∞ as ok).
    let held = 3 * S::POINTS.len();
    for bad in [f64::NAN, f64::INFINITY, -f64::INFINITY, 1e300] {
        let mut off = *v;
        for q in &mut off[..held] {
            *q = bad;
        }
        let r = sys.inverse(&off, reference);
        assert!(r.is_err(), "{}: the platform at {bad} gave {r:?}", S::NAME);
    }
    // The platform's last point moved away from its first by 2 % of the scale: no placement of
    // a platform of two points or more (the closed forms, which read one point per input, gave
    // the inputs for the points they read). Unknowns are by axis: v[a k + p].
    let k = S::POINTS.len();
    if k >= 2 {
        let scale = 1.0 + v[..held].iter().fold(0.0f64, |m, q| m.max(q.abs()));
        let d: [f64; 3] = std::array::from_fn(|a| v[a * k + k - 1] - v[a * k]);
        let len = d.iter().map(|c| c * c).sum::<f64>().sqrt();
        let mut off = *v;
        for a in 0..3 {
            off[a * k + k - 1] += 0.02 * scale * d[a] / len;
        }
        let r = sys.inverse(&off, reference);
        assert!(r.is_err(), "{}: the last point off gave {r:?}", S::NAME);
    }
    let mut nan = *reference;
    nan[0] = f64::NAN;
    assert_eq!(
        sys.inverse(v, &nan),
        Err(linkage::InverseError::NonFinite),
        "{}: a NaN reference",
        S::NAME
    );
}

/// The `mobility:` line of a listing.
pub fn mobility_line(listing: &str) -> &str {
    listing
        .lines()
        .find(|l| l.starts_with("mobility:"))
        .unwrap_or("")
}

/// The distances from `base[k]` to `platform[k]` placed by `pose`: the legs' lengths of a
/// platform on straight legs, in closed form.
#[cfg(feature = "catalogue")]
pub fn leg_lengths<const K: usize>(
    pose: &linkage::Pose,
    base: &[[f64; 3]; K],
    platform: &[[f64; 3]; K],
) -> [f64; K] {
    std::array::from_fn(|k| {
        let d = linkage_tests::vec3::sub(pose.apply(platform[k]), base[k]);
        linkage_tests::vec3::dot(d, d).sqrt()
    })
}

/// Panics unless `r` is the identity to `tol`.
pub fn identity_within(r: &[[f64; 3]; 3], tol: f64) {
    for (i, row) in r.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            let id = if i == j { 1.0 } else { 0.0 };
            assert!((x - id).abs() <= tol, "the platform turned: {r:?}");
        }
    }
}

/// The point `name` at `v`, in the base frame.
#[cfg(feature = "catalogue")]
pub fn point<S: Mechanism<N, M>, const N: usize, const M: usize>(
    v: &[f64; N],
    name: &str,
) -> [f64; 3] {
    ["x", "y", "z"].map(|c| {
        let u = format!("{c}_{name}");
        let i = S::UNKNOWNS
            .iter()
            .position(|n| *n == u)
            .unwrap_or_else(|| panic!("{}: no unknown {u} in {:?}", S::NAME, S::UNKNOWNS));
        v[i]
    })
}

/// The point at distance `ra` from `a` and `rb` from `b` on the side of a→b that `side`
/// (the sign of (b − a) × (p − a)) names; `None` if the circles do not meet.
#[cfg(feature = "catalogue")]
pub fn circles(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64, side: f64) -> Option<[f64; 2]> {
    let d = (b[0] - a[0]).hypot(b[1] - a[1]);
    let along = (ra * ra - rb * rb + d * d) / (2.0 * d);
    let h2 = ra * ra - along * along;
    if !(h2 > 0.0) {
        return None;
    }
    let h = h2.sqrt() * side.signum();
    let (ex, ey) = ((b[0] - a[0]) / d, (b[1] - a[1]) / d);
    Some([a[0] + along * ex - h * ey, a[1] + along * ey + h * ex])
}
