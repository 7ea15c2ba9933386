//! What every `ok` must satisfy, whatever the solver and whatever the input: a finite solution,
//! the requested tolerance met (as the solver reports it, and as measured again here), and
//! det B of the start's sign. An `unverified` result (NH,
//! NR) makes the same promises but the branch, and is held to them too. Shared by the stress
//! suite, the property tests and the fuzz targets.
//!
//! The tolerance bounds the Newton correction ‖B⁻¹F‖ at the answer (a first-order estimate of
//! its distance to the root). It is measured again here with F evaluated in double-double
//! arithmetic ([`crate::exact_root::exact_correction`]), not in `f64`: near a singularity the
//! `f64` residual's rounding shifts the root it sees by more than the tolerance (a Newton run
//! in `f64` converges quadratically to that shifted root), so an `f64` correction can neither
//! confirm an answer there nor refute one. The allowance of 2 % above the tolerance is the
//! rounding the solvers leave unmeasured where they predict it a hundred times below it.

use linkage::{Mechanism, Solution};

/// How an `ok` breaks the promise.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// `non_finite_ok`, `ok_above_tolerance` or `ok_wrong_det_sign`.
    pub kind: &'static str,
    pub what: String,
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.kind, self.what)
    }
}

/// Why an `ok` (or `unverified`) result breaks the promise, or `None` when it keeps it (or
/// claims nothing). `det0` is det B at the start (only its sign matters), `tolerance` the one
/// the solve was given.
pub fn ok_violation<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    det0: f64,
    x: &[f64; M],
    sol: &Solution<N>,
    tolerance: f64,
) -> Option<Violation> {
    if !sol.status.meets_tolerance() {
        return None;
    }
    if !sol.v.iter().all(|c| c.is_finite()) {
        return Some(Violation {
            kind: "non_finite_ok",
            what: format!("ok with v = {:?}", sol.v),
        });
    }
    if !(sol.error_estimate <= tolerance) {
        return Some(Violation {
            kind: "ok_above_tolerance",
            what: format!(
                "ok with a reported error estimate {:e} above the tolerance {tolerance:e}",
                sol.error_estimate
            ),
        });
    }
    point_violation(sys, det0, x, &sol.v, tolerance)
}

/// [`ok_violation`] for a point `v` accepted at inputs `x` (a tracker's sample): finite, its
/// Newton correction with an accurate residual within `tolerance` (and 2 %), det B of the sign
/// of `det0`.
pub fn point_violation<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    det0: f64,
    x: &[f64; M],
    v: &[f64; N],
    tolerance: f64,
) -> Option<Violation> {
    if !v.iter().all(|c| c.is_finite()) {
        return Some(Violation {
            kind: "non_finite_ok",
            what: format!("ok with v = {v:?}"),
        });
    }
    let measured = crate::exact_root::exact_correction(sys, v, x).unwrap_or(f64::INFINITY);
    if !(measured <= 1.02 * tolerance) {
        return Some(Violation {
            kind: "ok_above_tolerance",
            what: format!(
                "ok although the Newton correction there (F in double-double arithmetic) is {measured:e}, above the tolerance {tolerance:e}"
            ),
        });
    }
    det_violation(sys, det0, x, v)
}

/// det B at `v` of the sign of `det0`, or why not.
fn det_violation<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    det0: f64,
    x: &[f64; M],
    v: &[f64; N],
) -> Option<Violation> {
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let det = crate::dense::Lu::new(b).map_or(0.0, |lu| lu.det);
    if !(det * det0 > 0.0) {
        return Some(Violation {
            kind: "ok_wrong_det_sign",
            what: format!(
                "ok with det B = {det:e} at the result, not of the start's sign ({det0:e})"
            ),
        });
    }
    None
}

/// The Newton correction after the next: how small rounding lets the correction at (v, x) get
/// (if it is as large as the correction itself, that is rounding, not distance).
pub fn correction_noise<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> f64 {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let mut fac = sys.new_factor();
    if sys.factor(v, x, &mut fac).is_none() {
        return f64::INFINITY;
    }
    sys.solve(&fac, &mut f);
    let w: [f64; N] = std::array::from_fn(|i| v[i] - f[i]);
    linkage::error_estimate(sys, &w, x)
}
