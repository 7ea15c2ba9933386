//! Hostile values on the public entry points the solver hunts had not reached: the inverse's
//! reference, geometry set at run time (parameters, formulas of them, lengths), `home_start`
//! after a calibration, the velocity kinematics, `link_pose`, `pose_from_unknowns`, the
//! certificates, and every solver and the tracker under extreme `Options` — on a 3-RPS (legs in
//! closed form), a delta (cranks in closed form, coordinates declared from parameters), a
//! pan-tilt head and a SCARA (the numerical inverse) and a five-bar whose base is the square
//! root of a parameter.
//!
//! The oracle: an `Ok` keeps its promise (an inverse's inputs place the pivots given, each
//! angle within half a turn of its reference; a status that meets the tolerance is finite,
//! within it, and F(v, x) = 0 there), an error is typed and names what was wrong, and nothing
//! panics (`catch_unwind` turns a panic into a failure that names its input).

use linkage::velocity::{self, Twist, VelocityError, Wrench};
use linkage::{
    arc_length, arc_length_certified, arc_length_detour, certify, newton_homotopy, newton_raphson,
    pose_from_unknowns, unknowns_from_pose, CertifyError, GeometryError, InverseError, Mechanism,
    NewtonRaphson, Options, Pose, Solution, SolveError, Start, Status, TrackError, Tracker,
};
// The README's delta, declared once for all the tests.
use crate::mechanisms::delta::Delta;
use linkage_examples::rps::Rps3;
use linkage_serial_arms::{PanTilt, Scara};
use linkage_tests::residual_norm;
use std::panic::{catch_unwind, AssertUnwindSafe};

