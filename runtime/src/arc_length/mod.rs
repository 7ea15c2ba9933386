//! Pseudo-arc-length homotopy continuation (the paper's PH, Eqs. 6–12), made robust.
//!
//! The homotopy H(v, λ) = F(v, x0 + λ(x* − x0)) (Eq. 6) is tracked in `y = (v, μ)` with
//! μ = λ‖x* − x0‖, so that λ moves as much as the millimetre-sized v. Each step:
//! - predicts along the unit tangent (Eq. 12), the tangent's orientation kept by the bordered
//!   system whose last row is the previous tangent (Eq. 9);
//! - corrects on `[H(y); t·(y − y_pred)] = 0` (Keller's constraint, Eq. 8 as corrected in
//!   ERRATA.md) with the bordered matrix of Eq. 10 taken at the last accepted point — the
//!   chord iteration of Eq. 11 — solved by bordering on the generated factorisation of B;
//! - **accepts the step only if the corrector contracts fast**: the first correction must be
//!   small against the step and each next one at most a quarter of the previous. A corrector
//!   that would slide onto a neighbouring branch fails this test and the step is halved;
//! - rejects a step that turns the tangent by more than ~37°;
//! - keeps a step within twice the distance to det B = 0 extrapolated from the last chord,
//!   where |det B| falls, and rejects a step over which the parabola through the last three
//!   values of det B dips across zero: two folds close together leave det B of one sign at
//!   both ends of a step that passes both (an S-shaped segment, found by the stress suite);
//! - watches the sign of det B: it flips exactly where λ turns back (a fold). A fold means the
//!   straight joint-space path leaves the valid joint space, and the curve beyond it belongs to
//!   another assembly mode, so the solve stops there with [`Status::Fold`].
//!
//! Near a fold B is nearly singular and bordering on it loses accuracy; there the step falls
//! back to a dense LU of the whole bordered matrix, which stays regular through the fold. The
//! last step lands on λ = 1 exactly (a step whose corrector ends past it is taken again as
//! that last step), and Newton's method polishes the result to the requested tolerance by the
//! final rule every solver shares.
//!
//! Here is the step loop; `path` holds the path's points and H, `step` the step control and
//! the predictor, `corrector` the corrector and `bordered` the bordered solves both use.

mod bordered;
mod corrector;
mod path;
mod step;

use crate::convergence::Contraction;
use crate::correction::det_b;
use crate::math::norm;
use crate::mechanism::Mechanism;
use crate::newton::{Rule, newton};
use crate::outcome::{Account, conclude, finish};
use crate::solution::{Options, Solution, SolveError, Status};
use crate::start::Start;
use path::{Path, Point, Tangent, dot, first_order_travel};
use step::{Previous, StepControl, det_dips};

/// Below this cosine between successive tangents (about 37°) a step is rejected.
const MIN_TANGENT_COS: f64 = 0.8;
/// A last step of at most this many times the path's accuracy is Newton's at λ = 1 rather
/// than a corrector's: the corrector passes a point in error by up to the accuracy only on a
/// step of at least [`Contraction::SHORTEST_STEP_PER_ERROR`] times it (2), and twice that
/// leaves room for the predictor's own error (4).
const LAST_STEP_IN_TOL: f64 = 2.0 * Contraction::SHORTEST_STEP_PER_ERROR;
/// How far behind the start, as a share of the path's length, det B is taken to see its slope
/// before the first step (a thousandth of the first step, a quarter of the path).
const FIRST_PROBE: f64 = 2.5e-4;

/// Solves F(v, x*) = 0 by pseudo-arc-length continuation from the start along the straight
/// joint-space segment, stopping with [`Status::Fold`] where that segment leaves the valid
/// joint space.
///
/// ```
/// use linkage::{arc_length, Mechanism, Options, Status};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// # let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// # let start = linkage::Start::new(&rps, v0, x0).unwrap();
/// // `start`: a 3-RPS at its home pose, legs ≈ 158 mm (see the crate docs for the declaration).
/// let sol = arc_length(&rps, &start, &[170.0, 150.0, 160.0], &Options::TIGHT).unwrap();
/// assert_eq!(sol.status, Status::Converged);
/// assert!(sol.error_estimate < 1e-9 && sol.lambda == 1.0);
/// // Legs no platform pose can take: the path meets the workspace boundary, a fold.
/// let far = arc_length(&rps, &start, &[400.0, 60.0, 158.0], &Options::TIGHT).unwrap();
/// assert!(!far.is_ok() && far.lambda < 1.0);
/// ```
pub fn arc_length<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    from(sys, start, target, options, true)
}

