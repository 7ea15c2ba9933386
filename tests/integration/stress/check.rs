//! Judging one solve: count its outcome, and hold every `ok` to the invariants and to the truth.

use super::geometry::Machine;
use super::run::Tally;
use linkage::{Options, Solution, SolveError};
use linkage_examples::stewart::SixSix;
use linkage_tests::invariants::ok_violation;

/// Where an ok result must lie: `Ok` if `v` is a configuration the truth allows, else why not.
pub type Allowed<'a> = &'a dyn Fn(&[f64; 18]) -> Result<(), String>;

/// Counts `solver`'s outcome, checks an ok result's invariants and its place against
/// `allowed`; returns whether it was ok.
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
    if !sol.is_ok() {
        return false;
    }
    if let Some(v) = ok_violation(&m.sys, m.det0, x, sol, options.tolerance) {
        tally.fail(v.kind, case, format!("{solver}: {}", v.what), inputs);
    }
    if sol.v.iter().all(|c| c.is_finite()) {
        if let Err(why) = allowed(&sol.v) {
            tally.count(format!("{solver}: WRONG BRANCH ok"));
            tally.fail("wrong_branch_ok", case, format!("{solver}: {why}"), inputs);
        }
    }
    true
}
