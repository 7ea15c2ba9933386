//! A C interface to linkage's 6-6 hexapod kinematics: a static library and the header
//! `include/linkage_hexapod.h`.
//!
//! The geometry (six base and six platform joint centres) is set at run time. Inverse
//! kinematics is closed form; forward kinematics is the runtime's [`linkage::Tracker`]:
//! warm-started from the last accepted solution, confirmed by a contraction test, falling
//! back to pseudo-arc-length continuation, and refusing any result on another branch
//! (det B of the other sign). Every call returns a [status code](status) that keeps the
//! solver's typed outcome; only 0 is a solution. After `linkage_hexapod_init` nothing
//! allocates, and the handle lives in storage the caller owns.
//!
//! The same calls from Rust:
//!
//! ```
//! use linkage_ffi::{status, Hexapod, LinkageGeometry, LinkagePose, LinkageReport};
//! let geometry = LinkageGeometry {
//!     base: [[-22.95, 13.25, 0.0], [22.95, 13.25, 0.0], [22.95, 13.25, 0.0],
//!            [0.0, -26.5, 0.0], [0.0, -26.5, 0.0], [-22.95, 13.25, 0.0]],
//!     platform: [[-1.0, 11.5, 0.0], [1.0, 11.5, 0.0], [10.459, -4.884, 0.0],
//!                [9.459, -6.616, 0.0], [-9.459, -6.616, 0.0], [-10.459, -4.884, 0.0]],
//! };
//! let mut hex = Hexapod::new(&geometry).unwrap();
//! let home = LinkagePose { z: 20.0, ..Default::default() };
//! let legs = hex.inverse(&home).unwrap();
//! // The first forward call starts tracking at the pose it is given…
//! let mut pose = home;
//! let mut report = LinkageReport::default();
//! assert_eq!(hex.forward(&legs, &mut pose, &mut report), status::OK);
//! // …later ones follow the legs on that branch.
//! let moved = LinkagePose { x: 0.5, z: 20.5, c: 5.0, ..home };
//! assert_eq!(hex.forward(&hex.inverse(&moved).unwrap(), &mut pose, &mut report), status::OK);
//! // To the tolerance: 1e-9 length units on pivots about 11 units from the centre, so the
//! // angle in degrees is known to about 1e-9 / 11 · 180 / π, well within 1e-6.
//! assert!((pose.c - 5.0).abs() < 1e-6 && report.proximity > 0.0);
//! ```

pub mod calls;
mod exports;
mod geometry;
mod hexapod;
mod pose;
pub mod status;
mod strut_correction;

pub use calls::{ALIGN, STORAGE};
pub use exports::*;
pub use geometry::LinkageGeometry;
pub use hexapod::{Hexapod, LinkageReport};
pub use pose::LinkagePose;
pub use strut_correction::LinkageStrutCorrection;
