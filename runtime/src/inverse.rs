//! The numerical inverse kinematics, for mechanisms where some chain has no closed form: the
//! generated `Mechanism::inverse` fills in the closed-form chains' inputs and calls [`solve`]
//! for the rest.
//!
//! With the platform's coordinates held at the given v, F(v, x) = 0 is N equations in
//! Z = M + (N − held) unknowns — the inputs and the points of the links between (Z ≤ N, a
//! consistent least-squares problem). Levenberg–Marquardt, each damped step solved by
//! orthogonal factorisation ([`DampedLeastSquares`]; the normal equations square the
//! Jacobian's condition and stalled a SCARA's inputs short of the acceptance), with
//! Marquardt's diagonal scaling (inputs in rad and in mm weigh alike), the damping lowered
//! tenfold after a step that did as the linear model predicted and by Nielsen's factor after
//! one that did less, and each equation weighed
//! by its row's largest derivative where the run starts (equations in mm and in mm², on points
//! a unit apart and a hundred apart, count alike; the weights stay fixed for the run, so that
//! every step lowers the same sum). A run ends where its step is negligible (Gauss–Newton at
//! the rounding floor), where no step lowers the cost, or where ten iterations have lowered
//! it by less than a part in 10⁴ (a local minimum, or a creep along a valley); a fit so
//! ended has its inputs polished by Gauss–Newton on the distance from v to where they place
//! the platform (Newton on F(·, x) = 0 over every unknown).
//! A result is returned only where every equation is within [`ACCEPT`] of the scale of holding
//! (its residual over its largest derivative by the coordinates: a length), or where the
//! configuration the inputs place satisfies them so and has the platform within as much of v,
//! so any inputs returned do place the platform at v; a pose the mechanism cannot take is
//! `Unreachable` — at once where the platform is given out of shape (two of its points
//! farther apart or nearer than declared, or an equation on its points alone that no input
//! reads failing, by far more than that: [`FAR`]), after the search below otherwise.
//!
//! Where to start, in order: the reference inputs with whichever guess for the links between
//! fits better (the given v's, or the declared home's with each point moved as far as the
//! platform point that carries it), then the other — each first fitting the inputs alone to
//! the guess held whole (where v holds the links' points as solved, that is the answer, in a
//! few iterations of a problem of M unknowns), then everything from there; then, from the
//! declared home, the inputs alone searched by Levenberg–Marquardt on where they place the
//! platform, each iterate placed by continuation from the last (`by_the_inputs`: for a
//! platform given by its points alone, whose links' points the guesses only guess); then the
//! platform followed from home to v along a straight path of its pose, by steps that halve
//! where one fails and grow where they pass (a straight path can cross an inverse
//! singularity, where no step of a fixed size holds) and, where they stall short of a singular v, v itself from the last pose reached
//! with more iterations (they converge only linearly there); or, for a platform that leaves
//! its motion on a straight path, in 16 least-squares steps of which only the last must hold;
//! last, the inputs that turn started a quarter, half and three quarters of a turn from the
//! reference. An input the equations hold only through its sine and cosine is returned within
//! half a turn of the reference (the generated caller refuses a reference too far out for
//! that, `InverseError::FarReference`).

use core::cell::Cell;

use crate::damped_least_squares::DampedLeastSquares;
use crate::lu::Lu;
use crate::math::sqrt;
use crate::pose::{Pose, pose_from_unknowns, unknowns_from_pose};
use crate::{InverseError, Mechanism};

/// How far, relative to the scale (1 + the largest platform coordinate), the given platform
/// may be from the mechanism's motion and the answer's pivots from satisfying the equations.
/// Levenberg–Marquardt takes its unknowns to where their steps become negligible (1e-13 of the
/// coordinates): what is left then is how far the given v is off the motion — a forward solve to
/// a tolerance of 1e-8 mm leaves ~1e-10 of a 100 mm scale — and is accepted up to this.
pub const ACCEPT: f64 = 1e-9;

/// Levenberg–Marquardt iterations per solve from a guess (far from home, with several inputs,
/// a hundred can end short of the answer, at a residual that looks small only because the
/// problem is ill-conditioned there) and per step along a path (each starts near its answer).
const ITERATIONS: usize = 500;
const PATH_ITERATIONS: usize = 100;

