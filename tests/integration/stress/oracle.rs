//! Ground truth by fine continuation, written independently of the runtime's solvers: dense LU
//! only, small steps, det B checked at every accepted point.
//!
//! Along a straight joint-space segment from a point of the start's branch, natural-parameter
//! continuation with a tangent predictor and a Newton corrector that must contract at once
//! (so that it cannot slide onto another sheet of the solution set) either reaches the end with
//! det B of the start's sign at every point, or stops where the segment meets a singularity
//! (det B changes sign). Where its steps shrink to nothing, pseudo-arc-length steps
//! (`arc.rs`) decide between a fold (λ turns back, det B changes sign) and a near miss (the
//! branch goes on), and continuation resumes past it.

use super::arc::{pass, Pass};
use linkage::Mechanism;
use linkage_tests::dense::Lu;

/// The end of a segment followed by [`follow_segment`].
#[derive(Clone, Copy, Debug)]
pub struct Truth<const N: usize> {
    /// The last point reached (the end of the segment when `reached`).
    pub v: [f64; N],
    /// The end was reached without meeting a singularity.
    pub reached: bool,
    /// How far along the segment (1 when reached).
    pub lambda: f64,
    /// The smallest |det B| / |det0| at the points accepted on the way.
    pub min_ratio: f64,
    /// ‖∂v/∂x‖ at the end, (max over inputs): how much one unit of rounding in x moves v there.
    pub sensitivity: f64,
    /// How far the inputs still were from the end where it stopped (0 when reached).
    pub remaining: f64,
    /// Where it stopped: a bound on how far v can move on the way to the end if the branch does
    /// get there, 4 |dv/dλ| (1 − λ) (near a fold v moves as √(λ_f − λ), whose integral is twice
    /// the tangent times the distance; twice that again for safety).
    pub reach: f64,
    /// Neither reached nor shown to meet a singularity: the steps shrank to nothing.
    pub stuck: bool,
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

/// B factored at (v, x), or `None` where it is singular.
fn factored<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<Lu<N>> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    Lu::new(b).filter(|lu| lu.det.is_finite())
}

/// det B at (v, x), by this module's own factorisation (0 where singular).
pub fn det<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    factored(sys, v, x).map_or(0.0, |lu| lu.det)
}

/// dv/dλ along x(λ) = x0 + λ (x1 − x0): B dv = −(∂F/∂x)(x1 − x0).
fn tangent<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    dx: &[f64; M],
) -> Option<[f64; N]> {
    let lu = factored(sys, v, x)?;
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(v, x, &mut a);
    let mut t: [f64; N] = std::array::from_fn(|i| -(0..M).map(|j| a[i][j] * dx[j]).sum::<f64>());
    lu.solve(&mut t);
    t.iter().all(|c| c.is_finite()).then_some(t)
}

/// max over inputs j of ‖B⁻¹ ∂F/∂x_j‖∞ at (v, x).
pub fn sensitivity<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let Some(lu) = factored(sys, v, x) else {
        return f64::INFINITY;
    };
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(v, x, &mut a);
    (0..M)
        .map(|j| {
            let mut col: [f64; N] = std::array::from_fn(|i| a[i][j]);
            lu.solve(&mut col);
            sup(&col)
        })
        .fold(0.0, f64::max)
}

/// Newton at fixed x from `v`: the first correction at most `first`, each later one at most half
/// the one before; `Some((v, det B))` once the correction is at rounding level (below 1e-12 of
/// the scale, or below 1e-8 of it and no longer contracting, as near a singularity).
fn correct<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    mut v: [f64; N],
    x: &[f64; M],
    first: f64,
    iterations: usize,
) -> Option<([f64; N], f64)> {
    let scale = 1.0 + sup(&v);
    let (mut limit, mut last) = (first, f64::INFINITY);
    for _ in 0..iterations {
        let lu = factored(sys, &v, x)?;
        let mut f = [0.0; N];
        sys.residual(&v, x, &mut f);
        lu.solve(&mut f);
        let size = sup(&f);
        if !size.is_finite() {
            return None;
        }
        let done = size <= 1e-12 * scale;
        if done || (size <= 1e-8 * scale && size >= 0.5 * last) {
            if done {
                for i in 0..N {
                    v[i] -= f[i];
                }
            }
            return Some((v, det(sys, &v, x)));
        }
        if size > limit {
            return None;
        }
        for i in 0..N {
            v[i] -= f[i];
        }
        (limit, last) = (0.5 * size, size);
    }
    None
}