linkage::mechanism! {
    /// A five-bar whose base half-width is the square root of the parameter `w2`.
    pub struct RootFiveBar;
    params { crank = 100.0, w2 = 1600.0 }
    base { A1 = [-sqrt(w2), 0.0, 0.0], A1z = [-sqrt(w2), 0.0, 1.0], A2 = [sqrt(w2), 0.0, 0.0], A2z = [sqrt(w2), 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, crank * sin(pi / 3.0) + 120.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C1 = [-sqrt(w2) - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-sqrt(w2) - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [sqrt(w2) + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [sqrt(w2) + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
}

/// `f()`, or the panic's message.
fn guard<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|e| {
        e.downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    })
}

/// Values no coordinate, input or rate should be, or that floating point barely holds.
const HOSTILE: [f64; 12] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::MAX,
    1e300,
    -1e300,
    1e155,
    1e17,
    -0.0,
    5e-324,
    1e-310,
    f64::MIN_POSITIVE,
];

/// Whether F(v, x) = 0 to 1e-9 of the squared scale (F is quadratic in lengths): a start on
/// a machine of 1e17 mm holds to its own scale.
fn holds<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> bool {
    let scale = 1.0 + v.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    residual_norm(sys, v, x) <= 1e-9 * scale * scale
}

/// The inverse at a solved configuration `(v, x)` given each hostile reference: where it
/// answers, the inputs place the pivots (F(v, ·) = 0 to 1e-6 of the scale squared: F is
/// quadratic) and each input F holds only through its sine and cosine (`turning`) is within half
/// a turn of its reference; a finite reference within 2¹⁶ rad is answered; a non-finite one is
/// `NonFinite`, one farther out `FarReference` naming a turning input.
fn inverse_keeps_its_promise<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    turning: &[usize],
) {
    let (v, x) = (start.v(), start.x());
    let scale = 1.0 + v.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    let references = HOSTILE.iter().copied().chain([
        65536.0,
        -65536.0,
        65536.5,
        1000.0 * std::f64::consts::TAU + 0.25,
    ]);
    for r in references {
        let reference = [r; M];
        let got = guard(|| sys.inverse(v, &reference))
            .unwrap_or_else(|p| panic!("{}: inverse at reference {r:e} panicked: {p}", S::NAME));
        let far = !turning.is_empty() && r.abs() > 65536.0;
        match got {
            Ok(back) => {
                assert!(
                    r.is_finite() && !far,
                    "{}: reference {r:e} answered {back:?}",
                    S::NAME
                );
                let res = residual_norm(sys, v, &back);
                assert!(
                    res <= 1e-6 * scale * scale,
                    "{}: reference {r:e}: inputs {back:?} leave F = {res:e} (solved at {x:?})",
                    S::NAME
                );
                for &i in turning {
                    assert!(
                        (back[i] - r).abs() <= std::f64::consts::PI + 1e-9,
                        "{}: reference {r:e}: input {i} = {} is not within half a turn",
                        S::NAME,
                        back[i]
                    );
                }
            }
            Err(InverseError::NonFinite) => {
                assert!(!r.is_finite(), "{}: reference {r:e}: NonFinite", S::NAME)
            }
            Err(InverseError::FarReference { input }) => assert!(
                far && turning.contains(&input),
                "{}: reference {r:e}: FarReference {{ input: {input} }}",
                S::NAME
            ),
            Err(e) => panic!("{}: reference {r:e}: {e:?}", S::NAME),
        }
    }
}

/// A reference 1e17 or 1e300 rad out used to give inputs that placed nothing where v is: the
/// numerical inverse found the pan-tilt head's angles (0, 0) and returned (1e300, 1e300), "within
/// half a turn" of the reference once rounded, leaving F = 70 mm²; the delta's closed form said
/// `Inconsistent` (the pivots were fine). Now a reference past 2¹⁶ rad is `FarReference`, and
/// every answer places the pivots.
#[test]
fn the_inverse_answers_near_its_reference_or_says_the_reference_is_too_far_out() {
    let rps = Rps3::new();
    inverse_keeps_its_promise(&rps, &rps.home_start().unwrap(), &[]);
    let delta = Delta::new();
    let start = delta.home_start().unwrap();
    inverse_keeps_its_promise(&delta, &start, &[0, 1, 2]);
    let moved = arc_length(&delta, &start, &[0.3, -0.2, 0.1], &Options::TIGHT).unwrap();
    assert!(moved.is_ok());
    let moved = Start::new(&delta, moved.v, [0.3, -0.2, 0.1]).unwrap();
    inverse_keeps_its_promise(&delta, &moved, &[0, 1, 2]);
    let pan_tilt = PanTilt::new();
    inverse_keeps_its_promise(&pan_tilt, &pan_tilt.home_start().unwrap(), &[0, 1]);
    let scara = Scara::new();
    inverse_keeps_its_promise(&scara, &scara.home_start().unwrap(), &[0, 1, 3]);
    let five_bar = RootFiveBar::new();
    inverse_keeps_its_promise(&five_bar, &five_bar.home_start().unwrap(), &[0, 1]);
}

/// A value whose square overflows is `Overflow` wherever it is: a rod of 1e300 used to be
/// accepted (its derived constants do not square it), and every start from it then failed as
/// `NonFinite`; a parameter at 1e300 was `DegenerateAxis`. The mechanism is unchanged.
#[test]
fn a_geometry_value_whose_square_overflows_is_overflow() {
    let delta = Delta::new();
    for name in ["rod", "c", "h", "hw"] {
        for value in [1e300, -1e300, 1e155, f64::MAX] {
            let mut d = delta.clone();
            // (A rod of −1e300 is both; its square's overflow is what is said first.)
            let got = guard(|| d.set_geometry(name, value)).unwrap();
            if name == "c" && value == f64::MAX {
                // `rb * c` itself overflows: the coordinate is what is not finite.
                assert_eq!(
                    got,
                    Err(GeometryError::FormulaNotFinite {
                        name: "base.A2.x",
                        parameter: "rb"
                    })
                );
            } else {
                assert_eq!(got, Err(GeometryError::Overflow), "{name} = {value:e}");
            }
            assert_eq!(d, delta, "{name} = {value:e} changed the mechanism");
        }
    }
    // The largest scale whose squares fit is still a geometry.
    let mut d = delta.clone();
    d.set_geometry("rod", 1e150).unwrap();
    assert!(d.home_start().is_err());
}

/// A coordinate declared as a formula of a parameter that the parameter's value makes NaN
/// (`sqrt` of a negative) is refused naming the coordinate and the parameter to set — not as
/// `NonFinite { name: "base.A1.x" }`, a value that cannot be set by name; a NaN parameter is
/// named itself, not the first formula it poisons.
#[test]
fn a_formula_made_non_finite_by_its_parameter_names_the_parameter() {
    let five_bar = RootFiveBar::new();
    for w2 in [-1.0, -1e-300, f64::NEG_INFINITY / 2.0] {
        let mut m = five_bar.clone();
        let got = m.set_geometry("w2", w2);
        if w2.is_finite() {
            assert_eq!(
                got,
                Err(GeometryError::FormulaNotFinite {
                    name: "base.A1.x",
                    parameter: "w2"
                }),
                "w2 = {w2:e}"
            );
        } else {
            assert_eq!(got, Err(GeometryError::NonFinite { name: "w2" }));
        }
        assert_eq!(m, five_bar);
    }
    let slot = RootFiveBar::GEOMETRY_NAMES
        .iter()
        .position(|n| *n == "w2")
        .unwrap();
    let mut g = RootFiveBar::DEFAULT_GEOMETRY;
    g[slot] = -4.0;
    assert_eq!(
        RootFiveBar::from_geometry(g),
        Err(GeometryError::FormulaNotFinite {
            name: "base.A1.x",
            parameter: "w2"
        })
    );
    // 0 is a base of zero width: both cranks on one axis, still a mechanism with a home.
    let mut m = five_bar.clone();
    m.set_geometry("w2", 0.0).unwrap();
    assert!(m.home_start().is_ok());
    for name in ["rb", "hw", "c"] {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut d = Delta::new();
            assert_eq!(
                d.set_geometry(name, bad),
                Err(GeometryError::NonFinite { name }),
                "{name} = {bad}"
            );
        }
    }
    let text = GeometryError::FormulaNotFinite {
        name: "base.A1.x",
        parameter: "w2",
    }
    .to_string();
    assert!(text.contains("base.A1.x") && text.contains("w2"), "{text}");
}

