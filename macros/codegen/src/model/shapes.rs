//! Chains: Table I's pair constraints combined from the base to the platform (Section 2.2),
//! with the intermediate links' pivots eliminated.
//!
//! Combining a chain's pair equations and solving those in one unknown leaves, for every
//! supported chain, constraints on the platform pivot `G` alone:
//!
//! | chain | pivots eliminated | what remains |
//! |---|---|---|
//! | `S|U(A) - P(active x) - S|U(G)` | the leg's axis points D, E, F (Eq. 14) | `‖G − A‖² = (x + offset)²` (Eq. 15) |
//! | `S|U(A) - rod - S|U(G)`, `rod { length = l }` | — | `‖G − A‖² = l²` |
//! | `R|P|H|C(active …, axis = A -> B) - link - S|U(C) - rod - S|U(G)` | C, explicit in the inputs | `‖G − C(x)‖² = l²` |
//! | `R(passive, axis = A -> B) - P(active x) - S|U(G)` | the leg's axis point | `e·(G − A) = 0`, `‖G − A‖² = (x + offset)²` |
//!
//! For the active pair at the base, C(x) follows Table I: `C − B = R(C0 − B) + x e` with R of
//! Eq. 2, written `o + u cos θ + w sin θ (+ x e)` with o, u, w derived from the geometry.

use crate::expr::{self, Expr, Vec3};
use crate::front::ids::{ChainId, InputId, LinkId, PivotId};
use crate::front::resolved::{Decl, LinkRole, Pair, PairKind, Value};
use crate::model::builder::Scalar;
use crate::model::{is_point_joint, turn, Builder, Inverse, PointRef, Recipe};
use syn::Error;

/// A platform pivot a chain ends on: its id and its place among the platform's pivots.
#[derive(Clone, Copy)]
pub struct PlatformPivot {
    pub id: PivotId,
    pub index: usize,
}

pub enum Shape<'a> {
    Leg {
        anchor: PivotId,
        slider: &'a Pair,
        /// The slider's one input.
        input: InputId,
        platform: PlatformPivot,
    },
    Rod {
        anchor: PivotId,
        rod: LinkId,
        length: Value,
        platform: PlatformPivot,
    },
    Driven {
        driver: &'a Pair,
        axis: [PivotId; 2],
        /// The lead of a helical driver.
        lead: Option<Value>,
        link: LinkId,
        tip: PivotId,
        rod: LinkId,
        length: Value,
        platform: PlatformPivot,
    },
    Swing {
        hinge: &'a Pair,
        axis: [PivotId; 2],
        slider: &'a Pair,
        /// The slider's one input.
        input: InputId,
        platform: PlatformPivot,
    },
}

impl Shape<'_> {
    /// Whether the links the shape eliminates belong to its chain alone.
    pub fn links_private(&self, private: &dyn Fn(LinkId) -> bool) -> bool {
        match self {
            Shape::Rod { rod, .. } | Shape::Driven { rod, .. } => private(*rod),
            Shape::Leg { .. } | Shape::Swing { .. } => true,
        }
    }

    pub fn platform_pivot(&self) -> PlatformPivot {
        match self {
            Shape::Leg { platform, .. }
            | Shape::Rod { platform, .. }
            | Shape::Driven { platform, .. }
            | Shape::Swing { platform, .. } => *platform,
        }
    }
}

pub struct ChainModel {
    pub equations: Vec<Expr>,
    pub inverse: Inverse,
}

fn center(d: &Decl, p: &Pair, chain: ChainId) -> Result<PivotId, Error> {
    match p.centre {
        Some(c) => Ok(c.id),
        None => Err(Error::new(
            p.token.span(),
            format!(
                "pair `{}` in chain `{}` names its centre: one pivot, e.g. `{}(G1)`",
                p.kind.letter(),
                d.chain(chain).name,
                p.kind.letter()
            ),
        )),
    }
}

/// Why a chain is not reduced in closed form: it is not one of the shapes (`None`: the general
/// model takes it), or it is one with a mistake (`Some`: a spanned error).
type Fail = Option<Error>;

/// The closed-form shape of a chain from the base to the platform, if it has one.
pub fn classify(d: &Decl, c: ChainId) -> Result<Option<Shape<'_>>, Error> {
    let links = &d.chain(c).links;
    if links.first() != Some(&Some(LinkId::BASE)) || links.last() != Some(&Some(LinkId::PLATFORM)) {
        return Ok(None);
    }
    match shape(d, c) {
        Ok(s) => Ok(Some(s)),
        Err(None) => Ok(None),
        Err(Some(e)) => Err(e),
    }
}

