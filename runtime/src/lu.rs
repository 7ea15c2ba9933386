//! LU factorisation with partial pivoting, without heap: [`Lu`] for a dense n×n matrix, and
//! [`Factored`], what the factorisation `mechanism!` generates for B's sparsity pattern reports.
//!
//! Sizes are in the types: an [`Lu<N>`] owns its `N`×`N` factors and its `N` row swaps, so no
//! call can pass a matrix larger than its record of swaps. The (n+1)×(n+1) bordered matrix of
//! pseudo-arc-length continuation (Eq. 10) has its own type inside the crate; both run the one
//! elimination and substitution kernel below, over the `Square` storage each provides.
//!
//! ```
//! use linkage::lu::Lu;
//! let lu = Lu::new([[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]]).unwrap();
//! assert!((lu.det() + 5.0).abs() < 1e-12);
//! let mut b = [3.0, 2.0, 4.0];
//! lu.solve(&mut b);
//! assert!((b[0] - 1.0).abs() < 1e-12 && (b[1] - 1.0).abs() < 1e-12 && (b[2] - 1.0).abs() < 1e-12);
//! // An exactly singular matrix has no factorisation.
//! assert!(Lu::new([[1.0, 1.0], [1.0, 1.0]]).is_none());
//! ```
//!
//! A right-hand side of another size than the factorisation is a type error, not a wrong
//! answer:
//!
//! ```compile_fail
//! let lu = linkage::lu::Lu::new([[4.0, 1.0], [1.0, 4.0]]).unwrap();
//! lu.solve(&mut [1.0, 2.0, 3.0]);
//! ```

/// What a factorisation of B tells besides itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Factored {
    /// det B.
    pub det: f64,
    /// Smallest |pivot| / largest |pivot| of the dense part: a conditioning indicator.
    pub pivot_ratio: f64,
}

/// `P A = L U` of a dense `N`×`N` matrix with partial pivoting: the factors (`L` unit lower,
/// `U` upper, in one array), the row swaps, and ‖A‖₁ for condition estimates.
#[derive(Clone, Copy, Debug)]
pub struct Lu<const N: usize> {
    lu: [[f64; N]; N],
    piv: Pivots<N>,
    norm1: f64,
}

impl<const N: usize> Lu<N> {
    /// Factors `a`. `None` for an exactly singular or non-finite matrix.
    pub fn new(mut a: [[f64; N]; N]) -> Option<Self> {
        let norm1 = (0..N)
            .map(|j| a.iter().map(|row| row[j].abs()).sum::<f64>())
            .fold(0.0f64, |m, c| if c > m || c.is_nan() { c } else { m });
        let piv = eliminate(&mut a)?;
        if !piv.info.det.is_finite() {
            return None;
        }
        Some(Lu { lu: a, piv, norm1 })
    }

    /// The determinant of the factored matrix.
    pub fn det(&self) -> f64 {
        self.piv.info.det
    }

    /// Smallest |pivot| / largest |pivot|: cheap, but not scale-free (see
    /// [`Self::reciprocal_condition`]).
    pub fn pivot_ratio(&self) -> f64 {
        self.piv.info.pivot_ratio
    }

    /// Solves `A y = b` in place.
    pub fn solve(&self, b: &mut [f64; N]) {
        substitute(&self.lu, &self.piv.swaps, b);
    }

    /// Solves `Aᵀ y = b` in place.
    pub fn solve_transposed(&self, b: &mut [f64; N]) {
        substitute_transposed(&self.lu, &self.piv.swaps, b);
    }

    /// An estimate of `1 / (‖A‖₁ ‖A⁻¹‖₁)`, from a few solves with the factors (Hager's method as
    /// refined by Higham, the estimate LAPACK's `xGECON` makes): near 1 for a well-conditioned
    /// matrix, near 1e-16 for one singular to rounding. It can overestimate ‖A⁻¹‖₁'s inverse
    /// only rarely and by a modest factor. Scale the rows and columns of `A` first for a
    /// measure that does not depend on units.
    pub fn reciprocal_condition(&self) -> f64 {
        if N == 0 {
            return 1.0;
        }
        let inverse_norm = self.inverse_norm1();
        let r = 1.0 / (self.norm1 * inverse_norm);
        if r.is_nan() { 0.0 } else { r }
    }

