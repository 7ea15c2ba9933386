//! Table V: every test point solved by PH, NH and NR from the initial configuration, at the
//! paper's settings and at a tight tolerance, compared with the true pivots.

use super::path_dependence::{self, PathDependence};
use super::sampling::{Protocol, Sampler, SamplingError, TestPoint};
use linkage::reference::{straight_segment, straight_segment_from};
use linkage::{Method, Options, Status};
use rayon::prelude::*;
use std::time::Instant;

/// One solve of one point.
#[derive(Clone, Copy, Debug)]
pub struct Outcome {
    pub status: Status,
    /// ‖v − v_true‖ / ‖v_true‖ (Eq. 20), of whatever v the solve returned.
    pub relative_error: f64,
    pub seconds: f64,
    /// Answered (ok, or for NH and NR `unverified`: the tolerance met) but off the true
    /// pivots by more than 0.1 %.
    pub off_truth: bool,
    /// Of those: the straight joint-space segment is free of singularities and continuation
    /// along it ends where the solve did — the pose path and the segment end in different
    /// assembly modes without either meeting a singularity.
    pub path_dependent: bool,
    /// Answered (ok or unverified) and proven by the Krawczyk test ([`linkage::certify`], not timed): the
    /// only root near v, and within the proven error bound of it.
    pub certified: bool,
}

/// Per-method summary, as in Table V plus what the paper does not count. "Answered" is a
/// result that meets the tolerance: `Converged` (ok) from PH, `Unverified` from NH and NR, which
/// cannot establish the branch — the paper's measure of all three.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Summary {
    /// Near-singular points answered with relative error < 0.1 %, as a fraction.
    pub near_singular_ok_ratio: f64,
    /// Mean relative error over the normal points answered at the true pivots.
    pub normal_mean_rel_error: f64,
    /// Largest relative error over the normal points answered at the true pivots.
    pub normal_max_rel_error: f64,
    /// Normal points not answered at the true pivots.
    pub normal_failures: usize,
    /// Mean wall time per point, seconds.
    pub mean_time_s: f64,
    /// Answers off the true pivots and *not* reached from the start by a nonsingular path:
    /// another branch — the worst defect when labelled ok (PH), what `unverified` warns of
    /// (NH, NR).
    pub wrong_branch: usize,
    /// Answers off the true pivots but reached from the start by the
    /// straight joint-space segment without meeting a singularity (verified by fine
    /// continuation): a second solution on the start's branch, reached by a path that winds
    /// differently from the pose path (a nonsingular assembly-mode change).
    pub path_dependent: usize,
    /// Solves that ended with `Status::Fold`.
    pub fold_reported: usize,
    /// Solves that ended with any other status that does not meet the tolerance.
    pub other_failures: usize,
    /// Normal points answered, and of those the ones certified ([`Outcome::certified`]).
    pub normal_ok: usize,
    pub normal_certified: usize,
    /// Near-singular points answered, and of those the ones certified.
    pub near_singular_ok: usize,
    pub near_singular_certified: usize,
}

fn rel_error(v: &[f64; 18], truth: &[f64; 18]) -> f64 {
    let d: f64 = v
        .iter()
        .zip(truth)
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt();
    d / truth.iter().map(|a| a * a).sum::<f64>().sqrt()
}

/// Solves one point; `segment` is the fine continuation's verdict, computed once per point.
pub fn solve_point(
    sampler: &Sampler,
    p: &TestPoint,
    method: Method,
    options: &Options,
    segment: &([f64; 18], usize),
) -> Outcome {
    let t0 = Instant::now();
    let result = method.solve(&sampler.sys, &sampler.start, &p.x, options);
    let seconds = t0.elapsed().as_secs_f64();
    let (status, v) = match result {
        Ok(sol) => (sol.status, sol.v),
        Err(_) => (Status::Singular { lambda: 0.0 }, *sampler.start.v()),
    };
    let relative_error = rel_error(&v, &p.v);
    let off_truth = status.meets_tolerance() && relative_error >= 1e-3;
    let path_dependent = off_truth && segment.1 == 0 && rel_error(&v, &segment.0) < 1e-6;
    let certified = status.meets_tolerance() && linkage::certify(&sampler.sys, &v, &p.x).is_ok();
    Outcome {
        status,
        relative_error,
        seconds,
        off_truth,
        path_dependent,
        certified,
    }
}

