//! The tracker and PH (`arc_length`) on the five-bar, the planar 3-RPR, the spherical wrist,
//! the 3-PRS, the linear delta, the pan-tilt head, the SCARA, the 6-RSS hexapod and the 3-RPS
//! (the first hunt's curves, checked here since) over random smooth input curves from home, some
//! running into and past direct singularities and out of reach. Every answer labelled ok is
//! held to ground truth computed here, apart from the solvers:
//!
//! - it satisfies F(v, x) = 0: the Newton correction measured again with a dense LU of the
//!   tests' own (not the generated factorisation) is within ten tolerances, and the inverse
//!   kinematics of the pose gives the inputs back;
//! - it is on the start's branch: along the curve, a continuation 16 to 64 times finer than
//!   the samples (Newton at each step) watching det B: while its sign has not changed it is the
//!   start's branch, and an accepted sample must be it or else what fine continuation along
//!   the straight joint segment from the last accepted sample reaches without a sign change
//!   (the only connection the tracker can claim, seeing the samples alone; 1 000 steps, and
//!   10 000 where those do not confirm the answer: the oracle's own Newton can jump). The
//!   second is counted apart (`chord_not_curve`): the curve and its chord between two samples
//!   reaching different assembly modes without a singularity (a degenerate 6-RSS at 25 Hz,
//!   99 mm apart, with `LINKAGE_STRESS_SEED=31337`). Once the curve has met a singularity only
//!   the segment's end is a right answer. PH's answer for a point of the curve is held to the straight segment
//!   from the start, in 2 000 steps (20 000 likewise): ok where that segment meets a sign
//!   change of det B is a defect.
//!
//! Two more (`pus_keeps_its_branch`, `rus_hexapod_keeps_its_branch`) whose rods end in a
//! passive U at one end and an S at the other, which the model reduces to their lengths (no
//! second-axis point: `only_a_rod_to_a_ball` in the generator): the 6-PUS of `literature` and
//! a 6-RUS declared here.
//!
//! The five-bar and the planar 3-RPR have closed forms, checked in their own files; here they
//! get the same treatment as the rest, whose branch is defined by continuation only.

use super::five_bar::FiveBar;
use super::linear_delta::LinearDelta;
use super::literature::Pus;
use super::pan_tilt::PanTilt;
use super::planar_rpr::PlanarRpr;
use super::prs::Prs;
use super::scara::{Scara, ScaraWrist};
use super::spherical_wrist::Wrist;
use super::GENERAL_MODEL;
use linkage::reference::{straight_segment, straight_segment_from};
use linkage::{arc_length, det_b, Mechanism, Options, Start, Tracker};
use linkage_examples::rps::{self, Rps3};
use linkage_examples::rss_hexapod::RssHexapod;
use linkage_tests::{max_diff, Rng};
use std::f64::consts::TAU;

/// Inputs from home: per input a sine and a 1 − cos term, sampled at `rate` over one second.
pub(super) struct Curve<const M: usize> {
    home: [f64; M],
    amp: [[f64; M]; 2],
    phase: [f64; M],
    freq: [f64; 2],
    pub(super) rate: f64,
}

impl<const M: usize> Curve<M> {
    /// `reach[j]`: the largest excursion of input j (a random share of it is used).
    pub(super) fn random(rng: &mut Rng, home: [f64; M], reach: [f64; M]) -> Self {
        let share = rng.uniform(0.05, 1.0);
        Curve {
            home,
            amp: [0, 1].map(|_| std::array::from_fn(|j| share * reach[j] * rng.symmetric() / 2.0)),
            phase: std::array::from_fn(|_| rng.uniform(0.0, TAU)),
            freq: [rng.uniform(0.2, 3.0), rng.uniform(0.2, 3.0)],
            rate: [25.0, 100.0, 1000.0][(rng.next_u64() % 3) as usize],
        }
    }

    fn at(&self, t: f64) -> [f64; M] {
        std::array::from_fn(|i| {
            let p = self.phase[i];
            self.home[i]
                + self.amp[0][i] * ((TAU * self.freq[0] * t + p).sin() - p.sin())
                + self.amp[1][i] * (1.0 - (TAU * self.freq[1] * t).cos())
        })
    }
}

/// The Newton correction at (v, x) with the tests' own dense LU; infinite where B is singular.
fn correction<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> [f64; N] {
    let mut f = [0.0; N];
    sys.residual(v, x, &mut f);
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    match linkage_tests::dense::Lu::new(b) {
        Some(lu) => {
            lu.solve(&mut f);
            f
        }
        None => [f64::INFINITY; N],
    }
}