/// Whether (v, x) is a point of the branch of det0's sign to within what rounding allows next
/// to a singularity: its Newton correction below 1e-6 of its size.
fn stalled_near<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    det0: f64,
) -> bool {
    let Some(lu) = factored(sys, v, x) else {
        return false;
    };
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    lu.solve(&mut f);
    sup(&f) <= 1e-6 * (1.0 + sup(v)) && lu.det * det0 > 0.0
}

/// Follows the start's branch from (v0, x0), where det B has the sign of `det0`, along the
/// straight segment to `x1`, in steps of at most `max_step` in the inputs' largest component.
pub fn follow_segment<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (v0, x0): (&[f64; N], &[f64; M]),
    det0: f64,
    x1: &[f64; M],
    max_step: f64,
) -> Truth<N> {
    let dx: [f64; M] = std::array::from_fn(|j| x1[j] - x0[j]);
    let span = sup(&dx);
    let h_max = if span > 0.0 {
        (max_step / span).min(1.0)
    } else {
        1.0
    };
    let at = |l: f64| -> [f64; M] {
        if l >= 1.0 {
            *x1
        } else {
            std::array::from_fn(|j| x0[j] + l * dx[j])
        }
    };
    let stopped = |v: [f64; N], lambda: f64, min_ratio: f64, speed: f64, stuck: bool| Truth {
        v,
        reached: false,
        lambda,
        min_ratio,
        sensitivity: f64::INFINITY,
        remaining: (1.0 - lambda) * span,
        reach: 4.0 * speed * (1.0 - lambda),
        stuck,
    };
    // The first point may be a solver's result, accurate only to its tolerance: polish it
    // (next to a fold, where rounding stalls Newton, keep it as it is if it is that close).
    let mut v = match correct(sys, *v0, x0, f64::INFINITY, 30) {
        Some((v, det)) if det * det0 > 0.0 => v,
        _ if stalled_near(sys, v0, x0, det0) => *v0,
        _ => return stopped(*v0, 0.0, 0.0, f64::INFINITY, true),
    };
    let mut lambda = 0.0;
    let mut h = h_max;
    let mut min_ratio = 1.0f64;
    let mut passes = 0;
    while lambda < 1.0 {
        let Some(t) = tangent(sys, &v, &at(lambda), &dx) else {
            return stopped(v, lambda, 0.0, f64::INFINITY, true);
        };
        let next = (lambda + h).min(1.0);
        let step = next - lambda;
        let pred: [f64; N] = std::array::from_fn(|i| v[i] + step * t[i]);
        // The predictor's error is second order in the step: a first correction larger
        // than a tenth of the step means the predictor has left the sheet it was on.
        let first = 0.1 * step * sup(&t) + 1e-9 * (1.0 + sup(&v));
        match correct(sys, pred, &at(next), first, 8) {
            Some((w, det)) if det * det0 > 0.0 => {
                v = w;
                lambda = next;
                min_ratio = min_ratio.min((det / det0).abs());
                h = (2.0 * h).min(h_max);
            }
            Some((_, det)) if h <= 1e-3 * h_max || det == 0.0 => {
                // det B changed sign over a short step: the segment crosses a singularity.
                return stopped(v, lambda, 0.0, sup(&t), false);
            }
            _ => {
                h *= 0.25;
                if h < 1e-12 {
                    // No nearby solution ahead: a fold, or a near miss that natural-parameter
                    // steps cannot pass. Arc-length steps decide.
                    passes += 1;
                    let beyond = (lambda + 1e-6).min(1.0);
                    match pass(sys, (x0, &dx), det0, &v, lambda, &t, beyond) {
                        Pass::Beyond(w) if passes <= 100 => {
                            let r = (det(sys, &w, &at(beyond)) / det0).abs();
                            min_ratio = min_ratio.min(r);
                            (v, lambda, h) = (w, beyond, h_max);
                        }
                        Pass::Turned => return stopped(v, lambda, 0.0, sup(&t), false),
                        _ => return stopped(v, lambda, min_ratio, sup(&t), true),
                    }
                }
            }
        }
    }
    // Polish at the end to full precision.
    if let Some((w, _)) = correct(sys, v, x1, f64::INFINITY, 30) {
        v = w;
    }
    Truth {
        v,
        reached: true,
        lambda: 1.0,
        min_ratio,
        sensitivity: sensitivity(sys, &v, x1),
        remaining: 0.0,
        reach: 0.0,
        stuck: false,
    }
}

