//! General modelling (Section 2.2) of the chains that no closed-form elimination in [`crate::model::shapes`]
//! reduces: every pivot of a moving link is a point, every lower pair contributes its Table I
//! constraint on points, and every rigid moving link adds Eq. 3 on its points.
//!
//! The pairs act through the points they share between the two links they join (rule 1 of
//! Section 2.2: the pivot C of one pair is placed on the pivots of the next), one file each:
//!
//! | pair | what the links share | equations |
//! |---|---|---|
//! | `S(C)` | the centre C | none: C is one point of both links |
//! | `R(passive, axis = A -> B)` | A and B | none: both links keep their distances to A and B |
//! | `U(C, axis = P -> Q)` | C | the two axes stay perpendicular ([`universal`]) |
//! | `P`, between moving links | — | the link after the pair is the rail's motion plus a slide along the axis ([`prismatic`]) |
//! | active `R`, `P`, `H`, `C` from the base | — | none: the link after the pair is explicit in the input ([`explicit`]) |
//!
//! A link's Eq. 3 then ties its points together. Equations that hold whatever the unknowns
//! (between base points, or between points placed by the inputs) are dropped; the rest are
//! checked at the home configuration, where the rank of the Jacobian decides the mobility and
//! which equations are implied by the others (see [`crate::simplify::rank`]).

pub mod explicit;
pub mod prismatic;
pub mod relative;
pub mod universal;

use crate::expr::{Expr, Vec3};
use crate::front::ast::{ChainItem, Coord, LinkRole, Mechanism, PairDecl, PairKind};
use crate::model::{normalize, Builder, PointRef};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;

/// A link of the general model: a declared one, or an unnamed one between two pairs.
pub struct Link {
    pub name: String,
    pub role: LinkRole,
    pub length: Option<Coord>,
    /// Point names, in order of first use.
    pub members: Vec<String>,
}

/// How a point enters the equations.
#[derive(Clone)]
pub enum Repr {
    /// Known at run time without solving: a base pivot, or a point of a link the inputs place.
    Known(Vec3),
    /// Solved for: a platform point or an intermediate link's.
    Unknown(Vec3),
}

impl Repr {
    pub fn expr(&self) -> &Vec3 {
        match self {
            Repr::Known(e) | Repr::Unknown(e) => e,
        }
    }
}

/// A pair of a general chain, with the links it joins and its place in the chain.
pub struct Joint<'a> {
    pub pair: &'a PairDecl,
    pub before: usize,
    pub after: usize,
    /// Centres of the nearest pairs before and after it in its chain (an S or U centre, an
    /// R's first axis point), for the directions of legs.
    pub previous_centre: Option<String>,
    pub next_centre: Option<String>,
    /// The points the model adds for this pair (a slide's axis tip, a U's second axis).
    pub added: Vec<String>,
}

/// The general chains, resolved: links, every point's home position, the pairs.
pub struct Topology<'a> {
    pub links: Vec<Link>,
    pub home: HashMap<String, PointRef>,
    pub joints: Vec<Joint<'a>>,
}

impl Topology<'_> {
    pub fn link(&self, name: &str) -> Option<usize> {
        self.links.iter().position(|l| l.name == name)
    }

    fn add_member(&mut self, link: usize, q: &str) {
        if !self.links[link].members.iter().any(|m| m == q) {
            self.links[link].members.push(q.to_string());
        }
    }
}

pub fn err(span: Span, msg: impl Into<String>) -> (Span, String) {
    (span, msg.into())
}

/// A link's name in messages: unnamed links between two pairs are `chain#k`, k counted from
/// the chain's first link.
pub fn named(link: &str) -> String {
    match link.split_once('#') {
        Some((chain, k)) => format!("link {k} of chain `{chain}` (unnamed)"),
        None => format!("`{link}`"),
    }
}

