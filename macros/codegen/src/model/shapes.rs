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
use crate::front::ast::{ChainDecl, ChainItem, Coord, LinkRole, Mechanism, PairDecl, PairKind};
use crate::model::{is_point_joint, normalize, role, Builder, Inverse, PointRef, Recipe};
use proc_macro2::Span;
use syn::Ident;

pub enum Shape<'a> {
    Leg {
        anchor: &'a Ident,
        slider: &'a PairDecl,
        platform: &'a Ident,
    },
    Rod {
        anchor: &'a Ident,
        rod: &'a Ident,
        length: &'a Coord,
        platform: &'a Ident,
    },
    Driven {
        driver: &'a PairDecl,
        axis: (&'a Ident, &'a Ident),
        /// The lead of a helical driver.
        lead: Option<&'a Coord>,
        link: &'a Ident,
        tip: &'a Ident,
        rod: &'a Ident,
        length: &'a Coord,
        platform: &'a Ident,
    },
    Swing {
        hinge: &'a PairDecl,
        axis: (&'a Ident, &'a Ident),
        slider: &'a PairDecl,
        platform: &'a Ident,
    },
}

impl Shape<'_> {
    /// Whether the links the shape eliminates belong to its chain alone.
    pub fn links_private(&self, private: &dyn Fn(&Ident) -> bool) -> bool {
        match self {
            Shape::Rod { rod, .. } | Shape::Driven { rod, .. } => private(rod),
            Shape::Leg { .. } | Shape::Swing { .. } => true,
        }
    }

    pub fn platform_pivot(&self) -> &Ident {
        match self {
            Shape::Leg { platform, .. }
            | Shape::Rod { platform, .. }
            | Shape::Driven { platform, .. }
            | Shape::Swing { platform, .. } => platform,
        }
    }
}

pub struct ChainModel {
    pub equations: Vec<Expr>,
    pub inverse: Inverse,
}

fn center<'a>(p: &'a PairDecl, chain: &ChainDecl) -> Result<&'a Ident, (Span, String)> {
    match p.pivots.as_slice() {
        [c] => Ok(c),
        _ => Err((
            p.token.span(),
            format!(
                "pair `{}` in chain `{}` names its centre: one pivot, e.g. `{}(G1)`",
                p.kind.letter(),
                chain.name,
                p.kind.letter()
            ),
        )),
    }
}

fn on_link(m: &Mechanism, link: &str, pivot: &Ident) -> bool {
    m.all_links()
        .any(|l| l.name == link && l.pivots.iter().any(|p| p.name == *pivot))
}

/// The axis `A -> B` of a pair must not be given by points that coincide at the declared geometry.
fn check_axis(m: &Mechanism, p: &PairDecl) -> Result<(), (Span, String)> {
    let Some((a, b)) = &p.axis else { return Ok(()) };
    let Some(base) = m.base.as_ref() else {
        return Ok(());
    };
    let point = |n: &Ident| {
        base.pivots
            .iter()
            .find(|q| q.name == *n)
            .map(|q| q.coords.clone())
    };
    let value = |c: &Coord| match c {
        Coord::Literal(n) => Some(n.value),
        Coord::Param(name) => m
            .params
            .iter()
            .find(|q| q.name == *name)
            .map(|q| q.default.value),
    };
    if let (Some(pa), Some(pb)) = (point(a), point(b)) {
        let d: Option<Vec<f64>> = (0..3)
            .map(|k| Some(value(&pa[k])? - value(&pb[k])?))
            .collect();
        let scale = (0..3)
            .filter_map(|k| value(&pa[k]))
            .fold(1.0f64, |s, x| s.max(x.abs()));
        if d.is_some_and(|d| d.iter().map(|x| x * x).sum::<f64>().sqrt() <= 1e-9 * scale) {
            return Err((
                b.span(),
                format!(
                    "the axis of pair `{}` is given by coincident points `{a}` and `{b}`",
                    p.kind.letter()
                ),
            ));
        }
    }
    Ok(())
}

/// Why a chain is not reduced in closed form: it is not one of the shapes (`None`: the general
/// model takes it), or it is one with a mistake (`Some`: a spanned error).
type Fail = Option<(Span, String)>;

/// The closed-form shape of a chain from the base to the platform, if it has one.
pub fn classify<'a>(
    m: &'a Mechanism,
    c: &'a ChainDecl,
) -> Result<Option<Shape<'a>>, (Span, String)> {
    let ends = (c.items.first(), c.items.last());
    if !matches!(ends, (Some(ChainItem::Link(a)), Some(ChainItem::Link(b))) if a == "base" && b == "platform")
    {
        return Ok(None);
    }
    match shape(m, c) {
        Ok(s) => Ok(Some(s)),
        Err(None) => Ok(None),
        Err(Some(e)) => Err(e),
    }
}