pub fn summarize(normal: &[Outcome], near: &[Outcome]) -> Summary {
    // Answered (and, with `certified`, proven).
    let count = |o: &[Outcome], certified: bool| {
        o.iter()
            .filter(|o| o.status.meets_tolerance() && (o.certified || !certified))
            .count()
    };
    let ok = |o: &&Outcome| o.status.meets_tolerance() && !o.off_truth;
    // `normal_*` errors average the results that match the true pivots.
    let normal_ok: Vec<&Outcome> = normal.iter().filter(ok).collect();
    let all = normal.iter().chain(near);
    Summary {
        near_singular_ok_ratio: near
            .iter()
            .filter(|o| o.status.meets_tolerance() && o.relative_error < 1e-3)
            .count() as f64
            / near.len().max(1) as f64,
        normal_mean_rel_error: normal_ok.iter().map(|o| o.relative_error).sum::<f64>()
            / normal_ok.len().max(1) as f64,
        normal_max_rel_error: normal_ok
            .iter()
            .map(|o| o.relative_error)
            .fold(0.0, f64::max),
        normal_failures: normal.len() - normal_ok.len(),
        mean_time_s: all.clone().map(|o| o.seconds).sum::<f64>()
            / (normal.len() + near.len()).max(1) as f64,
        wrong_branch: all
            .clone()
            .filter(|o| o.off_truth && !o.path_dependent)
            .count(),
        path_dependent: all.clone().filter(|o| o.path_dependent).count(),
        fold_reported: all
            .clone()
            .filter(|o| matches!(o.status, Status::Fold { .. }))
            .count(),
        other_failures: all
            .filter(|o| !(o.status.meets_tolerance() || matches!(o.status, Status::Fold { .. })))
            .count(),
        normal_ok: count(normal, false),
        normal_certified: count(normal, true),
        near_singular_ok: count(near, false),
        near_singular_certified: count(near, true),
    }
}

/// Everything `stewart table-v` reports.
pub struct Report {
    pub protocol: Protocol,
    pub mean_det: f64,
    pub normal: Vec<TestPoint>,
    pub near: Vec<TestPoint>,
    /// Near-singular points whose straight joint-space segment leaves the valid joint space.
    pub segment_leaves_vjs: usize,
    /// `(method name, paper settings, tight tolerance)` outcomes, per point: normal then near.
    pub outcomes: Vec<(&'static str, Vec<Outcome>, Vec<Outcome>)>,
    /// PH with detours (`arc_length_detour`, tight tolerance) on the points where the straight
    /// segment ends in a fold.
    pub detours: Detours,
    /// Near-singular targets with a second mode reached from home without a singularity
    /// (every real root examined; an error if the stored start set could not be used).
    pub path_dependence: Result<PathDependence, String>,
}

/// Points checked along each candidate path of [`PathDependence`] (the README's 20 000).
pub const PATH_CHECKS: usize = 20_000;

/// What detours around folds achieved.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Detours {
    /// Points where straight PH reported a fold.
    pub folds: usize,
    /// Of those, reached through a waypoint.
    pub reached: usize,
    /// Of those reached, at the true pivots.
    pub at_truth: usize,
    /// Of those reached elsewhere: fine continuation along the same polyline confirms the
    /// result (a second solution on the start's branch).
    pub path_dependent: usize,
    /// Reached elsewhere and not confirmed: would be a wrong branch labelled ok.
    pub wrong_branch: usize,
}

pub const METHODS: [(&str, Method); 3] = [
    ("PH", Method::ArcLength),
    ("NH", Method::NewtonHomotopy),
    ("NR", Method::NewtonRaphson),
];

