//! Samples of the mechanism's motion from home, on the whole system of equations (the
//! dependent ones too): what the rank test checks its choice of equations against.
//!
//! An over-constrained mechanism's equations are dependent everywhere on its motion, and the
//! square system kept of them is independent at home; it need not stay so. On a Goldberg 5R
//! linkage the 21 equations kept at home turned singular 0.056 rad of the input away, where
//! the mechanism is regular: continuation stopped there with a fold. So the motion is followed
//! from home, each input in turn both ways, the others held: predictor along the tangent,
//! chord Gauss–Newton on all the equations (consistent on the motion, so least squares meets
//! them where the mechanism is regular; ∂F/∂v factored once a step, where it starts), the step
//! halved where the corrections do not contract. A ray ends at a fold or a singularity of the
//! mechanism (the step shrinks to nothing), after a travel of [`TRAVEL`] length scales, after
//! [`STEPS`] steps, or when the work allowed ([`WORK`]) is spent.

use super::derivatives::{Derivatives, Sparse};
use super::tape::Tape;

/// A ray's steps move the points by at most this fraction of the length scale.
const STEP: f64 = 0.1;

/// A ray ends after its points have travelled this many length scales (the sum of its steps'
/// largest coordinate changes).
const TRAVEL: f64 = 1.5;

/// And after this many steps, wherever it is,
const STEPS: usize = 40;

/// or once the rays together have done this many operations (expression nodes evaluated, and
/// n³/6 a factorisation): a bound on the compile time (about 0.1 s) that only large systems
/// reach, followed less far. (A random general chain of 135 equations, 125 000 nodes in its
/// Jacobian, took 2.4 s for its twelve rays before.)
const WORK: usize = 20_000_000;

/// Each chord correction at most this fraction of the one before. (Chord corrections
/// converge linearly; the samples only choose among equations each valid at home, and a
/// choice is checked again at run time, so a lenient rule costs nothing but a sample.)
const CONTRACTION: f64 = 0.7;

/// Gauss–Newton has converged below this fraction of the length scale: enough for the sign
/// of a determinant, which is all the samples are for.
const TOLERANCE: f64 = 1e-9;

/// A configuration on the motion, with ∂F/∂v there (sparse: each row's columns and values).
pub struct Sample {
    pub v: Vec<f64>,
    pub x: Vec<f64>,
    pub b: Sparse,
}

/// The motion from home along one input direction: the configurations reached, home first.
pub type Ray = Vec<Sample>;

struct System<'a> {
    by_v: &'a Derivatives<'a>,
    by_x: &'a Derivatives<'a>,
    c: &'a [f64],
    /// The equations.
    f: Tape,
    /// Operations evaluated so far.
    work: std::cell::Cell<usize>,
}

/// The normal equations BᵀB d = Bᵀr of a sparse B, factored (Cholesky). Squaring the
/// condition is harmless here: the residual is evaluated exactly, a correction only needs to
/// contract, and a ray ends where ∂F/∂v comes near losing rank.
struct Normal {
    n: usize,
    l: Vec<f64>,
}

impl Normal {
    fn new(b: &[Vec<(usize, f64)>], n: usize) -> Option<Normal> {
        let mut l = vec![0.0; n * n];
        for row in b {
            for &(i, a) in row {
                for &(j, c) in row {
                    if j <= i {
                        l[i * n + j] += a * c;
                    }
                }
            }
        }
        let top = (0..n).fold(0.0f64, |m, i| m.max(l[i * n + i]));
        for j in 0..n {
            let mut d = l[j * n + j];
            for k in 0..j {
                d -= l[j * n + k] * l[j * n + k];
            }
            // Below this, BᵀB is singular to working precision (B's condition beyond 1e6).
            if !(d > 1e-12 * top) {
                return None;
            }
            let d = d.sqrt();
            l[j * n + j] = d;
            for i in j + 1..n {
                let mut s = l[i * n + j];
                for k in 0..j {
                    s -= l[i * n + k] * l[j * n + k];
                }
                l[i * n + j] = s / d;
            }
        }
        Some(Normal { n, l })
    }

    /// The least-squares solution of `B d = r`.
    fn solve(&self, b: &[Vec<(usize, f64)>], r: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut d = vec![0.0; n];
        for (row, ri) in b.iter().zip(r) {
            for &(i, a) in row {
                d[i] += a * ri;
            }
        }
        for i in 0..n {
            let s: f64 = (0..i).map(|k| self.l[i * n + k] * d[k]).sum();
            d[i] = (d[i] - s) / self.l[i * n + i];
        }
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|k| self.l[k * n + i] * d[k]).sum();
            d[i] = (d[i] - s) / self.l[i * n + i];
        }
        d
    }
}

/// B, sparse, with its normal equations factored.
type Factored = (Sparse, Normal);

fn amax(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, b| m.max(b.abs()))
}

