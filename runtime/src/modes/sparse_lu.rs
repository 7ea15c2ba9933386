//! LU factorisation of the complex Jacobian B = ∂F/∂v, planned once from the generated
//! sparsity pattern.
//!
//! The constraint systems the DSL generates have many linear rows (rigid-body combinations with
//! a constant −1 per eliminated pivot). The plan first eliminates on such constant entries in
//! a fixed order (Markowitz: fewest updates first), which needs no pivot search and cannot meet
//! a small pivot; what remains, the Schur complement on the other rows and columns, is factored
//! densely with partial pivoting. For the Stewart platform that is 9 static pivots and a 9×9
//! complement instead of an 18×18 dense factorisation: about six times less work per step of
//! the path tracker, which is where the time of a query goes.

use super::complex::Complex;

/// The first `n` entries of one of the plan's lists (`n` ≤ N by construction).
///
/// Every index a [`Plan`] holds is below N by its construction (each comes from a loop over
/// `0..N`), and every count is at most N. The factorisation and the solves still read them
/// with `get` (a failed one is a failed factorisation, or a NaN solution): the same compare
/// and branch as a bounds check, which here cannot panic (`tests/no_panic` proves the query
/// total). A clamp (`min`) instead cost 1.6 % more instructions per query.
#[inline(always)]
fn head<const N: usize>(list: &[u8; N], n: u8) -> &[u8] {
    list.get(..n as usize).unwrap_or(&[])
}

/// Writes the indices `i < N` for which `keep(i)` holds to the front of `out`, in order, and
/// returns how many there are; the entry after them is left holding N − 1 (never read: every
/// list is read through [`head`]).
///
/// Every index is stored and the position advanced by `keep(i)` as a number, without a branch:
/// the same lists written as a `zip` of the slots with a `filter` of `0..N` made LLVM's
/// loop-idiom pass run for more than ten minutes at opt-level 3 for N = 36 (an Exechon's
/// all-modes query; BENCHMARKS.md), where this form builds in seconds.
#[inline(always)]
fn compact<const N: usize>(out: &mut [u8; N], keep: impl Fn(usize) -> bool) -> u8 {
    let mut n = 0usize;
    for i in 0..N {
        if let Some(slot) = out.get_mut(n) {
            *slot = i as u8;
        }
        n += usize::from(keep(i));
    }
    n as u8
}

/// `t -= s · x` on complex vectors held as separate real and imaginary parts, over the
/// shortest of the four slices: the one update of every dense loop of the factorisation and
/// the solves. The operations, and so the results, are the same bit for bit as the loops
/// written in place were.
///
/// A function of its own so that its slices are distinct by their types (`&mut` and `&`
/// arguments): written in place on columns of the same arrays, the loop checked for overlap
/// at run time and, in the tests' profile (optimised, with debug assertions), took its scalar
/// branch in every column. That profile keeps it out of line, where the arguments stay
/// distinct; release builds inline it, as their loops were already in vector code
/// (BENCHMARKS.md, Every assembly mode). Slices cut to one length and an index, not zips,
/// whose constructors the tests' profile left as calls.
#[cfg_attr(debug_assertions, inline(never))]
#[cfg_attr(not(debug_assertions), inline(always))]
fn sub_scaled(tr: &mut [f64], ti: &mut [f64], sr: &[f64], si: &[f64], xr: f64, xi: f64) {
    let n = tr.len().min(ti.len()).min(sr.len()).min(si.len());
    let (tr, ti, sr, si) = (&mut tr[..n], &mut ti[..n], &sr[..n], &si[..n]);
    for i in 0..n {
        tr[i] -= sr[i] * xr - si[i] * xi;
        ti[i] -= sr[i] * xi + si[i] * xr;
    }
}

