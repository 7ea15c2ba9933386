//! Making a start set: the seed and monodromy ([`AllModes::new`]), start solutions stored
//! before ([`AllModes::from_starts`]), and the set moved near given inputs
//! ([`AllModes::recenter`]).

use super::complex::Complex;
use super::inputs::Inputs;
use super::monodromy::{self, Stopping};
use super::path::ParameterPath;
use super::polish::{self, SAME, contains};
use super::rng::Rng;
use super::sparse_lu::Plan;
use super::track::{self, Chart, Settings, Workspace};
use super::{AllModes, ModesError, ModesOptions, StartReport, seed, symmetry};
use crate::mechanism::Mechanism;

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
            conjugate_finds: found.conjugate_finds,
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
}