fn shape(d: &Decl, c: ChainId) -> Result<Shape<'_>, Fail> {
    let chain = d.chain(c);
    let unsupported = || None;
    // A U at both ends of a leg constrains the leg's spin, and with it the platform: only a leg
    // with at least one S reduces to a distance.
    let ends_ok = |a: &Pair, b: &Pair| !(a.kind == PairKind::U && b.kind == PairKind::U);
    let on = |link: LinkId, q: PivotId| d.pivot(q).link == link;
    let base_axis = |p: &Pair| {
        p.axis
            .is_none_or(|[a, b]| on(LinkId::BASE, a.id) && on(LinkId::BASE, b.id))
    };
    let platform_center = |p: &Pair| -> Result<PlatformPivot, Fail> {
        let g = center(d, p, c).map_err(Some)?;
        match d.platform_pivots().iter().position(|&q| q == g) {
            Some(index) => Ok(PlatformPivot { id: g, index }),
            None => Err(None),
        }
    };
    let base_center = |p: &Pair| -> Result<PivotId, Fail> {
        let a = center(d, p, c).map_err(Some)?;
        if !on(LinkId::BASE, a) {
            return Err(None);
        }
        Ok(a)
    };
    let intermediate =
        |k: usize| chain.links[k].filter(|&l| d.link(l).role == LinkRole::Intermediate);
    let with_length = |l: Option<LinkId>| l.and_then(|l| d.link(l).length.map(|len| (l, len)));
    match chain.pairs.as_slice() {
        [s1, slider, s2]
            if is_point_joint(s1)
                && slider.kind == PairKind::P
                && is_point_joint(s2)
                && ends_ok(s1, s2)
                && slider.axis.is_none() =>
        {
            if !slider.active {
                return Err(Some(Error::new(slider.token.span(), format!("the `P` pair of leg `{}` is passive: the leg would not constrain the platform; make it `P(active L)`", chain.name))));
            }
            let input = single_variable(slider, &chain.name).map_err(Some)?;
            Ok(Shape::Leg {
                anchor: base_center(s1)?,
                slider,
                input,
                platform: platform_center(s2)?,
            })
        }
        [s1, s2] if is_point_joint(s1) && is_point_joint(s2) && ends_ok(s1, s2) => {
            match with_length(intermediate(1)) {
                Some((rod, length)) => Ok(Shape::Rod {
                    anchor: base_center(s1)?,
                    rod,
                    length,
                    platform: platform_center(s2)?,
                }),
                None => Err(unsupported()),
            }
        }
        [driver, s1, s2]
            if matches!(
                driver.kind,
                PairKind::R | PairKind::P | PairKind::H | PairKind::C
            ) && is_point_joint(s1)
                && is_point_joint(s2)
                && ends_ok(s1, s2)
                && base_axis(driver) =>
        {
            if !driver.active {
                return Err(unsupported());
            }
            let expected = if driver.kind == PairKind::C { 2 } else { 1 };
            if driver.inputs.len() != expected {
                return Err(Some(Error::new(
                    driver.token.span(),
                    format!(
                        "an active `{}` pair has {expected} joint variable(s), found {}",
                        driver.kind.letter(),
                        driver.inputs.len()
                    ),
                )));
            }
            let Some([ax_a, ax_b]) = driver.axis else {
                return Err(Some(Error::new(
                    driver.token.span(),
                    format!(
                        "the `{}` pair of chain `{}` needs its axis: `axis = A -> B` on `base`",
                        driver.kind.letter(),
                        chain.name
                    ),
                )));
            };
            if driver.kind == PairKind::H && driver.lead.is_none() {
                return Err(Some(Error::new(
                    driver.token.span(),
                    "a helical pair needs its `lead = ...`",
                )));
            }
            let Some(link) = intermediate(1) else {
                return Err(Some(Error::new(driver.token.span(), format!("chain `{}` needs a declared link after its driving pair, holding the centre of the next joint", chain.name))));
            };
            let tip = center(d, s1, c).map_err(Some)?;
            // The joint's centre declared on the link after it (which the front end allows:
            // a centre is on either link it joins) is no crank's tip: the general model takes
            // the chain. (It was refused, "`C` is not a pivot of link `crank`".)
            if !on(link, tip) {
                return Err(unsupported());
            }
            match with_length(intermediate(2)) {
                Some((rod, length)) => Ok(Shape::Driven {
                    driver,
                    axis: [ax_a.id, ax_b.id],
                    lead: driver.lead,
                    link,
                    tip,
                    rod,
                    length,
                    platform: platform_center(s2)?,
                }),
                None => Err(unsupported()),
            }
        }
        [hinge, slider, s]
            if hinge.kind == PairKind::R
                && slider.kind == PairKind::P
                && is_point_joint(s)
                && base_axis(hinge)
                && slider.axis.is_none() =>
        {
            if hinge.active || !slider.active {
                return Err(unsupported());
            }
            let Some([ax_a, ax_b]) = hinge.axis else {
                return Err(Some(Error::new(
                    hinge.token.span(),
                    format!(
                        "the `R` pair of chain `{}` needs its axis: `axis = A -> B` on `base`",
                        chain.name
                    ),
                )));
            };
            let input = single_variable(slider, &chain.name).map_err(Some)?;
            let platform = platform_center(s)?;
            // The plane through the hinge's first point, perpendicular to it, holds the leg
            // only where the declared leg is square to the hinge; an oblique leg sweeps a
            // cone, which the general model takes (its slide carried by the hinge's link).
            if !square_to_hinge(d, [ax_a.id, ax_b.id], platform.id) {
                return Err(unsupported());
            }
            Ok(Shape::Swing {
                hinge,
                axis: [ax_a.id, ax_b.id],
                slider,
                input,
                platform,
            })
        }
        _ => Err(unsupported()),
    }
}