/// The elimination order and the update lists, computed from the pattern.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plan<const N: usize> {
    /// Number of static pivots.
    statics: usize,
    /// `(row, column)` of each static pivot, in elimination order.
    pivot: [(u8, u8); N],
    /// Rows updated by static pivot k (structural nonzeros of its column below it).
    rows: [[u8; N]; N],
    n_rows: [u8; N],
    /// The other structural nonzeros of static pivot k's row, in columns not yet eliminated.
    cols: [[u8; N]; N],
    n_cols: [u8; N],
    /// Per row, the columns where static elimination creates an entry the pattern lacks
    /// (zeroed before each factorisation).
    fill: [[u8; N]; N],
    n_fill: [u8; N],
    /// Rows and columns of the dense remainder.
    rest_rows: [u8; N],
    rest_cols: [u8; N],
    rest: usize,
    /// Per static pivot k, the static pivots k' > k whose column is among `cols[k]`: the part
    /// of its back-substitution that must wait for them (the rest columns' part is a dense
    /// product, see [`Lu::solve`]).
    later: [[u8; N]; N],
    n_later: [u8; N],
    /// Number of pattern entries, and where each goes in the row-major N × N matrix.
    nnz: usize,
    flat: [[u16; N]; N],
}

/// Why no plan could be made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PlanError {
    /// More than 255 unknowns (the plan indexes with bytes).
    TooLarge,
    /// A pattern entry lies outside the matrix.
    BadPattern,
}

impl<const N: usize> Plan<N> {
    /// Plans the factorisation of matrices with nonzeros at `pattern`. `a` and `b` are the
    /// values at two unrelated points: an entry equal in both is taken as constant, and only
    /// constant entries at least a tenth of the largest magnitude in their row serve as static
    /// pivots (a constant pivot cannot become small relative to its row, and the bound keeps
    /// growth modest). Scaling a row by a common factor, as the projective formulation does,
    /// keeps that property.
    pub(crate) fn new(pattern: &[(usize, usize)], a: &[f64], b: &[f64]) -> Result<Self, PlanError> {
        if N > 255 {
            return Err(PlanError::TooLarge);
        }
        let mut nz = [[false; N]; N];
        // A constant, never-updated entry's value; NaN otherwise.
        let mut fixed = [[f64::NAN; N]; N];
        let mut row_max = [0.0f64; N];
        for (k, &(r, c)) in pattern.iter().enumerate() {
            if r >= N || c >= N || k >= a.len() || k >= b.len() {
                return Err(PlanError::BadPattern);
            }
            nz[r][c] = true;
            if a[k] == b[k] && a[k] != 0.0 && a[k].is_finite() {
                fixed[r][c] = a[k];
            }
            row_max[r] = row_max[r].max(a[k].abs()).max(b[k].abs());
        }
        let mut plan = Plan {
            statics: 0,
            pivot: [(0, 0); N],
            rows: [[0; N]; N],
            n_rows: [0; N],
            cols: [[0; N]; N],
            n_cols: [0; N],
            fill: [[0; N]; N],
            n_fill: [0; N],
            rest_rows: [0; N],
            rest_cols: [0; N],
            rest: 0,
            later: [[0; N]; N],
            n_later: [0; N],
            nnz: pattern.len(),
            flat: [[0; N]; N],
        };
        if pattern.len() > N * N {
            return Err(PlanError::BadPattern);
        }
        for (k, &(r, c)) in pattern.iter().enumerate() {
            plan.flat[k / N][k % N] = (r * N + c) as u16;
        }
        let mut row_done = [false; N];
        let mut col_done = [false; N];
        loop {
            // The constant pivot with the smallest Markowitz count.
            let mut best: Option<(usize, usize, usize)> = None;
            for r in (0..N).filter(|&r| !row_done[r]) {
                let rc = (0..N).filter(|&j| !col_done[j] && nz[r][j]).count();
                for c in (0..N).filter(|&c| !col_done[c]) {
                    let v = fixed[r][c];
                    if !(v.abs() >= 0.1 * row_max[r]) {
                        continue;
                    }
                    let cc = (0..N).filter(|&i| !row_done[i] && nz[i][c]).count();
                    let cost = (rc - 1) * (cc - 1);
                    if best.is_none_or(|(_, _, b)| cost < b) {
                        best = Some((r, c, cost));
                    }
                }
            }
            let Some((r, c, _)) = best else { break };
            // Each pivot retires a row, so there are at most N; the bounds below are what the
            // construction guarantees, written so that the no-panic proof sees them too.
            let k = plan.statics;
            if k >= N {
                return Err(PlanError::BadPattern);
            }
            plan.pivot[k] = (r as u8, c as u8);
            row_done[r] = true;
            col_done[c] = true;
            plan.n_rows[k] = compact(&mut plan.rows[k], |i| !row_done[i] && nz[i][c]);
            plan.n_cols[k] = compact(&mut plan.cols[k], |j| !col_done[j] && nz[r][j]);
            // Updated entries fill in and are no longer constant.
            let (rows, cols) = (plan.rows[k], plan.cols[k]);
            for &i in head(&rows, plan.n_rows[k]) {
                let i = usize::from(i).min(N - 1);
                for &j in head(&cols, plan.n_cols[k]) {
                    let j = usize::from(j).min(N - 1);
                    if !nz[i][j] {
                        // Each entry fills in once: at most N per row.
                        let Some(slot) = plan.fill[i].get_mut(usize::from(plan.n_fill[i])) else {
                            return Err(PlanError::BadPattern);
                        };
                        *slot = j as u8;
                        plan.n_fill[i] += 1;
                    }
                    nz[i][j] = true;
                    fixed[i][j] = f64::NAN;
                }
            }
            plan.statics += 1;
        }
        // The rows and columns left for the dense remainder (as many of each: every pivot
        // retired one of both).
        plan.rest = usize::from(compact(&mut plan.rest_rows, |i| !row_done[i]));
        compact(&mut plan.rest_cols, |j| !col_done[j]);
        let statics = plan.statics.min(N);
        for k in 0..statics {
            for k2 in k + 1..statics {
                let c2 = plan.pivot[k2].1;
                if head(&plan.cols[k], plan.n_cols[k]).contains(&c2) {
                    // At most one per later pivot: fewer than N.
                    let Some(slot) = plan.later[k].get_mut(usize::from(plan.n_later[k])) else {
                        return Err(PlanError::BadPattern);
                    };
                    *slot = k2 as u8;
                    plan.n_later[k] += 1;
                }
            }
        }
        Ok(plan)
    }

