//! Paths that failed, tried again along other γ-bent paths.
//!
//! With one γ a few paths of a query can end short of a regular root: the bent path passes
//! close to a parameter where roots run off very far (a delta robot's complex roots reach 10⁶
//! times its size at some real crank angles) and the tracker stalls there. The degenerate
//! parameters are isolated points of the complex line through p₀ and the target, and another γ
//! bends the path past them elsewhere; but it also pairs the starts with the roots
//! differently, so a failed path cannot be retracked alone. Every start is tracked again
//! instead, and each root it reaches that is not yet known takes the place of a path that
//! failed.
//!
//! Any nonsingular root of the target system is an answer, whichever path reached it; and a
//! target has at most as many isolated roots as the generic count, so once every place holds a
//! distinct nonsingular root the list is complete. Only roots clearly apart from every known
//! one are added ([`APART`]), so that a far-out root reached twice with a little less accuracy
//! is not counted as two.

use super::AllModes;
use super::complex::Complex;
use super::path::ParameterPath;
use super::polish::{SAME, contains};
use super::roots::Roots;
use super::track::Workspace;
use crate::Mechanism;

/// A root reached along another γ is new only if it is this many times [`SAME`] away from
/// every known root (weighted, in tracking coordinates).
const APART: f64 = 100.0;

/// The other values of γ tried for an incomplete query: its conjugate, and the two whose
/// arguments mirror γ's within the range π/6 ≤ |θ| ≤ π/2 that `gamma` draws from (θ ↦
/// ±(2π/3 − |θ|), moved where that is γ's own argument). All stay clear of −1, where the rational path has its pole.
fn other_gammas(gamma: Complex) -> [Complex; 3] {
    let theta = libm::atan2(gamma.im, gamma.re);
    let mut mirrored = 2.0 * core::f64::consts::FRAC_PI_3 - theta.abs();
    if (mirrored - theta.abs()).abs() < 0.2 {
        // γ near e^(±iπ/3) mirrors onto itself: move the mirror image (still ≤ π/2).
        mirrored += 0.25;
    }
    let at = |t: f64| Complex::new(libm::cos(t), libm::sin(t));
    [gamma.conj(), at(mirrored), at(-mirrored)]
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize> AllModes<S, N, M, K> {
    /// If some paths of `out` ended short of a regular root: every start along the paths of
    /// the other γ in turn ([`other_gammas`]), until every place holds a root or all were tried.
    pub(super) fn refill_failed(
        &self,
        target: &[Complex; M],
        out: &mut Roots<N, K>,
        ws: &mut Workspace<N>,
    ) {
        for gamma in other_gammas(self.gamma) {
            if out.is_complete() {
                return;
            }
            let path = ParameterPath::new(self.p0, *target, gamma);
            self.refill(&path, target, out, ws);
        }
    }

    /// Tracks every start along `path` (another γ) and puts each new nonsingular root in the
    /// place of a path that did not end at one, until none is left.
    fn refill(
        &self,
        path: &ParameterPath<M>,
        target: &[Complex; M],
        out: &mut Roots<N, K>,
        ws: &mut Workspace<N>,
    ) {
        let model = self.model();
        for i in 0..self.count {
            let Some(slot) = (0..self.count).find(|&j| !out.endpoints[j].is_root()) else {
                return;
            };
            let e = self.retried_endpoint(path, i, target, ws);
            if !e.is_root() {
                continue;
            }
            let known = out.endpoints[..self.count]
                .iter()
                .any(|k| k.is_root() && contains(&model, &[k.z], &e.z, APART * SAME));
            if known {
                continue;
            }
            let steps = out.endpoints[slot].steps;
            out.endpoints[slot] = e;
            out.endpoints[slot].steps += steps;
        }
    }
}
