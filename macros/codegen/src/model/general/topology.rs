//! The general chains' links, points and pairs: every declared link a chain passes through,
//! an unnamed link between every two pairs, the points the pairs share between the links they
//! join, and the points some pairs add (a slide's axis, a U's second axis).

use super::points::{Addition, Points};
use super::{prismatic, universal, PointId};
use crate::front::errors::Errors;
use crate::front::ids::{ChainId, LinkId, PivotId};
use crate::front::resolved::{Decl, LinkRole, Pair, PairKind, Value};
use crate::model::{Auto, Builder, PointRef};

/// A link of the general model: a declared one, or an unnamed one between two pairs.
pub struct Link {
    /// Its name in the listing: the declared name, or `chain#k` for the k-th link of a chain.
    pub name: String,
    /// The declared link, if it is one.
    pub declared: Option<LinkId>,
    /// Else its chain's name and its place there (k counted from the chain's first link).
    pub unnamed: Option<(String, usize)>,
    pub role: LinkRole,
    pub length: Option<Value>,
    /// Its points, in order of first use.
    pub members: Vec<PointId>,
}

impl Link {
    pub fn holds(&self, q: PointId) -> bool {
        self.members.contains(&q)
    }
}

/// A pair of a general chain, with the links it joins and its place in the chain.
pub struct Joint<'a> {
    pub pair: &'a Pair,
    pub before: usize,
    pub after: usize,
    /// Centres of the nearest pairs before and after it in its chain (an S or U centre, an
    /// R's first axis point), for the directions of legs.
    pub previous_centre: Option<PointId>,
    pub next_centre: Option<PointId>,
    /// The chain it belongs to.
    pub chain: ChainId,
    /// The points the model adds for this pair (a slide's axis tip, a U's second axis).
    pub added: Vec<PointId>,
}

/// The general chains, resolved: links, every point and its home position, the pairs.
pub struct Topology<'a> {
    pub links: Vec<Link>,
    pub points: Points,
    pub joints: Vec<Joint<'a>>,
    /// Where each declared link is among `links`, by [`LinkId`].
    declared: Vec<Option<usize>>,
    /// Whether a short declared axis got a lever of the model's own (see `levers`).
    pub levered: bool,
}

impl Topology<'_> {
    /// The general model's link for a declared link, if a general chain passes through it.
    pub fn link(&self, id: LinkId) -> Option<usize> {
        self.declared[id.index()]
    }

    pub(super) fn add_member(&mut self, link: usize, q: PointId) {
        if !self.links[link].holds(q) {
            self.links[link].members.push(q);
        }
    }

    /// A point's home position.
    pub fn home(&self, q: PointId) -> PointRef {
        self.points.home(q)
    }

    /// A point's name in the listing.
    pub fn name(&self, q: PointId) -> &str {
        self.points.name(q)
    }
}

/// The centre a pair gives a leg's direction: an S or U centre, an R's first axis point.
fn centre(p: &Pair) -> Option<PivotId> {
    match p.kind {
        PairKind::S | PairKind::U => p.centre.map(|c| c.id),
        PairKind::R => p.axis.map(|[a, _]| a.id),
        PairKind::P | PairKind::C | PairKind::H => None,
    }
}

/// Collects the links and pairs of the `general` chains and adds the points their pairs need.
/// `None` when a pair cannot be modelled (the reasons in `errors`, one per pair).
pub fn topology<'a>(
    b: &mut Builder,
    d: &'a Decl,
    general: &[ChainId],
    errors: &mut Errors,
    with_levers: bool,
) -> Option<Topology<'a>> {
    let mut topo = Topology {
        links: Vec::new(),
        points: Points::new(b, d),
        joints: Vec::new(),
        declared: vec![None; d.links.len()],
        levered: false,
    };
    for &c in general {
        let chain = d.chain(c);
        let mut ids = Vec::new();
        for (k, l) in chain.links.iter().enumerate() {
            let id = match l.and_then(|l| topo.link(l)) {
                Some(id) => id,
                None => {
                    let link = match *l {
                        Some(l) => {
                            let decl = d.link(l);
                            topo.declared[l.index()] = Some(topo.links.len());
                            Link {
                                name: decl.name.to_string(),
                                declared: Some(l),
                                unnamed: None,
                                role: decl.role,
                                length: decl.length,
                                members: decl.pivots.iter().map(|&p| PointId::of(p)).collect(),
                            }
                        }
                        None => Link {
                            name: format!("{}#{k}", chain.name),
                            declared: None,
                            unnamed: Some((chain.name.to_string(), k)),
                            role: LinkRole::Intermediate,
                            length: None,
                            members: Vec::new(),
                        },
                    };
                    topo.links.push(link);
                    topo.links.len() - 1
                }
            };
            ids.push(id);
        }
        for (k, p) in chain.pairs.iter().enumerate() {
            let previous_centre = chain.pairs[..k].iter().rev().find_map(centre);
            let next_centre = chain.pairs[k + 1..].iter().find_map(centre);
            topo.joints.push(Joint {
                pair: p,
                before: ids[k],
                after: ids[k + 1],
                previous_centre: previous_centre.map(PointId::of),
                next_centre: next_centre.map(PointId::of),
                chain: c,
                added: Vec::new(),
            });
        }
    }
    // The points the pairs share.
    for k in 0..topo.joints.len() {
        let j = &topo.joints[k];
        let (p, i, a) = (j.pair, j.before, j.after);
        let shared: Vec<PivotId> = match p.kind {
            PairKind::S | PairKind::U => p.centre.iter().map(|c| c.id).collect(),
            PairKind::R => p.axis.iter().flat_map(|[a, b]| [a.id, b.id]).collect(),
            PairKind::P | PairKind::C | PairKind::H => Vec::new(),
        };
        for q in shared {
            topo.add_member(i, PointId::of(q));
            topo.add_member(a, PointId::of(q));
        }
    }
    // The points some pairs add: a U's second axis, a slide's axis.
    let mut ok = true;
    for k in 0..topo.joints.len() {
        let p = topo.joints[k].pair;
        let added = match p.kind {
            PairKind::U => universal::add_points(b, &mut topo, k),
            PairKind::P => prismatic::add_points(b, &mut topo, k),
            PairKind::C | PairKind::H if !p.active => prismatic::add_points(b, &mut topo, k),
            // Active C and H: a link placed from the base (`explicit`) or by its motion
            // relative to the link before (`relative`); neither adds points to the links.
            PairKind::C | PairKind::H | PairKind::S | PairKind::R => Ok(()),
        };
        if let Err(e) = added {
            errors.add(e);
            ok = false;
        }
    }
    if with_levers {
        topo.levered = levers(b, &mut topo);
    }
    ok.then_some(topo)
}