    /// Number of pivots taken on constant entries, and the size of the dense remainder.
    pub(crate) fn shape(&self) -> (usize, usize) {
        (self.statics, self.rest)
    }
}

/// The border of a bordered matrix `[[B, col], [row, corner]]` (see [`Lu::factor`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Border<const N: usize> {
    pub(crate) col: [Complex; N],
    pub(crate) row: [Complex; N],
    pub(crate) corner: Complex,
}

/// A factorisation of B (or of B bordered by one row and column): the static phase in place in
/// `a` (and in the border vectors); the dense remainder — the Schur complement on the other
/// rows and columns, with the border as its last row and column — compacted, by columns, real
/// and imaginary parts in separate arrays, so that the eliminations and substitutions are
/// updates of plain f64 vectors (no dot products, which the compiler may not reorder into
/// vector code, and no shuffles of interleaved complex numbers). The static pivots' rows,
/// restricted to the remainder's columns, are kept the same way for the back-substitution.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lu<const N: usize> {
    a: [[Complex; N]; N],
    border: Option<Border<N>>,
    /// The remainder's factors by columns: `tr[j][i]` is entry (i, j) (L below the diagonal,
    /// U on and above it).
    tr: [[f64; N]; N],
    ti: [[f64; N]; N],
    /// `wr[j][k]`: static pivot k's row in column j of the remainder (the border's column
    /// last).
    wr: [[f64; N]; N],
    wi: [[f64; N]; N],
    /// Size of the compact remainder (the plan's plus one with a border).
    m: usize,
    /// Original row of each row of the remainder: an index into the plan's rest rows, or the
    /// plan's rest count for the border row.
    perm: [u8; N],
    inv_static: [Complex; N],
    inv_dense: [Complex; N],
    /// Smallest and largest |pivot| (max-norm of the complex value).
    pub(crate) min_pivot: f64,
    pub(crate) max_pivot: f64,
}

