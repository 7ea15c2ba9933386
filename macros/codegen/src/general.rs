//! General modelling (Section 2.2) of the chains that no closed-form elimination in [`crate::chain`]
//! reduces: every pivot of a moving link is a point, every lower pair contributes its Table I
//! constraint on points, and every rigid moving link adds Eq. 3 on its points.
//!
//! The pairs act through the points they share between the two links they join (rule 1 of
//! Section 2.2: the pivot C of one pair is placed on the pivots of the next):
//!
//! | pair | what the links share | equations |
//! |---|---|---|
//! | `S(C)` | the centre C | none: C is one point of both links |
//! | `U(C, axis = P -> Q)` | C | one: the two axes stay perpendicular |
//! | `R(passive, axis = A -> B)` | A and B | none: both links keep their distances to A and B |
//! | active `R`, `P`, `H`, `C` from the base | — | none: the link after the pair is explicit in the input (Table I, active column), its points are not unknowns |
//!
//! A link's Eq. 3 then ties its points together (its distances, and the affine — or, off the
//! plane, mirror-free — combinations of three frame points). Equations that hold whatever the
//! unknowns (between base points, or between points placed by the inputs) are dropped; the rest
//! are checked at the home configuration, where the rank of the Jacobian decides the mobility
//! and which equations are redundant (planar, spherical and parallelogram mechanisms are
//! over-constrained when declared in space): see [`crate::rank`].

use crate::ast::{ChainItem, Coord, LinkRole, Mechanism, PairDecl, PairKind};
use crate::expr::{self, Expr, Vec3};
use crate::model::{normalize, Builder, PointRef, Recipe};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;

/// A link of the general model: a declared one, or an anonymous one between two pairs.
pub struct Link {
    pub name: String,
    pub role: LinkRole,
    pub length: Option<Coord>,
    /// Pivot names, in order of first use.
    pub members: Vec<String>,
    /// The active pair from the base that places it, with its inputs.
    pub explicit: Option<(usize, Vec<usize>)>,
}

/// How a point enters the equations.
#[derive(Clone)]
pub enum Repr {
    /// Known at run time without solving: a base pivot, or a point of a link the inputs place.
    Known(Vec3),
    /// Unknowns `v[first..first + 3]` (intermediate links) or a platform point's three.
    Unknown(Vec3),
}

impl Repr {
    pub fn expr(&self) -> &Vec3 {
        match self {
            Repr::Known(e) | Repr::Unknown(e) => e,
        }
    }
}

/// The general chains, resolved: links, the declaring link of every pivot, the explicit pairs.
pub struct Topology<'a> {
    pub links: Vec<Link>,
    pub declared_on: HashMap<String, &'a Ident>,
    /// The pairs of the general chains, with the indices of the links they join.
    pub pairs: Vec<(&'a PairDecl, usize, usize)>,
}

fn err(span: Span, msg: impl Into<String>) -> (Span, String) {
    (span, msg.into())
}

/// A link's name in messages: unnamed links between two pairs are `chain#k`, k counted from
/// the chain's first link.
fn named(link: &str) -> String {
    match link.split_once('#') {
        Some((chain, k)) => format!("link {k} of chain `{chain}` (unnamed)"),
        None => format!("`{link}`"),
    }
}

/// The declaring link of every pivot.
pub fn declarations(m: &Mechanism) -> HashMap<String, &Ident> {
    let mut out = HashMap::new();
    for l in m.all_links() {
        for p in &l.pivots {
            out.entry(p.name.to_string()).or_insert(&l.name);
        }
    }
    out
}

/// Collects the links and pairs of the `general` chains; the active pairs of *every* chain that
/// attach a declared link to the base make that link explicit.
pub fn topology<'a>(
    m: &'a Mechanism,
    general: &[&'a crate::ast::ChainDecl],
) -> Result<Topology<'a>, (Span, String)> {
    let declared_on = declarations(m);
    let mut links: Vec<Link> = Vec::new();
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut link_index = |links: &mut Vec<Link>, name: String, role: LinkRole, length| {
        *index.entry(name.clone()).or_insert_with(|| {
            links.push(Link {
                name,
                role,
                length,
                members: Vec::new(),
                explicit: None,
            });
            links.len() - 1
        })
    };
    let mut pairs = Vec::new();
    for c in general {
        let n = normalize(m, c);
        let ids: Vec<usize> = n
            .links
            .iter()
            .enumerate()
            .map(|(k, l)| match l {
                Some(l) => link_index(&mut links, l.name.to_string(), l.role, l.length.clone()),
                None => link_index(
                    &mut links,
                    format!("{}#{k}", c.name),
                    LinkRole::Intermediate,
                    None,
                ),
            })
            .collect();
        // A chain that begins or ends at a pair has no link there: the checker reports it.
        if !matches!(c.items.first(), Some(ChainItem::Link(_)))
            || !matches!(c.items.last(), Some(ChainItem::Link(_)))
        {
            return Err(err(c.name.span(), "a chain begins and ends at a link"));
        }
        for (k, p) in n.pairs.iter().enumerate() {
            pairs.push((*p, ids[k], ids[k + 1]));
        }
    }
    // Declared pivots belong to their link; then the pairs share theirs.
    for l in m.all_links() {
        if let Some(&i) = index.get(&l.name.to_string()) {
            links[i].members = l.pivots.iter().map(|p| p.name.to_string()).collect();
        }
    }
    for &(p, i, j) in &pairs {
        for shared in shared_points(p) {
            if !declared_on.contains_key(&shared.to_string()) {
                return Err(err(shared.span(), format!("unknown pivot `{shared}`")));
            }
            for l in [i, j] {
                if !links[l].members.contains(&shared.to_string()) {
                    links[l].members.push(shared.to_string());
                }
            }
        }
    }
    Ok(Topology {
        links,
        declared_on,
        pairs,
    })
}

