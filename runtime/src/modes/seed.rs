//! A first solution of the family at a random complex parameter point: the seed of monodromy.
//!
//! The inputs are the parameters, so a solution can be made rather than searched for: place
//! the platform by a random complex rigid motion, take random complex inputs, and move the
//! pair (v, x) onto the solution variety F(v, x) = 0 by Gauss–Newton steps of least norm
//! (`Δ = −Jᴴ (J Jᴴ)⁻¹ F` with `J = [∂F/∂v  ∂F/∂x]`, N equations in N + M unknowns). Starting from
//! a rigid placement keeps the walk on the component of proper rigid motions; the point it
//! lands on has random complex inputs, which makes them a generic parameter point.

use super::complex::Complex;
use super::dense;
use super::inputs::Inputs;
use super::polish::POLISHED;
use super::rng::Rng;
use super::sparse_lu::Lu;
use super::taylor::Series;
use super::track::Model;
use crate::mechanism::Mechanism;

/// A complex rotation matrix from a quaternion with complex entries: `Rᵀ R = I`, det R = 1
/// whenever `q·q ≠ 0`.
fn rotation(q: [Complex; 4]) -> Option<[[Complex; 3]; 3]> {
    let [a, b, c, d] = q;
    let n = a * a + b * b + c * c + d * d;
    if !(n.abs_max() > 1e-3) {
        return None;
    }
    let two = Complex::real(2.0);
    let r = [
        [
            a * a + b * b - c * c - d * d,
            two * (b * c - a * d),
            two * (b * d + a * c),
        ],
        [
            two * (b * c + a * d),
            a * a - b * b + c * c - d * d,
            two * (c * d - a * b),
        ],
        [
            two * (b * d - a * c),
            two * (c * d + a * b),
            a * a - b * b - c * c + d * d,
        ],
    ];
    let inv = n.recip();
    Some(r.map(|row| row.map(|x| x * inv)))
}

/// Why an attempt made no seed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Miss {
    /// The walk did not converge onto F = 0 (or the random placement was unusable).
    Walk,
    /// It converged, to a point where B is singular.
    Singular,
}

/// A random complex point (v, x) with F(v, x) = 0 and B = ∂F/∂v regular there, or why this
/// attempt did not reach one.
pub(crate) fn seed<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
    rng: &mut Rng,
) -> Result<([Complex; N], [Complex; M]), Miss> {
    let scale = model.scale;
    let r = rotation([0; 4].map(|_| rng.complex_normal())).ok_or(Miss::Walk)?;
    let t = [0; 3].map(|_| rng.complex_normal().scale(scale));
    let k = S::POINTS.len();
    let mut v = [Complex::ZERO; N];
    for x in v.iter_mut() {
        *x = rng.complex_normal().scale(scale);
    }
    for p in 0..k {
        let local = model.sys.point_local(p);
        if !local.iter().all(|c| c.is_finite()) {
            continue;
        }
        for axis in 0..3 {
            if axis * k + p < N {
                let mut q = t[axis];
                for j in 0..3 {
                    q += r[axis][j].scale(local[j]);
                }
                v[axis * k + p] = q;
            }
        }
    }
    let x = inputs.random(rng, scale, 0.5);
    walk(model, inputs, v, x)
}

/// The mechanism's known real configuration (its home), moved onto F(v, x) = 0 for the
/// current geometry if need be: a seed on the component of the assembly mode the machine is
/// built in, which random rigid placements seldom reach where that component is small (a
/// delta's translations, 2 of its 40 roots).
pub(crate) fn seed_from_home<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
) -> Result<([Complex; N], [Complex; M]), Miss> {
    let (v, x) = model.sys.home_configuration().ok_or(Miss::Walk)?;
    if !v.iter().chain(&x).all(|c| c.is_finite()) {
        return Err(Miss::Walk);
    }
    walk(model, inputs, v.map(Complex::real), x.map(Complex::real))
}

