//! Trajectory mode: successive joint vectors (e.g. 1 kHz samples), each solved from the last
//! solution, never leaving the start's branch.

use crate::arc_length::from_accepted;
use crate::certified_steps::StepProof;
use crate::convergence::Contraction;
use crate::correction::{Correction, det_b};
use crate::math::size;
use crate::mechanism::Mechanism;
use crate::solution::{Options, SolveError, Status};
use crate::start::Start;
use crate::turns::Turns;

/// Corrections the fast path may take before it gives the sample to continuation.
const MAX_CORRECTIONS: u32 = 8;
/// A chord correction (B kept from the last sample) is taken while the corrections shrink at
/// least this fast; slower, B is factored afresh.
///
/// The chords also make the fast path stricter than Newton from the predicted point: the first
/// corrections use B at the last accepted sample, so they pass the contraction test only when
/// the step is short against the curvature of the branch there (the chord's rate grows like
/// ω h). At coarse sampling Newton from the predicted point alone would contract to roots that
/// the straight joint segment from the last sample does not reach without crossing det B = 0
/// (seen at 5 Hz); such steps go to continuation, which shows the connection or refuses.
const CHORD_RATIO: f64 = 0.1;
/// The bend of the last step is carried into the next prediction only while it is at most this
/// share of the predictor step: at fine sampling (up to about 5e-4 at 1 kHz on the case
/// study's trajectory), where the branch's curvature changes little from one sample to the
/// next. At coarse sampling and near folds the prediction stays the linear one: with 1e-2
/// the stress suite's random trajectories (10 Hz to 1 kHz) had 176 more samples refused (all
/// legitimately, the joint segment from the last accepted sample meeting a singularity) than
/// with the linear prediction alone; with 1e-3 no more than it.
const BEND_SHARE: f64 = 0.001;
/// A Newton correction that fails the contraction test is still followed while it is within
/// this many tolerances (and at the rounding floor): see [`at_rounding_floor`].
const FLOOR_BAND: f64 = 10.0;

/// One tracked sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<const N: usize> {
    /// The pivot coordinates at the sample, on the start's branch.
    pub v: [f64; N],
    /// |det B| / |det B at the start|: how far from a direct singularity (0 at one).
    pub proximity: f64,
    /// Newton iterations spent on this sample.
    pub newton_iterations: u32,
    /// Whether the fast path failed and continuation had to take over.
    pub fell_back: bool,
    /// With [`Tracker::certified`]: the proof that this step kept the branch (always
    /// [`StepProof::Proven`](crate::certified_steps::StepProof::Proven): an unproven step is refused).
    pub proof: Option<crate::certified_steps::StepProof>,
}

/// Why a sample was refused. The tracker keeps its last good state and stays usable.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TrackError {
    /// The sample itself is invalid.
    Input(SolveError),
    /// The sample cannot be reached on the branch from the last one.
    Lost(Status),
    /// With [`Tracker::certified`]: the sample was solved, but the step to it could not be
    /// proven to keep the branch ([`StepProof::Unproven`](crate::certified_steps::StepProof::Unproven) says
    /// after how many pieces and why). Not a statement that the branch changed.
    Unproven {
        /// How many pieces had been certified before the one that failed.
        pieces: u32,
        /// Why that piece failed.
        reason: crate::certify::CertifyError,
    },
}

impl core::fmt::Display for TrackError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TrackError::Input(e) => write!(f, "{e}"),
            TrackError::Lost(s) => write!(f, "{s}"),
            TrackError::Unproven { pieces, reason } => write!(
                f,
                "the step was not proven to keep the branch ({reason}, after {pieces} pieces)"
            ),
        }
    }
}

/// What the last fast step left beyond the linear prediction: `v` moved by `dv` more than
/// `B Δv = −(∂F/∂x) Δx` predicted, for the input step `dx`. Along a smooth branch that is
/// ½ v''(dx, dx) to leading order, so a next input step s·dx (plus a part across it) bends by
/// about s² dv: adding it to the next prediction takes the predictor's error from O(h²) to
/// O(h³) at fine sampling, and one chord correction less is needed.
#[derive(Clone, Copy, Debug)]
struct Bend<const N: usize, const M: usize> {
    dv: [f64; N],
    dx: [f64; M],
}

