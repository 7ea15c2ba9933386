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
mod conjugation;
mod dense;
mod endpoint;
mod extended;
mod found;
mod inputs;
mod monodromy;
mod options;
mod path;
mod polish;
mod query;
mod refill;
mod rng;
mod roots;
mod seed;
mod sparse_lu;
mod starts;
mod stored;
mod symmetry;
mod taylor;
mod track;

pub use complex::Complex;
pub use options::{Ended, ModesError, ModesOptions, StartReport};
pub use roots::{Endpoint, EndpointKind, RealRoot, Roots};
pub use taylor::Series;

use crate::mechanism::Mechanism;
use inputs::Inputs;
use sparse_lu::Plan;
use track::{Chart, Model};

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
}
