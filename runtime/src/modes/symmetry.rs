//! Symmetries of the equations: maps of v that take every root to another root at the same
//! parameters, such as a leg of Tsai's 3-UPU turned half a turn about its own axis
//! ([`Mechanism::symmetry`]). Where the generator offers candidates, monodromy keeps those that
//! map its first (generic) root to a different root and, for every root it finds, adds the whole
//! orbit under them at once — a root and its images are then found together rather than each
//! by chance of a loop — and carries one root per orbit around its loops: a loop commutes with
//! a symmetry of the family, so the images of the others follow from it.

use super::complex::Complex;
use super::polish::{SAME, contains, polish};
use super::track::{Model, Workspace};
use crate::mechanism::Mechanism;

/// At most this many candidates are looked at (orbits of up to 2¹⁶ roots).
pub(crate) const MAX: usize = 16;

/// The largest first Newton correction (weighted) at which the image of the generic seed counts
/// as a root: the seed is converged far below it, and an exact symmetry keeps it there.
const SEED_ROOT: f64 = 1e-8;

/// The largest first Newton correction (weighted) at which the image of a root found later
/// counts as a root (not a point in another root's basin): the accuracy [`polish`] accepts for
/// roots far out.
const IMAGE_ROOT: f64 = super::polish::FLOOR;

/// The candidates kept: indices into [`Mechanism::symmetry`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct Symmetries {
    kept: [u8; MAX],
    count: usize,
}

impl Symmetries {
    /// No symmetry (monodromy as without candidates).
    pub(crate) const NONE: Symmetries = Symmetries {
        kept: [0; MAX],
        count: 0,
    };

    /// The candidates that map the root `z` (tracking coordinates) at the generic parameters
    /// `p` to a different root: numerically, Newton's first correction from the image below
    /// [`SEED_ROOT`] of the scale, and the image not within [`SAME`] of `z`.
    pub(crate) fn detect<S: Mechanism<N, M>, const N: usize, const M: usize>(
        model: &Model<'_, S, N>,
        z: &[Complex; N],
        p: &[Complex; M],
        ws: &mut Workspace<N>,
    ) -> Symmetries {
        let mut out = Symmetries::NONE;
        for k in 0..S::SYMMETRIES.min(MAX) {
            let Some(w) = image(model, k, z, p, ws, SEED_ROOT) else {
                continue;
            };
            if !contains(model, &[*z], &w, SAME) {
                out.kept[out.count] = k as u8;
                out.count += 1;
            }
        }
        out
    }

    /// How many were kept.
    pub(crate) fn count(&self) -> usize {
        self.count
    }

    /// The image of the root `z` (tracking coordinates) at `p` under kept symmetry `i`, refined;
    /// `None` if it is not a nonsingular root itself (the symmetry does not hold on that root's
    /// component).
    pub(crate) fn apply<S: Mechanism<N, M>, const N: usize, const M: usize>(
        &self,
        i: usize,
        model: &Model<'_, S, N>,
        z: &[Complex; N],
        p: &[Complex; M],
        ws: &mut Workspace<N>,
    ) -> Option<[Complex; N]> {
        let k = *self.kept.get(i)?;
        image(model, usize::from(k), z, p, ws, IMAGE_ROOT)
    }
}

/// Candidate `k` applied to `z`, if Newton's first correction from the image is at most `tol`
/// (weighted) and it then polishes as a nonsingular root.
fn image<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    k: usize,
    z: &[Complex; N],
    p: &[Complex; M],
    ws: &mut Workspace<N>,
    tol: f64,
) -> Option<[Complex; N]> {
    let v = model.leave(z);
    let mut w = v;
    model.sys.symmetry(k, &v, p, &mut w);
    let mut w = model.enter(&w);
    if !w.iter().all(|c| c.is_finite()) {
        return None;
    }
    let (values, lu) = ws.scratch();
    if !model.factor(&w, p, values, lu) || !(model.norm(&model.newton(lu, &w, p), &w) <= tol) {
        return None;
    }
    polish(model, &mut w, p, ws, true).then_some(w)
}