/// `home_start` is the start at the declared home pose for the current geometry. The delta's
/// cranks have closed forms, but it used the declared configuration (cranks at 0) whatever
/// the geometry: its base radius set 1 mm smaller (`rb` = 99), and `home_start` was
/// `InconsistentStart { residual_norm: 781 }` while `inverse` placed the platform there.
#[test]
fn home_start_follows_a_calibrated_delta_to_its_home_pose() {
    let calibrations = [99.0, 101.0, 90.0, 50.0, 0.0, -0.0, 5e-324]
        .map(|v| ("rb", v))
        .into_iter()
        .chain([
            ("rp", 45.0),
            ("rp", 0.0),
            ("hw", 20.0),
            ("ra", 95.0),
            ("rod", 250.0),
        ]);
    for (name, value) in calibrations {
        let mut d = Delta::new();
        d.set_geometry(name, value).unwrap();
        let start = d
            .home_start()
            .unwrap_or_else(|e| panic!("{name} = {value:e}: {e:?}"));
        let pose = pose_from_unknowns(&d, start.v()).unwrap();
        assert!(
            (pose.translation[2] + 200.0).abs() < 1e-9
                && pose.translation[0].abs() < 1e-9
                && pose.euler().iter().all(|a| a.abs() < 1e-12),
            "{name} = {value:e}: {pose:?}"
        );
        let x = d.inverse(start.v(), &Delta::HOME_INPUTS).unwrap();
        assert!(
            linkage_tests::max_diff(&x, start.x()) < 1e-12,
            "{name} = {value:e}"
        );
        let target = start.x().map(|q| q + 0.05);
        let sol = arc_length(&d, &start, &target, &Options::TIGHT).unwrap();
        assert!(
            sol.is_ok() && residual_norm(&d, &sol.v, &target) < 1e-6,
            "{name} = {value:e}: {sol:?}"
        );
    }
}

/// Rates so large that the pivots' rates overflow are `NonFinite`, not `Singular` (B is
/// regular there); finite huge rates that fit are answered, and scale.
#[test]
fn velocities_of_overflowing_rates_are_non_finite_not_singular() {
    let rps = Rps3::new();
    let start = rps.home_start().unwrap();
    let (v, x) = (start.v(), start.x());
    for big in [f64::MAX, -f64::MAX, 1e308] {
        let rates = [big, 0.0, -big];
        assert_eq!(
            velocity::pivot_rates(&rps, v, x, &rates),
            Err(VelocityError::NonFinite),
            "{big:e}"
        );
        assert_eq!(
            velocity::twist(&rps, v, x, &rates),
            Err(VelocityError::NonFinite),
            "{big:e}"
        );
    }
    let unit = velocity::pivot_rates(&rps, v, x, &[1.0, 0.0, -1.0]).unwrap();
    let huge = velocity::pivot_rates(&rps, v, x, &[1e300, 0.0, -1e300]).unwrap();
    for (u, h) in unit.iter().zip(&huge) {
        assert!((h - u * 1e300).abs() <= 1e-9 * (u * 1e300).abs() + 1e285);
    }
}

/// A point too far out for interval bounds is `NonFinite` for every mechanism (a delta at
/// 1e300 was refused as `Singular`).
#[test]
fn a_certificate_far_out_is_refused_as_non_finite() {
    let delta = Delta::new();
    let start = delta.home_start().unwrap();
    for big in [1e300, -1e300, 1e150] {
        let v = start.v().map(|q| q + big);
        assert_eq!(
            certify(&delta, &v, start.x()).map(|c| c.radius),
            Err(CertifyError::NonFinite),
            "{big:e}"
        );
    }
}

