//! Random overconstrained mechanisms: planar and spherical ones of R and P pairs (four-bars,
//! five-bars, six-bars with a dyad from a link of an earlier chain, platforms on two or three
//! chains of three pairs, and a platform with a dyad besides; a spherical one in three with a
//! passive ball joint at its centre too; 3-RPR platforms, their slides between their hinges;
//! for one seed in five, S, U and C pairs among the passive turns), Bennett linkages, Goldberg
//! 5R linkages, line- and plane-symmetric Bricard linkages, platforms on two or three planar chains of different
//! planes (Sarrus linkages and their kin), Schoenflies platforms on four chains of three
//! parallel R and a slide, and deltas of random geometry whose parallelograms turn on balls or
//! on U pairs. As spatial mechanisms they are overconstrained: a loop of a planar or spherical
//! mechanism has three freedoms where a spatial loop has six, a Bennett loop one where
//! Grübler–Kutzbach counts −2, a Bricard loop one where it counts 0, so the model's spatial
//! equations are dependent at every configuration and its rank test must keep an independent
//! set that stays one along the motion. The planar and spherical mobility is known by the same
//! count in three dimensions: a chain of p pairs from a placed link to the platform adds p − 3
//! freedoms (the first, from the base, p).

use crate::common::Rng;
use crate::generator::{
    add, chance, cross, dot, finish, general_chain, norm, pick, placed_links, random_unit, scale,
    shuffle, start_near, sub, uniform, unit, within_contract, Chain, Group, Joint, Kind, Mech,
    BASE, PLATFORM, V3,
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
/// active pairs. Where `mixed`, a passive R is now and then an S, a U or a C instead: in a loop
/// of turns about one normal (or one centre) the rest of the loop lets each turn only as an R
/// does (the S about its centre's normal or the line to the centre, the U about its first axis,
/// along the normal or through the centre, the C with its slide held), which the model must find
/// from dependent equations.
fn pairs(rng: &mut Rng, active: &[bool], planar: bool, mixed: bool) -> Vec<(Kind, bool)> {
    loop {
        let seq: Vec<(Kind, bool)> = active
            .iter()
            .map(|&a| {
                let kind = if planar && chance(rng, 0.35) {
                    Kind::P
                } else if mixed && !a && chance(rng, 0.4) {
                    pick(rng, &[Kind::S, Kind::U, Kind::C])
                } else {
                    Kind::R
                };
                (kind, a)
            })
            .collect();
        if within_contract(&seq, 2.min(seq.len() - 1)) {
            return seq;
        }
    }
}

/// One random overconstrained mechanism from `seed`: a Bennett linkage, a delta of random
/// geometry or a Bricard linkage for one seed in twenty each, a platform on planar chains of
/// different planes, a Schoenflies platform or a Goldberg 5R linkage for one in forty each,
/// else a planar or spherical one.
pub fn generate(seed: u64) -> Mech {
    let mut rng = Rng::new(seed);
    // By the seed itself, so that the other seeds keep the mechanisms they had before
    // Bennett linkages joined the sweep.
    if seed % 20 == 4 {
        return bennett(&mut rng);
    }
    if seed % 20 == 14 {
        return delta(&mut rng);
    }
    // Half the seeds that were Bennett's (the rest keep their mechanisms), shared by two
    // families.
    if seed % 20 == 9 {
        return bricard(&mut rng);
    }
    if seed % 40 == 19 {
        return sarrus(&mut rng);
    }
    if seed % 40 == 39 {
        return schoenflies(&mut rng);
    }
    // One planar or spherical seed in twenty (the rest keep their mechanisms).
    if seed % 40 == 2 {
        return goldberg(&mut rng);
    }
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
        // S, U and C pairs among the passive turns for one seed in five (by the seed: the
        // others keep their mechanisms).
        let mixed = seed % 5 == 1;
        // For one seed in five, a planar one is a 3-RPR instead: legs whose slide runs between
        // their hinges' centres (no axis of its own), each driven (by the seed: the others
        // keep their mechanisms).
        if let (Group::Planar { normal }, 2) = (m.group, seed % 5) {
            for c in 0..3 {
                let leg = rpr_leg(&mut m, &mut rng, normal, c);
                m.chains.push(leg);
            }
            if finish(&mut m, &mut rng) {
                return m;
            }
            continue;
        }
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
            let pairs = pairs(&mut rng, chain_active, planar, mixed);
            let placed = placed_links(&m);
            let (from, start) = if from_placed && !placed.is_empty() {
                start_near(&m, &mut rng, &placed)
            } else {
                (BASE, m.random_base_point(&mut rng))
            };
            let chain = general_chain(&mut m, &mut rng, from, start, &pairs);
            m.chains.push(chain);
        }
        // For one spherical seed in three (by the seed: the others keep their mechanisms), a
        // passive ball joint at the centre besides, joining the base to the platform: it
        // allows what the chains allow, so it adds dependent equations and no freedom.
        if let (Group::Spherical { centre }, 0) = (m.group, seed % 3) {
            let owner = if chance(&mut rng, 0.5) {
                BASE
            } else {
                PLATFORM
            };
            let ball = m.pivot(owner, centre);
            m.chains.push(Chain {
                name: format!("c{}", m.chains.len()),
                links: vec![Some(BASE), Some(PLATFORM)],
                joints: vec![Joint {
                    kind: Kind::S,
                    inputs: Vec::new(),
                    centre: Some(ball),
                    axis: None,
                    offset: None,
                    lead: None,
                }],
                shape: "S@centre".into(),
            });
        }
        if finish(&mut m, &mut rng) {
            return m;
        }
    }
}

