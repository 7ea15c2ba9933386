//! The stress suite of issue 9: random machines, targets, trajectories and bad values, each
//! result held to ground truth computed independently (fine continuation, inverse kinematics).
//! No wrong branch and no non-finite value may be labelled ok; an ok must meet its tolerance
//! with det B of the start's sign. Sizing, seeds and replay: `stress/run.rs`
//! (`LINKAGE_STRESS=10` for ten times the cases); the counts print at the end of each test
//! (`-- --nocapture`).

mod arc;
mod bad_values;
mod check;
mod fk;
mod geometry;
mod oracle;
mod run;
mod starts;
mod tracker;
mod trajectory;

use geometry::random_geometry;
use linkage_examples::stewart::{Stewart, StewartGeneral};
use run::{Run, Tally};

fn forward_kinematics(run: &Run, solvers: fk::Solvers) {
    let mut tally = Tally::new(run);
    for case in run.cases(3000) {
        let mut rng = run.rng(case);
        let g = random_geometry(&mut rng);
        if g.coplanar() {
            fk::case::<Stewart>(&mut tally, case, &mut rng, g, solvers);
        } else {
            fk::case::<StewartGeneral>(&mut tally, case, &mut rng, g, solvers);
        }
    }
    tally.finish();
}

/// Random targets for random machines, solved by PH and PH with detours.
#[test]
fn forward_kinematics_by_continuation() {
    let run = Run::new("forward_kinematics_by_continuation", 0x5EED_0009);
    forward_kinematics(&run, fk::Solvers::Continuation);
}

/// The same targets (same seed), solved by NH and NR.
#[test]
fn forward_kinematics_by_newton() {
    let run = Run::new("forward_kinematics_by_newton", 0x5EED_0009);
    forward_kinematics(&run, fk::Solvers::Newton);
}

/// Random trajectories, 10 Hz to 1 kHz, clear of singular surfaces, grazing them, crossing
/// them, or fast at coarse sampling, followed by `Tracker::update`.
#[test]
fn tracker_on_random_trajectories() {
    let run = Run::new("tracker_on_random_trajectories", 0x5EED_0002);
    let mut tally = Tally::new(&run);
    for case in run.cases(200) {
        let mut rng = run.rng(case);
        let g = random_geometry(&mut rng);
        if g.coplanar() {
            tracker::case::<Stewart>(&mut tally, case, &mut rng, g);
        } else {
            tracker::case::<StewartGeneral>(&mut tally, case, &mut rng, g);
        }
    }
    tally.finish();
}

/// NaN, infinities, zero, negative, subnormal and huge legs, legs a few ulps from the start,
/// absurd options: for every solver and the tracker.
#[test]
fn bad_values_for_every_solver() {
    let run = Run::new("bad_values_for_every_solver", 0x5EED_0003);
    let mut tally = Tally::new(&run);
    for case in run.cases(3000) {
        let mut rng = run.rng(case);
        let g = if rng.next_u64().is_multiple_of(2) {
            geometry::Geometry::table_iii()
        } else {
            random_geometry(&mut rng)
        };
        if g.coplanar() {
            bad_values::case::<Stewart>(&mut tally, case, &mut rng, g);
        } else {
            bad_values::case::<StewartGeneral>(&mut tally, case, &mut rng, g);
        }
    }
    tally.finish();
}

/// Starts a relative 1e-15 … 1e-6 either side of a singular surface: a refusal says singular,
/// an acceptance survives rounding and scaling.
#[test]
fn starts_near_singular_surfaces() {
    let run = Run::new("starts_near_singular_surfaces", 0x5EED_0004);
    let mut tally = Tally::new(&run);
    for case in run.cases(1500) {
        let mut rng = run.rng(case);
        let g = random_geometry(&mut rng);
        if g.coplanar() {
            starts::case::<Stewart>(&mut tally, case, &mut rng, g);
        } else {
            starts::case::<StewartGeneral>(&mut tally, case, &mut rng, g);
        }
    }
    tally.finish();
}