/// Whether no unknown places the link: the base, or a link an active pair with an axis moves
/// from the base (explicit in that pair's inputs, as `build`'s `explicit_pairs` takes it).
fn known(topo: &Topology, li: usize) -> bool {
    let link = &topo.links[li];
    link.role == LinkRole::Base
        || link.declared.is_some()
            && topo.joints.iter().any(|j| {
                j.after == li
                    && super::explicit::places(j.pair, topo.links[j.before].role, link.role)
            })
}

/// Below this fraction of the mechanism's size, a passive revolute pair's declared axis is given
/// a lever of the model's own (see [`levers`]).
const SHORT_AXIS: f64 = 0.25;

/// A passive revolute pair whose axis `A -> B` is declared by pivots far closer together than
/// the mechanism is large (a second pivot 1 mm from a hinge beside links of hundreds of
/// millimetres, as most declarations give an axis) shares, instead of B, a point of the
/// model's own on the same axis as far from A as the mechanism is large, so that the equations
/// read the axis over a lever of the mechanism's scale. Read over 1 mm, a 3-RRS's ∂F/∂v had
/// σmin 1.0 against σmax 600 at home, a Krawczyk radius of 0.11 mm and every sample of its
/// certified tracker refused; with the lever σmin 220, 7.1 mm and every sample proven
/// (`mechanisms::rrs`; BENCHMARKS.md, thirty-seventh session). B stays on the known link,
/// whichever link declares it, and the moving link no longer holds it. Only where one of the
/// two links is placed without unknowns (the base, or a
/// crank an active pair turns from it), so that the lever is a constant or explicit in the
/// inputs and adds no unknown; and not for a pivot another pair also uses. `build` keeps the
/// model with levers only where no equation is left out as dependent.
fn levers(b: &mut Builder, topo: &mut Topology) -> bool {
    let mut added = false;
    let at = |b: &Builder, topo: &Topology, q: PointId| b.home(topo.home(q));
    let distance = linkage_geometry::distance;
    // The mechanism's size: the largest distance between two of its points at home. One length
    // for every lever, so that a symmetric mechanism's levers are symmetric too.
    let homes: Vec<[f64; 3]> = topo.points.homes().map(|h| b.home(h)).collect();
    let size = homes
        .iter()
        .flat_map(|p| homes.iter().map(move |q| distance(*p, *q)))
        .fold(0.0f64, f64::max);
    for k in 0..topo.joints.len() {
        let p = topo.joints[k].pair;
        let (PairKind::R, false, Some([from, to])) = (p.kind, p.active, p.axis) else {
            continue;
        };
        let (a, e) = (PointId::of(from.id), PointId::of(to.id));
        // On a link the unknowns do not place (the base, or one an active pair turns or slides
        // from the base) the lever is a constant or explicit in the inputs: no unknowns added.
        // Between two links the unknowns place it would be three more; not done.
        let (before, after) = (topo.joints[k].before, topo.joints[k].after);
        if !(known(topo, before) ^ known(topo, after)) {
            continue;
        }
        let used_elsewhere = topo.joints.iter().enumerate().any(|(j, other)| {
            j != k
                && (other.pair.centre.is_some_and(|c| c.id == to.id)
                    || other
                        .pair
                        .axis
                        .is_some_and(|[x, y]| x.id == to.id || y.id == to.id))
        });
        if used_elsewhere {
            continue;
        }
        let declared = distance(at(b, topo, a), at(b, topo, e));
        if !(declared < SHORT_AXIS * size) {
            continue;
        }
        let home = b.auto_point(Auto::Lever {
            origin: topo.home(a),
            toward: topo.home(e),
            length: size,
        });
        let name = format!("{}_lever", topo.name(e));
        let q = topo.points.add(
            Addition::AxisLever {
                origin: a,
                towards: e,
            },
            name,
            home,
        );
        // B leaves the moving link and stays on the known one, whichever declares it: a
        // constant or explicit point there, on the axis and so where the moving link carries it
        // too. Kept on its declaring link's side it would, declared on the moving link, be three
        // unknowns more with a distance to A implied (a dependent equation: no lever), and
        // taken from both links where a third declares it, free that third of the axis.
        let moving = if known(topo, before) { after } else { before };
        topo.add_member(before, q);
        topo.add_member(after, q);
        topo.links[moving].members.retain(|&m| m != e);
        added = true;
    }
    added
}
