//! Tracking one solution path of `F(v, p(s)) = 0` from s = 0 to s = 1 in complex arithmetic:
//! an adaptive predictor–corrector with one factorisation of B per step.
//!
//! - Predictor: the cubic Taylor polynomial of the path v(s), its coefficients computed order
//!   by order from Taylor-series evaluations of the generated residual (Taylor-mode automatic
//!   differentiation, as in HomotopyContinuation.jl), solved with the factorisation of the last
//!   step.
//! - Corrector: B is factored once at the predicted point and Newton's corrections use it for
//!   every iteration (the chord method). It is also the acceptance test: a step counts only if
//!   the corrections contract fast from the first on (ratio ≤ ¼) down to the path accuracy. A
//!   fast contraction means the predicted point lies well inside the quadratic basin of the
//!   root it converges to, so it cannot be another path's root unless the two paths are closer
//!   than the prediction error — which the step size keeps below a fraction of the basin radius
//!   1/ω, ω being Newton's constant measured from the contraction.
//! - Step size: from the observed prediction error (the first correction) against the target,
//!   for a fourth-order method; halved on rejection.
//!
//! The factorisation at the predicted point also serves the next predictor: it is B at a point
//! within the prediction error of the accepted one, which perturbs the Taylor coefficients by
//! about ω times that error, far below what the step-size control tolerates.
//!
//! All norms are weighted: `max_i |Δ_i| / max(scale, |v_i|)`, relative for large coordinates
//! and absolute (in units of the mechanism's size) for small ones.

use super::complex::Complex;
use super::path::ParameterPath;
use super::sparse_lu::{Border, Lu, Plan};
use super::taylor::Series;
use crate::mechanism::Mechanism;

/// Tolerances and limits of one path.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Settings {
    /// Newton's last correction must be below this for a step to count (weighted norm).
    pub(crate) tol: f64,
    /// Before the last step: a step also counts when the corrections contract so fast that
    /// the next one would be below this (the path is followed to this accuracy; the last step
    /// and the polish that follows reach the root to full precision).
    pub(crate) mid_tol: f64,
    /// A step whose corrections contracted fast to below this, and then stalled or ran out of
    /// iterations, also counts: the floor that rounding sets where B is ill-conditioned.
    pub(crate) limit: f64,
    /// The prediction error aimed at (weighted norm).
    pub(crate) tau: f64,
    /// The largest prediction error a step may have and still count.
    pub(crate) max_error: f64,
    /// Steps before giving up.
    pub(crate) max_steps: usize,
    /// A path whose weighted size exceeds this diverges.
    pub(crate) max_norm: f64,
    /// Newton's corrections far out from the residual in double-double (see `extended.rs`).
    pub(crate) extended: bool,
}

impl Settings {
    pub(crate) const DEFAULT: Settings = Settings {
        tol: 1e-8,
        mid_tol: 1e-5,
        limit: 1e-6,
        tau: 3e-2,
        max_error: 1e-1,
        max_steps: 2000,
        max_norm: 1e8,
        extended: false,
    };

    /// For the starts of places still empty after every γ's refill (see `refill.rs`): the
    /// corrections beyond `extended::WIDE_BEYOND` times the scale from the residual in
    /// double-double, whose rounding floor lies far below f64's; the steps between those of
    /// the default and the careful settings.
    pub(crate) const FAR: Settings = Settings {
        extended: true,
        tau: 1e-3,
        max_error: 1e-2,
        max_steps: 3000,
        ..Settings::CAREFUL
    };

    /// Smaller predictions: for paths retracked after they ended on another path's root.
    pub(crate) const CAREFUL: Settings = Settings {
        tol: 1e-10,
        mid_tol: 1e-10,
        limit: 1e-8,
        tau: 1e-6,
        max_error: 1e-4,
        max_steps: 20000,
        max_norm: 1e8,
        extended: false,
    };
}