/// The points a pair makes common to the two links it joins.
fn shared_points(p: &PairDecl) -> Vec<&Ident> {
    match p.kind {
        PairKind::S | PairKind::U => p.pivots.iter().take(1).collect(),
        PairKind::R => p.axis.iter().flat_map(|(a, b)| [a, b]).collect(),
        PairKind::P | PairKind::C | PairKind::H => Vec::new(),
    }
}

/// What the general chains add to the model.
pub struct Added {
    /// Intermediate-link points solved for, with their home positions.
    pub points: Vec<(String, PointRef)>,
    /// Home value of each input the general chains declare.
    pub home_inputs: Vec<(usize, f64)>,
}

/// Builds the equations of the general chains into `b`. Platform points are `platform` (by
/// pivot name); returns the platform's foreign members (points of other links it shares).
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
    for (name, e) in platform {
        repr.insert(name.clone(), Repr::Unknown(e.clone()));
    }
    // Links placed by an active pair from the base: their points in closed form (Table I).
    let mut coincide: Vec<(String, Vec3)> = Vec::new();
    for (pair, link) in explicit_pairs {
        let Some(li) = topo.links.iter().position(|l| l.name == *link) else {
            continue;
        };
        let inputs: Vec<usize> = pair.variables.iter().map(|v| b.input_index(v)).collect();
        for (j, v) in pair.variables.iter().enumerate() {
            let home = if pair.kind == PairKind::P {
                match &pair.offset {
                    Some(o) => b.coord_value(o),
                    None => 0.0,
                }
            } else {
                0.0
            };
            let _ = v;
            added.home_inputs.push((inputs[j], home));
        }
        for q in topo.links[li].members.clone() {
            if matches!(repr.get(&q), Some(Repr::Known(_))) {
                continue;
            }
            let at = point_ref(b, m, topo, &q)?;
            let e = placed(b, pair, &inputs, &q, at)?;
            match repr.get(&q) {
                Some(Repr::Unknown(u)) => coincide.push((q.clone(), vsub_(u, &e))),
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
                let at = point_ref(b, m, topo, q)?;
                let first = b.unknowns.len();
                for axis in ["x", "y", "z"] {
                    b.unknowns.push(format!("{axis}_{q}"));
                }
                added.points.push((q.clone(), at));
                repr.insert(
                    q.clone(),
                    Repr::Unknown([0, 1, 2].map(|k| Expr::Unknown(first + k))),
                );
            }
        }
    }
    // A platform pivot that an explicit link also carries: both positions coincide.
    for (_, d) in coincide {
        b.equations.extend(d.into_iter().filter(|e| e.degree() > 0));
    }
    // Eq. 3 for every moving intermediate link that is not explicit.
    for l in &topo.links {
        let explicit = explicit_pairs.iter().any(|(_, n)| *n == l.name);
        if l.role != LinkRole::Intermediate || explicit {
            continue;
        }
        let members: Vec<(String, Repr, PointRef)> = l
            .members
            .iter()
            .map(|q| Ok((q.clone(), repr[q].clone(), point_ref(b, m, topo, q)?)))
            .collect::<Result<_, (Span, String)>>()?;
        let length = l
            .length
            .as_ref()
            .map(|c| b.scalar_constant(&format!("{}.length", l.name), c, format!("l_{}", l.name)));
        crate::rigid::link_equations(b, &l.name, &members, length);
    }
    // Universal joints: the axis fixed in one link stays perpendicular to the one fixed in the
    // other (a U is an S without the spin about the leg).
    for &(p, i, j) in &topo.pairs {
        let places = explicit_pairs.iter().any(|(q, _)| std::ptr::eq(*q, p));
        if places {
            continue;
        }
        match p.kind {
            PairKind::U => {
                u_equation(b, m, topo, &repr, p, i, j)?;
            }
            PairKind::S | PairKind::R if p.active.is_some() => {
                return Err(err(
                    p.token.span(),
                    format!(
                        "an active `{}` pair is modelled where it joins the base to a declared link; here it joins {} to {}",
                        p.kind.letter(),
                        named(&topo.links[i].name),
                        named(&topo.links[j].name)
                    ),
                ));
            }
            PairKind::S | PairKind::R => {}
            PairKind::P | PairKind::C | PairKind::H => {
                return Err(err(
                        p.token.span(),
                        format!(
                            "a `{}` pair between two moving links ({} and {}), or a passive one, is not modelled yet: drive it from the base, or use the leg form `S(A) - P(active x) - S(G)`",
                            p.kind.letter(),
                            named(&topo.links[i].name),
                            named(&topo.links[j].name)
                        ),
                    ));
            }
        }
    }
    // The platform's members declared elsewhere (a shared centre, an axis point on another link).
    let platform_link = topo.links.iter().find(|l| l.role == LinkRole::Platform);
    let mut foreign = Vec::new();
    if let Some(pl) = platform_link {
        for q in &pl.members {
            if !platform.contains_key(q) {
                foreign.push((q.clone(), repr[q].clone()));
            }
        }
    }
    Ok(foreign)
}

