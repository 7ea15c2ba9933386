//! The universal joint `U(C, axis = P -> Q)`: a spherical joint less one rotation. Its first axis
//! P→Q is fixed in the link that declares P and Q; its second axis, perpendicular to the first
//! and to the leg (the line from C to the next joint's centre through the other link) at home,
//! is fixed in the other link, which carries the point `C_u` along it, as far from C as the leg
//! is long (a lever of the mechanism's size: `linkage_geometry::normal_point`). The constraint:
//! `(Q − P)·(C_u − C) = 0`, the two axes stay perpendicular — degree 2 in the points. A
//! passive U on a rod to an `S` gets no such point: it holds only the rod's spin.

use super::points::Addition;
use super::{err, named, PointId, Repr, Reprs, Topology};
use crate::expr::{self, Expr};
use crate::front::resolved::{LinkRole, PairKind};
use crate::model::{Auto, Builder};
use syn::Error;

pub fn add_points(b: &mut Builder, topo: &mut Topology, k: usize) -> Result<(), Error> {
    let j = &topo.joints[k];
    let p = j.pair;
    let Some(centre) = p.centre else {
        return Err(err(
            p.token.span(),
            "a `U` pair names its centre, e.g. `U(C, axis = P -> Q)`",
        ));
    };
    let Some([pa, qa]) = p.axis else {
        return Err(err(
            p.token.span(),
            "this universal joint needs its first axis, `U(C, axis = P -> Q)` with P and Q on one of the links it joins (outside the leg forms, where it acts as an `S`)",
        ));
    };
    let (c, a, q) = (
        PointId::of(centre.id),
        PointId::of(pa.id),
        PointId::of(qa.id),
    );
    let holds = |l: usize| topo.links[l].holds(a) && topo.links[l].holds(q);
    let (other, towards) = if holds(j.before) {
        (j.after, j.next_centre)
    } else if holds(j.after) {
        (j.before, j.previous_centre)
    } else {
        return Err(err(
            pa.span,
            format!(
                "the axis `{} -> {}` of this `U` is on neither of the links it joins ({} and {})",
                topo.name(a),
                topo.name(q),
                named(&topo.links[j.before]),
                named(&topo.links[j.after])
            ),
        ));
    };
    // At the end of a chain no joint follows: the other link's pivot farthest from the centre
    // gives the direction instead. Of a declared link, only the pivots declared on it: its
    // members also hold what other chains' pairs bring to it (an R's axis pivots declared on
    // the neighbouring link, the points a slide or a U adds), and the axis of this U must not
    // depend on the rest of the mechanism.
    let declared = topo.links[other].declared;
    let own = |m: PointId| match (declared, topo.points.pivot(m)) {
        (Some(link), Some(pivot)) => b.decl.pivot(pivot).link == link,
        (Some(_), None) => false,
        // An unnamed link belongs to this chain alone: its members are this chain's points.
        (None, _) => true,
    };
    let towards = towards.or_else(|| {
        let h = b.home(topo.home(c));
        topo.links[other]
            .members
            .iter()
            .filter(|&&m| m != c && own(m))
            .map(|&m| (m, linkage_geometry::distance(b.home(topo.home(m)), h)))
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .map(|(m, _)| m)
    });
    let Some(towards) = towards else {
        // The first axis on the link after the pair (its other link the one before) looks back
        // along the chain.
        let (next, follows) = if other == j.after {
            ("next", "follows")
        } else {
            ("previous", "precedes")
        };
        return Err(err(
            p.token.span(),
            format!(
                "the second axis of this `U` is perpendicular to the first and to the line from its centre to the {next} joint's, but no joint {follows} it and {} has no other pivot of its own to give the line: declare one",
                named(&topo.links[other])
            ),
        ));
    };
    let normal = Auto::Normal {
        origin: topo.home(c),
        a: [topo.home(a), topo.home(q)],
        b: [topo.home(c), topo.home(towards)],
    };
    let defined = linkage_geometry::normal_point(
        b.home(topo.home(c)),
        [b.home(topo.home(a)), b.home(topo.home(q))],
        [b.home(topo.home(c)), b.home(topo.home(towards))],
    )
    .is_ok_and(|n| n.iter().all(|x| x.is_finite()));
    if !defined {
        return Err(err(
            pa.span,
            format!(
                "the axis `{} -> {}` of this `U` lies along the leg from `{}` to `{}` at home: the second axis is undefined",
                topo.name(a),
                topo.name(q),
                topo.name(c),
                topo.name(towards)
            ),
        ));
    }
    if !p.active && only_a_rod_to_a_ball(topo, k, other) {
        return Ok(());
    }
    let auto = b.auto_point(normal);
    let name = format!("{}_u", topo.name(c));
    let second = topo
        .points
        .add(Addition::SecondAxis { centre: c }, name, auto);
    // A passive U holds the second axis in the other link; an active one turns about it by its
    // input (see `relative`), which needs only its direction at home.
    if !p.active {
        topo.add_member(other, second);
    }
    topo.joints[k].added.push(second);
    Ok(())
}