/// Options at and past their edges.
fn options() -> Vec<(String, Options)> {
    let mut out = vec![];
    for t in [
        0.0,
        -0.0,
        f64::NAN,
        f64::INFINITY,
        1e300,
        5e-324,
        1e-300,
        -1e-9,
        1e-9,
    ] {
        out.push((
            format!("tolerance {t:e}"),
            Options {
                tolerance: t,
                ..Options::TIGHT
            },
        ));
    }
    for k in [0u32, 1, u32::MAX] {
        for (what, o) in [
            (
                "max_iterations",
                Options {
                    max_iterations: k,
                    ..Options::TIGHT
                },
            ),
            (
                "max_steps",
                Options {
                    max_steps: k,
                    ..Options::TIGHT
                },
            ),
            (
                "homotopy_steps",
                Options {
                    homotopy_steps: k,
                    ..Options::TIGHT
                },
            ),
        ] {
            out.push((format!("{what} {k}"), o));
        }
    }
    out
}

/// A solve's result kept its promise: a status that meets the tolerance is finite, within it,
/// and F(v, x) = 0 there; an options error only for options `check_for` refuses.
fn judge<S: Mechanism<N, M>, const N: usize, const M: usize>(
    at: &str,
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    o: &Options,
    got: Result<Result<Solution<N>, SolveError>, String>,
) {
    let got = got.unwrap_or_else(|p| panic!("{at}: panicked: {p}"));
    let valid = o.check_for(start).is_ok();
    match got {
        Ok(s) if s.status.meets_tolerance() => {
            let res = residual_norm(sys, &s.v, x);
            assert!(
                valid
                    && s.v.iter().all(|q| q.is_finite())
                    && s.error_estimate <= o.tolerance
                    && res <= 1e-6,
                "{at}: {:?} with error {:e}, F = {res:e}",
                s.status,
                s.error_estimate
            );
        }
        Ok(_) => assert!(valid, "{at}: options {o:?} let through"),
        Err(SolveError::InvalidOptions { .. }) => assert!(!valid, "{at}: options refused"),
        Err(_) => {}
    }
}

/// Every solver, the prepared NR, the detour and the tracker (plain and certified), under
/// every extreme option, at a reachable target and at NaN, 1e300 and −0.0 inputs; the tracker
/// afterwards takes the start's own inputs whatever it refused.
fn solvers_keep_their_promises<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    target: [f64; M],
) {
    for (label, o) in options() {
        for (what, x) in [
            ("target", target),
            ("NaN", [f64::NAN; M]),
            ("1e300", [1e300; M]),
            ("-0", [-0.0; M]),
        ] {
            let at = format!("{} {label} at {what}", S::NAME);
            judge(
                &format!("{at} PH"),
                sys,
                start,
                &x,
                &o,
                guard(|| arc_length(sys, start, &x, &o)),
            );
            judge(
                &format!("{at} NH"),
                sys,
                start,
                &x,
                &o,
                guard(|| newton_homotopy(sys, start, &x, &o)),
            );
            judge(
                &format!("{at} NR"),
                sys,
                start,
                &x,
                &o,
                guard(|| newton_raphson(sys, start, &x, &o)),
            );
            let nr = NewtonRaphson::new(sys.clone(), *start);
            judge(
                &format!("{at} prepared NR"),
                sys,
                start,
                &x,
                &o,
                guard(|| nr.solve(&x, &o)),
            );
            judge(
                &format!("{at} detour"),
                sys,
                start,
                &x,
                &o,
                guard(|| arc_length_detour(sys, start, &x, &o).map(|d| d.solution)),
            );
            let certified = guard(|| arc_length_certified(sys, start, &x, &o));
            if let Ok(Ok((sol, proof))) = &certified {
                assert!(
                    proof.is_none() || sol.is_ok(),
                    "{at}: a proof of a solve that is not ok: {proof:?}"
                );
            }
            judge(
                &format!("{at} certified PH"),
                sys,
                start,
                &x,
                &o,
                certified.map(|r| r.map(|(sol, _)| sol)),
            );
            for certified in [false, true] {
                let r = guard(|| {
                    let mut t = Tracker::new(sys.clone(), *start, o);
                    if certified {
                        t = t.certified();
                    }
                    let first = t.update(&x).map(|s| s.v);
                    let kept = (*t.state().0, *t.state().1);
                    let back = t.update(start.x()).map(|s| s.v);
                    (first, kept, back)
                });
                let (first, kept, back) =
                    r.unwrap_or_else(|p| panic!("{at} tracker panicked: {p}"));
                let valid = o.check_for(start).is_ok();
                match first {
                    Ok(v) => {
                        assert!(valid, "{at}: the tracker took options {o:?}");
                        assert!(
                            v.iter().all(|q| q.is_finite()) && residual_norm(sys, &v, &x) <= 1e-6,
                            "{at}: tracker sample {v:?}"
                        );
                    }
                    Err(_) => {
                        assert_eq!(kept, (*start.v(), *start.x()), "{at}: a refusal moved it")
                    }
                }
                match back {
                    Ok(v) => assert!(
                        residual_norm(sys, &v, start.x()) <= 1e-6,
                        "{at}: back {v:?}"
                    ),
                    // Below the rounding floor even the start's own inputs end short of the
                    // tolerance.
                    Err(e) => assert!(
                        !valid
                            || o.tolerance < 1e-12
                                && matches!(e, TrackError::Lost(Status::ToleranceNotMet { .. })),
                        "{at}: the start's own inputs refused: {e:?}"
                    ),
                }
            }
        }
    }
}