fn shape<'a>(m: &'a Mechanism, c: &'a ChainDecl) -> Result<Shape<'a>, Fail> {
    let n0 = normalize(m, c);
    for p in &n0.pairs {
        check_axis(m, p).map_err(Some)?;
    }
    let n = normalize(m, c);
    let unsupported = || None;
    // A U at both ends of a leg constrains the leg's spin, and with it the platform: only a leg
    // with at least one S reduces to a distance.
    let ends_ok = |a: &PairDecl, b: &PairDecl| !(a.kind == PairKind::U && b.kind == PairKind::U);
    let base_axis = |p: &PairDecl| {
        p.axis
            .as_ref()
            .is_none_or(|(a, b)| on_link(m, "base", a) && on_link(m, "base", b))
    };
    let platform_center = |p: &'a PairDecl| -> Result<&'a Ident, Fail> {
        let g = center(p, c).map_err(Some)?;
        if !on_link(m, "platform", g) {
            return Err(None);
        }
        Ok(g)
    };
    let base_center = |p: &'a PairDecl| -> Result<&'a Ident, Fail> {
        let a = center(p, c).map_err(Some)?;
        if !on_link(m, "base", a) {
            return Err(None);
        }
        Ok(a)
    };
    let pairs = &n.pairs;
    match pairs.as_slice() {
        [s1, slider, s2]
            if is_point_joint(s1)
                && slider.kind == PairKind::P
                && is_point_joint(s2)
                && ends_ok(s1, s2)
                && slider.axis.is_none() =>
        {
            if slider.active.is_none() {
                return Err(Some((slider.token.span(), format!("the `P` pair of leg `{}` is passive: the leg would not constrain the platform; make it `P(active L)`", c.name))));
            }
            single_variable(slider, c).map_err(Some)?;
            Ok(Shape::Leg {
                anchor: base_center(s1)?,
                slider,
                platform: platform_center(s2)?,
            })
        }
        [s1, s2] if is_point_joint(s1) && is_point_joint(s2) && ends_ok(s1, s2) => {
            let rod = n.links[1].filter(|l| l.role == LinkRole::Intermediate);
            match rod.and_then(|l| l.length.as_ref().map(|len| (l, len))) {
                Some((rod, length)) => Ok(Shape::Rod {
                    anchor: base_center(s1)?,
                    rod: &rod.name,
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
            if driver.active.is_none() {
                return Err(unsupported());
            }
            let expected = if driver.kind == PairKind::C { 2 } else { 1 };
            if driver.variables.len() != expected {
                return Err(Some((
                    driver.token.span(),
                    format!(
                        "an active `{}` pair has {expected} joint variable(s), found {}",
                        driver.kind.letter(),
                        driver.variables.len()
                    ),
                )));
            }
            let Some((ax_a, ax_b)) = &driver.axis else {
                return Err(Some((
                    driver.token.span(),
                    format!(
                        "the `{}` pair of chain `{}` needs its axis: `axis = A -> B` on `base`",
                        driver.kind.letter(),
                        c.name
                    ),
                )));
            };
            if driver.kind == PairKind::H && driver.lead.is_none() {
                return Err(Some((
                    driver.token.span(),
                    "a helical pair needs its `lead = ...`".to_string(),
                )));
            }
            let link = match n.links[1] {
                Some(l) if l.role == LinkRole::Intermediate => l,
                _ => return Err(Some((driver.token.span(), format!("chain `{}` needs a declared link after its driving pair, holding the centre of the next joint", c.name)))),
            };
            let tip = center(s1, c).map_err(Some)?;
            if !link.pivots.iter().any(|p| p.name == *tip) {
                return Err(Some((
                    tip.span(),
                    format!("`{tip}` is not a pivot of link `{}`", link.name),
                )));
            }
            let rod = n.links[2].filter(|l| l.role == LinkRole::Intermediate);
            match rod.and_then(|l| l.length.as_ref().map(|len| (l, len))) {
                Some((rod, length)) => Ok(Shape::Driven {
                    driver,
                    axis: (ax_a, ax_b),
                    lead: driver.lead.as_ref(),
                    link: &link.name,
                    tip,
                    rod: &rod.name,
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
            if hinge.active.is_some() || slider.active.is_none() {
                return Err(unsupported());
            }
            let Some((ax_a, ax_b)) = &hinge.axis else {
                return Err(Some((
                    hinge.token.span(),
                    format!(
                        "the `R` pair of chain `{}` needs its axis: `axis = A -> B` on `base`",
                        c.name
                    ),
                )));
            };
            if role(n.links[0]) != Some(LinkRole::Base) {
                return Err(unsupported());
            }
            single_variable(slider, c).map_err(Some)?;
            Ok(Shape::Swing {
                hinge,
                axis: (ax_a, ax_b),
                slider,
                platform: platform_center(s)?,
            })
        }
        _ => Err(unsupported()),
    }
}

fn single_variable(p: &PairDecl, c: &ChainDecl) -> Result<(), (Span, String)> {
    if p.variables.len() == 1 {
        Ok(())
    } else {
        Err((
            p.token.span(),
            format!(
                "an active `P` pair in chain `{}` has one joint variable",
                c.name
            ),
        ))
    }
}

/// An active slider's joint variable, its offset constant, and the leg length `x + offset`.
fn leg_length(b: &mut Builder, slider: &PairDecl, chain: &str) -> (usize, Option<Expr>, Expr) {
    let input = b.input(&slider.variables[0]);
    let offset = slider
        .offset
        .as_ref()
        .map(|o| b.scalar_constant(&format!("{chain}.offset"), o, format!("offset_{chain}")));
    let length = match &offset {
        Some(o) => Expr::plus(Expr::Input(input), o.clone()),
        None => Expr::Input(input),
    };
    (input, offset, length)
}

/// Emits the chain's equations on platform point `p` (of `k` points).
pub fn model(b: &mut Builder, c: &ChainDecl, shape: &Shape, p: usize, k: usize) -> ChainModel {
    let g: Vec3 = [0, 1, 2].map(|a| Expr::Unknown(a * k + p));
    let chain = c.name.to_string();
    match shape {
        Shape::Leg { anchor, slider, .. } => {
            let a = b.pivot_constants("base", &anchor.to_string());
            let (input, offset, length) = leg_length(b, slider, &chain);
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
            rod,
            length,
            ..
        } => {
            let a = b.pivot_constants("base", &anchor.to_string());
            let l = b.scalar_constant(&format!("{rod}.length"), length, format!("l_{rod}"));
            let eq = Expr::minus(expr::squared_distance(&g, &a), l.square());
            ChainModel {
                equations: vec![eq],
                inverse: Inverse::None { inputs: vec![] },
            }
        }
        Shape::Driven {
            driver,
            axis: (ax_a, ax_b),
            lead,
            link,
            tip,
            rod,
            length,
            ..
        } => {
            let a = PointRef::Slots(b.pivot_slots("base", &ax_a.to_string()));
            let bb = PointRef::Slots(b.pivot_slots("base", &ax_b.to_string()));
            let c0 = PointRef::Slots(b.pivot_slots(&link.to_string(), &tip.to_string()));
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
            let l = b.scalar_constant(&format!("{rod}.length"), length, format!("l_{rod}"));
            let inputs: Vec<usize> = driver.variables.iter().map(|v| b.input(v)).collect();
            let (tip_expr, inverse) = match driver.kind {
                PairKind::P => {
                    let e = part(b, 0, "e");
                    let c0e = b.pivot_constants(&link.to_string(), &tip.to_string());
                    let t = expr::vadd(&c0e, &expr::vscale(&Expr::Input(inputs[0]), &e));
                    let inv = Inverse::PrismaticRod {
                        input: inputs[0],
                        point: p,
                        c0: c0e.each_ref().map(Builder::constant_index),
                        e: e.each_ref().map(Builder::constant_index),
                        length: Builder::constant_index(&l),
                    };
                    (t, inv)
                }
                kind => {
                    let o = part(b, 3, "o");
                    let u = part(b, 6, "u");
                    let w = part(b, 9, "w");
                    let th = Expr::Input(inputs[0]);
                    let cos = Expr::Cos(Box::new(th.clone()));
                    let sin = Expr::Sin(Box::new(th.clone()));
                    let mut t = expr::vadd(
                        &o,
                        &expr::vadd(&expr::vscale(&cos, &u), &expr::vscale(&sin, &w)),
                    );
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
                            &format!("{chain}.lead"),
                            lead,
                            format!("lead_{chain}"),
                        );
                        let rise = Expr::Product(vec![
                            Expr::Num(1.0 / (2.0 * std::f64::consts::PI)),
                            lead,
                            th,
                        ])
                        .simplify();
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
            axis: (ax_a, ax_b),
            slider,
            ..
        } => {
            let a_slots = PointRef::Slots(b.pivot_slots("base", &ax_a.to_string()));
            let b_slots = PointRef::Slots(b.pivot_slots("base", &ax_b.to_string()));
            let a = b.pivot_constants("base", &ax_a.to_string());
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
            let (input, offset, length) = leg_length(b, slider, &chain);
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
