//! The hexapod's geometry as C hands it over.

/// Joint centres: base ones in the base (world) frame, platform ones in the platform frame;
/// leg `i` joins `base[i]` to `platform[i]`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkageGeometry {
    pub base: [[f64; 3]; 6],
    pub platform: [[f64; 3]; 6],
}
