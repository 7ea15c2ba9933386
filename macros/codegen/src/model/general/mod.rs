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
//! The links, the points (by [`PointId`], never by name) and the pairs of the general chains
//! are gathered first ([`mod@topology`], [`points`]). A link's Eq. 3 then ties its points
//! together. Equations that hold whatever the unknowns (between base points, or between points
//! placed by the inputs) are dropped; the rest are checked at the home configuration, where the
//! rank of the Jacobian decides the mobility and which equations are implied by the others (see
//! [`crate::simplify::rank`]).

pub mod explicit;
pub mod points;
pub mod prismatic;
pub mod relative;
pub mod topology;
pub mod universal;

use crate::expr::{Expr, Vec3};
use crate::front::errors::Errors;
use crate::front::ids::{LinkId, PairId, PivotId};
use crate::front::resolved::{LinkRole, Pair, PairKind};
use crate::model::builder::Scalar;
use crate::model::{Builder, PointRef};
pub use points::{PointId, Points};
use proc_macro2::Span;
use syn::Error;
pub use topology::{topology, Joint, Link, Topology};

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

/// How every point enters the equations, by [`PointId`]; filled in a fixed order (base, platform,
/// points the inputs place, then unknowns), so that every member of a link has its entry by
/// the time the equations read it.
pub struct Reprs(Vec<Option<Repr>>);

impl Reprs {
    pub fn get(&self, q: PointId) -> Option<&Repr> {
        self.0[q.index()].as_ref()
    }

    fn set(&mut self, q: PointId, r: Repr) {
        self.0[q.index()] = Some(r);
    }

    /// The expression of a point the model has placed; zeros for one it has not, which
    /// [`model`] reports as an error before any equation is kept.
    pub fn expr(&self, q: PointId) -> Vec3 {
        match self.get(q) {
            Some(r) => r.expr().clone(),
            None => [Expr::Num(0.0), Expr::Num(0.0), Expr::Num(0.0)],
        }
    }
}

pub fn err(span: Span, msg: impl std::fmt::Display) -> Error {
    Error::new(span, msg)
}

/// A link's name in messages: an unnamed link between two pairs by its place in its chain.
pub fn named(link: &Link) -> String {
    match (link.declared, &link.unnamed) {
        (None, Some((chain, k))) => format!("link {k} of chain `{chain}` (unnamed)"),
        _ => format!("`{}`", link.name),
    }
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
    /// The links a prismatic (or passive cylindrical) pair between moving links carries.
    pub sliders: Vec<usize>,
    /// The equations by which such a pair places a slider that an earlier one already places
    /// (a platform on three guides): see `build`'s order for the rank test.
    pub slider_again: Vec<usize>,
    /// Whether an active pair places the platform relative to another link (see [`relative`]):
    /// its Eq. 3 is then implied.
    pub platform_placed: bool,
    /// Candidate leg spins, per chain ([`universal::spins`]).
    pub spins: Vec<Vec<(usize, Expr)>>,
}

