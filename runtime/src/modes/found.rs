//! The solutions known at the base point while monodromy runs, and how one is added: a tracked
//! solution polished, compared with the known ones in tracking coordinates, and kept with its
//! orbit under the symmetries. Shared by the loops and seeds (`monodromy.rs`) and by the
//! conjugates found at a real point (`conjugation.rs`).

use super::Ended;
use super::complex::Complex;
use super::path::ParameterPath;
use super::polish::{SAME, contains, polish};
use super::symmetry::Symmetries;
use super::track::{Model, Outcome, Settings, Workspace};
use crate::mechanism::Mechanism;

/// What monodromy found.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Found {
    pub(crate) count: usize,
    pub(crate) loops: usize,
    /// Seeds tried after the first.
    pub(crate) seeds: usize,
    /// Paths that failed on some segment (their solutions are simply not used).
    pub(crate) failed_paths: usize,
    /// Loops on which every path failed.
    pub(crate) empty_loops: usize,
    /// A solution would not fit the capacity.
    pub(crate) overflow: bool,
    /// Loops run since the last one that brought a new solution (or since the seed that did).
    pub(crate) loops_since_new: usize,
    /// Seeds tried since the last new solution.
    pub(crate) seeds_since_new: usize,
    /// Random seeds (not the home) that brought solutions the loops had not reached.
    pub(crate) seed_finds: usize,
    /// Conjugation steps (see `conjugation.rs`) that brought solutions.
    pub(crate) conjugate_finds: usize,
    /// The last new solution came from a random seed or from the loops that followed one.
    pub(crate) last_after_seed: bool,
    /// Solutions known when the first loops settled.
    pub(crate) first_settled: usize,
    /// How the run ended.
    pub(crate) ending: Ended,
    /// The fewest solutions one seed brought with the loops that followed it.
    pub(crate) smallest: usize,
    /// The run of fruitless fresh seeds the last stop required.
    pub(crate) seeds_needed: usize,
}

/// Tracks a seed solution `(v, p)` to `p0` and adds it to the known solutions; `true` if it
/// was new.
#[allow(clippy::too_many_arguments)]
pub(super) fn carry<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    model: &Model<'_, S, N>,
    ws: &mut Workspace<N>,
    (v, p): ([Complex; N], [Complex; M]),
    p0: &[Complex; M],
    sym: &Symmetries,
    out: &mut [[Complex; N]; K],
    orbit: &mut [usize; K],
    found: &mut Found,
) -> bool {
    let mut v = model.enter(&v);
    let path = ParameterPath::new(p, *p0, Complex::ONE);
    let reached = model.track(&path, &mut v, ws, &Settings::DEFAULT).outcome == Outcome::Reached;
    if !reached || !polish(model, &mut v, p0, ws, true) {
        found.failed_paths += 1;
        return false;
    }
    add(model, p0, sym, out, orbit, found, v, ws)
}

/// Adds `v` (tracking coordinates) to the known solutions if it is new and finite, with its
/// orbit under the symmetries; `true` if it was new. Compared in tracking coordinates: far-out
/// roots are accurate there, not in v.
#[allow(clippy::too_many_arguments)]
pub(super) fn add<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    model: &Model<'_, S, N>,
    p0: &[Complex; M],
    sym: &Symmetries,
    out: &mut [[Complex; N]; K],
    orbit: &mut [usize; K],
    found: &mut Found,
    v: [Complex; N],
    ws: &mut Workspace<N>,
) -> bool {
    if !(model.size(&v) <= 1e8) || contains(model, known(out, found), &v, SAME) {
        return false;
    }
    if found.count >= K {
        found.overflow = true;
        return false;
    }
    let first = found.count;
    out[first] = v;
    found.count += 1;
    close(model, p0, sym, out, orbit, found, first, ws);
    true
}

/// The roots found so far (`found.count` never exceeds K: [`add`] and [`close`] stop there).
fn known<'a, const N: usize, const K: usize>(
    out: &'a [[Complex; N]; K],
    found: &Found,
) -> &'a [[Complex; N]] {
    &out[..found.count.min(K)]
}

/// Completes the orbit of root `first` (the last one known) under the symmetries: the images of
/// every member under every symmetry until nothing new comes (they commute, so at most 2^k
/// members for k symmetries); each image a root itself (checked, see [`Symmetries::apply`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn close<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    model: &Model<'_, S, N>,
    p0: &[Complex; M],
    sym: &Symmetries,
    out: &mut [[Complex; N]; K],
    orbit: &mut [usize; K],
    found: &mut Found,
    first: usize,
    ws: &mut Workspace<N>,
) {
    // `first` and every `j` below are under `found.count` ≤ K; `get` lets the no-panic proof
    // see that too.
    if let Some(o) = orbit.get_mut(first) {
        *o = first;
    }
    let mut j = first;
    while j < found.count {
        for s in 0..sym.count() {
            let Some(z) = out.get(j) else { return };
            let Some(w) = sym.apply(s, model, z, p0, ws) else {
                continue;
            };
            if !(model.size(&w) <= 1e8) || contains(model, known(out, found), &w, SAME) {
                continue;
            }
            if found.count >= K {
                found.overflow = true;
                return;
            }
            out[found.count] = w;
            orbit[found.count] = first;
            found.count += 1;
        }
        j += 1;
    }
}
