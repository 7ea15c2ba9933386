//! The universal joint `U(C, axis = P -> Q)`: a spherical joint less one rotation. Its first axis
//! P→Q is fixed in the link that declares P and Q; its second axis, perpendicular to the first
//! and to the leg (the line from C to the next joint's centre through the other link) at home,
//! is fixed in the other link, which carries the point `C_u` one unit along it. The constraint:
//! `(Q − P)·(C_u − C) = 0`, the two axes stay perpendicular — degree 2 in the points.

use super::{err, named, Repr, Topology};
use crate::expr;
use crate::model::{Auto, Builder};
use proc_macro2::Span;
use std::collections::HashMap;

pub fn add_points(b: &mut Builder, topo: &mut Topology, k: usize) -> Result<(), (Span, String)> {
    let j = &topo.joints[k];
    let p = j.pair;
    let Some(centre) = p.pivots.first() else {
        return Err(err(
            p.token.span(),
            "a `U` pair names its centre, e.g. `U(C, axis = P -> Q)`",
        ));
    };
    let Some((pa, qa)) = &p.axis else {
        return Err(err(
            p.token.span(),
            "this universal joint needs its first axis, `U(C, axis = P -> Q)` with P and Q on one of the links it joins (outside the leg forms, where it acts as an `S`)",
        ));
    };
    let holds = |l: usize| {
        let m = &topo.links[l].members;
        m.iter().any(|x| pa == x) && m.iter().any(|x| qa == x)
    };
    let (holder, other, towards) = if holds(j.before) {
        (j.before, j.after, j.next_centre.clone())
    } else if holds(j.after) {
        (j.after, j.before, j.previous_centre.clone())
    } else {
        return Err(err(
            pa.span(),
            format!(
                "the axis `{pa} -> {qa}` of this `U` is on neither of the links it joins ({} and {})",
                named(&topo.links[j.before].name),
                named(&topo.links[j.after].name)
            ),
        ));
    };
    let c = centre.to_string();
    // At the end of a chain no joint follows: the other link's pivot farthest from the centre
    // gives the direction instead.
    let towards = towards.or_else(|| {
        let h = b.home(topo.home[&c]);
        topo.links[other]
            .members
            .iter()
            .filter(|q| **q != c)
            .map(|q| (q, linkage_geometry::distance(b.home(topo.home[q]), h)))
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .map(|(q, _)| q.clone())
    });
    let Some(towards) = towards else {
        return Err(err(
            p.token.span(),
            "the second axis of this `U` is perpendicular to the first and to the line from its centre to the next joint's, but no joint follows it and the link after it has no other pivot",
        ));
    };
    let at = |q: &str| topo.home[q];
    let auto = b.auto_point(Auto::Normal {
        origin: at(&c),
        a: [at(&pa.to_string()), at(&qa.to_string())],
        b: [at(&c), at(&towards)],
    });
    if b.home(auto).iter().any(|x| !x.is_finite()) {
        return Err(err(
            pa.span(),
            format!("the axis `{pa} -> {qa}` of this `U` lies along the leg from `{c}` to `{towards}` at home: the second axis is undefined"),
        ));
    }
    let name = format!("{c}_u");
    let _ = holder;
    topo.home.insert(name.clone(), auto);
    // A passive U holds the second axis in the other link; an active one turns about it by its
    // input (see `relative`), which needs only its direction at home.
    if p.active.is_none() {
        topo.add_member(other, &name);
    }
    topo.joints[k].added.push(name);
    Ok(())
}

pub fn equation(b: &mut Builder, topo: &Topology, repr: &HashMap<String, Repr>, k: usize) {
    let j = &topo.joints[k];
    let (Some(centre), Some((pa, qa)), Some(tip)) =
        (j.pair.pivots.first(), &j.pair.axis, j.added.first())
    else {
        return;
    };
    let e = |q: &str| repr[q].expr().clone();
    let first = expr::vsub(&e(&qa.to_string()), &e(&pa.to_string()));
    let second = expr::vsub(&e(tip), &e(&centre.to_string()));
    let eq = expr::dot(&first, &second);
    if eq.degree() > 0 {
        b.equations.push(eq);
    }
}