impl<const N: usize> Lu<N> {
    pub(crate) const fn new() -> Self {
        Lu {
            a: [[Complex::ZERO; N]; N],
            border: None,
            tr: [[0.0; N]; N],
            ti: [[0.0; N]; N],
            wr: [[0.0; N]; N],
            wi: [[0.0; N]; N],
            m: 0,
            perm: [0; N],
            inv_static: [Complex::ZERO; N],
            inv_dense: [Complex::ZERO; N],
            min_pivot: 0.0,
            max_pivot: 0.0,
        }
    }

    /// Smallest over largest |pivot|: a cheap indicator of how near B is to singular.
    pub(crate) fn pivot_ratio(&self) -> f64 {
        if self.max_pivot > 0.0 {
            self.min_pivot / self.max_pivot
        } else {
            0.0
        }
    }

    /// Factors the matrix whose nonzeros are `values` in the order of the plan's pattern,
    /// bordered by `border` if given. A border needs at least one static pivot (the compact
    /// remainder has room for N rows). `false` if a pivot is zero or not finite.
    pub(crate) fn factor(
        &mut self,
        plan: &Plan<N>,
        values: &[Complex],
        border: Option<&Border<N>>,
    ) -> bool {
        crate::dispatch::fastest(
            #[inline(always)]
            || self.factor_checked(plan, values, border),
        )
        .is_some()
    }