/// How a path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// s = 1 reached; the solution is in `v`.
    Reached,
    /// |v| grew beyond [`Settings::max_norm`].
    Diverged,
    /// B became singular to working precision.
    Singular,
    /// The step size fell below 1e-14 (typically near a singular endpoint).
    StepTooSmall,
    /// [`Settings::max_steps`] steps without reaching s = 1.
    TooManySteps,
}

/// The result of tracking one path.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tracked {
    pub(crate) outcome: Outcome,
    /// Where the path stopped.
    pub(crate) s: f64,
    pub(crate) steps: usize,
}

/// The mechanism with what the tracker needs to evaluate and factor B.
pub(crate) struct Model<'a, S, const N: usize> {
    pub(crate) sys: &'a S,
    pub(crate) plan: &'a Plan<N>,
    pub(crate) pattern: &'a [(usize, usize)],
    pub(crate) scale: f64,
    /// Projective coordinates, if the system allows them.
    pub(crate) chart: Option<&'a Chart<N>>,
}

/// A projective chart: the tracker works on `z = v / (1 + c·v)`, so `v = z / w` with
/// `w = 1 − c·z`, and on the homogenised equations `G_i(z) = w^(d_i) F_i(z / w)` (d_i the degree
/// of F_i in v). Roots far out in v — |v| of 10⁵ times the mechanism's size occur among the
/// complex roots of a general 6-6 platform — are ordinary points near `w = 0` in z, where the
/// affine equations are so ill-conditioned that rounding stalls Newton's method. The Jacobian
/// `∂G/∂z = D (B + r cᵀ)` with `D = diag(w^(d_i − 1))` and `r = B v − d∘F` is factored as the
/// bordered matrix `[[D B, D r], [cᵀ, −1]]`, which keeps B's sparsity and its static pivots
/// (D scales whole rows).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Chart<const N: usize> {
    pub(crate) c: [Complex; N],
    pub(crate) degree: [u8; N],
}

impl<S, const N: usize> Clone for Model<'_, S, N> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<S, const N: usize> Copy for Model<'_, S, N> {}

/// Scratch space of the tracker: Jacobian values and the factorisation.
pub(crate) struct Workspace<const N: usize> {
    values: [[Complex; N]; N],
    lu: Lu<N>,
}

impl<const N: usize> Workspace<N> {
    pub(crate) const fn new() -> Self {
        Workspace {
            values: [[Complex::ZERO; N]; N],
            lu: Lu::new(),
        }
    }

    /// Jacobian storage and one factorisation, for Newton outside the tracker.
    pub(crate) fn scratch(&mut self) -> (&mut [[Complex; N]; N], &mut Lu<N>) {
        (&mut self.values, &mut self.lu)
    }
}

/// `x^d` for a small power.
#[inline(always)]
fn powi(x: Complex, d: u8) -> Complex {
    let mut r = Complex::ONE;
    for _ in 0..d {
        r *= x;
    }
    r
}

impl<S, const N: usize> Model<'_, S, N> {
    /// The weighted max-norm of a correction `d` at `z` (tracking coordinates).
    pub(crate) fn norm(&self, d: &[Complex; N], z: &[Complex; N]) -> f64 {
        let mut m = 0.0f64;
        for i in 0..N {
            m = m.max(d[i].abs_max() / self.scale.max(z[i].abs_max()));
        }
        m
    }

    /// `w = 1 − c·z` (1 without a chart).
    pub(crate) fn w(&self, z: &[Complex; N]) -> Complex {
        match self.chart {
            Some(ch) => {
                let mut w = Complex::ONE;
                for i in 0..N {
                    w -= ch.c[i] * z[i];
                }
                w
            }
            None => Complex::ONE,
        }
    }

    /// Tracking coordinates of a point v.
    pub(crate) fn enter(&self, v: &[Complex; N]) -> [Complex; N] {
        match self.chart {
            Some(ch) => {
                let mut d = Complex::ONE;
                for i in 0..N {
                    d += ch.c[i] * v[i];
                }
                let inv = d.recip();
                v.map(|x| x * inv)
            }
            None => *v,
        }
    }

    /// The point v of tracking coordinates z (infinite entries where w = 0).
    pub(crate) fn leave(&self, z: &[Complex; N]) -> [Complex; N] {
        match self.chart {
            Some(_) => {
                let inv = self.w(z).recip();
                z.map(|x| x * inv)
            }
            None => *z,
        }
    }

    /// The size of v in units of the scale (infinite at w = 0).
    pub(crate) fn size(&self, z: &[Complex; N]) -> f64 {
        let m = z.iter().fold(0.0f64, |m, c| m.max(c.abs_max())) / self.scale;
        match self.chart {
            Some(_) => m / self.w(z).abs(),
            None => m,
        }
    }
}