/// [`arc_length`] from a point the crate accepted itself ([`Start::accepted`]: a tracked
/// sample, a detour's waypoint), whose consistency its acceptance showed to the caller's own
/// tolerance: not measured again.
pub(crate) fn from_accepted<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    from(sys, start, target, options, false)
}

fn from<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
    check_start: bool,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, start, target, options)?;
    let mut dx = [0.0; M];
    for j in 0..M {
        dx[j] = target[j] - start.x()[j];
    }
    // Scale λ by how far v moves over the whole path to first order, ‖B⁻¹(∂F/∂x)(x* − x0)‖,
    // so that λ and v weigh alike in the arc length whatever the inputs' units (mm, rad).
    // With the start's consistency: the factorisation is made here anyway.
    let length = first_order_travel(sys, start, &dx, check_start)?.unwrap_or_else(|| norm(&dx));
    let size = norm(start.v());
    let scale = crate::math::scale_or_one(size.max(length));
    let path = Path {
        sys,
        start,
        dx,
        length,
        tol: 1e-6 * scale,
        fine: 1e-6 * crate::math::scale_or_one(size).min(scale),
        linear: options.linear,
    };
    // A path shorter than the accuracy its points are computed to (a target within rounding of
    // the start, such as home legs printed as 170.00000000000003) has nothing for continuation
    // to resolve: its steps would fall below the resolution of v. The target's root is within
    // the corrector's tolerance of the start, so the final Newton run is the whole path, as it
    // is the last step of every longer one.
    if !(length > path.tol) {
        return Ok(polish(
            sys,
            start,
            *start.v(),
            target,
            options,
            Account::at(1.0),
        ));
    }
    let mut p = Point {
        v: *start.v(),
        mu: 0.0,
    };
    let e_mu = Tangent {
        v: [0.0; N],
        mu: 1.0,
    };
    let mut frame = path.frame(&p);
    let Some(first) = path.tangent(&p, &e_mu, frame.as_ref()) else {
        return Ok(finish(
            sys,
            start,
            p.v,
            start.x(),
            Status::Singular { lambda: 0.0 },
            Account::at(0.0),
        ));
    };
    let mut t = first.tangent;
    let mut dense = path.dense_frame(&p, &t, frame.as_ref());
    let mut det_prev = start.det();
    let mut previous: Option<Previous<N>> = None;
    let mut control = StepControl::new(length);
    // The first step has no earlier point to show det B heading for zero. det B a short way
    // behind the start along the tangent stands in for one (one determinant more per solve),
    // so that the first step too goes at most twice as far as det B = 0 lies by linear
    // extrapolation, and the parabola test sees a dip within it. Without it a first step of a
    // quarter of the segment, from a point near a singularity (a tracked sample the tracker
    // hands to continuation), went over two sign changes of det B and answered Converged
    // (the linear delta, found by the third hunt).
    let behind = {
        let chord = FIRST_PROBE * length;
        let mut v = p.v;
        for i in 0..N {
            v[i] -= chord * t.v[i];
        }
        let x = path.x(-chord * t.mu);
        // The generated factorisation's determinant (a tenth of a dense LU's work), the dense
        // one where it declines or the dense baseline was asked for.
        let mut factor = sys.new_factor();
        let generated = match options.linear {
            crate::solution::Linear::Dense => None,
            crate::solution::Linear::Generated => {
                sys.factor(&v, &x, &mut factor).map(|info| info.det)
            }
        };
        (generated.unwrap_or_else(|| det_b(sys, &v, &x)), chord)
    };
    control.toward_singularity(behind.0, behind.1, det_prev);
    let mut account = Account::at(0.0);
    // Ends the solve at the last accepted point `p`.
    let stop = |p: &Point<N>, status, account: Account| {
        let x = path.x(p.mu);
        let account = Account {
            lambda: path.lambda(p),
            ..account
        };
        Ok(finish(sys, start, p.v, &x, status, account))
    };
    while account.accepted + account.rejected < options.max_steps {
        let step = control.next(length, &p, &t, previous.as_ref());
        // A last step within a few times the accuracy the path's points are computed to (the
        // step before ended that near λ = 1) has nothing for continuation to resolve, as a
        // path that short has not: the final Newton run is the step. Its corrector would
        // measure the accepted point's own error (up to `path.tol`) against a first correction
        // allowed only half the step, and refuse it, and every shorter step after it (seen: a
        // last step of 4.7e-4 on a path whose points are computed to 3.2, refused at λ = 1 −
        // 1.5e-10; and one of 0.334 on a path computed to 0.303, left by a step that stopped
        // that short of the end, refused at λ = 1 − 1.1e-6, both with StepTooSmall).
        if step.end && !(step.length > LAST_STEP_IN_TOL * path.tol) {
            account.lambda = 1.0;
            return Ok(polish(sys, start, p.v, target, options, account));
        }
        let corrected = path.correct(
            &step.predicted,
            &t,
            step.end,
            step.length,
            frame.as_ref(),
            dense.as_ref(),
        );
        match corrected {
            // A step that is not the last may still end past λ = 1: the corrector moves μ too.
            // Land on λ = 1 from p instead (the next step is the last, and shorter).
            Ok(c) if !step.end && c.point.mu > length => {
                account.iterations += c.iterations;
                account.rejected += 1;
                control.overshot(&step, &t);
            }
            Ok(c) => {
                account.iterations += c.iterations;
                let q = c.point;
                let next_frame = path.frame(&q);
                let Some(next) = path.tangent(&q, &t, next_frame.as_ref()) else {
                    let status = Status::Singular {
                        lambda: path.lambda(&p),
                    };
                    return stop(&p, status, account);
                };
                let t1 = next.tangent;
                if next.det * det_prev <= 0.0 {
                    // det B changed sign between p and q: the curve passes a fold (λ turns
                    // back) or a singular point. Either way the branch ends here.
                    let status = Status::Fold {
                        lambda: p.mu.max(q.mu) / length,
                    };
                    let account = Account {
                        min_det_ratio: 0.0,
                        ..account
                    };
                    return stop(&p, status, account);
                }
                let chord = crate::math::sqrt(
                    (0..N)
                        .map(|i| (q.v[i] - p.v[i]) * (q.v[i] - p.v[i]))
                        .sum::<f64>()
                        + (q.mu - p.mu) * (q.mu - p.mu),
                );
                // det B of one sign at both ends may still hide two folds in between: where
                // the parabola through the last three values of det B dips across zero within
                // the step, take a shorter one.
                let (d0, c0) = previous.as_ref().map_or(behind, |pr| (pr.det, pr.chord));
                let dips = det_dips(d0, c0, det_prev, chord, next.det);
                if dips || (dot(&t.v, &t1.v) + t.mu * t1.mu < MIN_TANGENT_COS && !step.end) {
                    account.rejected += 1;
                    control.turned(&step);
                } else {
                    account.accepted += 1;
                    previous = Some(Previous {
                        point: p,
                        tangent: t,
                        chord,
                        det: det_prev,
                    });
                    p = q;
                    t = t1;
                    frame = next_frame;
                    dense = path.dense_frame(&p, &t, frame.as_ref());
                    det_prev = next.det;
                    account.min_det_ratio =
                        account.min_det_ratio.min((next.det / start.det()).abs());
                    if step.end {
                        account.lambda = 1.0;
                        return Ok(polish(sys, start, p.v, target, options, account));
                    }
                    control.accepted(&step, c.first, c.iterations);
                    if let Some(prev) = previous.as_ref() {
                        control.toward_singularity(prev.det, prev.chord, det_prev);
                    }
                }
            }
            Err(iterations) => {
                account.iterations += iterations;
                account.rejected += 1;
                control.failed(&step);
            }
        }
        if control.too_small() {
            let status = Status::StepTooSmall {
                lambda: path.lambda(&p),
            };
            return stop(&p, status, account);
        }
    }
    let status = Status::StepTooSmall {
        lambda: path.lambda(&p),
    };
    stop(&p, status, account)
}

/// Newton at λ = 1 down to the requested tolerance.
fn polish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    v: [f64; N],
    x: &[f64; M],
    options: &Options,
    mut account: Account,
) -> Solution<N> {
    let run = newton(sys, v, x, options, Rule::Final);
    account.iterations += run.iterations;
    conclude(sys, start, &run, x, options.tolerance, false, account)
}