/// Whether the leg from the hinge's first axis point to the platform pivot `g` is
/// perpendicular to the hinge's axis at the declared configuration (the platform at its
/// declared `home`, or at the base frame), to a cosine of 1e-4: declarations written to five
/// digits (86.603 for 50√3) keep their closed form, as they kept assembling at home before.
fn square_to_hinge(d: &Decl, [a, b]: [PivotId; 2], g: PivotId) -> bool {
    let (pa, pb, local) = (d.point(a), d.point(b), d.point(g));
    let [yaw, pitch, roll, tx, ty, tz] = d.platform.home.map_or([0.0; 6], |(_, h)| h);
    let r = linkage_geometry::rotation(yaw, pitch, roll);
    let pg: [f64; 3] =
        [0, 1, 2].map(|i| (0..3).map(|j| r[i][j] * local[j]).sum::<f64>() + [tx, ty, tz][i]);
    let e = [0, 1, 2].map(|i| pb[i] - pa[i]);
    let leg = [0, 1, 2].map(|i| pg[i] - pa[i]);
    let dot: f64 = (0..3).map(|i| e[i] * leg[i]).sum();
    let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    dot.abs() <= 1e-4 * norm(e) * norm(leg)
}

/// The one input of an active slider.
fn single_variable(p: &Pair, chain: &syn::Ident) -> Result<InputId, Error> {
    match p.inputs.as_slice() {
        [input] => Ok(*input),
        _ => Err(Error::new(
            p.token.span(),
            format!("an active `P` pair in chain `{chain}` has one joint variable"),
        )),
    }
}

/// An active slider's joint variable, its offset constant, and the leg length `x + offset`.
fn leg_length(
    b: &mut Builder,
    slider: &Pair,
    input: InputId,
    chain: &str,
) -> (usize, Option<Expr>, Expr) {
    let input = input.index();
    let offset = slider.offset.map(|o| {
        b.scalar_constant(
            Scalar::Offset(slider.id),
            format!("{chain}.offset"),
            o,
            format!("offset_{chain}"),
        )
    });
    let length = match &offset {
        Some(o) => Expr::plus(Expr::Input(input), o.clone()),
        None => Expr::Input(input),
    };
    (input, offset, length)
}