/// Samples the test points and solves them; an error when the protocol cannot produce its
/// points (see [`Sampler::sample`]).
pub fn run(protocol: Protocol, mut progress: impl FnMut(&str)) -> Result<Report, SamplingError> {
    protocol.validate()?;
    let sampler = Sampler::new(protocol);
    progress("sampling test points");
    let (mean_det, normal, near) = sampler.sample()?;
    progress("checking the straight joint-space segments");
    let points: Vec<&TestPoint> = normal.iter().chain(&near).collect();
    // Untimed work runs on every core; the timed solves below run one at a time, so that no
    // solve's time is shared with another thread's.
    let segments: Vec<([f64; 18], usize)> = points
        .par_iter()
        .map(|p| straight_segment(&sampler.sys, &sampler.start, &p.x, 4000))
        .collect();
    let segment_leaves_vjs = segments[normal.len()..].iter().filter(|s| s.1 > 0).count();
    let mut outcomes = Vec::new();
    for (name, method) in METHODS {
        progress(&format!("solving with {name}"));
        let paper = Options {
            tolerance: 5e-4,
            max_iterations: 150,
            ..Options::PAPER
        };
        let tight = Options::TIGHT;
        let solve_all = |o: &Options| {
            points
                .iter()
                .zip(&segments)
                .map(|(p, s)| solve_point(&sampler, p, method, o, s))
                .collect::<Vec<_>>()
        };
        outcomes.push((name, solve_all(&paper), solve_all(&tight)));
    }
    progress("detours around folds");
    let detours = detour_all(&sampler, &points, &outcomes[0].2);
    progress("every real mode of the near-singular targets");
    let path_dependence =
        path_dependence::examine(&sampler, &near, &segments[normal.len()..], PATH_CHECKS);
    Ok(Report {
        protocol,
        mean_det,
        normal,
        near,
        segment_leaves_vjs,
        outcomes,
        detours,
        path_dependence,
    })
}

/// Fine continuation along start → corners…: no sign change of det B, and it ends at `v`.
fn polyline_confirms(sampler: &Sampler, corners: &[[f64; 6]], v: &[f64; 18]) -> bool {
    let (mut here, mut at) = (*sampler.start.v(), *sampler.start.x());
    for corner in corners {
        let (next, flips) = straight_segment_from(
            &sampler.sys,
            (&here, &at),
            sampler.start.det(),
            corner,
            4000,
        );
        if flips > 0 {
            return false;
        }
        (here, at) = (next, *corner);
    }
    rel_error(&here, v) < 1e-6
}

fn detour_all(sampler: &Sampler, points: &[&TestPoint], ph: &[Outcome]) -> Detours {
    let mut d = Detours::default();
    for (p, o) in points.iter().zip(ph) {
        if !matches!(o.status, Status::Fold { .. }) {
            continue;
        }
        d.folds += 1;
        let Ok(r) = linkage::arc_length_detour(&sampler.sys, &sampler.start, &p.x, &Options::TIGHT)
        else {
            continue;
        };
        let (Some(via), Some(left_at), true) = (r.via, r.left_at, r.solution.is_ok()) else {
            continue;
        };
        d.reached += 1;
        if rel_error(&r.solution.v, &p.v) < 1e-3 {
            d.at_truth += 1;
            continue;
        }
        if polyline_confirms(sampler, &[left_at, via, p.x], &r.solution.v) {
            d.path_dependent += 1;
        } else {
            d.wrong_branch += 1;
        }
    }
    d
}

/// The report as `stewart table-v --json` prints it: `{"methods": {"PH": {...}, ...}, ...}`,
/// each method's keys at the paper's settings and again under `"tight"`.
pub fn to_json(r: &Report) -> serde_json::Value {
    let n = r.normal.len();
    let mut methods = serde_json::Map::new();
    for (name, paper, tight) in &r.outcomes {
        let mut m =
            serde_json::to_value(summarize(&paper[..n], &paper[n..])).expect("plain numbers");
        m["tight"] =
            serde_json::to_value(summarize(&tight[..n], &tight[n..])).expect("plain numbers");
        methods.insert(name.to_string(), m);
    }
    let p = &r.protocol;
    serde_json::json!({
        "methods": methods,
        "ph_detours": r.detours,
        "path_dependence": match &r.path_dependence {
            Ok(d) => serde_json::to_value(d).expect("plain numbers"),
            Err(e) => serde_json::json!({ "error": e }),
        },
        "points": { "normal": n, "near_singular": r.near.len() },
        "near_singular_segment_leaves_vjs": r.segment_leaves_vjs,
        "protocol": {
            "seed": p.seed, "rotation_rad": p.rotation, "translation_mm": p.translation, "heave_mm": p.heave,
            "path_checks": p.checks, "near_fraction": p.near_fraction, "mean_samples": p.mean_samples,
            "mean_abs_det": r.mean_det,
            "paper_settings": { "tolerance": 5e-4, "max_iterations": 150 },
            "tight_settings": { "tolerance": Options::TIGHT.tolerance },
        },
    })
}
