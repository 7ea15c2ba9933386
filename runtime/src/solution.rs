//! What every solve returns: the solution, how it ended, and what was met on the way.

use core::fmt;

/// How a solve ended. Only [`Status::Converged`] is a solution on the start's branch as far
/// as the method can tell; every other variant says why not. [`Status::Unverified`] is a
/// solution to the tolerance whose branch the method cannot establish (NH and NR).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Status {
    /// Converged to the requested tolerance: the returned v is finite, the Newton correction
    /// measured there is within the tolerance, and det B there has the start's sign.
    Converged,
    /// Converged to the requested tolerance, as [`Status::Converged`] (finite, the correction
    /// within the tolerance, det B of the start's sign), but the method cannot tell whether
    /// the result is on the start's branch: Newton–Raphson and Newton homotopy follow no path
    /// that would show it, and near a singularity they may converge to another assembly mode
    /// whose det B has the same sign. What [`newton_raphson`](crate::newton_raphson) and
    /// [`newton_homotopy`](crate::newton_homotopy) return where [`arc_length`](crate::arc_length)
    /// would return `Converged`; not ok.
    Unverified,
    /// The straight joint-space path from the start to the target meets a direct
    /// singularity: det B changed sign within the last step. At a fold the path turns back in
    /// λ there and leaves the valid joint space; at a singular point where branches cross it
    /// need not turn back. Either way, continuing along the curve would lead to another
    /// assembly mode.
    Fold {
        /// The larger λ of that step (0 at the start, 1 at the target): a bound on where the
        /// branch ends, which may lie past the point returned (at a crossing near λ = 0.98, 1.0
        /// was reported for a point returned at 0.92).
        lambda: f64,
    },
    /// The sign of det B differs from the start's: the result lies across a singular
    /// surface, on another branch. Also where an equation left out as dependent at home
    /// fails at the result ([`Mechanism::dependent_offset`](crate::mechanism::Mechanism::dependent_offset)):
    /// another component of an over-constrained mechanism's square system.
    BranchChanged,
    /// Newton did not converge within the iteration limit, or its iterates overflowed.
    NotConverged {
        /// ‖F(v, x)‖ at the returned v.
        residual_norm: f64,
    },
    /// Newton stopped improving at the floor rounding sets near a singularity before the
    /// requested tolerance was met: `achieved` is the error estimate (‖B⁻¹F‖) at the result.
    ToleranceNotMet {
        /// The error estimate reached, above the tolerance.
        achieved: f64,
    },
    /// The step size fell below its minimum before reaching λ = 1.
    StepTooSmall {
        /// Where on the path: λ is 0 at the start and 1 at the target.
        lambda: f64,
    },
    /// B (or the bordered matrix) became singular and the method cannot go on.
    Singular {
        /// Where on the path: λ is 0 at the start and 1 at the target.
        lambda: f64,
    },
}

impl Status {
    /// One lowercase word, for CSV and logs.
    pub fn word(&self) -> &'static str {
        match self {
            Status::Converged => "ok",
            Status::Unverified => "unverified",
            Status::Fold { .. } => "fold",
            Status::BranchChanged => "branch_changed",
            Status::NotConverged { .. } => "not_converged",
            Status::ToleranceNotMet { .. } => "tolerance_not_met",
            Status::StepTooSmall { .. } => "step_too_small",
            Status::Singular { .. } => "singular",
        }
    }

    /// Whether the result meets the requested tolerance ([`Status::Converged`] or
    /// [`Status::Unverified`]): a solution of F(v, x) = 0, on the start's branch only if
    /// `Converged`.
    ///
    /// ```
    /// use linkage::Status;
    /// assert!(Status::Unverified.meets_tolerance() && Status::Unverified != Status::Converged);
    /// assert!(!Status::Fold { lambda: 0.5 }.meets_tolerance());
    /// ```
    pub fn meets_tolerance(&self) -> bool {
        matches!(self, Status::Converged | Status::Unverified)
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Status::Converged => write!(f, "converged"),
            Status::Unverified => write!(
                f,
                "converged, but this method cannot tell whether on the start's branch"
            ),
            Status::Fold { lambda } => write!(
                f,
                "the joint-space path leaves the valid joint space at λ = {lambda:.4} (fold)"
            ),
            Status::BranchChanged => {
                write!(f, "the result lies on another branch (det B changed sign)")
            }
            Status::NotConverged { residual_norm } => {
                write!(f, "not converged (‖F‖ = {residual_norm:.3e})")
            }
            Status::ToleranceNotMet { achieved } => write!(
                f,
                "the tolerance was not met: rounding near a singularity stops Newton at an error estimate of {achieved:.3e}"
            ),
            Status::StepTooSmall { lambda } => write!(f, "step size underflow at λ = {lambda:.4}"),
            Status::Singular { lambda } => write!(f, "singular Jacobian at λ = {lambda:.4}"),
        }
    }
}

