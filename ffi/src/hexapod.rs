//! A 6-6 hexapod whose geometry is set at run time: closed-form inverse kinematics, and
//! forward kinematics by the trajectory tracker, which stays on one branch.

use linkage::{Options, Tracker};
use linkage_stewart::{
    find_start, legs_for_pose, platform_is_coplanar, SixSix, StartError, Stewart, StewartGeneral,
};

use crate::geometry::LinkageGeometry;
use crate::pose::LinkagePose;
use crate::status;
use crate::strut_correction::LinkageStrutCorrection;

/// What one forward call did, besides its status.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinkageReport {
    /// |det B| / |det B at the start|: 1 at the start, 0 at a direct singularity.
    /// Left unchanged by a refused call.
    pub proximity: f64,
    /// The call's status code (as returned).
    pub status: i32,
    /// Newton iterations spent.
    pub newton_iterations: u32,
    /// 1 when the predictor–corrector failed and continuation took over.
    pub fell_back: i32,
    /// 1 when this call started tracking (at the pose passed in).
    pub started: i32,
    /// 1 when certification is on and this call's step was proven to keep the branch.
    pub certified: i32,
}

/// The rigid-body form the geometry needs: the coplanar one is the paper's Eq. 19.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum Model {
    Coplanar(Stewart),
    General(StewartGeneral),
}

// Unboxed on purpose: the handle is one fixed-size block in caller storage, never allocated.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
enum Tracking {
    Coplanar(Tracker<Stewart, 18, 6>),
    General(Tracker<StewartGeneral, 18, 6>),
}

/// The state behind a C handle. Fixed size, never allocates, needs no destructor.
#[derive(Clone, Debug)]
pub struct Hexapod {
    geometry: LinkageGeometry,
    model: Model,
    tracking: Option<Tracking>,
    options: Options,
    correction: LinkageStrutCorrection,
    certify: bool,
}

/// Most passes of the strut-correction fixed point (each one tracker update); the
/// correction's share of a strut's length change is small, so a few passes suffice.
const CORRECTION_PASSES: usize = 20;

fn model(g: &LinkageGeometry) -> Result<Model, i32> {
    let finite = g
        .base
        .iter()
        .chain(&g.platform)
        .flatten()
        .all(|v| v.is_finite());
    if !finite {
        return Err(status::INVALID_GEOMETRY);
    }
    let built = if platform_is_coplanar(&g.platform) {
        Stewart::with_joints(&g.base, &g.platform).map(Model::Coplanar)
    } else {
        StewartGeneral::with_joints(&g.base, &g.platform).map(Model::General)
    };
    built.map_err(|_| status::INVALID_GEOMETRY)
}

fn check_legs(legs: &[f64; 6]) -> Result<(), i32> {
    if !legs.iter().all(|l| l.is_finite()) {
        return Err(status::NON_FINITE);
    }
    if !legs.iter().all(|l| *l > 0.0) {
        return Err(status::INVALID_INPUT);
    }
    Ok(())
}

fn inverse_with<S: SixSix>(sys: &S, pose: &LinkagePose) -> Result<[f64; 6], i32> {
    if !pose.is_finite() {
        return Err(status::NON_FINITE);
    }
    legs_for_pose(sys, &pose.to_pose())
        .map(|(legs, _)| legs)
        .ok_or(status::UNREACHABLE)
}

fn start_with<S: SixSix>(
    sys: &S,
    legs: &[f64; 6],
    at: &LinkagePose,
    options: Options,
    certify: bool,
) -> Result<Tracker<S, 18, 6>, i32> {
    let start = find_start(sys, *legs, Some(at.to_pose())).map_err(|e| match e {
        StartError::Solve(e) => status::of_error(&e),
        StartError::PoseMismatch | StartError::NoAssemblyMode => status::POSE_MISMATCH,
        // Not met with a start pose given (its own check comes first), but a geometry singular
        // everywhere is a singular start.
        StartError::SingularEverywhere => status::SINGULAR_START,
    })?;
    let tracker = Tracker::new(sys.clone(), start, options);
    Ok(if certify {
        tracker.certified()
    } else {
        tracker
    })
}

/// The largest angle word accepted, degrees: 2¹⁶ rad (about 10 400 turns), the runtime's bound
/// on an inverse's reference angle. The words reported are the solved angles moved by whole
/// turns to lie nearest the caller's; beyond this a double near the caller's word no longer
/// holds the solved angle (at 1e20° the words of an `OK` pose gave legs 8.8 units off).
const MAX_ANGLE_WORD: f64 = 65536.0 * (180.0 / core::f64::consts::PI);

