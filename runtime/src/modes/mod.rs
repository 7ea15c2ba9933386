//! Every assembly mode: all isolated complex roots of `F(v, x) = 0` at given inputs, the real
//! ones with their poses.
//!
//! The inputs x are the parameters of a family of systems. [`AllModes::new`] solves the family
//! once at a random complex parameter point p₀ — a seed made by placing the platform with a
//! random complex rigid motion and moving (v, x) onto F = 0, then monodromy: loops of parameters
//! around p₀ that permute the roots, until a number of loops in a row bring nothing new. Each
//! query ([`AllModes::solve`]) is then a parameter homotopy from p₀ to the real target with the
//! γ trick, tracked in complex arithmetic by an adaptive predictor–corrector (cubic Taylor
//! predictor from Taylor-mode derivatives of the generated residual, Newton corrector as the
//! acceptance test), the endpoints classified as real, complex, singular or diverging, and the
//! real roots refined in real arithmetic with their pose, the sign of det B, the residual and
//! the distance to the nearest other root. Two paths that end on the same root are tracked
//! again with smaller steps.
//!
//! A query is `no_std` and allocates nothing: the starts live in the [`AllModes`] value and the
//! results in a caller's [`Roots`] of fixed capacity `K`.
//!
//! ```
//! use linkage::modes::{AllModes, Ended, ModesOptions, EndpointKind};
//! # linkage::mechanism! {
//! #     pub struct Rps;
//! #     base {
//! #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
//! #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
//! #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
//! #     }
//! #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
//! #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
//! #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
//! #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
//! # }
//! // A 3-RPS: 16 complex assembly modes for generic leg lengths.
//! let modes = AllModes::<Rps, 9, 3, 32>::new(Rps::new(), &ModesOptions::default()).unwrap();
//! assert_eq!(modes.start_count(), 16);
//! // Count stability ended monodromy, after a run of fruitless seeds as long as the rule asks.
//! let report = modes.report();
//! assert_eq!(report.ended, Ended::Stable);
//! assert!(report.seeds_since_new >= report.seeds_needed);
//! let mut roots = linkage::modes::Roots::new();
//! modes.solve(&[150.0, 160.0, 155.0], &mut roots).unwrap();
//! assert!(roots.is_complete());
//! for mode in roots.real() {
//!     assert!(mode.residual < 1e-9 && mode.pose.is_some());
//! }
//! assert_eq!(roots.real().len(), roots.count(EndpointKind::Real));
//! ```

mod complex;
mod dense;
mod endpoint;
mod extended;
mod inputs;
mod monodromy;
mod path;
mod polish;
mod refill;
mod rng;
mod roots;
mod seed;
mod sparse_lu;
mod stored;
mod symmetry;
mod taylor;
mod track;

pub use complex::Complex;
pub use roots::{Endpoint, EndpointKind, RealRoot, Roots};
pub use taylor::Series;

use crate::Mechanism;
use inputs::Inputs;
use monodromy::Stopping;
use path::ParameterPath;
use polish::{SAME, contains};
use rng::Rng;
use sparse_lu::Plan;
use track::{Chart, Model, Settings, Workspace};

/// Random seeds tried before [`AllModes::new`] gives up.
const SEED_ATTEMPTS: usize = 12;

/// The largest first Newton correction (weighted) a stored start may need.
const STORED: f64 = 1e-8;

/// A random γ = e^(iθ) with π/6 ≤ |θ| ≤ π/2: a real bend of the path, but far from −1, where
/// the rational path (see `path.rs`) would pass near a pole and blow every solution up.
fn gamma(rng: &mut Rng) -> Complex {
    let t = core::f64::consts::PI * (1.0 / 6.0 + rng.uniform() / 3.0);
    let t = if rng.uniform() < 0.5 { -t } else { t };
    Complex::new(libm::cos(t), libm::sin(t))
}