/// Newton from `v` at `x` until the correction is at rounding; `None` if it does not settle.
pub(super) fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    mut v: [f64; N],
    x: &[f64; M],
) -> Option<[f64; N]> {
    let mut last = f64::INFINITY;
    for _ in 0..30 {
        let d = correction(sys, &v, x);
        let step = d.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        if !step.is_finite() {
            return None;
        }
        for i in 0..N {
            v[i] -= d[i];
        }
        let size = v.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        // The general model's rows leave a rounding floor near 1e-12 of the size: stop there,
        // or once the corrections stop shrinking below 1e-10 of it.
        if step <= 1e-13 * size || (step <= 1e-10 * size && step >= 0.5 * last) {
            return Some(v);
        }
        last = step;
    }
    None
}

#[derive(Default, Debug)]
pub(super) struct Tally {
    curves: usize,
    samples: usize,
    accepted: usize,
    /// Accepted while the curve's reference was intact, and matched it.
    on_curve: usize,
    /// Accepted after the curve met a singularity, matched by the straight joint segment.
    on_segment: usize,
    /// Accepted while the curve's branch was intact, not on it but on the straight joint
    /// segment from the last accepted sample, which meets no singularity either: the curve and
    /// its chord between two samples reach different assembly modes (a path dependence, as
    /// the stress suite's tracker cases allow; the tracker only sees the samples).
    chord_not_curve: usize,
    refused: usize,
    /// Refused while the curve's reference stayed above 5 % of the start's |det B| since the
    /// last accepted sample.
    refused_clear: usize,
    curves_through_singularities: usize,
    ph_targets: usize,
    ph_ok: usize,
    ph_refused: usize,
    /// PH refused a target whose straight segment keeps |det B| above 1 % of the start's.
    ph_refused_clear: usize,
    /// Ok answers whose pose the inverse kinematics refused (`Unreachable` for a pose the
    /// forward solve placed: a defect of the numerical inverse, not of the answer, whose
    /// F = 0 and det B sign are checked apart). None allowed on declared and calibrated
    /// geometry; counted on degenerate geometry (`geometry_hunt::degenerate`).
    pub(super) inverse_refused: usize,
}

impl Tally {
    /// No sample refused on a stretch clear of singularities, no PH target on a clear segment.
    pub(super) fn clean(&self) -> bool {
        self.refused_clear == 0 && self.ph_refused_clear == 0
    }

    /// [`Tally::clean`], and the inverse kinematics answered every ok pose.
    pub(super) fn clean_with_inverse(&self) -> bool {
        self.clean() && self.inverse_refused == 0
    }

    /// Answers labelled ok (all of them checked).
    pub(super) fn ok(&self) -> usize {
        self.accepted + self.ph_ok
    }
}

/// The checks every ok answer must pass at (v, x): the Newton correction within the tolerance
/// (and 2 %), measured by an independent LU with F in double-double arithmetic (an `f64`
/// residual's rounding alone shifts the root it sees by more than the tolerance near
/// singularities of these models: 1.6e-7 mm at a calibrated planar 3-RPR's sample, against
/// 1e-8), det B of the start's sign, and inverse kinematics giving x back where it answers.
/// Returns false where the inverse kinematics refuses the pose (counted by the caller:
/// [`Tally::inverse_refused`]).
fn holds<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    det0: f64,
    tol: f64,
    at: &str,
) -> bool {
    assert!(v.iter().all(|c| c.is_finite()), "{at}: ok with {v:?}");
    let step = linkage_tests::exact_root::exact_correction(sys, v, x).unwrap_or(f64::INFINITY);
    assert!(
        step <= 1.02 * tol,
        "{at}: ok, but the Newton correction there is {step:e} (tolerance {tol:e})"
    );
    assert!(
        det_b(sys, v, x) * det0 > 0.0,
        "{at}: ok with det B of the other sign"
    );
    let back = match sys.inverse(v, x) {
        Ok(back) => back,
        Err(e) => {
            eprintln!("{at}: the inverse kinematics refuses the answer {v:?}: {e:?}");
            return false;
        }
    };
    let scale = x.iter().fold(1.0f64, |m, c| m.max(c.abs()));
    // Next to an inverse singularity an input barely moves the pivots (a crank whose rod is
    // nearly tangent to its circle), so the pivots fix it loosely: there the inverse may give
    // inputs further from x at which v is as much a solution (found with
    // `LINKAGE_STRESS_SEED=20261204` on a 6-RSS with a crank's pivot at z = 0: crank 6 back
    // 1.5e-6 rad off, ∂F/∂x₆ about 0.2 mm²/rad, v's Newton correction 4.6e-9 mm there against
    // 8.4e-9 at x). An inverse that picks another branch of a chain is further still.
    let near = max_diff(&back, x) <= 1e-6 * scale
        || (max_diff(&back, x) <= 1e-3 * scale
            && linkage_tests::exact_root::exact_correction(sys, v, &back)
                .is_some_and(|c| c <= 1.02 * tol));
    assert!(
        near,
        "{at}: inverse kinematics of the answer gives {back:?}, not {x:?}"
    );
    true
}

