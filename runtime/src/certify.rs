//! Proofs by the Krawczyk test: that a box holds exactly one root of F(·, x), and that a tracked
//! step stayed on one branch.
//!
//! For a box X around a point c, an approximate inverse Y of B(c), and inputs P (a point, or
//! the interval hull of a joint-space segment),
//!
//! `K(X, P) = c − Y F(c, P) + (I − Y B(X, P)) (X − c)`.
//!
//! If K lies in the interior of X, then for every x in P there is exactly one root of F(·, x) in
//! X, every B in B(X, P) is nonsingular, and the root lies in K (Krawczyk 1969, Moore 1977; the
//! parametric form in Neumaier, *Interval Methods for Systems of Equations*, 1990, §5.1). Every
//! interval operation rounds outward, and F and B are evaluated by the generated `residual_in`
//! and `jacobian_in` over [`Interval`]s, so the test is a proof for the model with its
//! floating-point constants. X − c is symmetric, so (I − Y B)(X − c) needs only the magnitudes
//! of I − Y B.

use crate::interval::Interval;
use crate::lu::Lu;
use crate::Mechanism;

/// A proven statement about the roots near a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Certificate<const N: usize> {
    /// A box in which F(·, x) has exactly one root (for every x of the segment, for a step).
    pub unique_in: [Interval; N],
    /// A box that contains that root (for a step: the roots along the segment).
    pub enclosure: [Interval; N],
    /// The smallest half-width of [`Self::unique_in`]: no other root is nearer than this in any
    /// coordinate.
    pub radius: f64,
    /// The largest distance, coordinate by coordinate, from the given point to the enclosure:
    /// a proven bound on its error.
    pub error_bound: f64,
}

/// Why no certificate was found. Not a statement that none exists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CertifyError {
    /// A value is NaN or infinite.
    NonFinite,
    /// B is singular (to working precision) at the point.
    Singular,
    /// No box tried passed the test: the point may be too far from a root, or too close to a
    /// singularity or to another root.
    NotContracting,
}

impl core::fmt::Display for CertifyError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            CertifyError::NonFinite => write!(f, "non-finite input"),
            CertifyError::Singular => write!(f, "∂F/∂v is singular at the point"),
            CertifyError::NotContracting => {
                write!(f, "the Krawczyk test failed on every box tried")
            }
        }
    }
}

/// Y ≈ B(c)⁻¹, as a dense matrix.
fn approximate_inverse<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    c: &[f64; N],
    x: &[f64; M],
) -> Option<[[f64; N]; N]> {
    let mut y = [[0.0; N]; N];
    // The generated factorisation when it is well conditioned, else dense LU: Y needs only
    // to be a good approximation, the test itself is rigorous.
    let mut fac = sys.new_factor();
    let generated = sys
        .factor(c, x, &mut fac)
        .is_some_and(|info| info.pivot_ratio > 1e-10);
    let dense = if generated {
        None
    } else {
        let mut b = [[0.0; N]; N];
        sys.jacobian_dense(c, x, &mut b);
        Some(Lu::new(b)?)
    };
    for j in 0..N {
        let mut e = [0.0; N];
        e[j] = 1.0;
        match &dense {
            None => sys.solve(&fac, &mut e),
            Some(lu) => lu.solve(&mut e),
        }
        for i in 0..N {
            y[i][j] = e[i];
        }
    }
    y.iter().flatten().all(|v| v.is_finite()).then_some(y)
}

/// `Y · a` for a point matrix and an interval vector.
fn times<const N: usize>(y: &[[f64; N]; N], a: &[Interval; N]) -> [Interval; N] {
    core::array::from_fn(|i| {
        let mut s = Interval::point(0.0);
        for j in 0..N {
            s = s + a[j].scale(y[i][j]);
        }
        s
    })
}

