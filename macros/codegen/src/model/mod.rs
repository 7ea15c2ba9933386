//! From a checked declaration to the constraint system F(v, x) = 0 (Section 2 of Gao & Wu).
//!
//! Geometry lives in *slots* (pivot coordinates, link lengths, parameters) that can be changed
//! at run time; equations refer to *constants* derived from the slots (pivot coordinates,
//! the E_j of Eq. 17–18, axis frames). Unknowns are the base-frame coordinates of the moving
//! platform's pivots, coordinate-major as in Eq. 19: `[x_P1 … x_Pk, y_P1 … y_Pk, z_P1 … z_Pk]`.

pub mod general;
pub mod home_inputs;
pub mod mobility;
pub mod reference;
pub mod rigid;
pub mod shapes;

use crate::expr::{Expr, Names, Vec3};
use crate::front::ast::{
    ChainDecl, ChainItem, Coord, LinkDecl, LinkRole, Mechanism, PairDecl, PairKind,
};
use crate::front::errors::Errors;
use proc_macro2::Span;
use shapes::ChainModel;
use std::collections::HashMap;
use syn::Ident;

pub struct Slot {
    pub name: String,
    pub default: f64,
}

/// Where a point's position at the home configuration comes from, in the base frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PointRef {
    /// Three geometry slots: a base pivot, an intermediate link's pivot (declared at home), or
    /// a platform pivot in the platform's own frame (the closed-form shapes and Eq. 16 use the
    /// platform's own frame: rigid-body coefficients do not depend on the frame).
    Slots([usize; 3]),
    /// A platform pivot's platform-frame slots, placed by the declared home pose.
    PlatformHome([usize; 3]),
    /// A point the model adds to a link (see [`Auto`]), by index.
    Auto(usize),
}

/// Where a link's frame point was in the link's declared coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HomeOf {
    Point(PointRef),
    /// Constants holding an added point's home coordinates.
    Constants([usize; 3]),
}

/// A moving link and three of its points (where they are, where they were declared): its pose
/// is the motion between the two. `None` for a link whose points are collinear (a rod).
pub struct LinkFrame {
    pub name: String,
    pub frame: Option<[(Vec3, HomeOf); 3]>,
}

/// A point the general model adds to a link, derived from others at home.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Auto {
    /// `origin + unit(toward − origin)`: the axis of a prismatic pair on its rail.
    Along { origin: PointRef, toward: PointRef },
    /// `origin + unit((a1 − a0) × (b1 − b0))`: a universal joint's second axis.
    Normal {
        origin: PointRef,
        a: [PointRef; 2],
        b: [PointRef; 2],
    },
    /// The foot of `point` on the axis `a → b` (o of [`Recipe::Axis`]): where an active pair
    /// turns `point` about.
    Foot {
        a: PointRef,
        b: PointRef,
        point: PointRef,
    },
    /// `point` turned a quarter turn about the axis `a → b` (o + w of [`Recipe::Axis`]).
    Quarter {
        a: PointRef,
        b: PointRef,
        point: PointRef,
    },
    /// `origin + by`: a point one unit along a base axis from `origin`, for the directions of
    /// a link at home.
    Shift { origin: PointRef, by: [f64; 3] },
}

/// How a constant is computed from the geometry slots (in the emitted `from_geometry`).
#[derive(Clone, Debug, PartialEq)]
pub enum Recipe {
    Slot(usize),
    /// Coefficient `index` of `point` in the frame: `[a, b, c, d]` with
    /// `q = a p1 + b p2 + c p3 + d (p2 − p1) × (p3 − p1)` (d = 0 in the coplanar form).
    Rigid {
        frame: [PointRef; 3],
        point: PointRef,
        index: usize,
        coplanar: bool,
    },
    /// Coefficient `index` of `point` on the line: `q = a p1 + b p2`, `a + b = 1`.
    Collinear {
        line: [PointRef; 2],
        point: PointRef,
        index: usize,
    },
    Distance {
        a: PointRef,
        b: PointRef,
    },
    /// Coordinate `index` of a point's home position.
    Coordinate {
        point: PointRef,
        index: usize,
    },
    /// Component `index` of `[e, o, u, w]` for a rotation of `point` about the axis `a → b`:
    /// e the unit axis, o the foot of `point` on it, u the radial arm, w = e × u.
    Axis {
        a: PointRef,
        b: PointRef,
        point: PointRef,
        index: usize,
    },
}

