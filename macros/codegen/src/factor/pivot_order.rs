//! The pivot order of the Schur complement, fixed at generation time: Markowitz's rule
//! (eliminate where the fewest entries are touched and the least fill is made) restricted to
//! pivots that are large in their column at a sample configuration (threshold pivoting).
//!
//! The emitted factorisation follows this order without searching, so it costs what the
//! structure costs: three-nonzero rows are eliminated first and only their entries are
//! touched. The order is only as good as the sample is typical; at run time the emitted code
//! checks the multipliers it forms against [`MAX_MULTIPLIER`] and falls back to partial
//! pivoting when one is larger (see `emit::lu`).

/// A pivot is a candidate if it is at least this fraction of the largest entry of its column
/// at the sample: its multipliers are then at most 1 / `THRESHOLD` there. Stricter than the
/// run-time bound, so that the order holds away from the sample too.
const THRESHOLD: f64 = 0.5;

/// The largest multiplier the fixed order may form at run time (threshold pivoting with
/// u = 0.01). A larger one means the order is poor at that configuration — a fixed pivot is
/// small where B is not singular, and the factors would grow — and the factorisation is redone
/// with partial pivoting. Near singularities of B multipliers between 16 and 100 are common
/// and harmless (measured backward errors below 1e-13 on the Stewart platform's Table V
/// iterates); beyond the bound the tests see growth (`tests/integration/jacobians.rs`).
pub const MAX_MULTIPLIER: f64 = 100.0;

/// The pivot sequence `(row, column)` for a `k`×`k` matrix with structural nonzeros `pattern`
/// and, optionally, values `sample` at one configuration.
pub fn choose(pattern: &[Vec<bool>], sample: Option<&[Vec<f64>]>) -> Vec<(usize, usize)> {
    let k = pattern.len();
    let mut nz: Vec<Vec<bool>> = pattern.to_vec();
    let mut a: Vec<Vec<f64>> = match sample {
        Some(s) => s.to_vec(),
        None => vec![vec![0.0; k]; k],
    };
    let numeric = sample.is_some();
    let (mut row_done, mut col_done) = (vec![false; k], vec![false; k]);
    let mut order = Vec::with_capacity(k);
    for _ in 0..k {
        let rows: Vec<usize> = (0..k).filter(|&i| !row_done[i]).collect();
        let cols: Vec<usize> = (0..k).filter(|&j| !col_done[j]).collect();
        let row_count = |i: usize| cols.iter().filter(|&&j| nz[i][j]).count();
        let col_count = |j: usize| rows.iter().filter(|&&i| nz[i][j]).count();
        let col_max = |j: usize| rows.iter().map(|&i| a[i][j].abs()).fold(0.0, f64::max);
        // (cost, −relative size, row, column): the smallest wins.
        let mut best: Option<(usize, f64, usize, usize)> = None;
        for strict in [true, false] {
            for &j in &cols {
                let max = col_max(j);
                for &i in &rows {
                    if !nz[i][j] {
                        continue;
                    }
                    let relative = if numeric && max > 0.0 {
                        a[i][j].abs() / max
                    } else {
                        1.0
                    };
                    if strict && numeric && !(relative >= THRESHOLD) {
                        continue;
                    }
                    let cost = (row_count(i) - 1) * (col_count(j) - 1);
                    let candidate = (cost, -relative, i, j);
                    if best.is_none_or(|b| better(candidate, b)) {
                        best = Some(candidate);
                    }
                }
            }
            if best.is_some() {
                break;
            }
        }
        // A structurally singular remainder: any pairing (B is then singular everywhere, and
        // the run-time check sends every factorisation to the fallback).
        let (_, _, p, q) = best.unwrap_or((0, 0.0, rows[0], cols[0]));
        order.push((p, q));
        row_done[p] = true;
        col_done[q] = true;
        for &i in &rows {
            if i == p || !nz[i][q] {
                continue;
            }
            let l = if a[p][q] != 0.0 {
                a[i][q] / a[p][q]
            } else {
                0.0
            };
            for &j in &cols {
                if j != q && nz[p][j] {
                    nz[i][j] = true;
                    a[i][j] -= l * a[p][j];
                }
            }
        }
    }
    order
}

fn better(a: (usize, f64, usize, usize), b: (usize, f64, usize, usize)) -> bool {
    (a.0, a.1) < (b.0, b.1) || ((a.0, a.1) == (b.0, b.1) && (a.2, a.3) < (b.2, b.3))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sparse_rows_go_first_and_large_pivots_win() {
        // Row 0 has one entry: it is the cheapest pivot. Row 1's entries are then small in
        // their columns, so row 2 pivots next.
        let pattern = vec![
            vec![true, false, false],
            vec![true, true, true],
            vec![true, true, true],
        ];
        let sample = vec![
            vec![2.0, 0.0, 0.0],
            vec![1.0, 0.1, 0.1],
            vec![1.0, 3.0, 1.0],
        ];
        let order = choose(&pattern, Some(&sample));
        assert_eq!(order, vec![(0, 0), (2, 1), (1, 2)]);
    }

    #[test]
    fn without_a_sample_the_structure_decides() {
        let pattern = vec![vec![true, true], vec![true, false]];
        assert_eq!(choose(&pattern, None), vec![(0, 1), (1, 0)]);
    }
}
