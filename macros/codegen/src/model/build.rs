//! From the resolved declaration to the model: the chains the closed-form shapes reduce, the
//! general model for the rest, the platform's rigid-body equations, duplicates removed, and the
//! mobility checked (by counting, or by rank at home).

use crate::expr::{Expr, Vec3};
use crate::front::errors::Errors;
use crate::front::ids::{LinkId, PivotId};
use crate::front::resolved::{Decl, Form, Pair};
use crate::model::general::{self, Added, Topology};
use crate::model::shapes::{self, ChainModel};
use crate::model::PointRef;
use crate::model::{
    frame, rigid, Builder, HomeOf, Inverse, LinkFrame, Model, Placed, PlatformPoint,
};
use syn::Error;

/// Builds the model; `None` with every independent mistake in `errors`.
///
/// A short declared axis gets a lever of the model's own (`general::topology`'s `levers`), and
/// the model with it is kept where no equation is left out as dependent. Where some are (an
/// over-constrained mechanism), the model is built again as declared: the rank test's choice of
/// the square system among the rewritten equations gave false folds on a Bennett linkage, 6
/// roots for a Stephenson III six-bar's 12 and NR on another configuration of an Orthoglide
/// (BENCHMARKS.md, thirty-seventh session). A declaration in error is reported as declared.
pub fn build(d: &Decl, errors: &mut Errors) -> Option<Model> {
    let mut trial = Errors::default();
    match build_with(d, &mut trial, Levers::Short) {
        Some((model, false)) => return Some(model),
        Some((model, true)) if model.dependent.is_empty() => return Some(model),
        _ => {}
    }
    build_with(d, errors, Levers::AsDeclared).map(|(model, _)| model)
}

/// Whether short declared axes get levers of the model's own.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Levers {
    Short,
    AsDeclared,
}