    /// Hager–Higham estimate of ‖A⁻¹‖₁ (a lower bound, usually within a factor of 3).
    fn inverse_norm1(&self) -> f64 {
        let n = N as f64;
        let l1 = |y: &[f64; N]| y.iter().map(|v| v.abs()).sum::<f64>();
        let mut x = [1.0 / n; N];
        self.solve(&mut x);
        let mut estimate = l1(&x);
        let mut last = usize::MAX;
        for _ in 0..5 {
            let mut z = x.map(|v| if v >= 0.0 { 1.0 } else { -1.0 });
            self.solve_transposed(&mut z);
            let (mut j, mut best) = (0, -1.0);
            for (i, zi) in z.iter().enumerate() {
                if zi.abs() > best {
                    best = zi.abs();
                    j = i;
                }
            }
            if j == last {
                break;
            }
            last = j;
            let mut e = [0.0; N];
            e.set(j, 1.0);
            self.solve(&mut e);
            let next = l1(&e);
            x = e;
            if !(next > estimate) {
                break;
            }
            estimate = next;
        }
        // Higham's extra test vector catches the cases that defeat the search above.
        let mut alt: [f64; N] = core::array::from_fn(|i| {
            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
            s * (1.0 + i as f64 / (n - 1.0).max(1.0))
        });
        self.solve(&mut alt);
        estimate.max(2.0 * l1(&alt) / (3.0 * n))
    }
}

/// `[[B, c], [rᵀ, d]]`: an n×n block bordered by a column, a row and a corner.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bordered<const N: usize> {
    pub block: [[f64; N]; N],
    pub column: [f64; N],
    pub row: [f64; N],
    pub corner: f64,
}

/// `[head; tail]`, the (n+1)-vector of a bordered system.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Extended<const N: usize> {
    pub head: [f64; N],
    pub tail: f64,
}

/// The LU factorisation of a bordered matrix (size N + 1; its last step has no row left to
/// swap, so `N` swaps record it).
#[derive(Clone, Copy, Debug)]
pub(crate) struct BorderedLu<const N: usize> {
    m: Bordered<N>,
    piv: Pivots<N>,
}

impl<const N: usize> BorderedLu<N> {
    /// Factors `m`. `None` for an exactly singular or non-finite matrix.
    pub fn new(mut m: Bordered<N>) -> Option<Self> {
        let piv = eliminate(&mut m)?;
        Some(BorderedLu { m, piv })
    }

    /// Solves the bordered system in place.
    pub fn solve(&self, b: &mut Extended<N>) {
        substitute(&self.m, &self.piv.swaps, b);
    }
}

/// The row swaps of a factorisation (one per step but the last of an (N+1)×(N+1) matrix) and
/// what it tells.
#[derive(Clone, Copy, Debug)]
struct Pivots<const N: usize> {
    swaps: [usize; N],
    info: Factored,
}

/// A square matrix the kernel factors in place: a dense array or a bordered block.
trait Square {
    /// Rows (and columns).
    const SIZE: usize;
    fn at(&self, i: usize, j: usize) -> f64;
    fn set(&mut self, i: usize, j: usize, x: f64);
    /// Swaps rows `a < b`.
    fn swap_rows(&mut self, a: usize, b: usize);
}

/// A right-hand side of a [`Square`] system, solved in place.
trait Column {
    fn at(&self, i: usize) -> f64;
    fn set(&mut self, i: usize, x: f64);
    fn swap(&mut self, a: usize, b: usize);
}

