//! Newton–Raphson (the paper's NRA): Newton's method ([`newton`]) on F(v, x*) = 0 from the
//! start's v. Fast, and with no notion of branch: near a singularity it may converge to another
//! assembly mode. The det B sign check catches some of those, not all, so a converged result is
//! [`Status::Unverified`](crate::solution::Status::Unverified), never `Converged`.

use crate::mechanism::Mechanism;
use crate::newton::{Ending, Prefactored, Rule, Shortcuts, newton_scaled};
use crate::outcome::{Account, conclude, unverified};
use crate::solution::{Options, Solution, SolveError};
use crate::start::Start;

/// Solves F(v, x) = 0 by Newton's method from `start.v`. A result that meets the tolerance
/// with det B of the start's sign is [`Status::Unverified`](crate::solution::Status::Unverified):
/// Newton's method may converge to another assembly mode of the same det B sign, and nothing
/// here can tell (where the branch matters, solve with [`arc_length`](crate::arc_length)).
///
/// ```
/// use linkage::{newton_raphson, Mechanism, Options, Pose, Start, Status};
///
/// linkage::mechanism! {
///     /// A 3-RPS: three hinged legs of variable length carry a triangular platform.
///     pub struct Rps;
///     base {
///         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
///         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
///         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
///     }
///     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
///     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
///     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
///     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// }
///
/// let rps = Rps::new();
/// // Start: platform level, 150 mm up; its leg lengths from inverse kinematics.
/// let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// let start = Start::new(&rps, v0, x0).unwrap();
/// let sol = newton_raphson(&rps, &start, &[160.0, 155.0, 158.0], &Options::TIGHT).unwrap();
/// assert_eq!(sol.status, Status::Unverified);
/// assert!(sol.status.meets_tolerance() && !sol.is_ok());
/// assert!((rps.inverse(&sol.v, &x0).unwrap()[1] - 155.0).abs() < 1e-9);
/// ```
// Inline: a thin wrapper of `newton_scaled`; out of line, the caller pays a call and a copy
// of the `Solution` per solve (+63 instructions of about 7 400, `count nr-normal`).
#[inline]
pub fn newton_raphson<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    solve(sys, start, None, x, options)
}

/// [`newton_raphson`] for many targets from one start: where B does not depend on the inputs
/// ([`Mechanism::JACOBIAN_USES_INPUTS`] is `false`, as for a Stewart platform), B is factored
/// at the start once, here, and every solve's first Newton correction reuses it — the same
/// iterates, the same answer, one factorisation fewer per solve. Otherwise it is
/// [`newton_raphson`] with the start kept.
///
/// ```
/// use linkage::{newton_raphson, Mechanism, NewtonRaphson, Options, Pose, Start};
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
/// let rps = Rps::new();
/// let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// let start = Start::new(&rps, v0, x0).unwrap();
/// // The legs' lengths enter F as constants: B at the start serves every target.
/// assert!(!Rps::JACOBIAN_USES_INPUTS);
/// let nr = NewtonRaphson::new(rps.clone(), start);
/// for x in [[160.0, 155.0, 158.0], [150.0, 151.0, 149.0]] {
///     let once = newton_raphson(&rps, &start, &x, &Options::TIGHT).unwrap();
///     assert_eq!(nr.solve(&x, &Options::TIGHT).unwrap(), once);
/// }
/// ```
#[derive(Clone, Debug)]
pub struct NewtonRaphson<S: Mechanism<N, M>, const N: usize, const M: usize> {
    sys: S,
    start: Start<N, M>,
    /// B factored at the start, where it is the same for every target.
    at_start: Option<Prefactored<S::Factor>>,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> NewtonRaphson<S, N, M> {
    /// Newton–Raphson for `sys` (owned, like a [`Tracker`](crate::tracker::Tracker)'s) from `start`,
    /// with B factored there if it serves every target.
    pub fn new(sys: S, start: Start<N, M>) -> Self {
        let at_start = if S::JACOBIAN_USES_INPUTS {
            None
        } else {
            let mut factor = sys.new_factor();
            // `None` cannot happen for a checked start (B regular there); the solves then
            // factor B themselves.
            sys.factor(start.v(), start.x(), &mut factor)
                .map(|info| Prefactored {
                    factor,
                    det: info.det,
                })
        };
        NewtonRaphson {
            sys,
            start,
            at_start,
        }
    }

    /// The mechanism.
    pub fn sys(&self) -> &S {
        &self.sys
    }

    /// The start every solve begins at.
    pub fn start(&self) -> &Start<N, M> {
        &self.start
    }

    /// [`newton_raphson`] from the start to `x`.
    #[inline]
    pub fn solve(&self, x: &[f64; M], options: &Options) -> Result<Solution<N>, SolveError> {
        solve(&self.sys, &self.start, self.at_start.as_ref(), x, options)
    }
}

#[inline(always)]
fn solve<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    at_start: Option<&Prefactored<S::Factor>>,
    x: &[f64; M],
    options: &Options,
) -> Result<Solution<N>, SolveError> {
    // F at the start is Newton's first residual: its overflow shows there, not in a check.
    crate::start::check_sample(sys, start, x, options)?;
    // With chord steps: from a distant start, they save a factorisation in about half the
    // solves (BENCHMARKS.md, Instruction counts).
    let shortcuts = Shortcuts {
        chords: true,
        at_start,
    };
    let run = newton_scaled(
        sys,
        start.v(),
        start.scale(),
        x,
        options,
        Rule::Final,
        shortcuts,
    );
    if run.ending == Ending::NonFinite && run.iterations == 0 {
        return Err(SolveError::NonFinite);
    }
    let account = Account {
        iterations: run.iterations,
        ..Account::at(1.0)
    };
    Ok(unverified(conclude(
        sys,
        start,
        &run,
        x,
        options.tolerance,
        true,
        account,
    )))
}