pub(super) fn hunt<S, const N: usize, const M: usize>(
    sys: &S,
    start: Start<N, M>,
    options: Options,
    curve: &Curve<M>,
    tally: &mut Tally,
    at: &str,
) where
    S: Mechanism<N, M> + Clone,
{
    let det0 = start.det();
    let tol = options.tolerance;
    let mut tracker = Tracker::new(sys.clone(), start, options);
    tally.curves += 1;
    let mut reference = Some(*start.v());
    let mut low = f64::INFINITY;
    let sub = match curve.rate as usize {
        25 => 64,
        100 => 32,
        _ => 16,
    };
    let samples = curve.rate as usize;
    for k in 1..=samples {
        let t = k as f64 / curve.rate;
        let x = curve.at(t);
        if let Some(mut v) = reference {
            let mut intact = true;
            for s in 1..=sub {
                let ts = (k - 1) as f64 / curve.rate + s as f64 / (sub as f64 * curve.rate);
                let xs = curve.at(ts);
                match newton(sys, v, &xs) {
                    Some(next) => {
                        let ratio = det_b(sys, &next, &xs) / det0;
                        low = low.min(ratio);
                        v = next;
                        intact &= ratio > 0.0;
                    }
                    None => intact = false,
                }
                if !intact {
                    break;
                }
            }
            reference = intact.then_some(v);
            if !intact {
                tally.curves_through_singularities += 1;
            }
        }
        tally.samples += 1;
        let at = format!("{at}, sample {k} (t = {t}), x = {x:?}");
        let (v_a, x_a) = (*tracker.state().0, *tracker.state().1);
        match tracker.update(&x) {
            Ok(sample) => {
                tally.accepted += 1;
                low = f64::INFINITY;
                if !holds(sys, &sample.v, &x, det0, tol, &at) {
                    tally.inverse_refused += 1;
                }
                let near = |truth: &[f64; N]| {
                    max_diff(&sample.v, truth) <= 10.0 * tol / sample.proximity.min(1.0) + 1e-9
                };
                if reference.as_ref().is_some_and(near) {
                    tally.on_curve += 1;
                    continue;
                }
                let (seg, flips) =
                    segment_truth(sys, (&v_a, &x_a), det0, &x, 1000, |seg, flips| {
                        flips == 0 && near(seg)
                    });
                let off_curve = reference.as_ref().map(|r| max_diff(&sample.v, r));
                assert!(
                    flips == 0 && near(&seg),
                    "{at}: accepted {:?}, {} and the joint segment from the last accepted sample {} ({:e} from its end)",
                    sample.v,
                    match off_curve {
                        Some(d) => format!("{d:e} from the curve's own branch (proximity {:e}),", sample.proximity),
                        None => "after the curve met a singularity,".to_string(),
                    },
                    if flips == 0 { "does not reach it" } else { "meets a singularity" },
                    max_diff(&sample.v, &seg)
                );
                if let Some(d) = off_curve {
                    // The curve and the chord reach different assembly modes between two
                    // samples, neither meeting a singularity: the tracker answered what it was
                    // given (the chord), as its documentation says.
                    tally.chord_not_curve += 1;
                    eprintln!("{at}: accepted the joint segment's end, {d:e} from the curve's own branch: the curve and the chord between two samples reach different assembly modes");
                } else {
                    tally.on_segment += 1;
                }
            }
            Err(_) => {
                tally.refused += 1;
                assert_eq!((*tracker.state().0, *tracker.state().1), (v_a, x_a), "{at}");
                if reference.is_some() && low > 0.05 {
                    tally.refused_clear += 1;
                    eprintln!("{at}: refused on a stretch of the curve clear of singularities (det B ≥ {low:e} of the start's)");
                }
            }
        }
    }
    // PH from the start to four points of the curve, against the straight segment to each.
    for q in 1..=4 {
        let x = curve.at(q as f64 / 4.0);
        let at = format!("{at}, PH to t = {}, x = {x:?}", q as f64 / 4.0);
        tally.ph_targets += 1;
        let Ok(sol) = arc_length(sys, &start, &x, &options) else {
            tally.ph_refused += 1;
            continue;
        };
        if !sol.is_ok() {
            tally.ph_refused += 1;
            // Whether the segment stays clear: the smallest |det B| ratio along it.
            let (_, flips) = straight_segment(sys, &start, &x, 2000);
            if flips == 0 && clear_segment(sys, &start, &x, 0.01) {
                tally.ph_refused_clear += 1;
                eprintln!(
                    "{at}: PH {} on a segment clear of singularities",
                    sol.status.word()
                );
            }
            continue;
        }
        tally.ph_ok += 1;
        if !holds(sys, &sol.v, &x, det0, tol, &at) {
            tally.inverse_refused += 1;
        }
        let allowed = 10.0 * tol / sol.min_det_ratio.min(1.0) + 1e-9;
        let from = (start.v(), start.x());
        let (truth, flips) = segment_truth(sys, from, start.det(), &x, 2000, |truth, flips| {
            flips == 0 && max_diff(&sol.v, truth) <= allowed
        });
        assert!(
            flips == 0,
            "{at}: PH Converged to {:?}, but the straight segment meets {flips} sign changes of det B",
            sol.v
        );
        let off = max_diff(&sol.v, &truth);
        assert!(
            off <= allowed,
            "{at}: PH Converged {off:e} from the straight segment's end {truth:?}: {:?}",
            sol.v
        );
    }
}

