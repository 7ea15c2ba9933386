//! Random valid declarations of mechanisms of lower pairs, seeded and deterministic: a base, a
//! platform at a random home pose, and chains of random pairs at random axes and pivots whose
//! freedoms give a known mobility (Grübler–Kutzbach on a tree of chains: each chain of f
//! freedoms from a link already placed takes 6 − f from the platform's 6). The declaration is
//! kept as data (for the oracle, which reads it and nothing of the model) and rendered as text
//! (for the model, and for a failure's message).

use crate::common::Rng;
use std::fmt::Write as _;

pub type V3 = [f64; 3];

pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn scale(s: f64, a: V3) -> V3 {
    [s * a[0], s * a[1], s * a[2]]
}
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
pub fn unit(a: V3) -> V3 {
    scale(1.0 / norm(a), a)
}

/// Rz(yaw)·Ry(pitch)·Rx(roll), the README's `home`.
pub fn rotation(yaw: f64, pitch: f64, roll: f64) -> [[f64; 3]; 3] {
    let (cy, sy) = (yaw.cos(), yaw.sin());
    let (cp, sp) = (pitch.cos(), pitch.sin());
    let (cr, sr) = (roll.cos(), roll.sin());
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Kind {
    R,
    P,
    C,
    H,
    S,
    U,
}

impl Kind {
    pub fn freedoms(self) -> usize {
        match self {
            Kind::R | Kind::P | Kind::H => 1,
            Kind::C | Kind::U => 2,
            Kind::S => 3,
        }
    }
}

/// Index of the base and the platform in [`Mech::links`].
pub const BASE: usize = 0;
pub const PLATFORM: usize = 1;

pub struct Pivot {
    pub name: String,
    /// Base-frame position at home (a platform pivot is declared in the platform's frame).
    pub at: V3,
    pub link: usize,
}

pub struct Link {
    pub name: String,
    pub length: Option<f64>,
}

pub struct Joint {
    pub kind: Kind,
    /// Its joint variables, in the README's order (`active θ z`, `active a b`, `active yaw
    /// pitch roll`); empty for a passive pair.
    pub inputs: Vec<String>,
    pub centre: Option<usize>,
    pub axis: Option<(usize, usize)>,
    pub offset: Option<f64>,
    pub lead: Option<f64>,
}

pub struct Chain {
    pub name: String,
    /// The links between and around its pairs: `None` for an unnamed one.
    pub links: Vec<Option<usize>>,
    pub joints: Vec<Joint>,
    /// A short name of its shape, for the counts: `S-P-S`, `R-C-U-S`, …
    pub shape: String,
}

/// The motions the mechanism's pairs allow, as its axes are placed.
#[derive(Clone, Copy, Debug)]
pub enum Group {
    /// Axes anywhere: a spatial mechanism.
    Spatial,
    /// Every R axis along `normal`, every slide square to it: a planar mechanism, three
    /// freedoms to a loop where a spatial one has six, so its spatial equations are
    /// dependent (`overconstrained.rs`).
    Planar { normal: V3 },
    /// Every R axis through `centre`: a spherical mechanism, likewise.
    Spherical { centre: V3 },
    /// Every R axis along `axis`, every slide oblique to it: chains of the Schoenflies motions
    /// (three translations and turns about `axis`), four freedoms where a spatial loop has six.
    Schoenflies { axis: V3 },
}

pub struct Mech {
    pub family: &'static str,
    pub group: Group,
    pub links: Vec<Link>,
    pub pivots: Vec<Pivot>,
    pub chains: Vec<Chain>,
    pub home: [f64; 6],
    /// Every joint variable, once.
    pub inputs: Vec<String>,
    /// Whether a general chain's U pair may carry its first axis on the link after it (the
    /// README allows either link; its leg then looks back along the chain). Set by the seed,
    /// so that the other seeds' mechanisms stay as they were generated.
    pub u_axis_after: bool,
    /// Whether a crank's or carriage's leg may end in a U on an unnamed rod to the ball (R*-U-S,
    /// P*-U-S). Set by the seed, as `u_axis_after`, so that the other seeds' mechanisms (and
    /// the tests pinned to them) stay as they were generated.
    pub u_rods: bool,
}

/// Uniform in [lo, hi).
pub fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

pub fn pick<T: Copy>(rng: &mut Rng, items: &[T]) -> T {
    items[(rng.next_u64() % items.len() as u64) as usize]
}

pub fn chance(rng: &mut Rng, p: f64) -> bool {
    uniform(rng, 0.0, 1.0) < p
}

pub fn random_unit(rng: &mut Rng) -> V3 {
    loop {
        let v = [
            uniform(rng, -1.0, 1.0),
            uniform(rng, -1.0, 1.0),
            uniform(rng, -1.0, 1.0),
        ];
        let n = norm(v);
        if (0.2..=1.0).contains(&n) {
            return scale(1.0 / n, v);
        }
    }
}

pub fn shuffle<T>(rng: &mut Rng, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        let j = (rng.next_u64() % (i as u64 + 1)) as usize;
        items.swap(i, j);
    }
}