/// The model, and whether any lever was added.
fn build_with(d: &Decl, errors: &mut Errors, levers: Levers) -> Option<(Model, bool)> {
    let mut b = Builder::new(d);
    let axes = axes(d, &b, errors);

    // A named link inside a closed-form shape must belong to that chain alone; a crank an
    // active pair places may carry other chains (it is explicit in the input either way).
    let mut uses = vec![0usize; d.links.len()];
    for c in &d.chains {
        for l in c.links.iter().flatten() {
            uses[l.index()] += 1;
        }
    }
    let private = |l: LinkId| uses[l.index()] <= 1;

    // Which platform pivots the chains reach; which chains reduce in closed form.
    let platform_pivots = d.platform_pivots();
    let mut used: Vec<bool> = vec![false; platform_pivots.len()];
    let mut shapes = Vec::new();
    let mut general = Vec::new();
    for c in d.chain_ids() {
        match shapes::classify(d, c) {
            Ok(Some(shape)) if shape.links_private(&private) => {
                used[shape.platform_pivot().index] = true;
                shapes.push((c, shape));
            }
            Ok(_) => general.push(c),
            Err(e) => errors.add(e),
        }
    }
    let topo = general::topology(&mut b, d, &general, errors, levers == Levers::Short);
    if let Some(pl) = topo
        .as_ref()
        .and_then(|t| t.link(LinkId::PLATFORM).map(|l| &t.links[l]))
    {
        for &q in &pl.members {
            let pivot = topo.as_ref().and_then(|t| t.points.pivot(q));
            if let Some(i) = platform_pivots.iter().position(|&p| Some(p) == pivot) {
                used[i] = true;
            }
        }
    }
    let frame = frame::choose(d).map_err(|e| errors.add(e)).ok();
    let (Some(frame_idx), Some(topo)) = (frame, topo) else {
        return None;
    };
    let levered = topo.levered;
    if !errors.is_empty() {
        return None;
    }
    for f in frame_idx.into_iter().flatten() {
        used[f] = true;
    }

    // Platform points, in declaration order: the i-th used pivot is point `point_of[i]`.
    let mut point_of: Vec<Option<usize>> = vec![None; platform_pivots.len()];
    for (i, &pivot) in platform_pivots.iter().enumerate() {
        if used[i] {
            point_of[i] = Some(b.points.len());
            b.points.push(PlatformPoint {
                name: d.pivot(pivot).name.to_string(),
                local: b.pivot_slots(pivot),
            });
        }
    }
    // A used pivot's point: the number of used pivots before it.
    let point = |i: usize| used[..i].iter().filter(|u| **u).count();
    let k = b.points.len();
    for axis in ["x", "y", "z"] {
        for p in &b.points {
            b.unknowns.push(format!("{axis}_{}", p.name));
        }
    }
    let frame = frame_idx.map(|f| f.map(point));
    let unknown_point = |p: usize| -> Vec3 { [0, 1, 2].map(|a| Expr::Unknown(a * k + p)) };

    // Chain equations (Table I pairs, combined base to platform, simplified).
    for (c, shape) in &shapes {
        let p = point(shape.platform_pivot().index);
        let ChainModel { equations, inverse } = shapes::model(&mut b, *c, shape, p, k);
        b.equations.extend(equations);
        b.inverses.push(inverse);
    }
    let mut added = Added {
        points: Vec::new(),
        scalars: Vec::new(),
        home_inputs: Vec::new(),
        links: Vec::new(),
        link_equations: 0..0,
        sliders: Vec::new(),
        slider_again: Vec::new(),
        platform_placed: false,
        spins: Vec::new(),
    };
    let mut foreign = Vec::new();
    if !general.is_empty() {
        let platform: Vec<(PivotId, Vec3)> = platform_pivots
            .iter()
            .zip(&point_of)
            .filter_map(|(&pivot, p)| p.map(|p| (pivot, unknown_point(p))))
            .collect();
        let explicit = explicit_pairs(d, &topo);
        foreign = general::model(&mut b, &topo, &explicit, &platform, &mut added, errors)?;
        let inputs: Vec<usize> = general
            .iter()
            .flat_map(|&c| &d.chain(c).pairs)
            .flat_map(|p| &p.inputs)
            .map(|i| i.index())
            .collect();
        b.inverses.push(Inverse::None { inputs });
        if let Err(e) = consistent_home_inputs(d, &added.home_inputs) {
            errors.add(e);
            return None;
        }
    }

    // Rigid-body equations of the platform (Eq. 3 / Eq. 16).
    let chain_equations = b.equations.len();
    let coplanar = match frame {
        Some(frame) => {
            let planar = rigid::is_coplanar(&b, frame, k);
            let coplanar = match d.platform.form {
                Some((Form::General, _)) => false,
                Some((Form::Coplanar, span)) => {
                    if !planar {
                        errors.push(span, "`form = coplanar` but the platform pivots are not coplanar at the declared geometry");
                        return None;
                    }
                    true
                }
                None => planar,
            };
            if foreign.is_empty() && !added.platform_placed {
                rigid::platform_equations(&mut b, frame, k, coplanar);
            }
            coplanar
        }
        None => false,
    };
    if (frame.is_none() || !foreign.is_empty()) && !added.platform_placed {
        // The platform with points of other links on it (an axis point, a shared centre), or a
        // platform of one or two points: Eq. 3 on all its members, in the base frame at home.
        let mut members: Vec<(String, Vec3, PointRef)> = b
            .points
            .iter()
            .enumerate()
            .map(|(p, pt)| {
                (
                    pt.name.clone(),
                    unknown_point(p),
                    PointRef::PlatformHome(pt.local),
                )
            })
            .collect();
        if let Some(frame) = frame {
            // The declared (or best) frame first.
            for (slot, f) in frame.into_iter().enumerate() {
                members.swap(slot, f);
            }
        }
        for (q, repr) in foreign {
            members.push((topo.name(q).to_string(), repr.expr().clone(), topo.home(q)));
        }
        rigid::link_equations(&mut b, "platform", &members, None);
    }
    // Which equations the rank test keeps first where some depend on others (see
    // `simplify::rank`): the pairs' and chains' equations, then the links' Eq. 3, the
    // platform's last. A link's distance that the pairs' equations already imply goes rather
    // than one of those (the two points on a cylindrical pair's axis); and where the legs and
    // the platform overlap (a spherical mechanism), every leg keeps its own constraints and
    // the platform's go — dropping a leg's instead leaves that leg held only near home.
    // A link that several prismatic pairs carry (a platform on three guides): the first pair
    // places it, and the others' placements of it come after the links' Eq. 3 — offered
    // first, they kept all three placements and dropped the guides' own distances, which left
    // the square system singular at regular configurations of a 3-PRP.
    let mut priority = vec![0u8; chain_equations];
    for i in added.link_equations.clone() {
        priority[i] = 1;
    }
    for &i in &added.slider_again {
        if let Some(p) = priority.get_mut(i) {
            *p = 2;
        }
    }
    priority.resize(b.equations.len(), 3);
    let kept = crate::simplify::duplicates::remove_duplicates(&mut b.equations);
    let priority: Vec<u8> = kept.iter().map(|&i| priority[i]).collect();

    // Grübler–Kutzbach counts a platform as a body with six freedoms: right for the closed-form
    // shapes on a located platform, wrong for a point or line platform; and it counts every
    // active pair as an input, wrong where pairs share one.
    let shared = d.pairs().any(|p| p.shared);
    let by_rank = !general.is_empty() || frame.is_none() || shared;
    let mut links = Vec::new();
    let platform = match frame {
        Some(f) => Some(Placed::Frame(f.map(|p| {
            (
                unknown_point(p),
                HomeOf::Point(PointRef::Slots(b.points[p].local)),
            )
        }))),
        // A point or line platform has a pose by the runtime's convention.
        None if !b.points.is_empty() => Some(Placed::Unknowns),
        None => None,
    };
    if let Some(placed) = platform {
        links.push(LinkFrame {
            name: "platform".to_string(),
            placed,
        });
    }
    links.append(&mut added.links);
    let located = frame.is_some();
    let frame = frame.unwrap_or([0, 0, 0]);
    let carried_by = carriers(&b, &added.points);
    let followed = b
        .followed
        .iter()
        .map(|(name, s)| (name.clone(), b.slots[*s].name.clone()))
        .collect();
    let compile_time = b.compile_time_params();
    let mut model = Model {
        name: d.name.clone(),
        followed,
        compile_time,
        formulas: b.formulas,
        slots: b.slots,
        constants: b.constants,
        unknowns: b.unknowns,
        inputs: b.inputs,
        equations: b.equations,
        points: b.points,
        frame,
        located,
        axes,
        coplanar,
        inverses: b.inverses,
        home_pose: b.home_pose,
        general_points: added.points,
        general_scalars: added.scalars,
        carried_by,
        auto_points: b.auto_points,
        general_home_inputs: added.home_inputs,
        dropped: Vec::new(),
        dependent: Vec::new(),
        mobility: None,
        counted: crate::model::mobility::of(d).describe(),
        open: crate::model::mobility::of(d).is_tree(),
        links,
        spins: added.spins,
    };
    let checked = if by_rank {
        crate::model::reference::rank_at_home(&mut model, d, &priority)
    } else {
        check_system(&model, d)
    };
    match checked {
        Ok(()) => Some((model, levered)),
        Err(e) => {
            errors.add(e);
            None
        }
    }
}

