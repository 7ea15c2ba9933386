//! The stress suite of issue 9: random machines, targets, trajectories and bad values, each
//! result held to ground truth computed independently (fine continuation, inverse kinematics).
//! No wrong branch and no non-finite value may be labelled ok; an ok must meet its tolerance
//! with det B of the start's sign. Sizing, seeds and replay: `stress/run.rs`
//! (`LINKAGE_STRESS=10` for ten times the cases); the counts print at the end of each test
//! (`-- --nocapture`).
//!
//! These tests hunt the defects of issue 9. Each test's comment lists what it found on the
//! runtime it was written against (commit 71447e1) and what cured it; the `known_cases_*` tests
//! replay the cases that found a defect after that, each failing before its fix.
//!
//! All pass at ×1 (about 30 s for the suite on 2 cores) and at ×10 (351–438 s), no failure of any
//! kind:
//! `LINKAGE_STRESS=10 cargo test -p linkage-tests --test integration stress:: -- --nocapture`.
//! At ×10: PH 25 116 ok of 29 998 targets (2 626 fold, 2 109 tolerance_not_met), detours
//! 25 823 ok; NH 25 219 and NR 24 452 unverified, of which 28 and 137 are not the truth (as
//! that status allows); the tracker accepted 1 118 117 of 1 258 173 samples (58 581 refused
//! as folds); bad values: 30 000 cases, 0 ok without its promises; near-singular starts:
//! 11 024 cases. At ×1: PH 2 539 ok, NH 2 532 and NR 2 460 unverified (2 and 12 not the
//! truth), the tracker 120 100 of 135 253 samples.

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
mod velocity;

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
///
/// Found at 71447e1, cured by the issue 9 fixes:
/// - `ok_above_tolerance` (683 at ×1): `Converged` near singular targets with the error
///   estimate, reported or measured again at the result, above the tolerance (defect 10).
/// - `ph_refused_reachable_target` (5 at ×1, 10 at ×10): PH refuses targets whose straight
///   segment keeps |det B| above 1 % of the start's. Seven overshoot λ = 1 by 0.0004–0.012 and
///   end `StepTooSmall` (or `Fold` at λ = 1) (defect 3b; cases 220, 1898, 2656, 8307, 11170,
///   24062 with `Linear::Dense`, 11928 with the generated factorisation). Three, all with
///   `Linear::Dense`, report a fold at λ = 0.08–0.22 that the generated factorisation passes
///   (cases 449, 638, 13850): a Dense-only false fold (full Newton in the dense corrector,
///   now the chord iteration).
///
/// Found at 71447e1, cured by det B step control in PH: at ×10, `wrong_branch_ok` for PH
/// (case 5441) and for detours built on such a PH leg (cases 18854, 22865, 28043): the straight
/// segment is S-shaped (two folds within 3e-6 of λ, near 0.97957), PH steps over both in one
/// step, sees det B of the same sign on either side and calls the far sheet ok; PH itself
/// reports `Fold` for targets at λ = 0.979572 and 0.97958 on the same segment, and `Converged`
/// for λ = 0.98 and beyond. Case 17803 is another such pair, near λ = 0.0157.
#[test]
fn forward_kinematics_by_continuation() {
    let run = Run::new("forward_kinematics_by_continuation", 0x5EED_0009);
    forward_kinematics(&run, fk::Solvers::Continuation);
}

/// The same targets (same seed), solved by NH and NR.
///
/// Found at 71447e1:
/// - `ok_above_tolerance` (628 at ×1): as above, defect 10; cured. Later, at ×10, NH's last
///   step at x0 + (x* − x0), an ulp off the target: cured (it solves at the target itself).
/// - `wrong_branch_ok` (15 at ×1: NR 12, NH 3; 170 at ×10: NR 139, NH 31): NR converges to
///   another assembly mode of the start's det B sign (8 to 360 mm from every truth; e.g. cases
///   23, 304, 961), and NH jumps across a fold to such a mode (e.g. cases 1330, 1814). Cured
///   by `Status::Unverified`: NR and NH no longer say ok; their results are held to every
///   other promise and counted where they are not the truth.
#[test]
fn forward_kinematics_by_newton() {
    let run = Run::new("forward_kinematics_by_newton", 0x5EED_0009);
    forward_kinematics(&run, fk::Solvers::Newton);
}

