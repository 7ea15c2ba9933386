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

mod plan;
#[cfg(test)]
mod tests;

pub(crate) use plan::Plan;
use plan::head;

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
