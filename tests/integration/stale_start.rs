//! A `Start` made for one geometry, given to a solver whose mechanism has another (a
//! calibration applied with `set_geometry` after the start was made): every solver that claims
//! the start's branch refuses it, and a start made for the new geometry is accepted.

use linkage::{
    arc_length, arc_length_certified, arc_length_detour, newton_homotopy, newton_raphson, Options,
    SolveError, Status, TrackError, Tracker,
};
use linkage_examples::stewart::{home_start, Stewart};
use linkage_tests::stewart_pose_samples;

fn inconsistent<T: std::fmt::Debug>(r: Result<T, SolveError>) -> bool {
    matches!(r, Err(SolveError::InconsistentStart { residual_norm }) if residual_norm > 0.0)
}

#[test]
fn a_start_made_before_set_geometry_is_refused_by_every_branch_claiming_solver() {
    let old = Stewart::new();
    let stale = home_start(&old).unwrap();
    let target = stewart_pose_samples(3, 1, 0.2, 20.0, 20)[0].x;
    for (name, offset) in [
        ("base.D1.x", 3.0),
        ("platform.G2.y", -0.5),
        ("base.D4.y", 0.01),
    ] {
        let mut s = old.clone();
        let i = Stewart::GEOMETRY_NAMES
            .iter()
            .position(|n| *n == name)
            .unwrap();
        s.set_geometry(name, Stewart::DEFAULT_GEOMETRY[i] + offset)
            .unwrap();
        let o = Options::TIGHT;
        assert!(inconsistent(arc_length(&s, &stale, &target, &o)), "{name}");
        // The target the start was made for: the path is empty, the answer Newton's alone.
        assert!(
            inconsistent(arc_length(&s, &stale, stale.x(), &o)),
            "{name}"
        );
        assert!(
            inconsistent(arc_length_detour(&s, &stale, &target, &o)),
            "{name}"
        );
        assert!(
            inconsistent(arc_length_certified(&s, &stale, &target, &o)),
            "{name}"
        );
        assert!(
            inconsistent(newton_homotopy(&s, &stale, &target, &o)),
            "{name}"
        );
        for certified in [false, true] {
            let mut t = Tracker::new(s.clone(), stale, o);
            if certified {
                t = t.certified();
            }
            assert!(
                matches!(
                    t.update(&target),
                    Err(TrackError::Input(SolveError::InconsistentStart { .. }))
                ),
                "{name}"
            );
        }
        // Newton–Raphson starts from a guess and never claims the branch: it still answers,
        // Unverified (the contract on `Start`).
        let nr = newton_raphson(&s, &stale, &target, &o).unwrap();
        assert!(matches!(
            nr.status,
            Status::Unverified | Status::ToleranceNotMet { .. }
        ));
        // A start made for the new geometry is accepted by all of them.
        let fresh = s.home_start().unwrap();
        assert_eq!(
            arc_length(&s, &fresh, &target, &o).unwrap().status,
            Status::Converged
        );
        assert!(newton_homotopy(&s, &fresh, &target, &o).is_ok());
        assert!(Tracker::new(s.clone(), fresh, o).update(&target).is_ok());
        // The stale start carried to the new geometry at its own inputs (`Start::follow`) is
        // where continuation from the fresh start to those inputs arrives: the same
        // configuration, reached two ways.
        let carried = linkage::Start::follow(&s, *stale.v(), *stale.x()).unwrap();
        assert_eq!(carried.x(), stale.x());
        let there = arc_length(&s, &fresh, stale.x(), &o).unwrap();
        assert_eq!(there.status, Status::Converged, "{name}");
        assert!(
            linkage_tests::max_diff(carried.v(), &there.v) < 1e-8,
            "{name}: {:?} vs {:?}",
            carried.v(),
            there.v
        );
        assert!(carried.det() * fresh.det() > 0.0);
    }
}

#[test]
fn the_unchanged_mechanism_accepts_its_start() {
    let s = Stewart::new();
    let st = home_start(&s).unwrap();
    let o = Options::TIGHT;
    assert!(arc_length(&s, &st, st.x(), &o).unwrap().is_ok());
    assert!(Tracker::new(s.clone(), st, o).update(st.x()).is_ok());
}