impl<'a, S, const N: usize> Model<'a, S, N> {
    /// The equations in tracking coordinates: F(z, p), or G(z, p) with a chart.
    pub(crate) fn residual<const M: usize>(
        &self,
        z: &[Complex; N],
        p: &[Complex; M],
    ) -> [Complex; N]
    where
        S: Mechanism<N, M>,
    {
        let mut f = [Complex::ZERO; N];
        match self.chart {
            None => self.sys.residual_in(z, p, &mut f),
            Some(ch) => {
                let w = self.w(z);
                let inv = w.recip();
                let v = z.map(|x| x * inv);
                self.sys.residual_in(&v, p, &mut f);
                for i in 0..N {
                    f[i] *= powi(w, ch.degree[i]);
                }
            }
        }
        f
    }

    /// Evaluates the Jacobian at (z, p) and factors it into `lu`.
    pub(crate) fn factor<const M: usize>(
        &self,
        z: &[Complex; N],
        p: &[Complex; M],
        values: &mut [[Complex; N]; N],
        lu: &mut Lu<N>,
    ) -> bool
    where
        S: Mechanism<N, M>,
    {
        let flat = values.as_flattened_mut();
        let Some(ch) = self.chart else {
            self.sys.jacobian_in(z, p, flat);
            return lu.factor(self.plan, flat, None);
        };
        let w = self.w(z);
        let inv = w.recip();
        let v = z.map(|x| x * inv);
        self.sys.jacobian_in(&v, p, flat);
        let mut f = [Complex::ZERO; N];
        self.sys.residual_in(&v, p, &mut f);
        // r = B v − d∘F, then rows scaled by w^(d − 1).
        let mut r = [Complex::ZERO; N];
        // The pattern's entries are below N (the plan refused it otherwise).
        for (&(row, col), &b) in self.pattern.iter().zip(flat.iter()) {
            if let (Some(r), Some(v)) = (r.get_mut(row), v.get(col)) {
                *r += b * *v;
            }
        }
        let mut scale = [Complex::ONE; N];
        for i in 0..N {
            let d = ch.degree[i];
            r[i] -= f[i].scale(d as f64);
            scale[i] = powi(w, d.saturating_sub(1));
            r[i] *= scale[i];
        }
        for (&(row, _), b) in self.pattern.iter().zip(flat.iter_mut()) {
            if let Some(s) = scale.get(row) {
                *b *= *s;
            }
        }
        let border = Border {
            col: r,
            row: ch.c,
            corner: Complex::real(-1.0),
        };
        lu.factor(self.plan, flat, Some(&border))
    }

    /// The Newton correction −J⁻¹ G(z, p) with a factorisation of J.
    pub(crate) fn newton<const M: usize>(
        &self,
        lu: &Lu<N>,
        z: &[Complex; N],
        p: &[Complex; M],
    ) -> [Complex; N]
    where
        S: Mechanism<N, M>,
    {
        self.correction(lu, self.residual(z, p))
    }