/// The degree of each equation in v, from F at two points far out along a random direction
/// (`F_i(t z) ≈ t^(d_i) P_i(z)` for large t); `None` unless every one is a whole number from 1
/// to 4 (then no projective chart is used).
fn degrees<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    scale: f64,
    rng: &mut Rng,
) -> Option<[u8; N]> {
    let z = [0; N].map(|_| rng.uniform() - 0.5);
    let x = [0; M].map(|_| scale * (rng.uniform() + 0.5));
    let t = 1e6 * scale;
    let (mut f1, mut f2) = ([0.0; N], [0.0; N]);
    sys.residual(&z.map(|c| t * c), &x, &mut f1);
    sys.residual(&z.map(|c| 2.0 * t * c), &x, &mut f2);
    let mut out = [0u8; N];
    for i in 0..N {
        let d = libm::log2((f2[i] / f1[i]).abs());
        let r = libm::round(d);
        if !(d.is_finite() && (d - r).abs() < 0.01 && (1.0..=4.0).contains(&r)) {
            return None;
        }
        out[i] = r as u8;
    }
    Some(out)
}

/// How the start solutions are computed.
///
/// Monodromy ends by count stability, which is evidence, not proof, that every root was found.
/// Judge a start set by its [`StartReport`] (`AllModes::report`):
///
/// - [`Ended::LoopCap`]: the loops never settled (or kept failing: `empty_loops`); the count
///   is likely short. Raise `max_loops`.
/// - `failed_paths` comparable to `loops`: most loops lost their paths, and count stability
///   rests on the few that came round. The 3-PRP stopped at 1 of its 2 roots that way, when
///   loops reached too far and failed ones still counted as fruitless.
/// - `seed_finds > 0`, and above all `last_after_seed`: random seeds found solutions the loops
///   from the others could not reach, and the final count came only with such a late find —
///   components are being found by chance. The default rule then asks for a run of fruitless
///   seeds long enough to find a component as small as the smallest seen
///   ([`ModesOptions::confidence`], [`StartReport::seeds_needed`]); for more certainty raise
///   `confidence` (each unit divides the chance of missing such a component by about e) or
///   run other `seed`s and compare counts. Tsai's 3-UPU is such a mechanism: with
///   `confidence` 0 (the rule before it existed) seeds 2015 and 7 stopped at 608 of its 624
///   roots, 8 fruitless seeds after a late find; with the default, 117 were required
///   and seeds 2015, 7 and 99 all reached 624.
/// - `smallest_find` much below the count (a delta's two translations among its 40 roots):
///   small components exist, which random seeds seldom hit; the mechanism's home seeds one.
/// - `first_settled` equal to the count, `seed_finds` 0: the loops from the first seed found
///   everything (a general 6-6 platform), the usual case for one irreducible family.
///
/// A known generic count (`expected`) ends monodromy as soon as it is reached.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModesOptions {
    /// Seed of every random choice (seed point, loops, γ): the same seed gives the same starts.
    pub seed: u64,
    /// Monodromy stops after this many consecutive loops that bring no new solution (loops on
    /// which every path failed are skipped over, not counted: [`StartReport::empty_loops`]).
    pub stable_loops: usize,
    /// After the loops settle, fresh random solutions are tracked to the base point until this
    /// many in a row bring nothing new (they reach components that loops cannot).
    pub stable_seeds: usize,
    /// The run of fruitless fresh seeds that ends monodromy is at least this many times the
    /// number of solutions over the fewest that one seed brought (with the loops that followed
    /// it): seeds land on a component of the solutions about in proportion to its size, so a
    /// further component as small as the smallest found is missed with probability about
    /// e^(−confidence). 0: `stable_seeds` alone. Fruitless seeds are cheap (one path each).
    pub confidence: f64,
    /// Monodromy stops after this many loops in any case.
    pub max_loops: usize,
    /// A generic root count known in advance (40 for a general 6-6 platform): monodromy stops
    /// as soon as it has this many. `None`: count stability alone decides.
    pub expected: Option<usize>,
    /// Length scale of the mechanism (tolerances are relative to it below it); 0 takes the
    /// largest platform pivot coordinate.
    pub scale: f64,
    /// Track in projective coordinates (see [`AllModes`]): needed for roots very far out (a
    /// general 6-6 platform has complex roots 10⁶ times its size away), about a third slower
    /// per step. Ignored if the equations are not polynomial in v of degree 1 to 4.
    pub projective: bool,
}

