//! The `extern "C"` functions of `include/linkage_hexapod.h`: each one forwards to its
//! namesake in [`calls`](crate::calls), where the documentation and the no-panic proof are.

// The handle is opaque to C: it only ever holds a pointer to it.
#![allow(improper_ctypes_definitions)]

use std::ffi::c_char;
use std::mem::MaybeUninit;

use crate::calls;
use crate::geometry::LinkageGeometry;
use crate::hexapod::{Hexapod, LinkageReport};
use crate::pose::LinkagePose;
use crate::strut_correction::LinkageStrutCorrection;

/// [`calls::size`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_size() -> usize {
    calls::size()
}

/// [`calls::init`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_init(
    storage: Option<&mut MaybeUninit<Hexapod>>,
    geometry: Option<&LinkageGeometry>,
) -> i32 {
    calls::init(storage, geometry)
}

/// [`calls::set_geometry`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_geometry(
    h: Option<&mut Hexapod>,
    geometry: Option<&LinkageGeometry>,
) -> i32 {
    calls::set_geometry(h, geometry)
}

/// [`calls::set_options`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_options(
    h: Option<&mut Hexapod>,
    tolerance: f64,
    max_iterations: u32,
) -> i32 {
    calls::set_options(h, tolerance, max_iterations)
}

/// [`calls::set_strut_correction`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_strut_correction(
    h: Option<&mut Hexapod>,
    correction: Option<&LinkageStrutCorrection>,
) -> i32 {
    calls::set_strut_correction(h, correction)
}

/// [`calls::set_certify`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_set_certify(h: Option<&mut Hexapod>, on: i32) -> i32 {
    calls::set_certify(h, on)
}

/// [`calls::reset`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_reset(h: Option<&mut Hexapod>) -> i32 {
    calls::reset(h)
}

/// [`calls::is_tracking`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_is_tracking(h: Option<&Hexapod>) -> i32 {
    calls::is_tracking(h)
}

/// [`calls::inverse`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_inverse(
    h: Option<&Hexapod>,
    pose: Option<&LinkagePose>,
    legs: Option<&mut [f64; 6]>,
) -> i32 {
    calls::inverse(h, pose, legs)
}

/// [`calls::strut_corrections`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_strut_corrections(
    h: Option<&Hexapod>,
    pose: Option<&LinkagePose>,
    out: Option<&mut [f64; 6]>,
) -> i32 {
    calls::strut_corrections(h, pose, out)
}

/// [`calls::forward`].
#[no_mangle]
pub extern "C" fn linkage_hexapod_forward(
    h: Option<&mut Hexapod>,
    legs: Option<&[f64; 6]>,
    pose: Option<&mut LinkagePose>,
    report: Option<&mut LinkageReport>,
) -> i32 {
    calls::forward(h, legs, pose, report)
}

/// [`calls::status_name`].
#[no_mangle]
pub extern "C" fn linkage_status_name(code: i32) -> *const c_char {
    calls::status_name(code)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calls::STORAGE;
    use crate::status;

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