// The accessors are total: an index out of range (which the kernels never form) reads NaN and
// writes nothing, instead of panicking. In the kernels' loops the compiler proves the indices
// in range and removes the tests; what is left is for the row swaps, whose indices are data,
// and it is what lets `tests/no_panic` prove at link time that the solvers cannot panic.
impl<const N: usize> Square for [[f64; N]; N] {
    const SIZE: usize = N;
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.get(i)
            .and_then(|row| row.get(j))
            .copied()
            .unwrap_or(f64::NAN)
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, x: f64) {
        if let Some(e) = self.get_mut(i).and_then(|row| row.get_mut(j)) {
            *e = x;
        }
    }
    #[inline(always)]
    fn swap_rows(&mut self, a: usize, b: usize) {
        if a < N && b < N {
            self.swap(a, b);
        }
    }
}

impl<const N: usize> Column for [f64; N] {
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        self.get(i).copied().unwrap_or(f64::NAN)
    }
    #[inline(always)]
    fn set(&mut self, i: usize, x: f64) {
        if let Some(e) = self.get_mut(i) {
            *e = x;
        }
    }
    #[inline(always)]
    fn swap(&mut self, a: usize, b: usize) {
        if a < N && b < N {
            <[f64]>::swap(self, a, b);
        }
    }
}

impl<const N: usize> Square for Bordered<N> {
    const SIZE: usize = N + 1;
    #[inline(always)]
    fn at(&self, i: usize, j: usize) -> f64 {
        match (i < N, j < N) {
            (true, true) => self.block.at(i, j),
            (true, false) => self.column.at(i),
            (false, true) => self.row.at(j),
            (false, false) => self.corner,
        }
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, x: f64) {
        match (i < N, j < N) {
            (true, true) => self.block.set(i, j, x),
            (true, false) => self.column.set(i, x),
            (false, true) => self.row.set(j, x),
            (false, false) => self.corner = x,
        }
    }
    fn swap_rows(&mut self, a: usize, b: usize) {
        if a >= N {
            return;
        }
        if b < N {
            self.block.swap_rows(a, b);
            self.column.swap(a, b);
        } else {
            core::mem::swap(&mut self.block[a], &mut self.row);
            core::mem::swap(&mut self.column[a], &mut self.corner);
        }
    }
}

impl<const N: usize> Column for Extended<N> {
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        if i < N { self.head[i] } else { self.tail }
    }
    #[inline(always)]
    fn set(&mut self, i: usize, x: f64) {
        if i < N {
            self.head[i] = x;
        } else {
            self.tail = x;
        }
    }
    fn swap(&mut self, a: usize, b: usize) {
        let t = self.at(a);
        self.set(a, self.at(b));
        self.set(b, t);
    }
}

/// The fallback of a factorisation `mechanism!` generates (not public API): `z`, the Schur
/// complement its fixed pivot order could not factor, factored with partial pivoting by the
/// one kernel of this module, and stored in `stored` — the K² factors row by row, then the K
/// row swaps (as numbers: the generated storage is `f64`) — for [`fallback_solve`].
/// `Some((det Z, pivot ratio))`, `None` where a column has no usable pivot.
///
/// A function generic over K rather than code unrolled into every mechanism: this path is
/// cold, and unrolled it was an eighth of the code the integration tests compiled.
#[doc(hidden)]
pub fn fallback_factor<const K: usize>(
    mut z: [[f64; K]; K],
    stored: &mut [f64],
) -> Option<(f64, f64)> {
    // The generated storage always has room; a shorter one is a failure, not a panic.
    if stored.len() < K * K + K {
        return None;
    }
    let piv: Pivots<K> = eliminate(&mut z)?;
    let (factors, swaps) = stored.split_at_mut(K * K);
    for (to, &from) in factors.iter_mut().zip(z.as_flattened()) {
        *to = from;
    }
    for (to, &p) in swaps.iter_mut().zip(&piv.swaps) {
        *to = p as f64;
    }
    Some((piv.info.det, piv.info.pivot_ratio))
}