impl Default for ModesOptions {
    fn default() -> Self {
        ModesOptions {
            seed: 2015,
            stable_loops: 10,
            stable_seeds: 8,
            confidence: 3.0,
            max_loops: 200,
            expected: None,
            scale: 0.0,
            projective: true,
        }
    }
}

/// Why no start set could be made or a query could not be run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModesError {
    /// An input or option is NaN or infinite.
    NonFinite,
    /// Input `input` is out of its range (e.g. a negative leg length).
    InvalidInput { input: usize },
    /// The seeding reached solutions of F(v, x) = 0, and ∂F/∂v was singular at every one: the
    /// geometry is architecture-singular (or has a self-motion everywhere), so the family has
    /// no isolated roots to count.
    Degenerate,
    /// No seeding attempt converged onto F(v, x) = 0 at all (from random complex placements
    /// and inputs): nothing is known about the geometry, only that no start was found.
    Unseeded { attempts: usize },
    /// Monodromy found more than `K` solutions.
    Capacity { capacity: usize },
    /// More than 255 unknowns.
    TooLarge,
    /// A given start solution is not a nonsingular root at the given parameters.
    BadStart { index: usize },
}

impl core::fmt::Display for ModesError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ModesError::NonFinite => write!(f, "non-finite input"),
            ModesError::InvalidInput { input } => write!(f, "joint input {input} is out of range"),
            ModesError::Degenerate => write!(
                f,
                "∂F/∂v is singular at every solution the seeding reached: the geometry is \
                 architecture-singular or has a self-motion"
            ),
            ModesError::Unseeded { attempts } => write!(
                f,
                "no start solution: none of {attempts} random seeds converged onto F(v, x) = 0"
            ),
            ModesError::Capacity { capacity } => {
                write!(f, "more than {capacity} solutions: raise the capacity K")
            }
            ModesError::TooLarge => write!(f, "more than 255 unknowns"),
            ModesError::BadStart { index } => {
                write!(f, "start solution {index} is not a nonsingular root")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ModesError {}

/// How the start set was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct StartReport {
    /// Seeds tried (random solutions at random parameters: the first, and later ones that
    /// look for components the loops cannot reach).
    pub seeds: usize,
    /// Monodromy loops run.
    pub loops: usize,
    /// Paths that failed during monodromy (harmless if their solutions are found another way;
    /// many against `loops` mean the loops were hard to follow, and the count deserves less
    /// trust).
    pub failed_paths: usize,
    /// Loops on which every path failed (none came back to p₀). They are no evidence for the
    /// count and do not count toward [`ModesOptions::stable_loops`]; if loops keep failing,
    /// monodromy runs to [`ModesOptions::max_loops`] and ends with [`Ended::LoopCap`].
    pub empty_loops: usize,
    /// Candidate symmetries ([`Mechanism::symmetry`]) kept: each maps a generic root to
    /// another root (Tsai's 3-UPU: three, one leg spin each, so its roots come in eights).
    pub symmetries: usize,
    /// How monodromy ended.
    pub ended: Ended,
    /// Loops run after the last new solution (0 if it came from a seed with no loop after it).
    pub loops_since_new: usize,
    /// Fresh seeds tried after the last new solution.
    pub seeds_since_new: usize,
    /// Random seeds (after the first; the mechanism's home not counted) that brought solutions
    /// the loops had not reached. Each is a component of the solutions that the loops from
    /// the others do not join, found by chance.
    pub seed_finds: usize,
    /// Whether the last new solution came from such a random seed or from the loops that
    /// followed one: the final count was reached only by a late random find.
    pub last_after_seed: bool,
    /// Solutions known when the first loops settled (before any further seed).
    pub first_settled: usize,
    /// The fewest solutions one seed (the first, the home or a later one) brought with the
    /// loops that followed it: the smallest component seen.
    pub smallest_find: usize,
    /// The run of fruitless fresh seeds the last round of seeds required (see
    /// [`ModesOptions::confidence`]); 0 if the loop cap or the expected count ended monodromy
    /// before any.
    pub seeds_needed: usize,
}

