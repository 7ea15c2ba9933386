//! Checks on option values, applied while the command line is parsed: a bad value is a
//! message naming the option, before any work is done.

/// A finite number above 0.
pub fn positive(s: &str) -> Result<f64, String> {
    let x: f64 = s.parse().map_err(|_| format!("`{s}` is not a number"))?;
    if x.is_finite() && x > 0.0 {
        Ok(x)
    } else {
        Err(format!("must be a finite number above 0, not {s}"))
    }
}

/// Largest `--tolerance`, mm. A tolerance is a distance the answer may be off by; above 1 mm
/// (against a platform of about 360 mm) an `ok` row could be visibly wrong.
pub const MAX_TOLERANCE: f64 = 1.0;

/// A convergence tolerance: finite, above 0 and at most [`MAX_TOLERANCE`].
pub fn tolerance(s: &str) -> Result<f64, String> {
    let t = positive(s)?;
    if t <= MAX_TOLERANCE {
        Ok(t)
    } else {
        Err(format!(
            "{s} mm is not small against the mechanism: at most {MAX_TOLERANCE} mm"
        ))
    }
}

/// A half-width in yaw, pitch and roll: finite, above 0 and at most π.
pub fn angle(s: &str) -> Result<f64, String> {
    let a = positive(s)?;
    if a <= std::f64::consts::PI {
        Ok(a)
    } else {
        Err(format!("must be at most π rad, not {s}"))
    }
}
