//! Links every `#[no_panic]` entry point of the library (the proof), then runs them once on
//! good and on bad input (a smoke test that they are the real thing).

use core::hint::black_box;
use core::mem::MaybeUninit;
use linkage::modes::{EndpointKind, ModesError, ModesOptions, Roots};
use linkage::velocity::Wrench;
use linkage::{Mechanism, Options, Pose, Tracker};
use linkage_ffi::{status, LinkageGeometry, LinkagePose, LinkageReport, LinkageStrutCorrection};
use no_panic_proof::{ffi, hexapod, rps, stewart, Exechon, FiveBar, Rps, RssHexapod, Stewart};

fn main() {
    let o = black_box(Options::TIGHT);

    let sys = Rps::new();
    let v0 = linkage::unknowns_from_pose(&sys, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    let x0 = sys.inverse(&v0, &[0.0; 3]).expect("the 3-RPS at home");
    let s = rps::start(&sys, v0, x0).expect("the 3-RPS's start");
    let x = black_box([160.0, 155.0, 158.0]);
    let sol = rps::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(rps::nr(&sys, &s, &x, &o).is_ok() && rps::nh(&sys, &s, &x, &o).is_ok());
    let prepared = linkage::NewtonRaphson::new(sys.clone(), s);
    assert_eq!(
        rps::nr_prepared(&prepared, &x, &o),
        rps::nr(&sys, &s, &x, &o)
    );
    assert!(rps::detour(&sys, &s, &x, &o).is_ok());
    assert!(rps::proof(&sys, &sol.v, &x).is_ok());
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(rps::track(&mut t, &x).is_ok());
    let bad = black_box([f64::NAN, 155.0, 158.0]);
    assert!(rps::nr(&sys, &s, &bad, &o).is_err() && rps::ph(&sys, &s, &bad, &o).is_err());
    assert!(rps::track(&mut t, &bad).is_err() && rps::proof(&sys, &sol.v, &bad).is_err());
    assert!(rps::start(&sys, [f64::NAN; 9], x0).is_err());
    let xdot = black_box([1.0, -0.5, 0.25]);
    let back = rps::rates(&sys, &sol.v, &x, &xdot).expect("rates");
    assert!(
        back.iter().zip(&xdot).all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
    assert!(rps::rates(&sys, &sol.v, &x, &bad).is_err());
    let load = black_box(Wrench {
        moment: [0.0; 3],
        force: [0.0, 0.0, -30.0],
    });
    assert!(rps::efforts(&sys, &sol.v, &x, &load).is_ok());
    let nan = black_box(Wrench {
        moment: [f64::NAN; 3],
        force: [0.0; 3],
    });
    assert!(rps::efforts(&sys, &sol.v, &x, &nan).is_err());

    let sys = Stewart::new();
    let v0 = linkage::unknowns_from_pose(
        &sys,
        &Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]),
    );
    let x0 = sys
        .inverse(&v0, &[170.0; 6])
        .expect("the Stewart platform at home");
    let s = stewart::start(&sys, v0, x0).expect("the Stewart platform's start");
    let x = black_box([175.0, 172.0, 168.0, 171.0, 169.0, 173.0]);
    let sol = stewart::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(stewart::nr(&sys, &s, &x, &o).is_ok() && stewart::nh(&sys, &s, &x, &o).is_ok());
    let prepared = linkage::NewtonRaphson::new(sys.clone(), s);
    assert_eq!(
        stewart::nr_prepared(&prepared, &x, &o),
        stewart::nr(&sys, &s, &x, &o)
    );
    assert!(stewart::detour(&sys, &s, &x, &o).is_ok());
    assert!(stewart::proof(&sys, &sol.v, &x).is_ok());
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(stewart::track(&mut t, &x).is_ok());
    let bad = black_box([f64::INFINITY; 6]);
    assert!(stewart::nr(&sys, &s, &bad, &o).is_err() && stewart::track(&mut t, &bad).is_err());
    let xdot = black_box([1.0, -1.0, 0.5, 0.0, 2.0, -0.5]);
    let back = stewart::rates(&sys, &sol.v, &x, &xdot).expect("rates");
    assert!(
        back.iter().zip(&xdot).all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
    assert!(stewart::rates(&sys, &sol.v, &x, &bad).is_err());
    assert!(stewart::efforts(&sys, &sol.v, &x, &load).is_ok());
    let sys = RssHexapod::new();
    let s = sys.home_start().expect("the hexapod's start");
    let x = black_box(s.x().map(|q| q + 0.05));
    let sol = hexapod::ph(&sys, &s, &x, &o).expect("a solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    assert!(hexapod::nr(&sys, &s, &x, &o).is_ok() && hexapod::proof(&sys, &sol.v, &x).is_ok());
    let xdot = black_box([0.1, -0.2, 0.3, 0.0, 0.2, -0.1]);
    let back = hexapod::rates(&sys, &sol.v, &x, &xdot).expect("rates");
    assert!(
        back.iter().zip(&xdot).all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
    assert!(hexapod::efforts(&sys, &sol.v, &x, &load).is_ok());
    let prepared = linkage::NewtonRaphson::new(sys.clone(), s);
    assert_eq!(
        hexapod::nr_prepared(&prepared, &x, &o),
        hexapod::nr(&sys, &s, &x, &o)
    );
    let mut t = Tracker::new(sys.clone(), s, o);
    assert!(hexapod::track(&mut t, &x).is_ok());
    assert!(hexapod::nh(&sys, &s, &black_box([f64::NAN; 6]), &o).is_err());
    exechon();
    five_bar();
    c_interface();
    all_modes();
    inverse();
    println!("no-panic proof: linked; every entry point ran on good and bad input");
}

/// PH to `x` from start `s`, its answer given back by the inverse, and NR, NH, prepared NR,
/// the detour, the certificate and the tracker to the same target: `(PH's solution, the
/// tracker)`. For mechanisms whose proven module and inverse are both named `$m`.
macro_rules! every_solver {
    ($m:ident, $sys:ident, $s:ident, $x:ident, $o:ident) => {{
        let (sys, s, x, o) = (&$sys, &$s, &$x, &$o);
        let sol = $m::ph(sys, s, x, o).expect("a solve");
        assert!(sol.is_ok(), "{:?}", sol.status);
        let back = no_panic_proof::inverse::$m(sys, &sol.v, s.x()).expect("its inverse");
        assert!(
            back.iter().zip(x).all(|(a, b)| (a - b).abs() < 1e-9),
            "{back:?}"
        );
        assert!($m::nr(sys, s, x, o).is_ok() && $m::nh(sys, s, x, o).is_ok());
        let prepared = linkage::NewtonRaphson::new(sys.clone(), *s);
        assert_eq!($m::nr_prepared(&prepared, x, o), $m::nr(sys, s, x, o));
        assert!($m::detour(sys, s, x, o).is_ok());
        assert!($m::proof(sys, &sol.v, x).is_ok());
        let mut t = Tracker::new(sys.clone(), *s, *o);
        assert!($m::track(&mut t, x).is_ok());
        (sol, t)
    }};
}

/// Every solver on the Exechon (overconstrained: 36 unknowns, three inputs, an equation left
/// out of the square system): legs from 700 mm to a nearby target, then the refusals.
fn exechon() {
    use no_panic_proof::exechon;
    let o = Options::TIGHT;
    let sys = Exechon::new();
    let s = sys.home_start().expect("the Exechon's start");
    let v0 = *s.v();
    let s = exechon::start(&sys, v0, *s.x()).expect("the Exechon's start, checked");
    let x = black_box([705.0, 700.0, 698.0]);
    let (sol, mut t) = every_solver!(exechon, sys, s, x, o);
    let xdot = black_box([1.0, -0.5, 0.25]);
    let back = exechon::rates(&sys, &sol.v, &x, &xdot).expect("rates");
    assert!(
        back.iter().zip(&xdot).all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
    let load = black_box(Wrench {
        force: [0.0, 0.0, -100.0],
        moment: [0.0; 3],
    });
    assert!(exechon::efforts(&sys, &sol.v, &x, &load).is_ok());
    let bad = black_box([f64::NAN, 700.0, 700.0]);
    assert!(exechon::ph(&sys, &s, &bad, &o).is_err() && exechon::track(&mut t, &bad).is_err());
    assert!(exechon::start(&sys, [f64::NAN; 36], *s.x()).is_err());
    assert!(no_panic_proof::inverse::exechon(&sys, &[f64::NAN; 36], s.x()).is_err());
}

/// Every solver on the five-bar (a point for a platform: no orientation), its modes too.
fn five_bar() {
    use no_panic_proof::five_bar;
    let o = Options::TIGHT;
    let sys = FiveBar::new();
    let s = sys.home_start().expect("the five-bar's start");
    let s = five_bar::start(&sys, *s.v(), *s.x()).expect("the five-bar's start, checked");
    let x = black_box(s.x().map(|q| q + 0.05));
    let (sol, mut t) = every_solver!(five_bar, sys, s, x, o);
    let xdot = black_box([0.1, -0.2]);
    // A point's velocity and statics: its rates, no turn.
    let back = five_bar::rates(&sys, &sol.v, &x, &xdot).expect("the point's rates");
    assert!((0..2).all(|i| (back[i] - xdot[i]).abs() < 1e-9));
    let load = black_box(Wrench {
        force: [0.0, -10.0, 0.0],
        moment: [0.0; 3],
    });
    assert!(five_bar::efforts(&sys, &sol.v, &x, &load).is_ok());
    let bad = black_box([f64::NAN, 0.0]);
    assert!(five_bar::ph(&sys, &s, &bad, &o).is_err() && five_bar::track(&mut t, &bad).is_err());
    let options = ModesOptions::default();
    let modes = no_panic_proof::modes::five_bar_new(sys, &options).expect("starts");
    let mut roots = Roots::<3, 8>::new();
    no_panic_proof::modes::five_bar(&modes, &x, &mut roots).expect("a query");
    // Two assembly modes (the circles' two intersections), nothing else.
    assert!(roots.is_complete() && roots.roots() == 2 && roots.real().len() == 2);
    assert!(roots
        .real()
        .iter()
        .any(|r| (0..3).all(|k| (r.v[k] - sol.v[k]).abs() < 1e-6)));
    let bad = no_panic_proof::modes::five_bar(&modes, &black_box([f64::NAN; 2]), &mut roots);
    assert_eq!(bad, Err(ModesError::NonFinite));
}

/// The C interface as LinuxCNC's module drives it: a handle in caller storage, inverse and
/// forward kinematics on genhexkins' default geometry, then the refusals.
fn c_interface() {
    let geometry = black_box(LinkageGeometry {
        base: [
            [-22.95, 13.25, 0.0],
            [22.95, 13.25, 0.0],
            [22.95, 13.25, 0.0],
            [0.0, -26.5, 0.0],
            [0.0, -26.5, 0.0],
            [-22.95, 13.25, 0.0],
        ],
        platform: [
            [-1.0, 11.5, 0.0],
            [1.0, 11.5, 0.0],
            [10.459, -4.884, 0.0],
            [9.459, -6.616, 0.0],
            [-9.459, -6.616, 0.0],
            [-10.459, -4.884, 0.0],
        ],
    });
    assert!(ffi::size() <= linkage_ffi::STORAGE);
    let mut slot = MaybeUninit::uninit();
    assert_eq!(ffi::init(Some(&mut slot), Some(&geometry)), status::OK);
    // A copy of what init wrote, through the safe constructor (no `unsafe` here).
    let h = slot.write(linkage_ffi::Hexapod::new(&geometry).expect("the geometry"));
    assert_eq!(ffi::set_options(Some(&mut *h), 1e-10, 50), status::OK);
    assert_eq!(ffi::set_certify(Some(&mut *h), 1), status::OK);
    let home = LinkagePose {
        z: 20.0,
        ..Default::default()
    };
    let moved = black_box(LinkagePose {
        x: 0.5,
        z: 20.5,
        c: 5.0,
        ..home
    });
    let (mut legs, mut corrections) = ([0.0; 6], [1.0; 6]);
    assert_eq!(
        ffi::inverse(Some(&*h), Some(&home), Some(&mut legs)),
        status::OK
    );
    assert_eq!(
        ffi::strut_corrections(Some(&*h), Some(&home), Some(&mut corrections)),
        status::OK
    );
    assert_eq!(corrections, [0.0; 6]);
    let mut pose = home;
    let mut report = LinkageReport::default();
    assert_eq!(
        ffi::forward(
            Some(&mut *h),
            Some(&legs),
            Some(&mut pose),
            Some(&mut report)
        ),
        status::OK
    );
    assert_eq!(ffi::is_tracking(Some(&*h)), 1);
    assert_eq!(
        ffi::inverse(Some(&*h), Some(&moved), Some(&mut legs)),
        status::OK
    );
    assert_eq!(
        ffi::forward(
            Some(&mut *h),
            Some(&legs),
            Some(&mut pose),
            Some(&mut report)
        ),
        status::OK
    );
    assert!(
        (pose.c - 5.0).abs() < 1e-6 && report.certified == 1,
        "{pose:?} {report:?}"
    );
    // The strut correction on: forward kinematics solves for it.
    let mut correction = LinkageStrutCorrection::NONE;
    correction.base_n = [[1.0, 0.0, 0.0]; 6];
    correction.platform_n = [[0.0, 1.0, 0.0]; 6];
    correction.screw_lead = black_box(0.2);
    assert_eq!(
        ffi::set_strut_correction(Some(&mut *h), Some(&correction)),
        status::OK
    );
    assert_eq!(
        ffi::inverse(Some(&*h), Some(&moved), Some(&mut legs)),
        status::OK
    );
    assert_eq!(
        ffi::forward(Some(&mut *h), Some(&legs), Some(&mut pose), None),
        status::OK
    );

    // Bad input comes back as a status code.
    let nan = black_box(f64::NAN);
    let mut bad = geometry;
    bad.platform[2][1] = nan;
    assert_eq!(
        ffi::set_geometry(Some(&mut *h), Some(&bad)),
        status::INVALID_GEOMETRY
    );
    bad.platform[2][1] = bad.platform[0][1];
    bad.platform = [bad.platform[0]; 6];
    assert_eq!(
        ffi::set_geometry(Some(&mut *h), Some(&bad)),
        status::INVALID_GEOMETRY
    );
    assert_eq!(
        ffi::set_options(Some(&mut *h), nan, 50),
        status::INVALID_OPTIONS
    );
    assert_eq!(ffi::set_certify(Some(&mut *h), 7), status::INVALID_OPTIONS);
    correction.screw_lead = nan;
    assert_eq!(
        ffi::set_strut_correction(Some(&mut *h), Some(&correction)),
        status::NON_FINITE
    );
    let nan_pose = LinkagePose { a: nan, ..home };
    assert_eq!(
        ffi::inverse(Some(&*h), Some(&nan_pose), Some(&mut legs)),
        status::NON_FINITE
    );
    assert_eq!(
        ffi::strut_corrections(Some(&*h), Some(&nan_pose), Some(&mut legs)),
        status::NON_FINITE
    );
    assert_eq!(
        ffi::forward(Some(&mut *h), Some(&[nan; 6]), Some(&mut pose), None),
        status::NON_FINITE
    );
    assert_eq!(
        ffi::forward(Some(&mut *h), Some(&[-1.0; 6]), Some(&mut pose), None),
        status::INVALID_INPUT
    );
    assert_eq!(ffi::reset(Some(&mut *h)), status::OK);
    assert_eq!(ffi::is_tracking(Some(&*h)), 0);
    // Legs far from the start pose: refused, not started.
    let mut report = LinkageReport::default();
    assert_eq!(
        ffi::forward(
            Some(&mut *h),
            Some(&[40.0; 6]),
            Some(&mut pose),
            Some(&mut report)
        ),
        status::POSE_MISMATCH
    );
    assert_eq!(
        ffi::forward(None, None, None, Some(&mut report)),
        status::NULL_POINTER
    );
    assert_eq!(report.status, status::NULL_POINTER);
    assert_eq!(ffi::init(None, Some(&geometry)), status::NULL_POINTER);
    assert!(!ffi::status_name(black_box(1234)).is_null());
}

/// The all-modes query for each mechanism: its real roots include the pose it was given, and
/// bad input is an error.
fn all_modes() {
    let options = ModesOptions::default();
    let modes = no_panic_proof::modes::rps_new(Rps::new(), &options).expect("the 3-RPS's starts");
    let nan = black_box(ModesOptions {
        confidence: f64::NAN,
        ..options
    });
    assert_eq!(
        no_panic_proof::modes::rps_new(Rps::new(), &nan).err(),
        Some(ModesError::NonFinite)
    );
    let mut roots = Box::new(Roots::<9, 32>::new());
    no_panic_proof::modes::rps(&modes, &black_box([150.0, 160.0, 155.0]), &mut roots)
        .expect("a 3-RPS query");
    assert!(roots.is_complete() && roots.count(EndpointKind::Real) > 0);
    let bad = no_panic_proof::modes::rps(&modes, &black_box([f64::NAN; 3]), &mut roots);
    assert_eq!(bad, Err(ModesError::NonFinite));
    // The same starts stored and taken back; a start repeated is refused.
    let starts: Vec<_> = (0..modes.start_count())
        .filter_map(|i| modes.start(i))
        .collect();
    let (p0, gamma) = modes.base_point();
    let again = no_panic_proof::modes::rps_from_starts(Rps::new(), *p0, gamma, &starts, &options)
        .expect("the stored starts");
    assert_eq!(again.start_count(), modes.start_count());
    let twice = [starts[0], starts[0]];
    assert!(
        no_panic_proof::modes::rps_from_starts(Rps::new(), *p0, gamma, &twice, &options).is_err()
    );
    let mut moved = modes.clone();
    no_panic_proof::modes::rps_recenter(&mut moved, &black_box([150.0, 160.0, 155.0]), 0.1, 7)
        .expect("recentred");
    assert_eq!(
        no_panic_proof::modes::rps_recenter(&mut moved, &black_box([f64::NAN; 3]), 0.1, 7),
        Err(ModesError::NonFinite)
    );

    let sys = Stewart::new();
    let v = linkage::unknowns_from_pose(
        &sys,
        &Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]),
    );
    let x = sys
        .inverse(&v, &[170.0; 6])
        .expect("the Stewart platform at home");
    let modes = Box::new(no_panic_proof::modes::stewart_new(sys, &options).expect("starts"));
    let mut roots = Box::new(Roots::<18, 64>::new());
    no_panic_proof::modes::stewart(&modes, &black_box(x), &mut roots).expect("a query");
    let home = roots
        .real()
        .iter()
        .any(|r| (0..18).all(|k| (r.v[k] - v[k]).abs() < 1e-6 * 200.0));
    assert!(home, "the home pose among the real roots");
    let bad = no_panic_proof::modes::stewart(&modes, &black_box([f64::INFINITY; 6]), &mut roots);
    assert_eq!(bad, Err(ModesError::NonFinite));

    let sys = RssHexapod::new();
    let s = sys.home_start().expect("the hexapod's start");
    let modes = Box::new(no_panic_proof::modes::hexapod_new(sys, &options).expect("starts"));
    let mut roots = Box::new(Roots::<18, 64>::new());
    no_panic_proof::modes::hexapod(&modes, &black_box(*s.x()), &mut roots).expect("a query");
    assert!(roots
        .real()
        .iter()
        .any(|r| (0..18).all(|k| (r.v[k] - s.v()[k]).abs() < 1e-4)));
    let bad = no_panic_proof::modes::hexapod(&modes, &black_box([f64::NAN; 6]), &mut roots);
    assert_eq!(bad, Err(ModesError::NonFinite));

    // The Exechon at home, legs of 700 mm: 48 paths, 4 of them ending at roots of the square
    // system that the mechanism's left-out equation refuses.
    let sys = Exechon::new();
    let modes = Box::new(no_panic_proof::modes::exechon_new(sys, &options).expect("starts"));
    let mut roots = Box::new(Roots::<36, 64>::new());
    no_panic_proof::modes::exechon(&modes, &black_box([700.0; 3]), &mut roots).expect("a query");
    assert!(roots.is_complete() && roots.count(EndpointKind::Spurious) == 4);
    let bad = no_panic_proof::modes::exechon(&modes, &black_box([f64::NAN; 3]), &mut roots);
    assert_eq!(bad, Err(ModesError::NonFinite));
}

/// Inverse kinematics gives a solved pose's inputs back, and refuses a NaN pose.
fn inverse() {
    use no_panic_proof::{inverse, Rrs, ScaraWrist};
    let o = Options::TIGHT;
    let sys = ScaraWrist::new();
    let start = sys.home_start().expect("the SCARA's start");
    let x = black_box([0.3, -0.4, 5.0, 0.2, 0.1]);
    let sol = linkage::arc_length(&sys, &start, &x, &o).expect("a SCARA solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    let back = inverse::scara_wrist(&sys, &sol.v, start.x()).expect("its inputs");
    assert!(
        back.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-6),
        "{back:?}"
    );
    let mut bad = sol.v;
    bad[0] = f64::NAN;
    assert!(inverse::scara_wrist(&sys, &black_box(bad), start.x()).is_err());

    // The 3-RRS: answered, and refused where its platform is out of shape (G3's x moved).
    let rrs = Rrs::new();
    let start = rrs.home_start().expect("the 3-RRS's start");
    let x = black_box([0.1, -0.05, 0.08]);
    let sol = linkage::arc_length(&rrs, &start, &x, &o).expect("a 3-RRS solve");
    assert!(sol.is_ok(), "{:?}", sol.status);
    let back = inverse::rrs(&rrs, &sol.v, start.x()).expect("its inputs");
    assert!(
        back.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-6),
        "{back:?}"
    );
    let mut bad = sol.v;
    bad[2] += 5.0;
    assert!(inverse::rrs(&rrs, &black_box(bad), start.x()).is_err());

    let rps = Rps::new();
    let v = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    assert!(inverse::rps(&rps, &black_box(v), &[0.0; 3]).is_ok());
    let mut bad = v;
    bad[4] = f64::INFINITY;
    let r = inverse::rps(&rps, &black_box(bad), &[0.0; 3]);
    assert!(r.is_err(), "{r:?}");
    let st = Stewart::new();
    let v = linkage::unknowns_from_pose(
        &st,
        &Pose::from_euler(0.0, 0.0, 0.0, [58.971, -11.739, 159.011]),
    );
    assert!(inverse::stewart(&st, &black_box(v), &[170.0; 6]).is_ok());
    assert!(inverse::stewart(&st, &black_box([f64::NAN; 18]), &[170.0; 6]).is_err());
    let hex = RssHexapod::new();
    let s = hex.home_start().expect("the hexapod's start");
    let back = inverse::hexapod(&hex, &black_box(*s.v()), s.x()).expect("the hexapod at home");
    assert!(back.iter().zip(s.x()).all(|(a, b)| (a - b).abs() < 1e-9));
    assert!(inverse::hexapod(&hex, &black_box([f64::NAN; 18]), s.x()).is_err());
}