/// How monodromy ended ([`StartReport::ended`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Ended {
    /// Count stability: [`ModesOptions::stable_loops`] loops on which paths came round and
    /// then the required run of fresh seeds in a row brought nothing new.
    Stable,
    /// [`ModesOptions::max_loops`] was reached first: the count may be short.
    LoopCap,
    /// [`ModesOptions::expected`] solutions were found.
    Expected,
    /// No monodromy: the start solutions were given ([`AllModes::from_starts`]).
    #[default]
    Given,
}

/// The solver for every assembly mode of a mechanism: its start solutions at a generic
/// complex parameter point, ready for queries. `K` is the capacity (at least the generic root
/// count: 40 for a general 6-6 Stewart–Gough platform).
#[derive(Clone, Debug)]
pub struct AllModes<S, const N: usize, const M: usize, const K: usize> {
    sys: S,
    plan: Plan<N>,
    chart: Option<Chart<N>>,
    scale: f64,
    inputs: Inputs<M>,
    p0: [Complex; M],
    gamma: Complex,
    /// The start solutions in tracking coordinates (see `track::Chart`).
    starts: [[Complex; N]; K],
    count: usize,
    report: StartReport,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize> AllModes<S, N, M, K> {
    /// Computes the start solutions of `sys` (its geometry as it is now) by monodromy. Takes
    /// milliseconds to a fraction of a second; allocation-free.
    pub fn new(sys: S, options: &ModesOptions) -> Result<Self, ModesError> {
        let mut me = Self::prepare(sys, options)?;
        let mut rng = Rng::new(options.seed);
        me.gamma = gamma(&mut rng);
        let mut first = Err(ModesError::Unseeded {
            attempts: SEED_ATTEMPTS,
        });
        for attempt in 1..=SEED_ATTEMPTS {
            match seed::seed(&me.model(), &me.inputs, &mut rng) {
                Ok(found) => {
                    first = Ok((found, attempt));
                    break;
                }
                // Converged, but B is singular there: evidence of a degenerate family (one
                // converged attempt with a regular B would have been a seed).
                Err(seed::Miss::Singular) => first = Err(ModesError::Degenerate),
                Err(seed::Miss::Walk) => {}
            }
        }
        let ((v, p0), seeds) = first?;
        let model = me.model();
        let mut starts = [[Complex::ZERO; N]; K];
        if K == 0 {
            return Err(ModesError::Capacity { capacity: K });
        }
        starts[0] = model.enter(&v);
        let stop = Stopping {
            stable_loops: options.stable_loops.max(1),
            stable_seeds: options.stable_seeds,
            confidence: options.confidence,
            max_loops: options.max_loops.max(1),
            expected: options.expected,
        };
        // Symmetries of the equations (leg spins), kept where they map this generic root to
        // another root: monodromy then adds every root's orbit at once.
        let sym = symmetry::Symmetries::detect(&model, &starts[0], &p0, &mut Workspace::new());
        let found =
            monodromy::monodromy(&model, &me.inputs, &p0, &mut starts, &sym, &mut rng, &stop);
        if found.overflow {
            return Err(ModesError::Capacity { capacity: K });
        }
        let report = StartReport {
            seeds: seeds + found.seeds,
            loops: found.loops,
            failed_paths: found.failed_paths,
            empty_loops: found.empty_loops,
            symmetries: sym.count(),
            ended: found.ending,
            loops_since_new: found.loops_since_new,
            seeds_since_new: found.seeds_since_new,
            seed_finds: found.seed_finds,
            last_after_seed: found.last_after_seed,
            first_settled: found.first_settled,
            smallest_find: if found.smallest == usize::MAX {
                0
            } else {
                found.smallest
            },
            seeds_needed: found.seeds_needed,
        };
        me.report = report;
        me.starts = starts;
        me.count = found.count;
        me.p0 = p0;
        Ok(me)
    }

    /// Moves the start set to a parameter point near the real inputs `center` (each input
    /// perturbed by a random complex number of size `spread` × the scale, or `spread` radians for
    /// an angle), so that queries near
    /// `center` follow short paths. Every start is tracked there; if one fails, another random
    /// point is tried (four in all); if all fail, nothing changes and the error names the start
    /// that failed last.
    pub fn recenter(
        &mut self,
        center: &[f64; M],
        spread: f64,
        seed: u64,
    ) -> Result<(), ModesError> {
        if !center.iter().all(|c| c.is_finite()) || !spread.is_finite() {
            return Err(ModesError::NonFinite);
        }
        let mut rng = Rng::new(seed);
        let mut error = ModesError::BadStart { index: 0 };
        for _ in 0..4 {
            let p1: [Complex; M] = core::array::from_fn(|i| {
                Complex::real(center[i]) + rng.complex_normal().scale(spread * self.inputs.unit(i))
            });
            match self.moved_to(&p1) {
                Ok(moved) => {
                    self.starts = moved;
                    self.p0 = p1;
                    return Ok(());
                }
                Err(e) => error = e,
            }
        }
        Err(error)
    }

    /// The start set tracked from p₀ to `p1`, each path tried with the default and the careful
    /// settings; all distinct.
    fn moved_to(&self, p1: &[Complex; M]) -> Result<[[Complex; N]; K], ModesError> {
        let path = ParameterPath::new(self.p0, *p1, Complex::ONE);
        let model = self.model();
        let mut ws = Workspace::new();
        let mut moved = self.starts;
        for (index, v) in moved[..self.count()].iter_mut().enumerate() {
            let from = *v;
            let reached = [Settings::DEFAULT, Settings::CAREFUL].iter().any(|set| {
                *v = from;
                model.track(&path, v, &mut ws, set).outcome == track::Outcome::Reached
                    && polish::polish(&model, v, p1, &mut ws, true)
                    && model.size(v) <= 1e8
            });
            if !reached {
                return Err(ModesError::BadStart { index });
            }
        }
        for index in 1..self.count() {
            if contains(&model, &moved[..index], &moved[index], SAME) {
                return Err(ModesError::BadStart { index });
            }
        }
        Ok(moved)
    }

    /// Takes start solutions computed before (e.g. by [`AllModes::new`] and stored): each
    /// is checked to be a nonsingular root at `p0` — Newton's first correction from it below
    /// 1e-8 of the scale — and refined; no two may be the same root. Allocation-free.
    pub fn from_starts(
        sys: S,
        p0: [Complex; M],
        gamma: Complex,
        starts: &[[Complex; N]],
        options: &ModesOptions,
    ) -> Result<Self, ModesError> {
        if starts.len() > K {
            return Err(ModesError::Capacity { capacity: K });
        }
        if !p0.iter().all(|c| c.is_finite()) || !gamma.is_finite() || gamma.abs() == 0.0 {
            return Err(ModesError::NonFinite);
        }
        let mut me = Self::prepare(sys, options)?;
        me.p0 = p0;
        me.gamma = gamma;
        let mut ws = Workspace::new();
        for (index, s) in starts.iter().enumerate() {
            let model = me.model();
            let mut z = model.enter(s);
            // A stored root is a root to its printed digits: Newton's first correction must be
            // tiny (a point that merely lies in some root's basin is refused, not replaced by
            // that root). The factorisation serves the refinement that follows.
            let (values, lu) = ws.scratch();
            if !s.iter().all(|c| c.is_finite())
                || !model.factor(&z, &p0, values, lu)
                || !(model.norm(&model.newton(lu, &z, &p0), &z) <= STORED)
            {
                return Err(ModesError::BadStart { index });
            }
            if !polish::polish(&model, &mut z, &p0, &mut ws, true)
                || !(model.size(&z) <= 1e8)
                || contains(&model, &me.starts[..me.count()], &z, SAME)
            {
                return Err(ModesError::BadStart { index });
            }
            // There is room: no more starts than K, checked above.
            let Some(slot) = me.starts.get_mut(me.count) else {
                return Err(ModesError::Capacity { capacity: K });
            };
            *slot = z;
            me.count += 1;
        }
        Ok(me)
    }

    fn prepare(sys: S, options: &ModesOptions) -> Result<Self, ModesError> {
        if !options.scale.is_finite()
            || options.scale < 0.0
            || !options.confidence.is_finite()
            || options.confidence < 0.0
        {
            return Err(ModesError::NonFinite);
        }
        let scale = if options.scale > 0.0 {
            options.scale
        } else {
            let s = (0..S::POINTS.len())
                .flat_map(|p| sys.point_local(p))
                .filter(|c| c.is_finite())
                .fold(0.0f64, |m, c| m.max(c.abs()));
            if s > 0.0 { s } else { 1.0 }
        };
        // Two unrelated real points tell constant Jacobian entries from variable ones.
        let mut rng = Rng::new(options.seed ^ 0xA5A5);
        let mut samples = [[[0.0f64; N]; N]; 2];
        for sample in samples.iter_mut() {
            let v = [0; N].map(|_| scale * (rng.uniform() - 0.5));
            let x = [0; M].map(|_| scale * (rng.uniform() + 0.5));
            sys.jacobian_in(&v, &x, sample.as_flattened_mut());
        }
        let (a, b) = (samples[0].as_flattened(), samples[1].as_flattened());
        let plan = Plan::new(S::PATTERN, a, b).map_err(|_| ModesError::TooLarge)?;
        // The border of the projective Jacobian needs one static pivot (room in the compact
        // remainder).
        let chart = degrees(&sys, scale, &mut rng)
            .filter(|_| options.projective && plan.shape().0 > 0)
            .map(|degree| Chart {
                c: [0; N].map(|_| rng.complex_normal().scale(1.0 / (scale * N as f64))),
                degree,
            });
        let inputs = Inputs::detect(&sys, scale, &mut rng);
        Ok(AllModes {
            sys,
            plan,
            chart,
            scale,
            inputs,
            p0: [Complex::ZERO; M],
            gamma: Complex::ONE,
            starts: [[Complex::ZERO; N]; K],
            count: 0,
            report: StartReport::default(),
        })
    }

    fn model(&self) -> Model<'_, S, N> {
        Model {
            sys: &self.sys,
            plan: &self.plan,
            pattern: S::PATTERN,
            scale: self.scale,
            chart: self.chart.as_ref(),
        }
    }

