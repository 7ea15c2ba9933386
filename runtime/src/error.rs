//! Failures as data: every way a call can fail is a variant, never a panic.

use core::fmt;

pub use linkage_geometry::GeometryError;

/// Why joint inputs could not be recovered from pivot positions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InverseError {
    /// No joint value of input `input` places the chain's pivots there.
    Unreachable { input: usize },
    /// Input `input` has no closed-form inverse for this chain.
    NoClosedForm { input: usize },
    /// The pose or pivots contain NaN or infinite values.
    NonFinite,
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
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for InverseError {}
