//! The square system kept at home, checked along the motion (see [`super::motion`]): where
//! det ∂F/∂v of the equations kept changes sign between two configurations of a ray, the
//! system turns singular there. If that is the mechanism's own singularity (∂F/∂v of all the
//! equations loses rank), every choice does the same; if not, the choice is at fault, and the
//! rows are chosen again with every configuration in view: by pivoting, each time the row
//! whose smallest part off the span of those chosen (over the configurations) is largest.
//! The new choice replaces the first only if it crosses fewer times, so a mechanism whose
//! kept equations stay regular along its motion keeps them.

use super::derivatives::{condition, Derivatives, Sparse, DEPENDENT, NEARLY_SINGULAR};
use super::motion::Ray;

/// The rows are chosen again over at most about this many configurations (with those on both
/// sides of each crossing); the new choice is checked at all of them.
const CHOOSE_OVER: usize = 48;

type Rows = Vec<Vec<f64>>;

/// The sign of det of the kept rows of `b`, or 0 (LU with partial pivoting; the sign alone,
/// which neither overflows nor underflows).
fn det(b: &Sparse, kept: &[usize]) -> f64 {
    let n = kept.len();
    let mut a = vec![0.0; n * n];
    for (r, &i) in kept.iter().enumerate() {
        for &(k, value) in &b[i] {
            a[r * n + k] = value;
        }
    }
    let mut det = 1.0;
    for j in 0..n {
        let p = (j..n)
            .max_by(|&r, &s| a[r * n + j].abs().total_cmp(&a[s * n + j].abs()))
            .unwrap_or(j);
        let pivot = a[p * n + j];
        if pivot == 0.0 {
            return 0.0;
        }
        if p != j {
            det = -det;
            for k in 0..n {
                a.swap(p * n + k, j * n + k);
            }
        }
        det *= pivot.signum();
        let (top, rest) = a.split_at_mut((j + 1) * n);
        let row = &top[j * n + j..];
        for below in rest.chunks_exact_mut(n) {
            let f = below[j] / pivot;
            if f != 0.0 {
                below[j..]
                    .iter_mut()
                    .zip(row)
                    .for_each(|(x, r)| *x -= f * r);
            }
        }
    }
    det
}

/// The pairs of consecutive configurations `(ray, k)`, `(ray, k + 1)` between which det of
/// the kept rows changes sign or vanishes.
fn crossings(rays: &[Ray], kept: &[usize]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for (r, ray) in rays.iter().enumerate() {
        let signs: Vec<f64> = ray.iter().map(|s| det(&s.b, kept)).collect();
        for k in 0..signs.len().saturating_sub(1) {
            if !(signs[k] * signs[k + 1] > 0.0) {
                out.push((r, k));
            }
        }
    }
    out
}

/// `n` rows chosen class by class, by pivoting over all `samples` at once (home first): next,
/// the class's row whose part off the span of the rows chosen is largest at the configuration
/// where it is smallest, among those more than [`DEPENDENT`] of themselves off it at home.
fn pivoted(samples: &[&Rows], classes: &[Vec<usize>], n: usize) -> Vec<usize> {
    let norm = |r: &[f64]| r.iter().map(|a| a * a).sum::<f64>().sqrt();
    // Each sample's rows, less their parts along the rows chosen (Gram–Schmidt, updated as
    // each row is chosen), and each row's own size there.
    let mut left: Vec<Rows> = samples.iter().map(|b| (*b).clone()).collect();
    let size: Vec<Vec<f64>> = samples
        .iter()
        .map(|b| b.iter().map(|r| norm(r)).collect())
        .collect();
    let all = classes.concat();
    let mut kept = Vec::new();
    for class in classes {
        let mut open: Vec<usize> = class.clone();
        while kept.len() < n {
            let part = |s: usize, i: usize| norm(&left[s][i]) / size[s][i].max(1e-300);
            let best = open
                .iter()
                .enumerate()
                .filter(|(_, &i)| part(0, i) > DEPENDENT)
                .map(|(k, &i)| {
                    let worst = (0..samples.len())
                        .map(|s| part(s, i))
                        .fold(f64::INFINITY, f64::min);
                    (k, worst)
                })
                .max_by(|a, b| a.1.total_cmp(&b.1));
            let Some((k, _)) = best else {
                break;
            };
            let i = open.swap_remove(k);
            kept.push(i);
            for rows in left.iter_mut() {
                let l = norm(&rows[i]);
                let q: Vec<f64> = rows[i].iter().map(|a| a / l).collect();
                for &j in &all {
                    if !kept.contains(&j) {
                        let d: f64 = rows[j].iter().zip(&q).map(|(a, b)| a * b).sum();
                        rows[j].iter_mut().zip(&q).for_each(|(a, b)| *a -= d * b);
                    }
                }
            }
        }
    }
    kept.sort_unstable();
    kept
}