pub struct Constant {
    pub name: String,
    pub recipe: Recipe,
}

/// How joint inputs are recovered from the unknowns (inverse kinematics, per chain).
pub enum Inverse {
    /// `x = ‖P − anchor‖ − offset`
    Distance {
        input: usize,
        point: usize,
        anchor: [usize; 3],
        offset: Option<usize>,
    },
    /// `‖P − (o + u cos θ + w sin θ)‖ = length`, root nearest the reference.
    RevoluteRod {
        input: usize,
        point: usize,
        o: [usize; 3],
        u: [usize; 3],
        w: [usize; 3],
        length: usize,
    },
    /// `‖P − (c0 + x e)‖ = length`, root nearest the reference.
    PrismaticRod {
        input: usize,
        point: usize,
        c0: [usize; 3],
        e: [usize; 3],
        length: usize,
    },
    /// No closed form: the input is left at the reference value and reported as such.
    None { inputs: Vec<usize> },
}

pub struct PlatformPoint {
    pub name: String,
    pub local: [usize; 3],
}

pub struct Model {
    pub name: Ident,
    pub slots: Vec<Slot>,
    pub constants: Vec<Constant>,
    pub unknowns: Vec<String>,
    pub inputs: Vec<String>,
    pub equations: Vec<Expr>,
    pub points: Vec<PlatformPoint>,
    pub frame: [usize; 3],
    /// Whether `frame` locates the platform (three points off one line); a platform of one
    /// point or two has no frame, only a position.
    pub located: bool,
    pub coplanar: bool,
    pub inverses: Vec<Inverse>,
    /// The platform's declared home pose (identity if none): where the general model places the
    /// platform's pivots at home.
    pub home_pose: [f64; 6],
    /// Intermediate-link points solved for (after the platform's): name, home position, first
    /// index in v.
    pub general_points: Vec<(String, PointRef, usize)>,
    /// Scalar unknowns (passive slides), zero at home.
    pub general_scalars: Vec<usize>,
    /// For each of `general_points`, the platform point it is nearer to than to any base pivot
    /// at home (a joint's axis on the platform side of a leg): a guess for where it is moves
    /// with that point.
    pub carried_by: Vec<Option<usize>>,
    /// Points added to links, in dependency order.
    pub auto_points: Vec<Auto>,
    /// Inputs of the general chains and their values at home.
    pub general_home_inputs: Vec<(usize, f64)>,
    /// Equations dropped as dependent at home (rendered), for the listing.
    pub dropped: Vec<String>,
    /// How the mobility was decided, when not by Grübler–Kutzbach.
    pub mobility: Option<String>,
    /// The moving links whose pose `link_pose` reports: the platform (when located), then the
    /// named intermediate links of the general model.
    pub links: Vec<LinkFrame>,
}

impl Model {
    pub fn names(&self) -> (Vec<String>, Vec<String>, Vec<String>) {
        (
            self.unknowns.clone(),
            self.inputs.clone(),
            self.constants.iter().map(|c| c.name.clone()).collect(),
        )
    }

    pub fn render(&self, e: &Expr) -> String {
        let (u, i, c) = self.names();
        e.render(&Names {
            unknowns: &u,
            inputs: &i,
            constants: &c,
        })
    }

    /// Index of coordinate `axis` (0 = x) of platform point `p` in `v`.
    pub fn unknown(&self, p: usize, axis: usize) -> usize {
        axis * self.points.len() + p
    }

    pub fn point_expr(&self, p: usize) -> Vec3 {
        [0, 1, 2].map(|k| Expr::Unknown(self.unknown(p, k)))
    }