/// Random trajectories, 10 Hz to 1 kHz, clear of singular surfaces, grazing them, crossing
/// them, or fast at coarse sampling, followed by `Tracker::update`.
///
/// Found at 71447e1, cured by the issue 9 fixes:
/// - `ok_above_tolerance`: accepted samples whose next Newton correction is above the
///   tolerance (1.0–10× it, mostly at the rounding floor of large random machines): the fast
///   path takes the predictor step as the zeroth correction and extrapolates from it (defect 10,
///   if its fix covers the tracker: ok must mean the tolerance met at the point returned).
/// - `wrong_branch_ok` (1 at ×1, case 314; 15 at ×10: also 500, 541, 651, 658, 1065, 1339,
///   1392, 1570, 1775, 2477, 2758, 3098, 3102, 3391): every one right after a refused sample,
///   the tracker accepts a sample that no nonsingular path connects to the last accepted one,
///   up to 131 mm from the pose (defect 2; case 658 with a pose path that never meets a
///   singularity, the others after the pose crossed a singular surface and came back).
/// - `tracker_refused_reachable_sample` (at ×10: case 271): with `Linear::Dense` its fallback
///   PH reports a fold that the generated factorisation passes (the dense corrector, cured).
///   Later: refusals `tolerance_not_met` at 1.0–6.7e-10 mm with `Options::TIGHT` at 1e-10
///   (cured by 1e-9), and at ×10 just above 1e-9 where Newton stopped at the first scattered
///   correction (cured by three); a refusal where the truth's own rounding floor is within 4×
///   of the tolerance is honest and counted apart.
#[test]
fn tracker_on_random_trajectories() {
    trajectories(&Run::new("tracker_on_random_trajectories", 0x5EED_0002));
}

