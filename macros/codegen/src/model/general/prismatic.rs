//! A prismatic pair between moving links (or a passive one on the base): the link after the
//! pair (the slider) moves with the link before it (the rail) and slides along the rail's axis.
//! A passive cylindrical pair is the same slide with the turn about the axis left free: only
//! the slider's points on the axis follow the rail — two of them, added to the slider where it
//! declares none, hold its axis on the rail's (Table I: C is P and R on one axis).
//!
//! The rail carries the axis: its origin O (the declared `axis = A -> B`'s A, or for a leg the
//! centre of the joint before the pair) and the added point `O_T` one unit towards B, or for a
//! leg where the centre of the joint after the pair is at home (see `lever`). Every point q of
//! the slider is then where the rail carries its home position, plus the slide s along the axis:
//! `q = a O + b O_T (+ c T + d (O_T − O) × (T − O)) + (s / l) (O_T − O)`, with the Eq. 3
//! coefficients of q in the rail's frame at home (T a third point of the rail, when q is off the
//! axis) and l = |O_T − O| at home (1 but for a leg). An active slide is `s = x − x_home`, a
//! passive one an unknown: degree 2 either way.

use super::points::Addition;
use super::{err, named, Added, PointId, Reprs, Topology};
use crate::expr::{self, Expr};
use crate::front::resolved::{LinkRole, Pair, PairKind};
use crate::model::builder::Scalar;
use crate::model::{Auto, Builder, PointRef, Recipe};
use nalgebra::Vector3;
use std::collections::HashMap;
use syn::Error;

/// The rail's origin and the point the axis runs towards.
fn axis_ends(topo: &Topology, k: usize) -> Result<(PointId, PointId), Error> {
    let j = &topo.joints[k];
    let p = j.pair;
    match (p.axis, j.previous_centre, j.next_centre) {
        (Some([a, b]), _, _) => Ok((PointId::of(a.id), PointId::of(b.id))),
        (None, Some(from), Some(to)) => Ok((from, to)),
        _ => Err(err(
            p.token.span(),
            "this prismatic pair needs its axis: `axis = A -> B`, or joints with centres on both sides (a leg)",
        )),
    }
}

/// Where the rail's axis point `O_T` is: for a leg (no declared axis), where the centre of the
/// joint after the pair is at home, a lever as long as the leg — one length unit beside legs of
/// hundreds of millimetres bounded every certificate (a 3-UPU wrist's Krawczyk radius at home
/// 4.9e-4 mm, 0.16 mm so; see `linkage_geometry::normal_point`); for a declared axis one unit
/// along it, as the declaration gives only a direction (at its far point, a 3-PRP's square
/// system, which has components off the mechanism, kept its monodromy loops failing to the
/// loop cap: 40 s instead of 0.9).
fn lever(
    b: &mut Builder,
    topo: &Topology,
    k: usize,
    origin: PointId,
    towards: PointId,
) -> PointRef {
    if lever_is_the_leg(topo.joints[k].pair) {
        topo.home(towards)
    } else {
        b.auto_point(Auto::Along {
            origin: topo.home(origin),
            toward: topo.home(towards),
        })
    }
}

/// Whether the pair's axis point is at the far end of a leg (no declared axis), the slide then
/// divided by the leg's length at home; else one unit along the declared axis (see [`lever`]).
fn lever_is_the_leg(p: &Pair) -> bool {
    p.axis.is_none()
}

/// Whether the pair is a link placed from the base in closed form instead (see `explicit`).
fn from_base(topo: &Topology, k: usize) -> bool {
    let j = &topo.joints[k];
    topo.links[j.before].role == LinkRole::Base
        && j.pair.active
        && j.pair.axis.is_some()
        && topo.links[j.after].role == LinkRole::Intermediate
}

