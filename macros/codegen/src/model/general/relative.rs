//! An active pair whose link is not placed from the base in closed form ([`super::explicit`]):
//! an active R, C or H between two moving links (or from the base to the platform), and an
//! active S or U anywhere. Table I's active column, `P_C − P_B = R(P_C0 − P_B) (+ x e)`, with
//! the link before the pair (linkage I, which holds B, C₀ and the axis) free to move.
//!
//! The pair's motion is known in its inputs: a rotation R(x) about a centre c fixed in the
//! link before (an axis point, or the S or U centre) and, for C and H, a slide along the axis.
//! Every point q of the link after the pair is then where the link before carries the point
//! that sits at `y = c + R(x)(q₀ − c) (+ z e)` in the link's home configuration (q₀ its home
//! position). The link before carries a point of home position y to
//!
//! `p1 + b(y) E1 + c(y) E2 + d(y) E3`,  E1 = p2 − p1, E2 = p3 − p1, E3 = E1 × E2,
//!
//! with p1, p2, p3 three of its points and `[a, b, c, d]` the Eq. 3 coefficients of y in their
//! frame at home (the general, mirror-free form). The coefficients are affine in y, so with
//! R(x) and the slide as coefficients the equation is of degree 2 in the unknowns: E3 is the
//! only product of unknowns, and the inputs enter through cos and sin only. On the base the
//! carrier is the identity, and the equations are linear.
//!
//! For a turn about an axis `A → B` (R, C, H) the coefficients are those of three points of the
//! link before, all fixed at home: o, the foot of q₀ on the axis; q₀; and q₀ turned a quarter
//! turn (o + e × (q₀ − o)); the point is at `o + cos θ (q₀ − o) + sin θ (w − o)` (Eq. 2 with
//! the axial part in o). For S and U, R(x) is built from the inputs (yaw, pitch and roll of an
//! S; the two turns of a U about its axes) and the link's home directions.
//!
//! Each point of the link after the pair is placed this way; the points the two links share
//! (an R's axis points, an S's or U's centre) need no equation, and the link's own Eq. 3 is
//! implied, so it is left out.

