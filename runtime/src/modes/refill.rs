//! Paths that failed, tried again: by conjugation, along other γ-bent paths, and in
//! double-double far out.
//!
//! With one γ a few paths of a query can end short of a regular root: the bent path passes
//! close to a parameter where roots run off very far (a delta robot's complex roots reach 10⁷
//! times its size at crank angles close to one another) and the tracker stalls there. The
//! degenerate parameters are isolated points of the complex line through p₀ and the target,
//! and another γ bends the path past them elsewhere; but it also pairs the starts with the
//! roots differently, so a failed path cannot be retracked alone. Every start is tracked again
//! instead, and each root it reaches that is not yet known takes the place of a path that
//! failed. In order, until every place holds a root:
//!
//! 1. the conjugates of the complex roots found (the target is real: they are roots too);
//! 2. every start along each other γ ([`other_gammas`]), then conjugates again;
//! 3. the failed places' own starts along γ and the others with `Settings::FAR` (corrections
//!    from the residual in double-double far out, where f64's rounding floor stalls Newton),
//!    then conjugates again.
//!
//! Any nonsingular root of the target system is an answer, whichever path reached it; and a
//! target has at most as many isolated roots as the generic count, so once every place holds a
//! distinct nonsingular root the list is complete. Only roots clearly apart from every known
//! one are added ([`known`]), so that a far-out root reached twice with a little less accuracy
//! is not counted as two.

use super::AllModes;
use super::complex::Complex;
use super::path::ParameterPath;
use super::polish::{SAME, contains};
use super::roots::{Endpoint, EndpointKind, Roots};
use super::track::{Model, Settings, Workspace};
use crate::mechanism::Mechanism;

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

/// Whether a root (z in tracking coordinates, v) is one of the roots of `out`: within
/// [`APART`] × [`SAME`] in tracking coordinates and within 1 % in v (weighted). The second test
/// tells apart far-out roots near one point at infinity, which projective coordinates put
/// within 10⁻⁷ of one another (a delta's roots 10⁷ times its size away).
fn known<S, const N: usize, const K: usize>(
    model: &Model<'_, S, N>,
    out: &Roots<N, K>,
    z: &[Complex; N],
    v: &[Complex; N],
) -> bool {
    out.endpoints().iter().any(|k| {
        k.is_root()
            && contains(model, &[k.z], z, APART * SAME)
            && (0..N).all(|i| (v[i] - k.v[i]).abs_max() <= 1e-2 * model.scale.max(k.v[i].abs_max()))
    })
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize> AllModes<S, N, M, K> {
    /// If some paths of `out` ended short of a regular root: the three stages of the module
    /// docs, until every place holds a root or all were tried.
    pub(super) fn refill_failed(
        &self,
        target: &[Complex; M],
        out: &mut Roots<N, K>,
        ws: &mut Workspace<N>,
    ) {
        self.conjugates(target, out);
        for gamma in other_gammas(self.gamma) {
            if out.is_complete() {
                return;
            }
            let path = ParameterPath::new(self.p0, *target, gamma);
            self.refill(&path, target, out, ws);
            self.conjugates(target, out);
        }
        // Still short: the failed places' own starts, with the residual in double-double where
        // the path is far out (`Settings::FAR`), along γ and then the others.
        for gamma in [self.gamma].into_iter().chain(other_gammas(self.gamma)) {
            if out.is_complete() {
                return;
            }
            let path = ParameterPath::new(self.p0, *target, gamma);
            let model = self.model();
            for j in 0..self.count() {
                if out.endpoints[j].is_root() {
                    continue;
                }
                let mut e = self.endpoint(&model, &path, j, target, &Settings::FAR, ws);
                if e.is_root() && !known(&model, out, &e.z, &e.v) {
                    e.steps += out.endpoints[j].steps;
                    out.endpoints[j] = e;
                } else {
                    out.endpoints[j].steps += e.steps;
                }
            }
            self.conjugates(target, out);
        }
    }

    /// The target's parameters are real and so are the equations' coefficients, so the complex
    /// conjugate of a root is a root, as regular as it is (B(v̄) is the conjugate of B(v)).
    /// Puts each conjugate not yet known in the place of a path that did not end at a root.
    /// Not polished again: Newton from a point already at its rounding floor cannot tell it
    /// from a singular root (see `polish`), which is what far-out roots are; instead the
    /// residual at the conjugate must be the conjugate's (at most twice the root's: the
    /// evaluation is exactly symmetric in IEEE arithmetic, but a hand-written `residual_in`
    /// need not be), which also catches equations with complex coefficients.
    fn conjugates(&self, target: &[Complex; M], out: &mut Roots<N, K>) {
        let model = self.model();
        let count = self.count();
        for i in 0..count {
            let Some(slot) = (0..count).find(|&j| !out.endpoints[j].is_root()) else {
                return;
            };
            let root = out.endpoints[i];
            if root.kind != EndpointKind::Complex {
                continue;
            }
            let v = root.v.map(Complex::conj);
            let z = model.enter(&v);
            let known = known(&model, out, &z, &v);
            if known {
                continue;
            }
            let mut f = [Complex::ZERO; N];
            self.sys.residual_in(&v, target, &mut f);
            let residual = f.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            if !(residual <= 2.0 * root.residual) {
                continue;
            }
            let steps = out.endpoints[slot].steps;
            out.endpoints[slot] = Endpoint {
                v,
                z,
                residual,
                steps,
                ..root
            };
        }
    }

    /// The complex roots of `out` whose conjugate is not among its roots. At real inputs
    /// that conjugate is a root too, so each one counted is a root the start set lacks.
    pub(super) fn unpaired(&self, out: &Roots<N, K>) -> usize {
        let model = self.model();
        out.endpoints()
            .iter()
            .filter(|e| e.kind == EndpointKind::Complex)
            .filter(|e| {
                let v = e.v.map(Complex::conj);
                !known(&model, out, &model.enter(&v), &v)
            })
            .count()
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
        let count = self.count();
        for i in 0..count {
            let Some(slot) = (0..count).find(|&j| !out.endpoints[j].is_root()) else {
                return;
            };
            let e = self.retried_endpoint(path, i, target, ws);
            if !e.is_root() {
                continue;
            }
            let known = known(&model, out, &e.z, &e.v);
            if known {
                continue;
            }
            let steps = out.endpoints[slot].steps;
            out.endpoints[slot] = e;
            out.endpoints[slot].steps += steps;
        }
    }
}