pub fn add_points(b: &mut Builder, topo: &mut Topology, k: usize) -> Result<(), Error> {
    if from_base(topo, k) {
        return Ok(());
    }
    let p = topo.joints[k].pair;
    let cylinder = p.kind == PairKind::C && !p.active;
    if p.kind != PairKind::P && !cylinder {
        return Err(err(
            p.token.span(),
            format!(
                "a `{}` pair is modelled where it is active and joins the base to a declared link; here it joins {} to {}",
                p.kind.letter(),
                named(&topo.links[topo.joints[k].before]),
                named(&topo.links[topo.joints[k].after])
            ),
        ));
    }
    let (origin, towards) = axis_ends(topo, k)?;
    let (rail, slider) = (topo.joints[k].before, topo.joints[k].after);
    // An axis declared on the slider: its origin moves with the slider, so the rail carries a
    // point of its own where that origin is at home. (Taken as the rail's, the slider's origin
    // held the slide at zero: a passive slide lost its freedom, an active one its input.)
    let rail_origin =
        (!topo.links[rail].holds(origin) && topo.links[slider].holds(origin)).then(|| {
            let name = format!("{}_rail", topo.name(origin));
            let home = topo.home(origin);
            topo.points.add(Addition::RailOrigin { origin }, name, home)
        });
    let ends = format!("{}_{}", topo.name(origin), topo.name(towards));
    if linkage_geometry::along(b.home(topo.home(origin)), b.home(topo.home(towards))).is_err() {
        return Err(err(
            p.token.span(),
            format!(
                "the axis of this prismatic pair, from `{}` to `{}`, has no length at home",
                topo.name(origin),
                topo.name(towards)
            ),
        ));
    }
    let tip = lever(b, topo, k, origin, towards);
    let at = topo
        .points
        .add(Addition::AxisTip { origin, towards }, ends.clone(), tip);
    let origin = rail_origin.unwrap_or(origin);
    topo.add_member(rail, origin);
    topo.add_member(rail, at);
    if topo.links[rail].role == LinkRole::Base {
        base_point_off_axis(b, topo, rail, origin, at);
    }
    topo.joints[k].added.push(at);
    topo.joints[k].added.extend(rail_origin);
    if cylinder {
        // The slider's own two points on the axis, where the rail's are at home.
        let slider = topo.joints[k].after;
        for (end, home) in [topo.home(origin), tip].into_iter().enumerate() {
            let copy = topo.points.add(
                Addition::Copy { axis: at, end },
                format!("{ends}_c{end}"),
                home,
            );
            topo.add_member(slider, copy);
        }
    }
    Ok(())
}

/// A slide on the base whose base holds no point off its axis (`base { }` with the axis
/// declared on the slider, say): the base is fixed, so rather than ask for one it gets its own
/// point one unit off the axis, along the base axis most nearly square to it at home, which
/// carries the slider's points off the axis (see `equations`). A moving rail has no such point
/// for free: one would be three more unknowns.
fn base_point_off_axis(
    b: &mut Builder,
    topo: &mut Topology,
    rail: usize,
    origin: PointId,
    tip: PointId,
) {
    let at = |q: PointId| Vector3::from(b.home(topo.home(q)));
    let o = at(origin);
    let axis = at(tip) - o;
    let members = &topo.links[rail].members;
    let scale = members
        .iter()
        .map(|&q| (at(q) - o).norm())
        .fold(1.0f64, f64::max);
    // `equations` counts a point off the axis beyond 1e-9 of the scale; one this near it would
    // make a poor frame anyway.
    if members
        .iter()
        .any(|&q| (at(q) - o).cross(&axis).norm() > 1e-6 * scale)
    {
        return;
    }
    let k = (0..3)
        .min_by(|&i, &j| axis[i].abs().total_cmp(&axis[j].abs()))
        .unwrap_or(0);
    let mut by = [0.0; 3];
    by[k] = 1.0;
    let home = b.auto_point(Auto::Shift {
        origin: topo.home(origin),
        by,
    });
    let name = format!("{}_off", topo.name(tip));
    let off = topo.points.add(Addition::OffAxis { axis: tip }, name, home);
    topo.add_member(rail, off);
}