impl Mech {
    pub fn new(family: &'static str, rng: &mut Rng) -> Mech {
        let home = [
            uniform(rng, -0.4, 0.4),
            uniform(rng, -0.3, 0.3),
            uniform(rng, -0.3, 0.3),
            uniform(rng, -30.0, 30.0),
            uniform(rng, -30.0, 30.0),
            uniform(rng, 160.0, 240.0),
        ];
        Mech {
            family,
            group: Group::Spatial,
            links: vec![
                Link {
                    name: "base".into(),
                    length: None,
                },
                Link {
                    name: "platform".into(),
                    length: None,
                },
            ],
            pivots: Vec::new(),
            chains: Vec::new(),
            home,
            inputs: Vec::new(),
            u_axis_after: false,
            u_rods: false,
        }
    }

    pub fn pivot(&mut self, link: usize, at: V3) -> usize {
        let prefix = match link {
            BASE => "b",
            PLATFORM => "g",
            _ => "k",
        };
        self.pivots.push(Pivot {
            name: format!("{prefix}{}", self.pivots.len()),
            at,
            link,
        });
        self.pivots.len() - 1
    }

    pub fn link(&mut self, name: String, length: Option<f64>) -> usize {
        self.links.push(Link { name, length });
        self.links.len() - 1
    }

    fn input(&mut self, prefix: &str) -> String {
        let name = format!("{prefix}{}", self.inputs.len());
        self.inputs.push(name.clone());
        name
    }

    pub fn inputs_of(&mut self, kind: Kind) -> Vec<String> {
        match kind {
            Kind::R | Kind::H => vec![self.input("q")],
            Kind::P => vec![self.input("d")],
            Kind::C => vec![self.input("t"), self.input("z")],
            Kind::U => vec![self.input("a"), self.input("b")],
            Kind::S => vec![self.input("yaw"), self.input("pitch"), self.input("roll")],
        }
    }

    /// The platform's pose at home: a base-frame point's coordinates in the platform's frame.
    fn platform_local(&self, world: V3) -> V3 {
        let [yaw, pitch, roll, tx, ty, tz] = self.home;
        let r = rotation(yaw, pitch, roll);
        let d = sub(world, [tx, ty, tz]);
        [0, 1, 2].map(|j| (0..3).map(|i| r[i][j] * d[i]).sum())
    }

    fn platform_world(&self, local: V3) -> V3 {
        let [yaw, pitch, roll, tx, ty, tz] = self.home;
        let r = rotation(yaw, pitch, roll);
        [0, 1, 2].map(|i| dot(r[i], local) + [tx, ty, tz][i])
    }

    pub fn random_base_point(&self, rng: &mut Rng) -> V3 {
        let a = uniform(rng, 0.0, std::f64::consts::TAU);
        let r = uniform(rng, 110.0, 180.0);
        [r * a.cos(), r * a.sin(), uniform(rng, -10.0, 10.0)]
    }

    pub fn random_platform_point(&self, rng: &mut Rng) -> V3 {
        let a = uniform(rng, 0.0, std::f64::consts::TAU);
        let r = uniform(rng, 40.0, 80.0);
        self.platform_world([r * a.cos(), r * a.sin(), uniform(rng, -10.0, 10.0)])
    }
}

