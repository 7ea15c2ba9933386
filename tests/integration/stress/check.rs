//! Judging one solve: count its outcome, and hold every `ok` to the invariants and to the truth.
//! An `unverified` result (NH, NR) is held to the same invariants; off the truth it is counted,
//! not failed: its status does not claim the branch.

use super::geometry::Machine;
use super::run::Tally;
use linkage::{Options, Solution, SolveError, Status};
use linkage_examples::stewart::SixSix;
use linkage_tests::invariants::{correction_noise, ok_violation};

/// Where an ok result must lie: `Ok` if `v` is a configuration the truth allows, else why not.
pub type Allowed<'a> = &'a dyn Fn(&[f64; 18]) -> Result<(), String>;

/// Counts `solver`'s outcome, checks the invariants of a result that meets the tolerance and
/// an ok result's place against `allowed`; returns whether it met the tolerance (ok, or
/// `unverified` from NH and NR).
#[allow(clippy::too_many_arguments)]
pub fn judge<S: SixSix>(
    tally: &mut Tally,
    case: u64,
    inputs: &dyn std::fmt::Debug,
    solver: &str,
    m: &Machine<S>,
    x: &[f64; 6],
    options: &Options,
    result: &Result<Solution<18>, SolveError>,
    allowed: Allowed,
) -> bool {
    let sol = match result {
        Err(e) => {
            tally.count(format!("{solver}: error {}", e.word()));
            return false;
        }
        Ok(sol) => sol,
    };
    tally.count(format!("{solver}: {}", sol.status.word()));
    if !sol.status.meets_tolerance() {
        return false;
    }
    if let Some(v) = ok_violation(&m.sys, m.det0, x, sol, options.tolerance) {
        tally.fail(v.kind, case, format!("{solver}: {}", v.what), inputs);
    }
    if sol.v.iter().all(|c| c.is_finite()) {
        if let Err(why) = allowed(&sol.v) {
            if sol.is_ok() {
                tally.count(format!("{solver}: WRONG BRANCH ok"));
                tally.fail("wrong_branch_ok", case, format!("{solver}: {why}"), inputs);
            } else {
                tally.count(format!(
                    "{solver}: unverified and not the truth (as the status allows)"
                ));
            }
        }
    }
    true
}

/// Whether a refusal `status` is `tolerance_not_met` where rounding at the truth `v` (at inputs
/// `x`) comes within a factor of 4 of `tolerance`: the tolerance is then at the rounding floor
/// there and a refusal for it is honest, not a reachable target refused. Returns the floor
/// measured when so: at the (polished) truth the Newton correction and the one after it are
/// rounding alone, and the larger of the two is its size.
pub fn refused_at_rounding_floor<S: SixSix>(
    m: &Machine<S>,
    status: &Status,
    v: &[f64; 18],
    x: &[f64; 6],
    tolerance: f64,
) -> Option<f64> {
    if !matches!(status, Status::ToleranceNotMet { .. }) {
        return None;
    }
    let floor = linkage::error_estimate(&m.sys, v, x).max(correction_noise(&m.sys, v, x));
    (4.0 * floor >= tolerance).then_some(floor)
}
