//! Levenberg–Marquardt on the inputs and the unknowns after the platform's, with the platform
//! held: the numerical inverse's one iteration, and how far what it leaves is from an answer.

use core::cell::Cell;

use crate::damped_least_squares::DampedLeastSquares;
use crate::math::sqrt;
use crate::mechanism::Mechanism;

/// How far, relative to the scale (1 + the largest platform coordinate), the given platform
/// may be from the mechanism's motion and the answer's pivots from satisfying the equations.
/// Levenberg–Marquardt takes its unknowns to where their steps become negligible (1e-13 of the
/// coordinates): what is left then is how far the given v is off the motion — a forward solve to
/// a tolerance of 1e-8 mm leaves ~1e-10 of a 100 mm scale — and is accepted up to this.
pub(super) const ACCEPT: f64 = 1e-9;

/// What a solve cost: Levenberg–Marquardt runs, their iterations and their damped solves. A
/// few counters on the stack, read only by the unit tests' probe (`inverse/tests.rs`), which
/// measures what the stopping rule saves.
#[derive(Default)]
pub(crate) struct Work {
    pub(crate) runs: Cell<u32>,
    pub(crate) iterations: Cell<u32>,
    pub(crate) damped_solves: Cell<u32>,
}

impl Work {
    pub(super) fn add(counter: &Cell<u32>) {
        counter.set(counter.get().saturating_add(1));
    }
}

/// A run whose cost [`STALL`] iterations have lowered by less than a part in 10⁴ has stalled,
/// at a local minimum or creeping along a valley (a SCARA with a wrist, followed from home:
/// steps of 2e-2 mm that left its cost the same to four digits for a hundred iterations): it
/// ends there, as one that settled, and what it reached is judged by the acceptance. Linear
/// convergence to a singular answer (the cost halved, or better, each iteration) is far
/// quicker than this. A tenth instead of 10⁻⁴ cut short runs that did converge, through a
/// saddle (the wrist from its platform's points alone: 1 of 200 random poses refused against
/// none, and 19 against 14 without the search over the inputs); no such rule took a fifth more
/// iterations (the unit tests' probe, `inverse/tests.rs`).
pub(super) const STALL: usize = 10;
pub(super) const STALLED: f64 = 0.9999;