/// Whether the link carrying this U's second axis is a rod: an intermediate link (unnamed, or
/// declared without pivots of its own) of two points, this U's centre and that of its one
/// other joint, an `S`. Then the U holds nothing but the rod's spin about the line through its
/// two centres, which no other pair sees: for the rest of the mechanism the rod is the distance
/// between its centres (Eq. 3), as between two `S`, and the second axis's point would add three
/// unknowns and a twin of every root (the leg's half-turn, see [`spins`]) to a system no answer
/// needs them in. A link with other pivots or joints, the base or the platform, and a rod with
/// a U or R at its other end (which turns with the spin) keep the point.
fn only_a_rod_to_a_ball(topo: &Topology, k: usize, other: usize) -> bool {
    let link = &topo.links[other];
    if link.role != LinkRole::Intermediate || link.members.len() != 2 {
        return false;
    }
    let mut others = topo
        .joints
        .iter()
        .enumerate()
        .filter(|&(i, j)| i != k && (j.before == other || j.after == other));
    matches!(
        (others.next(), others.next()),
        (Some((_, j)), None) if j.pair.kind == PairKind::S
    )
}

pub fn equation(b: &mut Builder, topo: &Topology, repr: &Reprs, k: usize) {
    let j = &topo.joints[k];
    let (Some(centre), Some([pa, qa]), Some(&tip)) = (j.pair.centre, j.pair.axis, j.added.first())
    else {
        return;
    };
    let e = |q: PointId| repr.expr(q);
    let first = expr::vsub(&e(PointId::of(qa.id)), &e(PointId::of(pa.id)));
    let second = expr::vsub(&e(tip), &e(PointId::of(centre.id)));
    let eq = expr::dot(&first, &second);
    if eq.degree() > 0 {
        b.equations.push(eq);
    }
}

/// Per chain, the candidate half-turn of its legs about their own axes: every second-axis point
/// `C_u` of the chain's passive U pairs that is an unknown, each coordinate with the same
/// coordinate of its centre C (an unknown, a constant, or an input's expression). Turning a
/// leg half a turn about the line through its centres maps `C_u` to `2C − C_u` and leaves the
/// U equation `(Q − P)·(C_u − C) = 0` and the leg's distances as they were wherever the leg's
/// other points lie on that line: then every root has a twin. Whether that holds is not
/// decided here (a leg with a point off its axis breaks it): the runtime keeps a candidate only
/// where it maps a generic root to another root. Chains without such a point give none.
pub fn spins(topo: &Topology, repr: &Reprs) -> Vec<Vec<(usize, Expr)>> {
    let mut out: Vec<(crate::front::ids::ChainId, Vec<(usize, Expr)>)> = Vec::new();
    for j in &topo.joints {
        let p = j.pair;
        let (PairKind::U, false, Some(centre), Some(&tip)) =
            (p.kind, p.active, p.centre, j.added.first())
        else {
            continue;
        };
        let (Some(Repr::Unknown(t)), Some(c)) = (repr.get(tip), repr.get(PointId::of(centre.id)))
        else {
            continue;
        };
        let coords: Vec<(usize, Expr)> = t
            .iter()
            .zip(c.expr())
            .filter_map(|(t, c)| match t {
                Expr::Unknown(i) => Some((*i, c.clone())),
                _ => None,
            })
            .collect();
        match out.iter_mut().find(|(chain, _)| *chain == j.chain) {
            Some((_, list)) => list.extend(coords),
            None => out.push((j.chain, coords)),
        }
    }
    out.into_iter()
        .map(|(_, list)| list)
        .filter(|list| !list.is_empty())
        .collect()
}