    /// The sparsity pattern of ∂F/∂v, row-major, and each entry's expression.
    pub fn jacobian(&self) -> Vec<(usize, usize, Expr)> {
        let mut out = Vec::new();
        for (r, f) in self.equations.iter().enumerate() {
            for c in 0..self.unknowns.len() {
                let d = f.derivative(crate::expr::Var::Unknown(c));
                if !d.is_zero() {
                    out.push((r, c, d));
                }
            }
        }
        out
    }

    pub fn default_slots(&self) -> Vec<f64> {
        self.slots.iter().map(|s| s.default).collect()
    }
}

/// Builds the model. Assumes `Mechanism::validate` passed.
pub fn build(m: &Mechanism) -> syn::Result<Model> {
    let mut b = Builder::new(m);
    b.allocate_slots();
    let Some(platform) = m.platform.as_ref() else {
        return Err(syn::Error::new(
            m.name.span(),
            "mechanism has no `platform { ... }` link",
        ));
    };
    b.home_pose = platform.home.map_or([0.0; 6], |(_, pose)| pose);
    let mut errors = Errors::default();

    // A named link inside a closed-form shape must belong to that chain alone; a crank an
    // active pair places may carry other chains (it is explicit in the input either way).
    let mut uses: HashMap<String, usize> = HashMap::new();
    for c in &m.chains {
        for item in &c.items {
            if let ChainItem::Link(l) = item {
                *uses.entry(l.to_string()).or_default() += 1;
            }
        }
    }
    let private = |l: &Ident| uses.get(&l.to_string()).copied().unwrap_or(0) <= 1;

    // Which platform pivots the chains reach; which chains reduce in closed form.
    let mut used: Vec<bool> = vec![false; platform.pivots.len()];
    let mut shapes = Vec::new();
    let mut general = Vec::new();
    for c in &m.chains {
        match shapes::classify(m, c) {
            Ok(Some(shape)) if shape.links_private(&private) => {
                let g = shape.platform_pivot();
                if let Some(i) = platform.pivots.iter().position(|p| p.name == *g) {
                    used[i] = true;
                }
                shapes.push((c, shape));
            }
            Ok(_) => general.push(c),
            Err(e) => errors.push(e.0, e.1),
        }
    }
    let topo = match crate::model::general::topology(&mut b, m, &general) {
        Ok(t) => Some(t),
        Err((span, msg)) => {
            errors.push(span, msg);
            None
        }
    };
    if let Some(pl) = topo
        .as_ref()
        .and_then(|t| t.links.iter().find(|l| l.role == LinkRole::Platform))
    {
        for q in &pl.members {
            if let Some(i) = platform.pivots.iter().position(|p| p.name == *q) {
                used[i] = true;
            }
        }
    }
    let frame = choose_frame(&b, platform, &used);
    if let Err((span, msg)) = &frame {
        errors.push(*span, msg);
    }
    errors.finish()?;
    let (Ok(frame_idx), Some(topo)) = (frame, topo) else {
        return Err(syn::Error::new(
            platform.name.span(),
            "no frame for the platform",
        ));
    };
    for f in frame_idx.into_iter().flatten() {
        used[f] = true;
    }

    // Platform points, in declaration order.
    let mut point_of_pivot = HashMap::new();
    for (i, pivot) in platform.pivots.iter().enumerate() {
        if used[i] {
            point_of_pivot.insert(pivot.name.to_string(), b.points.len());
            b.points.push(PlatformPoint {
                name: pivot.name.to_string(),
                local: b.pivot_slots("platform", &pivot.name.to_string()),
            });
        }
    }
    let k = b.points.len();
    for axis in ["x", "y", "z"] {
        for p in &b.points {
            b.unknowns.push(format!("{axis}_{}", p.name));
        }
    }
    let frame = frame_idx.map(|f| f.map(|f| point_of_pivot[&platform.pivots[f].name.to_string()]));

    // Inputs in chain order, whichever model treats the chain.
    for c in &m.chains {
        for item in &c.items {
            if let ChainItem::Pair(p) = item {
                for v in &p.variables {
                    b.input(v);
                }
            }
        }
    }

    // Chain equations (Table I pairs, combined base to platform, simplified).
    for (c, shape) in &shapes {
        let p = point_of_pivot[&shape.platform_pivot().to_string()];
        let ChainModel { equations, inverse } = shapes::model(&mut b, c, shape, p, k);
        b.equations.extend(equations);
        b.inverses.push(inverse);
    }
    let mut added = crate::model::general::Added {
        points: Vec::new(),
        scalars: Vec::new(),
        home_inputs: Vec::new(),
        links: Vec::new(),
        link_equations: 0..0,
        platform_placed: false,
    };
    let mut foreign = Vec::new();
    if !general.is_empty() {
        let platform_exprs: HashMap<String, Vec3> = point_of_pivot
            .iter()
            .map(|(name, &p)| (name.clone(), [0, 1, 2].map(|a| Expr::Unknown(a * k + p))))
            .collect();
        let explicit = explicit_pairs(m, &topo);
        foreign =
            crate::model::general::model(&mut b, m, &topo, &explicit, &platform_exprs, &mut added)
                .map_err(|(span, msg)| syn::Error::new(span, msg))?;
        let inputs: Vec<usize> = general
            .iter()
            .flat_map(|c| c.items.iter())
            .filter_map(|i| match i {
                ChainItem::Pair(p) => Some(p.variables.iter()),
                ChainItem::Link(_) => None,
            })
            .flatten()
            .map(|v| b.input_index(v))
            .collect();
        b.inverses.push(Inverse::None { inputs });
        consistent_home_inputs(m, &b.inputs, &added.home_inputs)?;
    }

    // Rigid-body equations of the platform (Eq. 3 / Eq. 16).
    let chain_equations = b.equations.len();
    let coplanar = match frame {
        Some(frame) => {
            let planar = rigid::is_coplanar(&b, frame, k);
            let coplanar = match &platform.form {
                Some(form) if form == "general" => false,
                Some(form) => {
                    if !planar {
                        return Err(syn::Error::new(form.span(), "`form = coplanar` but the platform pivots are not coplanar at the declared geometry"));
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
                    [0, 1, 2].map(|a| Expr::Unknown(a * k + p)),
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
        for (name, repr) in foreign {
            let at = topo.home[&name];
            members.push((name, repr.expr().clone(), at));
        }
        rigid::link_equations(&mut b, "platform", &members, None);
    }
    // Which equations the rank test keeps first where some depend on others (see
    // `simplify::rank`): the pairs' and chains' equations, then the links' Eq. 3, the
    // platform's last. A link's distance that the pairs' equations already imply goes rather
    // than one of those (the two points on a cylindrical pair's axis); and where the legs and
    // the platform overlap (a spherical mechanism), every leg keeps its own constraints and
    // the platform's go — dropping a leg's instead leaves that leg held only near home.
    let mut priority = vec![0u8; chain_equations];
    for i in added.link_equations.clone() {
        priority[i] = 1;
    }
    priority.resize(b.equations.len(), 2);
    let kept = crate::simplify::duplicates::remove_duplicates(&mut b.equations);
    let priority: Vec<u8> = kept.iter().map(|&i| priority[i]).collect();

    // Grübler–Kutzbach counts a platform as a body with six freedoms: right for the closed-form
    // shapes on a located platform, wrong for a point or line platform; and it counts every
    // active pair as an input, wrong where pairs share one.
    let shared = m.chains.iter().any(|c| {
        c.items
            .iter()
            .any(|i| matches!(i, ChainItem::Pair(p) if p.shared))
    });
    let by_rank = !general.is_empty() || frame.is_none() || shared;
    let mut links = Vec::new();
    if let Some(f) = frame {
        links.push(LinkFrame {
            name: "platform".to_string(),
            frame: Some(f.map(|p| {
                (
                    [0, 1, 2].map(|a| Expr::Unknown(a * k + p)),
                    HomeOf::Point(PointRef::Slots(b.points[p].local)),
                )
            })),
        });
    }
    links.append(&mut added.links);
    let located = frame.is_some();
    let frame = frame.unwrap_or([0, 0, 0]);
    let carried_by = carriers(&b, m, &added.points);
    let mut model = Model {
        name: m.name.clone(),
        slots: b.slots,
        constants: b.constants,
        unknowns: b.unknowns,
        inputs: b.inputs,
        equations: b.equations,
        points: b.points,
        frame,
        located,
        coplanar,
        inverses: b.inverses,
        home_pose: b.home_pose,
        general_points: added.points,
        general_scalars: added.scalars,
        carried_by,
        auto_points: b.auto_points,
        general_home_inputs: added.home_inputs,
        dropped: Vec::new(),
        mobility: None,
        links,
    };
    if !by_rank {
        check_system(&model, m)?;
    } else {
        crate::model::reference::rank_at_home(&mut model, m, &priority)?;
    }
    Ok(model)
}

/// For each intermediate point, the platform point nearest it at home if no base pivot is
/// nearer.
fn carriers(
    b: &Builder,
    m: &Mechanism,
    points: &[(String, PointRef, usize)],
) -> Vec<Option<usize>> {
    let distance = |a: [f64; 3], c: [f64; 3]| linkage_geometry::distance(a, c);
    let base: Vec<[f64; 3]> = m
        .base
        .iter()
        .flat_map(|l| &l.pivots)
        .map(|p| b.default_point(&p.coords))
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

/// An added point's home position from those it derives from (NaN when degenerate: the
/// generator reports degenerate axes before it evaluates).
pub fn auto_point(a: &Auto, home: &dyn Fn(PointRef) -> [f64; 3]) -> [f64; 3] {
    let r = match *a {
        Auto::Along { origin, toward } => linkage_geometry::along(home(origin), home(toward)),
        Auto::Normal { origin, a, b } => {
            linkage_geometry::normal_point(home(origin), a.map(home), b.map(home))
        }
        Auto::Foot { a, b, point } => {
            linkage_geometry::axis_frame(home(a), home(b), home(point)).map(|f| [f[3], f[4], f[5]])
        }
        Auto::Quarter { a, b, point } => {
            linkage_geometry::axis_frame(home(a), home(b), home(point))
                .map(|f| [f[3] + f[9], f[4] + f[10], f[5] + f[11]])
        }
        Auto::Shift { origin, by } => {
            let o = home(origin);
            Ok([o[0] + by[0], o[1] + by[1], o[2] + by[2]])
        }
    };
    r.unwrap_or([f64::NAN; 3])
}

/// A shared input reads one value at home: every pair it drives must agree (a slide's offset).
fn consistent_home_inputs(
    m: &Mechanism,
    inputs: &[String],
    home: &[(usize, f64)],
) -> syn::Result<()> {
    for (k, &(input, value)) in home.iter().enumerate() {
        let Some(&(_, first)) = home[..k].iter().find(|(i, _)| *i == input) else {
            continue;
        };
        if (value - first).abs() > 1e-9 * (1.0 + first.abs()) {
            let name = &inputs[input];
            // The second pair that declares it, for the span.
            let span = m
                .chains
                .iter()
                .flat_map(|c| &c.items)
                .filter_map(|i| match i {
                    ChainItem::Pair(p) => p.variables.iter().find(|v| *v == name),
                    ChainItem::Link(_) => None,
                })
                .nth(1)
                .map_or_else(|| m.name.span(), |v| v.span());
            return Err(syn::Error::new(
                span,
                format!("shared input `{name}` reads {first} at home on one pair and {value} on another: the pairs it drives must agree at the declared configuration (same `offset`)"),
            ));
        }
    }
    Ok(())
}

/// Links an active pair attaches to the base (in any chain): explicit in that pair's inputs.
fn explicit_pairs<'a>(
    m: &'a Mechanism,
    topo: &crate::model::general::Topology,
) -> Vec<(&'a PairDecl, String)> {
    let mut out: Vec<(&PairDecl, String)> = Vec::new();
    for c in &m.chains {
        let n = normalize(m, c);
        for (k, p) in n.pairs.iter().enumerate() {
            let (Some(before), Some(after)) = (n.links[k], n.links[k + 1]) else {
                continue;
            };
            let moves = matches!(
                p.kind,
                PairKind::R | PairKind::P | PairKind::H | PairKind::C
            );
            if before.role == LinkRole::Base
                && after.role == LinkRole::Intermediate
                && p.active.is_some()
                && moves
                && p.axis.is_some()
                && topo.links.iter().any(|l| after.name == l.name)
                && !out.iter().any(|(_, l)| after.name == l)
            {
                out.push((*p, after.name.to_string()));
            }
        }
    }
    out
}

fn check_system(model: &Model, m: &Mechanism) -> syn::Result<()> {
    let mobility = crate::model::mobility::of(m);
    let inputs = model.inputs.len() as i64;
    if mobility.effective() != inputs {
        return Err(syn::Error::new(
            m.name.span(),
            format!(
                "the mechanism has {inputs} active joint variable{} but mobility {} ({}); declare one active pair per degree of freedom",
                if inputs == 1 { "" } else { "s" },
                mobility.effective(),
                mobility.describe()
            ),
        ));
    }
    let (n, e) = (model.unknowns.len(), model.equations.len());
    if n != e {
        let inputs = model.inputs.len() as i64;
        // Mobility by counting (Grübler–Kutzbach on the reduced system): each unknown platform
        // coordinate is a freedom, each equation removes one, each active input is fixed.
        let mobility = n as i64 - e as i64 + inputs;
        let msg = if n > e {
            format!("the chains give {e} equations for {n} unknown platform coordinates: the mechanism has mobility {mobility} but only {inputs} active joint variables; every degree of freedom needs an active pair (or another chain)")
        } else {
            format!("the chains give {e} equations for {n} unknown platform coordinates: the mechanism is overconstrained (mobility {mobility} with {inputs} active joint variables); make a pair passive or remove a chain")
        };
        return Err(syn::Error::new(m.name.span(), msg));
    }
    for (i, f) in model.equations.iter().enumerate() {
        if f.degree() > 2 {
            return Err(syn::Error::new(
                m.name.span(),
                format!("equation {} is of degree {} in the unknowns; the model must be at most quadratic", i + 1, f.degree()),
            ));
        }
    }
    Ok(())
}

/// The platform's three frame pivots: the declared ones, else the largest triangle; `None` for
/// a platform of one point or of collinear points (its chains fix only its position).
fn choose_frame(
    b: &Builder,
    platform: &LinkDecl,
    used: &[bool],
) -> Result<Option<[usize; 3]>, (Span, String)> {
    let _ = used;
    let pts: Vec<[f64; 3]> = platform
        .pivots
        .iter()
        .map(|p| b.default_point(&p.coords))
        .collect();
    let area = |i: usize, j: usize, l: usize| rigid::triangle_area(pts[i], pts[j], pts[l]);
    let scale = pts
        .iter()
        .flat_map(|p| p.iter())
        .fold(1e-300f64, |a, x| a.max(x.abs()));
    let tol = 1e-9 * scale * scale;
    if let Some(frame) = &platform.frame {
        // Unknown or missing names are reported by the resolver.
        let idx: Vec<usize> = frame
            .iter()
            .filter_map(|f| platform.pivots.iter().position(|p| p.name == *f))
            .collect();
        let [a, b, c] = idx[..] else {
            return Err((
                platform.name.span(),
                "`frame` names three pivots of the platform".to_string(),
            ));
        };
        if area(a, b, c) <= tol {
            return Err((frame[0].span(), format!("the `frame` pivots `{}`, `{}`, `{}` are collinear: the platform needs three non-collinear pivots", frame[0], frame[1], frame[2])));
        }
        return Ok(Some([a, b, c]));
    }
    // Largest triangle: the best-conditioned frame.
    let n = pts.len();
    let mut best = None;
    let mut best_area = tol;
    for i in 0..n {
        for j in i + 1..n {
            for l in j + 1..n {
                let a = area(i, j, l);
                if a > best_area * (1.0 + 1e-9) {
                    best_area = a;
                    best = Some([i, j, l]);
                }
            }
        }
    }
    if best.is_none() && platform.pivots.len() >= 3 {
        return Err((platform.name.span(), "the `platform` pivots are collinear: a platform needs three non-collinear pivots to be located (or declare one pivot, for a platform that is a point)".to_string()));
    }
    Ok(best)
}

/// Mutable state shared by the modelling phases.
pub struct Builder<'m> {
    pub mech: &'m Mechanism,
    pub slots: Vec<Slot>,
    slot_of: HashMap<String, usize>,
    pub constants: Vec<Constant>,
    pub unknowns: Vec<String>,
    pub inputs: Vec<String>,
    pub equations: Vec<Expr>,
    pub points: Vec<PlatformPoint>,
    pub inverses: Vec<Inverse>,
    pub home_pose: [f64; 6],
    pub auto_points: Vec<Auto>,
}

impl<'m> Builder<'m> {
    fn new(mech: &'m Mechanism) -> Self {
        Builder {
            mech,
            slots: Vec::new(),
            slot_of: HashMap::new(),
            constants: Vec::new(),
            unknowns: Vec::new(),
            inputs: Vec::new(),
            equations: Vec::new(),
            points: Vec::new(),
            inverses: Vec::new(),
            home_pose: [0.0; 6],
            auto_points: Vec::new(),
        }
    }

    fn allocate_slots(&mut self) {
        let m = self.mech;
        for p in &m.params {
            self.new_slot(p.name.to_string(), p.default.value);
        }
        for link in m.all_links() {
            for pivot in &link.pivots {
                for (k, c) in pivot.coords.iter().enumerate() {
                    let key = format!("{}.{}.{}", link.name, pivot.name, ["x", "y", "z"][k]);
                    self.coord_slot(key, c);
                }
            }
            if let Some(c) = &link.length {
                self.coord_slot(format!("{}.length", link.name), c);
            }
        }
    }

    fn coord_slot(&mut self, key: String, c: &Coord) -> usize {
        let slot = match c {
            Coord::Literal(n) => self.new_slot(key.clone(), n.value),
            Coord::Param(p) => self.slot_of[&p.to_string()],
        };
        self.slot_of.insert(key, slot);
        slot
    }

    fn new_slot(&mut self, name: String, default: f64) -> usize {
        self.slots.push(Slot {
            name: name.clone(),
            default,
        });
        self.slot_of.insert(name, self.slots.len() - 1);
        self.slots.len() - 1
    }

    pub fn slot(&self, key: &str) -> usize {
        self.slot_of[key]
    }

    pub fn pivot_slots(&self, link: &str, pivot: &str) -> [usize; 3] {
        ["x", "y", "z"].map(|a| self.slot(&format!("{link}.{pivot}.{a}")))
    }

    pub fn default_point(&self, coords: &[Coord; 3]) -> [f64; 3] {
        [0, 1, 2].map(|k| match &coords[k] {
            Coord::Literal(n) => n.value,
            Coord::Param(p) => self.slots[self.slot_of[&p.to_string()]].default,
        })
    }

    pub fn default_slot_point(&self, slots: [usize; 3]) -> [f64; 3] {
        slots.map(|s| self.slots[s].default)
    }

    /// A constant with the given recipe, shared if one already exists.
    pub fn constant(&mut self, name: String, recipe: Recipe) -> Expr {
        if let Some(i) = self.constants.iter().position(|c| c.recipe == recipe) {
            return Expr::Constant(i);
        }
        self.constants.push(Constant { name, recipe });
        Expr::Constant(self.constants.len() - 1)
    }

    pub fn constant_index(e: &Expr) -> usize {
        match e {
            Expr::Constant(i) => *i,
            _ => unreachable!("constants are built as Expr::Constant"),
        }
    }

    /// A fixed pivot's coordinates as constants named like the paper (`x_D1`).
    pub fn pivot_constants(&mut self, link: &str, pivot: &str) -> Vec3 {
        let slots = self.pivot_slots(link, pivot);
        [0, 1, 2].map(|k| {
            let name = if self
                .mech
                .params
                .iter()
                .any(|p| self.slot(&p.name.to_string()) == slots[k])
            {
                self.slots[slots[k]].name.clone()
            } else {
                format!("{}_{}", ["x", "y", "z"][k], pivot)
            };
            self.constant(name, Recipe::Slot(slots[k]))
        })
    }

    /// A length-like slot (link length, offset, lead) as a constant.
    pub fn scalar_constant(&mut self, key: &str, c: &Coord, fallback_name: String) -> Expr {
        let slot = match c {
            Coord::Param(p) => self.slot(&p.to_string()),
            Coord::Literal(_) => {
                if let Some(&s) = self.slot_of.get(key) {
                    s
                } else {
                    self.coord_slot(key.to_string(), c)
                }
            }
        };
        let name = match c {
            Coord::Param(p) => p.to_string(),
            Coord::Literal(_) => fallback_name,
        };
        self.constant(name, Recipe::Slot(slot))
    }

    /// The index of joint input `name`, registered on first use.
    pub fn input(&mut self, name: &Ident) -> usize {
        self.input_index(name)
    }

    pub fn input_index(&mut self, name: &Ident) -> usize {
        let name = name.to_string();
        if let Some(i) = self.inputs.iter().position(|n| *n == name) {
            return i;
        }
        self.inputs.push(name);
        self.inputs.len() - 1
    }

    /// A coordinate's value at the declared geometry.
    pub fn coord_value(&self, c: &Coord) -> f64 {
        match c {
            Coord::Literal(n) => n.value,
            Coord::Param(p) => self.slots[self.slot_of[&p.to_string()]].default,
        }
    }

    /// A point's home position (base frame; a platform pivot's own frame for `Slots`).
    pub fn home(&self, p: PointRef) -> [f64; 3] {
        match p {
            PointRef::Slots(s) => self.default_slot_point(s),
            PointRef::PlatformHome(s) => {
                linkage_geometry::place(self.home_pose, self.default_slot_point(s))
            }
            PointRef::Auto(i) => auto_point(&self.auto_points[i], &|p| self.home(p)),
        }
    }

    /// Adds a point to a link's home geometry.
    pub fn auto_point(&mut self, a: Auto) -> PointRef {
        if let Some(i) = self.auto_points.iter().position(|b| *b == a) {
            return PointRef::Auto(i);
        }
        self.auto_points.push(a);
        PointRef::Auto(self.auto_points.len() - 1)
    }
}

/// The items of a chain with anonymous links made explicit: `links.len() == pairs.len() + 1`.
pub struct Normalized<'a> {
    pub pairs: Vec<&'a PairDecl>,
    pub links: Vec<Option<&'a LinkDecl>>,
}

pub fn normalize<'a>(m: &'a Mechanism, c: &'a ChainDecl) -> Normalized<'a> {
    let mut pairs = Vec::new();
    let mut links = Vec::new();
    let mut last_was_link = false;
    for item in &c.items {
        match item {
            ChainItem::Link(l) => {
                links.push(m.link(l));
                last_was_link = true;
            }
            ChainItem::Pair(p) => {
                if !last_was_link {
                    links.push(None);
                }
                pairs.push(p);
                last_was_link = false;
            }
        }
    }
    if !last_was_link {
        links.push(None);
    }
    Normalized { pairs, links }
}

/// A passive S or U: a point the two links share, which the closed-form shapes eliminate (an
/// active one fixes the turn between its links and goes to the general model).
pub fn is_point_joint(p: &PairDecl) -> bool {
    matches!(p.kind, PairKind::S | PairKind::U) && p.active.is_none()
}

pub fn role(l: Option<&LinkDecl>) -> Option<LinkRole> {
    l.map(|l| l.role)
}