/// Levenberg–Marquardt on the inputs and the unknowns after the platform's.
pub(super) struct Solver<'a, S, const N: usize, const M: usize, const Z: usize> {
    pub(super) sys: &'a S,
    pub(super) held: usize,
    pub(super) work: &'a Work,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize> Solver<'_, S, N, M, Z> {
    /// Σ F², infinite where it is not finite.
    pub(super) fn cost(&self, v: &[f64; N], x: &[f64; M]) -> f64 {
        let mut f = [0.0; N];
        self.sys.residual(v, x, &mut f);
        let s: f64 = f.iter().map(|r| r * r).sum();
        if s.is_finite() { s } else { f64::INFINITY }
    }

    /// Each equation's weight for a whole run: 1 / its row's largest derivative, by the inputs
    /// or by any coordinate (the platform's too), or 0 for an equation nothing moves. Fixed
    /// for the run, because weights taken afresh at each iterate make each step a descent on a
    /// different sum: a SCARA with a wrist far from home went back and forth between two
    /// iterates for 450 iterations, each lower than the other under the other's weights. By
    /// the coordinates too, because an input's derivatives vanish where its axis lines up (at
    /// home, say) while an equation's by the points it holds, a length, stays within a factor
    /// of √3 of itself as the points turn.
    fn row_weights(&self, v: &[f64; N], x: &[f64; M]) -> [f64; N] {
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(v, x, &mut a);
        let mut b = [[0.0; N]; N];
        self.sys.jacobian_dense(v, x, &mut b);
        let mut w = [0.0; N];
        let mut all = 0.0f64;
        for r in 0..N {
            w[r] = a[r].iter().chain(&b[r]).fold(0.0f64, |t, q| t.max(q.abs()));
            all = all.max(w[r]);
        }
        for r in 0..N {
            w[r] = if w[r] > 1e-9 * all { 1.0 / w[r] } else { 0.0 };
        }
        w
    }

    /// J = [∂F/∂x | ∂F/∂v after the platform's].
    fn jacobian(&self, v: &[f64; N], x: &[f64; M]) -> [[f64; Z]; N] {
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(v, x, &mut a);
        let mut b = [[0.0; N]; N];
        if self.held < N {
            self.sys.jacobian_dense(v, x, &mut b);
        }
        let mut j = [[0.0; Z]; N];
        // Z = M + N − held: the inputs' columns, then the unknowns' after the platform's.
        for r in 0..N {
            for (d, s) in j[r].iter_mut().zip(&a[r]) {
                *d = *s;
            }
            for (d, s) in j[r].iter_mut().skip(M).zip(b[r].iter().skip(self.held)) {
                *d = *s;
            }
        }
        j
    }

    /// Iterates until the step is negligible, none lowers the cost, or the cost has stalled
    /// ([`STALLED`]) (a residual test alone would stop early on the equations of points a unit
    /// apart, an axis tip, whose residuals are small beside the slides that move them); returns
    /// what is left of F.
    pub(super) fn levenberg_marquardt(
        &self,
        v: &mut [f64; N],
        x: &mut [f64; M],
        iterations: usize,
    ) -> Left {
        let mut f = [0.0; N];
        self.sys.residual(v, x, &mut f);
        let mut mu = 1e-6f64;
        let mut nu = 2.0f64;
        let mut settled = false;
        Work::add(&self.work.runs);
        let w = self.row_weights(v, x);
        let weighted = |f: &[f64; N]| -> f64 {
            let c: f64 = (0..N).map(|r| (w[r] * f[r]) * (w[r] * f[r])).sum();
            if c.is_finite() { c } else { f64::INFINITY }
        };
        // The cost STALL iterations ago.
        let mut before = f64::INFINITY;
        for k in 0..iterations {
            Work::add(&self.work.iterations);
            let cost = weighted(&f);
            if cost == 0.0 {
                settled = true;
                break;
            }
            if !(cost > 0.0) || cost == f64::INFINITY {
                break;
            }
            if k % STALL == 0 {
                if cost > STALLED * before {
                    settled = true;
                    break;
                }
                before = cost;
            }
            let j = self.jacobian(v, x);
            // The weighted J and −F, factorised once; Marquardt's damping of each column by
            // its own size (inputs in rad and in mm weigh alike).
            let mut a = [[0.0; Z]; N];
            let mut b = [0.0; N];
            for r in 0..N {
                for p in 0..Z {
                    a[r][p] = w[r] * j[r][p];
                }
                b[r] = -w[r] * f[r];
            }
            let mut column = [0.0; Z];
            for row in &a {
                for p in 0..Z {
                    column[p] += row[p] * row[p];
                }
            }
            let least_squares = DampedLeastSquares::<Z>::new(a, b);
            // Damped steps until one lowers the cost.
            let mut accepted = false;
            while mu <= 1e12 {
                let damping = column.map(|c| sqrt(mu * (c + 1e-300)));
                Work::add(&self.work.damped_solves);
                let Some(d) = least_squares.solve(&damping) else {
                    mu *= nu;
                    nu *= 2.0;
                    continue;
                };
                let (mut vt, mut xt) = (*v, *x);
                // d = (Δx, Δv after the platform's): Z = M + N − held.
                for (xp, dp) in xt.iter_mut().zip(&d) {
                    *xp += dp;
                }
                for (vp, dp) in vt.iter_mut().skip(self.held).zip(d.iter().skip(M)) {
                    *vp += dp;
                }
                let mut ft = [0.0; N];
                self.sys.residual(&vt, &xt, &mut ft);
                let trial = weighted(&ft);
                if trial < cost {
                    // The reduction the linear model predicted, ‖b‖² − ‖b − a d‖².
                    let mut left = 0.0;
                    for r in 0..N {
                        let ad: f64 = (0..Z).map(|p| a[r][p] * d[p]).sum();
                        left += (b[r] - ad) * (b[r] - ad);
                    }
                    let rho = (cost - trial) / (cost - left);
                    let moved = xt.iter().chain(vt.iter().skip(self.held));
                    let negligible = d
                        .iter()
                        .zip(moved)
                        .all(|(s, q)| s.abs() <= 1e-13 * (1.0 + q.abs()));
                    (*v, *x, f) = (vt, xt, ft);
                    // Nielsen's factor alone (at least a third) took the pan-tilt far from
                    // home 16 iterations where a tenth took 9.
                    let factor = if !rho.is_finite() || rho > 0.75 {
                        0.1
                    } else {
                        // Written out: `powi` needs the standard library.
                        let e = 2.0 * rho - 1.0;
                        (1.0 - e * e * e).max(1.0 / 3.0)
                    };
                    mu = (mu * factor).max(1e-15);
                    nu = 2.0;
                    accepted = !negligible;
                    break;
                }
                mu *= nu;
                nu *= 2.0;
            }
            if !accepted {
                settled = true;
                break;
            }
        }
        let mut off = off_by(self.sys, v, x, &f);
        if settled {
            let mut polished = *x;
            let projected = self.polish(v, &mut polished);
            if projected < off {
                (*x, off) = (polished, projected);
            }
        }
        Left { off, settled }
    }
}

/// How far the pivots at `v` are from satisfying the equations: the largest of |F_r| over
/// the largest |∂F_r/∂v_j| — a length, whichever unknowns an equation holds. (Not over the
/// derivatives by the inputs: an angle's are the crank's length times larger, and a point
/// 1 µm off a planar mechanism's plane looked within 1e-9 of the scale that way.) An equation
/// no coordinate enters counts only where it fails. The equations left out as dependent at
/// home count too ([`Mechanism::dependent_offset`]).
pub(super) fn off_by<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    f: &[f64; N],
) -> f64 {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let mut off = 0.0f64;
    for r in 0..N {
        let slope = b[r].iter().fold(0.0f64, |m, q| m.max(q.abs()));
        off = off.max(as_length(f[r], slope));
    }
    // And the equations left out as dependent at home: platform pivots on another component
    // of an over-constrained mechanism's square system are no placement of it.
    off = off.max(sys.dependent_offset(v, x));
    if off.is_nan() { f64::INFINITY } else { off }
}

/// An equation's residual `f` over its largest derivative `slope`: how far, as a length, its
/// point is from holding it, to first order. Zero or infinite where no coordinate moves it,
/// as it holds or fails; NaN where `f` is.
fn as_length(f: f64, slope: f64) -> f64 {
    if slope > 0.0 {
        f.abs() / slope
    } else if f == 0.0 {
        0.0
    } else {
        f64::INFINITY
    }
}

/// What is left of F after a solve.
#[derive(Clone, Copy, Debug)]
pub(super) struct Left {
    /// How far the pivots are from satisfying the equations ([`off_by`]): what the inverse's
    /// unknowns could not remove, and how far the given platform is off the motion.
    off: f64,
    /// Whether the iteration ended where no step helps (negligible, or none lowers the cost)
    /// rather than by running out of iterations.
    settled: bool,
}

impl Left {
    /// Whether the iteration settled within the tolerance at this scale.
    pub(super) fn within(self, scale: f64) -> bool {
        self.settled && self.off <= ACCEPT * scale
    }
}