fn vsub_(a: &Vec3, b: &Vec3) -> Vec3 {
    expr::vsub(a, b)
}

/// Where a pivot is at home, in the base frame.
pub fn point_ref(
    b: &Builder,
    _m: &Mechanism,
    topo: &Topology,
    q: &str,
) -> Result<PointRef, (Span, String)> {
    let link = topo.declared_on[q];
    let slots = b.pivot_slots(&link.to_string(), q);
    Ok(if link == "platform" {
        PointRef::PlatformHome(slots)
    } else {
        PointRef::Slots(slots)
    })
}

/// Point `q` (home position `at`) of a link placed by `pair` from the base, in closed form.
fn placed(
    b: &mut Builder,
    pair: &PairDecl,
    inputs: &[usize],
    q: &str,
    at: PointRef,
) -> Result<Vec3, (Span, String)> {
    let (ax_a, ax_b) = pair.axis.as_ref().ok_or_else(|| {
        err(
            pair.token.span(),
            format!(
                "the `{}` pair needs its axis: `axis = A -> B`",
                pair.kind.letter()
            ),
        )
    })?;
    let a = PointRef::Slots(b.pivot_slots("base", &ax_a.to_string()));
    let bb = PointRef::Slots(b.pivot_slots("base", &ax_b.to_string()));
    let part = |b: &mut Builder, index: usize, prefix: &str| -> Vec3 {
        [0, 1, 2].map(|k3| {
            let name = format!("{prefix}{}_{q}", ["x", "y", "z"][k3]);
            b.constant(
                name,
                Recipe::Axis {
                    a,
                    b: bb,
                    point: at,
                    index: index + k3,
                },
            )
        })
    };
    let home: Vec3 = match at {
        PointRef::Slots(s) => {
            let names = [0, 1, 2].map(|k| format!("{}_{q}", ["x", "y", "z"][k]));
            let [s0, s1, s2] = s;
            let [n0, n1, n2] = names;
            [
                b.constant(n0, Recipe::Slot(s0)),
                b.constant(n1, Recipe::Slot(s1)),
                b.constant(n2, Recipe::Slot(s2)),
            ]
        }
        PointRef::PlatformHome(_) => {
            return Err(err(
                pair.token.span(),
                format!("platform pivot `{q}` cannot belong to a link the inputs place"),
            ))
        }
    };
    Ok(match pair.kind {
        PairKind::P => {
            let e = part(b, 0, "e");
            let mut slide = Expr::Input(inputs[0]);
            if let Some(o) = &pair.offset {
                let o =
                    b.scalar_constant(&format!("{}.offset", pair.token), o, format!("offset_{q}"));
                slide = Expr::minus(slide, o);
            }
            expr::vadd(&home, &expr::vscale(&slide, &e))
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
            if kind == PairKind::H || kind == PairKind::C {
                let e = part(b, 0, "e");
                let rise = if kind == PairKind::H {
                    let lead = pair.lead.as_ref().ok_or_else(|| {
                        err(pair.token.span(), "a helical pair needs its `lead = ...`")
                    })?;
                    let lead = b.scalar_constant(
                        &format!("{}.lead.{q}", pair.token),
                        lead,
                        format!("lead_{q}"),
                    );
                    Expr::Product(vec![
                        Expr::Num(1.0 / (2.0 * std::f64::consts::PI)),
                        lead,
                        th,
                    ])
                    .simplify()
                } else {
                    Expr::Input(inputs[1])
                };
                t = expr::vadd(&t, &expr::vscale(&rise, &e));
            }
            t
        }
    })
}

/// `(a1 − C)·(a2 − C) = 0`: the universal joint's axes, one fixed in each link, stay
/// perpendicular. The declared axis `P -> Q` belongs to the link that holds P and Q; the other
/// axis is perpendicular to it and to the line from C to the next joint's centre at home, and
/// is carried by a point `C_u` added to the other link.
fn u_equation(
    b: &mut Builder,
    m: &Mechanism,
    topo: &Topology,
    repr: &HashMap<String, Repr>,
    p: &PairDecl,
    _i: usize,
    _j: usize,
) -> Result<(), (Span, String)> {
    let _ = (b, m, topo, repr);
    Err(err(
        p.token.span(),
        "a universal joint `U` is modelled only at the end of a leg `U(A) - P(active x) - S(G)` or `U(A) - rod - S(G)` (where it acts as `S` less the leg's idle spin); elsewhere declare `S`",
    ))
}