/// Whether every angle word of `pose` is within [`MAX_ANGLE_WORD`].
fn angle_words_in_range(pose: &LinkagePose) -> bool {
    [pose.a, pose.b, pose.c]
        .iter()
        .all(|w| w.abs() <= MAX_ANGLE_WORD)
}

/// One tracker update; on `OK`, `pose` holds the solution in the angle words nearest the ones
/// it held. Those words must give back the legs to the tolerance, as strut lengths
/// |R p_i + t − b_i| of `geometry` (the check the `stewart` command line makes on every `ok`
/// row): words moved by whole turns round, and the configuration solved is only the answer
/// if the pose reported places it. On any refusal the tracker is left where it was.
fn track<S: SixSix>(
    tracker: &mut Tracker<S, 18, 6>,
    legs: &[f64; 6],
    pose: &mut LinkagePose,
    report: &mut LinkageReport,
    geometry: &LinkageGeometry,
    tolerance: f64,
) -> i32 {
    let before = tracker.clone();
    match tracker.update(legs) {
        Ok(sample) => {
            let words = linkage::pose_from_unknowns(tracker.mechanism(), &sample.v)
                .map(|p| LinkagePose::from_pose(&p, pose));
            let Some(words) = words else {
                *tracker = before;
                return status::FAILED;
            };
            let placed = words.to_pose();
            let gives_back = (0..6).all(|i| {
                let w = placed.apply(geometry.platform[i]);
                let d = [0, 1, 2].map(|k| w[k] - geometry.base[i][k]);
                let strut = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                (strut - legs[i]).abs() <= tolerance
            });
            if !gives_back {
                *tracker = before;
                return status::TOLERANCE_NOT_MET;
            }
            *pose = words;
            report.proximity = sample.proximity;
            report.newton_iterations = sample.newton_iterations;
            report.fell_back = i32::from(sample.fell_back);
            report.certified = i32::from(sample.proof.is_some_and(|p| p.is_proven()));
            status::OK
        }
        Err(linkage::TrackError::Input(e)) => status::of_error(&e),
        Err(linkage::TrackError::Lost(s)) => status::of_status(&s),
        // Only a certified tracker refuses a sample as unproven; this one is not: a refusal
        // all the same, never ok.
        Err(linkage::TrackError::Unproven { .. }) => status::UNPROVEN,
    }
}

impl Hexapod {
    /// A hexapod with this geometry, not yet tracking.
    pub fn new(geometry: &LinkageGeometry) -> Result<Hexapod, i32> {
        Ok(Hexapod {
            geometry: *geometry,
            model: model(geometry)?,
            tracking: None,
            options: Options::TIGHT,
            correction: LinkageStrutCorrection::NONE,
            certify: false,
        })
    }

    /// Replaces the geometry; tracking starts afresh at the next forward call.
    pub fn set_geometry(&mut self, geometry: &LinkageGeometry) -> Result<(), i32> {
        self.model = model(geometry)?;
        self.geometry = *geometry;
        self.tracking = None;
        Ok(())
    }

    /// Sets genhexkins' strut length correction (a zero screw lead turns it off); a change
    /// restarts tracking at the next forward call.
    pub fn set_strut_correction(&mut self, c: &LinkageStrutCorrection) -> Result<(), i32> {
        c.check()?;
        if *c != self.correction {
            self.correction = *c;
            self.tracking = None;
        }
        Ok(())
    }

    /// The convergence tolerance (length units of the geometry) and Newton iteration limit.
    /// Takes effect when tracking next starts.
    pub fn set_options(&mut self, tolerance: f64, max_iterations: u32) -> Result<(), i32> {
        if !(tolerance.is_finite() && tolerance > 0.0) || max_iterations == 0 {
            return Err(status::INVALID_OPTIONS);
        }
        if tolerance != self.options.tolerance || max_iterations != self.options.max_iterations {
            self.options.tolerance = tolerance;
            self.options.max_iterations = max_iterations;
            self.tracking = None;
        }
        Ok(())
    }

    /// Certification of every forward step: each accepted step proven (interval
    /// certificates chained from the start) to stay on the branch, an unproven one refused
    /// (`UNPROVEN`). A change restarts tracking at the next forward call.
    pub fn set_certify(&mut self, on: bool) {
        if on != self.certify {
            self.certify = on;
            self.tracking = None;
        }
    }

