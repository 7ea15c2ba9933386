//! Status codes: every outcome of a call as one C `int`, keeping the solvers' typed outcomes.
//!
//! 0 is a solution on the tracked branch. Positive codes are the solver's refusals (the
//! joints were valid, but no solution on the tracked branch could be confirmed); negative
//! codes are calls that could not be attempted. The mapping goes through the runtime's
//! `word()`s, so a status a newer runtime adds still lands on a non-zero code.

use std::ffi::{c_char, CStr};

use linkage::{SolveError, Status};

/// Converged on the tracked branch.
pub const OK: i32 = 0;
/// The joint-space path leaves the valid joint space through a fold (a direct singularity).
pub const FOLD: i32 = 1;
/// The only solution found lies on another branch (det B changed sign): refused.
pub const BRANCH_CHANGED: i32 = 2;
/// Newton did not converge within the iteration limit.
pub const NOT_CONVERGED: i32 = 3;
/// Continuation's step size underflowed before reaching the target.
pub const STEP_TOO_SMALL: i32 = 4;
/// B became singular and the method could not go on.
pub const SINGULAR: i32 = 5;
/// The iteration stopped short of the requested tolerance, or the pose it gives, in the angle
/// words nearest the caller's, misses the legs by more than the tolerance.
pub const TOLERANCE_NOT_MET: i32 = 6;
/// A non-ok solver status this interface does not name (never counted as a success).
pub const FAILED: i32 = 7;
/// Converged to the tolerance by a method that cannot establish the branch (Newton–Raphson,
/// Newton homotopy): possibly another assembly mode, so not a success. The hexapod interface
/// tracks by continuation and does not return it today; the code keeps it apart if it ever does.
pub const UNVERIFIED: i32 = 8;
/// With certification on: the step to the sample was solved but not proven to keep the
/// branch (interval certificates), so it is refused.
pub const UNPROVEN: i32 = 9;

/// A pointer argument was null.
pub const NULL_POINTER: i32 = -1;
/// A leg length, pose or option value is NaN or infinite.
pub const NON_FINITE: i32 = -2;
/// A leg length is out of range (not positive), or a pose angle word is beyond ±2¹⁶ rad
/// (about 3.75e6 degrees), where a double no longer holds an angle to report near it.
pub const INVALID_INPUT: i32 = -3;
/// The geometry cannot be modelled (non-finite values, collinear platform frame).
pub const INVALID_GEOMETRY: i32 = -4;
/// Tolerance not finite and positive, or an iteration limit of zero.
pub const INVALID_OPTIONS: i32 = -5;
/// The legs and the pose given to start tracking do not match.
pub const POSE_MISMATCH: i32 = -6;
/// B is singular at the start configuration: no branch to track.
pub const SINGULAR_START: i32 = -7;
/// The start configuration does not satisfy the constraints.
pub const INCONSISTENT_START: i32 = -8;
/// No leg lengths reach that pose.
pub const UNREACHABLE: i32 = -9;
/// The storage passed to init is smaller or less aligned than the handle needs.
pub const BAD_STORAGE: i32 = -10;

/// The code of a solver status: `Status::is_ok` alone decides 0.
pub fn of_status(status: &Status) -> i32 {
    if *status == Status::Converged {
        return OK;
    }
    match status.word() {
        "fold" => FOLD,
        "branch_changed" => BRANCH_CHANGED,
        "not_converged" => NOT_CONVERGED,
        "step_too_small" => STEP_TOO_SMALL,
        "singular" => SINGULAR,
        "tolerance_not_met" => TOLERANCE_NOT_MET,
        "unverified" => UNVERIFIED,
        _ => FAILED,
    }
}

/// The code of an input error.
pub fn of_error(error: &SolveError) -> i32 {
    match error.word() {
        "non_finite" => NON_FINITE,
        "invalid_input" => INVALID_INPUT,
        "invalid_options" => INVALID_OPTIONS,
        "singular_start" => SINGULAR_START,
        "inconsistent_start" => INCONSISTENT_START,
        _ => INVALID_INPUT,
    }
}

/// One lowercase word per code, as a static C string (never null).
pub fn name(code: i32) -> &'static CStr {
    match code {
        OK => c"ok",
        FOLD => c"fold",
        BRANCH_CHANGED => c"branch_changed",
        NOT_CONVERGED => c"not_converged",
        STEP_TOO_SMALL => c"step_too_small",
        SINGULAR => c"singular",
        TOLERANCE_NOT_MET => c"tolerance_not_met",
        FAILED => c"failed",
        UNVERIFIED => c"unverified",
        UNPROVEN => c"unproven",
        NULL_POINTER => c"null_pointer",
        NON_FINITE => c"non_finite",
        INVALID_INPUT => c"invalid_input",
        INVALID_GEOMETRY => c"invalid_geometry",
        INVALID_OPTIONS => c"invalid_options",
        POSE_MISMATCH => c"pose_mismatch",
        SINGULAR_START => c"singular_start",
        INCONSISTENT_START => c"inconsistent_start",
        UNREACHABLE => c"unreachable",
        BAD_STORAGE => c"bad_storage",
        _ => c"unknown",
    }
}

/// [`name`] as a C pointer.
pub fn name_ptr(code: i32) -> *const c_char {
    name(code).as_ptr()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_converged_is_ok() {
        assert_eq!(of_status(&Status::Converged), OK);
        let refusals = [
            (Status::Fold { lambda: 0.5 }, FOLD),
            (Status::BranchChanged, BRANCH_CHANGED),
            (Status::NotConverged { residual_norm: 1.0 }, NOT_CONVERGED),
            (Status::StepTooSmall { lambda: 0.5 }, STEP_TOO_SMALL),
            (Status::Singular { lambda: 0.5 }, SINGULAR),
            (Status::ToleranceNotMet { achieved: 1.0 }, TOLERANCE_NOT_MET),
            (Status::Unverified, UNVERIFIED),
        ];
        for (status, code) in refusals {
            assert_eq!(of_status(&status), code, "{status:?}");
            assert!(code > 0);
            assert_eq!(name(code).to_str().unwrap(), status.word());
        }
    }

    #[test]
    fn input_errors_are_negative_and_named() {
        for (e, code) in [
            (SolveError::NonFinite, NON_FINITE),
            (SolveError::InvalidInput { input: 2 }, INVALID_INPUT),
            (SolveError::SingularStart, SINGULAR_START),
            (
                SolveError::InconsistentStart { residual_norm: 1.0 },
                INCONSISTENT_START,
            ),
        ] {
            assert_eq!(of_error(&e), code);
            assert!(code < 0);
            assert_eq!(name(code).to_str().unwrap(), e.word());
        }
    }

    #[test]
    fn every_code_has_its_own_name() {
        let names: Vec<_> = (-10..=8).map(name).collect();
        for (i, a) in names.iter().enumerate() {
            assert_ne!(a.to_str().unwrap(), "unknown");
            assert!(names[i + 1..].iter().all(|b| b != a), "{a:?} twice");
        }
        assert_eq!(name(1000).to_str().unwrap(), "unknown");
    }
}
