//! The mechanism catalogue: the published mechanisms beyond the core ones of `super`, the
//! branch and geometry hunts across all of them, calibrated homes, and every declared
//! mechanism's generic root count. Built with `--features linkage-tests/catalogue` (`.ci/run`
//! does); a plain `cargo test` leaves it out (README, "What that command leaves out").

// The core mechanisms and the shared checks, by the names the files used beside them.
use super::*;

mod all_modes;
mod bennett;
mod branch_hunt;
mod calibrated_home;
mod delta_tracking;
mod delta_universal;
mod exechon;
mod four_bar;
mod geometry_hunt;
mod goldberg;
mod h4;
mod home_by_inputs;
mod jansen;
mod linear_delta;
mod linear_pentapod;
mod literature;
mod literature_more;
mod motors;
mod numerical_inverse;
mod orthoglide;
mod pan_tilt;
mod partly_driven_cylinders;
mod pcs;
mod peaucellier;
mod planar_rrr;
mod platform_centres;
mod published;
mod puu;
mod rrs;
mod scara;
mod slider_crank;
mod translational_upu;
mod triangle_platforms;
mod tricept;
mod tripteron;
mod upu_modes;
mod upu_wrist;

/// The distances from `base[k]` to `platform[k]` placed by `pose`: the legs' lengths of a
/// platform on straight legs, in closed form.
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

/// The point `name` at `v`, in the base frame.
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