/// A solve's result and its account of the path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<const N: usize> {
    /// The pivot coordinates reached (the last accepted point unless converged).
    pub v: [f64; N],
    /// How the solve ended; only [`Status::Converged`] is ok ([`Solution::is_ok`]).
    pub status: Status,
    /// How far along the homotopy the method got (1 when converged).
    pub lambda: f64,
    /// Continuation steps accepted (0 for the methods that follow no path).
    pub steps_accepted: u32,
    /// Continuation steps rejected and retried shorter.
    pub steps_rejected: u32,
    /// Newton corrections computed, chord (simplified Newton) corrections included: those
    /// reuse the last factorisation (NR takes one where it saves a factorisation).
    pub newton_iterations: u32,
    /// Estimated distance to the exact solution: the Newton correction ‖B⁻¹F‖ measured at the
    /// returned v, with B factored there (the practical form of Eq. 13); infinite where B is
    /// singular. Newton–Raphson may measure it with B factored one correction before, where B
    /// is predicted to differ by at most 0.1 %, and reports that correction enlarged by four
    /// times the difference.
    pub error_estimate: f64,
    /// The smallest |det B| / |det B at the start| met at accepted points.
    pub min_det_ratio: f64,
}

impl<const N: usize> Solution<N> {
    /// Whether the solve converged on the start's branch.
    pub fn is_ok(&self) -> bool {
        self.status == Status::Converged
    }
}

/// Input that cannot be solved at all: nothing was attempted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolveError {
    /// A start or target value is NaN or infinite, or so large that the constraint equations
    /// overflow at it; or a start at a scale where det B, B regular, over- or underflows (a
    /// Stewart platform declared in units that make it 1e40 or 1e-40 across: its 18×18
    /// determinant is not a double).
    NonFinite,
    /// An [`Options`] value is out of range: `reason` says which and why.
    InvalidOptions {
        /// Which option, and the range it must lie in.
        reason: &'static str,
    },
    /// Joint input `input` is out of its physical range (e.g. a negative leg length).
    InvalidInput {
        /// The input's index in [`Mechanism::INPUTS`](crate::mechanism::Mechanism::INPUTS).
        input: usize,
    },
    /// B is singular at the start configuration.
    SingularStart,
    /// The start configuration does not satisfy F(v0, x0) = 0.
    InconsistentStart {
        /// ‖F(v0, x0)‖ at the start as given (the refusal itself judges its Newton
        /// correction, a length).
        residual_norm: f64,
    },
}

impl SolveError {
    /// One lowercase word, for CSV and logs.
    pub fn word(&self) -> &'static str {
        match self {
            SolveError::NonFinite => "non_finite",
            SolveError::InvalidOptions { .. } => "invalid_options",
            SolveError::InvalidInput { .. } => "invalid_input",
            SolveError::SingularStart => "singular_start",
            SolveError::InconsistentStart { .. } => "inconsistent_start",
        }
    }
}

