//! Which near-singular Table V targets have a second assembly mode that is also reached from
//! home without a singularity: the path dependence the README describes, found from every
//! real root (`linkage::modes`) rather than from whichever one a solver happened to return.
//!
//! For each target: all real roots at its legs (the stored Table III start set); the true pose
//! (reached from home by a nonsingular pose path by construction) among them; and for every
//! other real root with the start's sign of det B — the only ones a nonsingular path can reach
//! — two candidate paths from home, each checked for a sign change of det B at `checks` evenly
//! spaced points:
//! - the straight pose path (yaw, pitch, roll, x, y, z from home's, angles the short way round),
//!   legs from inverse kinematics, every leg above the protocol's `min_leg`;
//! - the straight joint-space segment (fine continuation, computed once per target by Table V):
//!   it counts when it ends at this root.
//!
//! A root reached either way is a second valid answer on the start's branch: for such a target
//! "the forward kinematics solution" depends on the path the machine takes.

use super::sampling::{Sampler, TestPoint};
use crate::stewart::legs_for_pose;
use linkage::modes::Roots;
use linkage::{det_b, Pose};
use rayon::prelude::*;

/// What the search found over the near-singular targets.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct PathDependence {
    /// Targets examined (the near-singular points).
    pub targets: usize,
    /// Targets whose all-modes solve ended every path at a root.
    pub complete: usize,
    /// Of those, targets whose true pose is among the real roots found (to 1e-6 relative).
    pub truth_found: usize,
    /// Real roots per target, summed (mean = this / complete).
    pub real_roots: usize,
    /// Other real roots with the start's sign of det B, summed.
    pub same_sign_others: usize,
    /// Targets with at least one other root reached from home without a singularity.
    pub path_dependent_targets: usize,
    /// Other roots so reached, by the straight pose path.
    pub by_pose_path: usize,
    /// Other roots so reached, by the straight joint-space segment (and not by the pose path).
    pub by_segment_only: usize,
    /// 1-based indices (among the near-singular points) of the path-dependent targets.
    pub which: Vec<usize>,
}

fn relative(v: &[f64; 18], w: &[f64; 18]) -> f64 {
    let d: f64 = v.iter().zip(w).map(|(a, b)| (a - b) * (a - b)).sum();
    let n: f64 = w.iter().map(|a| a * a).sum();
    (d / n).sqrt()
}

/// `a − b` the short way round the circle.
fn angle_diff(a: f64, b: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let d = (a - b).rem_euclid(tau);
    if d > std::f64::consts::PI {
        d - tau
    } else {
        d
    }
}

/// The offset u with `sampler.pose(u, 1) == pose`: yaw, pitch, roll, x, y, z from home's,
/// angles the short way round; `None` if Euler coordinates do not reproduce `pose`.
pub fn offset_to(sampler: &Sampler, pose: &Pose) -> Option<[f64; 6]> {
    let home = linkage::pose_from_unknowns(&sampler.sys, sampler.start.v())?;
    let (e0, e1) = (home.euler(), pose.euler());
    let (t0, t1) = (home.translation, pose.translation);
    let u = [
        angle_diff(e1[0], e0[0]),
        e1[1] - e0[1],
        angle_diff(e1[2], e0[2]),
        t1[0] - t0[0],
        t1[1] - t0[1],
        t1[2] - t0[2],
    ];
    let end = sampler.pose(&u, 1.0);
    let same = (0..3).all(|i| {
        (0..3).all(|j| (end.rotation[i][j] - pose.rotation[i][j]).abs() < 1e-9)
            && (end.translation[i] - pose.translation[i]).abs() < 1e-6
    });
    same.then_some(u)
}

/// Whether the straight pose path from home to `pose` keeps det B's start sign at `checks`
/// points with every leg above `min_leg` (`None` if [`offset_to`] cannot represent `pose`).
fn pose_path_nonsingular(sampler: &Sampler, pose: &Pose, checks: usize) -> Option<bool> {
    let u = offset_to(sampler, pose)?;
    let sign = sampler.start.det();
    let min_leg = sampler.protocol.min_leg;
    Some((1..=checks).all(|k| {
        match legs_for_pose(&sampler.sys, &sampler.pose(&u, k as f64 / checks as f64)) {
            Some((x, v)) if x.iter().all(|l| *l > min_leg) => {
                det_b(&sampler.sys, &v, &x) * sign > 0.0
            }
            _ => false,
        }
    }))
}

/// Examines every near-singular target; `segments[i]` is Table V's fine continuation along the
/// straight joint-space segment to `near[i]` (its end and its number of det B sign changes).
pub fn examine(
    sampler: &Sampler,
    near: &[TestPoint],
    segments: &[([f64; 18], usize)],
    checks: usize,
) -> Result<PathDependence, String> {
    let modes =
        crate::start_sets::table_iii::<64>().map_err(|e| format!("stored start solutions: {e}"))?;
    let sign = sampler.start.det();
    // One target per task, on every core; the tallies are summed in target order.
    let per_target: Vec<PathDependence> = near
        .par_iter()
        .zip(segments)
        .enumerate()
        .map(|(i, (p, segment))| {
            let mut out = PathDependence::default();
            let mut roots = Box::new(Roots::<18, 64>::new());
            if modes.solve(&p.x, &mut roots).is_err() || !roots.is_complete() {
                return out;
            }
            out.complete += 1;
            out.real_roots += roots.real().len();
            if !roots.real().iter().any(|r| relative(&r.v, &p.v) < 1e-6) {
                return out;
            }
            out.truth_found += 1;
            let mut dependent = false;
            for r in roots.real() {
                if relative(&r.v, &p.v) < 1e-6 || r.det * sign <= 0.0 {
                    continue;
                }
                out.same_sign_others += 1;
                // A coarse check first (most paths meet a singularity early), then the fine one.
                let by_pose = r.pose.is_some_and(|pose| {
                    pose_path_nonsingular(sampler, &pose, checks / 10) == Some(true)
                        && pose_path_nonsingular(sampler, &pose, checks) == Some(true)
                });
                let by_segment = segment.1 == 0 && relative(&segment.0, &r.v) < 1e-6;
                if by_pose {
                    out.by_pose_path += 1;
                } else if by_segment {
                    out.by_segment_only += 1;
                }
                dependent |= by_pose || by_segment;
            }
            if dependent {
                out.path_dependent_targets += 1;
                out.which.push(i + 1);
            }
            out
        })
        .collect();
    let mut out = PathDependence {
        targets: near.len(),
        ..PathDependence::default()
    };
    for t in per_target {
        out.complete += t.complete;
        out.real_roots += t.real_roots;
        out.truth_found += t.truth_found;
        out.same_sign_others += t.same_sign_others;
        out.path_dependent_targets += t.path_dependent_targets;
        out.by_pose_path += t.by_pose_path;
        out.by_segment_only += t.by_segment_only;
        out.which.extend(t.which);
    }
    Ok(out)
}
