//! What a start set is made with ([`ModesOptions`]), how it went ([`StartReport`]), and
//! what can go wrong ([`ModesError`]).

#[cfg(doc)]
use super::AllModes;
#[cfg(doc)]
use crate::mechanism::Mechanism;

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
/// - `conjugate_finds > 0`: a component that is not real was found without its conjugate, and
///   the conjugate came by tracking conjugate roots back from a real point. Such components
///   hold complex roots only (at generic real inputs), never an assembly mode.
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
    /// Monodromy stops after this many loops in any case: a bound on its time. A start set
    /// that reached it ([`Ended::LoopCap`]) is likely short, and no list tracked from it is
    /// complete ([`Roots::is_complete`](super::Roots::is_complete)). 1 000 by default: each
    /// component seeds reach costs some loops before the count settles again, and Theo
    /// Jansen's leg (32 roots, 14 of its finds by seeds) took 246; the mechanisms that settle
    /// sooner stop sooner.
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
            max_loops: 1000,
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
    InvalidInput {
        /// The input's index in [`Mechanism::INPUTS`](crate::mechanism::Mechanism::INPUTS).
        input: usize,
    },
    /// The seeding reached solutions of F(v, x) = 0, and ∂F/∂v was singular at every one: the
    /// geometry is architecture-singular (or has a self-motion everywhere), so the family has
    /// no isolated roots to count.
    Degenerate,
    /// No seeding attempt converged onto F(v, x) = 0 at all (from random complex placements
    /// and inputs): nothing is known about the geometry, only that no start was found.
    Unseeded {
        /// The seeding attempts made.
        attempts: usize,
    },
    /// Monodromy found more than `K` solutions.
    Capacity {
        /// `K`, the most solutions the set holds.
        capacity: usize,
    },
    /// More than 255 unknowns.
    TooLarge,
    /// A given start solution is not a nonsingular root at the given parameters.
    BadStart {
        /// The start's index in the slice given.
        index: usize,
    },
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
    /// Conjugation steps that brought solutions: the starts tracked to a real point, where
    /// the conjugate of a complex root reached is a root too, and conjugates tracked back that
    /// no loop or seed had reached (the conjugate of a component found; an RCCC's model has
    /// such a pair).
    pub conjugate_finds: usize,
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