#[test]
fn solvers_and_tracker_under_extreme_options_keep_every_promise() {
    let rps = Rps3::new();
    let start = rps.home_start().unwrap();
    solvers_keep_their_promises(&rps, &start, start.x().map(|l| l + 5.0));
    let delta = Delta::new();
    solvers_keep_their_promises(&delta, &delta.home_start().unwrap(), [0.1, -0.1, 0.05]);
    let pan_tilt = PanTilt::new();
    solvers_keep_their_promises(&pan_tilt, &pan_tilt.home_start().unwrap(), [0.3, 0.2]);
}

/// The pose and velocity helpers at hostile points: `pose_from_unknowns` and `link_pose` give
/// a proper rotation or `None`, the velocities an answer that is finite or a typed error.
#[test]
fn poses_and_velocities_at_hostile_points() {
    let delta = Delta::new();
    let start = delta.home_start().unwrap();
    let (v, x) = (*start.v(), *start.x());
    let proper = |p: &Pose| {
        let r = p.rotation;
        (p.handedness() - 1.0).abs() < 1e-9
            && r.iter()
                .flatten()
                .chain(&p.translation)
                .all(|c| c.is_finite())
    };
    for bad in HOSTILE {
        for w in [[bad; 18], v.map(|q| q * bad), v.map(|q| q + bad)] {
            let at = format!("{bad:e} {:?}", &w[..2]);
            if let Some(p) = guard(|| pose_from_unknowns(&delta, &w)).unwrap() {
                assert!(proper(&p), "pose_from_unknowns {at}: {p:?}");
            }
            for link in [0, 1, 2, 3, 4, usize::MAX] {
                for xs in [x, [bad; 3]] {
                    if let Some(p) = guard(|| delta.link_pose(link, &w, &xs)).unwrap() {
                        assert!(proper(&p), "link_pose {link} {at}: {p:?}");
                    }
                }
            }
            // The pose helpers round trip where they answer.
            let pose = Pose::from_euler(bad, 0.1, -0.2, [bad, 0.0, 1.0]);
            let back = pose_from_unknowns(&delta, &unknowns_from_pose(&delta, &pose));
            assert!(back.is_none() || bad.is_finite(), "{at}: {back:?}");
        }
        for rates in [[bad; 3], [bad, 0.0, 1.0]] {
            let r = guard(|| velocity::twist(&delta, &v, &x, &rates)).unwrap();
            if let Ok(t) = r {
                assert!(t.angular.iter().chain(&t.linear).all(|c| c.is_finite()));
            }
            let r = guard(|| velocity::pivot_rates(&delta, &v, &x, &rates)).unwrap();
            assert!(
                r.is_ok_and(|r| r.iter().all(|c| c.is_finite())) || r.is_err(),
                "{rates:?}"
            );
        }
        let wanted = Twist {
            angular: [bad, 0.0, 0.0],
            linear: [0.0, bad, 1.0],
        };
        let r = guard(|| velocity::input_rates(&delta, &v, &x, &wanted)).unwrap();
        if let Ok(r) = r {
            assert!(r.rates.iter().all(|c| c.is_finite()), "{bad:e}: {r:?}");
        }
        let load = Wrench {
            moment: [0.0, bad, 0.0],
            force: [bad, 0.0, 0.0],
        };
        let r = guard(|| velocity::input_efforts(&delta, &v, &x, &load)).unwrap();
        assert!(r.is_err() || r.is_ok_and(|t| t.iter().all(|c| c.is_finite())));
        // A configuration that is not a solution has no velocity.
        let off = v.map(|q| q + 1.0);
        assert!(matches!(
            velocity::twist(&delta, &off, &x, &[1.0, 0.0, 0.0]),
            Err(VelocityError::NotASolution { .. })
        ));
    }
}