fn trajectories(run: &Run) {
    let mut tally = Tally::new(run);
    for case in run.cases(400) {
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
///
/// Found at 71447e1, cured by the issue 9 fixes:
/// - `non_finite_ok` (156 at ×1): NR, and NH, return `Converged` with v all NaN for legs whose
///   squares overflow (defect 1).
/// - `ok_above_tolerance` (220): ok with tolerances no solve can meet (1e-300, 5e-324) or legs of
///   1.7e8 mm, 0.1 mm from converged (defects 10, 11).
/// - `ok_wrong_det_sign` (3): NR and NH, with tolerances of 1e3 mm and more, ok after one step
///   with det B of the other sign (defect 11).
/// - `refused_a_target_at_the_start` (882): PH and detours end `StepTooSmall` for legs a few ulps
///   from the start, or the start's own legs recomputed from its pose (defect 3a).
/// - At ×10 also `tracker_refused_the_start_legs_again` (case 12411): having accepted legs a
///   few ulps from the start, the tracker refuses the start's own legs (its fallback PH ends
///   `StepTooSmall` at λ = 0.42 of a step of a few ulps: defect 3a).
#[test]
fn bad_values_for_every_solver() {
    bad_values(&Run::new("bad_values_for_every_solver", 0x5EED_0003));
}

fn bad_values(run: &Run) {
    let mut tally = Tally::new(run);
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
///
/// Found at 71447e1, cured by the scale-free singular-start test (defect 4)
/// and the meaning of ok (defect 10):
/// - `exact_start_called_inconsistent` (367 at ×1): an exact pose within 1e-12 of the surface
///   refused as `InconsistentStart`.
/// - `start_sign_unstable` (335): a start accepted, then rebuilt from its own refined pivots
///   (or those moved by 1e-12 of their size) accepted with det B of the other sign.
/// - `ok_above_tolerance` (1775): solves from such starts, even to the start's own legs, ok with
///   the next correction above the tolerance.
#[test]
fn starts_near_singular_surfaces() {
    starts(&Run::new("starts_near_singular_surfaces", 0x5EED_0004));
}

fn starts(run: &Run) {
    let mut tally = Tally::new(run);
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

// ---- Cases that found a defect, replayed alone as its regression test (each failed before
// its fix, with the seed and the test named here).

/// `Options::TIGHT` at 1e-10 mm sat at the rounding floor of the general model at regular
/// points: the tracker refused samples (`tracker_refused_reachable_sample`,
/// `tracker_refused_the_start_legs_again`) with `tolerance_not_met` at 1.0–6.7e-10 mm. Cured
/// by `Options::TIGHT.tolerance` = 1e-9.
#[test]
fn known_cases_tight_tolerance_at_the_rounding_floor() {
    trajectories(&Run::listed(
        "tracker_on_random_trajectories",
        0x5EED_0002,
        &[39, 66, 83, 89, 121, 168],
    ));
    bad_values(&Run::listed(
        "bad_values_for_every_solver",
        0x5EED_0003,
        &[1178, 1469],
    ));
}

/// NR and NH returned other assembly modes of the start's det B sign as ok (8 to 360 mm from
/// every truth); NH also ok at the rounding floor with the correction measured again just
/// above the tolerance. Cured by `Status::Unverified` (NR and NH cannot establish the branch)
/// and an oracle that allows a re-measurement its own rounding noise.
#[test]
fn known_cases_newton_methods_claim_no_branch() {
    forward_kinematics(
        &Run::listed(
            "forward_kinematics_by_newton",
            0x5EED_0009,
            &[
                23, 261, 304, 320, 476, 672, 821, 961, 980, 1159, 1282, 1330, 1480, 1814, 1846,
                2147, 2217, 2306, 2872,
            ],
        ),
        fk::Solvers::Newton,
    );
}

/// With `Linear::Dense`, PH's corrector was full Newton on the dense bordered matrix: from a
/// long first step (a quarter of the path) it contracted fast onto another sheet of the
/// solution curve, det B of the other sign there, and PH reported a fold the segment does not
/// have (|det B|/|det0| ≥ 0.04 all along; case 638 ≥ 1). Cured by the chord iteration on the
/// bordered matrix factored at the last accepted point, as with the generated factorisation.
#[test]
fn known_cases_dense_corrector_false_folds() {
    forward_kinematics(
        &Run::listed(
            "forward_kinematics_by_continuation",
            0x5EED_0009,
            &[220, 449, 638],
        ),
        fk::Solvers::Continuation,
    );
}

/// With `Linear::Dense`, a last step of 10 (from μ = 16.5 to the end at 23.4) where the straight
/// segment comes within |det B|/|det0| = 0.014 of a fold and turns away: the corrector landed
/// on the sheet beyond it, det B of the other sign, and PH reported `Fold` at λ = 1 (the
/// generated factorisation, by a step control that differed by a shorter step, converged).
/// Found with `LINKAGE_STRESS_SEED=90210` at ×10 (2026-11-30), the only failure there: a
/// refusal, not a wrong answer. Not cured: taking such a step again at half length cured it,
/// but let PH cross a bifurcation of the delta's level and tilted modes and call the tilted
/// one ok (`delta_tracking::known_case_a_bifurcation_onto_a_tilted_mode`), so it was withdrawn.
#[test]
#[ignore = "a known false fold with Linear::Dense (a refusal); the half-step cure crossed a bifurcation"]
fn known_cases_dense_corrector_lands_beyond_a_near_fold() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_continuation", 90210, &[16940]),
        fk::Solvers::Continuation,
    );
}

/// An S-shaped straight segment (two folds within 3e-6 of λ near 0.97957, det B of one sign
/// on either side): PH stepped over both folds in one step and called the far sheet ok, and
/// detours built on that leg too. Cured by keeping steps within twice the extrapolated
/// distance to det B = 0 and rejecting a step over which det B's parabola dips across zero.
/// Found at ×10 (case 17803: the same, two folds near λ = 0.0157, PH at the pose's pivots).
#[test]
fn known_cases_two_folds_in_one_step() {
    forward_kinematics(
        &Run::listed(
            "forward_kinematics_by_continuation",
            0x5EED_0009,
            &[5441, 17803],
        ),
        fk::Solvers::Continuation,
    );
}

/// At ×5 with `LINKAGE_STRESS_SEED=424242`: the straight segment of a random 6-6 platform
/// meets a singularity at λ ≈ 0.36288565 (the oracle, natural continuation in steps down to
/// 1e-5 of the segment, stops there with det B of the other sign just ahead, whatever its
/// step), where PH to nearby targets on the same line ends `StepTooSmall`; PH to the far
/// target stepped past it, accepted a point at λ = 0.36288629 with det B of the start's sign
/// and reported `Fold` at 0.36288678. `arc_length_detour` left from that point and returned
/// `Converged`: an answer the oracle could not connect to the start without meeting the
/// singularity. The detour now leaves from a point solved afresh a thousandth of the way back.
#[test]
fn known_cases_detour_from_past_a_singularity() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_continuation", 424242, &[4255]),
        fk::Solvers::Continuation,
    );
}

