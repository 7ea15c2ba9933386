//! The `extern "C"` functions of `include/linkage_hexapod.h`.
//!
//! Pointers arrive as `Option<&T>`: null is `None` and answers [`status::NULL_POINTER`], so
//! no function dereferences a raw pointer. The handle lives in storage the caller owns
//! (`LINKAGE_HEXAPOD_STORAGE` bytes, 16-byte aligned): nothing here allocates.

// The handle is opaque to C: it only ever holds a pointer to it.
#![allow(improper_ctypes_definitions)]

use std::ffi::c_char;
use std::mem::MaybeUninit;

use crate::geometry::LinkageGeometry;
use crate::hexapod::{Hexapod, LinkageReport};
use crate::pose::LinkagePose;
use crate::status;
use crate::strut_correction::LinkageStrutCorrection;

/// Bytes of caller storage a handle needs (`LINKAGE_HEXAPOD_STORAGE` in the header).
pub const STORAGE: usize = 4096;
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
#[no_mangle]
pub extern "C" fn linkage_hexapod_size() -> usize {
    std::mem::size_of::<Hexapod>()
}

/// Builds a handle in `storage` for `geometry`. On a non-zero return `storage` holds no handle.
#[no_mangle]
pub extern "C" fn linkage_hexapod_init(
    storage: Option<&mut MaybeUninit<Hexapod>>,
    geometry: Option<&LinkageGeometry>,
) -> i32 {
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
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_geometry(
    h: Option<&mut Hexapod>,
    geometry: Option<&LinkageGeometry>,
) -> i32 {
    let (Some(h), Some(geometry)) = (h, geometry) else {
        return status::NULL_POINTER;
    };
    code(h.set_geometry(geometry))
}

/// Convergence tolerance (geometry length units) and Newton iteration limit; a change
/// restarts tracking at the next forward call.
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_options(
    h: Option<&mut Hexapod>,
    tolerance: f64,
    max_iterations: u32,
) -> i32 {
    let Some(h) = h else {
        return status::NULL_POINTER;
    };
    code(h.set_options(tolerance, max_iterations))
}

/// genhexkins' strut length correction: the joints' axes and the screw lead (0 turns it off).
/// Inverse kinematics adds it to each strut; forward kinematics solves for it. A change
/// restarts tracking at the next forward call; on error the handle keeps its previous one.
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_strut_correction(
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
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_certify(h: Option<&mut Hexapod>, on: i32) -> i32 {
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
#[no_mangle]
pub extern "C" fn linkage_hexapod_reset(h: Option<&mut Hexapod>) -> i32 {
    let Some(h) = h else {
        return status::NULL_POINTER;
    };
    h.reset();
    status::OK
}

/// 1 while a branch is tracked, 0 before the first forward call or after a reset, -1 for null.
#[no_mangle]
pub extern "C" fn linkage_hexapod_is_tracking(h: Option<&Hexapod>) -> i32 {
    h.map_or(status::NULL_POINTER, |h| i32::from(h.is_tracking()))
}

/// Leg lengths for `pose` (closed form). `legs` is written only on success.
#[no_mangle]
pub extern "C" fn linkage_hexapod_inverse(
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
#[no_mangle]
pub extern "C" fn linkage_hexapod_strut_corrections(
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
/// tracking, otherwise the angle words nearest which to report; written only on success.
/// `report` may be null.
#[no_mangle]
pub extern "C" fn linkage_hexapod_forward(
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
#[no_mangle]
pub extern "C" fn linkage_status_name(code: i32) -> *const c_char {
    status::name_ptr(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn null_pointers_are_answered_not_followed() {
        let g = crate::hexapod::tests::genhex();
        assert_eq!(linkage_hexapod_init(None, Some(&g)), status::NULL_POINTER);
        let mut slot = MaybeUninit::<Hexapod>::uninit();
        assert_eq!(
            linkage_hexapod_init(Some(&mut slot), None),
            status::NULL_POINTER
        );
        assert_eq!(linkage_hexapod_init(Some(&mut slot), Some(&g)), status::OK);
        let h = slot.write(Hexapod::new(&g).unwrap());
        let mut report = LinkageReport::default();
        let legs = [30.0; 6];
        assert_eq!(
            linkage_hexapod_forward(Some(h), Some(&legs), None, Some(&mut report)),
            status::NULL_POINTER
        );
        assert_eq!(report.status, status::NULL_POINTER);
        assert_eq!(
            linkage_hexapod_inverse(None, None, None),
            status::NULL_POINTER
        );
        assert_eq!(linkage_hexapod_is_tracking(None), status::NULL_POINTER);
        assert_eq!(linkage_hexapod_reset(None), status::NULL_POINTER);
        assert_eq!(
            linkage_hexapod_set_options(None, 1e-9, 10),
            status::NULL_POINTER
        );
        assert_eq!(
            linkage_hexapod_set_geometry(None, Some(&g)),
            status::NULL_POINTER
        );
        assert_eq!(linkage_hexapod_set_certify(None, 1), status::NULL_POINTER);
        assert_eq!(
            linkage_hexapod_set_strut_correction(Some(h), None),
            status::NULL_POINTER
        );
        assert_eq!(
            linkage_hexapod_strut_corrections(Some(h), None, None),
            status::NULL_POINTER
        );
        // Only 0 and 1 switch certification.
        assert_eq!(
            linkage_hexapod_set_certify(Some(h), 2),
            status::INVALID_OPTIONS
        );
        assert_eq!(linkage_hexapod_set_certify(Some(h), 1), status::OK);
    }

    #[test]
    fn a_handle_round_trip_through_the_c_functions() {
        let g = crate::hexapod::tests::genhex();
        let mut slot = MaybeUninit::<Hexapod>::uninit();
        let mut bad = g;
        bad.base[0][0] = f64::NAN;
        assert_eq!(
            linkage_hexapod_init(Some(&mut slot), Some(&bad)),
            status::INVALID_GEOMETRY
        );
        let h = slot.write(Hexapod::new(&g).unwrap());
        assert_eq!(linkage_hexapod_is_tracking(Some(h)), 0);
        let home = LinkagePose {
            z: 20.0,
            ..Default::default()
        };
        let mut legs = [0.0; 6];
        assert_eq!(
            linkage_hexapod_inverse(Some(h), Some(&home), Some(&mut legs)),
            status::OK
        );
        let mut pose = home;
        assert_eq!(
            linkage_hexapod_forward(Some(h), Some(&legs), Some(&mut pose), None),
            status::OK
        );
        assert_eq!(linkage_hexapod_is_tracking(Some(h)), 1);
        assert_eq!(
            linkage_hexapod_set_geometry(Some(h), Some(&bad)),
            status::INVALID_GEOMETRY
        );
        assert_eq!(
            linkage_hexapod_is_tracking(Some(h)),
            1,
            "a refused geometry changes nothing"
        );
        assert_eq!(linkage_hexapod_set_geometry(Some(h), Some(&g)), status::OK);
        assert_eq!(linkage_hexapod_is_tracking(Some(h)), 0);
        assert!(linkage_hexapod_size() <= STORAGE);
        assert!(!linkage_status_name(status::BRANCH_CHANGED).is_null());
    }
}
