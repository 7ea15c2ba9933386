//! Failures as data: every way a call can fail is a variant, never a panic.

use core::fmt;

/// A geometry that cannot define the mechanism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeometryError {
    /// A geometry value is NaN or infinite.
    NonFinite { name: &'static str },
    /// No geometry value or pivot has this name.
    UnknownName,
    /// The platform's three frame pivots are (nearly) collinear.
    CollinearFrame,
    /// A platform pivot left the plane of the frame, but the system was generated in the
    /// coplanar form of Eq. 16; declare the platform with `form = general`.
    NotCoplanar,
    /// A pair's axis is given by (nearly) coincident points.
    DegenerateAxis,
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GeometryError::NonFinite { name } => write!(f, "geometry value `{name}` is not finite"),
            GeometryError::UnknownName => write!(f, "no geometry value or pivot has that name"),
            GeometryError::CollinearFrame => write!(f, "the platform's frame pivots are collinear"),
            GeometryError::NotCoplanar => write!(
                f,
                "a platform pivot is off the frame's plane but the system uses the coplanar form"
            ),
            GeometryError::DegenerateAxis => write!(f, "a pair axis is given by coincident points"),
        }
    }
}

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
impl std::error::Error for GeometryError {}
#[cfg(feature = "std")]
impl std::error::Error for InverseError {}