use super::{err, named, PointId, Reprs, Topology};
use crate::expr::{self, Expr, Vec3};
use crate::front::resolved::{LinkRole, Pair, PairKind, PivotRef};
use crate::model::builder::Scalar;
use crate::model::{Auto, Builder, PointRef, Recipe};
use syn::Error;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Whether pair `k` is modelled here: an active pair other than a slide (`P`, see
/// [`super::prismatic`]) that is not a link placed from the base in closed form.
pub fn applies(topo: &Topology, k: usize, explicit: bool) -> bool {
    let p = topo.joints[k].pair;
    p.active && p.kind != PairKind::P && !explicit
}

/// How the link before the pair carries a point of the link's home configuration.
// One per active pair, at compile time, never in a collection: its size does not matter.
#[allow(clippy::large_enum_variant)]
enum Carrier {
    /// The base: the point stays where it is.
    Base,
    /// A moving link: `origin + Σ t_j basis_j` for coefficients t of the point in `frame`.
    Link {
        frame: [PointRef; 3],
        origin: Vec3,
        basis: [Vec3; 3],
    },
}

impl Carrier {
    fn of(
        b: &Builder,
        topo: &Topology,
        repr: &Reprs,
        link: usize,
        pair: &Pair,
    ) -> Result<Carrier, Error> {
        let l = &topo.links[link];
        if l.role == LinkRole::Base {
            return Ok(Carrier::Base);
        }
        let homes: Vec<[f64; 3]> = l.members.iter().map(|&q| b.home(topo.home(q))).collect();
        let Some(f) = crate::model::rigid::frame_of(&homes) else {
            return Err(err(
                pair.token.span(),
                format!(
                    "the active `{}` turns its link relative to {}, whose points are all on one line: that link's own turn about the line is not defined, and with it neither is the pair's; declare a pivot on it off the line",
                    pair.kind.letter(),
                    named(l)
                ),
            ));
        };
        let e = |i: usize| repr.expr(l.members[f[i]]);
        let (p1, p2, p3) = (e(0), e(1), e(2));
        let (e1, e2) = (expr::vsub(&p2, &p1), expr::vsub(&p3, &p1));
        let e3 = expr::cross(&e1, &e2);
        Ok(Carrier::Link {
            frame: f.map(|i| topo.home(l.members[i])),
            origin: p1,
            basis: [e1, e2, e3],
        })
    }

    /// The three coordinates of home position `y` in the carrier, as constants (`tag` names
    /// them in the listing).
    fn coefficients(&self, b: &mut Builder, y: PointRef, tag: &str) -> [Expr; 3] {
        match self {
            Carrier::Base => [0, 1, 2].map(|index| {
                b.constant(
                    format!("{}{tag}", AXES[index]),
                    Recipe::Coordinate { point: y, index },
                )
            }),
            Carrier::Link { frame, .. } => [0, 1, 2].map(|j| {
                b.constant(
                    format!("k{}{tag}", j + 1),
                    Recipe::Rigid {
                        frame: *frame,
                        point: y,
                        index: j + 1,
                        coplanar: false,
                    },
                )
            }),
        }
    }

    /// Where the carrier holds the point of coordinates `t` now.
    fn place(&self, t: &[Expr; 3]) -> Vec3 {
        match self {
            Carrier::Base => t.clone(),
            Carrier::Link { origin, basis, .. } => [0, 1, 2].map(|a| {
                let mut terms = vec![origin[a].clone()];
                terms.extend((0..3).map(|j| Expr::times(t[j].clone(), basis[j][a].clone())));
                Expr::Sum(terms).simplify()
            }),
        }
    }
}

fn cos(x: &Expr) -> Expr {
    Expr::Cos(Box::new(x.clone()))
}

fn sin(x: &Expr) -> Expr {
    Expr::Sin(Box::new(x.clone()))
}

/// `v` turned by θ about the unit axis `e` (Eq. 2): `cos θ v + sin θ e × v + (1 − cos θ)(e·v) e`.
fn turn(e: &Vec3, theta: &Expr, v: &Vec3) -> Vec3 {
    let (c, s) = (cos(theta), sin(theta));
    let along = expr::dot(e, v);
    let cross = expr::cross(e, v);
    let one_minus = Expr::minus(Expr::Num(1.0), c.clone());
    [0, 1, 2].map(|k| {
        Expr::Sum(vec![
            Expr::times(c.clone(), v[k].clone()),
            Expr::times(s.clone(), cross[k].clone()),
            Expr::Product(vec![one_minus.clone(), along.clone(), e[k].clone()]).simplify(),
        ])
        .simplify()
    })
}

/// `v` turned by θ about base axis `k` (0 = x): the factors of Rz(yaw)·Ry(pitch)·Rx(roll).
fn turn_about(k: usize, theta: &Expr, v: &Vec3) -> Vec3 {
    let (c, s) = (cos(theta), sin(theta));
    let (i, j) = match k {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    let mut out = v.clone();
    out[i] = Expr::minus(
        Expr::times(c.clone(), v[i].clone()),
        Expr::times(s.clone(), v[j].clone()),
    );
    out[j] = Expr::plus(Expr::times(s, v[i].clone()), Expr::times(c, v[j].clone()));
    out
}

/// A point's home coordinates as constants.
fn coordinates(b: &mut Builder, y: PointRef, name: &str) -> Vec3 {
    [0, 1, 2].map(|index| {
        b.constant(
            format!("{}_{name}", AXES[index]),
            Recipe::Coordinate { point: y, index },
        )
    })
}

/// The unit direction `a → b` at home, as constants.
fn direction(b: &mut Builder, a: PointRef, to: PointRef, name: &str) -> Vec3 {
    [0, 1, 2].map(|index| {
        b.constant(
            format!("e{}_{name}", AXES[index]),
            Recipe::Axis {
                a,
                b: to,
                point: a,
                index,
            },
        )
    })
}

/// The equations of active pair `k`; returns the link it places.
pub fn equations(
    b: &mut Builder,
    topo: &Topology,
    repr: &Reprs,
    k: usize,
    home_inputs: &mut Vec<(usize, f64)>,
) -> Result<usize, Error> {
    let j = &topo.joints[k];
    let p = j.pair;
    let inputs: Vec<usize> = p.inputs.iter().map(|i| i.index()).collect();
    // Every input of these pairs reads zero at the declared configuration.
    home_inputs.extend(inputs.iter().map(|&i| (i, 0.0)));
    let (before, after) = (&topo.links[j.before], &topo.links[j.after]);
    let carrier = Carrier::of(b, topo, repr, j.before, p)?;
    let link_tag = before.name.replace('#', "_");
    let motion = Motion::of(b, topo, k, &inputs)?;
    for &q in &after.members {
        if before.holds(q) {
            // A point both links hold needs no equation only where the pair's motion leaves
            // it: on its axis, at its centre. Anywhere else one link would carry it and the
            // other not, so the pair could not move at all.
            if !stays(b, topo, p, &j.added, q) {
                return Err(err(
                    p.token.span(),
                    format!(
                        "pivot `{}` is on both {} and {}, off the {} of the active `{}` between them: the pair's motion would move it with one link and not the other, so the pair could not turn; declare it on one of the two links only",
                        topo.name(q),
                        named(before),
                        named(after),
                        if matches!(p.kind, PairKind::S | PairKind::U) { "centre" } else { "axis" },
                        p.kind.letter()
                    ),
                ));
            }
            continue;
        }
        // A base point the link after holds too (a ball joint's centre), which this pair's
        // turn and the carrier's leave where it is: both sides are the same point for every
        // input, and the equation would hold identically (a spherical mechanism's redundant
        // ball at its centre, carried by turns about axes through it).
        let on_base = topo
            .links
            .iter()
            .any(|l| l.role == LinkRole::Base && l.holds(q));
        if on_base && turns_leave(b, topo, k, q) {
            continue;
        }
        let at = topo.home(q);
        let t = motion.coefficients(b, &carrier, at, &format!("_{}_{link_tag}", topo.name(q)))?;
        let placed = carrier.place(&t);
        let here = repr.expr(q);
        for a in 0..3 {
            let eq = Expr::minus(here[a].clone(), placed[a].clone());
            if eq.degree() == 0 {
                return Err(err(
                    p.token.span(),
                    format!(
                        "the active `{}` joins {} to {}, which are both placed by inputs already: its input would be fixed by the others",
                        p.kind.letter(),
                        named(before),
                        named(after)
                    ),
                ));
            }
            b.equations.push(eq);
        }
    }
    Ok(j.after)
}

/// Whether active pair `k` and what places the link before it leave point `q` where it is:
/// `k` a turn (R, S, U) about an axis or centre at `q`, and the link before it the base or a
/// link an active R on the base turns about an axis through `q`.
fn turns_leave(b: &Builder, topo: &Topology, k: usize, q: PointId) -> bool {
    let j = &topo.joints[k];
    let turn = |p: &Pair| matches!(p.kind, PairKind::R | PairKind::S | PairKind::U);
    if !turn(j.pair) || !stays(b, topo, j.pair, &j.added, q) {
        return false;
    }
    if topo.links[j.before].role == LinkRole::Base {
        return true;
    }
    topo.joints.iter().any(|jj| {
        jj.after == j.before
            && topo.links[jj.before].role == LinkRole::Base
            && jj.pair.active
            && jj.pair.kind == PairKind::R
            && stays(b, topo, jj.pair, &jj.added, q)
    })
}

/// Whether the motion of pair `p` leaves point `q` where it is: its own pivots and the points
/// the model adds for it, a point on its axis (R, C, H: the axis pivots slide with a C or H
/// too, and are shared all the same), a point at its centre (S, U).
fn stays(b: &Builder, topo: &Topology, p: &Pair, added: &[PointId], q: PointId) -> bool {
    let is = |r: PivotRef| PointId::of(r.id) == q;
    let own = p.centre.is_some_and(is)
        || p.axis.is_some_and(|[a, c]| is(a) || is(c))
        || added.contains(&q);
    if own {
        return true;
    }
    let here = nalgebra::Vector3::from(b.home(topo.home(q)));
    let home = |r: PivotRef| nalgebra::Vector3::from(b.home(topo.home(PointId::of(r.id))));
    let scale = 1.0 + here.amax();
    match (p.axis, p.centre) {
        (Some([a, c]), _) => {
            let (a, c) = (home(a), home(c));
            let e = c - a;
            e.norm() > 0.0 && e.cross(&(here - a)).norm() / e.norm() <= 1e-9 * scale
        }
        (None, Some(centre)) => (here - home(centre)).norm() <= 1e-9 * scale,
        (None, None) => false,
    }
}

/// The relative motion of a pair, in the home configuration's coordinates.
enum Motion {
    /// A turn θ about the axis `a → b`, plus a slide along it (C: an input; H: lead·θ/2π).
    Axis {
        a: PointRef,
        b: PointRef,
        theta: Expr,
        slide: Option<Expr>,
    },
    /// A rotation about `centre`, built from the inputs by `rotate`.
    Turn {
        centre: PointRef,
        rotation: Rotation,
    },
}

enum Rotation {
    /// Rz(yaw)·Ry(pitch)·Rx(roll), the inputs in that order.
    Euler([Expr; 3]),
    /// Rot(outer, θo)·Rot(inner, θi): the outer axis fixed in the link before, the inner in
    /// the link after.
    Axes {
        outer: (Vec3, Expr),
        inner: (Vec3, Expr),
    },
}

impl Rotation {
    fn apply(&self, v: &Vec3) -> Vec3 {
        match self {
            Rotation::Euler([yaw, pitch, roll]) => {
                turn_about(2, yaw, &turn_about(1, pitch, &turn_about(0, roll, v)))
            }
            Rotation::Axes { outer, inner } => {
                turn(&outer.0, &outer.1, &turn(&inner.0, &inner.1, v))
            }
        }
    }
}

impl Motion {
    fn of(b: &mut Builder, topo: &Topology, k: usize, inputs: &[usize]) -> Result<Motion, Error> {
        let joint = &topo.joints[k];
        let p = joint.pair;
        let home = |q: PivotRef| topo.home(PointId::of(q.id));
        let name = |q: PivotRef| topo.name(PointId::of(q.id));
        let input = |i: usize| Expr::Input(inputs[i]);
        match p.kind {
            PairKind::R | PairKind::C | PairKind::H => {
                let Some([a, bb]) = p.axis else {
                    return Err(err(
                        p.token.span(),
                        format!(
                            "the `{}` pair needs its axis: `axis = A -> B`",
                            p.kind.letter()
                        ),
                    ));
                };
                let (a_at, b_at) = (home(a), home(bb));
                let (a, bb) = (name(a), name(bb));
                if linkage_geometry::along(b.home(a_at), b.home(b_at)).is_err() {
                    return Err(err(
                        p.axis.map_or(p.token.span(), |[_, to]| to.span),
                        format!("the axis of this `{}` pair, from `{a}` to `{bb}`, has no length at home", p.kind.letter()),
                    ));
                }
                let theta = input(0);
                let slide = match p.kind {
                    PairKind::C => Some(input(1)),
                    PairKind::H => {
                        let lead = p.lead.ok_or_else(|| {
                            err(p.token.span(), "a helical pair needs its `lead = ...`")
                        })?;
                        let lead = b.scalar_constant(
                            Scalar::Lead(p.id),
                            format!("{}.lead", b.decl.chain(p.id.chain).name),
                            lead,
                            format!("lead_{a}_{bb}"),
                        );
                        Some(
                            Expr::Product(vec![
                                Expr::Num(1.0 / (2.0 * std::f64::consts::PI)),
                                lead,
                                theta.clone(),
                            ])
                            .simplify(),
                        )
                    }
                    _ => None,
                };
                Ok(Motion::Axis {
                    a: a_at,
                    b: b_at,
                    theta,
                    slide,
                })
            }
            PairKind::S => {
                let Some(c) = p.centre else {
                    return Err(err(
                        p.token.span(),
                        "an `S` pair names its centre, e.g. `S(C)`",
                    ));
                };
                Ok(Motion::Turn {
                    centre: home(c),
                    rotation: Rotation::Euler([input(0), input(1), input(2)]),
                })
            }
            PairKind::U => {
                let (Some(c), Some([pa, qa])) = (p.centre, p.axis) else {
                    return Err(err(
                        p.token.span(),
                        "an active `U` names its centre and its first axis: `U(C, axis = P -> Q, active a b)`",
                    ));
                };
                let Some(&second) = joint.added.first() else {
                    return Err(err(p.token.span(), "this `U` has no second axis"));
                };
                let centre = home(c);
                let first = direction(b, home(pa), home(qa), &format!("{}_{}", name(pa), name(qa)));
                let second = direction(b, centre, topo.home(second), topo.name(second));
                let (t1, t2) = (input(0), input(1));
                // The first axis is fixed in the link that declares P and Q: the outer turn if
                // that is the link before the pair.
                let holder = &topo.links[joint.before];
                let first_before =
                    holder.holds(PointId::of(pa.id)) && holder.holds(PointId::of(qa.id));
                let rotation = if first_before {
                    Rotation::Axes {
                        outer: (first, t1),
                        inner: (second, t2),
                    }
                } else {
                    Rotation::Axes {
                        outer: (second, t2),
                        inner: (first, t1),
                    }
                };
                Ok(Motion::Turn { centre, rotation })
            }
            PairKind::P => unreachable!("slides are modelled in `prismatic`"),
        }
    }

    /// The coordinates in `carrier` of where the pair moves the point of home position `at`.
    fn coefficients(
        &self,
        b: &mut Builder,
        carrier: &Carrier,
        at: PointRef,
        tag: &str,
    ) -> Result<[Expr; 3], Error> {
        Ok(match self {
            Motion::Axis {
                a,
                b: to,
                theta,
                slide,
            } => {
                let foot = b.auto_point(Auto::Foot {
                    a: *a,
                    b: *to,
                    point: at,
                });
                let quarter = b.auto_point(Auto::Quarter {
                    a: *a,
                    b: *to,
                    point: at,
                });
                let ko = carrier.coefficients(b, foot, &format!("o{tag}"));
                let kq = carrier.coefficients(b, at, &format!("q{tag}"));
                let kw = carrier.coefficients(b, quarter, &format!("w{tag}"));
                let along = match slide {
                    Some(z) => {
                        let tip = b.auto_point(Auto::Along {
                            origin: *a,
                            toward: *to,
                        });
                        let kt = carrier.coefficients(b, tip, &format!("t{tag}"));
                        let ka = carrier.coefficients(b, *a, &format!("a{tag}"));
                        Some((z, kt, ka))
                    }
                    None => None,
                };
                let (c, s) = (cos(theta), sin(theta));
                [0, 1, 2].map(|j| {
                    let mut terms = vec![
                        ko[j].clone(),
                        Expr::times(c.clone(), Expr::minus(kq[j].clone(), ko[j].clone())),
                        Expr::times(s.clone(), Expr::minus(kw[j].clone(), ko[j].clone())),
                    ];
                    if let Some((z, kt, ka)) = &along {
                        terms.push(Expr::times(
                            (*z).clone(),
                            Expr::minus(kt[j].clone(), ka[j].clone()),
                        ));
                    }
                    Expr::Sum(terms).simplify()
                })
            }
            Motion::Turn { centre, rotation } => {
                let name = tag.trim_start_matches('_');
                let q0 = coordinates(b, at, name);
                let c0 = coordinates(b, *centre, &format!("c_{name}"));
                let arm = expr::vsub(&q0, &c0);
                let turned = rotation.apply(&arm);
                match carrier {
                    Carrier::Base => expr::vadd(&c0, &turned),
                    Carrier::Link { .. } => {
                        // t = k(c) + H (R (q₀ − c)), H's column k the coordinates of the base
                        // axis k as the link holds it.
                        let kc = carrier.coefficients(b, *centre, &format!("c{tag}"));
                        let columns: Vec<[Expr; 3]> = (0..3)
                            .map(|k| {
                                let mut by = [0.0; 3];
                                by[k] = 1.0;
                                let shifted = b.auto_point(Auto::Shift {
                                    origin: *centre,
                                    by,
                                });
                                carrier.coefficients(b, shifted, &format!("{}{tag}", AXES[k]))
                            })
                            .collect();
                        [0, 1, 2].map(|jj| {
                            let mut terms = vec![kc[jj].clone()];
                            for (k, col) in columns.iter().enumerate() {
                                terms.push(Expr::times(
                                    Expr::minus(col[jj].clone(), kc[jj].clone()),
                                    turned[k].clone(),
                                ));
                            }
                            Expr::Sum(terms).simplify()
                        })
                    }
                }
            }
        })
    }
}