/// A planar R-P-R leg from the base to the platform: hinges along `normal` at a base point
/// and a platform point in one plane square to it, the active slide between their centres.
fn rpr_leg(m: &mut Mech, rng: &mut Rng, normal: V3, c: usize) -> Chain {
    let a = m.random_base_point(rng);
    let g = m.random_platform_point(rng);
    // The platform's hinge moved into the base hinge's plane: the leg then stays in it.
    let g = add(g, scale(-dot(sub(g, a), normal), normal));
    let hinge = |m: &mut Mech, rng: &mut Rng, link: usize, at: V3| {
        let s = uniform(rng, 15.0, 40.0);
        let first = m.pivot(link, at);
        let second = m.pivot(link, add(at, scale(s, normal)));
        Joint {
            kind: Kind::R,
            inputs: Vec::new(),
            centre: None,
            axis: Some((first, second)),
            offset: None,
            lead: None,
        }
    };
    let base = hinge(m, rng, BASE, a);
    let slide = Joint {
        kind: Kind::P,
        inputs: m.inputs_of(Kind::P),
        centre: None,
        axis: None,
        offset: chance(rng, 0.5).then(|| uniform(rng, -40.0, 40.0)),
        lead: None,
    };
    let platform = hinge(m, rng, PLATFORM, g);
    Chain {
        name: format!("c{c}"),
        links: vec![Some(BASE), None, None, Some(PLATFORM)],
        joints: vec![base, slide, platform],
        shape: "R-P*-R".into(),
    }
}

/// Rz(θ) · Tx(a) · Rx(α), a Denavit–Hartenberg step, as a rotation and a translation.
fn dh(theta: f64, a: f64, alpha: f64) -> ([V3; 3], V3) {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    (
        [
            [ct, -st * ca, st * sa],
            [st, ct * ca, -ct * sa],
            [0.0, sa, ca],
        ],
        [a * ct, a * st, 0.0],
    )
}

/// The frame `(r, t)` followed by `(r2, t2)`.
fn then(f: &([V3; 3], V3), g: &([V3; 3], V3)) -> ([V3; 3], V3) {
    let (r, t) = f;
    let (r2, t2) = g;
    let rr = [0, 1, 2].map(|i| [0, 1, 2].map(|j| dot(r[i], [r2[0][j], r2[1][j], r2[2][j]])));
    (rr, add(*t, [0, 1, 2].map(|i| dot(r[i], *t2))))
}

