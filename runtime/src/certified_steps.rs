//! Certified tracking: a chain of parametric Krawczyk certificates ([`certify_step`]) proving
//! that each step of a sequence of solutions kept its branch, with a step that does not pass
//! split into shorter ones.
//!
//! A step certificate proves that for every input on the segment one root, and only one, lies
//! in its box. That the root in the box at the step's start is the root the chain came along,
//! and not another one the box happens to hold, needs an enclosure of that root inside the box:
//! the chain keeps one (from [`certify`] at its first point, then from each step's certificate,
//! which encloses the root at the step's end) and checks it against the next box.

use crate::certify::{CertifyError, certify, certify_step};
use crate::interval::Interval;
use crate::mechanism::Mechanism;

/// Pieces a tracked step may be split into, at most (in halves, then quarters, …).
const MAX_PIECES: u32 = 64;
/// How often a tracked step's piece may be halved: pieces down to 1/2⁸ of the step.
const MAX_DEPTH: usize = 8;
/// For a whole continuation path ([`crate::certified_path::arc_length_certified`]): pieces, and halvings
/// (down to 1/2³² of the segment, for paths that end near a singularity).
pub(crate) const PATH_PIECES: u32 = 4096;
pub(crate) const PATH_DEPTH: usize = 32;
/// Newton iterations for the root at a split point (the certificate checks it).
const SPLIT_NEWTON: usize = 8;

/// What certification proved about one step of a tracked sequence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepProof {
    /// The root at the new sample lies on one branch with the root at the previous sample,
    /// without a singularity of ∂F/∂v between them: the joint segment was covered by `pieces`
    /// parametric Krawczyk certificates, chained, whose smallest radius of uniqueness was
    /// `radius`; the root at the new sample is within `error_bound` of the given point in
    /// every coordinate (a proven bound, from the last piece's enclosure).
    Proven {
        /// How many certificates cover the joint segment.
        pieces: u32,
        /// The smallest radius of uniqueness among them, in the unknowns' units.
        radius: f64,
        /// A proven bound on the distance from the given point to the root, in every
        /// coordinate.
        error_bound: f64,
    },
    /// Not proven (which does not mean the branch changed): `reason` is why the last piece
    /// tried failed, after `pieces` pieces had passed.
    Unproven {
        /// How many pieces had been certified before the one that failed.
        pieces: u32,
        /// Why that piece failed.
        reason: CertifyError,
    },
}

impl StepProof {
    /// Whether the step is [`StepProof::Proven`].
    pub fn is_proven(&self) -> bool {
        matches!(self, StepProof::Proven { .. })
    }
}

/// Proves step after step that a sequence of solutions stays on one branch.
///
/// ```
/// use linkage::{newton_raphson, CertifiedSteps, Options, Pose, Start};
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
/// # let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = linkage::Mechanism::inverse(&rps, &v0, &[0.0; 3]).unwrap();
/// # let start = Start::new(&rps, v0, x0).unwrap();
/// let mut chain = CertifiedSteps::new();
/// let (mut v, mut x) = (*start.v(), x0);
/// for k in 1..=20 {
///     // Legs lengthened 1 mm per step, each row solved from the previous one by Newton.
///     let next = x0.map(|l| l + k as f64);
///     let from = Start::new(&rps, v, x).unwrap();
///     let sol = newton_raphson(&rps, &from, &next, &Options::TIGHT).unwrap();
///     assert!(chain.prove(&rps, (&v, &x), (&sol.v, &next)).is_proven());
///     (v, x) = (sol.v, next);
/// }
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifiedSteps<const N: usize, const M: usize> {
    /// The inputs at the end of the last proven step, and an enclosure of the root there on
    /// the chain's branch.
    end: Option<([f64; M], [Interval; N])>,
}

impl<const N: usize, const M: usize> Default for CertifiedSteps<N, M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize, const M: usize> CertifiedSteps<N, M> {
    /// A chain with no step yet: its first step starts from a root certified on its own.
    pub fn new() -> Self {
        CertifiedSteps { end: None }
    }

    /// Proves that the root near `v1` at `x1` is on one branch with the root near `v0` at
    /// `x0`: the step's certificate, or those of the halves, quarters, … (at most
    /// 64 pieces) when it does not pass whole; the roots at the split points are found by
    /// Newton's method and need no other check than the certificates. When `(v0, x0)` is not
    /// where the last proven step ended, its root is first certified on its own.
    pub fn prove<S: Mechanism<N, M>>(
        &mut self,
        sys: &S,
        (v0, x0): (&[f64; N], &[f64; M]),
        (v1, x1): (&[f64; N], &[f64; M]),
    ) -> StepProof {
        // The last step's enclosure serves if this step starts where it ended.
        let known = self
            .end
            .filter(|(x, e)| x == x0 && e.iter().zip(v0).all(|(e, &v)| e.contains(v)))
            .map(|(_, e)| e);
        let (proof, enclosure) =
            prove::<S, N, M, MAX_DEPTH>(sys, known, (v0, x0), (v1, x1), MAX_PIECES);
        // An unproven step leaves the chain where it was: a retry from the same point still
        // chains from it.
        if let Some(e) = enclosure {
            self.end = Some((*x1, e));
        }
        proof
    }