/// The centre a pair gives a leg's direction: an S or U centre, an R's first axis point.
fn centre(p: &PairDecl) -> Option<&Ident> {
    match p.kind {
        PairKind::S | PairKind::U => p.pivots.first(),
        PairKind::R => p.axis.as_ref().map(|(a, _)| a),
        PairKind::P | PairKind::C | PairKind::H => None,
    }
}

/// Collects the links and pairs of the `general` chains and adds the points their pairs need.
pub fn topology<'a>(
    b: &mut Builder,
    m: &'a Mechanism,
    general: &[&'a crate::front::ast::ChainDecl],
) -> Result<Topology<'a>, (Span, String)> {
    let mut topo = Topology {
        links: Vec::new(),
        home: HashMap::new(),
        joints: Vec::new(),
    };
    for l in m.all_links() {
        for p in &l.pivots {
            let slots = b.pivot_slots(&l.name.to_string(), &p.name.to_string());
            let at = if l.role == LinkRole::Platform {
                PointRef::PlatformHome(slots)
            } else {
                PointRef::Slots(slots)
            };
            topo.home.entry(p.name.to_string()).or_insert(at);
        }
    }
    for c in general {
        // A chain that begins or ends at a pair has no link there: the checker reports it.
        if !matches!(c.items.first(), Some(ChainItem::Link(_)))
            || !matches!(c.items.last(), Some(ChainItem::Link(_)))
        {
            return Err(err(c.name.span(), "a chain begins and ends at a link"));
        }
        let n = normalize(m, c);
        let mut ids = Vec::new();
        for (k, l) in n.links.iter().enumerate() {
            let (name, role, length) = match l {
                Some(l) => (l.name.to_string(), l.role, l.length.clone()),
                None => (format!("{}#{k}", c.name), LinkRole::Intermediate, None),
            };
            let id = match topo.link(&name) {
                Some(id) => id,
                None => {
                    let members = l.map_or(Vec::new(), |l| {
                        l.pivots.iter().map(|p| p.name.to_string()).collect()
                    });
                    topo.links.push(Link {
                        name,
                        role,
                        length,
                        members,
                    });
                    topo.links.len() - 1
                }
            };
            ids.push(id);
        }
        for (k, p) in n.pairs.iter().enumerate() {
            let previous_centre = n.pairs[..k]
                .iter()
                .rev()
                .find_map(|q| centre(q))
                .map(|c| c.to_string());
            let next_centre = n.pairs[k + 1..]
                .iter()
                .find_map(|q| centre(q))
                .map(|c| c.to_string());
            topo.joints.push(Joint {
                pair: p,
                before: ids[k],
                after: ids[k + 1],
                previous_centre,
                next_centre,
                added: Vec::new(),
            });
        }
    }
    // The points the pairs share.
    for k in 0..topo.joints.len() {
        let j = &topo.joints[k];
        let (p, i, a) = (j.pair, j.before, j.after);
        let shared: Vec<&Ident> = match p.kind {
            PairKind::S | PairKind::U => p.pivots.iter().take(1).collect(),
            PairKind::R => p.axis.iter().flat_map(|(a, b)| [a, b]).collect(),
            PairKind::P | PairKind::C | PairKind::H => Vec::new(),
        };
        for q in shared {
            if !topo.home.contains_key(&q.to_string()) {
                return Err(err(q.span(), format!("unknown pivot `{q}`")));
            }
            topo.add_member(i, &q.to_string());
            topo.add_member(a, &q.to_string());
        }
    }
    // The points some pairs add: a U's second axis, a slide's axis.
    for k in 0..topo.joints.len() {
        let p = topo.joints[k].pair;
        match p.kind {
            PairKind::U => universal::add_points(b, &mut topo, k)?,
            PairKind::P => prismatic::add_points(b, &mut topo, k)?,
            PairKind::C | PairKind::H if p.active.is_none() => {
                prismatic::add_points(b, &mut topo, k)?
            }
            // Active C and H: a link placed from the base (`explicit`) or by its motion
            // relative to the link before (`relative`); neither adds points to the links.
            PairKind::C | PairKind::H | PairKind::S | PairKind::R => {}
        }
    }
    Ok(topo)
}

