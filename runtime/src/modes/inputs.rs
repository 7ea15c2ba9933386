//! Which inputs are angles, and random complex input points of the right size for each kind.
//!
//! A revolute input q enters the equations through cos q and sin q; at a complex q these grow
//! like e^|Im q|. Random inputs the size of the mechanism (hundreds of millimetres) are right
//! for lengths but, for an angle, put cos q near 10⁸⁰: the seeding's Newton walk then fails
//! at every attempt, which used to be reported as an architecture-singular geometry (the delta
//! robot). Angles get a real part anywhere on the turn and an imaginary part of order one.

use super::complex::Complex;
use super::rng::Rng;
use crate::mechanism::Mechanism;

/// The kind of each input and the length scale.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Inputs<const M: usize> {
    /// Input j is an angle: it enters through cos and sin (F is 2π-periodic in it, or the
    /// generated kernels turn by it, as by a helical pair's angle, which also enters linearly
    /// through its slide).
    pub(crate) angular: [bool; M],
    pub(crate) scale: f64,
}

impl<const M: usize> Inputs<M> {
    /// Tells angles from lengths by periodicity: F(v, x + 2π e_j) = F(v, x) at a random real
    /// point, while F(v, x + π e_j) differs (a polynomial in x_j is never 2π-periodic); and
    /// an input whose sine or cosine the generated kernels read ([`Mechanism::turns`]) is an
    /// angle too, periodic or not: a helical pair's θ enters as cos θ, sin θ and its slide
    /// pθ/2π. Sampled as a length (complex, the mechanism's size), its cos θ was near 10⁸⁰:
    /// a 3-HRS's start set stopped at 1 of its 16 roots (every monodromy loop failed), and a
    /// query 0.05 rad from home answered complete with no real root where there are 8.
    pub(crate) fn detect<S: Mechanism<N, M>, const N: usize>(
        sys: &S,
        scale: f64,
        rng: &mut Rng,
    ) -> Self {
        let v = [0; N].map(|_| scale * (rng.uniform() - 0.5));
        let x = [0; M].map(|_| rng.uniform() + 0.5);
        let mut f = [0.0; N];
        sys.residual(&v, &x, &mut f);
        let size = f.iter().fold(scale * scale, |m, c| m.max(c.abs()));
        let differs = |shift: f64, j: usize| {
            let mut y = x;
            y[j] += shift;
            let mut g = [0.0; N];
            sys.residual(&v, &y, &mut g);
            (0..N).map(|i| (g[i] - f[i]).abs()).fold(0.0f64, f64::max) > 1e-9 * size
        };
        let tau = 2.0 * core::f64::consts::PI;
        // x lies in [0.5, 1.5]: a sine or cosine the kernels read is nonzero there.
        let turned = if S::TURNS {
            sys.turns(&x).0
        } else {
            [[0.0; 2]; M]
        };
        Inputs {
            angular: core::array::from_fn(|j| {
                turned[j] != [0.0, 0.0] || (!differs(tau, j) && differs(0.5 * tau, j))
            }),
            scale,
        }
    }

    /// The unit of input j: radians for an angle, the length scale otherwise.
    pub(crate) fn unit(&self, j: usize) -> f64 {
        if self.angular[j] { 1.0 } else { self.scale }
    }

    /// A random complex input point: lengths complex normal × `size` (the same draws as before
    /// angles were told apart, so that mechanisms without angles keep their start sets), angles
    /// uniform over the turn plus i × normal × `spread`.
    pub(crate) fn random(&self, rng: &mut Rng, size: f64, spread: f64) -> [Complex; M] {
        core::array::from_fn(|j| {
            if self.angular[j] {
                let re = core::f64::consts::PI * (2.0 * rng.uniform() - 1.0);
                Complex::new(re, spread * rng.complex_normal().re)
            } else {
                rng.complex_normal().scale(size)
            }
        })
    }

    /// The root mean square of the length inputs of `p` (the size of loops around it), or
    /// the scale if there are none.
    pub(crate) fn length_size(&self, p: &[Complex; M]) -> f64 {
        let (mut sum, mut n) = (0.0, 0usize);
        for j in 0..M {
            if !self.angular[j] {
                sum += p[j].norm_sqr();
                n += 1;
            }
        }
        if n == 0 {
            self.scale
        } else {
            crate::math::sqrt(sum / n as f64)
        }
    }
}