    /// Forgets the tracked branch: the next forward call starts again.
    pub fn reset(&mut self) {
        self.tracking = None;
    }

    pub fn is_tracking(&self) -> bool {
        self.tracking.is_some()
    }

    /// Leg lengths for a pose (closed form, one solution), with the strut correction.
    pub fn inverse(&self, pose: &LinkagePose) -> Result<[f64; 6], i32> {
        let struts = self.struts(pose)?;
        let corrections = self.strut_corrections(pose)?;
        Ok(std::array::from_fn(|i| struts[i] + corrections[i]))
    }

    /// The strut corrections at a pose (zeros when the correction is off).
    pub fn strut_corrections(&self, pose: &LinkagePose) -> Result<[f64; 6], i32> {
        if !pose.is_finite() {
            return Err(status::NON_FINITE);
        }
        self.correction.at(&self.geometry, &pose.to_pose())
    }

    /// The struts' geometric lengths at a pose.
    fn struts(&self, pose: &LinkagePose) -> Result<[f64; 6], i32> {
        match &self.model {
            Model::Coplanar(s) => inverse_with(s, pose),
            Model::General(s) => inverse_with(s, pose),
        }
    }

    /// Forward kinematics. When not tracking, tracking starts at `pose` (the legs must match
    /// it to 1 % of the platform's size); afterwards each call continues from the last
    /// accepted solution and `pose` only chooses the angle words nearest it. On success
    /// `pose` holds the result; on any refusal it is left as it was, and so is the tracker.
    pub fn forward(
        &mut self,
        legs: &[f64; 6],
        pose: &mut LinkagePose,
        report: &mut LinkageReport,
    ) -> i32 {
        let code = self.forward_inner(legs, pose, report);
        report.status = code;
        code
    }

    fn forward_inner(
        &mut self,
        legs: &[f64; 6],
        pose: &mut LinkagePose,
        report: &mut LinkageReport,
    ) -> i32 {
        report.started = 0;
        report.newton_iterations = 0;
        report.fell_back = 0;
        report.certified = 0;
        if let Err(code) = check_legs(legs) {
            return code;
        }
        if !pose.is_finite() {
            return status::NON_FINITE;
        }
        if !angle_words_in_range(pose) {
            return status::INVALID_INPUT;
        }
        if self.correction.is_on() {
            return self.forward_corrected(legs, pose, report);
        }
        self.forward_struts(legs, pose, report)
    }

