//! `home_start` after a calibration: a mechanism without closed forms starts at the
//! configuration its declared home inputs take on the calibrated geometry, on the declared
//! branch (`Start::follow`). Against the declared configuration itself for serial arms (at
//! their home inputs every link is where it was declared, wherever its pivots now are), and
//! for closed loops against an independent path: the geometry moved from the declared to the
//! calibrated in small steps, each start refined from the last by `Start::new`.

use super::four_bar::FourBar;
use super::published::{StephensonIII, WattI};
use linkage::{pose_from_unknowns, Mechanism, SolveError, Start};
use linkage_examples::rps::Rps3;
use linkage_serial_arms::{PanTilt, Scara, ScaraWrist};
use linkage_tests::{max_diff, residual_norm, Rng};

/// Steps of the geometry path the oracle takes (each moves the start by far less than the
/// 1e-3 of ‖v‖ that `Start::new` accepts).
const STEPS: usize = 200;

/// The oracle: the geometry moved from `from` to `to` in [`STEPS`] steps, the start refined
/// from the last at each by `Start::new` (which accepts only a small move).
fn geometry_path<S: Mechanism<N, M>, const N: usize, const M: usize, const G: usize>(
    home: Start<N, M>,
    from: [f64; G],
    to: [f64; G],
    make: impl Fn([f64; G]) -> S,
) -> Start<N, M> {
    let mut step = home;
    for k in 1..=STEPS {
        let t = k as f64 / STEPS as f64;
        let s = make(std::array::from_fn(|i| from[i] + t * (to[i] - from[i])));
        step = Start::new(&s, *step.v(), *step.x()).unwrap();
    }
    step
}

/// The platform's pose as `[yaw, pitch, roll, x, y, z]`.
fn pose_of<S: Mechanism<N, M>, const N: usize, const M: usize>(s: &S, v: &[f64; N]) -> [f64; 6] {
    let pose = pose_from_unknowns(s, v).unwrap();
    let [yaw, pitch, roll] = pose.euler();
    let [x, y, z] = pose.translation;
    [yaw, pitch, roll, x, y, z]
}

/// A serial arm's pivots moved at random by up to `$size` mm, three coordinates at a time:
/// the home start is the declared configuration of the calibrated arm (the platform at the
/// identity pose), at the declared inputs, on the declared branch. Returns how many
/// calibrations were checked (a move that takes a point off the axis it lies on is refused by
/// `set_geometry` and skipped).
macro_rules! serial_arm {
    ($ty:ty, $rng:expr, $size:expr) => {{
        let declared = <$ty>::new();
        let home = declared.home_start().unwrap();
        let mut checked = 0;
        for _ in 0..400 {
            if checked == 10 {
                break;
            }
            let mut s = declared.clone();
            let mut ok = true;
            for _ in 0..3 {
                let k = ($rng.next_u64() % <$ty>::GEOMETRY_NAMES.len() as u64) as usize;
                let value = <$ty>::DEFAULT_GEOMETRY[k] + $rng.uniform(-$size, $size);
                ok &= s.set_geometry(<$ty>::GEOMETRY_NAMES[k], value).is_ok();
            }
            if !ok {
                continue;
            }
            let start = s
                .home_start()
                .unwrap_or_else(|e| panic!("{}: {:?}: {e:?}", <$ty>::NAME, s.geometry()));
            assert_eq!(start.x(), home.x());
            assert!(start.det() * home.det() > 0.0, "{}", <$ty>::NAME);
            let at = pose_of(&s, start.v());
            assert!(
                max_diff(&at, &[0.0; 6]) < 1e-6,
                "{}: the platform at {at:?}, not where it was declared ({:?}, error estimate {})",
                <$ty>::NAME,
                s.geometry(),
                linkage::error_estimate(&s, start.v(), start.x())
            );
            checked += 1;
        }
        checked
    }};
}

#[test]
fn a_calibrated_serial_arm_starts_where_its_links_were_declared() {
    let mut rng = Rng::new(71);
    for size in [0.5, 5.0, 40.0] {
        let checked = [
            serial_arm!(PanTilt, rng, size),
            serial_arm!(Scara, rng, size),
            serial_arm!(ScaraWrist, rng, size),
        ];
        assert_eq!(checked, [10; 3], "{size}");
    }
}