/// What the general chains add to the model.
pub struct Added {
    /// Intermediate-link points solved for: name, home position, first index in v.
    pub points: Vec<(String, PointRef, usize)>,
    /// Scalar unknowns (passive slides), zero at home.
    pub scalars: Vec<usize>,
    /// Home value of each input the general chains declare.
    pub home_inputs: Vec<(usize, f64)>,
    /// Every named moving link and three of its points, for its pose.
    pub links: Vec<crate::model::LinkFrame>,
    /// Where the intermediate links' Eq. 3 are among the equations.
    pub link_equations: std::ops::Range<usize>,
    /// Whether an active pair places the platform relative to another link (see [`relative`]):
    /// its Eq. 3 is then implied.
    pub platform_placed: bool,
}

/// Builds the equations of the general chains into `b`. `platform` gives the platform's points
/// (by pivot name); returns the platform's foreign members (points declared on other links).
pub fn model(
    b: &mut Builder,
    m: &Mechanism,
    topo: &Topology,
    explicit_pairs: &[(&PairDecl, String)],
    platform: &HashMap<String, Vec3>,
    added: &mut Added,
) -> Result<Vec<(String, Repr)>, (Span, String)> {
    let mut repr: HashMap<String, Repr> = HashMap::new();
    // Base pivots are constants.
    if let Some(base) = &m.base {
        for p in &base.pivots {
            let name = p.name.to_string();
            let e = b.pivot_constants("base", &name);
            repr.insert(name, Repr::Known(e));
        }
    }
    // Points the model adds to the base (the axis tip of a slide on a base rail) are constants
    // too, derived from the geometry.
    for l in topo.links.iter().filter(|l| l.role == LinkRole::Base) {
        for q in &l.members {
            if !repr.contains_key(q) {
                let at = topo.home[q];
                let e = [0, 1, 2].map(|index| {
                    b.constant(
                        format!("{}_{q}", ["x", "y", "z"][index]),
                        crate::model::Recipe::Coordinate { point: at, index },
                    )
                });
                repr.insert(q.clone(), Repr::Known(e));
            }
        }
    }
    for (name, e) in platform {
        repr.insert(name.clone(), Repr::Unknown(e.clone()));
    }
    // Links placed by an active pair from the base: their points in closed form (Table I).
    let mut coincide: Vec<Vec3> = Vec::new();
    for (pair, link) in explicit_pairs {
        let Some(li) = topo.link(link) else {
            continue;
        };
        let inputs: Vec<usize> = pair.variables.iter().map(|v| b.input_index(v)).collect();
        for &input in &inputs {
            // Zero at the declared configuration; a slide with an offset reads the offset there.
            let home = match (&pair.kind, &pair.offset) {
                (PairKind::P, Some(o)) => b.coord_value(o),
                _ => 0.0,
            };
            added.home_inputs.push((input, home));
        }
        for q in topo.links[li].members.clone() {
            if matches!(repr.get(&q), Some(Repr::Known(_))) {
                continue;
            }
            let e = explicit::placed(b, pair, &inputs, &q, topo.home[&q], &topo.home)?;
            match repr.get(&q) {
                Some(Repr::Unknown(u)) => coincide.push(crate::expr::vsub(u, &e)),
                _ => {
                    repr.insert(q.clone(), Repr::Known(e));
                }
            }
        }
    }
    // The remaining points of moving links are unknowns.
    for l in &topo.links {
        if l.role == LinkRole::Base {
            continue;
        }
        for q in &l.members {
            if !repr.contains_key(q) {
                let first = b.unknowns.len();
                for axis in ["x", "y", "z"] {
                    b.unknowns.push(format!("{axis}_{q}"));
                }
                added.points.push((q.clone(), topo.home[q], first));
                repr.insert(
                    q.clone(),
                    Repr::Unknown([0, 1, 2].map(|k| Expr::Unknown(first + k))),
                );
            }
        }
    }
    // A platform pivot that an explicit link also carries: both positions coincide.
    for d in coincide {
        b.equations.extend(d.into_iter().filter(|e| e.degree() > 0));
    }
    // The links an active pair places relative to the link before it: every point of theirs is
    // placed, so their Eq. 3 is implied.
    let is_explicit = |p: &PairDecl| explicit_pairs.iter().any(|(q, _)| std::ptr::eq(*q, p));
    let placed: Vec<usize> = (0..topo.joints.len())
        .filter(|&k| relative::applies(topo, k, is_explicit(topo.joints[k].pair)))
        .map(|k| topo.joints[k].after)
        .collect();
    added.platform_placed = placed
        .iter()
        .any(|&l| topo.links[l].role == LinkRole::Platform);
    // Eq. 3 for every moving intermediate link that is not explicit.
    let links_from = b.equations.len();
    for (li, l) in topo.links.iter().enumerate() {
        let explicit = explicit_pairs.iter().any(|(_, n)| *n == l.name);
        if l.role != LinkRole::Intermediate || explicit || placed.contains(&li) {
            continue;
        }
        let members: Vec<(String, Vec3, PointRef)> = l
            .members
            .iter()
            .map(|q| (q.clone(), repr[q].expr().clone(), topo.home[q]))
            .collect();
        let length = l
            .length
            .as_ref()
            .map(|c| b.scalar_constant(&format!("{}.length", l.name), c, format!("l_{}", l.name)));
        crate::model::rigid::link_equations(b, &l.name, &members, length);
    }
    added.link_equations = links_from..b.equations.len();
    // Three points of every named moving link locate it.
    for l in &topo.links {
        if l.role != LinkRole::Intermediate || l.name.contains('#') {
            continue;
        }
        let homes: Vec<[f64; 3]> = l.members.iter().map(|q| b.home(topo.home[q])).collect();
        let frame = crate::model::rigid::frame_of(&homes).map(|f| {
            f.map(|i| {
                let q = &l.members[i];
                let home = match topo.home[q] {
                    PointRef::Auto(_) => crate::model::HomeOf::Constants([0, 1, 2].map(|index| {
                        let c = b.constant(
                            format!("h{}_{q}", ["x", "y", "z"][index]),
                            crate::model::Recipe::Coordinate {
                                point: topo.home[q],
                                index,
                            },
                        );
                        crate::model::Builder::constant_index(&c)
                    })),
                    at => crate::model::HomeOf::Point(at),
                };
                (repr[q].expr().clone(), home)
            })
        });
        added.links.push(crate::model::LinkFrame {
            name: l.name.clone(),
            frame,
        });
    }
    // The pairs' own equations.
    for (k, joint) in topo.joints.iter().enumerate() {
        let p = joint.pair;
        if is_explicit(p) {
            continue;
        }
        if relative::applies(topo, k, false) {
            relative::equations(b, topo, &repr, k, &mut added.home_inputs)?;
            continue;
        }
        match p.kind {
            PairKind::U => universal::equation(b, topo, &repr, k),
            PairKind::P | PairKind::C | PairKind::H => {
                prismatic::equations(b, topo, &repr, k, added)?
            }
            PairKind::S | PairKind::R => {}
        }
    }
    // The platform's members declared elsewhere (a shared centre, an axis point on another link).
    let mut foreign = Vec::new();
    if let Some(pl) = topo.links.iter().find(|l| l.role == LinkRole::Platform) {
        for q in &pl.members {
            if !platform.contains_key(q) {
                foreign.push((q.clone(), repr[q].clone()));
            }
        }
    }
    Ok(foreign)
}