/// The Krawczyk test on the box `c ± r` with inputs `p`: the image K if it lies inside the box.
fn krawczyk<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    y: &[[f64; N]; N],
    d: &[Interval; N],
    c: &[f64; N],
    r: &[f64; N],
    p: &[Interval; M],
) -> Option<[Interval; N]> {
    let xs: [Interval; N] = core::array::from_fn(|i| Interval::around(c[i], r[i]));
    // B over the box, sparse.
    let mut values = [Interval::point(0.0); 512];
    let values = values.get_mut(..S::NNZ)?;
    sys.jacobian_in(&xs, p, values);
    // |I − Y B(X)| entrywise, in midpoint-radius form with plain floating point and a bound on
    // its rounding (Rump's products): with B = mid ± rad, the entry is within
    // |δ − Σ Y mid| + Σ |Y| rad of 0, and computing those sums of at most N + 1 terms in
    // floating point errs by at most γ_{N+1} (Σ |Y| |mid| + 1 + Σ |Y| rad), γ_n = n u / (1 − n u).
    let mut centre = [[0.0f64; N]; N];
    let mut size = [[0.0f64; N]; N];
    let mut spread_of = [[0.0f64; N]; N];
    for (k, &(row, col)) in S::PATTERN.iter().enumerate() {
        let (mid, rad) = (values[k].mid(), values[k].radius());
        if !(mid.is_finite() && rad.is_finite()) {
            return None;
        }
        for i in 0..N {
            let yv = y[i][row];
            centre[i][col] += yv * mid;
            size[i][col] += yv.abs() * mid.abs();
            spread_of[i][col] += yv.abs() * rad;
        }
    }
    let u = f64::EPSILON / 2.0;
    let n1 = (N + 1) as f64;
    let gamma = (n1 * u / (1.0 - n1 * u)).next_up();
    let mut k = [Interval::point(0.0); N];
    for i in 0..N {
        // Σ_j |(I − Y B)_ij| r_j, rounded up.
        let mut spread = 0.0f64;
        for j in 0..N {
            let delta = if i == j { 1.0 } else { 0.0 };
            let bound = (delta - centre[i][j]).abs()
                + spread_of[i][j]
                + gamma * (size[i][j] + 1.0 + spread_of[i][j]);
            // Three more roundings above: widen by a few units.
            let m = (bound * (1.0 + 4.0 * u)).next_up();
            spread = (spread + (m * r[j]).next_up()).next_up();
        }
        if !spread.is_finite() {
            return None;
        }
        let centre = Interval::point(c[i]) - d[i];
        k[i] = Interval::new(
            (centre.lo - spread).next_down(),
            (centre.hi + spread).next_up(),
        );
        if !xs[i].contains_strictly(&k[i]) {
            return None;
        }
    }
    Some(k)
}

/// The radii for which the Krawczyk test should pass, predicted in floating point.
///
/// B is linear in v (the system is of degree ≤ 2), so over the box c ± r the radius of B is
/// `W_p + r W_v` (W_p from the inputs' widths, W_v from a unit box), and row i of the test
/// reads `|d_i| + E_i r + G_i r² < r` with `E = row sums of |I − Y mid B| + |Y| W_p` and
/// `G = row sums of |Y| W_v`: a quadratic in r whose roots bracket the radii that pass. The
/// prediction only chooses the boxes; the interval test decides.
fn predicted_radii<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    y: &[[f64; N]; N],
    d: &[Interval; N],
    c: &[f64; N],
    p: &[Interval; M],
) -> Option<(f64, f64)> {
    let mut at_c = [Interval::point(0.0); 512];
    let at_c = at_c.get_mut(..S::NNZ)?;
    let cs: [Interval; N] = core::array::from_fn(|i| Interval::point(c[i]));
    sys.jacobian_in(&cs, p, at_c);
    let mut unit = [Interval::point(0.0); 512];
    let unit = unit.get_mut(..S::NNZ)?;
    let xs: [Interval; N] = core::array::from_fn(|i| Interval::around(c[i], 1.0));
    sys.jacobian_in(&xs, p, unit);
    // E and G row by row, through the pattern.
    let mut ymb = [[0.0f64; N]; N];
    let mut e = [0.0f64; N];
    let mut g = [0.0f64; N];
    for (k, &(row, col)) in S::PATTERN.iter().enumerate() {
        let (mid, wp) = (at_c[k].mid(), at_c[k].radius());
        let wv = (unit[k].radius() - wp).max(0.0);
        for i in 0..N {
            ymb[i][col] += y[i][row] * mid;
            e[i] += y[i][row].abs() * wp;
            g[i] += y[i][row].abs() * wv;
        }
    }
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for i in 0..N {
        for j in 0..N {
            e[i] += ((if i == j { 1.0 } else { 0.0 }) - ymb[i][j]).abs();
        }
        let (a, b, cc) = (g[i], 1.0 - e[i], d[i].mag());
        if !(b > 0.0) {
            return None;
        }
        if a <= 0.0 {
            lo = lo.max(cc / b);
            continue;
        }
        let disc = b * b - 4.0 * a * cc;
        if !(disc > 0.0) {
            return None;
        }
        let root = crate::math::sqrt(disc);
        lo = lo.max((b - root) / (2.0 * a));
        hi = hi.min((b + root) / (2.0 * a));
    }
    (lo < hi && hi.is_finite()).then_some((lo, hi))
}

