//! The symbolic phase: from the generated sparsity pattern (and two samples of its values,
//! which tell the constant entries), the static pivots' order and every update list, once per
//! mechanism.

/// The first `n` entries of one of the plan's lists (`n` ≤ N by construction).
///
/// Every index a [`Plan`] holds is below N by its construction (each comes from a loop over
/// `0..N`), and every count is at most N. The factorisation and the solves still read them
/// with `get` (a failed one is a failed factorisation, or a NaN solution): the same compare
/// and branch as a bounds check, which here cannot panic (`tests/no_panic` proves the query
/// total). A clamp (`min`) instead cost 1.6 % more instructions per query.
#[inline(always)]
pub(super) fn head<const N: usize>(list: &[u8; N], n: u8) -> &[u8] {
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
pub(super) fn compact<const N: usize>(out: &mut [u8; N], keep: impl Fn(usize) -> bool) -> u8 {
    let mut n = 0usize;
    for i in 0..N {
        if let Some(slot) = out.get_mut(n) {
            *slot = i as u8;
        }
        n += usize::from(keep(i));
    }
    n as u8
}

/// The elimination order and the update lists, computed from the pattern.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plan<const N: usize> {
    /// Number of static pivots.
    pub(super) statics: usize,
    /// `(row, column)` of each static pivot, in elimination order.
    pub(super) pivot: [(u8, u8); N],
    /// Rows updated by static pivot k (structural nonzeros of its column below it).
    pub(super) rows: [[u8; N]; N],
    pub(super) n_rows: [u8; N],
    /// The other structural nonzeros of static pivot k's row, in columns not yet eliminated.
    pub(super) cols: [[u8; N]; N],
    pub(super) n_cols: [u8; N],
    /// Per row, the columns where static elimination creates an entry the pattern lacks
    /// (zeroed before each factorisation).
    pub(super) fill: [[u8; N]; N],
    pub(super) n_fill: [u8; N],
    /// Rows and columns of the dense remainder.
    pub(super) rest_rows: [u8; N],
    pub(super) rest_cols: [u8; N],
    pub(super) rest: usize,
    /// Per static pivot k, the static pivots k' > k whose column is among `cols[k]`: the part
    /// of its back-substitution that must wait for them (the rest columns' part is a dense
    /// product, see [`Lu::solve`](super::Lu::solve)).
    pub(super) later: [[u8; N]; N],
    pub(super) n_later: [u8; N],
    /// Number of pattern entries, and where each goes in the row-major N × N matrix.
    pub(super) nnz: usize,
    pub(super) flat: [[u16; N]; N],
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