/// The straight joint segment from `from` (det B of `det0`'s sign) to `x` in `steps`
/// ([`straight_segment_from`]), and where that run does not `confirm` an answer (given the
/// segment's end and its sign changes of det B), again in ten, a hundred and a thousand times
/// as many, until one does: the oracle's own Newton can jump where the segment turns fast. On
/// the spherical wrist (case 46 with `LINKAGE_STRESS_SEED=31337`, a sample the tracker reached
/// by continuation) it counted 2 sign changes in 10 and in 100 steps and 86 in 1 000, none in
/// 10 000, every run ending where the tracker did; in 400 pieces of 100 steps |det B| stays
/// above 2.5 % of the start's, where the wrist moves 18 mm in one piece. On a calibrated
/// planar 3-RPR (case 11 of `geometry_hunt::planar_rpr_calibrated` with
/// `LINKAGE_STRESS_SEED=20261130`, sample 47) the segment passes within 1.4e-3 of the start's
/// |det B| near a hundredth of the way: 6 sign changes in 1 000 and 10 000 steps, 8 in
/// 100 000, none in 1 000 000, whose end is 7.7e-9 from the tracker's answer (and PH along the
/// segment has det B of the start's sign at every point asked for).
fn segment_truth<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    from: (&[f64; N], &[f64; M]),
    det0: f64,
    x: &[f64; M],
    steps: usize,
    confirm: impl Fn(&[f64; N], usize) -> bool,
) -> ([f64; N], usize) {
    let mut n = steps;
    loop {
        let (end, flips) = straight_segment_from(sys, from, det0, x, n);
        if confirm(&end, flips) || n >= 1000 * steps {
            return (end, flips);
        }
        n *= 10;
    }
}

/// Whether |det B| stays above `share` of the start's along the straight segment to `x`.
fn clear_segment<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
    share: f64,
) -> bool {
    let mut v = *start.v();
    let x0 = *start.x();
    for k in 1..=400 {
        let l = k as f64 / 400.0;
        let xs: [f64; M] = std::array::from_fn(|j| x0[j] + l * (x[j] - x0[j]));
        match newton(sys, v, &xs) {
            Some(next) if det_b(sys, &next, &xs) / start.det() > share => v = next,
            _ => return false,
        }
    }
    true
}