/// The Krawczyk test on a few boxes around `c` with inputs `p`: a small one, just outside the
/// Newton step, for a tight enclosure of the root; a large one, near the largest predicted to
/// pass, for the radius of uniqueness (halved until it passes).
fn search<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    c: &[f64; N],
    x_mid: &[f64; M],
    p: &[Interval; M],
    at_least: &[f64; N],
) -> Result<Certificate<N>, CertifyError> {
    if S::NNZ > 512 {
        // The interval Jacobians live on the stack; larger systems are not certified.
        return Err(CertifyError::NotContracting);
    }
    let y = approximate_inverse(sys, c, x_mid).ok_or(CertifyError::Singular)?;
    let cs: [Interval; N] = core::array::from_fn(|i| Interval::point(c[i]));
    let mut f = [Interval::point(0.0); N];
    sys.residual_in(&cs, p, &mut f);
    if f.iter().any(|v| !v.is_finite()) {
        return Err(CertifyError::NonFinite);
    }
    let d = times(&y, &f);
    let scale = c.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let cover = at_least.iter().fold(0.0f64, |m, v| m.max(*v));
    let (lo, hi) = predicted_radii(sys, &y, &d, c, p).ok_or(CertifyError::NotContracting)?;
    let small = (2.0 * lo).max(1e-13 * scale).max(1.25 * cover);
    let box_of = |r: f64| -> [f64; N] { core::array::from_fn(|_| r) };
    let mut tight = None;
    for k in 0..4 {
        let r = small * libm::pow(4.0, k as f64);
        if let Some(e) = krawczyk(sys, &y, &d, c, &box_of(r), p) {
            tight = Some((e, r));
            break;
        }
    }
    let (enclosure, r_small) = tight.ok_or(CertifyError::NotContracting)?;
    let error_bound = (0..N).fold(0.0f64, |m, i| {
        m.max(
            (enclosure[i].hi - c[i])
                .max(c[i] - enclosure[i].lo)
                .next_up(),
        )
    });
    // The largest box: start at half the predicted limit and halve while it fails.
    let mut radius = r_small;
    let mut r = 0.5 * hi;
    for _ in 0..6 {
        if r <= r_small {
            break;
        }
        if krawczyk(sys, &y, &d, c, &box_of(r), p).is_some() {
            radius = r;
            break;
        }
        r *= 0.25;
    }
    Ok(Certificate {
        unique_in: core::array::from_fn(|i| Interval::around(c[i], radius)),
        enclosure,
        radius,
        error_bound,
    })
}

/// Proves that F(·, x) has exactly one root near `v`, and bounds its distance from `v`.
///
/// ```
/// use linkage::{certify, newton_raphson, Mechanism, Options, Pose, Start};
/// # linkage::mechanism! {
/// #     pub struct Rps;
/// #     base {
/// #         A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
/// #         A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
/// #         A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
/// #     }
/// #     platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
/// #     chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
/// #     chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
/// #     chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
/// # }
/// # let rps = Rps::new();
/// # let v0 = linkage::unknowns_from_pose(&rps, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]));
/// # let x0 = rps.inverse(&v0, &[0.0; 3]).unwrap();
/// # let start = Start::new(&rps, v0, x0).unwrap();
/// let target = [160.0, 155.0, 158.0];
/// let sol = newton_raphson(&rps, &start, &target, &Options::TIGHT).unwrap();
/// let proof = certify(&rps, &sol.v, &target).unwrap();
/// // The root is unique within `radius` of the solution and at most `error_bound` from it.
/// assert!(proof.radius > 1.0 && proof.error_bound < 1e-9);
/// ```
pub fn certify<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
) -> Result<Certificate<N>, CertifyError> {
    if v.iter().chain(x).any(|a| !a.is_finite()) {
        return Err(CertifyError::NonFinite);
    }
    let p: [Interval; M] = core::array::from_fn(|j| Interval::point(x[j]));
    search(sys, v, x, &p, &[0.0; N])
}

/// Proves that the roots `v0` at `x0` and `v1` at `x1` lie on one branch without a singularity
/// between them: for every input on the segment from `x0` to `x1`, one root and only one lies in
/// [`Certificate::unique_in`], which holds both, and ∂F/∂v is nonsingular throughout.
pub fn certify_step<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    (v0, x0): (&[f64; N], &[f64; M]),
    (v1, x1): (&[f64; N], &[f64; M]),
) -> Result<Certificate<N>, CertifyError> {
    if v0
        .iter()
        .chain(x0)
        .chain(v1)
        .chain(x1)
        .any(|a| !a.is_finite())
    {
        return Err(CertifyError::NonFinite);
    }
    let c: [f64; N] = core::array::from_fn(|i| 0.5 * (v0[i] + v1[i]));
    let x_mid: [f64; M] = core::array::from_fn(|j| 0.5 * (x0[j] + x1[j]));
    let p: [Interval; M] = core::array::from_fn(|j| {
        Interval::new(x0[j].min(x1[j]).next_down(), x0[j].max(x1[j]).next_up())
    });
    let half: [f64; N] = core::array::from_fn(|i| 0.5 * (v1[i] - v0[i]).abs());
    let cert = search(sys, &c, &x_mid, &p, &half)?;
    // Both ends must be inside the box of uniqueness (the search sized it so).
    let inside = |v: &[f64; N]| (0..N).all(|i| cert.unique_in[i].contains(v[i]));
    if inside(v0) && inside(v1) {
        Ok(cert)
    } else {
        Err(CertifyError::NotContracting)
    }
}
