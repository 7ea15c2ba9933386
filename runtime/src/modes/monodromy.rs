//! All solutions at the base parameter point by monodromy: carry every known solution around a
//! random loop of parameters (p₀ → a → b → p₀); where it comes back as a solution not yet known,
//! keep it; stop when loops stop producing new ones.
//!
//! Each loop permutes the solutions on the component of the seed, and random loops generate
//! the monodromy group, which acts transitively on them: while some are missing, a random
//! loop maps a known one to a missing one with high probability. The stopping rule is count
//! stability (a number of consecutive loops that bring nothing new), or a count known in
//! advance.

use super::Ended;
use super::complex::Complex;
use super::conjugation::conjugates;
use super::found::{Found, add, carry, close};
use super::inputs::Inputs;
use super::path::ParameterPath;
use super::polish::polish;
use super::rng::Rng;
use super::symmetry::Symmetries;
use super::track::{Model, Outcome, Settings, Workspace};
use crate::mechanism::Mechanism;

/// The loop points' size relative to p₀'s, alternating: loops as small as p₀ itself leave many
/// roots fixed (their branch points lie further out), so that monodromy on a general 6-6
/// platform stalled at 34 or 35 of its 40 roots; three times as large found all 40 in trials
/// but stalled at 38 on a planar one, which loops ten times as large completed.
const LOOP_SIZES: [f64; 2] = [3.0, 10.0];

/// The loops' size (before [`LOOP_SIZES`]) is at most this many times the mechanism's scale.
/// The seed's walk onto F = 0 can carry the inputs far from the mechanism's size (the planar
/// 3-PRP's slides to 50 times its scale), and loops ten times as far again put the links
/// hundreds of scales from the origin, where the tracker's relative norm no longer resolves
/// a link's own size (a guide 110 mm long at 10⁴ mm, a unit direction point beside it): every
/// step's corrector contracted slowly, and 9 of its 10 loops ran out of steps, so monodromy
/// saw 1 of the 3-PRP's 2 roots. Where p₀'s lengths are within this (the Stewart platforms,
/// the 3-RPS, every other mechanism tested) nothing changes.
const LOOP_REACH: f64 = 8.0;

/// When monodromy stops.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Stopping {
    pub(crate) stable_loops: usize,
    pub(crate) stable_seeds: usize,
    pub(crate) confidence: f64,
    pub(crate) max_loops: usize,
    pub(crate) expected: Option<usize>,
}