    /// Forgets the chain: the next step starts from a root certified on its own.
    pub fn reset(&mut self) {
        self.end = None;
    }
}

/// Whether box `a` lies in box `b`.
fn within<const N: usize>(a: &[Interval; N], b: &[Interval; N]) -> bool {
    a.iter().zip(b).all(|(a, b)| b.lo <= a.lo && a.hi <= b.hi)
}

/// The root of F(·, x) by Newton's method from `v`, if it settles.
fn newton<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    mut v: [f64; N],
    x: &[f64; M],
) -> Option<[f64; N]> {
    let mut fac = sys.new_factor();
    let scale = v.iter().fold(1.0f64, |m, a| m.max(a.abs()));
    for _ in 0..SPLIT_NEWTON {
        let mut d = [0.0; N];
        sys.residual(&v, x, &mut d);
        sys.factor(&v, x, &mut fac)?;
        sys.solve(&fac, &mut d);
        let size = d.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        if !size.is_finite() {
            return None;
        }
        for i in 0..N {
            v[i] -= d[i];
        }
        if size <= 1e-13 * scale {
            break;
        }
    }
    Some(v)
}

/// The step proof, and the enclosure of the root at `x1` to chain the next step from; at most
/// `max_pieces` pieces, each at least 1/2^DEPTH of the step.
pub(crate) fn prove<S: Mechanism<N, M>, const N: usize, const M: usize, const DEPTH: usize>(
    sys: &S,
    known: Option<[Interval; N]>,
    (v0, x0): (&[f64; N], &[f64; M]),
    (v1, x1): (&[f64; N], &[f64; M]),
    max_pieces: u32,
) -> (StepProof, Option<[Interval; N]>) {
    let unproven = |pieces, reason| (StepProof::Unproven { pieces, reason }, None);
    // An enclosure of the root at the start.
    let start = match known {
        Some(e) => e,
        None => match certify(sys, v0, x0) {
            Ok(c) => c.enclosure,
            Err(e) => return unproven(0, e),
        },
    };
    // The pieces' right ends still to reach, the nearest last.
    let mut ends = [([0.0; N], [0.0; M]); DEPTH];
    ends[0] = (*v1, *x1);
    let mut depth = 1;
    let (mut v, mut x, mut enclosure) = (*v0, *x0, start);
    let (mut pieces, mut radius) = (0u32, f64::INFINITY);
    while depth > 0 {
        // `get`, not indexing: 0 < depth ≤ DEPTH holds, and this way no panic path is left
        // for the compiler to keep (tests/no_panic); the `else` is never taken.
        let Some(&(ve, xe)) = ends.get(depth - 1) else {
            return unproven(pieces, CertifyError::NotContracting);
        };
        let reason = match certify_step(sys, (&v, &x), (&ve, &xe)) {
            Ok(c) if within(&enclosure, &c.unique_in) => {
                pieces += 1;
                radius = radius.min(c.radius);
                (v, x, enclosure) = (ve, xe, c.enclosure);
                depth -= 1;
                continue;
            }
            // The box does not hold the chain's root for certain: maybe another root's.
            Ok(_) => CertifyError::NotContracting,
            Err(e) => e,
        };
        if depth == DEPTH || pieces + depth as u32 >= max_pieces {
            return unproven(pieces, reason);
        }
        // Split: the root at the middle of the joint segment, from the middle of the two.
        let xm: [f64; M] = core::array::from_fn(|j| 0.5 * (x[j] + xe[j]));
        let guess: [f64; N] = core::array::from_fn(|i| 0.5 * (v[i] + ve[i]));
        match newton(sys, guess, &xm) {
            Some(vm) => match ends.get_mut(depth) {
                Some(end) => {
                    *end = (vm, xm);
                    depth += 1;
                }
                None => return unproven(pieces, reason),
            },
            None => return unproven(pieces, reason),
        }
    }
    // The enclosure holds the root at x1: its farthest face from v1 bounds v1's error.
    let error_bound = (0..N).fold(0.0f64, |m, i| {
        let e = enclosure[i];
        m.max((v1[i] - e.lo).next_up())
            .max((e.hi - v1[i]).next_up())
    });
    (
        StepProof::Proven {
            pieces,
            radius,
            error_bound,
        },
        Some(enclosure),
    )
}