/// At ×3 with `LINKAGE_STRESS_SEED=777` (`Linear::Dense`): on a path whose first-order travel
/// is 3.2e6 (the start's B nearly singular across the legs' step), so that its points are
/// computed to 3.15, a step ended 4.7e-4 short of λ = 1; the last step's corrector measured the
/// accepted point's own error (3.6) against that step, refused it, and PH ended `StepTooSmall`
/// at λ = 1 − 1.5e-10 on a segment with |det B|/|det0| ≥ 1 all along
/// (`ph_refused_reachable_target`). Cured by taking a last step shorter than that accuracy as
/// the final Newton run, as a path that short already was.
#[test]
fn known_cases_last_step_within_the_paths_accuracy() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_continuation", 777, &[4311]),
        fk::Solvers::Continuation,
    );
}

/// At ×2 with `LINKAGE_STRESS_SEED=20261201`: a random 6-6 platform whose start is nearly
/// singular across the legs' step (first-order travel 3.5e5 against |v| of a few hundred, so the
/// path's points were computed to 0.35). PH's first step of 0.059 was accepted after a first
/// correction of 0.068; from there every step, however short, landed 0.09 off the accepted
/// point at a tangent turned 56°, the turn test refused each, and PH ended `StepTooSmall` at
/// λ = 2.5e-7 on a segment with |det B|/|det0| ≥ 1 all along (`ph_refused_reachable_target`).
/// Cured by a corrector tolerance of at most a hundredth of the step (and at least 1e-6 of
/// |v|).
#[test]
fn known_cases_corrector_tolerance_within_the_step() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_continuation", 20261201, &[3446]),
        fk::Solvers::Continuation,
    );
}

/// At ×8 with `LINKAGE_STRESS_SEED=1618033`: a random 6-6 platform whose start is nearly
/// singular across the legs' step (first-order travel 5.1e4, so the corrector's tolerance was
/// 0.051). A step of 5.9 ending 0.11 short of λ = 1 was accepted after corrections of 0.065 and
/// 0.039: the last within the tolerance, but at a ratio of 0.6, so the point was left 0.087 off
/// the curve. The last step (0.11) and every shorter one after it measured that error against
/// its own length and were refused, and PH ended `StepTooSmall` at λ = 1 − 2.2e-6 on a segment
/// with |det B|/|det0| ≥ 0.085 all along (`ph_refused_reachable_target`). Cured by holding a
/// correction within the tolerance to the contraction test too.
#[test]
fn known_cases_last_correction_contracts_too() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_continuation", 1618033, &[23613]),
        fk::Solvers::Continuation,
    );
}