/// The calibrated start of a closed loop against the geometry path: `$ty`'s planar pivots
/// `$moves` (a pivot and the other end of its vertical axis, moved together in the plane),
/// then the geometry moved from the declared to that in [`STEPS`] steps, the start refined
/// from the last at each. Both must agree on v (the same configuration of the same branch,
/// reached two different ways), at the declared inputs.
macro_rules! closed_loop {
    ($ty:ty, $moves:expr) => {{
        let declared = <$ty>::new();
        let home = declared.home_start().unwrap();
        let mut to = <$ty>::DEFAULT_GEOMETRY;
        for (link, pivot, [dx, dy]) in $moves {
            for name in [pivot.to_string(), format!("{pivot}z")] {
                let i = |c: &str| {
                    let n = format!("{link}.{name}.{c}");
                    <$ty>::GEOMETRY_NAMES.iter().position(|m| *m == n).unwrap()
                };
                to[i("x")] += dx;
                to[i("y")] += dy;
            }
        }
        let calibrated = <$ty>::from_geometry(to).unwrap();
        let followed = calibrated.home_start().unwrap();
        let step = geometry_path(home, <$ty>::DEFAULT_GEOMETRY, to, |g| {
            <$ty>::from_geometry(g).unwrap()
        });
        let scale = followed.v().iter().map(|e| e * e).sum::<f64>().sqrt();
        assert_eq!(followed.x(), home.x());
        assert!(residual_norm(&calibrated, followed.v(), followed.x()) < 1e-9 * scale);
        assert!(followed.det() * home.det() > 0.0);
        assert!(
            max_diff(followed.v(), step.v()) < 1e-8 * scale,
            "{}: followed {:?}, the geometry path {:?}",
            <$ty>::NAME,
            followed.v(),
            step.v()
        );
        // What `home_start` did before it followed: the declared configuration, refused.
        assert!(
            matches!(
                Start::new(&calibrated, <$ty>::HOME_V, <$ty>::HOME_INPUTS),
                Err(SolveError::InconsistentStart { .. })
            ),
            "{}",
            <$ty>::NAME
        );
    }};
}

#[test]
fn a_calibrated_closed_loop_starts_on_its_declared_branch() {
    closed_loop!(
        FourBar,
        [("base", "D", [4.0, -3.0]), ("platform", "C", [6.0, 5.0])]
    );
    closed_loop!(
        WattI,
        [("t1", "E", [3.0, 2.0]), ("platform", "G", [-6.0, 4.0])]
    );
    closed_loop!(
        StephensonIII,
        [("t1", "A1", [2.0, -3.0]), ("platform", "Q2", [-6.0, 3.0])]
    );
}

/// A 3-RPS has three freedoms and its home pose six coordinates: a calibration that moves a
/// platform pivot out of its leg's plane (G1 3 mm along the hinge axis) leaves the declared
/// home pose off the machine's motion, where the closed forms cannot place it. `home_start`
/// is then the configuration at the declared home inputs (it was an error), the same as the
/// geometry path's, with G1 in its leg's plane.
#[test]
fn a_calibrated_3_rps_whose_home_pose_it_cannot_take_starts_at_its_home_inputs() {
    let declared = Rps3::new();
    let home = declared.home_start().unwrap();
    let mut to = Rps3::DEFAULT_GEOMETRY;
    to[Rps3::GEOMETRY_NAMES
        .iter()
        .position(|n| *n == "platform.G1.x")
        .unwrap()] += 3.0;
    let calibrated = Rps3::from_geometry(to).unwrap();
    let start = calibrated.home_start().unwrap();
    assert_eq!(start.x(), home.x());
    assert!(start.det() * home.det() > 0.0);
    let step = geometry_path(home, Rps3::DEFAULT_GEOMETRY, to, |g| {
        Rps3::from_geometry(g).unwrap()
    });
    assert!(max_diff(start.v(), step.v()) < 1e-8 * 200.0);
    // G1 where its leg swings: the plane x = 0 through A1, normal to the hinge A1 → B1.
    let pose = linkage::pose_from_unknowns(&calibrated, start.v()).unwrap();
    assert!(pose.apply([3.0, 50.0, 0.0])[0].abs() < 1e-9);
    assert!(residual_norm(&calibrated, start.v(), start.x()) < 1e-9);
}

/// The four-bar's rocker pivot D moved onto the line through the coupler's joints B and C
/// (B, C, D in a line: coupler and rocker folded, the dyad's two assembly modes met): no
/// regular start there, and `home_start` refuses rather than follow to somewhere near. Just
/// off the line, on either side, the declared configuration solves the calibrated geometry
/// and is the start as declared (on one side it is the dyad's other mode than before the
/// calibration: the declaration says so).
#[test]
fn a_calibration_onto_a_fold_is_refused() {
    let c_at = |v: &[f64]| {
        let at = |n: &str| v[FourBar::UNKNOWNS.iter().position(|u| *u == n).unwrap()];
        [at("x_C"), at("y_C")]
    };
    for dy in [70.0, 69.5, 70.5] {
        let mut g = FourBar::DEFAULT_GEOMETRY;
        for (name, value) in [
            ("base.D.x", 150.0),
            ("base.D.y", dy),
            ("base.Dz.x", 150.0),
            ("base.Dz.y", dy),
        ] {
            g[FourBar::GEOMETRY_NAMES
                .iter()
                .position(|m| *m == name)
                .unwrap()] = value;
        }
        let s = FourBar::from_geometry(g).unwrap();
        match s.home_start() {
            Ok(start) => {
                assert!(dy != 70.0, "a start at the fold: {start:?}");
                assert!(max_diff(&c_at(start.v()), &[100.0, 60.0]) < 1e-9);
            }
            Err(e) => assert!(dy == 70.0 && e == SolveError::SingularStart, "{dy}: {e:?}"),
        }
    }
}