    /// Forward kinematics with the strut correction: the struts' geometric lengths are the
    /// joints less the correction at the pose, which the pose depends on. A fixed point:
    /// track the struts for the correction at the last pose, until the correction changes by
    /// at most a quarter of the tolerance. On any failure the tracker goes back to where it was.
    fn forward_corrected(
        &mut self,
        joints: &[f64; 6],
        pose: &mut LinkagePose,
        report: &mut LinkageReport,
    ) -> i32 {
        let saved = self.tracking.clone();
        let tolerance = self.options.tolerance;
        let (mut iterations, mut started, mut fell_back) = (0, 0, 0);
        // Proven only if every pass's step is.
        let mut certified = 1;
        let mut out = *pose;
        let mut previous_change = f64::INFINITY;
        let code = 'passes: {
            let mut corrections = match self.correction.at(&self.geometry, &out.to_pose()) {
                Ok(c) => c,
                Err(code) => break 'passes code,
            };
            for _ in 0..CORRECTION_PASSES {
                let struts: [f64; 6] = std::array::from_fn(|i| joints[i] - corrections[i]);
                if let Err(code) = check_legs(&struts) {
                    break 'passes code;
                }
                let code = self.forward_struts(&struts, &mut out, report);
                iterations += report.newton_iterations;
                started |= report.started;
                fell_back |= report.fell_back;
                certified &= report.certified;
                if code != status::OK {
                    break 'passes code;
                }
                let next = match self.correction.at(&self.geometry, &out.to_pose()) {
                    Ok(c) => c,
                    Err(code) => break 'passes code,
                };
                let change = (0..6).fold(0.0f64, |m, i| m.max((next[i] - corrections[i]).abs()));
                corrections = next;
                // A quarter of the tolerance: the struts then match the joints to about the
                // tracker's own accuracy.
                if change <= 0.25 * tolerance {
                    break 'passes status::OK;
                }
                // The passes contract by the correction's small share of a strut's change;
                // where they do not (near a singularity), there is no fixed point to trust.
                if change > 0.5 * previous_change {
                    break 'passes status::NOT_CONVERGED;
                }
                previous_change = change;
            }
            status::NOT_CONVERGED
        };
        report.newton_iterations = iterations;
        report.started = started;
        report.fell_back = fell_back;
        report.certified = if code == status::OK { certified } else { 0 };
        if code == status::OK {
            *pose = out;
        } else {
            self.tracking = saved;
        }
        code
    }

    /// Forward kinematics for the struts' geometric lengths (no correction).
    fn forward_struts(
        &mut self,
        legs: &[f64; 6],
        pose: &mut LinkagePose,
        report: &mut LinkageReport,
    ) -> i32 {
        report.started = 0;
        // A start this call made is kept only if the call succeeds: on a refusal the handle is
        // left as it was, not tracking (the tracker made for options every sample refuses, or
        // whose first sample missed the tolerance, was kept, and `is_tracking` said 1).
        let starting = self.tracking.is_none();
        if starting {
            let started = match &self.model {
                Model::Coplanar(s) => {
                    start_with(s, legs, pose, self.options, self.certify).map(Tracking::Coplanar)
                }
                Model::General(s) => {
                    start_with(s, legs, pose, self.options, self.certify).map(Tracking::General)
                }
            };
            match started {
                Ok(t) => self.tracking = Some(t),
                Err(code) => return code,
            }
        }
        let mut out = *pose;
        let code = match self.tracking.as_mut() {
            Some(Tracking::Coplanar(t)) => track(
                t,
                legs,
                &mut out,
                report,
                &self.geometry,
                self.options.tolerance,
            ),
            Some(Tracking::General(t)) => track(
                t,
                legs,
                &mut out,
                report,
                &self.geometry,
                self.options.tolerance,
            ),
            None => status::FAILED,
        };
        if code == status::OK {
            *pose = out;
            report.started = i32::from(starting);
        } else if starting {
            self.tracking = None;
        }
        code
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// genhexkins' default geometry (genhexkins.h, inches), platform joints coplanar.
    pub(crate) fn genhex() -> LinkageGeometry {
        LinkageGeometry {
            base: [
                [-22.950, 13.250, 0.0],
                [22.950, 13.250, 0.0],
                [22.950, 13.250, 0.0],
                [0.0, -26.500, 0.0],
                [0.0, -26.500, 0.0],
                [-22.950, 13.250, 0.0],
            ],
            platform: [
                [-1.000, 11.500, 0.0],
                [1.000, 11.500, 0.0],
                [10.459, -4.884, 0.0],
                [9.459, -6.616, 0.0],
                [-9.459, -6.616, 0.0],
                [-10.459, -4.884, 0.0],
            ],
        }
    }

    const HOME: LinkagePose = LinkagePose {
        x: 0.0,
        y: 0.0,
        z: 20.0,
        a: 0.0,
        b: 0.0,
        c: 0.0,
    };

    /// Strut lengths as genhexkins' inverse computes them: |t + R a_i − b_i|.
    fn struts(g: &LinkageGeometry, p: &LinkagePose) -> [f64; 6] {
        let pose = p.to_pose();
        std::array::from_fn(|i| {
            let w = pose.apply(g.platform[i]);
            let d = [0, 1, 2].map(|k| w[k] - g.base[i][k]);
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
        })
    }

    fn max_diff(a: &LinkagePose, b: &LinkagePose) -> f64 {
        [
            a.x - b.x,
            a.y - b.y,
            a.z - b.z,
            a.a - b.a,
            a.b - b.b,
            a.c - b.c,
        ]
        .iter()
        .fold(0.0, |m, d| m.max(d.abs()))
    }

    /// A pose path from home through the workspace, `t` from 0 to 1.
    fn along_path(t: f64) -> LinkagePose {
        LinkagePose {
            x: 2.0 * t,
            y: -t,
            z: 20.0 + 3.0 * t,
            a: 8.0 * t,
            b: -6.0 * t,
            c: 40.0 * t,
        }
    }

    /// Drives three legs longer and three shorter from `home` until a forward call is
    /// refused; checks every accepted pose against the inverse and the refused call left
    /// `pose` alone. The refusal's code, if any.
    fn drive_out_of_the_workspace(
        h: &mut Hexapod,
        home: &[f64; 6],
        pose: &mut LinkagePose,
    ) -> Option<i32> {
        let mut report = LinkageReport::default();
        for k in 1..=400 {
            let s = k as f64 * 0.05;
            let legs: [f64; 6] = std::array::from_fn(|i| home[i] + if i % 2 == 0 { s } else { -s });
            let before = *pose;
            let code = h.forward(&legs, pose, &mut report);
            if code != status::OK {
                assert_eq!(*pose, before, "pose untouched on refusal");
                return Some(code);
            }
            let back = h.inverse(pose).unwrap();
            for i in 0..6 {
                assert!(
                    (back[i] - legs[i]).abs() < 1e-7,
                    "step {k}: accepted a wrong pose"
                );
            }
        }
        None
    }

    #[test]
    fn inverse_is_genhexkins_strut_lengths() {
        let g = genhex();
        let h = Hexapod::new(&g).unwrap();
        let p = LinkagePose {
            x: 1.0,
            y: -0.5,
            z: 21.0,
            a: 3.0,
            b: -2.0,
            c: 10.0,
        };
        let legs = h.inverse(&p).unwrap();
        let want = struts(&g, &p);
        for i in 0..6 {
            assert!((legs[i] - want[i]).abs() < 1e-9, "{legs:?} {want:?}");
        }
        assert_eq!(
            h.inverse(&LinkagePose { x: f64::NAN, ..p }),
            Err(status::NON_FINITE)
        );
    }

    #[test]
    fn forward_tracks_a_path_and_inverts_the_inverse() {
        let g = genhex();
        let mut h = Hexapod::new(&g).unwrap();
        let mut report = LinkageReport::default();
        let mut pose = HOME;
        let legs = h.inverse(&HOME).unwrap();
        assert_eq!(h.forward(&legs, &mut pose, &mut report), status::OK);
        assert_eq!(report.started, 1);
        assert!(max_diff(&pose, &HOME) < 1e-9);
        for k in 1..=400 {
            let want = along_path(k as f64 / 400.0);
            let legs = h.inverse(&want).unwrap();
            assert_eq!(
                h.forward(&legs, &mut pose, &mut report),
                status::OK,
                "step {k}"
            );
            assert_eq!(report.started, 0);
            assert!(
                max_diff(&pose, &want) < 1e-7,
                "step {k}: {pose:?} vs {want:?}"
            );
            assert!(report.proximity > 0.0 && report.proximity.is_finite());
        }
    }

    #[test]
    fn a_start_pose_that_does_not_match_is_refused() {
        let mut h = Hexapod::new(&genhex()).unwrap();
        let legs = h.inverse(&HOME).unwrap();
        let mut far = LinkagePose { z: 26.0, ..HOME };
        let before = far;
        let mut report = LinkageReport::default();
        assert_eq!(
            h.forward(&legs, &mut far, &mut report),
            status::POSE_MISMATCH
        );
        assert_eq!(far, before, "pose untouched on refusal");
        assert!(!h.is_tracking());
    }

    #[test]
    fn bad_input_is_typed_and_leaves_the_tracker_alone() {
        let mut h = Hexapod::new(&genhex()).unwrap();
        let mut pose = HOME;
        let mut report = LinkageReport::default();
        let legs = h.inverse(&HOME).unwrap();
        assert_eq!(h.forward(&legs, &mut pose, &mut report), status::OK);
        let mut bad = legs;
        bad[3] = f64::NAN;
        assert_eq!(h.forward(&bad, &mut pose, &mut report), status::NON_FINITE);
        bad[3] = -1.0;
        assert_eq!(
            h.forward(&bad, &mut pose, &mut report),
            status::INVALID_INPUT
        );
        assert_eq!(report.status, status::INVALID_INPUT);
        assert!(h.is_tracking());
        assert_eq!(h.forward(&legs, &mut pose, &mut report), status::OK);
        assert!(max_diff(&pose, &HOME) < 1e-9);
    }

    #[test]
    fn geometry_and_options_are_checked() {
        let mut g = genhex();
        g.platform[2][0] = f64::INFINITY;
        assert_eq!(Hexapod::new(&g).err(), Some(status::INVALID_GEOMETRY));
        let mut h = Hexapod::new(&genhex()).unwrap();
        assert_eq!(h.set_options(0.0, 10), Err(status::INVALID_OPTIONS));
        assert_eq!(h.set_options(f64::NAN, 10), Err(status::INVALID_OPTIONS));
        assert_eq!(h.set_options(1e-9, 0), Err(status::INVALID_OPTIONS));
        assert_eq!(h.set_options(1e-9, 120), Ok(()));
        // A platform with joints out of plane takes the general model, and still inverts.
        let mut g = genhex();
        g.platform[1][2] = 0.7;
        let mut h = Hexapod::new(&g).unwrap();
        assert!(matches!(h.model, Model::General(_)));
        let p = LinkagePose {
            x: 0.3,
            z: 19.0,
            a: 2.0,
            ..HOME
        };
        let legs = h.inverse(&p).unwrap();
        let mut pose = p;
        let mut report = LinkageReport::default();
        assert_eq!(h.forward(&legs, &mut pose, &mut report), status::OK);
        assert!(max_diff(&pose, &p) < 1e-9);
    }

    /// Joint-space steps toward a fold: the tracker either follows the branch or refuses with
    /// a positive code, keeps its last good state, and carries on when the legs come back.
    #[test]
    fn past_a_fold_the_tracker_refuses_and_recovers() {
        let g = genhex();
        let mut h = Hexapod::new(&g).unwrap();
        let mut pose = HOME;
        let mut report = LinkageReport::default();
        let home = h.inverse(&HOME).unwrap();
        assert_eq!(h.forward(&home, &mut pose, &mut report), status::OK);
        // Shorten three legs and lengthen three until no assembly exists near the branch.
        let refused = drive_out_of_the_workspace(&mut h, &home, &mut pose);
        let code = refused.expect("the legs were driven out of the workspace");
        assert!(code > 0, "a refusal, not an input error: {code}");

        assert_eq!(h.forward(&home, &mut pose, &mut report), status::OK);
        assert!(max_diff(&pose, &HOME) < 1e-7, "{pose:?}");
    }

    /// genhexkins' default joint axes (genhexkins.h) with a screw lead of 0.2 in per turn.
    fn screws() -> LinkageStrutCorrection {
        let r = std::f64::consts::FRAC_1_SQRT_2; // genhexkins.h writes 0.707107
        LinkageStrutCorrection {
            base_n: [
                [r, 0.0, r],
                [0.0, -r, r],
                [-r, 0.0, r],
                [-r, 0.0, r],
                [0.0, r, r],
                [r, 0.0, r],
            ],
            platform_n: [
                [-1.0, 0.0, 0.0],
                [0.866025, 0.5, 0.0],
                [0.866025, 0.5, 0.0],
                [0.866025, -0.5, 0.0],
                [0.866025, -0.5, 0.0],
                [-1.0, 0.0, 0.0],
            ],
            screw_lead: 0.2,
        }
    }

    /// genhexkins' correction written out from its source's steps, with the rotation built
    /// from the angle words directly (R = Rz(C) Ry(B) Rx(A)), not through `Pose`.
    fn genhex_correction(
        g: &LinkageGeometry,
        c: &LinkageStrutCorrection,
        p: &LinkagePose,
    ) -> [f64; 6] {
        let (a, b, cc) = (p.a.to_radians(), p.b.to_radians(), p.c.to_radians());
        let (sa, ca, sb, cb, sc, c3) = (a.sin(), a.cos(), b.sin(), b.cos(), cc.sin(), cc.cos());
        let r = [
            [c3 * cb, c3 * sb * sa - sc * ca, c3 * sb * ca + sc * sa],
            [sc * cb, sc * sb * sa + c3 * ca, sc * sb * ca - c3 * sa],
            [-sb, cb * sa, cb * ca],
        ];
        let mul = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
        };
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let unit = |a: [f64; 3]| {
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            a.map(|v| v / n)
        };
        std::array::from_fn(|i| {
            let ra = mul(g.platform[i]);
            let strut = [0, 1, 2].map(|k| p_t(p)[k] + ra[k] - g.base[i][k]);
            let u = unit(strut);
            let nb3 = unit(cross(u, cross(c.base_n[i], u)));
            let na2 = unit(cross(mul(c.platform_n[i]), u));
            let dot = nb3[0] * na2[0] + nb3[1] * na2[1] + nb3[2] * na2[2];
            c.screw_lead * dot.asin() / (2.0 * std::f64::consts::PI)
        })
    }

    fn p_t(p: &LinkagePose) -> [f64; 3] {
        [p.x, p.y, p.z]
    }

    #[test]
    fn inverse_adds_genhexkins_strut_correction() {
        let g = genhex();
        let mut h = Hexapod::new(&g).unwrap();
        h.set_strut_correction(&screws()).unwrap();
        let mut largest = 0.0f64;
        for k in 0..50 {
            let t = k as f64 / 49.0;
            let p = LinkagePose {
                x: 2.0 * t - 1.0,
                y: 0.5 - t,
                z: 19.0 + 2.0 * t,
                a: 10.0 * t - 5.0,
                b: 4.0 - 8.0 * t,
                c: 60.0 * t - 30.0,
            };
            let legs = h.inverse(&p).unwrap();
            let (struts, corr) = (struts(&g, &p), genhex_correction(&g, &screws(), &p));
            for i in 0..6 {
                assert!(
                    (legs[i] - struts[i] - corr[i]).abs() < 1e-12,
                    "{k}: {legs:?}"
                );
                largest = largest.max(corr[i].abs());
            }
        }
        // The correction is there to be tested: a good share of a lead.
        assert!(largest > 0.01, "largest correction {largest}");
    }

    #[test]
    fn forward_solves_for_the_strut_correction() {
        let g = genhex();
        let mut h = Hexapod::new(&g).unwrap();
        h.set_strut_correction(&screws()).unwrap();
        let mut report = LinkageReport::default();
        let mut pose = HOME;
        assert_eq!(
            h.forward(&h.inverse(&HOME).unwrap(), &mut pose, &mut report),
            status::OK
        );
        assert!(max_diff(&pose, &HOME) < 1e-9, "{pose:?}");
        for k in 1..=300 {
            let want = along_path(k as f64 / 300.0);
            let joints = h.inverse(&want).unwrap();
            assert_eq!(
                h.forward(&joints, &mut pose, &mut report),
                status::OK,
                "step {k}"
            );
            assert!(
                max_diff(&pose, &want) < 1e-7,
                "step {k}: {pose:?} vs {want:?}"
            );
            // What the tracker returns gives the joints back through the corrected inverse.
            let back = h.inverse(&pose).unwrap();
            assert!(
                (0..6).all(|i| (back[i] - joints[i]).abs() < 1e-8),
                "step {k}"
            );
        }
        // Without the correction the same joints are another pose: the correction mattered.
        let joints = h.inverse(&pose).unwrap();
        let mut plain = Hexapod::new(&g).unwrap();
        let mut p = pose;
        assert_eq!(
            plain.forward(&plain.inverse(&pose).unwrap(), &mut p, &mut report),
            status::OK
        );
        assert_eq!(plain.forward(&joints, &mut p, &mut report), status::OK);
        assert!(max_diff(&p, &pose) > 1e-3, "{p:?} vs {pose:?}");
    }

    #[test]
    fn a_failed_corrected_call_leaves_the_tracker_where_it_was() {
        let g = genhex();
        let mut h = Hexapod::new(&g).unwrap();
        h.set_strut_correction(&screws()).unwrap();
        let mut report = LinkageReport::default();
        let mut pose = HOME;
        let home = h.inverse(&HOME).unwrap();
        assert_eq!(h.forward(&home, &mut pose, &mut report), status::OK);
        // Legs driven out of the workspace through a fold: refused, the pose and tracker
        // untouched, and the next call from home still works.
        assert!(drive_out_of_the_workspace(&mut h, &home, &mut pose).is_some());
        assert!(h.is_tracking());
        assert_eq!(h.forward(&home, &mut pose, &mut report), status::OK);
        assert!(max_diff(&pose, &HOME) < 1e-9);
        // Bad axes are refused and leave the old correction in place.
        let mut bad = screws();
        bad.base_n[2] = [0.0; 3];
        assert_eq!(h.set_strut_correction(&bad), Err(status::INVALID_GEOMETRY));
        bad.base_n[2] = [f64::NAN, 0.0, 1.0];
        assert_eq!(h.set_strut_correction(&bad), Err(status::NON_FINITE));
        assert_eq!(h.inverse(&HOME).unwrap(), home);
    }

    /// The pose words reported are the solved angles moved by whole turns to lie nearest the
    /// caller's: with the caller's C at 1e10 or 1e20 degrees no double there held the angle
    /// solved, and forward said OK with words whose legs were 1.4e-7 and 8.8 units off the
    /// legs given (the tolerance is 1e-9). Angle words beyond 2¹⁶ rad are now INVALID_INPUT,
    /// and every OK pose gives back its legs to the tolerance, or the call is refused with
    /// the tracker left alone.
    #[test]
    fn far_angle_words_are_refused_and_every_ok_pose_gives_back_its_legs() {
        for c in [1e6, 3.7e6, 3.8e6, 1e10, 1e15, 1e20, 1e300] {
            for tolerance in [1e-9, 1e-11] {
                let mut h = Hexapod::new(&genhex()).unwrap();
                h.set_options(tolerance, 20).unwrap();
                let start = LinkagePose { c, ..HOME };
                let legs = h.inverse(&start).unwrap();
                let mut pose = start;
                let mut report = LinkageReport::default();
                let code = h.forward(&legs, &mut pose, &mut report);
                if c.abs() > MAX_ANGLE_WORD {
                    assert_eq!(code, status::INVALID_INPUT, "C = {c:e}");
                    assert_eq!(pose, start, "C = {c:e}: the pose untouched on refusal");
                    assert!(!h.is_tracking(), "C = {c:e}");
                    continue;
                }
                // The rotation's own angle, moved 3° on: the words must follow it.
                let own = (c.to_radians() % core::f64::consts::TAU).to_degrees();
                let moved = LinkagePose {
                    x: 0.5,
                    z: 20.5,
                    c: own + 3.0,
                    ..HOME
                };
                let legs = h.inverse(&moved).unwrap();
                for _ in 0..2 {
                    let before = pose;
                    let code = h.forward(&legs, &mut pose, &mut report);
                    if code == status::OK {
                        let back = h.inverse(&pose).unwrap();
                        let off = (0..6).fold(0.0f64, |m, i| m.max((back[i] - legs[i]).abs()));
                        assert!(
                            off <= tolerance,
                            "C = {c:e}, tolerance {tolerance:e}: OK {off:e} off"
                        );
                    } else {
                        assert_eq!(code, status::TOLERANCE_NOT_MET, "C = {c:e}");
                        assert_eq!(pose, before, "C = {c:e}: the pose untouched on refusal");
                    }
                }
            }
        }
    }

    /// A call that starts tracking and is then refused leaves the handle not tracking: with a
    /// tolerance every sample refuses (above 1e-3 of the mechanism's size, refused only
    /// when checked against the start), the first call said INVALID_OPTIONS and left a
    /// tracker behind, `is_tracking` 1 and `report.started` 1.
    #[test]
    fn a_refused_first_call_starts_no_tracking() {
        let mut h = Hexapod::new(&genhex()).unwrap();
        h.set_options(1e3, 20).unwrap();
        let legs = h.inverse(&HOME).unwrap();
        let mut pose = HOME;
        let mut report = LinkageReport::default();
        assert_eq!(
            h.forward(&legs, &mut pose, &mut report),
            status::INVALID_OPTIONS
        );
        assert!(!h.is_tracking());
        assert_eq!(report.started, 0);
        h.set_options(1e-9, 20).unwrap();
        assert_eq!(h.forward(&legs, &mut pose, &mut report), status::OK);
        assert_eq!(report.started, 1);
        assert!(h.is_tracking());
    }

    #[test]
    fn certified_tracking_proves_every_step_or_refuses() {
        let g = genhex();
        for correction in [LinkageStrutCorrection::NONE, screws()] {
            let mut h = Hexapod::new(&g).unwrap();
            h.set_strut_correction(&correction).unwrap();
            h.set_certify(true);
            let mut report = LinkageReport::default();
            let mut pose = HOME;
            assert_eq!(
                h.forward(&h.inverse(&HOME).unwrap(), &mut pose, &mut report),
                status::OK
            );
            for k in 1..=100 {
                let want = along_path(k as f64 / 100.0);
                let joints = h.inverse(&want).unwrap();
                assert_eq!(
                    h.forward(&joints, &mut pose, &mut report),
                    status::OK,
                    "step {k}"
                );
                assert_eq!(
                    report.certified, 1,
                    "step {k}: an accepted step is a proven one"
                );
                assert!(max_diff(&pose, &want) < 1e-7, "step {k}");
            }
            // Off again: tracking restarts and samples are no longer certified.
            h.set_certify(false);
            assert!(!h.is_tracking());
            let mut report = LinkageReport::default();
            let back = along_path(1.0);
            assert_eq!(
                h.forward(&h.inverse(&back).unwrap(), &mut pose, &mut report),
                status::OK
            );
            assert_eq!(report.certified, 0);
        }
        assert_eq!(status::name(status::UNPROVEN).to_str().unwrap(), "unproven");
    }
}
