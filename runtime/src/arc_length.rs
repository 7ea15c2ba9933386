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
//! - watches the sign of det B: it flips exactly where λ turns back (a fold). A fold means the
//!   straight joint-space path leaves the valid joint space, and the curve beyond it belongs to
//!   another assembly mode, so the solve stops there with [`Status::Fold`].
//!
//! Near a fold B is nearly singular and bordering on it loses accuracy; there the step falls
//! back to a dense LU of the whole bordered matrix, which stays regular through the fold. The
//! last step lands on λ = 1 exactly (a step whose corrector ends past it is taken again as
//! that last step), and Newton's method polishes the result to the requested tolerance by the
//! final rule every solver shares.

use crate::convergence::Contraction;
use crate::correction::{newton, Rule};
use crate::lu::{Bordered, BorderedLu, Extended, Lu};
use crate::math::norm;
use crate::outcome::{conclude, finish, Account};
use crate::{Linear, Mechanism, Options, Solution, SolveError, Start, Status};

const MAX_CORRECTOR: usize = 5;
const MIN_TANGENT_COS: f64 = 0.8;
/// Below this pivot ratio the generated factorisation is not trusted for bordering.
const MIN_PIVOT_RATIO: f64 = 1e-10;

struct Path<'a, S, const N: usize, const M: usize> {
    sys: &'a S,
    start: &'a Start<N, M>,
    dx: [f64; M],
    length: f64,
    tol: f64,
    linear: Linear,
}

#[derive(Clone, Copy)]
struct Point<const N: usize> {
    v: [f64; N],
    mu: f64,
}

#[derive(Clone, Copy)]
struct Tangent<const N: usize> {
    v: [f64; N],
    mu: f64,
}

/// B and H_μ at an accepted point, factored: what the next corrector and tangent reuse.
struct Frame<F, const N: usize> {
    factor: F,
    det: f64,
    /// B⁻¹ H_μ, with H_μ = (∂F/∂x)(x* − x0)/‖x* − x0‖.
    y2: [f64; N],
}

fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter().zip(b).map(|(p, q)| p * q).sum()
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    fn x(&self, mu: f64) -> [f64; M] {
        let l = mu / self.length;
        let mut x = [0.0; M];
        for j in 0..M {
            x[j] = self.start.x()[j] + l * self.dx[j];
        }
        x
    }

    fn residual(&self, p: &Point<N>) -> [f64; N] {
        let mut f = [0.0; N];
        self.sys.residual(&p.v, &self.x(p.mu), &mut f);
        f
    }

    fn column(&self, p: &Point<N>) -> [f64; N] {
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(&p.v, &self.x(p.mu), &mut a);
        let mut c = [0.0; N];
        for i in 0..N {
            c[i] = (0..M).map(|j| a[i][j] * self.dx[j]).sum::<f64>() / self.length;
        }
        c
    }

    /// The generated factorisation at `p`, if it is trustworthy for bordering.
    fn frame(&self, p: &Point<N>) -> Option<Frame<S::Factor, N>> {
        if self.linear == Linear::Dense {
            return None;
        }
        let mut factor = self.sys.new_factor();
        let info = self.sys.factor(&p.v, &self.x(p.mu), &mut factor)?;
        if !(info.pivot_ratio > MIN_PIVOT_RATIO) {
            return None;
        }
        let column = self.column(p);
        let mut y2 = column;
        self.sys.solve(&factor, &mut y2);
        Some(Frame {
            factor,
            det: info.det,
            y2,
        })
    }

    /// The dense bordered matrix `[[B, H_μ], [rowᵀ]]` at `p`, and H at `p`.
    fn bordered(&self, p: &Point<N>, row: &Tangent<N>) -> ([f64; N], Bordered<N>) {
        let x = self.x(p.mu);
        let f = self.residual(p);
        let mut m = Bordered {
            block: [[0.0; N]; N],
            column: self.column(p),
            row: row.v,
            corner: row.mu,
        };
        self.sys.jacobian_dense(&p.v, &x, &mut m.block);
        (f, m)
    }

    /// Solves `[[B, c], [rᵀ, d]] [z; μ] = [f; g]` by bordering on a frame.
    fn border(
        &self,
        frame: &Frame<S::Factor, N>,
        row: &Tangent<N>,
        f: [f64; N],
        g: f64,
    ) -> Option<([f64; N], f64)> {
        let den = row.mu - dot(&row.v, &frame.y2);
        let size = row.mu.abs() + norm(&row.v) * norm(&frame.y2);
        if !(den.abs() > 1e-10 * size) {
            return None;
        }
        let mut y1 = f;
        self.sys.solve(&frame.factor, &mut y1);
        let mu = (g - dot(&row.v, &y1)) / den;
        let mut z = y1;
        for i in 0..N {
            z[i] -= mu * frame.y2[i];
        }
        Some((z, mu))
    }

    /// The unit tangent at `p`, oriented along `prev`, and det B there.
    fn tangent(
        &self,
        p: &Point<N>,
        prev: &Tangent<N>,
        frame: Option<&Frame<S::Factor, N>>,
    ) -> Option<(Tangent<N>, f64)> {
        let (z, zmu, det) = match frame.and_then(|fr| {
            self.border(fr, prev, [0.0; N], 1.0)
                .map(|(z, m)| (z, m, fr.det))
        }) {
            Some(t) => t,
            None => {
                let (_, m) = self.bordered(p, prev);
                let det = Lu::new(m.block).map_or(0.0, |lu| lu.det());
                let lu = BorderedLu::new(m)?;
                let mut z = Extended {
                    head: [0.0; N],
                    tail: 1.0,
                };
                lu.solve(&mut z);
                (z.head, z.tail, det)
            }
        };
        let nrm = crate::math::sqrt(dot(&z, &z) + zmu * zmu);
        if !(nrm > 0.0) || !nrm.is_finite() {
            return None;
        }
        Some((
            Tangent {
                v: z.map(|zi| zi / nrm),
                mu: zmu / nrm,
            },
            det,
        ))
    }

    /// Corrects `pred`, predicted by a step of length `step`, on `[H; t·(y − pred)] = 0` (or on
    /// H at fixed μ), under the [`Contraction`] test. With a frame the iteration is the chord
    /// method of Eq. 11; without, full Newton on the dense bordered matrix.
    fn correct(
        &self,
        pred: &Point<N>,
        t: &Tangent<N>,
        fixed_mu: bool,
        step: f64,
        frame: Option<&Frame<S::Factor, N>>,
    ) -> Result<(Point<N>, u32, f64), u32> {
        let mut p = *pred;
        let mut contraction = Contraction::new(step, self.tol);
        let mut first = 0.0;
        for k in 0..MAX_CORRECTOR {
            let its = k as u32 + 1;
            let g = dot(&t.v, &p.v) - dot(&t.v, &pred.v) + t.mu * (p.mu - pred.mu);
            let step = match (frame, fixed_mu) {
                (Some(fr), true) => {
                    let mut d = self.residual(&p);
                    self.sys.solve(&fr.factor, &mut d);
                    Some((d, 0.0))
                }
                (Some(fr), false) => self.border(fr, t, self.residual(&p), g),
                (None, true) => crate::correction::correction_in(
                    self.sys,
                    &p.v,
                    &self.x(p.mu),
                    self.linear,
                    &mut self.sys.new_factor(),
                )
                .ok()
                .map(|c| (c.delta, 0.0)),
                (None, false) => {
                    let (f, m) = self.bordered(&p, t);
                    BorderedLu::new(m).map(|lu| {
                        let mut rhs = Extended { head: f, tail: g };
                        lu.solve(&mut rhs);
                        (rhs.head, rhs.tail)
                    })
                }
            };
            let Some((d, dmu)) = step else {
                return Err(its);
            };
            let size = crate::math::sqrt(dot(&d, &d) + dmu * dmu);
            if !size.is_finite() {
                return Err(its);
            }
            for i in 0..N {
                p.v[i] -= d[i];
            }
            p.mu -= dmu;
            if k == 0 {
                first = size;
            }
            if size <= self.tol {
                return Ok((p, its, first));
            }
            if !contraction.admits(size) {
                return Err(its);
            }
        }
        Err(MAX_CORRECTOR as u32)
    }
}

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
    crate::start::check_target(sys, start, target, options)?;
    let mut dx = [0.0; M];
    for j in 0..M {
        dx[j] = target[j] - start.x()[j];
    }
    // Scale λ by how far v moves over the whole path to first order, ‖B⁻¹(∂F/∂x)(x* − x0)‖,
    // so that λ and v weigh alike in the arc length whatever the inputs' units (mm, rad).
    let length = first_order_travel(sys, start, &dx).unwrap_or_else(|| norm(&dx));
    let scale = norm(start.v()).max(length).max(1.0);
    let path = Path {
        sys,
        start,
        dx,
        length,
        tol: 1e-6 * scale,
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
    let Some((mut t, _)) = path.tangent(&p, &e_mu, frame.as_ref()) else {
        return Ok(finish(
            sys,
            start,
            p.v,
            start.x(),
            Status::Singular { lambda: 0.0 },
            Account::at(0.0),
        ));
    };
    let mut det_prev = start.det();
    let mut previous: Option<(Point<N>, Tangent<N>, f64)> = None;
    let mut just_rejected = false;
    let (h_max, h_min) = (length / 2.0, 1e-10 * length);
    let mut h = length / 4.0;
    let (mut accepted, mut rejected, mut iterations) = (0u32, 0u32, 0u32);
    let mut min_ratio = 1.0f64;
    let stop = |p: &Point<N>, status, acc, rej, it, ratio| {
        let x = path.x(p.mu);
        Ok(finish(
            sys,
            start,
            p.v,
            &x,
            status,
            Account {
                lambda: p.mu / length,
                accepted: acc,
                rejected: rej,
                iterations: it,
                min_det_ratio: ratio,
            },
        ))
    };
    while accepted + rejected < options.max_steps {
        let to_end = if t.mu > 0.0 {
            (length - p.mu) / t.mu
        } else {
            f64::INFINITY
        };
        let end = to_end <= h;
        let step = if end { to_end } else { h };
        let mut pred = Point {
            v: p.v,
            mu: if end { length } else { p.mu + step * t.mu },
        };
        match (&previous, end) {
            // Cubic Hermite extrapolation through the last two points and their tangents:
            // third-order accurate where Euler is first-order, so steps near a fold can be
            // longer. Only within one previous chord length, where it is reliable.
            (Some((p0, t0, chord)), false) if step <= *chord => {
                let u = 1.0 + step / chord;
                let (u2, u3) = (u * u, u * u * u);
                let (h00, h10, h01, h11) = (
                    2.0 * u3 - 3.0 * u2 + 1.0,
                    u3 - 2.0 * u2 + u,
                    -2.0 * u3 + 3.0 * u2,
                    u3 - u2,
                );
                for i in 0..N {
                    pred.v[i] =
                        h00 * p0.v[i] + h10 * chord * t0.v[i] + h01 * p.v[i] + h11 * chord * t.v[i];
                }
                pred.mu = h00 * p0.mu + h10 * chord * t0.mu + h01 * p.mu + h11 * chord * t.mu;
            }
            _ => {
                for i in 0..N {
                    pred.v[i] += step * t.v[i];
                }
            }
        }
        match path.correct(&pred, &t, end, step, frame.as_ref()) {
            // A step that is not the last may still end past λ = 1: the corrector moves μ too.
            // Land on λ = 1 from p instead (the next step is the last, and shorter).
            Ok((q, its, _)) if !end && q.mu > length => {
                iterations += its;
                rejected += 1;
                // λ = 1 is about a step away (this one, plus what the corrector added to μ):
                // the next step lands on it.
                h = if t.mu > 0.0 {
                    to_end.max(step)
                } else {
                    0.5 * step
                };
                just_rejected = true;
            }
            Ok((q, its, first)) => {
                iterations += its;
                let next_frame = path.frame(&q);
                let Some((t1, det1)) = path.tangent(&q, &t, next_frame.as_ref()) else {
                    return stop(
                        &p,
                        Status::Singular {
                            lambda: p.mu / length,
                        },
                        accepted,
                        rejected,
                        iterations,
                        min_ratio,
                    );
                };
                if det1 * det_prev <= 0.0 {
                    // det B changed sign between p and q: the curve passes a fold (λ turns
                    // back) or a singular point. Either way the branch ends here.
                    let status = Status::Fold {
                        lambda: p.mu.max(q.mu) / length,
                    };
                    return stop(&p, status, accepted, rejected, iterations, 0.0);
                }
                if dot(&t.v, &t1.v) + t.mu * t1.mu < MIN_TANGENT_COS && !end {
                    rejected += 1;
                    h = step * 0.5;
                    just_rejected = true;
                } else {
                    accepted += 1;
                    let chord = crate::math::sqrt(
                        (0..N)
                            .map(|i| (q.v[i] - p.v[i]) * (q.v[i] - p.v[i]))
                            .sum::<f64>()
                            + (q.mu - p.mu) * (q.mu - p.mu),
                    );
                    previous = Some((p, t, chord));
                    p = q;
                    t = t1;
                    frame = next_frame;
                    det_prev = det1;
                    min_ratio = min_ratio.min((det1 / start.det()).abs());
                    if end {
                        let account = Account {
                            lambda: 1.0,
                            accepted,
                            rejected,
                            iterations,
                            min_det_ratio: min_ratio,
                        };
                        return Ok(polish(sys, start, p.v, target, options, account));
                    }
                    // The Euler predictor's error grows like h²: aim the next first correction
                    // at a twentieth of the step, changing h by at most a factor of two.
                    let ideal = if first > 0.0 {
                        0.05 * step * step / first
                    } else {
                        2.0 * step
                    };
                    h = ideal.clamp(0.5 * step, 2.0 * step).min(h_max);
                    // Right after a rejection, do not grow again: growing straight back into the
                    // step that failed makes the step size oscillate.
                    if its >= 4 || just_rejected {
                        h = h.min(step);
                    }
                    just_rejected = false;
                }
            }
            Err(its) => {
                iterations += its;
                rejected += 1;
                h = 0.5 * step.min(h);
                just_rejected = true;
            }
        }
        if h < h_min {
            return stop(
                &p,
                Status::StepTooSmall {
                    lambda: p.mu / length,
                },
                accepted,
                rejected,
                iterations,
                min_ratio,
            );
        }
    }
    let status = Status::StepTooSmall {
        lambda: p.mu / length,
    };
    stop(&p, status, accepted, rejected, iterations, min_ratio)
}

/// ‖B⁻¹ (∂F/∂x) dx‖ at the start, if B is regular there.
fn first_order_travel<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    dx: &[f64; M],
) -> Option<f64> {
    let mut fac = sys.new_factor();
    sys.factor(start.v(), start.x(), &mut fac)?;
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(start.v(), start.x(), &mut a);
    let mut y = [0.0; N];
    for i in 0..N {
        y[i] = (0..M).map(|j| a[i][j] * dx[j]).sum();
    }
    sys.solve(&fac, &mut y);
    let travel = norm(&y);
    (travel.is_finite() && travel > 1e-12 * norm(dx).max(1e-300)).then_some(travel)
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
    conclude(sys, start, &run, x, account)
}
