//! Dense LU factorisation with partial pivoting, for the n×n Jacobian B and for the
//! (n+1)×(n+1) bordered matrix of pseudo-arc-length continuation (Eq. 10), without heap.

/// A square matrix the factorisation can work on in place.
pub trait Square {
    fn dim(&self) -> usize;
    fn get(&self, i: usize, j: usize) -> f64;
    fn set(&mut self, i: usize, j: usize, x: f64);
}

impl<const N: usize> Square for [[f64; N]; N] {
    #[inline(always)]
    fn dim(&self) -> usize {
        N
    }
    #[inline(always)]
    fn get(&self, i: usize, j: usize) -> f64 {
        self[i][j]
    }
    #[inline(always)]
    fn set(&mut self, i: usize, j: usize, x: f64) {
        self[i][j] = x;
    }
}

/// `[[B, c], [rᵀ, d]]`: an n×n block bordered by a column, a row and a corner.
#[derive(Clone, Copy, Debug)]
pub struct Bordered<const N: usize> {
    pub block: [[f64; N]; N],
    pub column: [f64; N],
    pub row: [f64; N],
    pub corner: f64,
}

impl<const N: usize> Square for Bordered<N> {
    #[inline(always)]
    fn dim(&self) -> usize {
        N + 1
    }
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

/// The row swaps of a factorisation (at most `N` of them for a matrix of size `N + 1`) and
/// what it tells about conditioning.
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

/// Factors a dense `N`×`N` array in place (`L` unit lower, `U` upper) with partial pivoting:
/// the same algorithm as [`factor`], written over rows so that the compiler can drop bounds
/// checks. `None` for an exactly singular or non-finite matrix.
pub fn factor_dense<const N: usize>(a: &mut [[f64; N]; N]) -> Option<Pivots<N>> {
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
    Some(piv)
}

/// Solves `A y = b` in place with a factorisation from [`factor_dense`].
pub fn solve_dense<const N: usize>(a: &[[f64; N]; N], piv: &Pivots<N>, b: &mut [f64; N]) {
    for k in 0..N {
        let p = piv.swaps[k];
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

/// Factors `a` in place (`L` unit lower, `U` upper). Returns `None` for an exactly singular
/// or non-finite matrix.
pub fn factor<const N: usize, A: Square>(a: &mut A) -> Option<Pivots<N>> {
    let n = a.dim();
    debug_assert!(n <= N + 1);
    let mut piv = Pivots {
        swaps: [0; N],
        det: 1.0,
        pivot_ratio: 0.0,
    };
    let (mut pmin, mut pmax) = (f64::INFINITY, 0.0f64);
    for k in 0..n {
        let mut p = k;
        let mut best = a.get(k, k).abs();
        for i in k + 1..n {
            let v = a.get(i, k).abs();
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
                let t = a.get(k, j);
                a.set(k, j, a.get(p, j));
                a.set(p, j, t);
            }
            piv.det = -piv.det;
        }
        let d = a.get(k, k);
        piv.det *= d;
        pmin = pmin.min(best);
        pmax = pmax.max(best);
        let inv = 1.0 / d;
        for i in k + 1..n {
            let l = a.get(i, k) * inv;
            a.set(i, k, l);
            if l != 0.0 {
                for j in k + 1..n {
                    a.set(i, j, a.get(i, j) - l * a.get(k, j));
                }
            }
        }
    }
    piv.pivot_ratio = pmin / pmax;
    Some(piv)
}

/// A right-hand side: a plain array, or an n-vector with one more entry for bordered systems.
pub trait Column {
    fn at(&self, i: usize) -> f64;
    fn put(&mut self, i: usize, x: f64);
}

impl<const N: usize> Column for [f64; N] {
    #[inline(always)]
    fn at(&self, i: usize) -> f64 {
        self[i]
    }
    #[inline(always)]
    fn put(&mut self, i: usize, x: f64) {
        self[i] = x;
    }
}

/// `[head; tail]`, the (n+1)-vector of a bordered system.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Extended<const N: usize> {
    pub head: [f64; N],
    pub tail: f64,
}

impl<const N: usize> Column for Extended<N> {
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

impl<const N: usize> Extended<N> {
    pub fn norm(&self) -> f64 {
        let mut s = self.tail * self.tail;
        for h in &self.head {
            s += h * h;
        }
        crate::math::sqrt(s)
    }
}

/// Solves `A y = b` in place with a factorisation from [`factor`].
pub fn solve<const N: usize, A: Square, B: Column>(a: &A, piv: &Pivots<N>, b: &mut B) {
    let n = a.dim();
    for k in 0..n.min(N) {
        let p = piv.swaps[k];
        if p != k {
            let t = b.at(k);
            b.put(k, b.at(p));
            b.put(p, t);
        }
    }
    for i in 0..n {
        let mut s = b.at(i);
        for j in 0..i {
            s -= a.get(i, j) * b.at(j);
        }
        b.put(i, s);
    }
    for i in (0..n).rev() {
        let mut s = b.at(i);
        for j in i + 1..n {
            s -= a.get(i, j) * b.at(j);
        }
        b.put(i, s / a.get(i, i));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_and_reports_determinant() {
        let mut a = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 1.0]];
        let orig = a;
        let piv: Pivots<3> = factor(&mut a).unwrap();
        // det = 0*(1-0) - 2*(1-0) + 1*(0-3) = -5
        assert!((piv.det + 5.0).abs() < 1e-12);
        let mut b = [3.0, 2.0, 4.0];
        solve(&a, &piv, &mut b);
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| orig[i][j] * b[j]).sum();
            assert!((r - [3.0, 2.0, 4.0][i]).abs() < 1e-12);
        }
    }

    #[test]
    fn dense_and_generic_factorisations_agree() {
        let a = [
            [2.0, -1.0, 0.5, 3.0],
            [1.0, 4.0, -2.0, 0.0],
            [0.0, 1.5, 1.0, -1.0],
            [-3.0, 0.0, 2.0, 1.0],
        ];
        let (mut g, mut d) = (a, a);
        let pg: Pivots<4> = factor(&mut g).unwrap();
        let pd = factor_dense(&mut d).unwrap();
        assert_eq!(g, d);
        assert_eq!(pg.det, pd.det);
        let (mut yg, mut yd) = ([1.0, 2.0, 3.0, 4.0], [1.0, 2.0, 3.0, 4.0]);
        solve(&g, &pg, &mut yg);
        solve_dense(&d, &pd, &mut yd);
        for i in 0..4 {
            assert!((yg[i] - yd[i]).abs() < 1e-14);
        }
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
        let mut f = m;
        let piv: Pivots<2> = factor(&mut f).unwrap();
        let mut y = Extended {
            head: [1.0, 2.0],
            tail: 3.0,
        };
        solve(&f, &piv, &mut y);
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| m.get(i, j) * y.at(j)).sum();
            assert!((r - [1.0, 2.0, 3.0][i]).abs() < 1e-12);
        }
        let mut s = [[1.0, 1.0], [1.0, 1.0]];
        assert!(factor::<2, _>(&mut s).is_none());
    }
}
