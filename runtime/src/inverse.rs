//! The numerical inverse kinematics, for mechanisms where some chain has no closed form: the
//! generated `Mechanism::inverse` fills in the closed-form chains' inputs and calls [`solve`]
//! for the rest.
//!
//! With the platform's coordinates held at the given v, F(v, x) = 0 is N equations in
//! Z = M + (N − held) unknowns — the inputs and the points of the links between (Z ≤ N, a
//! consistent least-squares problem). Levenberg–Marquardt, each damped step solved by
//! orthogonal factorisation ([`DampedLeastSquares`](crate::damped_least_squares::DampedLeastSquares); the normal equations square the
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
//! A result is returned only where every equation is within [`ACCEPT`](levenberg_marquardt::ACCEPT) of the scale of holding
//! (its residual over its largest derivative by the coordinates: a length), or where the
//! configuration the inputs place satisfies them so and has the platform within as much of v,
//! so any inputs returned do place the platform at v; a pose the mechanism cannot take is
//! `Unreachable` — at once where the platform is given out of shape (two of its points
//! farther apart or nearer than declared, or an equation on its points alone that no input
//! reads failing, by far more than that: `closed_form::FAR`), after the search below otherwise.
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

use crate::error::InverseError;
use crate::mechanism::Mechanism;

/// Levenberg–Marquardt iterations per solve from a guess (far from home, with several inputs,
/// a hundred can end short of the answer, at a residual that looks small only because the
/// problem is ill-conditioned there)
const ITERATIONS: usize = 500;

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
mod follow;
mod levenberg_marquardt;
mod polish;
#[cfg(test)]
mod tests;

use by_the_inputs::by_the_inputs;
pub use closed_form::{closed_form_places, platform_in_shape, platform_keeps_its_distances};
use follow::{copy_tail, follow, half_turn};
use levenberg_marquardt::{Solver, Work};

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