/// Levenberg–Marquardt iterations from where the path from home stalled to a singular v, where
/// they converge only linearly: a SCARA with a wrist stretched to q2 = 4.6e-5 (1e-7 mm inside
/// its reach) took more than 500 from q2 = 0.06.
const STALLED_ITERATIONS: usize = 5000;

/// A run whose cost [`STALL`] iterations have lowered by less than a part in 10⁴ has stalled,
/// at a local minimum or creeping along a valley (a SCARA with a wrist, followed from home:
/// steps of 2e-2 mm that left its cost the same to four digits for a hundred iterations): it
/// ends there, as one that settled, and what it reached is judged by the acceptance. Linear
/// convergence to a singular answer (the cost halved, or better, each iteration) is far
/// quicker than this. A tenth instead of 10⁻⁴ cut short runs that did converge, through a
/// saddle (the wrist from its platform's points alone: 1 of 200 random poses refused against
/// none, and 19 against 14 without the search over the inputs); no such rule took a fifth more
/// iterations (the unit tests' probe, `inverse/tests.rs`).
const STALL: usize = 10;
const STALLED: f64 = 0.9999;

/// Smallest step, as a fraction of the path from home, before following the platform gives up.
const SMALLEST_STEP: f64 = 1.0 / 4096.0;

/// Steps taken in all along the path from home.
const PATH_STEPS: usize = 400;

/// How far (a length, relative to the scale) an equation on the platform's coordinates alone
/// that reads no input (a rigid platform's distances, say) may be off at the given v before
/// the pose is unreachable without a search ([`platform_in_shape`], which the generated
/// `inverse` calls with the generator's list of such equations before this module's search):
/// no inputs or links' points move it, and an answer needs it within [`ACCEPT`] at v, or at a
/// configuration whose platform is within [`ACCEPT`] of v — which moves it by at most the
/// row's nonzeros times that, to first order. A thousand times [`ACCEPT`] leaves room for both
/// and for the second-order term; a pose between the two is searched as any other. Without it
/// a platform given out of shape cost the whole search (every start, the path from home) to
/// be refused: about 50 ms for the 6-PCS of 60 unknowns in the tests' build.
///
/// The same bound holds the platform's distances ([`platform_keeps_its_distances`]), which
/// every model has, equations on the platform alone or not (the 3-PRP's model places its
/// platform's points through links, a delta's tool through its carriage: 25–75 ms a refusal
/// before). A configuration that satisfies F exactly moves the platform rigidly; one an answer
/// accepts satisfies it within [`ACCEPT`] as lengths, which moves the platform's points off its
/// shape by that times the platform's own equations' coefficients, to first order — a thousand
/// leaves room for coefficients up to hundreds (a frame of three points nearly on a line).
const FAR: f64 = 1e3 * ACCEPT;

/// What the generated `inverse` tells [`solve`] besides the equations.
#[derive(Clone, Copy, Debug)]
pub struct Plan<'a, const N: usize, const M: usize> {
    /// The platform's coordinates: the first `held` unknowns, held at the given v.
    pub held: usize,
    /// The declared home (unknowns, inputs), where one is declared.
    pub home: Option<(&'a [f64; N], &'a [f64; M])>,
    /// Points of the links between that move with a platform point: (their first coordinate —
    /// the three are consecutive — and the platform point's index).
    pub carried: &'a [(usize, usize)],
    /// The inputs that F holds only through their sine and cosine.
    pub turning: &'a [usize],
    /// The first input without a closed form (named in `Unreachable`).
    pub unsolved: usize,
}

/// Inputs `x` that place the platform at `v`, from `x0` (the reference with the closed-form
/// inputs filled in). `Z` must be `M + N − plan.held`.
pub fn solve<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    sys: &S,
    v: &[f64; N],
    reference: &[f64; M],
    x0: &[f64; M],
    plan: &Plan<'_, N, M>,
) -> Result<[f64; M], InverseError> {
    let work = Work::default();
    let answer = solve_counting::<S, N, M, Z>(sys, v, reference, x0, plan, &work);
    #[cfg(test)]
    tests::record(&work);
    answer
}

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
    fn add(counter: &Cell<u32>) {
        counter.set(counter.get().saturating_add(1));
    }
}

