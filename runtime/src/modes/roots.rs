//! What a query returns: every path's endpoint, classified, and the real roots with their
//! poses.

use super::complex::Complex;
use crate::pose::Pose;

/// How a path from a start solution ended at the target inputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EndpointKind {
    /// A nonsingular root with real coordinates: an assembly mode.
    Real,
    /// A nonsingular root with complex coordinates.
    Complex,
    /// The path converged to a point where B is singular (a double or higher root, or a
    /// positive-dimensional set such as a self-motion), or stalled just before the target.
    Singular,
    /// The path went to infinity: the target has fewer finite roots than the generic count.
    Diverging,
    /// The path ended on a root another path also reached, even when retracked carefully.
    Duplicate,
    /// The tracker gave up before the target, away from it.
    Failed,
    /// A real root of the square system at which an equation left out as dependent at home
    /// fails ([`Mechanism::dependent_offset`](crate::mechanism::Mechanism::dependent_offset)): not an
    /// assembly of the mechanism.
    Spurious,
}

/// The end of one path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Endpoint<const N: usize> {
    /// Where the path ended (the root, for [`EndpointKind::Real`] and
    /// [`EndpointKind::Complex`]).
    pub v: [Complex; N],
    /// The same point in the tracker's coordinates (accurate also far out).
    pub(crate) z: [Complex; N],
    /// What the endpoint is: a real or complex root, or why the path gave none.
    pub kind: EndpointKind,
    /// Steps the tracker took (over both attempts if the path was retracked).
    pub steps: usize,
    /// max |Fᵢ(v, x)| at the endpoint.
    pub residual: f64,
    /// Euclidean distance to the nearest other finite root (real or complex), in the units of
    /// v; infinite if there is none.
    pub nearest: f64,
    /// Smallest over largest pivot of B's factorisation at the endpoint (a cheap measure of
    /// how far B is from singular; 0 where it is singular).
    pub pivot_ratio: f64,
}

impl<const N: usize> Endpoint<N> {
    pub(crate) const EMPTY: Self = Endpoint {
        v: [Complex::ZERO; N],
        z: [Complex::ZERO; N],
        kind: EndpointKind::Failed,
        steps: 0,
        residual: f64::NAN,
        nearest: f64::INFINITY,
        pivot_ratio: 0.0,
    };

    /// A finite, nonsingular root.
    pub fn is_root(&self) -> bool {
        matches!(self.kind, EndpointKind::Real | EndpointKind::Complex)
    }
}

/// A real root: one assembly mode at the target inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RealRoot<const N: usize> {
    /// The pivots, refined by Newton's method in real arithmetic.
    pub v: [f64; N],
    /// The platform pose (`None` if the frame pivots are collinear).
    pub pose: Option<Pose>,
    /// det B at the root: its sign tells the branch (assembly mode) apart.
    pub det: f64,
    /// max |Fᵢ(v, x)|.
    pub residual: f64,
    /// Distance to the nearest other root, real or complex.
    pub nearest: f64,
    /// Distance to the nearest other real root; infinite if there is none.
    pub nearest_real: f64,
    /// The index of its path among [`Roots::endpoints`].
    pub path: usize,
}

impl<const N: usize> RealRoot<N> {
    const EMPTY: Self = RealRoot {
        v: [0.0; N],
        pose: None,
        det: 0.0,
        residual: f64::NAN,
        nearest: f64::INFINITY,
        nearest_real: f64::INFINITY,
        path: 0,
    };

    /// The sign of det B: +1 or −1.
    pub fn det_sign(&self) -> i8 {
        if self.det < 0.0 { -1 } else { 1 }
    }
}

/// All roots at one input: filled by [`AllModes::solve`](super::AllModes::solve), without heap
/// (capacity `K` paths).
#[derive(Clone, Debug)]
pub struct Roots<const N: usize, const K: usize> {
    pub(crate) endpoints: [Endpoint<N>; K],
    pub(crate) paths: usize,
    pub(crate) real: [RealRoot<N>; K],
    pub(crate) n_real: usize,
    /// Complex roots whose conjugate, a root too at real inputs, is not among them.
    pub(crate) unpaired: usize,
    /// The start set's monodromy stopped at its loop cap
    /// ([`Ended::LoopCap`](super::Ended::LoopCap)): its count is likely short, and so is
    /// every list tracked from it.
    pub(crate) capped: bool,
}

impl<const N: usize, const K: usize> Default for Roots<N, K> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const K: usize> Roots<N, K> {
    /// Empty storage.
    pub const fn new() -> Self {
        Roots {
            endpoints: [Endpoint::EMPTY; K],
            paths: 0,
            real: [RealRoot::EMPTY; K],
            n_real: 0,
            unpaired: 0,
            capped: false,
        }
    }

    /// One endpoint per start solution, in the order of the starts.
    pub fn endpoints(&self) -> &[Endpoint<N>] {
        // `paths` ≤ K by construction; the `min` lets the compiler see it (no panic path).
        &self.endpoints[..self.paths.min(K)]
    }

    /// The real roots (assembly modes), distinct.
    pub fn real(&self) -> &[RealRoot<N>] {
        &self.real[..self.n_real.min(K)]
    }

    /// Number of paths that ended as `kind`.
    pub fn count(&self, kind: EndpointKind) -> usize {
        self.endpoints().iter().filter(|e| e.kind == kind).count()
    }

    /// Number of distinct finite nonsingular roots, real and complex.
    pub fn roots(&self) -> usize {
        self.endpoints().iter().filter(|e| e.is_root()).count()
    }

    /// Whether every path ended at a distinct nonsingular root: the target is generic, and the
    /// list holds as many isolated roots as the start set (a root the start set lacks —
    /// see [`StartReport`](super::StartReport) for how far its count can be trusted — is
    /// missing here too). A [`EndpointKind::Spurious`] endpoint counts: it is a nonsingular
    /// root of the square system, real, that an equation left out as dependent refuses, so
    /// no assembly mode is missing for it (an overconstrained mechanism, such as a planar one
    /// declared in space, can have some at every input).
    ///
    /// And the complex roots come in conjugate pairs: the inputs are real and so are the
    /// equations' coefficients, so the conjugate of a root is a root. A complex root found
    /// without its conjugate ([`Roots::unpaired`]) shows that the start set lacks roots
    /// however stable its count looked, and the list is not complete.
    ///
    /// Nor is a list tracked from a start set whose monodromy stopped at its loop cap
    /// ([`Ended::LoopCap`](super::Ended::LoopCap) in [`StartReport::ended`](super::StartReport::ended)) while
    /// roots were still coming: a Jansen leg's model, capped at 200 loops (the default until
    /// 2026-12-02), stopped at 25 of its 32 roots (`tests/integration/mechanisms/catalogue/jansen.rs`).
    /// Raise [`ModesOptions::max_loops`](super::ModesOptions::max_loops).
    pub fn is_complete(&self) -> bool {
        self.roots() + self.count(EndpointKind::Spurious) == self.paths
            && self.unpaired == 0
            && !self.capped
    }

    /// Whether the start set this list was tracked from stopped at its loop cap
    /// ([`Ended::LoopCap`](super::Ended::LoopCap)): its count, and this list, likely short.
    pub fn start_set_capped(&self) -> bool {
        self.capped
    }

    /// How many complex roots were found without their conjugate (which is a root too, at
    /// real inputs): 0 in a complete list. More than 0 says the start set is short of
    /// the generic root count; the roots found are roots all the same.
    pub fn unpaired(&self) -> usize {
        self.unpaired
    }
}
