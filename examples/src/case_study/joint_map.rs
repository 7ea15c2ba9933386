//! The valid joint space of the Table III platform over a grid in (L2, L4, L6), with
//! L1 = L3 = L5 fixed (Figs. 5–6): det B of the start's branch at every grid point reached.
//!
//! Every grid point is solved by continuation from an already-solved neighbour (pseudo-arc-
//! length, which refuses to pass a fold), starting from the initial configuration. A point
//! that no chain of such steps reaches is outside the valid joint space of this slice, and
//! is left empty rather than filled with a solution of another branch.

use crate::stewart::Stewart;
use linkage::{arc_length, det_b, Options, Start};
use std::collections::VecDeque;

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

/// Flood-fills the grid by continuation from the start. `progress` gets the share done.
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
    let x_of = |m: &JointMap, i: usize, j: usize, k: usize| {
        [m.fixed, m.l2[i], m.fixed, m.l4[j], m.fixed, m.l6[k]]
    };
    let options = Options {
        tolerance: 1e-9,
        ..Options::TIGHT
    };
    let mut queue = VecDeque::new();
    // Seeds: grid points reached straight from the initial configuration, nearest first.
    let mut seeds: Vec<(usize, usize, usize)> = (0..n6)
        .flat_map(|k| (0..n4).flat_map(move |j| (0..n2).map(move |i| (i, j, k))))
        .collect();
    let dist = |m: &JointMap, c: &(usize, usize, usize)| {
        let x = x_of(m, c.0, c.1, c.2);
        x.iter()
            .zip(start.x())
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
    };
    seeds.sort_by(|a, b| dist(&map, a).total_cmp(&dist(&map, b)));
    for seed in seeds.iter().take(20) {
        let x = x_of(&map, seed.0, seed.1, seed.2);
        if let Ok(sol) = arc_length(sys, start, &x, &options) {
            if sol.is_ok() {
                let c = map.index(seed.0, seed.1, seed.2);
                solved[c] = Some(sol.v);
                map.ratio[c] = Some(det_b(sys, &sol.v, &x) / start.det());
                queue.push_back(*seed);
                break;
            }
        }
    }
    let mut done = 0usize;
    while let Some((i, j, k)) = queue.pop_front() {
        done += 1;
        if done.is_multiple_of((total / 20).max(1)) {
            progress(done as f64 / total as f64);
        }
        let from = map.index(i, j, k);
        let v = solved[from].expect("queued cells are solved");
        // A checked start; a cell too near a fold to be one seeds no neighbours (they may
        // still be reached from another side).
        let Ok(here) = Start::new(sys, v, x_of(&map, i, j, k)) else {
            continue;
        };
        let neighbours = [
            (i.wrapping_sub(1), j, k),
            (i + 1, j, k),
            (i, j.wrapping_sub(1), k),
            (i, j + 1, k),
            (i, j, k.wrapping_sub(1)),
            (i, j, k + 1),
        ];
        for (a, b, c) in neighbours {
            if a >= n2 || b >= n4 || c >= n6 {
                continue;
            }
            let to = map.index(a, b, c);
            if solved[to].is_some() {
                continue;
            }
            let x = x_of(&map, a, b, c);
            match arc_length(sys, &here, &x, &options) {
                Ok(sol) if sol.is_ok() => {
                    solved[to] = Some(sol.v);
                    map.ratio[to] = Some(det_b(sys, &sol.v, &x) / start.det());
                    queue.push_back((a, b, c));
                }
                Ok(sol) => {
                    if let linkage::Status::Fold { lambda } = sol.status {
                        let at = |p: f64, q: f64| p + lambda * (q - p);
                        map.folds.push([
                            at(here.x()[1], x[1]),
                            at(here.x()[3], x[3]),
                            at(here.x()[5], x[5]),
                        ]);
                    }
                }
                Err(_) => {}
            }
        }
    }
    progress(1.0);
    map
}