    /// [`Lu::factor`], `None` for `false`; inlined into each of
    /// [`fastest`](crate::dispatch::fastest)'s twins.
    #[inline(always)]
    fn factor_checked(
        &mut self,
        plan: &Plan<N>,
        values: &[Complex],
        border: Option<&Border<N>>,
    ) -> Option<()> {
        let n = plan.rest.min(N);
        let statics = plan.statics.min(N);
        if border.is_some() && n >= N {
            return None;
        }
        self.border = border.copied();
        let a = &mut self.a;
        for (row, (fill, &n_fill)) in a.iter_mut().zip(plan.fill.iter().zip(&plan.n_fill)) {
            for &j in head(fill, n_fill) {
                *row.get_mut(j as usize)? = Complex::ZERO;
            }
        }
        {
            let flat = a.as_flattened_mut();
            let places = &plan.flat.as_flattened()[..plan.nnz.min(N * N)];
            for (&at, &x) in places.iter().zip(values) {
                *flat.get_mut(at as usize)? = x;
            }
        }
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for k in 0..statics {
            let (r, c) = (plan.pivot[k].0 as usize, plan.pivot[k].1 as usize);
            let p = *a.get(r)?.get(c)?;
            let m = p.abs_max();
            if !(m > 0.0) || !p.is_finite() {
                return None;
            }
            lo = lo.min(m);
            hi = hi.max(m);
            let inv = p.recip();
            self.inv_static[k] = inv;
            let cols = head(&plan.cols[k], plan.n_cols[k]);
            for &i in head(&plan.rows[k], plan.n_rows[k]) {
                let i = i as usize;
                let l = *a.get(i)?.get(c)? * inv;
                a[i][c] = l;
                for &j in cols {
                    let j = j as usize;
                    let u = *a[r].get(j)?;
                    a[i][j] -= l * u;
                }
                if let Some(b) = self.border.as_mut() {
                    let u = b.col[r];
                    b.col[i] -= l * u;
                }
            }
            if let Some(b) = self.border.as_mut() {
                // The border row has an entry in every column.
                let l = b.row[c] * inv;
                b.row[c] = l;
                for &j in cols {
                    let j = j as usize;
                    let u = *a[r].get(j)?;
                    b.row[j] -= l * u;
                }
                let u = b.col[r];
                b.corner -= l * u;
            }
        }
        let m = (n + self.border.is_some() as usize).min(N);
        self.m = m;
        // The static rows in the remainder's columns.
        let rest_cols = &plan.rest_cols[..n];
        for k in 0..statics {
            let r = plan.pivot[k].0 as usize;
            let row = a.get(r)?;
            for ((wr, wi), &c) in self.wr.iter_mut().zip(self.wi.iter_mut()).zip(rest_cols) {
                let x = *row.get(c as usize)?;
                wr[k] = x.re;
                wi[k] = x.im;
            }
            if let Some(b) = &self.border {
                let x = b.col[r];
                self.wr.get_mut(n)?[k] = x.re;
                self.wi.get_mut(n)?[k] = x.im;
            }
        }
        // The remainder, by columns.
        let (tr, ti) = (&mut self.tr, &mut self.ti);
        for (i, &r) in plan.rest_rows[..n].iter().enumerate() {
            let r = r as usize;
            let row = a.get(r)?;
            for ((tr, ti), &c) in tr.iter_mut().zip(ti.iter_mut()).zip(rest_cols) {
                let x = *row.get(c as usize)?;
                tr[i] = x.re;
                ti[i] = x.im;
            }
            if let Some(b) = &self.border {
                tr.get_mut(n)?[i] = b.col[r].re;
                ti.get_mut(n)?[i] = b.col[r].im;
            }
            self.perm[i] = i as u8;
        }
        if let Some(b) = &self.border {
            for ((tr, ti), &c) in tr.iter_mut().zip(ti.iter_mut()).zip(rest_cols) {
                let x = *b.row.get(c as usize)?;
                *tr.get_mut(n)? = x.re;
                *ti.get_mut(n)? = x.im;
            }
            *tr.get_mut(n)?.get_mut(n)? = b.corner.re;
            *ti.get_mut(n)?.get_mut(n)? = b.corner.im;
            *self.perm.get_mut(n)? = n as u8;
        }
        for k in 0..m {
            let mut best = k;
            let mut bm = 0.0f64;
            for i in k..m {
                let v = tr[k][i].abs().max(ti[k][i].abs());
                if v > bm {
                    bm = v;
                    best = i;
                }
            }
            if !(bm > 0.0) || !bm.is_finite() {
                return None;
            }
            if best != k {
                // `best` is below m ≤ N: checked once here, not in every column's swap.
                if best >= N {
                    return None;
                }
                for j in 0..m {
                    tr[j].swap(k, best);
                    ti[j].swap(k, best);
                }
                self.perm.swap(k, best);
            }
            lo = lo.min(bm);
            hi = hi.max(bm);
            let inv = Complex::new(tr[k][k], ti[k][k]).recip();
            self.inv_dense[k] = inv;
            let (rleft, rright) = tr.split_at_mut(k + 1);
            let (ileft, iright) = ti.split_at_mut(k + 1);
            let (lr, li) = (&mut rleft[k], &mut ileft[k]);
            for i in k + 1..m {
                let l = Complex::new(lr[i], li[i]) * inv;
                lr[i] = l.re;
                li[i] = l.im;
            }
            let (lr, li) = (lr.get(k + 1..m)?, li.get(k + 1..m)?);
            for (cr, ci) in rright.iter_mut().zip(iright.iter_mut()).take(m - k - 1) {
                let (ur, ui) = (cr[k], ci[k]);
                let (cr, ci) = (cr.get_mut(k + 1..m)?, ci.get_mut(k + 1..m)?);
                sub_scaled(cr, ci, lr, li, ur, ui);
            }
        }
        self.min_pivot = lo;
        self.max_pivot = hi;
        (lo.is_finite() && hi.is_finite()).then_some(())
    }

    /// Solves `B y = b` (with a border: `[[B, col], [row, corner]] [y; σ] = [b; 0]`, and σ is
    /// dropped); `b` is overwritten with `y` (NaN if the plan were inconsistent, which its
    /// construction rules out).
    pub(crate) fn solve(&self, plan: &Plan<N>, b: &mut [Complex; N]) {
        let solved = crate::dispatch::fastest(
            #[inline(always)]
            || self.solve_checked(plan, b),
        );
        if solved.is_none() {
            *b = [Complex::new(f64::NAN, f64::NAN); N];
        }
    }

