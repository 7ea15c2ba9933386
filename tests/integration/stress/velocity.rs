//! One velocity case: a random machine at a random pose, moved along a random direction in pose
//! space; the truth by inverse kinematics alone (central differences of the legs and of the
//! pose along that motion), held against `velocity::twist` and `velocity::input_rates`.

use super::geometry::{pose_at, Geometry, Machine};
use super::run::Tally;
use linkage::velocity::{input_rates, twist, Twist};
use linkage::Pose;
use linkage_examples::stewart::{legs_for_pose, SixSix};
use linkage_tests::Rng;

#[derive(Debug)]
#[allow(dead_code)] // read through Debug
struct Inputs<'a> {
    geometry: &'a Geometry,
    offset: [f64; 6],
    direction: [f64; 6],
    legs: [f64; 6],
    det_ratio: f64,
}

/// Below this |det B| / |det B₀| the rates are large and the differences' rounding with them:
/// counted, not judged.
const NEAR_SINGULAR: f64 = 1e-3;

pub fn case<S: SixSix>(tally: &mut Tally, case: u64, rng: &mut Rng, g: Geometry) {
    let Some(m) = Machine::<S>::for_case(&g, tally) else {
        return;
    };
    tally.case();
    let offset: [f64; 6] = std::array::from_fn(|i| {
        let by = if i < 3 { 0.3 } else { 0.15 * m.size };
        by * rng.symmetric()
    });
    let direction: [f64; 6] = std::array::from_fn(|i| {
        let by = if i < 3 { 1.0 } else { m.size };
        by * rng.symmetric()
    });
    let Some((x, v, ratio)) = m.at(&offset, 1.0) else {
        tally.count("pose with a leg too short (skipped)");
        return;
    };
    let inputs = Inputs {
        geometry: &g,
        offset,
        direction,
        legs: x,
        det_ratio: ratio,
    };
    if !(ratio.abs() > NEAR_SINGULAR) {
        tally.count("near-singular pose (not judged)");
        return;
    }
    // The pose along the motion: parameters offset + s · direction.
    let pose = |s: f64| -> Pose {
        let u: [f64; 6] = std::array::from_fn(|i| offset[i] + s * direction[i]);
        pose_at(&m.home, &u, 1.0)
    };
    let h = 1e-6;
    let (Some((xp, _)), Some((xm, _))) = (
        legs_for_pose(&m.sys, &pose(h)),
        legs_for_pose(&m.sys, &pose(-h)),
    ) else {
        tally.count("no inverse kinematics beside the pose (skipped)");
        return;
    };
    let xdot: [f64; 6] = std::array::from_fn(|j| (xp[j] - xm[j]) / (2.0 * h));
    let (pp, pm, p0) = (pose(h), pose(-h), pose(0.0));
    let linear: [f64; 3] =
        std::array::from_fn(|i| (pp.translation[i] - pm.translation[i]) / (2.0 * h));
    // Ṙ Rᵀ = [ω]×.
    let w = |i: usize, j: usize| -> f64 {
        (0..3)
            .map(|c| (pp.rotation[i][c] - pm.rotation[i][c]) / (2.0 * h) * p0.rotation[j][c])
            .sum()
    };
    let truth = Twist {
        angular: [w(2, 1), w(0, 2), w(1, 0)],
        linear,
    };
    // Differences of IK: truncation O(h²), rounding about 1e-16 · size / h relative to the
    // rates, amplified where the machine is poorly conditioned.
    let scale = sup(&truth.linear).max(m.size * sup(&truth.angular));
    let allowed = 1e-5 * scale / ratio.abs().min(1.0);

    match twist(&m.sys, &v, &x, &xdot) {
        Ok(t) => {
            tally.count("twists");
            let off = sup(&sub(&t.linear, &truth.linear))
                .max(m.size * sup(&sub(&t.angular, &truth.angular)));
            if !(off <= allowed) {
                tally.fail(
                    "twist_wrong",
                    case,
                    format!(
                        "twist {t:?}, by differences {truth:?} (off {off:e}, allowed {allowed:e})"
                    ),
                    &inputs,
                );
            }
        }
        Err(e) => tally.fail("twist_refused", case, format!("{e:?}"), &inputs),
    }
    match input_rates(&m.sys, &v, &x, &truth) {
        Ok(r) => {
            tally.count("input rates");
            let off = sup(&sub(&r.rates, &xdot));
            if !(off <= 1e-5 * sup(&xdot) / ratio.abs().min(1.0)) {
                tally.fail(
                    "input_rates_wrong",
                    case,
                    format!("rates {:?}, by differences {xdot:?}", r.rates),
                    &inputs,
                );
            }
            let left = sup(&r.left_over.linear).max(m.size * sup(&r.left_over.angular));
            if !(left <= allowed) {
                tally.fail(
                    "reachable_twist_left_over",
                    case,
                    format!("left over {:?} of a twist the legs made", r.left_over),
                    &inputs,
                );
            }
        }
        Err(e) => tally.fail("input_rates_refused", case, format!("{e:?}"), &inputs),
    }
    // Rates of a configuration with the inputs of another: refused, never rates of nothing.
    let other: [f64; 6] = std::array::from_fn(|j| x[j] + if j == 0 { 0.05 * m.size } else { 0.0 });
    if let Ok(t) = twist(&m.sys, &v, &other, &xdot) {
        tally.fail(
            "rates_of_a_non_solution",
            case,
            format!("a twist {t:?} for legs {other:?} that are not the pose's"),
            &inputs,
        );
    }
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

fn sub<const K: usize>(a: &[f64; K], b: &[f64; K]) -> [f64; K] {
    std::array::from_fn(|i| a[i] - b[i])
}
