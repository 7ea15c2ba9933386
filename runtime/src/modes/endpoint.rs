//! From a tracked path to a classified endpoint, and from a real endpoint to an assembly mode.

use super::complex::Complex;
use super::polish::polish;
use super::roots::{Endpoint, EndpointKind};
use super::track::{Model, Outcome, Tracked, Workspace};
use crate::lu::Lu;
use crate::mechanism::Mechanism;

/// A path that stops this close to the target without reaching it is taken to approach a
/// singular endpoint.
const NEAR_TARGET: f64 = 1e-6;

/// Coordinates whose imaginary parts are all below this (weighted) are real.
const REAL_TOL: f64 = 1e-7;

/// Beyond this size (in units of the scale) an endpoint that is not a regular root (a path
/// that stalled, or ended where Newton converges only slowly) counts as at infinity.
const AT_INFINITY: f64 = 1e8;

/// Beyond this size a root that Newton polished as regular (in f64 or, far out, double-double)
/// counts as at infinity. A regular point at infinity polishes to |w| near 10⁻¹⁶ (sizes of
/// 10¹⁶), so roots at 10⁸–10¹² are told apart from it; a delta robot with two crank angles a
/// few thousandths of a radian apart has roots there.
const REGULAR_AT_INFINITY: f64 = 1e12;

/// Classifies the end of a path tracked to the target `p` (a finite or singular root, a
/// diverging path, a failure), polishing finite roots to full precision. `z` is the endpoint in
/// tracking coordinates; the endpoint reports v.
pub(crate) fn classify<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    p: &[Complex; M],
    tracked: &Tracked,
    z: &[Complex; N],
    ws: &mut Workspace<N>,
) -> Endpoint<N> {
    let mut e = Endpoint {
        v: model.leave(z),
        z: *z,
        kind: EndpointKind::Failed,
        steps: tracked.steps,
        residual: f64::NAN,
        nearest: f64::INFINITY,
        pivot_ratio: 0.0,
    };
    match tracked.outcome {
        Outcome::Reached => {
            let mut polished = *z;
            if polish(model, &mut polished, p, ws, true) {
                e.v = model.leave(&polished);
                e.z = polished;
                e.kind = if !(model.size(&polished) <= REGULAR_AT_INFINITY) {
                    EndpointKind::Diverging
                } else if is_real(model, &e.v) {
                    EndpointKind::Real
                } else {
                    EndpointKind::Complex
                };
            } else {
                e.kind = if model.size(z) <= AT_INFINITY {
                    EndpointKind::Singular
                } else {
                    EndpointKind::Diverging
                };
            }
        }
        Outcome::Diverged => e.kind = EndpointKind::Diverging,
        Outcome::Singular | Outcome::StepTooSmall | Outcome::TooManySteps => {
            if tracked.s >= 1.0 - NEAR_TARGET {
                e.kind = if model.size(z) <= AT_INFINITY {
                    EndpointKind::Singular
                } else {
                    EndpointKind::Diverging
                };
            }
        }
    }
    if e.kind != EndpointKind::Diverging && e.v.iter().all(|c| c.is_finite()) {
        let mut f = [Complex::ZERO; N];
        model.sys.residual_in(&e.v, p, &mut f);
        e.residual = f.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        // B itself, not the projective Jacobian: what a user means by "near singular". In
        // affine coordinates polishing left it factored at (or next to) the root.
        let polished = matches!(e.kind, EndpointKind::Real | EndpointKind::Complex);
        let (values, lu) = ws.scratch();
        e.pivot_ratio = if model.chart.is_none() && polished {
            lu.pivot_ratio()
        } else {
            let affine = Model {
                chart: None,
                ..*model
            };
            if affine.factor(&e.v, p, values, lu) {
                lu.pivot_ratio()
            } else {
                0.0
            }
        };
    }
    e
}

fn is_real<S, const N: usize>(model: &Model<'_, S, N>, v: &[Complex; N]) -> bool {
    (0..N).all(|i| v[i].im.abs() <= REAL_TOL * model.scale.max(v[i].abs_max()))
}

/// Newton's method in real arithmetic from the real parts of a real endpoint; the refined
/// root, its residual max |Fᵢ| and det B, or `None` if it does not converge close by.
pub(crate) fn real_root<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    scale: f64,
    v: &[Complex; N],
    x: &[f64; M],
) -> Option<([f64; N], f64, f64)> {
    let start = v.map(|c| c.re);
    let mut w = start;
    let mut f = [0.0; N];
    // The generated elimination (fast) and its det B; the dense LU where it declines (its
    // static pivots can meet an exact zero that partial pivoting avoids).
    let mut fac = sys.new_factor();
    let mut converged = false;
    let mut last = f64::INFINITY;
    for _ in 0..8 {
        sys.residual(&w, x, &mut f);
        if sys.factor(&w, x, &mut fac).is_some() {
            sys.solve(&fac, &mut f);
        } else {
            let mut b = [[0.0; N]; N];
            sys.jacobian_dense(&w, x, &mut b);
            Lu::new(b)?.solve(&mut f);
        }
        let mut size = 0.0f64;
        for i in 0..N {
            w[i] -= f[i];
            size = size.max(f[i].abs() / scale.max(w[i].abs()));
        }
        if !size.is_finite() {
            return None;
        }
        last = size;
        if size <= 1e-14 {
            converged = true;
            break;
        }
    }
    // Next to another real root (near a fold) rounding stops the corrections above 1e-14;
    // a last one below 1e-11 (of the scale) still places the root far more precisely than any
    // two roots are apart.
    converged |= last <= 1e-11;
    let moved = (0..N)
        .map(|i| (w[i] - start[i]).abs() / scale.max(w[i].abs()))
        .fold(0.0f64, f64::max);
    // Rounding may keep the last correction just above 1e-14; a small move is what counts.
    if !(moved <= 1e-6) || !(converged || moved <= 1e-9) {
        return None;
    }
    sys.residual(&w, x, &mut f);
    let residual = f.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    let det = match sys.factor(&w, x, &mut fac) {
        Some(factored) => factored.det,
        None => crate::correction::det_b(sys, &w, x),
    };
    Some((w, residual, det))
}

/// Euclidean distance between two complex points.
pub(crate) fn distance<const N: usize>(a: &[Complex; N], b: &[Complex; N]) -> f64 {
    crate::math::sqrt((0..N).map(|i| (a[i] - b[i]).norm_sqr()).sum::<f64>())
}