    /// [`Lu::solve`], `None` for the NaN solution; inlined into each of
    /// [`fastest`](crate::dispatch::fastest)'s twins.
    #[inline(always)]
    fn solve_checked(&self, plan: &Plan<N>, b: &mut [Complex; N]) -> Option<()> {
        let a = &self.a;
        let statics = plan.statics.min(N);
        let mut bb = Complex::ZERO;
        for k in 0..statics {
            let (r, c) = (plan.pivot[k].0 as usize, plan.pivot[k].1 as usize);
            let br = *b.get(r)?;
            for &i in head(&plan.rows[k], plan.n_rows[k]) {
                let i = i as usize;
                let l = *a.get(i)?.get(c)?;
                b[i] -= l * br;
            }
            if let Some(border) = &self.border {
                bb -= *border.row.get(c)? * br;
            }
        }
        let n = plan.rest.min(N);
        let m = self.m.min(N);
        let (tr, ti) = (&self.tr, &self.ti);
        let mut zr = [0.0; N];
        let mut zi = [0.0; N];
        for i in 0..m {
            let p = self.perm[i] as usize;
            let x = if p == n {
                bb
            } else {
                *b.get(*plan.rest_rows.get(p)? as usize)?
            };
            zr[i] = x.re;
            zi[i] = x.im;
        }
        // L (unit diagonal), column by column.
        for k in 0..m {
            let (xr, xi) = (zr[k], zi[k]);
            let (lr, li) = (tr.get(k)?.get(k + 1..m)?, ti.get(k)?.get(k + 1..m)?);
            let (zr, zi) = (zr.get_mut(k + 1..m)?, zi.get_mut(k + 1..m)?);
            sub_scaled(zr, zi, lr, li, xr, xi);
        }
        // U, column by column from the last.
        for k in (0..m).rev() {
            let x = Complex::new(zr[k], zi[k]) * self.inv_dense[k];
            zr[k] = x.re;
            zi[k] = x.im;
            let (ur, ui) = (tr.get(k)?.get(..k)?, ti.get(k)?.get(..k)?);
            let (zr, zi) = (zr.get_mut(..k)?, zi.get_mut(..k)?);
            sub_scaled(zr, zi, ur, ui, x.re, x.im);
        }
        // The static pivots' right-hand sides less their rows' remainder part (σ included).
        let mut sr = [0.0; N];
        let mut si = [0.0; N];
        for k in 0..statics {
            let x = *b.get(plan.pivot[k].0 as usize)?;
            sr[k] = x.re;
            si[k] = x.im;
        }
        for j in 0..m {
            let (wr, wi) = (
                self.wr.get(j)?.get(..statics)?,
                self.wi.get(j)?.get(..statics)?,
            );
            let (sr, si) = (sr.get_mut(..statics)?, si.get_mut(..statics)?);
            sub_scaled(sr, si, wr, wi, zr[j], zi[j]);
        }
        let mut y = [Complex::ZERO; N];
        for ((&c, &r), &i) in plan.rest_cols[..n].iter().zip(&zr).zip(&zi) {
            *y.get_mut(c as usize)? = Complex::new(r, i);
        }
        for k in (0..statics).rev() {
            let (r, c) = (plan.pivot[k].0 as usize, plan.pivot[k].1 as usize);
            let row = a.get(r)?;
            let mut s = Complex::new(sr[k], si[k]);
            for &k2 in head(&plan.later[k], plan.n_later[k]) {
                let c2 = plan.pivot.get(k2 as usize)?.1 as usize;
                s -= *row.get(c2)? * *y.get(c2)?;
            }
            *y.get_mut(c)? = s * self.inv_static[k];
        }
        *b = y;
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compact_lists_the_kept_indices_in_order() {
        let mut out = [0u8; 6];
        assert_eq!(compact(&mut out, |i| i % 2 == 1), 3);
        assert_eq!(head(&out, 3), &[1, 3, 5]);
        assert_eq!(compact(&mut out, |i| i == 0 || i == 4), 2);
        assert_eq!(head(&out, 2), &[0, 4]);
        assert_eq!(compact(&mut out, |_| true), 6);
        assert_eq!(out, [0, 1, 2, 3, 4, 5]);
        assert_eq!(compact(&mut out, |_| false), 0);
    }

    #[test]
    fn an_inconsistent_plan_fails_instead_of_panicking() {
        // Two constant diagonal entries: two static pivots, no dense remainder.
        let pattern = [(0, 0), (1, 1)];
        let v = [2.0, 4.0];
        let mut plan = Plan::<2>::new(&pattern, &v, &v).unwrap();
        assert_eq!(plan.shape(), (2, 0));
        let values = [Complex::real(2.0), Complex::real(4.0)];
        let mut lu = Lu::<2>::new();
        assert!(lu.factor(&plan, &values, None));
        let mut b = [Complex::ONE; 2];
        lu.solve(&plan, &mut b);
        assert_eq!(b, [Complex::real(0.5), Complex::real(0.25)]);
        // A pivot past the matrix (which `Plan::new` never makes): a failed factorisation and
        // a NaN solution, not an index out of bounds.
        plan.pivot[1] = (7, 1);
        assert!(!lu.factor(&plan, &values, None));
        let mut b = [Complex::ONE; 2];
        lu.solve(&plan, &mut b);
        assert!(b.iter().all(|x| !x.is_finite()), "{b:?}");
    }

    #[test]
    fn static_and_dense_pivots_solve_a_sparse_system() {
        // Rows 0 and 1 are "linear" with constant −1 on columns 2 and 3; rows 2, 3 vary.
        let pattern = [
            (0, 0),
            (0, 2),
            (1, 1),
            (1, 3),
            (2, 0),
            (2, 2),
            (3, 1),
            (3, 3),
            (3, 0),
        ];
        let a = [0.5, -1.0, 0.3, -1.0, 1.0, 2.0, 3.0, 1.0, 0.7];
        let b = [0.5, -1.0, 0.3, -1.0, 4.0, -2.0, 1.5, 2.5, 0.1];
        let plan = Plan::<4>::new(&pattern, &a, &b).unwrap();
        assert_eq!(plan.shape(), (2, 2));
        let vals = [
            Complex::real(0.5),
            Complex::real(-1.0),
            Complex::real(0.3),
            Complex::real(-1.0),
            Complex::new(1.0, 2.0),
            Complex::new(-3.0, 0.5),
            Complex::new(0.2, 0.1),
            Complex::new(2.0, -1.0),
            Complex::new(0.0, 1.0),
        ];
        let mut lu = Lu::<4>::new();
        assert!(lu.factor(&plan, &vals, None));
        let x = [
            Complex::new(1.0, 1.0),
            Complex::new(-2.0, 0.5),
            Complex::new(0.25, 0.0),
            Complex::new(0.0, -3.0),
        ];
        let mut rhs = [Complex::ZERO; 4];
        for (&(r, c), &v) in pattern.iter().zip(&vals) {
            rhs[r] += v * x[c];
        }
        lu.solve(&plan, &mut rhs);
        for i in 0..4 {
            assert!((rhs[i] - x[i]).abs() < 1e-13, "{i}: {:?}", rhs[i]);
        }
        // Bordered: [[B, col], [row, −1]] [x; σ] = [b; 0] with σ = row · x.
        let border = Border {
            col: [
                Complex::new(0.5, 1.0),
                Complex::real(-2.0),
                Complex::new(0.0, 3.0),
                Complex::ONE,
            ],
            row: [
                Complex::new(1.0, -1.0),
                Complex::real(0.25),
                Complex::new(0.3, 0.3),
                Complex::real(-0.7),
            ],
            corner: Complex::real(-1.0),
        };
        assert!(lu.factor(&plan, &vals, Some(&border)));
        let sigma = (0..4).fold(Complex::ZERO, |s, j| s + border.row[j] * x[j]);
        let mut rhs = [Complex::ZERO; 4];
        for (&(r, c), &v) in pattern.iter().zip(&vals) {
            rhs[r] += v * x[c];
        }
        for i in 0..4 {
            rhs[i] += border.col[i] * sigma;
        }
        lu.solve(&plan, &mut rhs);
        for i in 0..4 {
            assert!((rhs[i] - x[i]).abs() < 1e-13, "bordered {i}: {:?}", rhs[i]);
        }
    }
}
