//! A root made exact at fixed parameters, and when two roots are one: Newton to full precision
//! (with the rounding floor of far-out, ill-conditioned roots), and the identity test in
//! tracking coordinates. Shared by monodromy, the seeding, the symmetries, the refill and the
//! queries' endpoints.

use super::complex::Complex;
use super::extended::WIDE_BEYOND;
use super::track::{Model, Workspace};
use crate::mechanism::Mechanism;

/// Newton at fixed parameters to full precision. `true` if it converges as at a nonsingular
/// root: the correction falls below 1e-13 (weighted), or it stalls at the floor rounding sets
/// for an ill-conditioned root (below [`FLOOR`]) after contracting quadratically or starting
/// there.
/// At a singular root Newton converges only linearly (ratio ½ at a double root) from the path
/// accuracy, and this is `false`.
///
/// `factored`: `ws` already holds a factorisation of the Jacobian near `v` at `p` (the
/// tracker's last step leaves one at its predicted point), used until the corrections stop
/// contracting fast.
///
/// Far out (beyond [`WIDE_BEYOND`] times the scale), where the floor of f64 can lie above
/// [`FLOOR`],
/// a failure is tried again with the residual in double-double (`extended.rs`).
pub(crate) fn polish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    v: &mut [Complex; N],
    p: &[Complex; M],
    ws: &mut Workspace<N>,
    factored: bool,
) -> bool {
    let from = *v;
    if newton(model, v, p, ws, factored, false) {
        return true;
    }
    if !(model.size(&from) > WIDE_BEYOND) {
        return false;
    }
    *v = from;
    newton(model, v, p, ws, false, true)
}

fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    v: &mut [Complex; N],
    p: &[Complex; M],
    ws: &mut Workspace<N>,
    factored: bool,
    wide: bool,
) -> bool {
    let (values, lu) = ws.scratch();
    let mut previous = f64::INFINITY;
    let mut fast = false;
    // The factorisation is kept while the corrections contract fast (the chord method); from
    // the path accuracy one factorisation usually does.
    let mut refactor = !factored;
    for it in 0..10 {
        if refactor && !model.factor(v, p, values, lu) {
            return false;
        }
        let d = if wide {
            model.newton_wide(lu, v, p)
        } else {
            model.newton(lu, v, p)
        };
        let n = model.norm(&d, v);
        if !n.is_finite() {
            return false;
        }
        // Converged as at a nonsingular root: below the rounding floor of most roots at once,
        // or below POLISHED after a fast contraction (going on would end at the floor, true
        // all the same, after more factorisations).
        if n <= 1e-13 || ((fast || it == 0) && n <= POLISHED) {
            for i in 0..N {
                v[i] += d[i];
            }
            return true;
        }
        if n >= 0.5 * previous {
            if !refactor {
                // Stalled with an old factorisation: refresh it before judging.
                refactor = true;
                continue;
            }
            // No progress: the rounding floor (keep the previous iterate) or a singular root.
            return fast && previous <= FLOOR;
        }
        fast |= (it == 0 && n <= 1e-11) || n < 0.1 * previous;
        refactor = n > 0.1 * previous;
        for i in 0..N {
            v[i] += d[i];
        }
        previous = n;
    }
    fast && previous <= FLOOR
}

/// A correction this small after a fast contraction ends [`polish`]: the root to about 1e-11
/// of the scale, far below what tells roots apart ([`SAME`]); real roots are refined again in
/// real arithmetic.
pub(crate) const POLISHED: f64 = 1e-11;

/// The largest rounding floor [`polish`] accepts (weighted): roots 10⁶ times the mechanism's
/// size away, which a general 6-6 platform can have, stall near 1e-7 in double precision.
pub(crate) const FLOOR: f64 = 1e-6;

/// Two roots closer than this (weighted, in tracking coordinates) are one: ten times the worst
/// accuracy [`polish`] accepts, and far below the distance between distinct roots at a generic
/// parameter point.
pub(crate) const SAME: f64 = 1e-5;

/// Whether `v` is within `tol` (weighted) of one of `known`.
pub(crate) fn contains<S, const N: usize>(
    model: &Model<'_, S, N>,
    known: &[[Complex; N]],
    v: &[Complex; N],
    tol: f64,
) -> bool {
    // The weighted norm of v − w, without divisions and stopping at the first coordinate
    // that differs (most do).
    known
        .iter()
        .any(|w| (0..N).all(|i| (v[i] - w[i]).abs_max() <= tol * model.scale.max(w[i].abs_max())))
}