/// Fills `out` with the solutions at `p0` in tracking coordinates, starting from `out[0]`
/// (already a solution):
/// rounds of loops until `stable_loops` in a row bring nothing new (loops on which every path
/// failed are not counted), then fresh seeds (random
/// solutions at random parameter points, tracked to p₀) until one brings a new solution — and
/// loops again — or `stable_seeds` in a row bring nothing. Loops cannot leave the irreducible
/// component of the seed's solution; seeds land on every component (the 3-RPS example's
/// solutions split into two components of eight over its leg lengths), though seldom on a
/// small one, so the mechanism's home configuration is tried first. With symmetries (`sym`,
/// see `symmetry.rs`) every new root comes with its orbit, and a loop carries one member of each
/// orbit (the next one where a member's path fails).
pub(crate) fn monodromy<S: Mechanism<N, M>, const N: usize, const M: usize, const K: usize>(
    model: &Model<'_, S, N>,
    inputs: &Inputs<M>,
    p0: &[Complex; M],
    out: &mut [[Complex; N]; K],
    sym: &Symmetries,
    rng: &mut Rng,
    stop: &Stopping,
) -> Found {
    let mut ws = Workspace::new();
    let mut found = Found {
        count: 1,
        loops: 0,
        seeds: 0,
        failed_paths: 0,
        empty_loops: 0,
        overflow: false,
        loops_since_new: 0,
        seeds_since_new: 0,
        seed_finds: 0,
        conjugate_finds: 0,
        last_after_seed: false,
        first_settled: 0,
        ending: Ended::Stable,
        smallest: usize::MAX,
        seeds_needed: 0,
    };
    // Whether the loops now running follow a random seed that found something.
    let mut after_seed = false;
    let mut settled_once = false;
    // Solutions known before the seed whose loops run now.
    let mut round_from = 0;
    // Each root's orbit under the symmetries, as the index of its first member: an orbit is
    // added at once, so its members are consecutive.
    let mut orbit = [0usize; K];
    close(model, p0, sym, out, &mut orbit, &mut found, 0, &mut ws);
    let done = |found: &Found| {
        found.overflow
            || found.loops >= stop.max_loops
            || stop.expected.is_some_and(|e| found.count >= e)
    };
    // Loop points as far from zero as p₀'s lengths, times LOOP_SIZES (angles: anywhere on
    // the turn, imaginary parts LOOP_SIZES / 6 in size), but no further than LOOP_REACH times
    // the mechanism's scale (see there).
    let size = inputs.length_size(p0).min(LOOP_REACH * inputs.scale);
    let mut home_pending = true;
    // The count at the last conjugation step: another is worth its paths only once the count
    // has changed.
    let mut conjugated_at = 0;
    // Loops carry out[from..count], until `stable` in a row bring nothing new.
    let (mut from, mut stable) = (0, stop.stable_loops);
    loop {
        let mut stale = 0;
        while stale < stable && !done(&found) {
            found.loops += 1;
            let ls = LOOP_SIZES[found.loops % LOOP_SIZES.len()];
            let a = inputs.random(rng, ls * size, ls / 6.0);
            let b = inputs.random(rng, ls * size, ls / 6.0);
            let legs = [
                ParameterPath::new(*p0, a, Complex::ONE),
                ParameterPath::new(a, b, Complex::ONE),
                ParameterPath::new(b, *p0, Complex::ONE),
            ];
            let mut new = false;
            let mut i = from;
            // The orbit one of whose members has come round this loop: the images of the
            // others are its images (a loop commutes with the symmetries), and are known.
            let mut carried = usize::MAX;
            // Whether any path came back to p₀ on this loop.
            let mut came_round = false;
            while i < found.count && !done(&found) {
                // i < count ≤ K: `get` only spells that out for the no-panic proof.
                let Some(mut v) = out.get(i).copied() else {
                    break;
                };
                let this = orbit[i];
                i += 1;
                if this == carried {
                    continue;
                }
                let ok = legs.iter().all(|leg| {
                    model
                        .track(leg, &mut v, &mut ws, &Settings::DEFAULT)
                        .outcome
                        == Outcome::Reached
                });
                if !ok || !polish(model, &mut v, p0, &mut ws, true) {
                    found.failed_paths += 1;
                    continue;
                }
                carried = this;
                came_round = true;
                new |= add(model, p0, sym, out, &mut orbit, &mut found, v, &mut ws);
            }
            // A loop on which every path failed shows nothing about the count: it is not one
            // of the fruitless loops count stability asks for (the 3-PRP's monodromy once
            // stopped "stable" at 1 of its 2 roots after 10 loops, 9 of which had failed).
            if new {
                stale = 0;
            } else if came_round {
                stale += 1;
            } else {
                found.empty_loops += 1;
            }
            if new {
                found.loops_since_new = 0;
                found.seeds_since_new = 0;
                found.last_after_seed = after_seed;
            } else {
                found.loops_since_new += 1;
            }
        }
        if !settled_once {
            settled_once = true;
            found.first_settled = found.count;
        }
        if found.count > round_from {
            found.smallest = found.smallest.min(found.count - round_from);
        }
        (from, stable) = (0, stop.stable_loops);
        let mut new = false;
        // The mechanism's home first, once (where it has one): its component need not be
        // the first seed's, and random seeds can miss a small one (a delta's two
        // translations among its 40 roots: 26 of 30 seeds stopped at 38 without this).
        if home_pending && !done(&found) {
            home_pending = false;
            if let Ok((v, p)) = super::seed::seed_from_home(model, inputs) {
                found.seeds += 1;
                found.seeds_since_new += 1;
                let before = found.count;
                new = carry(model, &mut ws, (v, p), p0, sym, out, &mut orbit, &mut found);
                if new {
                    round_from = before;
                    (found.loops_since_new, found.seeds_since_new) = (0, 0);
                    found.last_after_seed = false;
                    after_seed = false;
                    // The loops carry the home's component alone, and four times as long: a
                    // small component is cheap to carry, and needs many loops to show all of
                    // itself (the delta's two translations swap in about one loop of four:
                    // ten loops left one out for 1 to 3 seeds of 30).
                    (from, stable) = (before, 4 * stop.stable_loops);
                }
            }
        }
        // The conjugates of the roots at a real point (see `conjugation.rs`): the conjugate
        // of a component the loops and seeds have found, which seeds seldom reach if small.
        if !new && !done(&found) && found.count != conjugated_at {
            conjugated_at = found.count;
            let before = found.count;
            new = conjugates(
                model, inputs, p0, size, sym, out, &mut orbit, &mut found, &mut ws,
            );
            if new {
                round_from = before;
                found.conjugate_finds += 1;
                (found.loops_since_new, found.seeds_since_new) = (0, 0);
                found.last_after_seed = false;
                after_seed = false;
                (from, stable) = (before, stop.stable_loops);
            }
        }
        let mut stale_seeds = 0;
        // Fresh seeds land on a component about in proportion to its number of solutions;
        // one as small as the smallest found so far (m of n) is missed by k seeds in a row
        // with probability (1 − m/n)^k ≈ e^(−k m / n).
        let needed = stop.stable_seeds.max(libm::ceil(
            stop.confidence * found.count as f64 / found.smallest.max(1) as f64,
        ) as usize);
        if !done(&found) {
            found.seeds_needed = needed;
        }
        while !new && stale_seeds < needed && !done(&found) {
            found.seeds += 1;
            found.seeds_since_new += 1;
            stale_seeds += 1;
            let Ok(seed) = super::seed::seed(model, inputs, rng) else {
                continue;
            };
            let before = found.count;
            new = carry(model, &mut ws, seed, p0, sym, out, &mut orbit, &mut found);
            if new {
                round_from = before;
                found.seed_finds += 1;
                (found.loops_since_new, found.seeds_since_new) = (0, 0);
                found.last_after_seed = true;
                after_seed = true;
            }
        }
        if !new || done(&found) {
            found.ending = if stop.expected.is_some_and(|e| found.count >= e) {
                Ended::Expected
            } else if found.loops >= stop.max_loops {
                Ended::LoopCap
            } else {
                Ended::Stable
            };
            return found;
        }
    }
}
