//! A prismatic pair between moving links (or a passive one on the base): the link after the
//! pair (the slider) moves with the link before it (the rail) and slides along the rail's axis.
//! A passive cylindrical pair is the same slide with the turn about the axis left free: only
//! the slider's points on the axis follow the rail — two of them, added to the slider where it
//! declares none, hold its axis on the rail's (Table I: C is P and R on one axis).
//!
//! The rail carries the axis: its origin O (the declared `axis = A -> B`'s A, or for a leg the
//! centre of the joint before the pair) and the added point `O_T` one unit towards B (or towards
//! the centre of the joint after the pair). Every point q of the slider is then where the rail
//! carries its home position, plus the slide s along the axis:
//! `q = a O + b O_T (+ c T + d (O_T − O) × (T − O)) + s (O_T − O)`, with the Eq. 3 coefficients
//! of q in the rail's frame at home (T a third point of the rail, when q is off the axis). An
//! active slide is `s = x − x_home`, a passive one an unknown: degree 2 either way.

use super::{err, named, Added, Repr, Topology};
use crate::expr::{self, Expr};
use crate::front::ast::PairKind;
use crate::model::{Auto, Builder, PointRef, Recipe};
use nalgebra::Vector3;
use proc_macro2::Span;
use std::collections::HashMap;

/// The rail's origin and the point the axis runs towards.
fn axis_ends(topo: &Topology, k: usize) -> Result<(String, String), (Span, String)> {
    let j = &topo.joints[k];
    let p = j.pair;
    match (&p.axis, &j.previous_centre, &j.next_centre) {
        (Some((a, b)), _, _) => Ok((a.to_string(), b.to_string())),
        (None, Some(from), Some(to)) => Ok((from.clone(), to.clone())),
        _ => Err(err(
            p.token.span(),
            "this prismatic pair needs its axis: `axis = A -> B`, or joints with centres on both sides (a leg)",
        )),
    }
}

/// Whether the pair is a link placed from the base in closed form instead (see `explicit`).
fn from_base(topo: &Topology, k: usize) -> bool {
    let j = &topo.joints[k];
    topo.links[j.before].role == crate::front::ast::LinkRole::Base
        && j.pair.active.is_some()
        && j.pair.axis.is_some()
        && topo.links[j.after].role == crate::front::ast::LinkRole::Intermediate
}

pub fn add_points(b: &mut Builder, topo: &mut Topology, k: usize) -> Result<(), (Span, String)> {
    if from_base(topo, k) {
        return Ok(());
    }
    let p = topo.joints[k].pair;
    let cylinder = p.kind == PairKind::C && p.active.is_none();
    if p.kind != PairKind::P && !cylinder {
        return Err(err(
            p.token.span(),
            format!(
                "a `{}` pair is modelled where it is active and joins the base to a declared link; here it joins {} to {}",
                p.kind.letter(),
                named(&topo.links[topo.joints[k].before].name),
                named(&topo.links[topo.joints[k].after].name)
            ),
        ));
    }
    let (origin, towards) = axis_ends(topo, k)?;
    let tip = b.auto_point(Auto::Along {
        origin: topo.home[&origin],
        toward: topo.home[&towards],
    });
    if b.home(tip).iter().any(|x| !x.is_finite()) {
        return Err(err(
            p.token.span(),
            format!("the axis of this prismatic pair, from `{origin}` to `{towards}`, has no length at home"),
        ));
    }
    let name = format!("{origin}_{towards}");
    let rail = topo.joints[k].before;
    topo.home.insert(name.clone(), tip);
    topo.add_member(rail, &origin);
    topo.add_member(rail, &name);
    topo.joints[k].added.push(name.clone());
    if cylinder {
        // The slider's own two points on the axis, where the rail's are at home.
        let slider = topo.joints[k].after;
        for (copy, at) in [
            (format!("{name}_c0"), topo.home[&origin]),
            (format!("{name}_c1"), tip),
        ] {
            topo.home.insert(copy.clone(), at);
            topo.add_member(slider, &copy);
        }
    }
    Ok(())
}