    /// The Newton correction with the residual evaluated in double-double.
    pub(crate) fn newton_wide<const M: usize>(
        &self,
        lu: &Lu<N>,
        z: &[Complex; N],
        p: &[Complex; M],
    ) -> [Complex; N]
    where
        S: Mechanism<N, M>,
    {
        let chart = self.chart.map(|ch| (&ch.c, &ch.degree));
        self.correction(lu, super::extended::residual(self.sys, chart, z, p))
    }

    /// −J⁻¹ G for the residual `f` = G(z, p), with a factorisation of J.
    fn correction(&self, lu: &Lu<N>, mut f: [Complex; N]) -> [Complex; N] {
        for x in f.iter_mut() {
            *x = -*x;
        }
        lu.solve(self.plan, &mut f);
        f
    }

    /// Taylor coefficients z₁, z₂, z₃ of the path through `z` at `s` (J at z factored in `lu`).
    fn taylor<const M: usize>(
        &self,
        lu: &Lu<N>,
        path: &ParameterPath<M>,
        s: f64,
        z: &[Complex; N],
    ) -> [[Complex; N]; 3]
    where
        S: Mechanism<N, M>,
    {
        let mut pc = [[Complex::ZERO; M]; 4];
        path.taylor(s, &mut pc);
        let mut out = [[Complex::ZERO; N]; 3];
        // Order k: the coefficient of h^k in G(z + z₁h + … + z_(k−1)h^(k−1), p(h)) is
        // J z_k + g_k with g_k from the known coefficients, so z_k = −J⁻¹ g_k.
        macro_rules! order {
            ($k:literal) => {{
                type T = Series<{ $k + 1 }>;
                let mut zs = [T::ZERO; N];
                for i in 0..N {
                    zs[i].0[0] = z[i];
                    for (j, known) in out.iter().enumerate().take($k - 1) {
                        zs[i].0[j + 1] = known[i];
                    }
                }
                let mut xs = [T::ZERO; M];
                for i in 0..M {
                    for j in 0..=$k {
                        xs[i].0[j] = pc[j][i];
                    }
                }
                let mut f = [T::ZERO; N];
                match self.chart {
                    None => self.sys.residual_in(&zs, &xs, &mut f),
                    Some(ch) => {
                        // w(h) = 1 − c·z(h); v(h) = z(h) / w(h); G = w(h)^d F(v(h)).
                        let mut w = T::constant(Complex::ONE);
                        for i in 0..N {
                            w = w - zs[i].times(ch.c[i]);
                        }
                        let inv = w.recip();
                        let vs = zs.map(|x| x * inv);
                        self.sys.residual_in(&vs, &xs, &mut f);
                        for i in 0..N {
                            for _ in 0..ch.degree[i] {
                                f[i] = f[i] * w;
                            }
                        }
                    }
                }
                let mut g = [Complex::ZERO; N];
                for i in 0..N {
                    g[i] = -f[i].0[$k];
                }
                lu.solve(self.plan, &mut g);
                out[$k - 1] = g;
            }};
        }
        order!(1);
        order!(2);
        order!(3);
        out
    }