/// At ×6 with `LINKAGE_STRESS_SEED=99999989`: NR (`Linear::Generated`, tolerance 5e-4) to a
/// target next to a singularity answered `Unverified` with an error estimate of 1.8e-4 where
/// the Newton correction, in `f64` and in double-double alike, is 1.8e-3 (det B at 0.3 % of the
/// start's; Newton from there halves its corrections: a root next to a fold). A chord
/// correction had vouched for the point with q = 0.0052, estimated from the corrections 2.97
/// and 0.046 (B well conditioned at the start), which predicted B to change by 5e-4 (`Chords`).
/// Cured by letting the vouching chord correction raise q as it shows it.
#[test]
fn known_cases_chord_correction_vouches_with_its_own_q() {
    forward_kinematics(
        &Run::listed("forward_kinematics_by_newton", 99999989, &[15039]),
        fk::Solvers::Newton,
    );
}

/// At ×4 with `LINKAGE_STRESS_SEED=31415926` (`Linear::Dense`, tolerance 5e-4): the tracker's
/// fast path refused five samples of a random 6-6 platform's trajectory, and continuation from
/// the last accepted sample ended `StepTooSmall` at λ = 0, where PH from a start rebuilt there
/// reached the truth (2.4e-5 off) on a segment with |det B|/|det0| ≥ 0.19. A 1 kHz sample's step
/// (legs 1e-4 mm apart) is shorter than the tolerance the accepted point is on the branch to:
/// every first correction carried the point's own error and was refused. Cured by refining the
/// accepted point, as a start is, before continuing from it.
#[test]
fn known_cases_continuation_from_a_refined_sample() {
    trajectories(&Run::listed(
        "tracker_on_random_trajectories",
        31415926,
        &[987],
    ));
}

/// NH solved its last step at x0 + (x* − x0), an ulp from the target, and near a singularity
/// the correction measured at the target was then 2–4× the tolerance (×10). Cured by solving
/// the last step at the target itself.
#[test]
fn known_cases_newton_homotopy_ends_at_the_target_itself() {
    forward_kinematics(
        &Run::listed(
            "forward_kinematics_by_newton",
            0x5EED_0009,
            &[6692, 10678, 15403, 15644, 19047, 23206, 28876],
        ),
        fk::Solvers::Newton,
    );
}

/// At ×10: the tracker refused samples `tolerance_not_met` at 1.08e-9 and 1.18e-9 mm with the
/// truth's rounding floor well below the tolerance: Newton stopped at the first correction that
/// did not shrink, one scattered value at the floor. Cured by allowing three such before a
/// final run ends `Stalled`. And (suite, not runtime) targets a few ulps from a start next to a
/// singular surface, which every solver refuses: refusals there are counted, not failed.
/// With `LINKAGE_STRESS_SEED=20261129` at ×3: the tracker accepted a sample whose `f64`
/// correction, 9.37e-10 mm, was within the tolerance 1e-9 but whose accurate one (F in
/// double-double) was 1.03e-9: the floor, predicted at 5.6e-11 mm, was checked against the
/// tolerance rather than against the 6.3e-11 the correction left under it. Cured in
/// `floor::vouch`.
#[test]
fn known_cases_rounding_floor_near_the_tolerance() {
    trajectories(&Run::listed(
        "tracker_on_random_trajectories",
        0x5EED_0002,
        &[2109, 3602],
    ));
    trajectories(&Run::listed(
        "tracker_on_random_trajectories",
        20261129,
        &[211],
    ));
    bad_values(&Run::listed(
        "bad_values_for_every_solver",
        0x5EED_0003,
        &[4709, 23615, 29734],
    ));
}

/// Velocity kinematics on random machines at random poses (`velocity::twist`,
/// `velocity::input_rates`), against central differences of inverse kinematics along a random
/// motion: no wrong twist or input rates, nothing left over of a twist the legs made, no rates
/// for legs that are not the pose's.
#[test]
fn velocity_on_random_machines() {
    let run = Run::new("velocity_on_random_machines", 0x5EED_0007);
    let mut tally = Tally::new(&run);
    for case in run.cases(800) {
        let mut rng = run.rng(case);
        let g = random_geometry(&mut rng);
        if g.coplanar() {
            velocity::case::<Stewart>(&mut tally, case, &mut rng, g);
        } else {
            velocity::case::<StewartGeneral>(&mut tally, case, &mut rng, g);
        }
    }
    tally.finish();
}