/// `AllModes` queried at hostile inputs answers each with a typed error or roots that hold,
/// and the next query at a sound input gives the same roots as before; extreme
/// `ModesOptions` are a typed error or a start set whose roots hold; `recenter` at hostile
/// centres leaves the start set as it was.
#[test]
fn all_modes_at_hostile_inputs_options_and_centres() {
    use linkage::modes::{AllModes, ModesError, ModesOptions, Roots};
    let x = [150.0, 160.0, 155.0];
    let holds = |roots: &Roots<9, 32>, x: &[f64; 3], at: &str| {
        for r in roots.real() {
            assert!(
                r.v.iter().all(|q| q.is_finite()) && residual_norm(&Rps3::new(), &r.v, x) <= 1e-6,
                "{at}: a real root off: {r:?}"
            );
        }
    };
    let mut modes = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &ModesOptions::default()).unwrap();
    let mut before = Box::new(Roots::<9, 32>::new());
    modes.solve(&x, &mut before).unwrap();
    holds(&before, &x, "sound");
    let same = |roots: &Roots<9, 32>| {
        roots.real().len() == before.real().len()
            && before.real().iter().all(|r| {
                roots
                    .real()
                    .iter()
                    .any(|q| linkage_tests::max_diff(&q.v, &r.v) < 1e-9)
            })
    };
    let mut roots = Box::new(Roots::<9, 32>::new());
    for bad in HOSTILE {
        for xs in [[bad; 3], [150.0, bad, 155.0]] {
            let at = format!("inputs {xs:?}");
            match guard(|| modes.solve(&xs, &mut roots)).unwrap_or_else(|p| panic!("{at}: {p}")) {
                Ok(()) => holds(&roots, &xs, &at),
                Err(ModesError::NonFinite) => assert!(!bad.is_finite(), "{at}"),
                Err(ModesError::InvalidInput { .. }) => assert!(bad.is_finite(), "{at}"),
                Err(e) => panic!("{at}: {e:?}"),
            }
            modes.solve(&x, &mut roots).unwrap();
            assert!(same(&roots), "{at}: the next sound query differs");
        }
        for (center, spread) in [([bad; 3], 1.0), (x, bad)] {
            let kept = modes.base_point().0.map(|c| c.re);
            let r = guard(|| modes.recenter(&center, spread, 7)).unwrap();
            if r.is_err() {
                assert_eq!(
                    modes.base_point().0.map(|c| c.re),
                    kept,
                    "recenter {center:?} {spread:e}"
                );
            }
            modes.solve(&x, &mut roots).unwrap();
            assert!(same(&roots), "recentered at {center:?}, {spread:e}: {r:?}");
        }
    }
    for (what, o) in [
        (
            "scale NaN",
            ModesOptions {
                scale: f64::NAN,
                ..ModesOptions::default()
            },
        ),
        (
            "scale -1",
            ModesOptions {
                scale: -1.0,
                ..ModesOptions::default()
            },
        ),
        (
            "scale inf",
            ModesOptions {
                scale: f64::INFINITY,
                ..ModesOptions::default()
            },
        ),
        (
            "scale 1e300",
            ModesOptions {
                scale: 1e300,
                ..ModesOptions::default()
            },
        ),
        (
            "scale 5e-324",
            ModesOptions {
                scale: 5e-324,
                ..ModesOptions::default()
            },
        ),
        (
            "max_loops 0",
            ModesOptions {
                max_loops: 0,
                ..ModesOptions::default()
            },
        ),
        (
            "stable_loops 0",
            ModesOptions {
                stable_loops: 0,
                ..ModesOptions::default()
            },
        ),
        (
            "stable_seeds 0",
            ModesOptions {
                stable_seeds: 0,
                ..ModesOptions::default()
            },
        ),
        (
            "expected 0",
            ModesOptions {
                expected: Some(0),
                ..ModesOptions::default()
            },
        ),
        (
            "expected 1",
            ModesOptions {
                expected: Some(1),
                ..ModesOptions::default()
            },
        ),
    ] {
        let got = guard(|| AllModes::<_, 9, 3, 32>::new(Rps3::new(), &o))
            .unwrap_or_else(|p| panic!("{what}: {p}"));
        if let Ok(m) = got {
            let r = guard(|| m.solve(&x, &mut roots)).unwrap_or_else(|p| panic!("{what}: {p}"));
            if r.is_ok() {
                holds(&roots, &x, what);
            }
            eprintln!(
                "{what}: {} starts, {:?}, {} real",
                m.start_count(),
                r,
                roots.real().len()
            );
        } else {
            eprintln!("{what}: {:?}", got.err());
        }
    }
}