impl fmt::Display for SolveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolveError::NonFinite => {
                write!(f, "non-finite input (or one so large that F overflows)")
            }
            SolveError::InvalidOptions { reason } => write!(f, "invalid options: {reason}"),
            SolveError::InvalidInput { input } => write!(f, "joint input {input} is out of range"),
            SolveError::SingularStart => write!(f, "the start configuration is singular"),
            SolveError::InconsistentStart { residual_norm } => {
                write!(
                    f,
                    "the start configuration does not satisfy the constraints (‖F‖ = {residual_norm:.3e})"
                )
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for SolveError {}

/// Solver settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Converged when the Newton correction ‖Δv‖ at the result is at most this (same units as
    /// v). Finite, positive and at most 1e-3 of the start's ‖v‖ (or of 1, if larger): a looser
    /// tolerance would call answers ok that are visibly off. Where the `f64` evaluation of F
    /// cannot show an error that small (near a singularity, or below the floor the equations'
    /// rounding sets: about 1e-13 mm for the Table III platform, about 1e-10 mm for the general
    /// model's rows at regular points of a 200 mm machine), the answer's correction is measured
    /// again with F evaluated in double-double arithmetic, and the answer refined by it; where
    /// even that is not within the tolerance (B singular to rounding), the solve ends
    /// [`Status::ToleranceNotMet`] with what was achieved.
    pub tolerance: f64,
    /// Newton iterations allowed for the final correction (and for NR altogether).
    pub max_iterations: u32,
    /// Continuation steps allowed (accepted plus rejected).
    pub max_steps: u32,
    /// Newton homotopy: the number of uniform λ steps.
    pub homotopy_steps: u32,
    /// How linear systems in B are solved.
    pub linear: Linear,
}

/// How the solvers factor B = ∂F/∂v.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Linear {
    /// The elimination `mechanism!` generated for B's sparsity pattern (fast).
    #[default]
    Generated,
    /// Dense LU with partial pivoting on the assembled B: the internal baseline.
    Dense,
}

impl Options {
    /// The paper's settings (Section 5): accuracy 0.0005, at most 150 iterations.
    pub const PAPER: Options = Options {
        tolerance: 5e-4,
        max_iterations: 150,
        max_steps: 2000,
        homotopy_steps: 10,
        linear: Linear::Generated,
    };
    /// Near machine precision for millimetre-sized mechanisms: 1e-9, a few times above the
    /// rounding floor the general model's equations leave at regular points of a 200 mm
    /// machine (about 1e-10 mm), so that [`Status::ToleranceNotMet`] means what it says — a
    /// point near a singularity, or a machine too large for this tolerance — and not rounding
    /// at a regular point.
    pub const TIGHT: Options = Options {
        tolerance: 1e-9,
        max_iterations: 50,
        max_steps: 2000,
        homotopy_steps: 10,
        linear: Linear::Generated,
    };

    /// Largest tolerance, as a share of the problem's scale ‖v0‖ (1 where v0 = 0): a tolerance
    /// larger than that would call points converged that lie anywhere on a small mechanism.
    pub const MAX_RELATIVE_TOLERANCE: f64 = 1e-3;

    /// Checks the options for a problem whose start has `‖v0‖ = scale`.
    pub(crate) fn check(&self, scale: f64) -> Result<(), SolveError> {
        let reason = if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            "the tolerance must be a positive number"
        } else if !(self.tolerance
            <= Self::MAX_RELATIVE_TOLERANCE * crate::math::scale_or_one(scale))
        {
            "the tolerance exceeds 1e-3 of the mechanism's scale (‖v0‖)"
        } else if self.max_iterations == 0 {
            "max_iterations must be positive"
        } else if self.max_steps == 0 {
            "max_steps must be positive"
        } else if self.homotopy_steps == 0 {
            "homotopy_steps must be positive"
        } else {
            return Ok(());
        };
        Err(SolveError::InvalidOptions { reason })
    }
}

impl Default for Options {
    fn default() -> Self {
        Options::TIGHT
    }
}
