//! Past a stall of the oracle's natural-parameter continuation: pseudo-arc-length steps on the
//! curve F(v, x0 + λ dx) = 0 in (v, λ), which decide what natural-parameter steps cannot. At a
//! fold the curve turns back in λ and det B changes sign there; where the segment only passes
//! close to a singular point, λ goes on increasing and the branch continues.
//!
//! Independent of the runtime: its own dense elimination, its own step control.

use linkage::Mechanism;

/// How a pass ended.
pub enum Pass<const N: usize> {
    /// λ reached the target with det B of det0's sign all along: v there.
    Beyond([f64; N]),
    /// det B changed sign, or λ turned back: the segment meets a singularity.
    Turned,
    /// The steps shrank to nothing without deciding.
    Stuck,
}

fn sup(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, c| m.max(c.abs()))
}

/// Solves the n×n system `a y = b` (row-major) by Gaussian elimination with partial pivoting.
fn solve(mut a: Vec<f64>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))?;
        if !(a[p * n + k].abs() > 0.0) || !a[p * n + k].is_finite() {
            return None;
        }
        if p != k {
            for c in 0..n {
                a.swap(k * n + c, p * n + c);
            }
            b.swap(k, p);
        }
        for i in k + 1..n {
            let l = a[i * n + k] / a[k * n + k];
            for c in k..n {
                a[i * n + c] -= l * a[k * n + c];
            }
            b[i] -= l * b[k];
        }
    }
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|c| a[k * n + c] * b[c]).sum();
        b[k] = (b[k] - s) / a[k * n + k];
    }
    b.iter().all(|c| c.is_finite()).then_some(b)
}

/// The curve in (v, μ), μ = s λ, with the bordering row `tau`.
struct Curve<'a, S, const N: usize, const M: usize> {
    sys: &'a S,
    x0: &'a [f64; M],
    dx: &'a [f64; M],
    s: f64,
}

impl<S: Mechanism<N, M>, const N: usize, const M: usize> Curve<'_, S, N, M> {
    fn x(&self, mu: f64) -> [f64; M] {
        std::array::from_fn(|j| self.x0[j] + mu / self.s * self.dx[j])
    }

    /// The bordered Jacobian [[B, (∂F/∂x) dx / s], [tauᵀ]], row-major, (N+1)².
    fn bordered(&self, y: &[f64], tau: &[f64]) -> Vec<f64> {
        let v: [f64; N] = std::array::from_fn(|i| y[i]);
        let x = self.x(y[N]);
        let mut b = [[0.0; N]; N];
        self.sys.jacobian_dense(&v, &x, &mut b);
        let mut a = [[0.0; M]; N];
        self.sys.input_jacobian(&v, &x, &mut a);
        let n = N + 1;
        let mut m = vec![0.0; n * n];
        for i in 0..N {
            m[i * n..i * n + N].copy_from_slice(&b[i]);
            m[i * n + N] = (0..M).map(|j| a[i][j] * self.dx[j]).sum::<f64>() / self.s;
        }
        m[N * n..].copy_from_slice(tau);
        m
    }

    /// The unit tangent at y, oriented along `prev`.
    fn tangent(&self, y: &[f64], prev: &[f64]) -> Option<Vec<f64>> {
        let mut rhs = vec![0.0; N + 1];
        rhs[N] = 1.0;
        let t = solve(self.bordered(y, prev), rhs)?;
        let n = t.iter().map(|c| c * c).sum::<f64>().sqrt();
        let sign = if t.iter().zip(prev).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        Some(t.iter().map(|c| sign * c / n).collect())
    }

    /// Newton on [F; tauᵀ(y − pred)] = 0 from pred: the first correction at most `first`, each
    /// later one at most half the one before, until rounding.
    fn correct(&self, pred: &[f64], tau: &[f64], first: f64) -> Option<Vec<f64>> {
        let scale = 1.0 + sup(pred);
        let mut y = pred.to_vec();
        let mut limit = first;
        for _ in 0..10 {
            let v: [f64; N] = std::array::from_fn(|i| y[i]);
            let mut f = [0.0; N];
            self.sys.residual(&v, &self.x(y[N]), &mut f);
            let mut g = f.to_vec();
            g.push(
                tau.iter()
                    .zip(&y)
                    .zip(pred)
                    .map(|((t, a), b)| t * (a - b))
                    .sum(),
            );
            let d = solve(self.bordered(&y, tau), g)?;
            let size = sup(&d);
            if size > limit.max(1e-13 * scale) {
                return None;
            }
            y.iter_mut().zip(&d).for_each(|(a, b)| *a -= b);
            if size <= 1e-12 * scale {
                return Some(y);
            }
            limit = 0.5 * size;
        }
        None
    }
}

/// Pseudo-arc-length steps from (v, λ) on the segment x0 + λ dx (det B of det0's sign there,
/// `t` = dv/dλ) until λ reaches `target`.
#[allow(clippy::too_many_arguments)]
pub fn pass<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (x0, dx): (&[f64; M], &[f64; M]),
    det0: f64,
    v: &[f64; N],
    lambda: f64,
    t: &[f64; N],
    target: f64,
) -> Pass<N> {
    let s = sup(t).max(1.0);
    let curve = Curve { sys, x0, dx, s };
    let mut y: Vec<f64> = v.iter().copied().chain([s * lambda]).collect();
    let mut tau: Vec<f64> = t.iter().map(|c| c / s).chain([1.0]).collect();
    let n = tau.iter().map(|c| c * c).sum::<f64>().sqrt();
    tau.iter_mut().for_each(|c| *c /= n);
    let scale = 1.0 + sup(v);
    let (h_min, h_max) = (1e-13 * scale, 1e-2 * scale);
    let mut h = 1e-6 * scale;
    for _ in 0..4000 {
        let pred: Vec<f64> = y.iter().zip(&tau).map(|(a, b)| a + h * b).collect();
        let Some(mut z) = curve.correct(&pred, &tau, 0.1 * h + 1e-12 * scale) else {
            h *= 0.25;
            if h < h_min {
                return Pass::Stuck;
            }
            continue;
        };
        if z[N] >= s * target {
            // Land on λ = target: interpolate, then correct at fixed λ.
            let w = (s * target - y[N]) / (z[N] - y[N]);
            z = y.iter().zip(&z).map(|(a, b)| a + w * (b - a)).collect();
            z[N] = s * target;
            let mut fixed = vec![0.0; N + 1];
            fixed[N] = 1.0;
            match curve.correct(&z, &fixed, 0.1 * h + 1e-12 * scale) {
                Some(end) => {
                    let v: [f64; N] = std::array::from_fn(|i| end[i]);
                    let x = curve.x(end[N]);
                    if super::oracle::det(sys, &v, &x) * det0 > 0.0 {
                        return Pass::Beyond(v);
                    }
                    return Pass::Turned;
                }
                None => {
                    h *= 0.25;
                    if h < h_min {
                        return Pass::Stuck;
                    }
                    continue;
                }
            }
        }
        let v: [f64; N] = std::array::from_fn(|i| z[i]);
        if !(super::oracle::det(sys, &v, &curve.x(z[N])) * det0 > 0.0) {
            return Pass::Turned;
        }
        let Some(next) = curve.tangent(&z, &tau) else {
            return Pass::Stuck;
        };
        (y, tau) = (z, next);
        h = (2.0 * h).min(h_max);
    }
    Pass::Stuck
}
