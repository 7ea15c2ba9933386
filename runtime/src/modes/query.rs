//! A query: every root at given inputs, by a parameter homotopy from the start set.

use super::complex::Complex;
use super::endpoint;
use super::path::ParameterPath;
use super::polish::{SAME, contains};
use super::roots::{Endpoint, EndpointKind, RealRoot, Roots};
use super::track::{Model, Settings, Workspace};
use super::{AllModes, Ended, ModesError};
use crate::mechanism::Mechanism;

impl<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize> AllModes<S, N, M, K> {
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
        out.unpaired = 0;
        out.capped = self.report.ended == Ended::LoopCap;
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
        out.unpaired = self.unpaired(out);
        Ok(())
    }

    /// Tracks start `i` along `path` and classifies its end: first in affine coordinates (a
    /// third cheaper per step, and enough for every path that stays within reach of double
    /// precision), then, if it did not end at a regular root, in projective coordinates, then
    /// with small steps. (At a target with fewer roots than generic it ends as it did.)
    pub(super) fn retried_endpoint(
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
                pose: crate::pose::pose_from_unknowns(&self.sys, &v),
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
