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

/// The geometry path with its own check: `None` where a step was refused or det B changed
/// sign between two steps (no path of regular configurations at the home inputs from the
/// declared geometry to this one, or one too bent for `steps`).
fn checked_geometry_path<S: Mechanism<N, M>, const N: usize, const M: usize, const G: usize>(
    home: Start<N, M>,
    from: [f64; G],
    to: [f64; G],
    make: impl Fn([f64; G]) -> Option<S>,
    steps: usize,
) -> Option<Start<N, M>> {
    let mut step = home;
    for k in 1..=steps {
        let t = k as f64 / steps as f64;
        let s = make(std::array::from_fn(|i| from[i] + t * (to[i] - from[i])))?;
        let next = Start::new(&s, *step.v(), *step.x()).ok()?;
        if next.det().signum() != step.det().signum() {
            return None;
        }
        step = next;
    }
    Some(step)
}

/// What random calibrations of one mechanism came to.
#[derive(Debug, Default)]
struct Calibrations {
    /// `home_start` where the geometry path arrives.
    agreed: usize,
    /// Both refused: no path of regular configurations to the calibrated geometry.
    refused: usize,
    /// The declared configuration, solving the calibrated geometry as it stands.
    as_declared: usize,
    /// Near the home pose, at the inputs the closed forms give there (where they place every
    /// unknown): not on the path at the home inputs, and checked as a pose.
    posed: usize,
}

/// `$count` random calibrations of `$ty`: one to three geometry values each moved by up to
/// `$reach` mm (a ratio by `$reach` % of itself), as `set_geometry` accepts them: small
/// enough that no axis's second point, 1 mm from its first in some declarations, passes
/// through it (an axis reversed is another mechanism, and the straight path of geometry to
/// it meets an axis of no length). `home_start` must
/// be where the geometry path arrives (checked with twice the steps where it does not at
/// first), on the declared home's branch, or refuse where the path cannot be followed either;
/// never a refusal where the path arrives, never a start somewhere else.
macro_rules! calibrations {
    ($ty:ty, $rng:expr, $reach:expr, $count:expr) => {{
        let declared = <$ty>::new();
        let home = declared.home_start().unwrap();
        let names = <$ty>::GEOMETRY_NAMES;
        let mut tally = Calibrations::default();
        let mut tries = 0;
        while tally.agreed + tally.refused + tally.as_declared + tally.posed < $count {
            tries += 1;
            assert!(
                tries < 100 * $count,
                "{}: too few calibrations accepted",
                <$ty>::NAME
            );
            let mut cal = declared.clone();
            let moves = 1 + ($rng.next_u64() % 3) as usize;
            let mut ok = true;
            for _ in 0..moves {
                let k = ($rng.next_u64() % names.len() as u64) as usize;
                let value = cal.geometry()[k];
                // A coordinate or length by up to `$reach` mm; a ratio (a value strictly
                // between −1 and 1, not 0) by `$reach` % of itself.
                let reach = if value != 0.0 && value.abs() < 1.0 {
                    0.01 * $reach * value.abs()
                } else {
                    $reach
                };
                ok &= cal
                    .set_geometry(names[k], value + $rng.uniform(-reach, reach))
                    .is_ok();
            }
            if !ok || cal.geometry() == declared.geometry() {
                continue;
            }
            let to = *cal.geometry();
            let make = |g| <$ty>::from_geometry(g).ok();
            let path = checked_geometry_path(home, <$ty>::DEFAULT_GEOMETRY, to, make, 200)
                .or_else(|| checked_geometry_path(home, <$ty>::DEFAULT_GEOMETRY, to, make, 2000));
            let scale = home.v().iter().map(|e| e * e).sum::<f64>().sqrt();
            match (cal.home_start(), path) {
                (Ok(start), _) if start.x() != &<$ty>::HOME_INPUTS => {
                    // Within what `Start::new` refines (1e-3 of the scale): the home pose may
                    // be off the calibrated machine's motion (a delta with three freedoms).
                    let at = pose_of(&cal, start.v());
                    assert!(
                        max_diff(&at, &<$ty>::HOME) < 1e-3 * scale,
                        "{}: {at:?}",
                        <$ty>::NAME
                    );
                    tally.posed += 1;
                }
                (Ok(start), Some(path)) => {
                    assert!(
                        max_diff(start.v(), path.v()) < 1e-7 * scale,
                        "{}: calibrated to {to:?}: home_start {:?}, the geometry path {:?}",
                        <$ty>::NAME,
                        start.v(),
                        path.v()
                    );
                    assert!(start.det() * home.det() > 0.0);
                    tally.agreed += 1;
                }
                (Ok(start), None) => {
                    // Only the declared configuration itself, where it solves the new geometry
                    // (a U's axis reversed along its line: a path through the calibrations
                    // between meets the axis of no length where its two points meet).
                    assert!(
                        max_diff(start.v(), &<$ty>::HOME_V) < 1e-8 * scale,
                        "{}: calibrated to {to:?}: home_start {:?} where the geometry path \
                         cannot go",
                        <$ty>::NAME,
                        start.v()
                    );
                    tally.as_declared += 1;
                }
                (Err(e), Some(path)) => panic!(
                    "{}: calibrated to {to:?}: home_start refused ({e:?}) where the geometry \
                     path arrives at {:?}",
                    <$ty>::NAME,
                    path.v()
                ),
                (Err(_), None) => tally.refused += 1,
            }
        }
        tally
    }};
}