    /// Tracks `v` (a solution at p(0), in tracking coordinates) to s = 1; on
    /// [`Outcome::Reached`] `v` holds the solution at p(1) to the path accuracy, otherwise where
    /// the path stopped.
    pub(crate) fn track<const M: usize>(
        &self,
        path: &ParameterPath<M>,
        v: &mut [Complex; N],
        ws: &mut Workspace<N>,
        set: &Settings,
    ) -> Tracked
    where
        S: Mechanism<N, M>,
    {
        let mut s = 0.0f64;
        let mut steps = 0;
        let end = |outcome, s, steps| Tracked { outcome, s, steps };
        let p = path.at(0.0);
        if !self.factor(v, &p, &mut ws.values, &mut ws.lu) {
            return end(Outcome::Singular, s, steps);
        }
        let mut coeffs = self.taylor(&ws.lu, path, s, v);
        // First step: where the cubic term alone reaches the error target.
        let c3 = self.norm(&coeffs[2], v).max(1e-300);
        // `pow`, not `libm::cbrt`: cbrt reaches fma through a function pointer (chosen by CPU
        // feature), a call the optimiser cannot prove never unwinds, so the no-panic proof of
        // the query fails on it. The ratio is positive (or 0, or +inf); a first step size
        // needs no correctly rounded root.
        let mut h = libm::pow(set.tau / c3, 1.0 / 3.0).min(1.0);
        let mut omega = 0.0f64;
        loop {
            if steps >= set.max_steps {
                return end(Outcome::TooManySteps, s, steps);
            }
            steps += 1;
            let last = h >= 1.0 - s;
            if last {
                h = 1.0 - s;
            }
            let s1 = if last { 1.0 } else { s + h };
            let mut w = *v;
            for i in 0..N {
                w[i] += (coeffs[0][i] + (coeffs[1][i] + coeffs[2][i].scale(h)).scale(h)).scale(h);
            }
            let p1 = path.at(s1);
            let correction = self.correct(&mut w, &p1, ws, set, last);
            let Some((first, second)) = correction else {
                h *= 0.5;
                if h < 1e-14 {
                    return end(Outcome::StepTooSmall, s, steps);
                }
                continue;
            };
            // Newton's constant, from the first contraction when it is measurable.
            if second.is_finite() && first > 1e3 * set.tol {
                omega = 2.0 * second / (first * first);
            } else {
                omega *= 0.5;
            }
            *v = w;
            s = s1;
            // In projective coordinates a path may pass far out (or end at infinity) harmlessly.
            if self.chart.is_none() && self.size(v) > set.max_norm {
                return end(Outcome::Diverged, s, steps);
            }
            if last {
                return end(Outcome::Reached, s, steps);
            }
            coeffs = self.taylor(&ws.lu, path, s, v);
            let target = if omega > 0.0 {
                set.tau.min(0.125 / omega)
            } else {
                set.tau
            };
            let grow = if first > 0.0 {
                0.8 * libm::pow(target / first, 0.25)
            } else {
                2.0
            };
            h *= grow.clamp(0.5, 2.0);
        }
    }

    /// The chord corrector at parameters `p`: factors B at `w` and iterates `w += −B⁻¹F(w)`.
    /// `Some((first, second))` correction sizes if the step counts (see the module docs).
    fn correct<const M: usize>(
        &self,
        w: &mut [Complex; N],
        p: &[Complex; M],
        ws: &mut Workspace<N>,
        set: &Settings,
        last: bool,
    ) -> Option<(f64, f64)>
    where
        S: Mechanism<N, M>,
    {
        if !self.factor(w, p, &mut ws.values, &mut ws.lu) {
            return None;
        }
        let mut first = 0.0;
        let mut second = f64::NAN;
        let mut previous = f64::INFINITY;
        for it in 0..4 {
            let d = if set.extended && self.size(w) > super::extended::WIDE_BEYOND {
                self.newton_wide(&ws.lu, w, p)
            } else {
                self.newton(&ws.lu, w, p)
            };
            let n = self.norm(&d, w);
            if !n.is_finite() || (it == 0 && n > set.max_error) {
                return None;
            }
            if it == 0 {
                first = n;
            } else if it == 1 {
                second = n;
            }
            if n > 0.25 * previous {
                // No longer contracting fast: the rounding floor if the previous correction
                // was already small, else too far from the path.
                return (previous <= set.limit).then_some((first, second));
            }
            for i in 0..N {
                w[i] += d[i];
            }
            if n <= set.tol {
                return Some((first, second));
            }
            // Chord iterations contract linearly, at about the rate just seen.
            if it > 0 && !last && n * (n / previous) <= set.mid_tol {
                return Some((first, second));
            }
            previous = n;
        }
        (previous <= set.limit).then_some((first, second))
    }
}