/// Gauss–Newton steps of least norm from (v, x) onto F(v, x) = 0; the point reached if B is
/// regular there.
fn walk<S: Mechanism<N, M>, const N: usize, const M: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
    mut v: [Complex; N],
    mut x: [Complex; M],
) -> Result<([Complex; N], [Complex; M]), Miss> {
    let mut converged = false;
    let mut previous = f64::INFINITY;
    for _ in 0..80 {
        // F and the columns of A = ∂F/∂x, one directional derivative per input.
        let mut f = [Complex::ZERO; N];
        let mut a = [[Complex::ZERO; M]; N];
        let vs = v.map(Series::<2>::constant);
        for j in 0..M {
            let mut xs = x.map(Series::<2>::constant);
            xs[j].0[1] = Complex::ONE;
            let mut out = [Series::<2>::ZERO; N];
            model.sys.residual_in(&vs, &xs, &mut out);
            for i in 0..N {
                f[i] = out[i].0[0];
                a[i][j] = out[i].0[1];
            }
        }
        let mut values = [[Complex::ZERO; N]; N];
        model.sys.jacobian_in(&v, &x, values.as_flattened_mut());
        let mut b = [[Complex::ZERO; N]; N];
        for (&(row, col), &val) in S::PATTERN.iter().zip(values.as_flattened()) {
            b[row][col] = val;
        }
        // Each row of [B A] and F scaled to unit length: the same equations, but G below no
        // longer squares the spread between rows of unit coefficients and rows of squared
        // lengths (a planar 3-RRR driven at its base: 10⁹ between G's diagonal entries,
        // which the elimination's pivot test took for a singular G at every start).
        for i in 0..N {
            let mut sq = 0.0;
            for l in 0..N {
                sq += b[i][l].norm_sqr();
            }
            for l in 0..M {
                sq += a[i][l].norm_sqr();
            }
            let inv = 1.0 / crate::math::sqrt(sq);
            if !(inv.is_finite()) {
                return Err(Miss::Walk);
            }
            for l in 0..N {
                b[i][l] = b[i][l].scale(inv);
            }
            for l in 0..M {
                a[i][l] = a[i][l].scale(inv);
            }
            f[i] = f[i].scale(inv);
        }
        // G = B Bᴴ + A Aᴴ.
        let mut g = [[Complex::ZERO; N]; N];
        for i in 0..N {
            for j in 0..N {
                let mut s = Complex::ZERO;
                for l in 0..N {
                    s += b[i][l] * b[j][l].conj();
                }
                for l in 0..M {
                    s += a[i][l] * a[j][l].conj();
                }
                g[i][j] = s;
            }
        }
        let mut y = f;
        if !dense::solve(&mut g, &mut y) {
            return Err(Miss::Walk);
        }
        let mut dv = [Complex::ZERO; N];
        let mut dx = [Complex::ZERO; M];
        for i in 0..N {
            for l in 0..N {
                dv[l] -= b[i][l].conj() * y[i];
            }
            for l in 0..M {
                dx[l] -= a[i][l].conj() * y[i];
            }
        }
        let mut size = model.norm(&dv, &v);
        for l in 0..M {
            size = size.max(dx[l].abs_max() / inputs.unit(l).max(x[l].abs_max()));
        }
        if !size.is_finite() {
            return Err(Miss::Walk);
        }
        // Damped far from the variety: at most half the scale per step.
        let damp = if size > 0.5 { 0.5 / size } else { 1.0 };
        for l in 0..N {
            v[l] += dv[l].scale(damp);
        }
        for l in 0..M {
            x[l] += dx[l].scale(damp);
        }
        // Converged: below 1e-13, or stalled at a rounding floor below what `polish` accepts
        // (inputs that enter through cos and sin leave steps near 1e-12 of the scale).
        if size <= 1e-13 || (size <= POLISHED && size >= 0.5 * previous) {
            converged = true;
            break;
        }
        previous = size;
    }
    if !converged {
        return Err(Miss::Walk);
    }
    // B with its rows and columns scaled to unit largest entry before the pivot test: rows of
    // lengths beside rows of unit coefficients (the Stewart platform's) differ by the
    // machine's size, and a machine of 1e-12 mm was called singular at every seed.
    let mut values = [[Complex::ZERO; N]; N];
    let flat = values.as_flattened_mut();
    model.sys.jacobian_in(&v, &x, flat);
    equilibrate::<N>(S::PATTERN, flat);
    let mut lu = Lu::new();
    if lu.factor(model.plan, flat, None) && lu.pivot_ratio() > 1e-9 {
        Ok((v, x))
    } else {
        Err(Miss::Singular)
    }
}

/// Scales the nonzeros `values` (in the order of `pattern`) so that every row, then every
/// column, has largest entry 1 in magnitude (`abs_max`): the pivot ratio of the result does not
/// depend on the units of the equations or of the unknowns. A zero row or column is left.
fn equilibrate<const N: usize>(pattern: &[(usize, usize)], values: &mut [Complex]) {
    for by_column in [false, true] {
        let mut max = [0.0f64; N];
        let line = |&(row, col): &(usize, usize)| if by_column { col } else { row };
        for (rc, v) in pattern.iter().zip(values.iter()) {
            if let Some(m) = max.get_mut(line(rc)) {
                *m = m.max(v.abs_max());
            }
        }
        for (rc, v) in pattern.iter().zip(values.iter_mut()) {
            if let Some(&m) = max.get(line(rc))
                && m > 0.0
                && m.is_finite()
            {
                *v = v.scale(1.0 / m);
            }
        }
    }
}