/// `kept` (the choice at home), or a choice that crosses fewer times along the `rays`.
pub fn steady(
    by_v: &Derivatives,
    classes: &[Vec<usize>],
    kept: Vec<usize>,
    rays: &[Ray],
    c: &[f64],
) -> Vec<usize> {
    let home = crossings(rays, &kept);
    if home.is_empty() {
        return kept;
    }
    let all: Vec<(usize, usize)> = rays
        .iter()
        .enumerate()
        .flat_map(|(r, ray)| (0..ray.len()).map(move |k| (r, k)))
        .collect();
    let stride = all.len().div_ceil(CHOOSE_OVER).max(1);
    // Home first: (0, 0), where every ray starts, sorts first.
    let mut chosen: Vec<(usize, usize)> = all.iter().copied().step_by(stride).collect();
    for &(r, k) in &home {
        chosen.extend([(r, k), (r, k + 1)]);
    }
    chosen.sort_unstable();
    chosen.dedup();
    let samples: Vec<Rows> = chosen
        .iter()
        .map(|&(r, k)| by_v.rows(&rays[r][k].v, &rays[r][k].x, c))
        .collect();
    let samples: Vec<&Rows> = samples.iter().collect();
    let n = kept.len();
    let (count, choice) = [
        pivoted(&samples, classes, n),
        pivoted(&samples, &[classes.concat()], n),
    ]
    .into_iter()
    .filter(|choice| choice.len() == n)
    .map(|choice| (crossings(rays, &choice).len(), choice))
    .fold((home.len(), kept), |best, other| {
        if other.0 < best.0 {
            other
        } else {
            best
        }
    });
    if count == 0 {
        return choice;
    }
    let equations = classes.iter().map(Vec::len).sum();
    swapped(rays, choice, count, equations)
}

/// From `choice` (crossing `count` times), single swaps of a row kept for one left out, the
/// swap that crosses fewest taken while it crosses fewer, within [`SWAP_WORK`]. The greedy
/// orders above take rows one at a time, each the best at its turn; a row that only pairs well
/// with a later one is out of their reach. (A Bennett linkage with its axes' second points
/// 250 mm out: both orders kept rows whose det vanished about 1 rad of the input from home,
/// where one swap of a platform equation for a dropped one crosses nowhere.) A swap must leave the
/// rows as well conditioned at home, where every ray starts, as the rank test asks there.
fn swapped(rays: &[Ray], mut choice: Vec<usize>, mut count: usize, equations: usize) -> Vec<usize> {
    let Some(home) = rays.first().and_then(|ray| ray.first()) else {
        return choice;
    };
    let n = choice.len();
    let dense: Vec<Vec<f64>> = home
        .b
        .iter()
        .map(|row| {
            let mut d = vec![0.0; n];
            row.iter().for_each(|&(k, a)| d[k] = a);
            d
        })
        .collect();
    let samples: usize = rays.iter().map(Vec::len).sum();
    let per_swap = samples * n * n * n / 3 + 1;
    let mut budget = SWAP_WORK;
    while count > 0 {
        let out: Vec<usize> = (0..equations).filter(|j| !choice.contains(j)).collect();
        if n * out.len() * per_swap > budget {
            break;
        }
        budget -= n * out.len() * per_swap;
        let mut fewer: Vec<(usize, Vec<usize>)> = Vec::new();
        for a in 0..n {
            for &j in &out {
                let mut c = choice.clone();
                c[a] = j;
                c.sort_unstable();
                let k = crossings(rays, &c).len();
                if k < count {
                    fewer.push((k, c));
                }
            }
        }
        // The fewest crossings first; of those, one no worse conditioned at home than the
        // rank test accepts there.
        fewer.sort_by_key(|(k, _)| *k);
        match fewer
            .into_iter()
            .find(|(_, c)| condition(&dense, c) >= NEARLY_SINGULAR)
        {
            Some((k, c)) => (count, choice) = (k, c),
            None => break,
        }
    }
    choice
}

/// The swap search's bound, in floating-point operations (n³/3 per determinant): a fraction of
/// a second of compile time, which a system of a few dozen equations never reaches and a larger one reaches before its
/// first full round of swaps.
const SWAP_WORK: usize = 200_000_000;
