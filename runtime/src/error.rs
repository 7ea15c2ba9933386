//! Failures as data: every way a call can fail is a variant, never a panic.

use core::fmt;

pub use linkage_geometry::GeometryError;

/// Why joint inputs could not be recovered from pivot positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InverseError {
    /// No joint value of input `input` places the chain's pivots there.
    Unreachable {
        /// The input's index in [`Mechanism::INPUTS`](crate::mechanism::Mechanism::INPUTS).
        input: usize,
    },
    /// Input `input` has no closed-form inverse for this chain.
    NoClosedForm {
        /// The input's index in [`Mechanism::INPUTS`](crate::mechanism::Mechanism::INPUTS).
        input: usize,
    },
    /// The pose, the pivots or the reference contain NaN or infinite values, or the inputs
    /// they give overflow.
    NonFinite,
    /// The closed forms gave inputs, but the pivots given are not one placement of the
    /// platform: with those inputs an equation on the platform's points fails (its pivots are
    /// not a rigid body at this geometry, or one the closed forms do not read is elsewhere).
    Inconsistent,
    /// Input `input` is an angle, returned within half a turn of its reference, and the
    /// reference is too large for that (beyond 2¹⁶ rad, about 10 400 turns): a double near it
    /// no longer holds the angle found. Give a reference within a few turns.
    FarReference {
        /// The input's index in [`Mechanism::INPUTS`](crate::mechanism::Mechanism::INPUTS).
        input: usize,
    },
}

impl fmt::Display for InverseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InverseError::Unreachable { input } => {
                write!(f, "joint input {input} cannot reach that pose")
            }
            InverseError::NoClosedForm { input } => {
                write!(f, "joint input {input} has no closed-form inverse")
            }
            InverseError::NonFinite => write!(f, "non-finite pose"),
            InverseError::Inconsistent => {
                write!(f, "the pivots are not one placement of the platform")
            }
            InverseError::FarReference { input } => write!(
                f,
                "the reference of joint input {input} is too many turns out to return an angle near it"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for InverseError {}