/// The unit direction of a pair's axis through `at`: random for a spatial mechanism; a
/// planar one's R along the normal (either way), its slides across it; a spherical one's
/// axes through the centre; a Schoenflies chain's R along its axis, its slides oblique to it.
fn axis_direction(group: Group, kind: Kind, at: V3, rng: &mut Rng) -> V3 {
    let sign = |rng: &mut Rng| if chance(rng, 0.5) { 1.0 } else { -1.0 };
    match group {
        Group::Spatial => random_unit(rng),
        Group::Planar { normal } if kind == Kind::P => loop {
            let r = random_unit(rng);
            let across = sub(r, scale(dot(r, normal), normal));
            if norm(across) > 0.3 {
                break unit(across);
            }
        },
        Group::Planar { normal } => scale(sign(rng), normal),
        Group::Spherical { centre } => scale(sign(rng), unit_or_up(sub(at, centre))),
        Group::Schoenflies { axis } if kind == Kind::P => loop {
            let r = random_unit(rng);
            if dot(r, axis).abs() > 0.3 {
                break r;
            }
        },
        Group::Schoenflies { axis } => scale(sign(rng), axis),
    }
}

/// `a` scaled to length 1, or +z if it has none to speak of.
fn unit_or_up(a: V3) -> V3 {
    if norm(a) > 1e-9 {
        unit(a)
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// The pairs of a general chain of `freedoms`, with one active pair for each entry of
/// `actives` (its number of joint variables), in a random order such that the chain is
/// generically of full rank and within the README's contract: no two S in a row (a rod's idle
/// spin) and at most two slides (P, C).
fn general_pairs(rng: &mut Rng, freedoms: usize, actives: &[usize]) -> Vec<(Kind, bool)> {
    loop {
        let mut seq: Vec<(Kind, bool)> = actives
            .iter()
            .map(|&a| {
                let kind = match a {
                    1 => pick(rng, &[Kind::R, Kind::P, Kind::H]),
                    2 => pick(rng, &[Kind::U, Kind::C]),
                    _ => Kind::S,
                };
                (kind, true)
            })
            .collect();
        let mut rest = freedoms - actives.iter().sum::<usize>();
        while rest > 0 {
            let kind = pick(rng, &[Kind::R, Kind::R, Kind::P, Kind::C, Kind::U, Kind::S]);
            if kind.freedoms() <= rest {
                seq.push((kind, false));
                rest -= kind.freedoms();
            }
        }
        shuffle(rng, &mut seq);
        if within_contract(&seq, 2) {
            return seq;
        }
    }
}

/// Whether a chain's pairs keep to the README's contract: at most `slides` slides (P, C), and
/// no two S in a row (the rod between them would be free to spin).
pub fn within_contract(seq: &[(Kind, bool)], slides: usize) -> bool {
    let n = seq
        .iter()
        .filter(|(k, _)| matches!(k, Kind::P | Kind::C))
        .count();
    n <= slides
        && !seq
            .windows(2)
            .any(|w| w[0].0 == Kind::S && w[1].0 == Kind::S)
}

/// A general chain: every link between its pairs declared, each pair's pivots on one of the
/// links it joins, joint locations scattered about the line from `start` to the platform.
pub fn general_chain(
    m: &mut Mech,
    rng: &mut Rng,
    from: usize,
    start: V3,
    pairs: &[(Kind, bool)],
) -> Chain {
    let c = m.chains.len();
    let n = pairs.len();
    let end = m.random_platform_point(rng);
    let span = norm(sub(end, start));
    let mut links = vec![Some(from)];
    for k in 1..n {
        links.push(Some(m.link(format!("l{c}_{k}"), None)));
    }
    links.push(Some(PLATFORM));
    let mut joints = Vec::new();
    for (k, &(kind, active)) in pairs.iter().enumerate() {
        let (before, after) = (links[k].unwrap(), links[k + 1].unwrap());
        let at = if k == 0 {
            start
        } else if k + 1 == n {
            end
        } else {
            let t = k as f64 / (n - 1) as f64;
            let line = add(start, scale(t, sub(end, start)));
            add(line, scale(0.3 * span, random_unit(rng)))
        };
        // A spherical mechanism's axes run through its centre: a joint kept off it, so that
        // the axis has a direction.
        let at = match m.group {
            Group::Spherical { centre } if norm(sub(at, centre)) < 40.0 => {
                add(centre, scale(40.0, unit_or_up(sub(at, centre))))
            }
            _ => at,
        };
        // Pivots at the chain's ends mostly on the base (or the link it starts at) and the
        // platform, sometimes on the link beyond; in between on either link.
        let owner = |rng: &mut Rng| {
            let p = if k == 0 {
                0.2
            } else if k + 1 == n {
                0.8
            } else {
                0.5
            };
            if chance(rng, p) {
                after
            } else {
                before
            }
        };
        let inputs = if active {
            m.inputs_of(kind)
        } else {
            Vec::new()
        };
        let mut joint = Joint {
            kind,
            inputs,
            centre: None,
            axis: None,
            offset: None,
            lead: None,
        };
        match kind {
            Kind::S => {
                let o = owner(rng);
                joint.centre = Some(m.pivot(o, at));
            }
            Kind::U => {
                // The first axis on the link before, or (for the seeds that allow it) on the
                // link after; the centre on either link, the axis's first point at the centre or
                // elsewhere on the axis. In a planar or spherical mechanism the first axis is
                // one of its turns'.
                let u = axis_direction(m.group, kind, at, rng);
                let o = owner(rng);
                let carrier = if m.u_axis_after && chance(rng, 0.5) {
                    // Its leg looks back along the chain: mostly a pivot of the link before
                    // to give it a direction where no pair before has a centre (without one
                    // the model asks for it, and the oracle finds the U undefined).
                    if chance(rng, 0.7) {
                        m.pivot(
                            before,
                            add(at, scale(uniform(rng, 15.0, 30.0), random_unit(rng))),
                        );
                    }
                    after
                } else {
                    before
                };
                let centre = m.pivot(o, at);
                let first = if o == carrier && chance(rng, 0.5) {
                    centre
                } else {
                    m.pivot(carrier, add(at, scale(uniform(rng, -30.0, -8.0), u)))
                };
                let second = m.pivot(carrier, add(at, scale(uniform(rng, 10.0, 30.0), u)));
                joint.centre = Some(centre);
                joint.axis = Some((first, second));
            }
            Kind::R | Kind::P | Kind::C | Kind::H => {
                let u = axis_direction(m.group, kind, at, rng);
                let o = owner(rng);
                let a = add(at, scale(uniform(rng, -10.0, 10.0), u));
                let first = m.pivot(o, a);
                let second = m.pivot(o, add(a, scale(uniform(rng, 15.0, 40.0), u)));
                joint.axis = Some((first, second));
                if kind == Kind::H {
                    joint.lead = Some(uniform(rng, 2.0, 12.0));
                }
                if kind == Kind::P && active && chance(rng, 0.5) {
                    joint.offset = Some(uniform(rng, -40.0, 40.0));
                }
            }
        }
        joints.push(joint);
    }
    let shape = pairs
        .iter()
        .map(|(k, a)| format!("{k:?}{}", if *a { "*" } else { "" }))
        .collect::<Vec<_>>()
        .join("-");
    Chain {
        name: format!("c{c}"),
        links,
        joints,
        shape,
    }
}

/// The closed-form legs: S-P-S, U-P-S, R-S-S (a crank and a rod), P-S-S (a carriage and a
/// rod), and for a 3-DOF platform R-P-S; and R-U-S and P-U-S, a crank's or carriage's U on an
/// unnamed rod to the ball, which the general model takes.
fn classic_chain(m: &mut Mech, rng: &mut Rng, five: bool) -> Chain {
    let c = m.chains.len();
    let start = m.random_base_point(rng);
    let end = m.random_platform_point(rng);
    let g = m.pivot(PLATFORM, end);
    let passive = |kind| Joint {
        kind,
        inputs: Vec::new(),
        centre: None,
        axis: None,
        offset: None,
        lead: None,
    };
    let slide = |m: &mut Mech, rng: &mut Rng| Joint {
        inputs: m.inputs_of(Kind::P),
        offset: chance(rng, 0.5).then(|| uniform(rng, -40.0, 40.0)),
        ..passive(Kind::P)
    };
    let end_s = Joint {
        centre: Some(g),
        ..passive(Kind::S)
    };
    let which = if five {
        "R-P*-S"
    } else {
        pick(rng, &["S-P*-S", "U-P*-S", "R*-S-S", "P*-S-S"])
    };
    let (links, joints) = match which {
        "S-P*-S" => {
            let a = m.pivot(BASE, start);
            let first = Joint {
                centre: Some(a),
                ..passive(Kind::S)
            };
            (
                vec![Some(BASE), None, None, Some(PLATFORM)],
                vec![first, slide(m, rng), end_s],
            )
        }
        "U-P*-S" => {
            let a = m.pivot(BASE, start);
            let aa = m.pivot(BASE, add(start, scale(20.0, random_unit(rng))));
            let first = Joint {
                centre: Some(a),
                axis: Some((a, aa)),
                ..passive(Kind::U)
            };
            (
                vec![Some(BASE), None, None, Some(PLATFORM)],
                vec![first, slide(m, rng), end_s],
            )
        }
        "R-P*-S" => {
            // The hinge square to the leg (a 3-RPS), or oblique to it (the leg sweeps a cone).
            let leg = unit(sub(end, start));
            let r = random_unit(rng);
            let square = unit(sub(r, scale(dot(r, leg), leg)));
            let u = if chance(rng, 0.7) {
                square
            } else {
                unit(add(square, scale(uniform(rng, -0.6, 0.6), leg)))
            };
            let a = m.pivot(BASE, start);
            let b = m.pivot(BASE, add(start, scale(20.0, u)));
            let first = Joint {
                axis: Some((a, b)),
                ..passive(Kind::R)
            };
            (
                vec![Some(BASE), None, None, Some(PLATFORM)],
                vec![first, slide(m, rng), end_s],
            )
        }
        _ => {
            let rotary = which == "R*-S-S";
            let u = random_unit(rng);
            let a = m.pivot(BASE, start);
            let b = m.pivot(BASE, add(start, scale(25.0, u)));
            let kind = if rotary { Kind::R } else { Kind::P };
            let first = Joint {
                axis: Some((a, b)),
                inputs: m.inputs_of(kind),
                offset: (!rotary && chance(rng, 0.5)).then(|| uniform(rng, -40.0, 40.0)),
                ..passive(kind)
            };
            // The crank's (or carriage's) ball joint a crank's length off the axis, towards the
            // platform.
            let towards = sub(end, start);
            let off = unit(sub(towards, scale(dot(towards, u), u)));
            let e = add(
                add(start, scale(uniform(rng, 10.0, 40.0), u)),
                scale(
                    uniform(rng, 40.0, 70.0),
                    unit(add(off, scale(0.5, random_unit(rng)))),
                ),
            );
            let crank = m.link(format!("crank{c}"), None);
            let ce = m.pivot(crank, e);
            if m.u_rods && chance(rng, 0.4) {
                // A U on the crank (its first axis fixed there, in a random direction) and an
                // unnamed rod to the ball: the general model's leg, whose U holds only the
                // rod's spin.
                let ce2 = m.pivot(crank, add(e, scale(20.0, random_unit(rng))));
                let middle = Joint {
                    centre: Some(ce),
                    axis: Some((ce, ce2)),
                    ..passive(Kind::U)
                };
                let shape = if rotary { "R*-U-S" } else { "P*-U-S" };
                return Chain {
                    name: format!("c{c}"),
                    links: vec![Some(BASE), Some(crank), None, Some(PLATFORM)],
                    joints: vec![first, middle, end_s],
                    shape: shape.to_string(),
                };
            }
            let rod = m.link(format!("rod{c}"), Some(norm(sub(end, e))));
            let middle = Joint {
                centre: Some(ce),
                ..passive(Kind::S)
            };
            (
                vec![Some(BASE), Some(crank), Some(rod), Some(PLATFORM)],
                vec![first, middle, end_s],
            )
        }
    };
    Chain {
        name: format!("c{c}"),
        links,
        joints,
        shape: which.to_string(),
    }
}

/// Declared pivots of a link that is the link before an active pair (the README: its turn
/// must be defined) or the rail of a slide between moving links (the model asks for a point
/// off the rail's axis, to carry the slider's points off it): at least three off one line,
/// adding pivots near it where they are not.
pub fn locate_links_before_actives(m: &mut Mech, rng: &mut Rng) {
    let mut needed = Vec::new();
    for chain in &m.chains {
        for (k, j) in chain.joints.iter().enumerate() {
            let rail = matches!(j.kind, Kind::P | Kind::C);
            if let (true, Some(l)) = (!j.inputs.is_empty() || rail, chain.links[k]) {
                if l != BASE && l != PLATFORM && !needed.contains(&l) {
                    needed.push(l);
                }
            }
        }
    }
    for l in needed {
        loop {
            let pts: Vec<V3> = m
                .pivots
                .iter()
                .filter(|p| p.link == l)
                .map(|p| p.at)
                .collect();
            if spans_a_plane(&pts) {
                break;
            }
            let near = pts.first().copied().unwrap_or([0.0, 0.0, 100.0]);
            m.pivot(
                l,
                add(near, scale(uniform(rng, 15.0, 30.0), random_unit(rng))),
            );
        }
    }
}

/// Whether some three of the points span a triangle of fair size (sides ≳ 5, not flat).
pub fn spans_a_plane(pts: &[V3]) -> bool {
    pts.iter().enumerate().any(|(i, a)| {
        pts[i + 1..].iter().enumerate().any(|(j, b)| {
            pts[i + j + 2..].iter().any(|c| {
                let area = norm(cross(sub(*b, *a), sub(*c, *a)));
                let longest = [norm(sub(*b, *a)), norm(sub(*c, *a)), norm(sub(*c, *b))]
                    .into_iter()
                    .fold(0.0, f64::max);
                area > 0.2 * longest * longest && longest > 5.0
            })
        })
    })
}

/// Whether every two pivots are apart (no coincident points by chance).
pub fn pivots_apart(m: &Mech) -> bool {
    m.pivots.iter().enumerate().all(|(i, a)| {
        m.pivots[i + 1..]
            .iter()
            .all(|b| norm(sub(a.at, b.at)) > 4.0)
    })
}

/// One random mechanism from `seed`, its family decided by the seed too.
pub fn generate(seed: u64) -> Mech {
    let mut rng = Rng::new(seed);
    loop {
        let family = pick(
            &mut rng,
            &[
                "hexapod",
                "hexapod",
                "three-dof",
                "two-actives",
                "mixed-actives",
                "serial",
            ],
        );
        let mut m = Mech::new(family, &mut rng);
        // One seed in four (4 and 5 modulo 8: even and odd seeds, which the sweep's two parts
        // share out): U pairs whose first axis may be on the link after them.
        m.u_axis_after = matches!(seed % 8, 4 | 5);
        // One in four again (0 and 7 modulo 8): legs of a U on a rod to the ball.
        m.u_rods = matches!(seed % 8, 0 | 7);
        // Each entry: a chain's freedoms and its actives' variable counts.
        let plan: Vec<(usize, Vec<usize>)> = match family {
            "hexapod" => (0..6).map(|_| (6, vec![1])).collect(),
            "three-dof" => (0..3).map(|_| (5, vec![1])).collect(),
            "two-actives" => (0..3)
                .map(|_| (6, pick(&mut rng, &[&[2][..], &[1, 1]]).to_vec()))
                .collect(),
            "mixed-actives" => {
                let mut p = vec![(6, vec![3]), (6, vec![2]), (6, vec![1])];
                shuffle(&mut rng, &mut p);
                p
            }
            _ => {
                let f = pick(&mut rng, &[3, 4, 5, 6]);
                let mut actives = Vec::new();
                let mut rest = f;
                while rest > 0 {
                    let a = pick(&mut rng, &[1, 1, 1, 2, 3]);
                    // Two active S fill a chain of six: always side by side, which
                    // `general_pairs` refuses (a rod's idle spin) and would redraw forever.
                    if a <= rest && !(a == 3 && actives.contains(&3)) {
                        actives.push(a);
                        rest -= a;
                    }
                }
                vec![(f, actives)]
            }
        };
        for (f, actives) in plan {
            let classic = actives == [1]
                && (family == "hexapod" || family == "three-dof")
                && chance(&mut rng, 0.5);
            let chain = if classic {
                classic_chain(&mut m, &mut rng, f == 5)
            } else {
                // Some chains start at a declared link of an earlier chain (a link placed
                // already, as the second rod of a delta's parallelogram starts at the crank).
                let placed = placed_links(&m);
                let pairs = general_pairs(&mut rng, f, &actives);
                let (from, start) = if !placed.is_empty() && chance(&mut rng, 0.3) {
                    start_near(&m, &mut rng, &placed)
                } else {
                    (BASE, m.random_base_point(&mut rng))
                };
                general_chain(&mut m, &mut rng, from, start, &pairs)
            };
            m.chains.push(chain);
        }
        if finish(&mut m, &mut rng) {
            return m;
        }
    }
}

/// The declared links of earlier chains (placed already), which a chain may start at.
pub fn placed_links(m: &Mech) -> Vec<usize> {
    (2..m.links.len())
        .filter(|&l| m.links[l].length.is_none())
        .collect()
}

/// A chain's start on one of the `placed` links: 20 to 40 from its first pivot.
pub fn start_near(m: &Mech, rng: &mut Rng, placed: &[usize]) -> (usize, V3) {
    let l = pick(rng, placed);
    let near = m
        .pivots
        .iter()
        .find(|p| p.link == l)
        .map(|p| p.at)
        // Drawn whether needed or not: the seeds' mechanisms stay as they were generated.
        .unwrap_or(m.random_base_point(rng));
    let off = scale(uniform(rng, 20.0, 40.0), random_unit(rng));
    (l, add(near, off))
}

/// The chains declared: the platform's frame (a platform of fewer than three pivots off one
/// line gets more), the links before active pairs located; whether every two pivots are apart
/// (else the caller draws again).
pub fn finish(m: &mut Mech, rng: &mut Rng) -> bool {
    while !spans_a_plane(
        &m.pivots
            .iter()
            .filter(|p| p.link == PLATFORM)
            .map(|p| p.at)
            .collect::<Vec<_>>(),
    ) {
        let p = m.random_platform_point(rng);
        m.pivot(PLATFORM, p);
    }
    locate_links_before_actives(m, rng);
    pivots_apart(m)
}

fn number(x: f64) -> String {
    format!("{x:?}")
}

fn point(x: V3) -> String {
    format!("[{}, {}, {}]", number(x[0]), number(x[1]), number(x[2]))
}

/// The declaration as `mechanism!` takes it.
pub fn render(m: &Mech) -> String {
    let mut s = String::from("pub struct Random;\n");
    let pivots_of = |l: usize| -> String {
        m.pivots
            .iter()
            .filter(|p| p.link == l)
            .map(|p| {
                let at = if l == PLATFORM {
                    m.platform_local(p.at)
                } else {
                    p.at
                };
                format!("{} = {}", p.name, point(at))
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = writeln!(s, "base {{ {} }}", pivots_of(BASE));
    let h = m.home;
    let _ = writeln!(
        s,
        "platform(home = [{}]) {{ {} }}",
        h.map(number).join(", "),
        pivots_of(PLATFORM)
    );
    for (l, link) in m.links.iter().enumerate().skip(2) {
        match link.length {
            Some(len) => {
                let _ = writeln!(s, "link {} {{ length = {} }}", link.name, number(len));
            }
            None => {
                let _ = writeln!(s, "link {} {{ {} }}", link.name, pivots_of(l));
            }
        }
    }
    for chain in &m.chains {
        let mut items = vec![m.links[chain.links[0].unwrap()].name.clone()];
        for (k, j) in chain.joints.iter().enumerate() {
            let mut args = Vec::new();
            if let Some(c) = j.centre {
                args.push(m.pivots[c].name.clone());
            }
            if j.inputs.is_empty() {
                if !matches!(j.kind, Kind::S | Kind::U) {
                    args.push("passive".into());
                }
            } else {
                args.push(format!("active {}", j.inputs.join(" ")));
            }
            if let Some((a, b)) = j.axis {
                args.push(format!(
                    "axis = {} -> {}",
                    m.pivots[a].name, m.pivots[b].name
                ));
            }
            if let Some(o) = j.offset {
                args.push(format!("offset = {}", number(o)));
            }
            if let Some(p) = j.lead {
                args.push(format!("lead = {}", number(p)));
            }
            items.push(format!("{:?}({})", j.kind, args.join(", ")));
            if let Some(l) = chain.links[k + 1] {
                items.push(m.links[l].name.clone());
            }
        }
        let _ = writeln!(s, "chain {} = {};", chain.name, items.join(" - "));
    }
    s
}
