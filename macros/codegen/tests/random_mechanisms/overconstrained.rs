//! Random planar and spherical mechanisms of R and P pairs: four-bars, five-bars, six-bars
//! (a dyad from a link of an earlier chain), platforms on two or three chains of three pairs,
//! and a platform with a dyad besides. As spatial mechanisms they are overconstrained: a loop
//! of a planar or spherical mechanism has three freedoms where a spatial loop has six, so the
//! model's spatial equations are dependent at every configuration and its rank test must keep
//! an independent set that stays one along the motion. The mobility is known by the same count
//! in three dimensions: a chain of p pairs from a placed link to the platform adds p − 3
//! freedoms (the first, from the base, p).

use crate::common::Rng;
use crate::generator::{
    add, chance, general_chain, locate_links_before_actives, pick, pivots_apart, random_unit,
    scale, shuffle, spans_a_plane, uniform, Group, Kind, Mech, BASE, PLATFORM,
};

/// Each shape: its chains' pair counts, and whether a chain starts at a placed link of an
/// earlier chain (else at the base).
const SHAPES: [&[(usize, bool)]; 6] = [
    &[(2, false), (2, false)],
    &[(2, false), (3, false)],
    &[(2, false), (2, false), (3, true)],
    &[(3, false), (3, false)],
    &[(3, false), (3, false), (3, false)],
    &[(3, false), (3, false), (3, true)],
];

/// The pairs of one chain: R only in a spherical mechanism; R or P in a planar one, at most two
/// slides (three would leave the chain no turn), in a random order. `active[k]` marks the
/// active pairs.
fn pairs(rng: &mut Rng, active: &[bool], planar: bool) -> Vec<(Kind, bool)> {
    loop {
        let seq: Vec<(Kind, bool)> = active
            .iter()
            .map(|&a| {
                let kind = if planar && chance(rng, 0.35) {
                    Kind::P
                } else {
                    Kind::R
                };
                (kind, a)
            })
            .collect();
        if seq.iter().filter(|(k, _)| *k == Kind::P).count() <= 2.min(seq.len() - 1) {
            return seq;
        }
    }
}

/// One random planar or spherical mechanism from `seed`.
pub fn generate(seed: u64) -> Mech {
    let mut rng = Rng::new(seed);
    loop {
        let planar = chance(&mut rng, 0.5);
        let family = if planar { "planar" } else { "spherical" };
        let mut m = Mech::new(family, &mut rng);
        m.group = if planar {
            Group::Planar {
                normal: random_unit(&mut rng),
            }
        } else {
            Group::Spherical {
                centre: [
                    uniform(&mut rng, -30.0, 30.0),
                    uniform(&mut rng, -30.0, 30.0),
                    m.home[5] * uniform(&mut rng, 0.3, 0.7),
                ],
            }
        };
        let shape = pick(&mut rng, &SHAPES);
        // Σ p − 3 (chains − 1) freedoms, each driven by one active pair placed at random.
        let total: usize = shape.iter().map(|(p, _)| p).sum();
        let mobility = total - 3 * (shape.len() - 1);
        let mut active = vec![false; total];
        for a in active.iter_mut().take(mobility) {
            *a = true;
        }
        shuffle(&mut rng, &mut active);
        let mut next = 0;
        for &(n, from_placed) in shape {
            let chain_active = &active[next..next + n];
            next += n;
            let pairs = pairs(&mut rng, chain_active, planar);
            let placed: Vec<usize> = (2..m.links.len())
                .filter(|&l| m.links[l].length.is_none())
                .collect();
            let (from, start) = if from_placed && !placed.is_empty() {
                let l = pick(&mut rng, &placed);
                let near = m
                    .pivots
                    .iter()
                    .find(|p| p.link == l)
                    .map(|p| p.at)
                    .unwrap_or(m.random_base_point(&mut rng));
                let off = scale(uniform(&mut rng, 20.0, 40.0), random_unit(&mut rng));
                (l, add(near, off))
            } else {
                (BASE, m.random_base_point(&mut rng))
            };
            let chain = general_chain(&mut m, &mut rng, from, start, &pairs);
            m.chains.push(chain);
        }
        while !spans_a_plane(
            &m.pivots
                .iter()
                .filter(|p| p.link == PLATFORM)
                .map(|p| p.at)
                .collect::<Vec<_>>(),
        ) {
            let p = m.random_platform_point(&mut rng);
            m.pivot(PLATFORM, p);
        }
        locate_links_before_actives(&mut m, &mut rng);
        if pivots_apart(&m) {
            return m;
        }
    }
}