/// For each intermediate point, the platform point nearest it at home if no base pivot is
/// nearer.
fn carriers(b: &Builder, points: &[(String, PointRef, usize)]) -> Vec<Option<usize>> {
    let distance = |a: [f64; 3], c: [f64; 3]| linkage_geometry::distance(a, c);
    let base: Vec<[f64; 3]> = b
        .decl
        .base_pivots()
        .iter()
        .map(|&p| b.decl.point(p))
        .collect();
    let platform: Vec<[f64; 3]> = b
        .points
        .iter()
        .map(|p| b.home(PointRef::PlatformHome(p.local)))
        .collect();
    points
        .iter()
        .map(|(_, at, _)| {
            let h = b.home(*at);
            let to_base = base
                .iter()
                .map(|q| distance(h, *q))
                .fold(f64::INFINITY, f64::min);
            let (nearest, to_platform) = platform
                .iter()
                .enumerate()
                .map(|(i, q)| (i, distance(h, *q)))
                .min_by(|a, c| a.1.total_cmp(&c.1))?;
            (to_platform < to_base).then_some(nearest)
        })
        .collect()
}

/// A shared input reads one value at home: every pair it drives must agree (a slide's offset).
fn consistent_home_inputs(d: &Decl, home: &[(usize, f64)]) -> Result<(), Error> {
    for (k, &(input, value)) in home.iter().enumerate() {
        let Some(&(_, first)) = home[..k].iter().find(|(i, _)| *i == input) else {
            continue;
        };
        if (value - first).abs() > 1e-9 * (1.0 + first.abs()) {
            let declared = &d.inputs[input];
            // The second pair that declares it, for the span.
            let span = declared.uses.get(1).copied().unwrap_or(d.name.span());
            return Err(Error::new(
                span,
                format!("shared input `{}` reads {first} at home on one pair and {value} on another: the pairs it drives must agree at the declared configuration (same `offset`)", declared.name),
            ));
        }
    }
    Ok(())
}

