//! Starts at and near singular configurations (issue 9, defect 4): exact poses a relative
//! 1e-15 … 1e-6 (in the pose path's parameter) either side of the first singular surface along a
//! random ray from home, each given to `Start::new` with its legs from inverse kinematics.
//!
//! The pose is exact, so the start is consistent: a refusal must say `SingularStart`, not
//! `InconsistentStart`. An accepted start must be one that rounding cannot move across the
//! singular surface: rebuilt from its own refined pivots, or from them moved by 1e-12 of
//! their size, it is accepted again with det B of the same sign or refused as singular. The
//! verdict is scale-free: the same machine and pose scaled by 1/16 and by 16 (exact in binary)
//! get the same verdict and det B of the same sign. Solves from an accepted start keep the
//! invariants, and reach the start's own legs.

use super::geometry::{pose_at, random_offset, start_parts, Geometry, Machine};
use super::run::Tally;
use linkage::{arc_length, newton_raphson, Options, SolveError, Start};
use linkage_examples::stewart::{legs_for_pose, SixSix};
use linkage_tests::invariants::ok_violation;
use linkage_tests::Rng;

#[derive(Debug)]
#[allow(dead_code)] // read through Debug
struct Inputs<'a> {
    geometry: &'a Geometry,
    u: [f64; 6],
    t: f64,
    side: &'static str,
    /// How far from the crossing, relative to t.
    offset: f64,
    legs: [f64; 6],
}

/// `Start::new`'s verdict in one word, with det B's sign when accepted.
fn verdict(r: &Result<Start<18, 6>, SolveError>) -> (&'static str, f64) {
    match r {
        Ok(s) => ("accepted", start_parts(s).2.signum()),
        Err(e) => (e.word(), 0.0),
    }
}

/// The start for the pose `home ⊕ t u` of the geometry `g` scaled by `k`.
fn start_at<S: SixSix>(
    g: &Geometry,
    u: &[f64; 6],
    t: f64,
    k: f64,
) -> Option<Result<Start<18, 6>, SolveError>> {
    let g = g.scaled(k);
    let sys = S::with_joints(&g.base, &g.platform).ok()?;
    let mut u = *u;
    u[3..].iter_mut().for_each(|c| *c *= k);
    let (x, v) = legs_for_pose(&sys, &pose_at(&g.home, &u, t))?;
    Some(Start::new(&sys, v, x))
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

pub fn case<S: SixSix>(tally: &mut Tally, case: u64, rng: &mut Rng, g: Geometry) {
    let Some(m) = Machine::<S>::for_case(&g, tally) else {
        return;
    };
    let u = random_offset(rng, 0.7, 0.5 * m.size);
    let Some((t_in, t_out)) = m.crossing(&u, 3.0, 200) else {
        tally.count("no singular surface on the ray (skipped)");
        return;
    };
    tally.case();
    let e = pick_offset(rng);
    let (side, t) = match rng.next_u64() % 2 {
        0 => ("inside", t_in * (1.0 - e)),
        _ => ("outside", t_out * (1.0 + e)),
    };
    let Some((x, v)) = legs_for_pose(&m.sys, &pose_at(&g.home, &u, t)) else {
        tally.count("no inverse kinematics (skipped)");
        return;
    };
    let inputs = Inputs {
        geometry: &g,
        u,
        t,
        side,
        offset: e,
        legs: x,
    };
    let first = Start::new(&m.sys, v, x);
    let (word, sign) = verdict(&first);
    tally.count(format!("{side} by {e:.0e}: {word}"));
    if let Err(SolveError::InconsistentStart { residual_norm }) = first {
        tally.fail(
            "exact_start_called_inconsistent",
            case,
            format!(
                "an exact pose refused as inconsistent (‖F‖ = {residual_norm:e}), not as singular"
            ),
            &inputs,
        );
    }
    for k in [1.0 / 16.0, 16.0] {
        if let Some(scaled) = start_at::<S>(&g, &u, t, k) {
            if verdict(&scaled) != (word, sign) {
                tally.fail(
                    "start_verdict_not_scale_free",
                    case,
                    format!(
                        "{word} (det B sign {sign}) at scale 1, {:?} at scale {k}",
                        verdict(&scaled)
                    ),
                    &inputs,
                );
            }
        }
    }
    let Ok(start) = first else {
        return;
    };
    let (vs, xs, det) = start_parts(&start);
    if !(super::oracle::det(&m.sys, &vs, &xs) * det > 0.0) {
        tally.fail(
            "start_sign_unstable",
            case,
            format!(
                "the start's det B {det:e} and det B recomputed at its pivots {:e} differ in sign",
                super::oracle::det(&m.sys, &vs, &xs)
            ),
            &inputs,
        );
    }
    let scale = sup(&vs);
    for (what, w) in [
        ("its own pivots", vs),
        (
            "its pivots moved by 1e-12",
            vs.map(|c| c + 1e-12 * scale * rng.symmetric()),
        ),
    ] {
        match Start::new(&m.sys, w, xs) {
            Ok(again) if start_parts(&again).2 * det > 0.0 => {}
            Err(SolveError::SingularStart) => {}
            other => tally.fail(
                "start_sign_unstable",
                case,
                format!(
                    "rebuilt from {what}: {:?} (first: det B {det:e})",
                    verdict(&other)
                ),
                &inputs,
            ),
        }
    }
    // Solves from it: the invariants, and its own legs reached.
    let x_near = xs.map(|l| l * (1.0 + 1e-9 * rng.symmetric()));
    for (target, name) in [(xs, "its own legs"), (x_near, "legs 1e-9 from its own")] {
        for (solver, result) in [
            ("PH", arc_length(&m.sys, &start, &target, &Options::TIGHT)),
            (
                "NR",
                newton_raphson(&m.sys, &start, &target, &Options::TIGHT),
            ),
        ] {
            match &result {
                Ok(sol) => {
                    tally.count(format!("{solver} to {name}: {}", sol.status.word()));
                    if let Some(v) =
                        ok_violation(&m.sys, det, &target, sol, Options::TIGHT.tolerance)
                    {
                        tally.fail(
                            v.kind,
                            case,
                            format!("{solver} to {name}: {}", v.what),
                            &inputs,
                        );
                    }
                }
                Err(e) => tally.count(format!("{solver} to {name}: error {}", e.word())),
            }
        }
    }
}

/// How far from the crossing (relative): 1e-15 … 1e-6, log-uniform.
fn pick_offset(rng: &mut Rng) -> f64 {
    10f64.powi(-(6 + (rng.next_u64() % 10) as i32))
}
