//! LU factorisation with partial pivoting, without heap: [`Lu`] for a dense n×n matrix, and
//! the storage and record of the factorisation `mechanism!` generates for B's sparsity pattern
//! ([`SparseFactor`], [`Pivots`], [`Factored`]).
//!
//! Sizes are in the types: an [`Lu<N>`] owns its `N`×`N` factors and its `N` row swaps, so no
//! call can pass a matrix larger than its record of swaps (the old `factor::<N, _>` trusted a
//! debug assertion for that). The (n+1)×(n+1) bordered matrix of pseudo-arc-length continuation
//! (Eq. 10) has its own type inside the crate, built on the same kernel.
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
//! A matrix larger than the factorisation's record is a type error, not a wrong answer:
//!
//! ```compile_fail
//! let mut a = [[4.0, 1.0, 0.0], [1.0, 4.0, 1.0], [0.0, 1.0, 4.0]];
//! let _ = linkage::lu::factor::<1, _>(&mut a);
//! ```

/// The row swaps of a factorisation of a `K`×`K` block and what it tells about conditioning.
/// The generated factorisation records its dense Schur complement with this.
#[derive(Clone, Copy, Debug)]
pub struct Pivots<const N: usize> {
    swaps: [usize; N],
    /// The determinant (sign and magnitude) of the factored matrix.
    pub det: f64,
    /// Smallest |pivot| / largest |pivot|: a cheap conditioning indicator.
    pub pivot_ratio: f64,
}

impl<const N: usize> Pivots<N> {
    /// The row swap made at each step of the factorisation.
    pub fn swaps(&self) -> [usize; N] {
        self.swaps
    }

    /// A factorisation's record, for generated elimination code.
    pub const fn from_parts(swaps: [usize; N], det: f64, pivot_ratio: f64) -> Self {
        Pivots {
            swaps,
            det,
            pivot_ratio,
        }
    }

    /// No swaps, determinant 1: the state before a factorisation.
    pub const fn new() -> Self {
        Pivots {
            swaps: [0; N],
            det: 1.0,
            pivot_ratio: 1.0,
        }
    }
}

impl<const N: usize> Default for Pivots<N> {
    fn default() -> Self {
        Self::new()
    }
}

/// What a factorisation of B tells besides itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Factored {
    /// det B.
    pub det: f64,
    /// Smallest |pivot| / largest |pivot| of the dense part: a conditioning indicator.
    pub pivot_ratio: f64,
}

/// Storage of the factorisation that `mechanism!` generates for a sparsity pattern: the
/// `K`×`K` dense Schur complement with its pivots, `L` multipliers and `U` entries of the
/// statically eliminated rows.
#[derive(Clone, Copy, Debug)]
pub struct SparseFactor<const K: usize, const L: usize, const U: usize> {
    pub z: [[f64; K]; K],
    pub piv: Pivots<K>,
    pub l: [f64; L],
    pub u: [f64; U],
}

impl<const K: usize, const L: usize, const U: usize> SparseFactor<K, L, U> {
    pub const fn new() -> Self {
        SparseFactor {
            z: [[0.0; K]; K],
            piv: Pivots::new(),
            l: [0.0; L],
            u: [0.0; U],
        }
    }
}