/// Builds the equations of the general chains into `b`. `platform` gives the platform's points
/// that are unknowns (by pivot); returns the platform's foreign members (points declared on
/// other links), or `None` with the reasons in `errors`.
pub fn model(
    b: &mut Builder,
    topo: &Topology,
    explicit_pairs: &[(&Pair, usize)],
    platform: &[(PivotId, Vec3)],
    added: &mut Added,
    errors: &mut Errors,
) -> Option<Vec<(PointId, Repr)>> {
    let d = b.decl;
    let mut repr = Reprs(vec![None; topo.points.len()]);
    // Base pivots are constants.
    for &p in d.base_pivots() {
        let e = b.pivot_constants(p);
        repr.set(PointId::of(p), Repr::Known(e));
    }
    // Points the model adds to the base (the axis tip of a slide on a base rail) are constants
    // too, derived from the geometry.
    for l in topo.links.iter().filter(|l| l.role == LinkRole::Base) {
        for &q in &l.members {
            if repr.get(q).is_none() {
                let at = topo.home(q);
                // A platform pivot's own name is its unknowns'.
                let on_platform = platform.iter().any(|&(p, _)| PointId::of(p) == q);
                let suffix = if on_platform { "_base" } else { "" };
                let e = [0, 1, 2].map(|index| {
                    b.constant(
                        format!("{}_{}{suffix}", ["x", "y", "z"][index], topo.name(q)),
                        crate::model::Recipe::Coordinate { point: at, index },
                    )
                });
                repr.set(q, Repr::Known(e));
            }
        }
    }
    // A platform pivot that the base holds too (the centre of an `S` or `U`, a point of an `R`'s
    // axis, joining the base to the platform) is solved for like every platform pivot, and
    // stays where the base holds it.
    let mut coincide: Vec<Vec3> = Vec::new();
    for (p, e) in platform {
        let q = PointId::of(*p);
        if let Some(Repr::Known(fixed)) = repr.get(q) {
            coincide.push(crate::expr::vsub(e, fixed));
        }
        repr.set(q, Repr::Unknown(e.clone()));
    }
    let mut ok = true;
    // Links placed by an active pair from the base: their points in closed form (Table I).
    for &(pair, li) in explicit_pairs {
        let inputs: Vec<usize> = pair.inputs.iter().map(|i| i.index()).collect();
        for &input in &inputs {
            // Zero at the declared configuration; a slide with an offset reads the offset there.
            let home = match (pair.kind, pair.offset) {
                (PairKind::P, Some(o)) => d.value(o),
                _ => 0.0,
            };
            added.home_inputs.push((input, home));
        }
        for &q in &topo.links[li].members {
            if matches!(repr.get(q), Some(Repr::Known(_))) {
                continue;
            }
            let e = match explicit::placed(b, topo, pair, &inputs, q) {
                Ok(e) => e,
                Err(e) => {
                    errors.add(e);
                    ok = false;
                    break;
                }
            };
            match repr.get(q) {
                Some(Repr::Unknown(u)) => coincide.push(crate::expr::vsub(u, &e)),
                _ => repr.set(q, Repr::Known(e)),
            }
        }
    }
    // The remaining points of moving links are unknowns.
    for l in &topo.links {
        if l.role == LinkRole::Base {
            continue;
        }
        for &q in &l.members {
            if repr.get(q).is_none() {
                let first = b.unknowns.len();
                for axis in ["x", "y", "z"] {
                    b.unknowns.push(format!("{axis}_{}", topo.name(q)));
                }
                added
                    .points
                    .push((topo.name(q).to_string(), topo.home(q), first));
                repr.set(
                    q,
                    Repr::Unknown([0, 1, 2].map(|k| Expr::Unknown(first + k))),
                );
            }
        }
    }
    // Every point a link holds now has its place (base, platform, explicit or unknown): the
    // equations below read them. Checked rather than assumed, so that a gap is an error and
    // never a point at the origin.
    for l in &topo.links {
        for &q in &l.members {
            if repr.get(q).is_none() {
                errors.push(
                    d.name.span(),
                    format!(
                        "point `{}` of {} is placed by nothing (a bug in the generator; please report it)",
                        topo.name(q),
                        named(l)
                    ),
                );
                ok = false;
            }
        }
    }
    // A platform pivot that the base or an explicit link also carries: both positions coincide.
    for d in coincide {
        b.equations.extend(d.into_iter().filter(|e| e.degree() > 0));
    }
    // The links an active pair places relative to the link before it: every point of theirs is
    // placed, so their Eq. 3 is implied.
    let is_explicit = |p: PairId| explicit_pairs.iter().any(|(q, _)| q.id == p);
    let placed: Vec<usize> = (0..topo.joints.len())
        .filter(|&k| relative::applies(topo, k, is_explicit(topo.joints[k].pair.id)))
        .map(|k| topo.joints[k].after)
        .collect();
    added.platform_placed = placed
        .iter()
        .any(|&l| topo.links[l].role == LinkRole::Platform);
    // Eq. 3 for every moving intermediate link that is not explicit.
    let links_from = b.equations.len();
    for (li, l) in topo.links.iter().enumerate() {
        let explicit = explicit_pairs.iter().any(|&(_, e)| e == li);
        if l.role != LinkRole::Intermediate || explicit || placed.contains(&li) {
            continue;
        }
        let members: Vec<(String, Vec3, PointRef)> = l
            .members
            .iter()
            .map(|&q| (topo.name(q).to_string(), repr.expr(q), topo.home(q)))
            .collect();
        let length = match (l.declared, l.length) {
            (Some(id), Some(len)) => Some(b.scalar_constant(
                Scalar::Length(id),
                format!("{}.length", l.name),
                len,
                format!("l_{}", l.name),
            )),
            _ => None,
        };
        crate::model::rigid::link_equations(b, &l.name, &members, length);
    }
    added.link_equations = links_from..b.equations.len();
    // Three points of every named moving link locate it.
    for l in &topo.links {
        if l.role != LinkRole::Intermediate || l.declared.is_none() {
            continue;
        }
        let homes: Vec<[f64; 3]> = l.members.iter().map(|&q| b.home(topo.home(q))).collect();
        let frame = crate::model::rigid::frame_of(&homes).map(|f| {
            f.map(|i| {
                let q = l.members[i];
                let home = match topo.home(q) {
                    PointRef::Auto(_) => crate::model::HomeOf::Constants([0, 1, 2].map(|index| {
                        let c = b.constant(
                            format!("h{}_{}", ["x", "y", "z"][index], topo.name(q)),
                            crate::model::Recipe::Coordinate {
                                point: topo.home(q),
                                index,
                            },
                        );
                        crate::model::Builder::constant_index(&c)
                    })),
                    at => crate::model::HomeOf::Point(at),
                };
                (repr.expr(q), home)
            })
        });
        added.links.push(crate::model::LinkFrame {
            name: l.name.clone(),
            placed: frame.map_or(
                crate::model::Placed::Unmodelled,
                crate::model::Placed::Frame,
            ),
        });
    }
    // The pairs' own equations.
    for (k, joint) in topo.joints.iter().enumerate() {
        let p = joint.pair;
        if is_explicit(p.id) {
            continue;
        }
        let done = if relative::applies(topo, k, false) {
            relative::equations(b, topo, &repr, k, &mut added.home_inputs).map(|_| ())
        } else {
            match p.kind {
                PairKind::U => {
                    universal::equation(b, topo, &repr, k);
                    Ok(())
                }
                PairKind::P | PairKind::C | PairKind::H => {
                    prismatic::equations(b, topo, &repr, k, added)
                }
                PairKind::S | PairKind::R => Ok(()),
            }
        };
        if let Err(e) = done {
            errors.add(e);
            ok = false;
        }
    }
    added.spins = universal::spins(topo, &repr);
    // The platform's members declared elsewhere (a shared centre, an axis point on another link).
    let mut foreign = Vec::new();
    if let Some(pl) = topo.link(LinkId::PLATFORM) {
        for &q in &topo.links[pl].members {
            let own = topo
                .points
                .pivot(q)
                .is_some_and(|p| platform.iter().any(|(o, _)| *o == p));
            if let (false, Some(r)) = (own, repr.get(q)) {
                foreign.push((q, r.clone()));
            }
        }
    }
    ok.then_some(foreign)
}