/// Solves `Z y = b` in place with what [`fallback_factor`] stored.
#[doc(hidden)]
pub fn fallback_solve<const K: usize>(stored: &[f64], y: &mut [f64; K]) {
    // What `fallback_factor` stored; a storage too short for it (never generated) leaves
    // missing entries NaN, so that the solution shows it, rather than panic.
    let mut z = [[f64::NAN; K]; K];
    for (to, &from) in z.as_flattened_mut().iter_mut().zip(stored) {
        *to = from;
    }
    let mut swaps = [0usize; K];
    for (p, &from) in swaps.iter_mut().zip(stored.get(K * K..).unwrap_or(&[])) {
        // Written by `fallback_factor` from an index below K; clamped all the same, so that a
        // storage that did not come from it cannot make the solve index out of bounds.
        *p = (from as usize).min(K.saturating_sub(1));
    }
    substitute(&z, &swaps, y);
}

/// `P A = L U` in place, with partial pivoting: the row swap of each step (the last step of
/// an (S+1)×(S+1) matrix has none to record), det A and the pivot ratio. `None` when a pivot
/// column is zero or not finite. det A itself may have over- or underflowed.
fn eliminate<A: Square, const S: usize>(a: &mut A) -> Option<Pivots<S>> {
    let n = A::SIZE;
    let mut swaps = [0; S];
    let mut det = 1.0;
    let (mut pmin, mut pmax) = (f64::INFINITY, 0.0f64);
    for k in 0..n {
        let mut p = k;
        let mut best = a.at(k, k).abs();
        for i in k + 1..n {
            let v = a.at(i, k).abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if !(best > 0.0) || !best.is_finite() {
            return None;
        }
        if k < S {
            swaps[k] = p;
        }
        if p != k {
            a.swap_rows(k, p);
            det = -det;
        }
        let d = a.at(k, k);
        det *= d;
        pmin = pmin.min(best);
        pmax = pmax.max(best);
        let inv = 1.0 / d;
        for i in k + 1..n {
            let l = a.at(i, k) * inv;
            a.set(i, k, l);
            if l != 0.0 {
                for j in k + 1..n {
                    a.set(i, j, a.at(i, j) - l * a.at(k, j));
                }
            }
        }
    }
    let pivot_ratio = if n == 0 { 1.0 } else { pmin / pmax };
    Some(Pivots {
        swaps,
        info: Factored { det, pivot_ratio },
    })
}

/// Solves `A y = b` in place with the factors of [`eliminate`].
fn substitute<A: Square, B: Column, const S: usize>(a: &A, swaps: &[usize; S], b: &mut B) {
    let n = A::SIZE;
    for (k, &p) in swaps.iter().enumerate() {
        if p != k {
            b.swap(k, p);
        }
    }
    for i in 0..n {
        let mut s = 0.0;
        for j in 0..i {
            s += a.at(i, j) * b.at(j);
        }
        b.set(i, b.at(i) - s);
    }
    for i in (0..n).rev() {
        let mut s = 0.0;
        for j in i + 1..n {
            s += a.at(i, j) * b.at(j);
        }
        b.set(i, (b.at(i) - s) / a.at(i, i));
    }
}

/// Solves `Aᵀ y = b` in place with the factors of [`eliminate`]: `Uᵀ z = b` forward, `Lᵀ w = z`
/// backward, then the row swaps undone in reverse.
fn substitute_transposed<A: Square, B: Column, const S: usize>(
    a: &A,
    swaps: &[usize; S],
    b: &mut B,
) {
    let n = A::SIZE;
    for i in 0..n {
        let mut s = 0.0;
        for j in 0..i {
            s += a.at(j, i) * b.at(j);
        }
        b.set(i, (b.at(i) - s) / a.at(i, i));
    }
    for i in (0..n).rev() {
        let mut s = 0.0;
        for j in i + 1..n {
            s += a.at(j, i) * b.at(j);
        }
        b.set(i, b.at(i) - s);
    }
    for (k, &p) in swaps.iter().enumerate().rev() {
        if p != k {
            b.swap(k, p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mul<const N: usize>(a: &[[f64; N]; N], y: &[f64; N]) -> [f64; N] {
        core::array::from_fn(|i| (0..N).map(|j| a[i][j] * y[j]).sum())
    }

    #[test]
    fn solves_both_ways_and_reports_determinant() {
        let a = [
            [2.0, -1.0, 0.5, 3.0],
            [1.0, 4.0, -2.0, 0.0],
            [0.0, 1.5, 1.0, -1.0],
            [-3.0, 0.0, 2.0, 1.0],
        ];
        let lu = Lu::new(a).unwrap();
        let b = [1.0, 2.0, 3.0, 4.0];
        let mut y = b;
        lu.solve(&mut y);
        let back = mul(&a, &y);
        let at: [[f64; 4]; 4] = core::array::from_fn(|i| core::array::from_fn(|j| a[j][i]));
        let mut z = b;
        lu.solve_transposed(&mut z);
        let back_t = mul(&at, &z);
        for i in 0..4 {
            assert!((back[i] - b[i]).abs() < 1e-12);
            assert!((back_t[i] - b[i]).abs() < 1e-12);
        }
        // det by cofactor expansion of the same matrix.
        let det = Lu::new(at).unwrap().det();
        assert!((lu.det() - det).abs() < 1e-12 * det.abs());
    }

    #[test]
    fn condition_estimate_tracks_the_distance_to_singularity() {
        assert!(
            Lu::new([[1.0, 0.0], [0.0, 1.0]])
                .unwrap()
                .reciprocal_condition()
                > 0.99
        );
        for eps in [1e-3, 1e-8, 1e-13] {
            let r = Lu::new([[1.0, 1.0], [1.0, 1.0 + eps]])
                .unwrap()
                .reciprocal_condition();
            // κ₁ = 4 (2 + ε) / ε exactly.
            let exact = eps / (4.0 * (2.0 + eps));
            assert!(
                r >= exact * 0.3 && r <= exact * 3.0,
                "{eps}: {r} vs {exact}"
            );
        }
        assert!(Lu::new([[f64::NAN, 0.0], [0.0, 1.0]]).is_none());
        assert!(
            Lu::new([[1e300, 1e300], [-1e300, 1e300]]).is_none(),
            "det overflows"
        );
    }

    #[test]
    fn bordered_matrix_is_solved_even_when_the_block_is_singular() {
        // B singular (fold), bordered system regular; the border row must be swapped up.
        let m = Bordered {
            block: [[1.0, 1.0], [1.0, 1.0]],
            column: [1.0, 0.0],
            row: [1.0, -1.0],
            corner: 0.0,
        };
        let lu = BorderedLu::new(m).unwrap();
        let mut y = Extended {
            head: [1.0, 2.0],
            tail: 3.0,
        };
        lu.solve(&mut y);
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| m.at(i, j) * y.at(j)).sum();
            assert!((r - [1.0, 2.0, 3.0][i]).abs() < 1e-12);
        }
        assert!(Lu::new([[1.0, 1.0], [1.0, 1.0]]).is_none());
    }

    #[test]
    fn bordered_and_dense_factorisations_agree() {
        // The same 3×3 matrix as a dense array and as a 2×2 block with its border.
        let a = [[0.5, 2.0, -1.0], [3.0, 1.0, 4.0], [-2.0, 6.0, 0.25]];
        let m = Bordered {
            block: [[0.5, 2.0], [3.0, 1.0]],
            column: [-1.0, 4.0],
            row: [-2.0, 6.0],
            corner: 0.25,
        };
        let dense = Lu::new(a).unwrap();
        let bordered = BorderedLu::new(m).unwrap();
        assert_eq!(dense.det(), bordered.piv.info.det);
        let mut y = [1.0, -2.0, 0.5];
        let mut z = Extended {
            head: [1.0, -2.0],
            tail: 0.5,
        };
        dense.solve(&mut y);
        bordered.solve(&mut z);
        assert_eq!(y, [z.head[0], z.head[1], z.tail]);
    }
}