/// Runs `cases` random curves on `sys` from its home, each input up to `reach` from home.
fn run<S, const N: usize, const M: usize>(
    name: &str,
    sys: S,
    start: Start<N, M>,
    options: Options,
    reach: [f64; M],
    seed: u64,
    cases: usize,
) where
    S: Mechanism<N, M> + Clone,
{
    let mut rng = Rng::new(linkage_tests::sweep_seed(seed));
    let mut tally = Tally::default();
    for case in 0..cases {
        let curve = Curve::random(&mut rng, *start.x(), reach);
        let at = format!("{name}, case {case}");
        // `LINKAGE_CASE=k` replays case k alone (with the `LINKAGE_STRESS_SEED` it ran with).
        if std::env::var("LINKAGE_CASE").is_ok_and(|k| k != case.to_string()) {
            continue;
        }
        hunt(&sys, start, options, &curve, &mut tally, &at);
    }
    eprintln!("{name}: {tally:?}");
    assert!(tally.on_curve > 0 || tally.curves == 1, "{name}: {tally:?}");
    assert_eq!(tally.refused_clear, 0, "{name}: {tally:?}");
    assert_eq!(tally.ph_refused_clear, 0, "{name}: {tally:?}");
    assert_eq!(tally.inverse_refused, 0, "{name}: {tally:?}");
}

#[test]
fn five_bar_keeps_its_branch() {
    let sys = FiveBar::new();
    let start = sys.home_start().unwrap();
    run(
        "five-bar",
        sys,
        start,
        Options::TIGHT,
        [2.5; 2],
        0x5BA2,
        linkage_tests::sweep(6, 60),
    );
}

#[test]
fn planar_rpr_keeps_its_branch() {
    let sys = PlanarRpr::new();
    let start = sys.home_start().unwrap();
    run(
        "planar 3-RPR",
        sys,
        start,
        GENERAL_MODEL,
        [160.0; 3],
        0x3B9B,
        linkage_tests::sweep(6, 60),
    );
}

#[test]
fn spherical_wrist_keeps_its_branch() {
    let sys = Wrist::new();
    let start = sys.home_start().unwrap();
    run(
        "wrist",
        sys,
        start,
        GENERAL_MODEL,
        [2.5; 3],
        0x5A15,
        linkage_tests::sweep(6, 60),
    );
}

#[test]
fn prs_keeps_its_branch() {
    let sys = Prs::new();
    let start = sys.home_start().unwrap();
    run(
        "3-PRS",
        sys,
        start,
        GENERAL_MODEL,
        [200.0; 3],
        0x3A25,
        linkage_tests::sweep(6, 60),
    );
}

#[test]
fn linear_delta_keeps_its_branch() {
    let sys = LinearDelta::new();
    let start = sys.home_start().unwrap();
    run(
        "linear delta",
        sys,
        start,
        GENERAL_MODEL,
        [400.0; 3],
        0x1DE1,
        linkage_tests::sweep(3, 40),
    );
}

#[test]
fn pan_tilt_keeps_its_branch() {
    let sys = PanTilt::new();
    let start = sys.home_start().unwrap();
    run(
        "pan-tilt",
        sys,
        start,
        GENERAL_MODEL,
        [6.0; 2],
        0x9A27,
        linkage_tests::sweep(6, 60),
    );
}

#[test]
fn scara_keeps_its_branch() {
    let sys = Scara::new();
    let start = sys.home_start().unwrap();
    run(
        "SCARA",
        sys,
        start,
        GENERAL_MODEL,
        [6.0, 6.0, 300.0, 6.0],
        0x5CA7,
        linkage_tests::sweep(4, 50),
    );
    let sys = ScaraWrist::new();
    let start = sys.home_start().unwrap();
    run(
        "SCARA wrist",
        sys,
        start,
        GENERAL_MODEL,
        [6.0, 6.0, 300.0, 6.0, 6.0],
        0x5CA8,
        linkage_tests::sweep(3, 30),
    );
}

/// The 3-RPS (16 assembly modes in the complex): legs up to 90 mm from home on legs of
/// 158 mm, into its singular configurations and out of reach (the first round's curves).
#[test]
fn rps_keeps_its_branch() {
    let sys = Rps3::new();
    let start = rps::home_start(&sys).unwrap();
    run(
        "3-RPS",
        sys,
        start,
        Options::TIGHT,
        [90.0; 3],
        0x3295,
        linkage_tests::sweep(4, 150),
    );
}

#[test]
fn rss_hexapod_keeps_its_branch() {
    let sys = RssHexapod::new();
    let start = sys.home_start().unwrap();
    run(
        "6-RSS",
        sys,
        start,
        GENERAL_MODEL,
        [3.0; 6],
        0x6255,
        linkage_tests::sweep(3, 30),
    );
}