/// Whether the branch from `(v0, x0)` reaches a point at `x1` that `accepts` through a
/// waypoint off the straight segment: the two segments `x0 → w → x1` for each of `tries`
/// waypoints `w = (x0 + x1) / 2 + d e` (e a direction of unit largest entry, d from a tenth to
/// ten times the segment's span, both drawn from `rng`), each followed by [`follow_segment`].
/// A path that reaches `x1` is nonsingular, so its end is on the branch as surely as the
/// straight segment's would be (where paths around a cusp reach different points, each is).
/// For a straight segment that leaves the branch's region and comes back within a step too
/// short for a solver to see (a graze of a fold surface): the point there is the branch's,
/// but the straight segment is not the path that shows it.
pub fn reached_via<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (v0, x0): (&[f64; N], &[f64; M]),
    det0: f64,
    x1: &[f64; M],
    max_step: f64,
    (tries, rng): (usize, &mut linkage_tests::Rng),
    accepts: impl Fn(&Truth<N>) -> bool,
) -> bool {
    let span = sup(&std::array::from_fn::<f64, M, _>(|j| x1[j] - x0[j]));
    for k in 0..tries {
        let d = [0.1, 0.3, 1.0, 3.0, 10.0][k % 5] * span;
        let e: [f64; M] = std::array::from_fn(|_| rng.symmetric());
        let size = sup(&e);
        if !(size > 0.0) {
            continue;
        }
        let w: [f64; M] = std::array::from_fn(|j| 0.5 * (x0[j] + x1[j]) + d * e[j] / size);
        let first = follow_segment(sys, (v0, x0), det0, &w, max_step);
        if !first.reached {
            continue;
        }
        let second = follow_segment(sys, (&first.v, &w), det0, x1, max_step);
        if second.reached && accepts(&second) {
            return true;
        }
    }
    false
}

impl<const N: usize> Truth<N> {
    /// Stopped so near the end that the end may lie within rounding of a fold: within 1e-6 of
    /// the segment, or 1e-7 of the inputs' size (a fold's place is known to about √ε of the
    /// size, 1.5e-8, since v moves as the square root of the distance to it; and a target whose
    /// pose is δ from a singular surface has legs O(δ²) from the workspace boundary).
    pub fn near_end(&self, x_size: f64) -> bool {
        !self.reached && (1.0 - self.lambda <= 1e-6 || self.remaining <= 1e-7 * x_size)
    }

    /// Neither reached nor shown to meet a singularity before the end.
    pub fn undecided(&self, x_size: f64) -> bool {
        !self.reached && (self.stuck || self.near_end(x_size))
    }

    /// Whether `v`, from a solve with `tolerance` at inputs of size `x_size`, is this branch's
    /// point at the end: the end's truth when reached; when stopped near the end, within
    /// `reach` of where it stopped.
    pub fn allows(&self, v: &[f64; N], tolerance: f64, x_size: f64) -> bool {
        let v_size = sup(&self.v);
        if self.reached {
            distance(v, &self.v) <= agreement(tolerance, self.sensitivity, x_size, v_size)
        } else {
            self.near_end(x_size)
                && distance(v, &self.v) <= self.reach + agreement(tolerance, 0.0, x_size, v_size)
        }
    }
}

/// Largest coordinate difference between two points.
pub fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max)
}

/// How far an ok result may lie from the truth and still be the truth: ten times the tolerance
/// (the error estimate is first order), plus what rounding the inputs at the truth can move it
/// (`sensitivity` · 1e-13 · |x|), plus rounding in v itself.
pub fn agreement(tolerance: f64, sensitivity: f64, x_size: f64, v_size: f64) -> f64 {
    10.0 * tolerance + 1e-13 * x_size * sensitivity.min(1e9) + 1e-12 * v_size
}