impl System<'_> {
    fn residual(&self, v: &[f64], x: &[f64]) -> Vec<f64> {
        self.work.set(self.work.get() + self.f.len());
        let mut r = Vec::new();
        self.f.eval(v, x, self.c, &mut r);
        r
    }

    /// B = ∂F/∂v at `(v, x)`, factored.
    fn factor(&self, v: &[f64], x: &[f64]) -> Option<Factored> {
        let n = self.by_v.columns;
        self.work
            .set(self.work.get() + self.by_v.size() + n * n * n / 6);
        let b = self.by_v.sparse(v, x, self.c);
        let normal = Normal::new(&b, self.by_v.columns)?;
        Some((b, normal))
    }

    /// ∂v per unit of the inputs' direction `dx`, on B factored at `(v, x)`.
    fn tangent(&self, (b, normal): &Factored, v: &[f64], x: &[f64], dx: &[f64]) -> Vec<f64> {
        self.work.set(self.work.get() + self.by_x.size());
        let fx = self.by_x.sparse(v, x, self.c);
        let r: Vec<f64> = fx
            .iter()
            .map(|row| -row.iter().map(|(k, a)| a * dx[*k]).sum::<f64>())
            .collect();
        normal.solve(b, &r)
    }

    /// Chord Gauss–Newton from `v` at `x`, on B factored nearby: the point on the motion, or
    /// `None` where the corrections do not contract (each at most [`CONTRACTION`] of the one
    /// before, the first at most `first`) or the equations are not met there.
    fn correct(
        &self,
        (b, normal): &Factored,
        v: &[f64],
        x: &[f64],
        first: f64,
        length: f64,
    ) -> Option<Vec<f64>> {
        let mut v = v.to_vec();
        let mut last = first / CONTRACTION;
        for _ in 0..16 {
            let r: Vec<f64> = self.residual(&v, x).iter().map(|a| -a).collect();
            let d = normal.solve(b, &r);
            let size = amax(&d);
            if !(size <= CONTRACTION * last) {
                return None;
            }
            v.iter_mut().zip(&d).for_each(|(a, s)| *a += s);
            if size <= TOLERANCE * length {
                let r = amax(&self.residual(&v, x));
                return (r <= 1e-7 * length * length).then_some(v);
            }
            last = size;
        }
        None
    }

    /// Steps along `dx` from `(v0, x0)`: the tangent and the chord corrections on B factored
    /// where the step starts (one factorisation a step), the step halved where they do not
    /// contract.
    fn ray(&self, v0: &[f64], x0: &[f64], dx: &[f64], length: f64, work: usize) -> Ray {
        let mut ray = Vec::new();
        let (mut v, mut x) = (v0.to_vec(), x0.to_vec());
        let mut travel = 0.0;
        let mut scale = 1.0;
        let Some(mut factored) = self.factor(&v, &x) else {
            return ray;
        };
        while ray.len() <= STEPS && travel < TRAVEL * length && self.work.get() < work {
            let t = self.tangent(&factored, &v, &x, dx);
            let speed = amax(&t);
            if !(speed > 0.0) {
                break;
            }
            let h = scale * STEP * length / speed;
            let xn: Vec<f64> = x.iter().zip(dx).map(|(a, d)| a + h * d).collect();
            let predicted: Vec<f64> = v.iter().zip(&t).map(|(a, d)| a + h * d).collect();
            let next = self
                .correct(&factored, &predicted, &xn, 0.25 * h * speed, length)
                .and_then(|w| Some((self.factor(&w, &xn)?, w)));
            match next {
                Some((f, w)) => {
                    travel += v
                        .iter()
                        .zip(&w)
                        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                    let b = std::mem::replace(&mut factored, f).0;
                    ray.push(Sample { v, x, b });
                    (v, x) = (w, xn);
                    scale = (1.5 * scale).min(1.0);
                }
                None if scale > 1e-4 => scale *= 0.5,
                None => break,
            }
        }
        ray.push(Sample {
            v,
            x,
            b: factored.0,
        });
        ray
    }
}

/// The motion from home `(v, x)`, each input in turn both ways, the others held: `2 m` rays.
/// `by_v` and `by_x`: ∂F/∂v and ∂F/∂x of all the equations.
pub fn rays(by_v: &Derivatives, by_x: &Derivatives, v: &[f64], x: &[f64], c: &[f64]) -> Vec<Ray> {
    let system = System {
        by_v,
        by_x,
        c,
        f: Tape::new(by_v.equations),
        work: std::cell::Cell::new(0),
    };
    let length = 1.0 + amax(v);
    let m = by_x.columns;
    let mut out = Vec::new();
    for i in 0..m {
        for sign in [1.0, -1.0] {
            let mut dx = vec![0.0; m];
            dx[i] = sign;
            // Each ray its share of the work: the rays left share what is left.
            let share = (WORK.saturating_sub(system.work.get())) / (2 * m - out.len());
            out.push(system.ray(v, x, &dx, length, system.work.get() + share));
        }
    }
    out
}