    /// The start count as an index bound: `count` ≤ K by construction (`new` and
    /// `from_starts` refuse more); the `min` lets the compiler see it too, so that the query's
    /// loops over the paths have no panic path (`tests/no_panic`).
    fn count(&self) -> usize {
        self.count.min(K)
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &S {
        &self.sys
    }

    /// Number of start solutions: the generic number of complex roots as far as monodromy
    /// found them. Count stability is evidence, not proof ([`ModesOptions`],
    /// [`AllModes::report`]): a root missing here is missing from every query.
    pub fn start_count(&self) -> usize {
        self.count
    }

    /// The start parameters p₀ and γ (to store and pass to [`AllModes::from_starts`]).
    pub fn base_point(&self) -> (&[Complex; M], Complex) {
        (&self.p0, self.gamma)
    }

    /// Start solution `i` (v at p₀), `None` past [`AllModes::start_count`].
    pub fn start(&self, i: usize) -> Option<[Complex; N]> {
        self.starts[..self.count()]
            .get(i)
            .map(|s| self.model().leave(s))
    }

    /// How the start set was found.
    pub fn report(&self) -> StartReport {
        self.report
    }

    /// The length scale of the tolerances.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Every root at inputs `x`, into `out`. No heap, no panic; NaN, infinite or out-of-range
    /// inputs are errors. Each of the [`AllModes::start_count`] paths gets an endpoint; a
    /// target with fewer isolated roots than generic shows diverging or singular endpoints.
    /// Where some paths end short of a regular root, the conjugates of the complex roots
    /// found (the target is real), every start tracked again along up to three other γ-bent
    /// paths, and the failed paths retracked with double-double residuals far out fill their
    /// places (so an endpoint's index is its start's only where no such refill happened).
    pub fn solve(&self, x: &[f64; M], out: &mut Roots<N, K>) -> Result<(), ModesError> {
        if !x.iter().all(|c| c.is_finite()) {
            return Err(ModesError::NonFinite);
        }
        self.sys
            .validate_inputs(x)
            .map_err(|input| ModesError::InvalidInput { input })?;
        let target = x.map(Complex::real);
        let mut ws = Workspace::new();
        out.paths = self.count();
        out.n_real = 0;
        let path = ParameterPath::new(self.p0, target, self.gamma);
        for (i, e) in out.endpoints.iter_mut().take(self.count()).enumerate() {
            *e = self.retried_endpoint(&path, i, &target, &mut ws);
        }
        self.separate_duplicates(&path, &target, out, &mut ws);
        // Paths that still end short of a regular root: conjugates, every start again along
        // other γ-bent paths (which pass the degenerate parameters elsewhere), the failed ones
        // in double-double far out; their new roots fill the failed paths' places
        // (see `refill.rs`).
        self.refill_failed(&target, out, &mut ws);
        self.finish(x, out);
        Ok(())
    }

    /// Tracks start `i` along `path` and classifies its end: first in affine coordinates (a
    /// third cheaper per step, and enough for every path that stays within reach of double
    /// precision), then, if it did not end at a regular root, in projective coordinates, then
    /// with small steps. (At a target with fewer roots than generic it ends as it did.)
    fn retried_endpoint(
        &self,
        path: &ParameterPath<M>,
        i: usize,
        target: &[Complex; M],
        ws: &mut Workspace<N>,
    ) -> Endpoint<N> {
        let model = self.model();
        let affine = Model {
            chart: None,
            ..model
        };
        let mut e = self.endpoint(&affine, path, i, target, &Settings::DEFAULT, ws);
        for set in [&Settings::DEFAULT, &Settings::CAREFUL] {
            if e.is_root() {
                break;
            }
            let steps = e.steps;
            e = self.endpoint(&model, path, i, target, set, ws);
            e.steps += steps;
        }
        e
    }

    /// Two paths on one nonsingular root: one of them jumped. Tracks both again carefully; if
    /// they still meet, the second is a [`EndpointKind::Duplicate`].
    fn separate_duplicates(
        &self,
        path: &ParameterPath<M>,
        target: &[Complex; M],
        out: &mut Roots<N, K>,
        ws: &mut Workspace<N>,
    ) {
        let model = self.model();
        let count = self.count();
        for i in 0..count {
            for j in i + 1..count {
                if !(out.endpoints[i].is_root() && out.endpoints[j].is_root()) {
                    continue;
                }
                let (a, b) = (out.endpoints[i].z, out.endpoints[j].z);
                if !contains(&model, &[a], &b, SAME) {
                    continue;
                }
                for k in [i, j] {
                    let Some(e) = out.endpoints.get_mut(k) else {
                        continue;
                    };
                    let steps = e.steps;
                    *e = self.endpoint(&model, path, k, target, &Settings::CAREFUL, ws);
                    e.steps += steps;
                }
                let (a, b) = (out.endpoints[i].z, out.endpoints[j].z);
                if out.endpoints[i].is_root() && contains(&model, &[a], &b, SAME) {
                    out.endpoints[j].kind = EndpointKind::Duplicate;
                }
            }
        }
    }

    /// Tracks start `i` along `path` with `model` and classifies where it ends; the endpoint's
    /// `z` is in the solver's own tracking coordinates whichever model tracked it.
    pub(super) fn endpoint(
        &self,
        model: &Model<'_, S, N>,
        path: &ParameterPath<M>,
        i: usize,
        target: &[Complex; M],
        settings: &Settings,
        ws: &mut Workspace<N>,
    ) -> Endpoint<N> {
        let own = self.model();
        // `i` is below the start count wherever this is called; past it no path exists.
        let Some(start) = self.starts.get(i) else {
            return Endpoint::EMPTY;
        };
        let mut z = model.enter(&own.leave(start));
        let tracked = model.track(path, &mut z, ws, settings);
        let mut e = endpoint::classify(model, target, &tracked, &z, ws);
        if model.chart.is_none() && e.v.iter().all(|c| c.is_finite()) {
            e.z = own.enter(&e.v);
        }
        e
    }

    /// Distances between roots and the real roots' refinement.
    fn finish(&self, x: &[f64; M], out: &mut Roots<N, K>) {
        let n = out.paths.min(K);
        for i in 0..n {
            out.endpoints[i].nearest = f64::INFINITY;
        }
        for i in 0..n {
            if !out.endpoints[i].is_root() {
                continue;
            }
            for j in i + 1..n {
                if !out.endpoints[j].is_root() {
                    continue;
                }
                let d = endpoint::distance(&out.endpoints[i].v, &out.endpoints[j].v);
                let e = &mut out.endpoints;
                e[i].nearest = e[i].nearest.min(d);
                e[j].nearest = e[j].nearest.min(d);
            }
        }
        for i in 0..n {
            if out.endpoints[i].kind != EndpointKind::Real {
                continue;
            }
            let refined = endpoint::real_root(&self.sys, self.scale, &out.endpoints[i].v, x);
            let Some((v, residual, det)) = refined else {
                // Tiny imaginary parts but no real root next to them: a complex pair
                // close to the real space (near a fold).
                out.endpoints[i].kind = EndpointKind::Complex;
                continue;
            };
            if !crate::outcome::holds_dependent(&self.sys, &v, x) {
                out.endpoints[i].kind = EndpointKind::Spurious;
                continue;
            }
            let seen = out.real().iter().any(|r| {
                (0..N).all(|k| (r.v[k] - v[k]).abs() <= 1e-9 * self.scale.max(v[k].abs()))
            });
            if seen {
                // Both members of a complex pair with tiny imaginary parts refined to one
                // real point: a double root, not two modes.
                out.endpoints[i].kind = EndpointKind::Complex;
                continue;
            }
            // At most one real root per path: `n_real` stays below `paths` ≤ K.
            let Some(slot) = out.real.get_mut(out.n_real) else {
                break;
            };
            *slot = RealRoot {
                v,
                pose: crate::pose_from_unknowns(&self.sys, &v),
                det,
                residual,
                nearest: out.endpoints[i].nearest,
                nearest_real: f64::INFINITY,
                path: i,
            };
            out.n_real += 1;
        }
        let n_real = out.n_real.min(K);
        for i in 0..n_real {
            for j in i + 1..n_real {
                let d = crate::math::norm(&core::array::from_fn::<f64, N, _>(|k| {
                    out.real[i].v[k] - out.real[j].v[k]
                }));
                out.real[i].nearest_real = out.real[i].nearest_real.min(d);
                out.real[j].nearest_real = out.real[j].nearest_real.min(d);
            }
        }
    }
}