/// The 6-PUS on parallel rails (`literature::Pus`), each rod a U on its slider and a ball on the
/// platform, which the model holds by its length alone: slides up to 60 mm from home (about a
/// third of the curves meet a direct singularity).
#[test]
fn pus_keeps_its_branch() {
    let sys = Pus::new();
    let start = sys.home_start().unwrap();
    run(
        "6-PUS",
        sys,
        start,
        GENERAL_MODEL,
        [60.0; 6],
        0x6905,
        linkage_tests::sweep(6, 60),
    );
}

linkage::mechanism! {
    /// A 6-RUS rotary hexapod: the 6-RSS's motors, cranks and platform (`RssHexapod`), each
    /// rod on a passive U at its crank (first axis along the motor's) and a ball on the
    /// platform; the rods' lengths are what home gives them (inputs zero at home).
    pub struct Rus;
    base {
        A1 = [93.969, -34.202, 0.0],   B1 = [87.129, -52.996, 0.0],
        A2 = [93.969, 34.202, 0.0],    B2 = [87.129, 52.996, 0.0],
        A3 = [-17.365, 98.481, 0.0],   B3 = [2.331, 101.954, 0.0],
        A4 = [-76.604, 64.279, 0.0],   B4 = [-89.46, 48.958, 0.0],
        A5 = [-76.604, -64.279, 0.0],  B5 = [-89.46, -48.958, 0.0],
        A6 = [-17.365, -98.481, 0.0],  B6 = [2.331, -101.954, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
        G1 = [49.497, -49.497, 0.0],
        G2 = [49.497, 49.497, 0.0],
        G3 = [18.117, 67.615, 0.0],
        G4 = [-67.615, 18.117, 0.0],
        G5 = [-67.615, -18.117, 0.0],
        G6 = [18.117, -67.615, 0.0],
    }
    link crank1 { C1 = [131.557, -47.883, 0.0], D1 = [124.717, -66.677, 0.0] }
    link crank2 { C2 = [131.557, 47.883, 0.0], D2 = [124.717, 66.677, 0.0] }
    link crank3 { C3 = [-24.311, 137.873, 0.0], D3 = [-4.615, 141.346, 0.0] }
    link crank4 { C4 = [-107.246, 89.99, 0.0], D4 = [-120.102, 74.669, 0.0] }
    link crank5 { C5 = [-107.246, -89.99, 0.0], D5 = [-120.102, -74.669, 0.0] }
    link crank6 { C6 = [-24.311, -137.873, 0.0], D6 = [-4.615, -141.346, 0.0] }
    chain arm1 = base - R(active q1, axis = A1 -> B1) - crank1 - U(C1, axis = C1 -> D1) - S(G1) - platform;
    chain arm2 = base - R(active q2, axis = A2 -> B2) - crank2 - U(C2, axis = C2 -> D2) - S(G2) - platform;
    chain arm3 = base - R(active q3, axis = A3 -> B3) - crank3 - U(C3, axis = C3 -> D3) - S(G3) - platform;
    chain arm4 = base - R(active q4, axis = A4 -> B4) - crank4 - U(C4, axis = C4 -> D4) - S(G4) - platform;
    chain arm5 = base - R(active q5, axis = A5 -> B5) - crank5 - U(C5, axis = C5 -> D5) - S(G5) - platform;
    chain arm6 = base - R(active q6, axis = A6 -> B6) - crank6 - U(C6, axis = C6 -> D6) - S(G6) - platform;
}

/// The 6-RUS: its U–S rods reduced to their lengths (18 unknowns, the platform's six balls, as
/// the 6-RSS), home's inputs zero; cranks up to 1.2 rad from home (a few curves meet a direct
/// singularity at `LINKAGE_STRESS=8`).
#[test]
fn rus_hexapod_keeps_its_branch() {
    assert_eq!(Rus::UNKNOWNS.len(), 18, "{:?}", Rus::UNKNOWNS);
    let sys = Rus::new();
    assert!(
        max_diff(&Rus::HOME_INPUTS, &[0.0; 6]) < 1e-9,
        "{:?}",
        Rus::HOME_INPUTS
    );
    let start = sys.home_start().unwrap();
    linkage_tests::check_jacobians(&sys, start.v(), start.x());
    super::check_inverse(&sys, start.v(), start.x(), &Rus::HOME_INPUTS, 1e-9);
    run(
        "6-RUS",
        sys,
        start,
        GENERAL_MODEL,
        [1.2; 6],
        0x6905 ^ 0x52,
        linkage_tests::sweep(6, 60),
    );
}