/// [`solve`], counting its work in `work`.
fn solve_counting<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    sys: &S,
    v: &[f64; N],
    reference: &[f64; M],
    x0: &[f64; M],
    plan: &Plan<'_, N, M>,
    work: &Work,
) -> Result<[f64; M], InverseError> {
    if !v.iter().chain(reference).chain(x0).all(|a| a.is_finite()) {
        return Err(InverseError::NonFinite);
    }
    let unreachable = InverseError::Unreachable {
        input: plan.unsolved,
    };
    if plan.held > N || Z + plan.held != M + N {
        return Err(unreachable);
    }
    // The plan's indices are the generator's; `get` keeps a panic path out all the same.
    let nearest = |mut x: [f64; M]| {
        for &i in plan.turning {
            if let (Some(xi), Some(&r)) = (x.get_mut(i), reference.get(i)) {
                *xi = r + half_turn(*xi - r);
            }
        }
        x
    };
    let solver = Solver::<S, N, M, Z> {
        sys,
        held: plan.held,
        work,
    };
    let scale = |v: &[f64; N]| closed_form::scale(v, plan.held);
    let tolerance = scale(v);

    let inputs_only = Solver::<S, N, M, M> { sys, held: N, work };
    let guesses = guesses(&solver, v, x0, plan);
    for guess in guesses.iter().flatten() {
        let (mut vv, mut x) = (*guess, *x0);
        if plan.held < N {
            let mut w = vv;
            let left = inputs_only.levenberg_marquardt(&mut w, &mut x, ITERATIONS);
            if left.within(tolerance) {
                return Ok(nearest(x));
            }
        }
        if solver
            .levenberg_marquardt(&mut vv, &mut x, ITERATIONS)
            .within(tolerance)
        {
            return Ok(nearest(x));
        }
    }
    if let Some((home_v, home_x)) = plan.home
        && let Some(x) = by_the_inputs(&solver, v, (home_v, home_x), x0, tolerance)
    {
        return Ok(nearest(x));
    }
    if let Some((home_v, home_x)) = plan.home
        && let Some(x) = follow(&solver, v, home_v, home_x, &scale)
    {
        return Ok(nearest(x));
    }
    if !plan.turning.is_empty() {
        for k in 1..4 {
            let shift = k as f64 * 0.5 * core::f64::consts::PI;
            for guess in guesses.iter().flatten() {
                let (mut vv, mut x) = (*guess, *x0);
                for &i in plan.turning {
                    if let Some(xi) = x.get_mut(i) {
                        *xi += shift;
                    }
                }
                if solver
                    .levenberg_marquardt(&mut vv, &mut x, ITERATIONS)
                    .within(tolerance)
                {
                    return Ok(nearest(x));
                }
            }
        }
    }
    Err(unreachable)
}

mod by_the_inputs;
mod closed_form;
#[cfg(test)]
mod tests;

use by_the_inputs::by_the_inputs;
pub use closed_form::{closed_form_places, platform_in_shape, platform_keeps_its_distances};

/// `d` brought into (−π, π].
fn half_turn(d: f64) -> f64 {
    let turn = 2.0 * core::f64::consts::PI;
    let mut d = d % turn;
    if d > 0.5 * turn {
        d -= turn;
    } else if d <= -0.5 * turn {
        d += turn;
    }
    d
}

/// `dst[..to] = src[..to]` (all of it past N), with no panic path for the no-panic proof.
fn copy_head<const N: usize>(dst: &mut [f64; N], src: &[f64; N], to: usize) {
    for (d, s) in dst.iter_mut().zip(src).take(to) {
        *d = *s;
    }
}

/// `dst[from..] = src[from..]` (nothing past N), with no panic path.
fn copy_tail<const N: usize>(dst: &mut [f64; N], src: &[f64; N], from: usize) {
    for (d, s) in dst.iter_mut().zip(src).skip(from) {
        *d = *s;
    }
}

/// The starting unknowns, the better-fitting first: the given v, and (with a declared home
/// and links between) the home's links between carried along with the platform.
fn guesses<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    solver: &Solver<'_, S, N, M, Z>,
    v: &[f64; N],
    x0: &[f64; M],
    plan: &Plan<'_, N, M>,
) -> [Option<[f64; N]>; 2] {
    let Some((home_v, _)) = plan.home.filter(|_| plan.held < N) else {
        return [Some(*v), None];
    };
    let k = S::POINTS.len();
    let mut other = *v;
    copy_tail(&mut other, home_v, plan.held);
    for &(first, carrier) in plan.carried {
        for a in 0..3 {
            let c = a * k + carrier;
            if first + a < N && c < plan.held {
                other[first + a] += v[c] - home_v[c];
            }
        }
    }
    if solver.cost(v, x0) <= solver.cost(&other, x0) {
        [Some(*v), Some(other)]
    } else {
        [Some(other), Some(*v)]
    }
}

