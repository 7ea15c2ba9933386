//! Pseudo-arc-length homotopy continuation (the paper's PH, Eqs. 6–12), made robust.
//!
//! The homotopy H(v, λ) = F(v, x0 + λ(x* − x0)) (Eq. 6) is tracked in `y = (v, μ)` with
//! μ = λ‖x* − x0‖, so that λ moves as much as the millimetre-sized v. Each step:
//! - predicts along the unit tangent (Eq. 12), the tangent's orientation kept by the bordered
//!   system whose last row is the previous tangent (Eq. 9);
//! - corrects with Newton on `[H(y); t·(y − y_pred)] = 0` (Keller's constraint, Eq. 8 as
//!   corrected in ERRATA.md), re-evaluating the bordered matrix (Eq. 10) each iteration;
//! - **accepts the step only if Newton contracts fast**: the first correction must be small
//!   against the step and each next one at most a quarter of the previous. A corrector that
//!   would slide onto a neighbouring branch fails this test and the step is halved;
//! - rejects a step that turns the tangent by more than ~37°;
//! - watches the sign of det B: it flips exactly where λ turns back (a fold). A fold means the
//!   straight joint-space path leaves the valid joint space, and the curve beyond it belongs to
//!   another assembly mode, so the solve stops there with [`Status::Fold`].
//!
//! The last step lands on λ = 1 exactly, and a Newton iteration polishes the result to the
//! requested tolerance.

use crate::lu::{factor, solve, Bordered, Extended};
use crate::math::norm;
use crate::newton::finish;
use crate::start::correction;
use crate::{Mechanism, Options, Solution, SolveError, Start, Status};

const MAX_CORRECTOR: usize = 6;
const CONTRACTION: f64 = 0.25;
const MIN_TANGENT_COS: f64 = 0.8;

struct Path<'a, S, const N: usize, const M: usize> {
    sys: &'a S,
    start: &'a Start<N, M>,
    dx: [f64; M],
    length: f64,
    tol: f64,
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

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Path<'_, S, N, M> {
    fn x(&self, mu: f64) -> [f64; M] {
        let l = mu / self.length;
        let mut x = [0.0; M];
        for j in 0..M {
            x[j] = self.start.x[j] + l * self.dx[j];
        }
        x
    }

    /// H, and the bordered matrix with the given last row.
    fn system(&self, p: &Point<N>, row: &Tangent<N>) -> ([f64; N], Bordered<N>) {
        let x = self.x(p.mu);
        let mut f = [0.0; N];
        self.sys.residual(&p.v, &x, &mut f);
        let mut m = Bordered {
            block: [[0.0; N]; N],
            column: [0.0; N],
            row: row.v,
            corner: row.mu,
        };
        self.sys.jacobian_dense(&p.v, &x, &mut m.block);
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(&p.v, &x, &mut a);
        for i in 0..N {
            let mut s = 0.0;
            for j in 0..M {
                s += a[i][j] * self.dx[j];
            }
            m.column[i] = s / self.length;
        }
        (f, m)
    }

    /// The unit tangent at `p`, oriented along `prev`, and det B there.
    fn tangent(&self, p: &Point<N>, prev: &Tangent<N>) -> Option<(Tangent<N>, f64)> {
        let (_, mut m) = self.system(p, prev);
        let mut b = m.block;
        let det = factor::<N, _>(&mut b).map_or(0.0, |piv| piv.det);
        let piv = factor::<N, _>(&mut m)?;
        let mut z = Extended {
            head: [0.0; N],
            tail: 1.0,
        };
        solve(&m, &piv, &mut z);
        let nrm = z.norm();
        if !(nrm > 0.0) || !nrm.is_finite() {
            return None;
        }
        for zi in &mut z.head {
            *zi /= nrm;
        }
        Some((
            Tangent {
                v: z.head,
                mu: z.tail / nrm,
            },
            det,
        ))
    }

    /// Newton on `[H; t·(y − y_pred)] = 0` (or on H at fixed μ), with the contraction test.
    fn correct(
        &self,
        pred: &Point<N>,
        t: &Tangent<N>,
        fixed_mu: bool,
        first_max: f64,
    ) -> Result<(Point<N>, u32), u32> {
        let mut p = *pred;
        let mut prev = f64::INFINITY;
        for k in 0..MAX_CORRECTOR {
            let (d, dmu) = if fixed_mu {
                let x = self.x(p.mu);
                match correction(self.sys, &p.v, &x) {
                    Some((d, _)) => (d, 0.0),
                    None => return Err(k as u32 + 1),
                }
            } else {
                let (f, mut m) = self.system(&p, t);
                let mut g = 0.0;
                for i in 0..N {
                    g += t.v[i] * (p.v[i] - pred.v[i]);
                }
                g += t.mu * (p.mu - pred.mu);
                let Some(piv) = factor::<N, _>(&mut m) else {
                    return Err(k as u32 + 1);
                };
                let mut rhs = Extended { head: f, tail: g };
                solve(&m, &piv, &mut rhs);
                (rhs.head, rhs.tail)
            };
            let mut s = dmu * dmu;
            for di in &d {
                s += di * di;
            }
            let size = crate::math::sqrt(s);
            if !size.is_finite() {
                return Err(k as u32 + 1);
            }
            for i in 0..N {
                p.v[i] -= d[i];
            }
            p.mu -= dmu;
            if size <= self.tol {
                return Ok((p, k as u32 + 1));
            }
            if (k == 0 && size > first_max) || (k > 0 && size > CONTRACTION * prev) {
                return Err(k as u32 + 1);
            }
            prev = size;
        }
        Err(MAX_CORRECTOR as u32)
    }
}