pub fn equations(
    b: &mut Builder,
    topo: &Topology,
    repr: &HashMap<String, Repr>,
    k: usize,
    added: &mut Added,
) -> Result<(), (Span, String)> {
    let j = &topo.joints[k];
    let p = j.pair;
    let (origin, towards) = axis_ends(topo, k)?;
    let Some(tip) = j.added.first() else {
        return Ok(());
    };
    let (rail, slider) = (&topo.links[j.before], &topo.links[j.after]);
    let homes: HashMap<String, Vector3<f64>> = rail
        .members
        .iter()
        .chain(&slider.members)
        .chain([&origin, &towards, tip])
        .map(|q| (q.clone(), Vector3::from(b.home(topo.home[q]))))
        .collect();
    let home = |q: &str| homes[q];
    let (o, t) = (home(&origin), home(tip));
    let axis = t - o;
    let scale = rail
        .members
        .iter()
        .chain(&slider.members)
        .map(|q| (home(q) - o).norm())
        .fold(1.0f64, f64::max);
    let off_axis = |q: &str| (home(q) - o).cross(&axis).norm() > 1e-9 * scale;
    // A third point of the rail, off its axis, for slider points off the axis.
    let third = rail
        .members
        .iter()
        .filter(|q| **q != origin && *q != tip)
        .max_by(|a, b| {
            let (da, db) = (
                (home(a) - o).cross(&axis).norm(),
                (home(b) - o).cross(&axis).norm(),
            );
            da.total_cmp(&db)
        })
        .filter(|q| off_axis(q))
        .cloned();
    // The slide from home.
    let slide = match (&p.active, p.variables.first()) {
        (Some(_), Some(v)) => {
            let input = b.input_index(v);
            let offset = p.offset.as_ref().map(|c| {
                b.scalar_constant(
                    &format!("{origin}_{towards}.offset"),
                    c,
                    format!("offset_{origin}_{towards}"),
                )
            });
            let offset_value = p.offset.as_ref().map_or(0.0, |c| b.coord_value(c));
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
                    format!("d_{origin}_{towards}"),
                    Recipe::Distance {
                        a: topo.home[&origin],
                        b: topo.home[&towards],
                    },
                );
                added
                    .home_inputs
                    .push((input, (home(&towards) - o).norm() - offset_value));
                let length = match offset {
                    Some(off) => Expr::plus(Expr::Input(input), off),
                    None => Expr::Input(input),
                };
                Expr::minus(length, d0)
            }
        }
        _ => {
            let first = b.unknowns.len();
            b.unknowns.push(format!("s_{origin}_{towards}"));
            added.scalars.push(first);
            Expr::Unknown(first)
        }
    };
    let e = |q: &str| repr[q].expr().clone();
    let (eo, et) = (e(&origin), e(tip));
    let direction = expr::vsub(&et, &eo);
    let at = |q: &str| -> PointRef { topo.home[q] };
    let cylinder = p.kind == PairKind::C;
    for q in &slider.members {
        // The turn about a cylindrical pair's axis is free: its slider's other points follow
        // from the slider's own Eq. 3.
        if cylinder && off_axis(q) {
            continue;
        }
        let terms: Vec<[Expr; 3]> = if !off_axis(q) {
            let c: Vec<Expr> = (0..2)
                .map(|index| {
                    b.constant(
                        format!("k{index}_{q}_{}", rail.name.replace('#', "_")),
                        Recipe::Collinear {
                            line: [at(&origin), at(tip)],
                            point: at(q),
                            index,
                        },
                    )
                })
                .collect();
            vec![expr::vscale(&c[0], &eo), expr::vscale(&c[1], &et)]
        } else {
            let Some(third) = &third else {
                return Err(err(
                    p.token.span(),
                    format!(
                        "`{q}` on {} is off the slide's axis, but the rail {} has no point off the axis to carry it: declare one",
                        named(&slider.name),
                        named(&rail.name)
                    ),
                ));
            };
            let f = home(third);
            let normal = axis.cross(&(f - o));
            let coplanar = normal.dot(&(home(q) - o)).abs() / normal.norm() <= 1e-9 * scale;
            let c: Vec<Expr> = (0..if coplanar { 3 } else { 4 })
                .map(|index| {
                    b.constant(
                        format!("k{index}_{q}_{}", rail.name.replace('#', "_")),
                        Recipe::Rigid {
                            frame: [at(&origin), at(tip), at(third)],
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
            sum.push(Expr::times(slide.clone(), direction[a].clone()));
            sum.push(eq_q[a].clone().negated());
            let eq = Expr::Sum(sum).simplify();
            if eq.degree() > 0 {
                b.equations.push(eq);
            }
        }
    }
    Ok(())
}