/// A stored start set made of hostile values is refused, typed; `Start::new` at hostile
/// points is a typed error or a start that holds; a left-out equation's offset at NaN is
/// infinitely far, never small.
#[test]
fn stored_starts_and_starts_from_hostile_values() {
    use linkage::modes::{AllModes, Complex, ModesError, ModesOptions};
    let o = ModesOptions::default();
    let modes = AllModes::<_, 9, 3, 32>::new(Rps3::new(), &o).unwrap();
    let (p0, gamma) = (*modes.base_point().0, modes.base_point().1);
    let starts: Vec<[Complex; 9]> = (0..modes.start_count())
        .map(|i| modes.start(i).unwrap())
        .collect();
    for bad in HOSTILE {
        let z = Complex::real(bad);
        let tries = [
            (p0.map(|_| z), gamma, starts.clone()),
            (p0, z, starts.clone()),
            (p0, gamma, vec![[z; 9]]),
            (p0, gamma, {
                let mut s = starts.clone();
                s[1][4] = z;
                s
            }),
        ];
        for (k, (p, g, s)) in tries.into_iter().enumerate() {
            let r = guard(|| AllModes::<_, 9, 3, 32>::from_starts(Rps3::new(), p, g, &s, &o))
                .unwrap_or_else(|e| panic!("try {k} at {bad:e}: {e}"));
            match r {
                Ok(m) => assert!(
                    m.start_count() == starts.len(),
                    "try {k} at {bad:e}: accepted {} starts",
                    m.start_count()
                ),
                Err(ModesError::NonFinite | ModesError::BadStart { .. }) => {}
                Err(e) => panic!("try {k} at {bad:e}: {e:?}"),
            }
        }
    }
    let delta = Delta::new();
    let start = delta.home_start().unwrap();
    let five_bar = RootFiveBar::new();
    let home = five_bar.home_start().unwrap();
    assert_eq!(
        five_bar.dependent_offset(&[f64::NAN; 3], home.x()),
        f64::INFINITY
    );
    assert_eq!(five_bar.dependent_offset(home.v(), home.x()), 0.0);
    for bad in HOSTILE {
        // The error estimate never calls a point far off a root (or not finite) near one, and
        // det B of a non-finite point is 0.
        let off = start.v().map(|q| q + bad);
        let estimate = linkage::error_estimate(&delta, &off, start.x());
        if !bad.is_finite() || bad.abs() >= 1e17 {
            assert!(!(estimate < 1.0), "{bad:e}: error estimate {estimate:e}");
        }
        if !bad.is_finite() {
            assert_eq!(linkage::det_b(&delta, &off, start.x()), 0.0, "{bad:e}");
        }
        for v in [
            [bad; 18],
            start.v().map(|q| q + bad),
            start.v().map(|q| q * bad),
        ] {
            for x in [*start.x(), [bad; 3]] {
                // `Start::follow` too: from a point that solves nothing it follows a path, and
                // must still end at a start that holds or say why not.
                for follow in [false, true] {
                    let made = guard(|| {
                        if follow {
                            Start::follow(&delta, v, x)
                        } else {
                            Start::new(&delta, v, x)
                        }
                    });
                    match made.unwrap() {
                        Ok(s) => assert!(holds(&delta, s.v(), s.x()), "{bad:e}: {v:?} {x:?}"),
                        Err(
                            SolveError::NonFinite
                            | SolveError::InconsistentStart { .. }
                            | SolveError::SingularStart
                            | SolveError::InvalidInput { .. },
                        ) => {}
                        Err(e) => panic!("{bad:e}: {e:?}"),
                    }
                }
            }
        }
    }
}