impl<const N: usize, const M: usize> Bend<N, M> {
    /// The bend expected for the input step `dx`: `s² dv` with `s` the projection of `dx`
    /// on the last input step (a step across it bends by the part along it only).
    #[inline(always)]
    fn toward(&self, dx: &[f64; M]) -> Option<f64> {
        let (mut along, mut last) = (0.0, 0.0);
        for j in 0..M {
            along += dx[j] * self.dx[j];
            last += self.dx[j] * self.dx[j];
        }
        let s = along / last;
        s.is_finite().then_some(s * s)
    }
}

/// Follows one branch through a stream of joint vectors.
///
/// Each update predicts with the linearisation `B Δv = −(∂F/∂x) Δx` (Eq. 5), reusing the
/// factorisation of B kept from the last accepted sample, plus the bend the last step showed
/// beyond its own linear prediction (scaled to this step, at fine sampling only), corrects
/// first with that same B (chord steps: no new factorisation) while they contract fast, then
/// with Newton, all under the contraction test of [`arc_length`](crate::arc_length). A
/// sample is accepted by the rule every
/// solver shares: at the returned point itself the Newton correction is within the tolerance
/// and det B has the start's sign (B is factored there, and kept for the next prediction).
/// When the test fails the sample goes to full pseudo-arc-length continuation from the last
/// accepted sample along the joint segment, which refuses to pass a fold.
///
/// After a refused sample the fast path is not used again until a sample has been accepted:
/// the next sample may lie far from the last accepted one, and only continuation along the
/// segment between them shows that it is connected to it without a singularity.
///
/// Between two samples the tracker knows only the straight joint segment joining them, and
/// its answer is that segment's. The machine's own path between the samples can pass a cusp
/// of the singular surface on the other side from the segment: then both are free of
/// singularities and still end in different assembly modes (the nonsingular mode change of the
/// README's "What ok means"). Sample so that the segment stays close to the path: the
/// branch hunts found it on a degenerate 6-RSS fed a fast curve at 25 Hz (the segment's end
/// 99 mm from the curve's); their 100 Hz and 1 kHz curves have not shown it.
///
/// ```
/// use linkage::{Mechanism, Options, Tracker};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// # let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// # let start = linkage::Start::new(&rps, v0, x0).unwrap();
/// let mut tracker = Tracker::new(rps.clone(), start, Options::TIGHT);
/// for k in 1..=1000 {
///     // 1 kHz samples of a slow heave.
///     let t = k as f64 * 1e-3;
///     let legs = x0.map(|l| l + 10.0 * (2.0 * std::f64::consts::PI * t).sin());
///     let sample = tracker.update(&legs).unwrap();
///     assert!(sample.proximity > 0.1, "far from a singularity");
/// }
/// // A bad sample is refused, and the tracker carries on.
/// assert!(tracker.update(&[f64::NAN; 3]).is_err());
/// assert!(tracker.update(&x0).is_ok());
/// ```
#[derive(Clone, Debug)]
pub struct Tracker<S: Mechanism<N, M>, const N: usize, const M: usize> {
    sys: S,
    start: Start<N, M>,
    v: [f64; N],
    x: [f64; M],
    /// det B at (v, x).
    det: f64,
    options: Options,
    /// B factored at (v, x), for the next predictor; `None` until first needed.
    factor: Option<S::Factor>,
    /// The last sample was refused: the next must be reached by continuation.
    refused: bool,
    /// The second-order part of the last fast step: the accepted point minus the linear
    /// prediction, and the input step it belongs to; `None` after continuation.
    bend: Option<Bend<N, M>>,
    /// With [`Tracker::certified`]: the chain of step certificates.
    certified: Option<crate::certified_steps::CertifiedSteps<N, M>>,
    /// The options checked against the start once: neither changes while tracking.
    options_checked: Result<(), SolveError>,
    /// The sines and cosines of the inputs (for a mechanism that turns by them) at the inputs
    /// beside them: those of the last fast step's sample, which the next predictor reuses
    /// where that sample was accepted (the inputs compared, so no other path can leave them
    /// stale).
    turns: (Turns<M>, [f64; M]),
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Tracker<S, N, M> {
    /// A tracker of `sys` (owned: a controller keeps one per machine) on the branch of `start`,
    /// solving every sample to `options`. Nothing is checked here: a start made for another
    /// geometry, or options out of range, are refused at the first [`Tracker::update`] as
    /// [`TrackError::Input`], and the tracker stays at the start.
    pub fn new(sys: S, start: Start<N, M>, options: Options) -> Self {
        // A start made for another geometry is refused at the first sample, like bad options.
        let options_checked = options
            .check(start.scale())
            .and_then(|()| crate::start::check_consistent(&sys, &start));
        Tracker {
            v: *start.v(),
            x: *start.x(),
            det: start.det(),
            sys,
            start,
            options,
            factor: None,
            refused: false,
            bend: None,
            certified: None,
            options_checked,
            turns: (Turns::NONE, [f64::NAN; M]),
        }
    }

    /// Certifies every step ([`CertifiedSteps`](crate::certified_steps::CertifiedSteps)): a sample is accepted
    /// only when the joint segment from the last accepted sample is proven, by parametric
    /// Krawczyk certificates (the segment split into up to 64 pieces when it does not pass
    /// whole), to lead along one branch without a singularity; [`Sample::proof`] holds the
    /// proof. A sample that is solved but not proven is refused with
    /// [`TrackError::Unproven`], like any refused sample: the state stays at the last accepted
    /// one, so the chain of proofs is never broken: called on a new tracker (as below), every
    /// accepted sample is proven to lie on the start's branch. Called later, the chain starts
    /// at the last accepted sample.
    ///
    /// ```
    /// use linkage::{Mechanism, Options, StepProof, Tracker};
    /// # linkage::mechanism! {
    /// #     pub struct Rps;
    /// #     base {
    /// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
    /// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
    /// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    /// #     }
    /// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    /// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    /// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    /// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
    /// # }
    /// # let rps = Rps::new();
    /// # let v0 = linkage::unknowns_from_pose(&rps, &linkage::Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
    /// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
    /// # let start = linkage::Start::new(&rps, v0, x0).unwrap();
    /// let mut tracker = Tracker::new(rps.clone(), start, Options::TIGHT).certified();
    /// for k in 1..=100 {
    ///     let legs = x0.map(|l| l + 10.0 * (k as f64 * 1e-2).sin());
    ///     let sample = tracker.update(&legs).unwrap();
    ///     let Some(StepProof::Proven { error_bound, .. }) = sample.proof else {
    ///         unreachable!("an accepted sample is proven")
    ///     };
    ///     assert!(error_bound < 1.0);
    /// }
    /// ```
    pub fn certified(mut self) -> Self {
        self.certified = Some(crate::certified_steps::CertifiedSteps::new());
        self
    }

    /// The last accepted pivot coordinates and joint inputs.
    pub fn state(&self) -> (&[f64; N], &[f64; M]) {
        (&self.v, &self.x)
    }

    /// The mechanism tracked.
    pub fn mechanism(&self) -> &S {
        &self.sys
    }

    /// Solves the next sample. On error the state is kept, and the next sample is reached
    /// from it by continuation only.
    pub fn update(&mut self, x: &[f64; M]) -> Result<Sample<N>, TrackError> {
        if self.certified.is_none() {
            let result = self.step(x);
            self.refused = result.is_err();
            return result;
        }
        // The state to return to if the step is solved but not proven. The factorisation is
        // not kept: after a refusal the next sample is reached by continuation, which drops it.
        let before = (self.v, self.x, self.det);
        let result = self.step(x).and_then(|mut sample| {
            let Some(chain) = &mut self.certified else {
                return Ok(sample);
            };
            match chain.prove(&self.sys, (&before.0, &before.1), (&sample.v, x)) {
                proof @ StepProof::Proven { .. } => {
                    sample.proof = Some(proof);
                    Ok(sample)
                }
                StepProof::Unproven { pieces, reason } => {
                    (self.v, self.x, self.det) = before;
                    self.factor = None;
                    self.bend = None;
                    Err(TrackError::Unproven { pieces, reason })
                }
            }
        });
        self.refused = result.is_err();
        result
    }

    fn step(&mut self, x: &[f64; M]) -> Result<Sample<N>, TrackError> {
        self.options_checked.map_err(TrackError::Input)?;
        if !crate::start::all_finite(x) {
            return Err(TrackError::Input(SolveError::NonFinite));
        }
        self.sys
            .validate_inputs(x)
            .map_err(|input| TrackError::Input(SolveError::InvalidInput { input }))?;
        let mut iterations = 0;
        if !self.refused {
            let mut v = self.v;
            if let Some(det) = self.fast(x, &mut v, &mut iterations)
                && det * self.start.det() > 0.0
                && crate::outcome::holds_dependent(&self.sys, &v, x)
            {
                return Ok(self.accept(v, x, det, iterations, false));
            }
            // The factorisation was overwritten on the way; continuation does not use it.
            self.factor = None;
            self.bend = None;
        }
        // Continuation from the last accepted sample, whose branch is the start's. Its point is
        // on the branch to within the tolerance only, and continuation resolves a path far
        // finer (a 1 kHz sample's step can be shorter than that tolerance: every first
        // correction would then carry the point's own error and be refused), so it is refined
        // first, as a start is, unless that moves it off or across the start's det B sign.
        let here = match Start::new(&self.sys, self.v, self.x) {
            Ok(refined) if refined.det() * self.start.det() > 0.0 => {
                Start::accepted(*refined.v(), self.x, refined.det(), *self.start.floor())
            }
            _ => Start::accepted(self.v, self.x, self.det, *self.start.floor()),
        };
        let sol = from_accepted(&self.sys, &here, x, &self.options).map_err(TrackError::Input)?;
        if !sol.is_ok() {
            return Err(TrackError::Lost(sol.status));
        }
        let det = det_b(&self.sys, &sol.v, x);
        if det * self.start.det() <= 0.0 {
            return Err(TrackError::Lost(Status::BranchChanged));
        }
        self.factor = None;
        self.bend = None;
        Ok(self.accept(sol.v, x, det, iterations + sol.newton_iterations, true))
    }

    /// Predictor, chord and Newton corrections from `v` (the last accepted point) to a point,
    /// left in `v`, where the Newton correction is within the tolerance; returns det B there.
    /// B is factored at the returned point in `self.factor`, which is left unspecified when
    /// the fast path fails.
    fn fast(&mut self, x: &[f64; M], v: &mut [f64; N], iterations: &mut u32) -> Option<f64> {
        crate::dispatch::fastest_or(
            (self, v, iterations),
            #[inline(always)]
            |(t, v, i)| {
                t.fast_here(
                    x,
                    v,
                    i,
                    #[inline(always)]
                    |s: &S, f: &S::Factor, b: &mut [f64; N]| s.solve(f, b),
                )
            },
            // Built for the plain x86-64 level, the three solves inlined into one function
            // spill more than two calls cost (`count track` as built: 3 072 instructions a
            // sample inlined, 2 952 so; BENCHMARKS.md).
            #[inline(always)]
            |(t, v, i)| t.fast_here(x, v, i, solve_out_of_line::<S, N, M>),
        )
    }

    /// [`Self::fast`]'s work, inlined into each of
    /// [`fastest_or`](crate::dispatch::fastest_or)'s closures; `solve` is the predictor's and
    /// the chords' solve.
    #[inline(always)]
    fn fast_here(
        &mut self,
        x: &[f64; M],
        v: &mut [f64; N],
        iterations: &mut u32,
        solve: impl Fn(&S, &S::Factor, &mut [f64; N]),
    ) -> Option<f64> {
        let tol = self.options.tolerance;
        let fac = match &mut self.factor {
            Some(f) => f,
            none => {
                let mut f = self.sys.new_factor();
                self.sys.factor(&self.v, &self.x, &mut f)?;
                none.insert(f)
            }
        };
        let dx: [f64; M] = core::array::from_fn(|j| x[j] - self.x[j]);
        // The predictor step is −dv: B dv = (∂F/∂x) dx.
        let mut dv = [0.0; N];
        let mut at_last = Turns::NONE;
        let t_last = if S::TURNS && self.turns.1 == self.x {
            &self.turns.0
        } else {
            Turns::of(&self.sys, &self.x, &mut at_last)
        };
        self.sys
            .input_derivative_turned(&self.v, &self.x, t_last, &dx, &mut dv);
        solve(&self.sys, fac, &mut dv);
        let step = size(&dv);
        if !step.is_finite() {
            return None;
        }
        // The linear prediction (`self.v - dv`, which measures this step's bend once it is
        // accepted: `v` starts as `self.v`).
        for i in 0..N {
            v[i] -= dv[i];
        }
        // The bend the last step had, scaled to this one, where it is a small part of it.
        let mut bend = 0.0;
        if let Some(last) = &self.bend
            && let Some(s2) = last.toward(&dx)
        {
            let expected = s2 * size(&last.dv);
            if expected <= BEND_SHARE * step {
                for i in 0..N {
                    v[i] += s2 * last.dv[i];
                }
                bend = expected;
            }
        }
        let mut contraction = Contraction::new(step, tol);
        // The chord's rate: at first as the linear predictor's error suggests (it grows like
        // ω h², the chord's rate like ω h; the bend added is most of that error), then
        // measured.
        let mut previous = f64::INFINITY;
        let mut chord = true;
        let mut c = Correction::new();
        // The sample's inputs stay fixed through its corrections.
        let mut turned = Turns::NONE;
        let t = Turns::of(&self.sys, x, &mut turned);
        while *iterations < MAX_CORRECTIONS {
            *iterations += 1;
            if chord {
                let mut d = [0.0; N];
                self.sys.residual_turned(v, x, t, &mut d);
                solve(&self.sys, fac, &mut d);
                let size = size(&d);
                let admitted = contraction.admits(size);
                if !size.is_finite() || !(admitted || size <= tol) {
                    return None;
                }
                for i in 0..N {
                    v[i] -= d[i];
                }
                let rate = if previous.is_finite() {
                    size / previous
                } else {
                    2.0 * (size + bend) / step.max(f64::MIN_POSITIVE)
                };
                // Factor at v once the next correction is predicted within the tolerance (to
                // confirm it there), or when chords have become slow.
                chord = rate <= CHORD_RATIO && rate * size > tol;
                previous = size;
            } else {
                c.update(&self.sys, v, x, t, self.options.linear, fac)
                    .ok()?;
                if c.size <= tol {
                    // Within the tolerance by its correction, but not by what rounding lets it
                    // show (near a singularity): continuation decides, and says so.
                    let floor = self.start.floor();
                    let squares = crate::math::squares(v);
                    match crate::floor::vouch(&self.sys, floor, (v, x), squares, c.det, c.size, tol)
                    {
                        crate::floor::Vouched::Within(_) => {}
                        crate::floor::Vouched::Refined(w, _) => *v = w,
                        crate::floor::Vouched::Short(..) => return None,
                    }
                    let mut bent = [0.0; N];
                    for i in 0..N {
                        bent[i] = v[i] - (self.v[i] - dv[i]);
                    }
                    self.bend = Some(Bend { dv: bent, dx });
                    if S::TURNS {
                        self.turns = (turned, *x);
                    }
                    return Some(c.det);
                }
                if !contraction.admits(c.size) && !at_rounding_floor(c.size, tol, v) {
                    return None;
                }
                for i in 0..N {
                    v[i] -= c.delta[i];
                }
            }
        }
        None
    }

    fn accept(
        &mut self,
        v: [f64; N],
        x: &[f64; M],
        det: f64,
        newton_iterations: u32,
        fell_back: bool,
    ) -> Sample<N> {
        self.v = v;
        self.x = *x;
        self.det = det;
        Sample {
            v,
            proximity: (det / self.start.det()).abs(),
            newton_iterations,
            fell_back,
            proof: None,
        }
    }
}

/// The generated solve, called rather than inlined.
#[inline(never)]
fn solve_out_of_line<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    f: &S::Factor,
    b: &mut [f64; N],
) {
    sys.solve(f, b);
}

/// Whether a Newton correction that did not contract is rounding, not a corrector sliding
/// away: within a few tolerances, and below the floor where `newton`'s final rule lets
/// corrections scatter (1e-6 of the scale). There the corrections scatter (on a machine of
/// 900 mm legs at 1e-9 mm: 2.2e-9, then 1.2e-9, then below), and a few more are tried, within
/// [`MAX_CORRECTIONS`], instead of handing a converged sample to continuation, whose final
/// Newton run may then stop at the same floor.
fn at_rounding_floor<const N: usize>(size: f64, tolerance: f64, v: &[f64; N]) -> bool {
    size <= FLOOR_BAND * tolerance && size <= 1e-6 * crate::math::scale_or_one(crate::math::size(v))
}