/// The platform from home to `v`, each step solved from the last: its pose's Euler angles and
/// translation interpolated (its coordinates, for a platform of one or two points), the last
/// step at `v` itself.
fn follow<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize>(
    solver: &Solver<'_, S, N, M, Z>,
    v: &[f64; N],
    home_v: &[f64; N],
    home_x: &[f64; M],
    scale: &dyn Fn(&[f64; N]) -> f64,
) -> Option<[f64; M]> {
    let held = solver.held;
    let poses = pose_from_unknowns(solver.sys, home_v).zip(pose_from_unknowns(solver.sys, v));
    let at = |t: f64| -> [f64; N] {
        if t >= 1.0 {
            return *v;
        }
        match poses {
            Some((a, b)) => {
                let (ea, eb) = (a.euler(), b.euler());
                let angle = |i: usize| ea[i] + t * half_turn(eb[i] - ea[i]);
                let (ta, tb) = (a.translation, b.translation);
                let pose = Pose::from_euler(
                    angle(0),
                    angle(1),
                    angle(2),
                    core::array::from_fn(|i| ta[i] + t * (tb[i] - ta[i])),
                );
                unknowns_from_pose(solver.sys, &pose)
            }
            None => core::array::from_fn(|i| home_v[i] + t * (v[i] - home_v[i])),
        }
    };
    let (mut vv, mut x) = (*home_v, *home_x);
    let (mut t, mut h) = (0.0f64, 1.0 / 16.0);
    for _ in 0..PATH_STEPS {
        let next = (t + h).min(1.0);
        let target = at(next);
        let (mut vt, mut xt) = (vv, x);
        copy_head(&mut vt, &target, held);
        if solver
            .levenberg_marquardt(&mut vt, &mut xt, PATH_ITERATIONS)
            .within(scale(&vt))
        {
            (t, vv, x) = (next, vt, xt);
            if t >= 1.0 {
                return Some(x);
            }
            h = (2.0 * h).min(0.25);
        } else {
            h *= 0.5;
            if h < SMALLEST_STEP {
                break;
            }
        }
    }
    // Stalled short of v: where v is a singular pose (a serial arm stretched to the edge of its
    // reach), each step converges only linearly and ends short of its iterations; from the
    // last pose reached, v itself with [`STALLED_ITERATIONS`].
    if t > 0.0 {
        let (mut vt, mut xt) = (vv, x);
        copy_head(&mut vt, v, held);
        if solver
            .levenberg_marquardt(&mut vt, &mut xt, STALLED_ITERATIONS)
            .within(scale(&vt))
        {
            return Some(xt);
        }
    }
    // A platform of fewer freedoms than its points have (a coupler point, which moves on a
    // curve) leaves the motion on any straight path: then each step's least-squares answer is
    // the next one's start, and only the last must be exact.
    let (mut vv, mut x) = (*home_v, *home_x);
    for k in 1..=16 {
        copy_head(&mut vv, &at(k as f64 / 16.0), held);
        let left = solver.levenberg_marquardt(&mut vv, &mut x, PATH_ITERATIONS);
        if k == 16 && left.within(scale(&vv)) {
            return Some(x);
        }
    }
    None
}