impl<const K: usize, const L: usize, const U: usize> Default for SparseFactor<K, L, U> {
    fn default() -> Self {
        Self::new()
    }
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
        let piv = factor_rows(&mut a)?;
        Some(Lu { lu: a, piv, norm1 })
    }

    /// The determinant of the factored matrix.
    pub fn det(&self) -> f64 {
        self.piv.det
    }

    /// Smallest |pivot| / largest |pivot|: cheap, but not scale-free (see
    /// [`Self::reciprocal_condition`]).
    pub fn pivot_ratio(&self) -> f64 {
        self.piv.pivot_ratio
    }

    /// Solves `A y = b` in place.
    pub fn solve(&self, b: &mut [f64; N]) {
        let a = &self.lu;
        for k in 0..N {
            let p = self.piv.swaps[k];
            if p != k {
                b.swap(k, p);
            }
        }
        for i in 0..N {
            let s: f64 = a[i][..i].iter().zip(&b[..i]).map(|(l, y)| l * y).sum();
            b[i] -= s;
        }
        for i in (0..N).rev() {
            let s: f64 = a[i][i + 1..]
                .iter()
                .zip(&b[i + 1..])
                .map(|(u, y)| u * y)
                .sum();
            b[i] = (b[i] - s) / a[i][i];
        }
    }

    /// Solves `Aᵀ y = b` in place.
    pub fn solve_transposed(&self, b: &mut [f64; N]) {
        let a = &self.lu;
        // Uᵀ z = b (forward), Lᵀ w = z (backward), then undo the row swaps in reverse.
        for i in 0..N {
            let s: f64 = (0..i).map(|j| a[j][i] * b[j]).sum();
            b[i] = (b[i] - s) / a[i][i];
        }
        for i in (0..N).rev() {
            let s: f64 = (i + 1..N).map(|j| a[j][i] * b[j]).sum();
            b[i] -= s;
        }
        for k in (0..N).rev() {
            let p = self.piv.swaps[k];
            if p != k {
                b.swap(k, p);
            }
        }
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
        if r.is_nan() {
            0.0
        } else {
            r
        }
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
            e[j] = 1.0;
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

/// The kernel of [`Lu::new`], written over rows so that the compiler can drop bounds checks.
fn factor_rows<const N: usize>(a: &mut [[f64; N]; N]) -> Option<Pivots<N>> {
    let mut piv = Pivots {
        swaps: [0; N],
        det: 1.0,
        pivot_ratio: 0.0,
    };
    let (mut pmin, mut pmax) = (f64::INFINITY, 0.0f64);
    for k in 0..N {
        let mut p = k;
        let mut best = a[k][k].abs();
        for (i, row) in a.iter().enumerate().skip(k + 1) {
            let v = row[k].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if !(best > 0.0) || !best.is_finite() {
            return None;
        }
        piv.swaps[k] = p;
        if p != k {
            a.swap(k, p);
            piv.det = -piv.det;
        }
        let (top, bottom) = a.split_at_mut(k + 1);
        let pivot_row = &top[k];
        let d = pivot_row[k];
        piv.det *= d;
        pmin = pmin.min(best);
        pmax = pmax.max(best);
        let inv = 1.0 / d;
        for row in bottom.iter_mut() {
            let l = row[k] * inv;
            row[k] = l;
            if l != 0.0 {
                for (x, u) in row[k + 1..].iter_mut().zip(&pivot_row[k + 1..]) {
                    *x -= l * u;
                }
            }
        }
    }
    piv.pivot_ratio = if N == 0 { 1.0 } else { pmin / pmax };
    if !piv.det.is_finite() {
        return None;
    }
    Some(piv)
}

/// `[[B, c], [rᵀ, d]]`: an n×n block bordered by a column, a row and a corner.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Bordered<const N: usize> {
    pub block: [[f64; N]; N],
    pub column: [f64; N],
    pub row: [f64; N],
    pub corner: f64,
}

impl<const N: usize> Bordered<N> {
    #[inline(always)]
    fn get(&self, i: usize, j: usize) -> f64 {
        match (i < N, j < N) {
            (true, true) => self.block[i][j],
            (true, false) => self.column[i],
            (false, true) => self.row[j],
            (false, false) => self.corner,
        }
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, x: f64) {
        match (i < N, j < N) {
            (true, true) => self.block[i][j] = x,
            (true, false) => self.column[i] = x,
            (false, true) => self.row[j] = x,
            (false, false) => self.corner = x,
        }
    }
}

/// `[head; tail]`, the (n+1)-vector of a bordered system.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Extended<const N: usize> {
    pub head: [f64; N],
    pub tail: f64,
}

impl<const N: usize> Extended<N> {
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        if i < N {
            self.head[i]
        } else {
            self.tail
        }
    }
    #[inline(always)]
    fn put(&mut self, i: usize, x: f64) {
        if i < N {
            self.head[i] = x;
        } else {
            self.tail = x;
        }
    }
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
        let n = N + 1;
        let mut piv = Pivots {
            swaps: [0; N],
            det: 1.0,
            pivot_ratio: 0.0,
        };
        for k in 0..n {
            let mut p = k;
            let mut best = m.get(k, k).abs();
            for i in k + 1..n {
                let v = m.get(i, k).abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if !(best > 0.0) || !best.is_finite() {
                return None;
            }
            if k < N {
                piv.swaps[k] = p;
            }
            if p != k {
                for j in 0..n {
                    let t = m.get(k, j);
                    m.set(k, j, m.get(p, j));
                    m.set(p, j, t);
                }
                piv.det = -piv.det;
            }
            let d = m.get(k, k);
            piv.det *= d;
            let inv = 1.0 / d;
            for i in k + 1..n {
                let l = m.get(i, k) * inv;
                m.set(i, k, l);
                if l != 0.0 {
                    for j in k + 1..n {
                        m.set(i, j, m.get(i, j) - l * m.get(k, j));
                    }
                }
            }
        }
        Some(BorderedLu { m, piv })
    }

    /// Solves the bordered system in place.
    pub fn solve(&self, b: &mut Extended<N>) {
        let n = N + 1;
        for k in 0..N {
            let p = self.piv.swaps[k];
            if p != k {
                let t = b.at(k);
                b.put(k, b.at(p));
                b.put(p, t);
            }
        }
        for i in 0..n {
            let mut s = b.at(i);
            for j in 0..i {
                s -= self.m.get(i, j) * b.at(j);
            }
            b.put(i, s);
        }
        for i in (0..n).rev() {
            let mut s = b.at(i);
            for j in i + 1..n {
                s -= self.m.get(i, j) * b.at(j);
            }
            b.put(i, s / self.m.get(i, i));
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
        // B singular (fold), bordered system regular.
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
            let r: f64 = (0..3).map(|j| m.get(i, j) * y.at(j)).sum();
            assert!((r - [1.0, 2.0, 3.0][i]).abs() < 1e-12);
        }
        assert!(Lu::new([[1.0, 1.0], [1.0, 1.0]]).is_none());
    }
}