/// `set_pivot` and `set_geometry` with hostile values: a typed error and the mechanism
/// unchanged, or a mechanism whose `home_start` is a typed error or a start that holds.
#[test]
fn set_pivot_and_set_geometry_with_hostile_values() {
    let delta = Delta::new();
    let mut tried = 0;
    for (link, pivot) in [
        ("base", "B1"),
        ("platform", "F11"),
        ("arm1", "E11"),
        ("base", "A2"),
    ] {
        for bad in HOSTILE {
            for p in [[bad; 3], [bad, 0.0, 0.0], [0.0, 0.0, 0.0]] {
                let mut d = delta.clone();
                let r = guard(|| d.set_pivot(link, pivot, p)).unwrap();
                tried += 1;
                match r {
                    Err(_) => assert_eq!(d, delta, "{link}.{pivot} = {p:?}: changed on error"),
                    Ok(()) => {
                        let start = guard(|| d.home_start()).unwrap();
                        if let Ok(s) = start {
                            assert!(holds(&d, s.v(), s.x()), "{link}.{pivot} = {p:?}");
                        }
                    }
                }
            }
        }
    }
    for name in Delta::GEOMETRY_NAMES {
        for bad in HOSTILE {
            let mut d = delta.clone();
            let r = guard(|| d.set_geometry(name, bad)).unwrap();
            tried += 1;
            match r {
                Err(GeometryError::NonFinite { name: n }) => {
                    assert!(!bad.is_finite() && n == name, "{name} = {bad:e}")
                }
                Err(_) => assert_eq!(d, delta, "{name} = {bad:e}: changed on error"),
                Ok(()) => {
                    if let Ok(s) = guard(|| d.home_start()).unwrap() {
                        assert!(holds(&d, s.v(), s.x()), "{name} = {bad:e}");
                    }
                }
            }
        }
    }
    assert!(tried > 700);
}

/// Table III's platform scaled by k (a geometry `with_joints` and `from_geometry` accept, its
/// constants finite): from 1e-20 to 1e20 it starts and solves as the unscaled machine does; at
/// 1e±40 and 1e±60 det B, a product of 18 pivots of size ~k, over- or underflows although B is
/// regular by its scale-free condition, and `Start::new` says so as `NonFinite` (a value out of
/// range), not `SingularStart` (which it said before).
#[test]
fn a_stewart_platform_at_a_scale_det_b_cannot_hold_is_refused_as_out_of_range() {
    use linkage_examples::stewart::{SixSix, Stewart, HOME_LEGS, HOME_POSE};
    let table = Stewart::new();
    for k in [1e-60, 1e-40, 1e-20, 1.0, 1e20, 1e40, 1e60] {
        let base = table.base_joints().map(|p| p.map(|c| c * k));
        let platform: [[f64; 3]; 6] = std::array::from_fn(|i| table.point_local(i).map(|c| c * k));
        let sys = Stewart::with_joints(&base, &platform).unwrap();
        let [yaw, pitch, roll, x, y, z] = HOME_POSE;
        let pose = Pose::from_euler(yaw, pitch, roll, [x * k, y * k, z * k]);
        let v = unknowns_from_pose(&sys, &pose);
        let start = Start::new(&sys, v, HOME_LEGS.map(|l| l * k));
        if !(1e-30..=1e30).contains(&k) {
            assert_eq!(start, Err(SolveError::NonFinite), "scale {k:e}");
            continue;
        }
        let start = start.unwrap_or_else(|e| panic!("scale {k:e}: {e:?}"));
        let o = Options {
            tolerance: 1e-9 * k,
            ..Options::TIGHT
        };
        let sol = arc_length(&sys, &start, &HOME_LEGS.map(|l| l * k * 1.01), &o).unwrap();
        assert!(sol.is_ok(), "scale {k:e}: {:?}", sol.status);
    }
}

/// A pivot declared on a prismatic axis, moved off it by moving the axis (a SCARA's quill
/// axis tilted: `arm2.W` 10 mm out, `Wz` kept), is `NotCollinear` — it was `NotCoplanar`,
/// which speaks of the platform's plane — and the mechanism is unchanged; moving the link's
/// own pivots within its motion is a mechanism that starts.
#[test]
fn a_point_moved_off_its_axis_is_not_collinear() {
    let scara = Scara::new();
    let mut s = scara.clone();
    assert_eq!(
        s.set_pivot("arm2", "W", [360.0, 0.0, 0.0]),
        Err(GeometryError::NotCollinear)
    );
    assert_eq!(s, scara);
    assert!(GeometryError::NotCollinear.to_string().contains("line"));
    s.set_pivot("arm1", "E", [210.0, 0.0, 0.0]).unwrap();
    let start = s.home_start().unwrap();
    assert!(holds(&s, start.v(), start.x()));
}