/// Emits the chain's equations on platform point `p` (of `k` points).
pub fn model(b: &mut Builder, c: ChainId, shape: &Shape, p: usize, k: usize) -> ChainModel {
    let g: Vec3 = [0, 1, 2].map(|a| Expr::Unknown(a * k + p));
    let chain = b.decl.chain(c).name.to_string();
    match shape {
        Shape::Leg {
            anchor,
            slider,
            input,
            ..
        } => {
            let a = b.pivot_constants(*anchor);
            let (input, offset, length) = leg_length(b, slider, *input, &chain);
            let eq = Expr::minus(expr::squared_distance(&g, &a), length.square());
            ChainModel {
                equations: vec![eq],
                inverse: Inverse::Distance {
                    input,
                    point: p,
                    anchor: a.each_ref().map(Builder::constant_index),
                    offset: offset.as_ref().map(Builder::constant_index),
                },
            }
        }
        Shape::Rod {
            anchor,
            rod: rod_id,
            length,
            ..
        } => {
            let a = b.pivot_constants(*anchor);
            let rod = b.decl.link(*rod_id).name.to_string();
            let l = b.scalar_constant(
                Scalar::Length(*rod_id),
                format!("{rod}.length"),
                *length,
                format!("l_{rod}"),
            );
            let eq = Expr::minus(expr::squared_distance(&g, &a), l.square());
            ChainModel {
                equations: vec![eq],
                inverse: Inverse::None { inputs: vec![] },
            }
        }
        Shape::Driven {
            driver,
            axis: [ax_a, ax_b],
            lead,
            tip,
            rod: rod_id,
            length,
            ..
        } => {
            let a = PointRef::Slots(b.pivot_slots(*ax_a));
            let bb = PointRef::Slots(b.pivot_slots(*ax_b));
            let c0 = PointRef::Slots(b.pivot_slots(*tip));
            let part = |b: &mut Builder, index: usize, prefix: &str| -> Vec3 {
                [0, 1, 2].map(|k3| {
                    let name = format!("{prefix}{}_{chain}", ["x", "y", "z"][k3]);
                    b.constant(
                        name,
                        Recipe::Axis {
                            a,
                            b: bb,
                            point: c0,
                            index: index + k3,
                        },
                    )
                })
            };
            let rod = b.decl.link(*rod_id).name.to_string();
            let l = b.scalar_constant(
                Scalar::Length(*rod_id),
                format!("{rod}.length"),
                *length,
                format!("l_{rod}"),
            );
            let inputs: Vec<usize> = driver.inputs.iter().map(|i| i.index()).collect();
            let (tip_expr, inverse) = match driver.kind {
                PairKind::P => {
                    let e = part(b, 0, "e");
                    let c0e = b.pivot_constants(*tip);
                    // The input is the slide from the declared configuration plus the offset
                    // (the README's P with an axis); the offset was left out here, so that the
                    // input read the bare slide.
                    let offset = driver.offset.map(|o| {
                        b.scalar_constant(
                            Scalar::Offset(driver.id),
                            format!("{chain}.offset"),
                            o,
                            format!("offset_{chain}"),
                        )
                    });
                    let slide = match &offset {
                        Some(off) => Expr::minus(Expr::Input(inputs[0]), off.clone()),
                        None => Expr::Input(inputs[0]),
                    };
                    let t = expr::vadd(&c0e, &expr::vscale(&slide, &e));
                    let inv = Inverse::PrismaticRod {
                        input: inputs[0],
                        point: p,
                        c0: c0e.each_ref().map(Builder::constant_index),
                        e: e.each_ref().map(Builder::constant_index),
                        length: Builder::constant_index(&l),
                        offset: offset.as_ref().map(Builder::constant_index),
                    };
                    (t, inv)
                }
                kind => {
                    let o = part(b, 3, "o");
                    let u = part(b, 6, "u");
                    let w = part(b, 9, "w");
                    let th = Expr::Input(inputs[0]);
                    let mut t = turn::turned(&o, &u, &w, &th);
                    let inv = match kind {
                        PairKind::R => Inverse::RevoluteRod {
                            input: inputs[0],
                            point: p,
                            o: o.each_ref().map(Builder::constant_index),
                            u: u.each_ref().map(Builder::constant_index),
                            w: w.each_ref().map(Builder::constant_index),
                            length: Builder::constant_index(&l),
                        },
                        _ => Inverse::None {
                            inputs: inputs.clone(),
                        },
                    };
                    let e = if matches!(kind, PairKind::H | PairKind::C) {
                        part(b, 0, "e")
                    } else {
                        o.clone()
                    };
                    if let (PairKind::H, Some(lead)) = (kind, lead) {
                        let lead = b.scalar_constant(
                            Scalar::Lead(driver.id),
                            format!("{chain}.lead"),
                            *lead,
                            format!("lead_{chain}"),
                        );
                        let rise = turn::helical_rise(lead, th);
                        t = expr::vadd(&t, &expr::vscale(&rise, &e));
                    }
                    if kind == PairKind::C {
                        t = expr::vadd(&t, &expr::vscale(&Expr::Input(inputs[1]), &e));
                    }
                    (t, inv)
                }
            };
            let eq = Expr::minus(expr::squared_distance(&g, &tip_expr), l.square());
            ChainModel {
                equations: vec![eq],
                inverse,
            }
        }
        Shape::Swing {
            axis: [ax_a, ax_b],
            slider,
            input,
            ..
        } => {
            let a_slots = PointRef::Slots(b.pivot_slots(*ax_a));
            let b_slots = PointRef::Slots(b.pivot_slots(*ax_b));
            let a = b.pivot_constants(*ax_a);
            let e: Vec3 = [0, 1, 2].map(|k3| {
                let name = format!("e{}_{chain}", ["x", "y", "z"][k3]);
                b.constant(
                    name,
                    Recipe::Axis {
                        a: a_slots,
                        b: b_slots,
                        point: a_slots,
                        index: k3,
                    },
                )
            });
            let (input, offset, length) = leg_length(b, slider, *input, &chain);
            let plane = expr::dot(&e, &expr::vsub(&g, &a));
            let dist = Expr::minus(expr::squared_distance(&g, &a), length.square());
            ChainModel {
                equations: vec![plane, dist],
                inverse: Inverse::Distance {
                    input,
                    point: p,
                    anchor: a.each_ref().map(Builder::constant_index),
                    offset: offset.as_ref().map(Builder::constant_index),
                },
            }
        }
    }
}
