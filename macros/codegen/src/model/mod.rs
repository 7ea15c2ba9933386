//! From a checked declaration to the constraint system F(v, x) = 0 (Section 2 of Gao & Wu).
//!
//! Geometry lives in *slots* (pivot coordinates, link lengths, parameters) that can be changed
//! at run time; equations refer to *constants* derived from the slots (pivot coordinates,
//! the E_j of Eq. 17–18, axis frames). Unknowns are the base-frame coordinates of the moving
//! platform's pivots, coordinate-major as in Eq. 19: `[x_P1 … x_Pk, y_P1 … y_Pk, z_P1 … z_Pk]`.

pub mod build;
pub mod builder;
pub mod frame;
pub mod general;
pub mod home_inputs;
pub mod mobility;
pub mod reference;
pub mod rigid;
pub mod shapes;
pub mod turn;

pub use build::build;
pub use builder::Builder;

use crate::expr::{Expr, Names, Vec3};
use crate::front::resolved::{Pair, PairKind};
use syn::Ident;

pub use linkage_geometry::recipe::{Auto, PointRef, Recipe, Recipes};

pub struct Slot {
    pub name: String,
    pub default: f64,
    /// A link's length: `from_geometry` refuses a value that is not positive.
    pub positive: bool,
}

/// Where a link's frame point was in the link's declared coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HomeOf {
    Point(PointRef),
    /// Constants holding an added point's home coordinates.
    Constants([usize; 3]),
}

/// A moving link and how its pose is found.
pub struct LinkFrame {
    pub name: String,
    pub placed: Placed,
}

/// How [`LinkFrame`]'s pose is found.
// A few per mechanism, at generation time: the size of the frame variant does not matter.
#[allow(clippy::large_enum_variant)]
pub enum Placed {
    /// By three of its points (where they are, where they were declared): the motion between
    /// the two.
    Frame([(Vec3, HomeOf); 3]),
    /// A platform of one pivot or of pivots on one line: the runtime's convention for it
    /// (`linkage::pose_from_unknowns`), which no pair fixes entirely.
    Unknowns,
    /// Not at all: a link whose points are collinear (a rod), whose spin is not modelled.
    Unmodelled,
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
    /// `‖P − (c0 + (x − offset) e)‖ = length`, root nearest the reference.
    PrismaticRod {
        input: usize,
        point: usize,
        c0: [usize; 3],
        e: [usize; 3],
        length: usize,
        offset: Option<usize>,
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
    /// Geometry names that follow a parameter, with the parameter's name (see
    /// [`Builder::followed`]).
    pub followed: Vec<(String, String)>,
    /// The slots of parameters nothing evaluated at run time reads (see
    /// [`Builder::compile_time_params`]).
    pub compile_time: Vec<usize>,
    /// The slots declared as formulas of parameters, with their formulas over the slots: the
    /// generated `from_geometry` sets them before it derives anything.
    pub formulas: Vec<(usize, Vec<linkage_geometry::formula::Op>)>,
    pub constants: Vec<Constant>,
    pub unknowns: Vec<String>,
    pub inputs: Vec<String>,
    pub equations: Vec<Expr>,
    pub points: Vec<PlatformPoint>,
    pub frame: [usize; 3],
    /// Whether `frame` locates the platform (three points off one line); a platform of one
    /// point or two has no frame, only a position.
    pub located: bool,
    /// The geometry slots of the two points of every pair axis on one link (checked apart at
    /// run time, as at compile time).
    pub axes: Vec<[[usize; 3]; 2]>,
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
    /// The same equations, for the check that they hold at every answer
    /// (`Mechanism::dependent_offset`): implied near home, but not on every component of the
    /// square system that is left.
    pub dependent: Vec<Expr>,
    /// How the mobility was decided, when not by Grübler–Kutzbach.
    pub mobility: Option<String>,
    /// The mobility by Grübler–Kutzbach, as the listing states it where rank did not decide.
    pub counted: String,
    /// No closed loop: the pairs join the links as a tree (a serial arm), so the inputs place
    /// every link and there is one configuration for them, whatever the geometry.
    pub open: bool,
    /// The moving links whose pose `link_pose` reports: the platform (where it has a pivot), then
    /// named intermediate links of the general model.
    pub links: Vec<LinkFrame>,
    /// Candidate symmetries of the equations, per chain: unknowns to reflect through an
    /// expression (`v[i] → 2 e − v[i]`), see [`general::universal::spins`].
    pub spins: Vec<Vec<(usize, Expr)>>,
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

    /// One recipe per constant, in order: the table `from_geometry` evaluates.
    pub fn recipe_table(&self) -> Vec<Recipe> {
        self.constants.iter().map(|c| c.recipe).collect()
    }
}

/// A point's home position on the slots `g` (base frame; a platform pivot's own frame for
/// `PointRef::Slots`), by the recipes the runtime evaluates: the added points it needs are made
/// in order, NaN for one that cannot be (the generator reports degenerate axes before it
/// evaluates).
pub fn home_of(home_pose: [f64; 6], auto: &[Auto], g: &[f64], p: PointRef) -> [f64; 3] {
    let needed = match p {
        PointRef::Auto(i) => (i + 1).min(auto.len()),
        _ => 0,
    };
    let recipes = Recipes {
        home_pose,
        auto: &auto[..needed],
        constants: &[],
    };
    let mut made: Vec<[f64; 3]> = Vec::with_capacity(needed);
    for a in recipes.auto {
        let q = recipes.added_point(g, &made, a).unwrap_or([f64::NAN; 3]);
        made.push(q);
    }
    recipes.point(g, &made, p)
}

/// A passive S or U: a point the two links share, which the closed-form shapes eliminate (an
/// active one fixes the turn between its links and goes to the general model).
pub fn is_point_joint(p: &Pair) -> bool {
    matches!(p.kind, PairKind::S | PairKind::U) && !p.active
}
