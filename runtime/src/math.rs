//! Float maths through `libm` (shared with the generator).

pub use linkage_geometry::math::*;