/// Solves F(v, x*) = 0 by pseudo-arc-length continuation from the start along the straight
/// joint-space segment, stopping with [`Status::Fold`] where that segment leaves the valid
/// joint space.
pub fn arc_length<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    crate::start::check_target(sys, target, options)?;
    let mut dx = [0.0; M];
    for j in 0..M {
        dx[j] = target[j] - start.x[j];
    }
    let length = norm(&dx);
    if length == 0.0 {
        return Ok(finish(
            sys,
            start,
            start.v,
            target,
            Status::Converged,
            1.0,
            0,
            0,
            0,
            1.0,
        ));
    }
    let scale = norm(&start.v).max(length).max(1.0);
    let path = Path {
        sys,
        start,
        dx,
        length,
        tol: 1e-9 * scale,
    };
    let mut p = Point {
        v: start.v,
        mu: 0.0,
    };
    let e_mu = Tangent {
        v: [0.0; N],
        mu: 1.0,
    };
    let Some((mut t, _)) = path.tangent(&p, &e_mu) else {
        return Ok(finish(
            sys,
            start,
            p.v,
            &start.x,
            Status::Singular { lambda: 0.0 },
            0.0,
            0,
            0,
            0,
            1.0,
        ));
    };
    let mut det_prev = start.det;
    let (h_max, h_min) = (length / 2.0, 1e-10 * length);
    let mut h = length / 8.0;
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
            p.mu / length,
            acc,
            rej,
            it,
            ratio,
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
        for i in 0..N {
            pred.v[i] += step * t.v[i];
        }
        match path.correct(&pred, &t, end, 0.5 * step + path.tol) {
            Ok((q, its)) => {
                iterations += its;
                let Some((t1, det1)) = path.tangent(&q, &t) else {
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
                let turn: f64 =
                    t.v.iter().zip(&t1.v).map(|(a, b)| a * b).sum::<f64>() + t.mu * t1.mu;
                if det1 * det_prev <= 0.0 {
                    // det B changed sign between p and q: the curve passes a fold (λ turns
                    // back) or a singular point. Either way the branch ends here.
                    let status = Status::Fold {
                        lambda: p.mu.max(q.mu) / length,
                    };
                    return stop(
                        &p,
                        status,
                        accepted,
                        rejected,
                        iterations,
                        min_ratio.min(0.0),
                    );
                }
                if turn < MIN_TANGENT_COS && !end {
                    rejected += 1;
                    h = step * 0.5;
                } else {
                    accepted += 1;
                    p = q;
                    t = t1;
                    det_prev = det1;
                    min_ratio = min_ratio.min((det1 / start.det).abs());
                    if end {
                        return Ok(polish(
                            sys, start, p.v, target, options, accepted, rejected, iterations,
                            min_ratio,
                        ));
                    }
                    h = if its <= 2 {
                        (2.0 * step).min(h_max)
                    } else if its >= 4 {
                        0.5 * step
                    } else {
                        step
                    };
                }
            }
            Err(its) => {
                iterations += its;
                rejected += 1;
                h = 0.5 * step.min(h);
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

/// Newton at λ = 1 down to the requested tolerance.
#[allow(clippy::too_many_arguments)]
fn polish<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    mut v: [f64; N],
    x: &[f64; M],
    options: &Options,
    accepted: u32,
    rejected: u32,
    mut iterations: u32,
    min_ratio: f64,
) -> Solution<N> {
    let mut status = crate::newton::not_converged(sys, &v, x);
    let mut convergence = crate::start::Convergence::new(options.tolerance, &v);
    for _ in 0..options.max_iterations {
        let Some((d, _)) = correction(sys, &v, x) else {
            status = Status::Singular { lambda: 1.0 };
            break;
        };
        iterations += 1;
        for i in 0..N {
            v[i] -= d[i];
        }
        if convergence.reached(norm(&d)) {
            status = Status::Converged;
            break;
        }
    }
    finish(
        sys, start, v, x, status, 1.0, accepted, rejected, iterations, min_ratio,
    )
}