pub fn equations(
    b: &mut Builder,
    topo: &Topology,
    repr: &Reprs,
    k: usize,
    added: &mut Added,
) -> Result<(), Error> {
    let j = &topo.joints[k];
    let p = j.pair;
    let (origin, towards) = axis_ends(topo, k)?;
    let Some(&tip) = j.added.first() else {
        return Ok(());
    };
    // The rail's own origin, where the axis is declared on the slider (see `add_points`).
    let origin = j.added.get(1).copied().unwrap_or(origin);
    let (rail, slider) = (&topo.links[j.before], &topo.links[j.after]);
    let homes: HashMap<PointId, Vector3<f64>> = rail
        .members
        .iter()
        .chain(&slider.members)
        .chain([&origin, &towards, &tip])
        .map(|&q| (q, Vector3::from(b.home(topo.home(q)))))
        .collect();
    let home = |q: PointId| homes[&q];
    let (o, t) = (home(origin), home(tip));
    let axis = t - o;
    let scale = rail
        .members
        .iter()
        .chain(&slider.members)
        .map(|&q| (home(q) - o).norm())
        .fold(1.0f64, f64::max);
    let off_axis = |q: PointId| (home(q) - o).cross(&axis).norm() > 1e-9 * scale;
    // A third point of the rail, off its axis, for slider points off the axis.
    let third = rail
        .members
        .iter()
        .copied()
        .filter(|&q| q != origin && q != tip)
        .max_by(|&a, &b| {
            let (da, db) = (
                (home(a) - o).cross(&axis).norm(),
                (home(b) - o).cross(&axis).norm(),
            );
            da.total_cmp(&db)
        })
        .filter(|&q| off_axis(q));
    let ends = format!("{}_{}", topo.name(origin), topo.name(towards));
    // The slide from home.
    let slide = match (p.active, p.inputs.first()) {
        (true, Some(v)) => {
            let input = v.index();
            let offset = p.offset.map(|c| {
                b.scalar_constant(
                    Scalar::Offset(p.id),
                    format!("{ends}.offset"),
                    c,
                    format!("offset_{ends}"),
                )
            });
            let offset_value = p.offset.map_or(0.0, |c| b.decl.value(c));
            if p.axis.is_some() {
                // x reads the offset at home.
                added.home_inputs.push((input, offset_value));
                match offset {
                    Some(off) => Expr::minus(Expr::Input(input), off),
                    None => Expr::Input(input),
                }
            } else {
                // A leg: x + offset is the distance between the joint centres.
                let d0 = b.constant(
                    format!("d_{ends}"),
                    Recipe::Distance {
                        a: topo.home(origin),
                        b: topo.home(towards),
                    },
                );
                added
                    .home_inputs
                    .push((input, (home(towards) - o).norm() - offset_value));
                let length = match offset {
                    Some(off) => Expr::plus(Expr::Input(input), off),
                    None => Expr::Input(input),
                };
                Expr::minus(length, d0)
            }
        }
        _ => {
            let first = b.unknowns.len();
            b.unknowns.push(format!("s_{ends}"));
            added.scalars.push(first);
            Expr::Unknown(first)
        }
    };
    let e = |q: PointId| repr.expr(q);
    let (eo, et) = (e(origin), e(tip));
    // The slide is a length, the direction `tip − origin` as long as the lever at home.
    let direction = expr::vsub(&et, &eo);
    let per_length = if lever_is_the_leg(p) {
        b.constant(
            format!("inv_l_{ends}"),
            Recipe::InverseDistance {
                a: topo.home(origin),
                b: topo.home(tip),
            },
        )
    } else {
        Expr::Num(1.0)
    };
    let at = |q: PointId| -> PointRef { topo.home(q) };
    let cylinder = p.kind == PairKind::C;
    let again = added.sliders.contains(&j.after);
    if !again {
        added.sliders.push(j.after);
    }
    for &q in &slider.members {
        // The turn about a cylindrical pair's axis is free: its slider's other points follow
        // from the slider's own Eq. 3.
        if cylinder && off_axis(q) {
            continue;
        }
        let terms: Vec<[Expr; 3]> = if !off_axis(q) {
            let c: Vec<Expr> = (0..2)
                .map(|index| {
                    b.constant(
                        format!("k{index}_{}_{}", topo.name(q), rail.name.replace('#', "_")),
                        Recipe::Collinear {
                            line: [at(origin), at(tip)],
                            point: at(q),
                            index,
                        },
                    )
                })
                .collect();
            vec![expr::vscale(&c[0], &eo), expr::vscale(&c[1], &et)]
        } else {
            let Some(third) = third else {
                return Err(err(
                    p.token.span(),
                    format!(
                        "`{}` on {} is off the slide's axis, but the rail {} has no point off the axis to carry it: declare one",
                        topo.name(q),
                        named(slider),
                        named(rail)
                    ),
                ));
            };
            let f = home(third);
            let normal = axis.cross(&(f - o));
            let coplanar = normal.dot(&(home(q) - o)).abs() / normal.norm() <= 1e-9 * scale;
            let c: Vec<Expr> = (0..if coplanar { 3 } else { 4 })
                .map(|index| {
                    b.constant(
                        format!("k{index}_{}_{}", topo.name(q), rail.name.replace('#', "_")),
                        Recipe::Rigid {
                            frame: [at(origin), at(tip), at(third)],
                            point: at(q),
                            index,
                            coplanar,
                        },
                    )
                })
                .collect();
            let ef = e(third);
            let mut terms = vec![
                expr::vscale(&c[0], &eo),
                expr::vscale(&c[1], &et),
                expr::vscale(&c[2], &ef),
            ];
            if !coplanar {
                let cross = expr::cross(&direction, &expr::vsub(&ef, &eo));
                terms.push(expr::vscale(&c[3], &cross));
            }
            terms
        };
        let eq_q = e(q);
        for a in 0..3 {
            let mut sum: Vec<Expr> = terms.iter().map(|t| t[a].clone()).collect();
            sum.push(
                Expr::Product(vec![
                    slide.clone(),
                    per_length.clone(),
                    direction[a].clone(),
                ])
                .simplify(),
            );
            sum.push(eq_q[a].clone().negated());
            let eq = Expr::Sum(sum).simplify();
            if eq.degree() > 0 {
                if again {
                    added.slider_again.push(b.equations.len());
                }
                b.equations.push(eq);
            }
        }
    }
    Ok(())
}