/// Random calibrations of the declared mechanisms, each checked against the geometry path.
/// Before `home_start` followed the change of geometry (it followed the residual of the
/// declared configuration on the new geometry), a spherical 3-UPU wrist with its base 0.3 mm
/// deeper started in another operation mode, and 1–3 % calibrations of a 3-PUU were refused.
#[test]
fn a_calibrated_mechanism_starts_where_its_geometry_path_arrives() {
    use super::bennett::Bennett;
    use super::delta::Delta;
    use super::delta_universal::DeltaUniversal;
    use super::five_bar::FiveBar;
    use super::goldberg::Goldberg;
    use super::partly_driven_cylinders::Crr;
    use super::pcs::Pcs;
    use super::planar_rpr::PlanarRpr;
    use super::prs::Prs;
    use super::rrs::Rrs;
    use super::spherical_wrist::Wrist;
    use super::translational_upu::TranslationalUpu;
    use super::tricept::Tricept;
    use super::tripteron::Tripteron;
    use super::upu_wrist::UpuWrist;
    let mut rng = Rng::new(20_261_130);
    let mut tallies = Vec::new();
    for reach in [0.02, 0.3] {
        tallies.push(("UpuWrist", calibrations!(UpuWrist, rng, reach, 4)));
        tallies.push((
            "TranslationalUpu",
            calibrations!(TranslationalUpu, rng, reach, 4),
        ));
        tallies.push(("Tricept", calibrations!(Tricept, rng, reach, 4)));
        tallies.push(("Tripteron", calibrations!(Tripteron, rng, reach, 4)));
        tallies.push((
            "DeltaUniversal",
            calibrations!(DeltaUniversal, rng, reach, 4),
        ));
        tallies.push(("Delta", calibrations!(Delta, rng, reach, 4)));
        tallies.push(("Pcs", calibrations!(Pcs, rng, reach, 4)));
        tallies.push(("Prs", calibrations!(Prs, rng, reach, 4)));
        tallies.push(("Rrs", calibrations!(Rrs, rng, reach, 4)));
        tallies.push(("Wrist", calibrations!(Wrist, rng, reach, 4)));
        tallies.push(("Goldberg", calibrations!(Goldberg, rng, reach, 4)));
        tallies.push(("Bennett", calibrations!(Bennett, rng, reach, 4)));
        tallies.push(("PlanarRpr", calibrations!(PlanarRpr, rng, reach, 4)));
        tallies.push(("FiveBar", calibrations!(FiveBar, rng, reach, 4)));
        tallies.push(("Crr", calibrations!(Crr, rng, reach, 4)));
        tallies.push(("Rps3", calibrations!(Rps3, rng, reach, 4)));
    }
    let agreed: usize = tallies.iter().map(|(_, t)| t.agreed).sum();
    println!("{tallies:?}");
    // The check has teeth only where calibrations moved the start: most of them.
    assert!(agreed >= tallies.len() * 2, "{tallies:?}");
}