/// A Bennett linkage (tests/integration/mechanisms/catalogue/bennett.rs): four R pairs on skew axes,
/// links of lengths a, b, a, b and twists α, β, α, β with a / sin α = b / sin β, at a random
/// crank angle, placed anywhere; one of its three moving links the platform, one joint driven.
/// One freedom where Grübler–Kutzbach counts −2.
fn bennett(rng: &mut Rng) -> Mech {
    loop {
        let mut m = Mech::new("bennett", rng);
        let a = uniform(rng, 60.0, 150.0);
        let alpha = uniform(rng, 0.35, 1.35);
        let beta = uniform(rng, 0.35, 1.35);
        let theta1 = uniform(rng, 0.5, 2.6);
        let b = a * beta.sin() / alpha.sin();
        let theta2 = bennett_next(theta1, alpha, beta);
        // Twists apart (equal ones make a planar parallelogram's degenerate cousin) and the
        // loop away from its flat folds.
        if (alpha - beta).abs() < 0.2 || theta2.sin().abs() < 0.3 || !(30.0..200.0).contains(&b) {
            continue;
        }
        let placed = random_frame(rng);
        let mut frames = vec![placed];
        for (theta, len, twist) in [
            (theta1, a, alpha),
            (theta2, b, beta),
            (std::f64::consts::TAU - theta1, a, alpha),
        ] {
            let next = then(frames.last().unwrap(), &dh(theta, len, twist));
            frames.push(next);
        }
        // Joint j's axis is frame j − 1's z through its origin.
        let axes: Vec<(V3, V3)> = frames[..4]
            .iter()
            .map(|(r, o)| (*o, [r[0][2], r[1][2], r[2][2]]))
            .collect();
        r_loop(&mut m, rng, &axes);
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// Whether a loop's neighbouring axes are well apart, in angle and in distance (a link of
/// length and twist near zero is a degenerate loop, whose mobility the oracle cannot judge at
/// home).
fn neighbours_apart(axes: &[(V3, V3)]) -> bool {
    (0..axes.len()).all(|i| {
        let (p, u) = axes[i];
        let (q, w) = axes[(i + 1) % axes.len()];
        let n = cross(u, w);
        norm(n) >= 0.3 && dot(sub(q, p), unit(n)).abs() >= 15.0
    })
}

/// A frame placed at random above the base, for a spatial loop to start from.
fn random_frame(rng: &mut Rng) -> ([V3; 3], V3) {
    (
        crate::generator::rotation(
            uniform(rng, -3.0, 3.0),
            uniform(rng, -1.5, 1.5),
            uniform(rng, -3.0, 3.0),
        ),
        [
            uniform(rng, -40.0, 40.0),
            uniform(rng, -40.0, 40.0),
            uniform(rng, 60.0, 140.0),
        ],
    )
}

/// The closing Bennett angle: with links (a, α) then (b, β) from a joint turned by θ, the next
/// joint's angle (Bennett 1903; `bennett` above).
fn bennett_next(theta: f64, alpha: f64, beta: f64) -> f64 {
    let k = ((beta + alpha) / 2.0).sin() / ((beta - alpha) / 2.0).sin();
    2.0 * (k / (theta / 2.0).tan()).atan()
}

/// A Goldberg 5R linkage (Goldberg 1943; Baker 1979): two Bennett linkages sharing a link
/// (J4→J1, length b and twist β), the first of links a, b, a, b (joints J1–J4), the second of
/// c, b, c, b (joints J1, J5, J6, J4), with a / sin α = b / sin β = c / sin γ. With the shared
/// link, each moves on its own; fusing the two links that leave J1 (the first's to J2, the
/// second's to J5) ties their motions, and taking the shared link away joins J4's two links by
/// one R: a loop of five R (J2, J3, J4, J6, J5) that keeps one freedom where Grübler–Kutzbach
/// counts −1. Both Bennett loops at random angles; one moving link the platform, one joint
/// driven.
fn goldberg(rng: &mut Rng) -> Mech {
    use std::f64::consts::TAU;
    loop {
        let mut m = Mech::new("goldberg", rng);
        let b = uniform(rng, 60.0, 150.0);
        let beta = uniform(rng, 0.35, 1.35);
        let ratio = b / beta.sin();
        // The other two links' twists, their lengths by the Bennett condition.
        let alpha = uniform(rng, 0.35, 1.35);
        let gamma = uniform(rng, 0.35, 1.35);
        let (a, c) = (ratio * alpha.sin(), ratio * gamma.sin());
        if (alpha - beta).abs() < 0.2
            || (gamma - beta).abs() < 0.2
            || (alpha - gamma).abs() < 0.2
            || !(30.0..200.0).contains(&a)
            || !(30.0..200.0).contains(&c)
        {
            continue;
        }
        let theta1 = uniform(rng, 0.5, 2.6);
        let theta2 = bennett_next(theta1, alpha, beta);
        let psi1 = uniform(rng, 0.5, 2.6);
        let psi2 = bennett_next(psi1, gamma, beta);
        if theta2.sin().abs() < 0.3 || psi2.sin().abs() < 0.3 {
            continue;
        }
        // J1's frame, its x along the shared link's normal as it arrives at J1.
        let j1 = random_frame(rng);
        let walk = |steps: &[(f64, f64, f64)]| {
            let mut frames = vec![j1];
            for &(theta, len, twist) in steps {
                let next = then(frames.last().unwrap(), &dh(theta, len, twist));
                frames.push(next);
            }
            frames
        };
        // J1, J2, J3, J4 and back to J1; J1, J5, J6, J4 and back to J1.
        let first = walk(&[
            (theta1, a, alpha),
            (theta2, b, beta),
            (TAU - theta1, a, alpha),
            (TAU - theta2, b, beta),
        ]);
        let second = walk(&[
            (psi1, c, gamma),
            (psi2, b, beta),
            (TAU - psi1, c, gamma),
            (TAU - psi2, b, beta),
        ]);
        let axis = |f: &([V3; 3], V3)| (f.1, [f.0[0][2], f.0[1][2], f.0[2][2]]);
        // Both loops close on J1's frame, and meet at J4 on one axis (the test's own check of
        // the construction).
        for frames in [&first, &second] {
            let (o, z) = axis(&frames[4]);
            let (o1, z1) = axis(&j1);
            assert!(
                norm(sub(o, o1)) < 1e-9 * b && norm(sub(z, z1)) < 1e-9,
                "a Bennett loop of the Goldberg linkage does not close"
            );
            let (o4, z4) = axis(&frames[3]);
            let (f4, w4) = axis(&first[3]);
            assert!(
                norm(sub(o4, f4)) < 1e-9 * b && norm(sub(z4, w4)) < 1e-9,
                "the Goldberg linkage's Bennett loops do not share J4"
            );
        }
        // The loop of five: J2, J3, J4, J6, J5 (the fused link between J5 and J2).
        let axes: Vec<(V3, V3)> = [first[1], first[2], first[3], second[2], second[1]]
            .iter()
            .map(axis)
            .collect();
        if !neighbours_apart(&axes) {
            continue;
        }
        r_loop(&mut m, rng, &axes);
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// A Bricard linkage: six R pairs in a loop, symmetric about a line (a half-turn about it maps
/// joint i's axis to joint i + 3's, so links i and i + 3 are alike) or, for half the seeds,
/// about a plane (a reflection in it maps joint 2's axis to 6's and 3's to 5's, joints 1 and 4
/// in the plane); one freedom where Grübler–Kutzbach counts 0 (Bricard 1927; Baker 1980).
/// Axes at random and the line or plane at random give a configuration of one; one of its five
/// moving links the platform, one joint driven.
fn bricard(rng: &mut Rng) -> Mech {
    'again: loop {
        let mut m = Mech::new("bricard", rng);
        let c = [
            uniform(rng, -30.0, 30.0),
            uniform(rng, -30.0, 30.0),
            uniform(rng, 80.0, 140.0),
        ];
        let d = random_unit(rng);
        let random_axis = |rng: &mut Rng| {
            let p = [0, 1, 2].map(|i| c[i] + uniform(rng, -70.0, 70.0));
            (p, random_unit(rng))
        };
        let axes: Vec<(V3, V3)> = if chance(rng, 0.5) {
            // A half-turn about the line through c along d.
            let half_turn = |v: V3| sub(scale(2.0 * dot(v, d), d), v);
            let first: Vec<(V3, V3)> = (0..3).map(|_| random_axis(rng)).collect();
            let images: Vec<(V3, V3)> = first
                .iter()
                .map(|&(p, u)| (add(c, half_turn(sub(p, c))), half_turn(u)))
                .collect();
            [first, images].concat()
        } else {
            // A reflection in the plane through c square to d; axes 1 and 4 in it.
            let mirror = |v: V3| sub(v, scale(2.0 * dot(v, d), d));
            let in_plane = |rng: &mut Rng| loop {
                let (p, u) = random_axis(rng);
                if norm(flat(u, d)) > 0.3 {
                    break (add(c, flat(sub(p, c), d)), unit(flat(u, d)));
                }
            };
            let (a1, a4) = (in_plane(rng), in_plane(rng));
            let (a2, a3) = (random_axis(rng), random_axis(rng));
            let image = |(p, u): (V3, V3)| (add(c, mirror(sub(p, c))), mirror(u));
            vec![a1, a2, a3, a4, image(a3), image(a2)]
        };
        if !neighbours_apart(&axes) {
            continue 'again;
        }
        r_loop(&mut m, rng, &axes);
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// `v` with its part along the unit `d` taken off: into the plane square to `d`.
fn flat(v: V3, d: V3) -> V3 {
    sub(v, scale(dot(v, d), d))
}

/// A platform on two or three chains of three pairs, each planar in a plane of its own: its R
/// axes along that chain's normal, its slides square to it (a Sarrus linkage where all are R and
/// there are two). Each chain allows the platform the planar motions of its plane; together
/// they allow the translation along the one direction square to every normal, so one freedom
/// where Grübler–Kutzbach counts 0 (two chains) or −3 (three, their normals square to one
/// direction). One pair driven.
fn sarrus(rng: &mut Rng) -> Mech {
    loop {
        let mut m = Mech::new("sarrus", rng);
        let d = random_unit(rng);
        let chains = if chance(rng, 0.5) { 2 } else { 3 };
        let mut normals: Vec<V3> = Vec::new();
        let mut seqs = Vec::new();
        for _ in 0..chains {
            // A normal square to d, at least 0.5 rad from the others.
            let normal = loop {
                let n = unit(cross(d, random_unit(rng)));
                if normals.iter().all(|o| norm(cross(*o, n)) > 0.5) {
                    break n;
                }
            };
            normals.push(normal);
            seqs.push(pairs(rng, &[false; 3], true, false));
        }
        // The driven pair one that moves: not a chain's only R, which turns as the platform
        // does, not at all.
        let movers: Vec<(usize, usize)> = (0..chains)
            .flat_map(|c| (0..3).map(move |k| (c, k)))
            .filter(|&(c, k)| {
                seqs[c][k].0 == Kind::P || seqs[c].iter().filter(|p| p.0 == Kind::R).count() > 1
            })
            .collect();
        let (c, k) = pick(rng, &movers);
        seqs[c][k].1 = true;
        for (normal, seq) in normals.into_iter().zip(&seqs) {
            m.group = Group::Planar { normal };
            let start = m.random_base_point(rng);
            let chain = general_chain(&mut m, rng, BASE, start, seq);
            m.chains.push(chain);
        }
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// A delta of random geometry: three cranks, each on a hinge of random direction at a random
/// base point and driven, carrying a parallelogram of two equal rods to the platform, its sides
/// on the crank and on the platform along the hinge. The rods turn on balls (the delta as
/// built with balls), or on U pairs whose first axes run along the hinge, on the crank and on
/// the platform (overconstrained: each rod holds its spin and its angle across the
/// parallelogram). Either way each parallelogram keeps the platform's side along its hinge, so
/// the platform only translates: three freedoms where Grübler–Kutzbach counts 3 (balls, less
/// the rods' idle spins) or −3 (U pairs).
fn delta(rng: &mut Rng) -> Mech {
    'again: loop {
        let mut m = Mech::new("delta", rng);
        for i in 0..3 {
            let h = random_unit(rng);
            let a = m.random_base_point(rng);
            let r = random_unit(rng);
            let arm = scale(uniform(rng, 60.0, 120.0), unit(sub(r, scale(dot(r, h), h))));
            let w = uniform(rng, 30.0, 70.0);
            let mid = add(a, arm);
            let e = [add(mid, scale(w / 2.0, h)), add(mid, scale(-w / 2.0, h))];
            let f1 = m.random_platform_point(rng);
            let f = [f1, sub(f1, scale(w, h))];
            // Rods of some length, across the parallelogram from their hinge's side.
            let rod = norm(sub(f[0], e[0]));
            if rod < 40.0 || norm(cross(unit(sub(f[0], e[0])), h)) < 0.3 {
                continue 'again;
            }
            let balls = chance(rng, 0.5);
            let crank = m.link(format!("crank{i}"), None);
            let hinge = (m.pivot(BASE, a), m.pivot(BASE, add(a, scale(25.0, h))));
            let ep = [m.pivot(crank, e[0]), m.pivot(crank, e[1])];
            let fp = [m.pivot(PLATFORM, f[0]), m.pivot(PLATFORM, f[1])];
            for side in 0..2 {
                let other = 1 - side;
                let end = |centre: usize, along: usize| Joint {
                    kind: if balls { Kind::S } else { Kind::U },
                    inputs: Vec::new(),
                    centre: Some(centre),
                    axis: (!balls).then_some((centre, along)),
                    offset: None,
                    lead: None,
                };
                let rod_link = m.link(format!("rod{i}_{side}"), balls.then_some(rod));
                let mut links = vec![Some(crank), Some(rod_link), Some(PLATFORM)];
                let mut joints = vec![end(ep[side], ep[other]), end(fp[side], fp[other])];
                if side == 0 {
                    links.insert(0, Some(BASE));
                    joints.insert(
                        0,
                        Joint {
                            kind: Kind::R,
                            inputs: m.inputs_of(Kind::R),
                            centre: None,
                            axis: Some(hinge),
                            offset: None,
                            lead: None,
                        },
                    );
                }
                let pair = if balls { "S" } else { "U" };
                m.chains.push(Chain {
                    name: format!("c{}", m.chains.len()),
                    links,
                    shape: if side == 0 {
                        format!("R*-{pair}-{pair}")
                    } else {
                        format!("{pair}-{pair}")
                    },
                    joints,
                });
            }
        }
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// A Schoenflies platform: four chains of three R pairs along one axis and a slide oblique to
/// it, in a random order, each with one pair driven. Each chain allows the platform the
/// Schoenflies motions (three translations, turns about the axis) and no other, so the four
/// leave it those four freedoms where Grübler–Kutzbach counts −2, the inputs fixing them.
fn schoenflies(rng: &mut Rng) -> Mech {
    loop {
        let mut m = Mech::new("schoenflies", rng);
        m.group = Group::Schoenflies {
            axis: random_unit(rng),
        };
        // Every slide's rate is the platform's along the axis over the slide's share of it:
        // two driven slides would drive one freedom twice.
        let mut slide_driven = false;
        for _ in 0..4 {
            let mut seq = vec![
                (Kind::R, false),
                (Kind::R, false),
                (Kind::R, false),
                (Kind::P, false),
            ];
            shuffle(rng, &mut seq);
            let driven = loop {
                let k = (rng.next_u64() % 4) as usize;
                if !(slide_driven && seq[k].0 == Kind::P) {
                    break k;
                }
            };
            slide_driven |= seq[driven].0 == Kind::P;
            seq[driven].1 = true;
            let start = m.random_base_point(rng);
            let chain = general_chain(&mut m, rng, BASE, start, &seq);
            m.chains.push(chain);
        }
        if finish(&mut m, rng) {
            return m;
        }
    }
}

/// A single loop of R pairs on `axes` (each a point and a direction), joint j between loop
/// links j − 1 and j with loop link 0 the base: a random one of the moving links the platform,
/// one joint driven, each axis's two pivots on either link it joins, and two chains from the
/// base to the platform, one each way round the loop.
fn r_loop(m: &mut Mech, rng: &mut Rng, axes: &[(V3, V3)]) {
    let n = axes.len();
    // Loop link i (0 the base) between joints i and i + 1.
    let p = 1 + (rng.next_u64() % (n as u64 - 1)) as usize;
    let mut loop_links = vec![BASE];
    let mut names = 1;
    for i in 1..n {
        loop_links.push(if i == p {
            PLATFORM
        } else {
            names += 1;
            m.link(format!("l{names}"), None)
        });
    }
    let driven = (rng.next_u64() % n as u64) as usize;
    let mut joints = Vec::new();
    for (j, &(o, z)) in axes.iter().enumerate() {
        let z = if chance(rng, 0.5) { z } else { scale(-1.0, z) };
        let s = uniform(rng, -20.0, 20.0);
        let owner = if chance(rng, 0.5) {
            loop_links[j]
        } else {
            loop_links[(j + 1) % n]
        };
        let first = m.pivot(owner, add(o, scale(s, z)));
        let second = m.pivot(owner, add(o, scale(s + uniform(rng, 15.0, 40.0), z)));
        let inputs = if j == driven {
            m.inputs_of(Kind::R)
        } else {
            Vec::new()
        };
        joints.push(Some(Joint {
            kind: Kind::R,
            inputs,
            centre: None,
            axis: Some((first, second)),
            offset: None,
            lead: None,
        }));
    }
    let mut chain = |m: &mut Mech, name: &str, order: &[usize]| {
        let mut links = vec![Some(BASE)];
        let mut js = Vec::new();
        let mut shape = Vec::new();
        for &j in order {
            let joint = joints[j].take().unwrap();
            shape.push(if joint.inputs.is_empty() { "R" } else { "R*" });
            js.push(joint);
            // Joint j joins loop links j and j + 1: forwards it leads to j + 1, backwards
            // (j, from loop link j + 1) to j.
            let to = if order[0] == 0 { (j + 1) % n } else { j };
            links.push(Some(loop_links[to]));
        }
        m.chains.push(Chain {
            name: name.into(),
            links,
            joints: js,
            shape: shape.join("-"),
        });
    };
    let forwards: Vec<usize> = (0..p).collect();
    let backwards: Vec<usize> = (p..n).rev().collect();
    chain(m, "c0", &forwards);
    chain(m, "c1", &backwards);
}
