//! The valid joint space of the Table III platform over a grid in (L2, L4, L6), with
//! L1 = L3 = L5 fixed (Figs. 5–6): det B of the start's branch at every grid point reached.
//!
//! Every grid point is solved by continuation from an already-solved neighbour (pseudo-arc-
//! length, which refuses to pass a fold), starting from the initial configuration, on every
//! core. A point
//! that no chain of such steps reaches is outside the valid joint space of this slice, and
//! is left empty rather than filled with a solution of another branch.

use crate::stewart::Stewart;
use linkage::{arc_length, det_b, Options, Start};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// A grid over L2 × L4 × L6 and what continuation found there.
pub struct JointMap {
    pub fixed: f64,
    pub l2: Vec<f64>,
    pub l4: Vec<f64>,
    pub l6: Vec<f64>,
    /// det B / det B at the start, per cell (index `(k * l4.len() + j) * l2.len() + i`);
    /// `None` where the start's branch cannot be continued to.
    pub ratio: Vec<Option<f64>>,
    /// `(L2, L4, L6)` where continuation along a grid edge met a fold: points of the singular
    /// surface that bounds the valid joint space, located to the step tolerance.
    pub folds: Vec<[f64; 3]>,
}

impl JointMap {
    pub fn index(&self, i: usize, j: usize, k: usize) -> usize {
        (k * self.l4.len() + j) * self.l2.len() + i
    }

    /// Mean |det B / det B₀| over the reached cells.
    pub fn mean_ratio(&self) -> f64 {
        let reached: Vec<f64> = self.ratio.iter().flatten().map(|r| r.abs()).collect();
        reached.iter().sum::<f64>() / reached.len().max(1) as f64
    }

    pub fn reached(&self) -> usize {
        self.ratio.iter().flatten().count()
    }
}

pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            if n == 1 {
                lo
            } else {
                lo + (hi - lo) * i as f64 / (n - 1) as f64
            }
        })
        .collect()
}

/// What continuation into one cell found: its solution and det B ratio, if a source reached
/// it, and where folds stopped the sources tried before.
struct Reach {
    solved: Option<([f64; 18], f64)>,
    folds: Vec<[f64; 3]>,
}

/// Flood-fills the grid by continuation from the start, in waves: every cell solved in one
/// wave is a source for the next, and the cells a wave can reach are solved in parallel (on
/// every core, by rayon). Each cell is tried from its solved neighbours in index order until
/// one reaches it, so the map does not depend on the number of threads. `progress` gets the
/// share of cells visited after each wave.
pub fn explore(
    sys: &Stewart,
    start: &Start<18, 6>,
    fixed: f64,
    l2: Vec<f64>,
    l4: Vec<f64>,
    l6: Vec<f64>,
    mut progress: impl FnMut(f64),
) -> JointMap {
    let (n2, n4, n6) = (l2.len(), l4.len(), l6.len());
    let total = n2 * n4 * n6;
    let mut map = JointMap {
        fixed,
        l2,
        l4,
        l6,
        ratio: vec![None; total],
        folds: Vec::new(),
    };
    let mut solved: Vec<Option<[f64; 18]>> = vec![None; total];
    let x_of = |m: &JointMap, c: usize| {
        let (i, j, k) = (c % n2, (c / n2) % n4, c / (n2 * n4));
        [m.fixed, m.l2[i], m.fixed, m.l4[j], m.fixed, m.l6[k]]
    };
    let options = Options {
        tolerance: 1e-9,
        ..Options::TIGHT
    };
    // Seed: the grid point nearest the initial configuration that continuation reaches.
    let mut seeds: Vec<usize> = (0..total).collect();
    let dist = |m: &JointMap, c: usize| {
        x_of(m, c)
            .iter()
            .zip(start.x())
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
    };
    seeds.sort_by(|a, b| dist(&map, *a).total_cmp(&dist(&map, *b)));
    let mut wave = Vec::new();
    for &seed in seeds.iter().take(20) {
        let x = x_of(&map, seed);
        if let Ok(sol) = arc_length(sys, start, &x, &options) {
            if sol.is_ok() {
                solved[seed] = Some(sol.v);
                map.ratio[seed] = Some(det_b(sys, &sol.v, &x) / start.det());
                wave.push(seed);
                break;
            }
        }
    }
    let neighbours = |c: usize| {
        let (i, j, k) = (c % n2, (c / n2) % n4, c / (n2 * n4));
        let mut out = Vec::with_capacity(6);
        if i > 0 {
            out.push(c - 1);
        }
        if i + 1 < n2 {
            out.push(c + 1);
        }
        if j > 0 {
            out.push(c - n2);
        }
        if j + 1 < n4 {
            out.push(c + n2);
        }
        if k > 0 {
            out.push(c - n2 * n4);
        }
        if k + 1 < n6 {
            out.push(c + n2 * n4);
        }
        out
    };
    let mut visited = wave.len();
    while !wave.is_empty() {
        // A checked start at every source; a cell too near a fold to be one seeds no
        // neighbours (they may still be reached from another side).
        let starts: Vec<(usize, Start<18, 6>)> = wave
            .par_iter()
            .filter_map(|&c| {
                let v = solved[c].expect("a wave holds solved cells");
                Start::new(sys, v, x_of(&map, c)).ok().map(|s| (c, s))
            })
            .collect();
        // Every unsolved cell next to a source, with its sources in index order.
        let mut targets: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for (n, (c, _)) in starts.iter().enumerate() {
            for t in neighbours(*c) {
                if solved[t].is_none() {
                    targets.entry(t).or_default().push(n);
                }
            }
        }
        let targets: Vec<(usize, Vec<usize>)> = targets.into_iter().collect();
        let reached: Vec<Reach> = targets
            .par_iter()
            .map(|(t, sources)| {
                let x = x_of(&map, *t);
                let mut folds = Vec::new();
                for &n in sources {
                    let here = &starts[n].1;
                    match arc_length(sys, here, &x, &options) {
                        Ok(sol) if sol.is_ok() => {
                            let ratio = det_b(sys, &sol.v, &x) / start.det();
                            return Reach {
                                solved: Some((sol.v, ratio)),
                                folds,
                            };
                        }
                        Ok(sol) => {
                            if let linkage::Status::Fold { lambda } = sol.status {
                                let at = |p: f64, q: f64| p + lambda * (q - p);
                                folds.push([
                                    at(here.x()[1], x[1]),
                                    at(here.x()[3], x[3]),
                                    at(here.x()[5], x[5]),
                                ]);
                            }
                        }
                        Err(_) => {}
                    }
                }
                Reach {
                    solved: None,
                    folds,
                }
            })
            .collect();
        wave.clear();
        for ((t, _), r) in targets.iter().zip(reached) {
            map.folds.extend(r.folds);
            if let Some((v, ratio)) = r.solved {
                solved[*t] = Some(v);
                map.ratio[*t] = Some(ratio);
                wave.push(*t);
            }
        }
        visited += wave.len();
        progress(visited as f64 / total as f64);
    }
    progress(1.0);
    map
}
