//! Going around a fold: when the straight joint-space segment leaves the valid joint space,
//! try to reach the target along a two-segment path that bends away from the singular surface.
//!
//! At the last point before the fold, B is nearly singular; its left null vector w (wᵀB ≈ 0,
//! found by inverse iteration) gives the singular surface's normal in joint space,
//! n = (∂F/∂x)ᵀ w, since along the surface wᵀ(B dv + (∂F/∂x) dx) = 0 forces n·dx ≈ 0. The
//! detour leaves the straight segment a little before that point (solved afresh: the last
//! point before a fold is where continuation's steps are least sure), steps toward an offset
//! from it along ±n, to the side the straight segment came from, then heads for the target.
//! Every segment is pseudo-arc-length continuation, which refuses to pass a fold, so whatever
//! is reached is connected to the start by a nonsingular path: it is on the start's branch. It is the valid solution for a machine that moves along that path (see the
//! README on path dependence).

use crate::arc_length::{arc_length, from_accepted};
use crate::correction::det_b;
use crate::lu::Lu;
use crate::math::norm;
use crate::mechanism::Mechanism;
use crate::solution::{Options, Solution, SolveError, Status};
use crate::start::Start;

/// How far back from the last point before the fold (a share of the way to it) the detour
/// leaves the straight segment.
const BACK_OFF: f64 = 1e-3;

/// A solve that may have gone around a fold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Detoured<const N: usize, const M: usize> {
    /// The solve's result at the target, whichever way it went.
    pub solution: Solution<N>,
    /// The waypoint of the detour, if the straight segment was not the way: the solution is
    /// then the detour's, `Converged` or, where rounding near the singular surface stopped the
    /// last Newton run short of the tolerance, `ToleranceNotMet`.
    pub via: Option<[f64; M]>,
    /// Where the detour left the straight segment (a thousandth of the way back from the last
    /// point continuation accepted before the fold): the path taken is start → `left_at` →
    /// `via` → target.
    pub left_at: Option<[f64; M]>,
}

/// The joint-space normal of the singular surface near (v, x), unit length.
fn surface_normal<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Option<[f64; M]> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let lu = Lu::new(b)?;
    let mut w = [1.0; N];
    for _ in 0..3 {
        lu.solve_transposed(&mut w);
        let nw = norm(&w);
        if !(nw > 0.0 && nw.is_finite()) {
            return None;
        }
        w.iter_mut().for_each(|x| *x /= nw);
    }
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(v, x, &mut a);
    let mut n = [0.0; M];
    for j in 0..M {
        n[j] = (0..N).map(|i| w[i] * a[i][j]).sum();
    }
    let nn = norm(&n);
    (nn > 0.0 && nn.is_finite()).then(|| n.map(|c| c / nn))
}

/// [`arc_length`], and where the straight segment ends in a fold, detours through waypoints
/// offset from the fold along the singular surface's normal by 10 %, 25 %, 50 % and 100 % of
/// the remaining distance. The first detour that converges is taken; failing that, one that
/// reached the target short of the tolerance; failing that, the straight segment's result.
pub fn arc_length_detour<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Detoured<N, M>, SolveError> {
    let straight = arc_length(sys, start, target, options)?;
    let Status::Fold { lambda } = straight.status else {
        return Ok(Detoured {
            solution: straight,
            via: None,
            left_at: None,
        });
    };
    // The last accepted point before the fold, on the start's branch.
    let l = straight.lambda.min(lambda);
    let x0 = start.x();
    let x_fold: [f64; M] = core::array::from_fn(|j| x0[j] + l * (target[j] - x0[j]));
    let Some(n) = surface_normal(sys, &straight.v, &x_fold) else {
        return Ok(Detoured {
            solution: straight,
            via: None,
            left_at: None,
        });
    };
    let dx: [f64; M] = core::array::from_fn(|j| target[j] - x0[j]);
    // Inward: against the direction in which the straight segment approached the surface.
    let side = if (0..M).map(|j| n[j] * dx[j]).sum::<f64>() > 0.0 {
        -1.0
    } else {
        1.0
    };
    let remaining: f64 = norm(&core::array::from_fn::<f64, M, _>(|j| {
        target[j] - x_fold[j]
    }));
    // The corner the detour leaves from: not the last point continuation accepted before the
    // fold, which may lie just past a singularity next to it (PH stepped over one, det B of
    // the start's sign again, in the stress suite's
    // `known_cases_detour_from_past_a_singularity`), but a point solved afresh a thousandth of
    // the way back, short of what the straight segment met. It must be reached, with det B of
    // the start's sign.
    let l_back = l * (1.0 - BACK_OFF);
    let x_back: [f64; M] = core::array::from_fn(|j| x0[j] + l_back * dx[j]);
    let Some((back, det_here)) = arc_length(sys, start, &x_back, options)
        .ok()
        .map(|back| (back, det_b(sys, &back.v, &x_back)))
        .filter(|(back, det)| back.is_ok() && det * start.det() > 0.0)
    else {
        return Ok(Detoured {
            solution: straight,
            via: None,
            left_at: None,
        });
    };
    let here = Start::accepted(back.v, x_back, det_here, *start.floor());
    let mut near = None;
    for share in [0.1, 0.25, 0.5, 1.0] {
        let via: [f64; M] = core::array::from_fn(|j| x_fold[j] + side * share * remaining * n[j]);
        if sys.validate_inputs(&via).is_err() {
            continue;
        }
        let Ok(first) = from_accepted(sys, &here, &via, options) else {
            continue;
        };
        // The waypoint only leads on: reached by continuation, on the branch (det B checked
        // below), it serves even where rounding near the singular surface stopped its final
        // Newton run just short of the tolerance.
        if !(first.is_ok() || matches!(first.status, Status::ToleranceNotMet { .. })) {
            continue;
        }
        let det_mid = det_b(sys, &first.v, &via);
        if !(det_mid * start.det() > 0.0) {
            continue;
        }
        let mid = Start::accepted(first.v, via, det_mid, *start.floor());
        let Ok(second) = from_accepted(sys, &mid, target, options) else {
            continue;
        };
        if second.is_ok() || matches!(second.status, Status::ToleranceNotMet { .. }) {
            let solution = Solution {
                steps_accepted: straight.steps_accepted
                    + back.steps_accepted
                    + first.steps_accepted
                    + second.steps_accepted,
                steps_rejected: straight.steps_rejected
                    + back.steps_rejected
                    + first.steps_rejected
                    + second.steps_rejected,
                newton_iterations: straight.newton_iterations
                    + back.newton_iterations
                    + first.newton_iterations
                    + second.newton_iterations,
                // Each leg's ratios are to det B at its own start; the straight segment went
                // on past the corner, which is not the path taken.
                min_det_ratio: back
                    .min_det_ratio
                    .min(first.min_det_ratio * (det_here / start.det()).abs())
                    .min(second.min_det_ratio * (det_mid / start.det()).abs()),
                ..second
            };
            let detoured = Detoured {
                solution,
                via: Some(via),
                left_at: Some(x_back),
            };
            if second.is_ok() {
                return Ok(detoured);
            }
            // Reached, but short of the tolerance: better than the fold unless a wider detour
            // meets it.
            near.get_or_insert(detoured);
        }
    }
    Ok(near.unwrap_or(Detoured {
        solution: straight,
        via: None,
        left_at: None,
    }))
}