/// Levenberg–Marquardt on the inputs and the unknowns after the platform's.
struct Solver<'a, S, const N: usize, const M: usize, const Z: usize> {
    sys: &'a S,
    held: usize,
    work: &'a Work,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize> Solver<'_, S, N, M, Z> {
    /// Σ F², infinite where it is not finite.
    fn cost(&self, v: &[f64; N], x: &[f64; M]) -> f64 {
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
    fn levenberg_marquardt(&self, v: &mut [f64; N], x: &mut [f64; M], iterations: usize) -> Left {
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

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const Z: usize> Solver<'_, S, N, M, Z> {
    /// The unknowns where the inputs `x` place the mechanism: Newton on F(·, x) = 0 over every
    /// unknown from `v`; `None` where B is singular or Newton does not settle.
    fn placed(&self, v: &[f64; N], x: &[f64; M]) -> Option<([f64; N], Lu<N>)> {
        let mut w = *v;
        let mut f = [0.0; N];
        for _ in 0..8 {
            self.sys.residual(&w, x, &mut f);
            let mut b = [[0.0; N]; N];
            self.sys.jacobian_dense(&w, x, &mut b);
            let lu = Lu::<N>::new(b)?;
            let mut d = f;
            lu.solve(&mut d);
            let mut step = 0.0f64;
            for i in 0..N {
                w[i] -= d[i];
                step = step.max(d[i].abs());
            }
            if !step.is_finite() {
                return None;
            }
            if step <= 1e-14 * (1.0 + w.iter().fold(0.0f64, |m, q| m.max(q.abs()))) {
                return Some((w, lu));
            }
        }
        None
    }

    /// How far the platform at v is from where inputs place it, after Gauss–Newton on that
    /// distance from `x` (which it updates to the best inputs found): the largest move of a
    /// platform coordinate from v to where the inputs place it, or what is left of the
    /// equations there if more ([`off_by`]). Infinite where B is singular.
    ///
    /// Where v is off the motion by the forward solver's tolerance, the least-squares fit of
    /// the equations spreads that over the links between and the inputs alike: a SCARA's
    /// tool 6.7e-9 mm off gave inputs that placed it 1.4e-6 mm away, and left the quill's
    /// rigidity (equations left out as dependent) 1.05e-7 mm off. Whether the inputs place the
    /// platform at v is what an answer must hold, and what this measures and minimises.
    fn polish(&self, v: &[f64; N], x: &mut [f64; M]) -> f64 {
        let held = self.held.min(N);
        let mut best = f64::INFINITY;
        let mut best_x = *x;
        let mut trial = *x;
        for _ in 0..4 {
            let Some((w, lu)) = self.placed(v, &trial) else {
                break;
            };
            let mut f = [0.0; N];
            self.sys.residual(&w, &trial, &mut f);
            let moved = (0..held).fold(0.0f64, |m, i| m.max((w[i] - v[i]).abs()));
            let off = moved.max(off_by(self.sys, &w, &trial, &f));
            if !(off < best) {
                break;
            }
            (best, best_x) = (off, trial);
            // The platform's motion by the inputs, −B⁻¹ ∂F/∂x, and the inputs' step that
            // moves it onto v in least squares.
            let mut a = [[0.0; M]; N];
            self.sys.input_jacobian(&w, &trial, &mut a);
            let mut s = [[0.0; M]; N];
            for j in 0..M {
                let mut column: [f64; N] = core::array::from_fn(|i| a[i][j]);
                lu.solve(&mut column);
                for i in 0..held {
                    s[i][j] = column[i];
                }
            }
            let mut b = [0.0; N];
            for i in 0..held {
                b[i] = w[i] - v[i];
            }
            let Some(d) = DampedLeastSquares::<M>::new(s, b).solve(&[0.0; M]) else {
                break;
            };
            for j in 0..M {
                trial[j] += d[j];
            }
        }
        *x = best_x;
        best
    }
}

/// How far the pivots at `v` are from satisfying the equations: the largest of |F_r| over
/// the largest |∂F_r/∂v_j| — a length, whichever unknowns an equation holds. (Not over the
/// derivatives by the inputs: an angle's are the crank's length times larger, and a point
/// 1 µm off a planar mechanism's plane looked within 1e-9 of the scale that way.) An equation
/// no coordinate enters counts only where it fails. The equations left out as dependent at
/// home count too ([`Mechanism::dependent_offset`]).
fn off_by<S: Mechanism<N, M>, const N: usize, const M: usize>(
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
struct Left {
    /// How far the pivots are from satisfying the equations ([`off_by`]): what the inverse's
    /// unknowns could not remove, and how far the given platform is off the motion.
    off: f64,
    /// Whether the iteration ended where no step helps (negligible, or none lowers the cost)
    /// rather than by running out of iterations.
    settled: bool,
}

impl Left {
    /// Whether the iteration settled within the tolerance at this scale.
    fn within(self, scale: f64) -> bool {
        self.settled && self.off <= ACCEPT * scale
    }
}
