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

// The catalogue (`catalogue/`): the published mechanisms beyond those, the branch and geometry
// hunts across them, calibrated homes, every declared mechanism's generic root count. Each
// declaration instantiates the solvers for its own type, and together they were most of the
// integration binary's build (BENCHMARKS.md, forty-fifth session), so they build with
// `--features linkage-tests/catalogue`, as `.ci/run` does.
#[cfg(feature = "catalogue")]
mod catalogue;

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

/// Panics unless `r` is the identity to `tol`.
pub fn identity_within(r: &[[f64; 3]; 3], tol: f64) {
    for (i, row) in r.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            let id = if i == j { 1.0 } else { 0.0 };
            assert!((x - id).abs() <= tol, "the platform turned: {r:?}");
        }
    }
}
