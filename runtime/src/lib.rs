#![no_std]
#![deny(unsafe_code)]
#![warn(missing_docs)]
#![doc = include_str!("../../README.md")]

#[cfg(feature = "std")]
extern crate std;

// Lets the generated code's `::linkage::` paths resolve inside this crate's own tests.
extern crate self as linkage;

/// Declares a mechanism of lower pairs and generates its constraint system at compile time.
///
/// # Grammar
///
/// ```text
/// mechanism! {
///     /// docs
///     pub struct Name;
///     params { r = 100.0, h = r * sqrt(3.0) / 2.0 }     // optional; arithmetic allowed
///     base { A1 = [x, y, z], ... }                      // base pivots, base frame
///     platform(frame = [P1, P2, P3], home = [yaw, pitch, roll, x, y, z]) { P1 = [x, y, z], ... }
///     link crank1 { C1 = [x, y, z] }                    // pivots at the home configuration, base frame
///     link rod1 { length = 150.0 }                      // a binary link between two point joints
///     chain leg1 = base - S(A1) - P(active L1) - S(P1) - platform;
///     chain arm1 = base - R(active q1, axis = A1 -> B1) - crank1 - S(C1) - rod1 - S(P1) - platform;
///     chain arm1b = crank1 - S(C2) - rod2 - S(P2) - platform;   // a chain may start at a link
///     chain leg3 = base - U(A3, axis = A3 -> B3) - P(active L3) - U(P3, axis = P3 -> Q3) - platform;
/// }
/// ```
///
/// Pairs: `R`, `P`, `C`, `H` (with `lead = ...`), `S`, `U`; each `active NAME` (its joint
/// variables) or `passive`; `S` and `U` name their centre pivot, `R`, `C`, `H` (and `P`, `U`
/// optionally) an axis `A -> B`. `frame` chooses the three platform pivots that locate it
/// (default: the largest triangle); `form = coplanar | general` the rigid-body form (default:
/// from the geometry); `home` the platform's pose at the home configuration (also as
/// `rotation(...)` or `quaternion(...)`), checked at compile time (the mechanism must assemble
/// there, ∂F/∂v must be regular) and offered as `home_start()`. The README's grammar section
/// gives each pair's arguments and the zero and sense of its input. The generated type
/// implements [`Mechanism`].
pub use linkage_macros::mechanism;

mod arc_length;
mod ball;
mod certified_path;
mod certified_steps;
mod certify;
mod convergence;
mod correction;
mod damped_least_squares;
mod detour;
mod dispatch;
mod double_double;
mod error;
mod floor;
mod householder;
mod interval;
mod inverse;
pub mod lu;
mod math;
mod mechanism;
pub mod modes;
mod newton;
mod newton_homotopy;
mod newton_raphson;
mod outcome;
mod pose;
pub mod reference;
mod scalar;
mod slope;
mod solution;
mod start;
mod tracker;
mod turns;
pub mod velocity;

#[doc(hidden)]
pub mod __private;

pub use arc_length::arc_length;
pub use certified_path::arc_length_certified;
pub use certified_steps::{CertifiedSteps, StepProof};
pub use certify::{Certificate, CertifyError, certify, certify_step};
pub use correction::{det_b, error_estimate};
pub use detour::{Detoured, arc_length_detour};
pub use dispatch::uses_x86_64_v3;
pub use error::{GeometryError, InverseError};
pub use interval::Interval;
pub use mechanism::Mechanism;
pub use newton_homotopy::newton_homotopy;
pub use newton_raphson::{NewtonRaphson, newton_raphson};
pub use pose::{Pose, pose_from_unknowns, unknowns_from_pose};
pub use scalar::Scalar;
pub use solution::{Linear, Options, Solution, SolveError, Status};
pub use start::Start;
pub use tracker::{Sample, TrackError, Tracker};
pub use turns::Turns;

/// The three solvers of Table V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Pseudo-arc-length homotopy continuation ([`arc_length`]).
    ArcLength,
    /// Newton homotopy ([`newton_homotopy`]).
    NewtonHomotopy,
    /// Newton–Raphson ([`newton_raphson`]).
    NewtonRaphson,
}

impl Method {
    /// Solves for `target` from `start` with this method.
    pub fn solve<S: Mechanism<N, M>, const N: usize, const M: usize>(
        self,
        sys: &S,
        start: &Start<N, M>,
        target: &[f64; M],
        options: &Options,
    ) -> Result<Solution<N>, SolveError> {
        match self {
            Method::ArcLength => arc_length(sys, start, target, options),
            Method::NewtonHomotopy => newton_homotopy(sys, start, target, options),
            Method::NewtonRaphson => newton_raphson(sys, start, target, options),
        }
    }
}
