//! The calls of `include/linkage_hexapod.h` in the Rust ABI: `exports` gives each its C
//! symbol through a one-line `extern "C"` shim.
//!
//! They live apart from the shims for the link-time no-panic proof (`tests/no_panic`): an
//! `extern "C"` function cannot unwind (a panic inside aborts), so the optimiser treats a call
//! to one as panic-free and a `#[no_panic]` wrapper around it would prove nothing. Wrapped
//! around these, it proves that nothing the C side can pass (bar the pointers' validity, its
//! contract) reaches a panic, which in LinuxCNC would abort the motion controller.
//!
//! Pointers arrive as `Option<&T>`: null is `None` and answers [`status::NULL_POINTER`], so
//! no function dereferences a raw pointer. The handle lives in storage the caller owns
//! (`LINKAGE_HEXAPOD_STORAGE` bytes, 16-byte aligned): nothing here allocates.

use std::ffi::c_char;
use std::mem::MaybeUninit;

use crate::geometry::LinkageGeometry;
use crate::hexapod::{Hexapod, LinkageReport};
use crate::pose::LinkagePose;
use crate::status;
use crate::strut_correction::LinkageStrutCorrection;

/// Bytes of caller storage a handle needs (`LINKAGE_HEXAPOD_STORAGE` in the header).
pub const STORAGE: usize = 8192;
/// The alignment the header gives that storage.
pub const ALIGN: usize = 16;

// The header's storage must hold a handle, and C never runs a destructor.
const _: () = assert!(std::mem::size_of::<Hexapod>() <= STORAGE);
const _: () = assert!(std::mem::align_of::<Hexapod>() <= ALIGN);
const _: () = assert!(!std::mem::needs_drop::<Hexapod>());

fn code(r: Result<(), i32>) -> i32 {
    r.err().unwrap_or(status::OK)
}

/// The size of a handle, for a caller to check its storage against.
pub fn size() -> usize {
    std::mem::size_of::<Hexapod>()
}

/// Builds a handle in `storage` for `geometry`. On a non-zero return `storage` holds no handle.
pub fn init(storage: Option<&mut MaybeUninit<Hexapod>>, geometry: Option<&LinkageGeometry>) -> i32 {
    let (Some(storage), Some(geometry)) = (storage, geometry) else {
        return status::NULL_POINTER;
    };
    match Hexapod::new(geometry) {
        Ok(h) => {
            storage.write(h);
            status::OK
        }
        Err(c) => c,
    }
}

/// Replaces the geometry; the next forward call starts tracking afresh. On error the handle
/// keeps its previous geometry and state.
pub fn set_geometry(h: Option<&mut Hexapod>, geometry: Option<&LinkageGeometry>) -> i32 {
    let (Some(h), Some(geometry)) = (h, geometry) else {
        return status::NULL_POINTER;
    };
    code(h.set_geometry(geometry))
}

/// Convergence tolerance (geometry length units) and Newton iteration limit; a change
/// restarts tracking at the next forward call.
pub fn set_options(h: Option<&mut Hexapod>, tolerance: f64, max_iterations: u32) -> i32 {
    let Some(h) = h else {
        return status::NULL_POINTER;
    };
    code(h.set_options(tolerance, max_iterations))
}

/// genhexkins' strut length correction: the joints' axes and the screw lead (0 turns it off).
/// Inverse kinematics adds it to each strut; forward kinematics solves for it. A change
/// restarts tracking at the next forward call; on error the handle keeps its previous one.
pub fn set_strut_correction(
    h: Option<&mut Hexapod>,
    correction: Option<&LinkageStrutCorrection>,
) -> i32 {
    let (Some(h), Some(correction)) = (h, correction) else {
        return status::NULL_POINTER;
    };
    code(h.set_strut_correction(correction))
}

/// Certification of every forward step: 0 off (the default), 1 on; a change restarts
/// tracking at the next forward call. Any other value is `INVALID_OPTIONS`.
pub fn set_certify(h: Option<&mut Hexapod>, on: i32) -> i32 {
    let Some(h) = h else {
        return status::NULL_POINTER;
    };
    match on {
        0 | 1 => {
            h.set_certify(on == 1);
            status::OK
        }
        _ => status::INVALID_OPTIONS,
    }
}

/// Forgets the tracked branch: the next forward call starts at the pose it is given.
pub fn reset(h: Option<&mut Hexapod>) -> i32 {
    let Some(h) = h else {
        return status::NULL_POINTER;
    };
    h.reset();
    status::OK
}

/// 1 while a branch is tracked, 0 before the first forward call or after a reset, -1 for null.
pub fn is_tracking(h: Option<&Hexapod>) -> i32 {
    h.map_or(status::NULL_POINTER, |h| i32::from(h.is_tracking()))
}

/// Leg lengths for `pose` (closed form). `legs` is written only on success.
pub fn inverse(
    h: Option<&Hexapod>,
    pose: Option<&LinkagePose>,
    legs: Option<&mut [f64; 6]>,
) -> i32 {
    let (Some(h), Some(pose), Some(legs)) = (h, pose, legs) else {
        return status::NULL_POINTER;
    };
    match h.inverse(pose) {
        Ok(l) => {
            *legs = l;
            status::OK
        }
        Err(c) => c,
    }
}

/// The strut corrections at `pose` (what `linkage_hexapod_inverse` added to each strut;
/// zeros when the correction is off). `out` is written only on success.
pub fn strut_corrections(
    h: Option<&Hexapod>,
    pose: Option<&LinkagePose>,
    out: Option<&mut [f64; 6]>,
) -> i32 {
    let (Some(h), Some(pose), Some(out)) = (h, pose, out) else {
        return status::NULL_POINTER;
    };
    match h.strut_corrections(pose) {
        Ok(c) => {
            *out = c;
            status::OK
        }
        Err(c) => c,
    }
}

/// Forward kinematics on the tracked branch. `pose` is in–out: the start pose when not yet
/// tracking, otherwise the angle words nearest which to report (each within 2¹⁶ rad, else
/// `INVALID_INPUT`); written only on success, and then its strut lengths match the legs to the
/// tolerance.
/// `report` may be null.
pub fn forward(
    h: Option<&mut Hexapod>,
    legs: Option<&[f64; 6]>,
    pose: Option<&mut LinkagePose>,
    report: Option<&mut LinkageReport>,
) -> i32 {
    let (Some(h), Some(legs), Some(pose)) = (h, legs, pose) else {
        if let Some(r) = report {
            r.status = status::NULL_POINTER;
        }
        return status::NULL_POINTER;
    };
    let mut scratch = LinkageReport::default();
    h.forward(legs, pose, report.unwrap_or(&mut scratch))
}

/// A static, lowercase name for a status code ("ok", "branch_changed", …); never null.
pub fn status_name(code: i32) -> *const c_char {
    status::name_ptr(code)
}