/// Links an active pair attaches to the base (in any chain): explicit in that pair's inputs.
/// Each with the general model's link it places.
fn explicit_pairs<'d>(d: &'d Decl, topo: &Topology) -> Vec<(&'d Pair, usize)> {
    let mut out: Vec<(&Pair, usize)> = Vec::new();
    for c in d.chain_ids() {
        let chain = d.chain(c);
        for (k, p) in chain.pairs.iter().enumerate() {
            let (Some(before), Some(after)) = (chain.links[k], chain.links[k + 1]) else {
                continue;
            };
            let Some(link) = topo.link(after) else {
                continue;
            };
            if general::explicit::places(p, d.link(before).role, d.link(after).role)
                && !out.iter().any(|&(_, l)| l == link)
            {
                out.push((p, link));
            }
        }
    }
    out
}

fn check_system(model: &Model, d: &Decl) -> Result<(), Error> {
    let mobility = crate::model::mobility::of(d);
    let inputs = model.inputs.len() as i64;
    if mobility.effective() != inputs {
        return Err(crate::model::mobility::mismatch(
            d,
            model,
            mobility.effective(),
            &mobility.describe(),
        ));
    }
    let (n, e) = (model.unknowns.len(), model.equations.len());
    if n != e {
        // Mobility by counting (Grübler–Kutzbach on the reduced system): each unknown platform
        // coordinate is a freedom, each equation removes one, each active input is fixed.
        let mobility = n as i64 - e as i64 + inputs;
        let msg = if n > e {
            format!("the chains give {e} equations for {n} unknown platform coordinates: the mechanism has mobility {mobility} but only {inputs} active joint variables; every degree of freedom needs an active pair (or another chain)")
        } else {
            format!("the chains give {e} equations for {n} unknown platform coordinates: the mechanism is overconstrained (mobility {mobility} with {inputs} active joint variables); make a pair passive or remove a chain")
        };
        return Err(Error::new(d.name.span(), msg));
    }
    for (i, f) in model.equations.iter().enumerate() {
        if f.degree() > 2 {
            return Err(Error::new(
                d.name.span(),
                format!("equation {} is of degree {} in the unknowns; the model must be at most quadratic", i + 1, f.degree()),
            ));
        }
    }
    Ok(())
}

/// The geometry slots of every pair axis `A -> B` whose points are on one link, for the
/// run-time check of a changed geometry; an error for each given by points that coincide at the
/// declared geometry (the rule of [`linkage_geometry::check_axis`]).
fn axes(d: &Decl, b: &Builder, errors: &mut Errors) -> Vec<[[usize; 3]; 2]> {
    let mut axes = Vec::new();
    for p in d.pairs() {
        let Some([a, c]) = p.axis else { continue };
        if d.pivot(a.id).link != d.pivot(c.id).link {
            continue;
        }
        if linkage_geometry::check_axis(d.point(a.id), d.point(c.id)).is_err() {
            errors.add(Error::new(
                c.span,
                format!(
                    "the axis of pair `{}` is given by coincident points `{}` and `{}`",
                    p.kind.letter(),
                    d.pivot(a.id).name,
                    d.pivot(c.id).name
                ),
            ));
        }
        let slots = [b.pivot_slots(a.id), b.pivot_slots(c.id)];
        if !axes.contains(&slots) {
            axes.push(slots);
        }
    }
    axes
}
