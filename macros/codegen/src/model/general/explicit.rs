//! Links placed by an active pair from the base (Table I, active column): every point of the
//! link after the pair is explicit in the pair's inputs — `C − B = R(C0 − B) + x e`, written
//! `o + u cos θ + w sin θ (+ x e)` with o, u, w derived from the geometry — so it is not solved
//! for.

use super::{err, PointId, Topology};
use crate::expr::{self, Expr, Vec3};
use crate::front::resolved::{LinkRole, Pair, PairKind};
use crate::model::builder::Scalar;
use crate::model::{turn, Builder, PointRef, Recipe};
use syn::Error;

/// Whether `pair`, from a link of role `before` to a declared link of role `after`, places that
/// link explicitly in its inputs: an active R, P, H or C with an axis, from the base to an
/// intermediate link. The one rule for which links are explicit (`build`'s `explicit_pairs`)
/// and for the links a lever may be added to (`topology`'s `levers`).
pub fn places(pair: &Pair, before: LinkRole, after: LinkRole) -> bool {
    before == LinkRole::Base
        && after == LinkRole::Intermediate
        && pair.active
        && pair.axis.is_some()
        && matches!(
            pair.kind,
            PairKind::R | PairKind::P | PairKind::H | PairKind::C
        )
}

/// Point `q` of a link placed by `pair` from the base, in closed form.
pub fn placed(
    b: &mut Builder,
    topo: &Topology,
    pair: &Pair,
    inputs: &[usize],
    q: PointId,
) -> Result<Vec3, Error> {
    let Some([ax_a, ax_b]) = pair.axis else {
        return Err(err(
            pair.token.span(),
            format!(
                "the `{}` pair needs its axis: `axis = A -> B`",
                pair.kind.letter()
            ),
        ));
    };
    let (a, bb) = (
        topo.home(PointId::of(ax_a.id)),
        topo.home(PointId::of(ax_b.id)),
    );
    let at = topo.home(q);
    let q = topo.name(q);
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
        // A point the model adds, or a platform pivot the link also carries (an axis the
        // platform shares with it: the model makes the two coincide): its home position in
        // the base frame, derived from the geometry.
        PointRef::Auto(_) | PointRef::PlatformHome(_) => [0, 1, 2].map(|index| {
            b.constant(
                format!("{}_{q}", ["x", "y", "z"][index]),
                Recipe::Coordinate { point: at, index },
            )
        }),
    };
    Ok(match pair.kind {
        PairKind::P => {
            let e = part(b, 0, "e");
            let mut slide = Expr::Input(inputs[0]);
            if let Some(o) = pair.offset {
                let o = b.scalar_constant(
                    Scalar::Offset(pair.id),
                    // One slot per pair, named for its chain (as the closed-form legs' are).
                    format!("{}.offset", b.decl.chain(pair.id.chain).name),
                    o,
                    format!("offset_{q}"),
                );
                slide = Expr::minus(slide, o);
            }
            expr::vadd(&home, &expr::vscale(&slide, &e))
        }
        kind => {
            let o = part(b, 3, "o");
            let u = part(b, 6, "u");
            let w = part(b, 9, "w");
            let th = Expr::Input(inputs[0]);
            let mut t = turn::turned(&o, &u, &w, &th);
            if kind == PairKind::H || kind == PairKind::C {
                let e = part(b, 0, "e");
                let rise = if kind == PairKind::H {
                    let lead = pair.lead.ok_or_else(|| {
                        err(pair.token.span(), "a helical pair needs its `lead = ...`")
                    })?;
                    let lead = b.scalar_constant(
                        Scalar::Lead(pair.id),
                        format!("{}.lead", b.decl.chain(pair.id.chain).name),
                        lead,
                        format!("lead_{q}"),
                    );
                    turn::helical_rise(lead, th)
                } else {
                    Expr::Input(inputs[1])
                };
                t = expr::vadd(&t, &expr::vscale(&rise, &e));
            }
            t
        }
    })
}
