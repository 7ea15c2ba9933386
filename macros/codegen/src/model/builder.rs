//! The state the modelling phases share: the geometry slots (by typed id, never by name), the
//! derived constants, the unknowns and inputs, the equations so far.

use crate::expr::{Expr, Vec3};
use crate::front::ids::{LinkId, PairId, PivotId};
use crate::front::resolved::{Decl, Value};
use crate::model::{home_of, Auto, Constant, Inverse, PlatformPoint, PointRef, Recipe, Slot};
use linkage_geometry::formula::Op;
use std::collections::HashMap;

/// A length-like slot that is not a pivot coordinate: a link's `length`, a pair's `offset` or
/// `lead` (a literal gets its own slot on first use; a parameter is the parameter's slot).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Scalar {
    Length(LinkId),
    Offset(PairId),
    Lead(PairId),
}

/// Mutable state shared by the modelling phases.
pub struct Builder<'d> {
    pub decl: &'d Decl,
    pub slots: Vec<Slot>,
    /// By `ParamId`.
    param_slots: Vec<usize>,
    /// By `ParamId`: whether anything the generated code evaluates at run time reads the
    /// parameter (see [`Self::compile_time_params`]).
    param_read: Vec<bool>,
    /// By `PivotId`.
    pivot_slots: Vec<[usize; 3]>,
    scalar_slots: HashMap<Scalar, usize>,
    /// Geometry names that follow a parameter (a pivot coordinate or a length declared as
    /// one, which has no slot of its own, or as a formula of parameters, whose slot the
    /// formula sets), with the parameter's slot (a formula's first): not to be set by name.
    pub followed: Vec<(String, usize)>,
    /// The slots declared as formulas of parameters, each with its formula over the slots.
    pub formulas: Vec<(usize, Vec<Op>)>,
    pub constants: Vec<Constant>,
    pub unknowns: Vec<String>,
    /// The inputs' names, by `InputId`.
    pub inputs: Vec<String>,
    pub equations: Vec<Expr>,
    pub points: Vec<PlatformPoint>,
    pub inverses: Vec<Inverse>,
    pub home_pose: [f64; 6],
    pub auto_points: Vec<Auto>,
}

impl<'d> Builder<'d> {
    /// The slots in declaration order: parameters, then each link's pivot coordinates and
    /// length.
    pub fn new(decl: &'d Decl) -> Self {
        let mut b = Builder {
            decl,
            slots: Vec::new(),
            param_slots: Vec::new(),
            param_read: vec![false; decl.params.len()],
            pivot_slots: Vec::new(),
            scalar_slots: HashMap::new(),
            followed: Vec::new(),
            formulas: Vec::new(),
            constants: Vec::new(),
            unknowns: Vec::new(),
            inputs: decl.inputs.iter().map(|i| i.name.to_string()).collect(),
            equations: Vec::new(),
            points: Vec::new(),
            inverses: Vec::new(),
            home_pose: decl.platform.home.map_or([0.0; 6], |(_, pose)| pose),
            auto_points: Vec::new(),
        };
        for p in &decl.params {
            let s = b.new_slot(p.name.to_string(), p.value);
            b.param_slots.push(s);
        }
        // Pivots are numbered link by link, in the links' order.
        for (id, link) in decl.links_with_ids() {
            for &pivot in &link.pivots {
                let name = &decl.pivot(pivot).name;
                let coords = decl.pivot(pivot).coords;
                let slots = [0, 1, 2].map(|k| {
                    b.value_slot(
                        format!("{}.{name}.{}", link.name, ["x", "y", "z"][k]),
                        coords[k],
                    )
                });
                debug_assert_eq!(b.pivot_slots.len(), pivot.index());
                b.pivot_slots.push(slots);
            }
            if let Some(length) = link.length {
                let s = b.value_slot(format!("{}.length", link.name), length);
                b.slots[s].positive = true;
                b.scalar_slots.insert(Scalar::Length(id), s);
            }
        }
        b
    }

    fn value_slot(&mut self, name: String, v: Value) -> usize {
        match v {
            Value::Literal(x) => self.new_slot(name, x),
            Value::Param(p) => {
                let s = self.param_slot(p.index());
                self.followed.push((name, s));
                s
            }
            Value::Formula(f) => self.formula_slot(name, f),
        }
    }

    /// A slot of its own for formula `f`, which `from_geometry` sets from the parameters.
    fn formula_slot(&mut self, name: String, f: usize) -> usize {
        let formula = &self.decl.formulas[f];
        let ops = formula
            .ops
            .iter()
            .map(|op| match *op {
                Op::Slot(p) => Op::Slot(self.param_slot(p)),
                other => other,
            })
            .collect();
        let first = self.param_slot(formula.first.index());
        let s = self.new_slot(name.clone(), formula.value);
        self.followed.push((name, first));
        self.formulas.push((s, ops));
        s
    }

    /// Parameter `p`'s slot, read by the generated code.
    fn param_slot(&mut self, p: usize) -> usize {
        self.param_read[p] = true;
        self.param_slots[p]
    }

    /// The slots of the parameters nothing evaluated at run time reads: used only at compile
    /// time (in `home`, or in another parameter's value, evaluated where it is declared) or
    /// not at all. `from_geometry` refuses a change to them rather than ignore it.
    pub fn compile_time_params(&self) -> Vec<usize> {
        (0..self.param_slots.len())
            .filter(|&p| !self.param_read[p])
            .map(|p| self.param_slots[p])
            .collect()
    }

    fn new_slot(&mut self, name: String, default: f64) -> usize {
        self.slots.push(Slot {
            name,
            default,
            positive: false,
        });
        self.slots.len() - 1
    }

    pub fn pivot_slots(&self, pivot: PivotId) -> [usize; 3] {
        self.pivot_slots[pivot.index()]
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

    /// A fixed pivot's coordinates as constants named like the paper (`x_D1`), or like the
    /// parameter that gives them.
    pub fn pivot_constants(&mut self, pivot: PivotId) -> Vec3 {
        let slots = self.pivot_slots(pivot);
        let p = self.decl.pivot(pivot);
        [0, 1, 2].map(|k| {
            let name = match p.coords[k] {
                Value::Param(q) => self.decl.param(q).name.to_string(),
                Value::Literal(_) | Value::Formula(_) => {
                    format!("{}_{}", ["x", "y", "z"][k], p.name)
                }
            };
            self.constant(name, Recipe::Slot(slots[k]))
        })
    }

    /// A length-like value (link length, offset, lead) as a constant: its own slot (named
    /// `slot_name`) on first use if a literal; named like its parameter, or `fallback_name`.
    pub fn scalar_constant(
        &mut self,
        key: Scalar,
        slot_name: String,
        v: Value,
        fallback_name: String,
    ) -> Expr {
        let (slot, name) = match v {
            Value::Param(p) => (
                self.param_slot(p.index()),
                self.decl.param(p).name.to_string(),
            ),
            Value::Literal(_) | Value::Formula(_) => {
                let slot = match self.scalar_slots.get(&key) {
                    Some(&s) => s,
                    None => {
                        let s = match v {
                            Value::Formula(f) => self.formula_slot(slot_name, f),
                            _ => self.new_slot(slot_name, self.decl.value(v)),
                        };
                        self.scalar_slots.insert(key, s);
                        s
                    }
                };
                (slot, fallback_name)
            }
        };
        self.constant(name, Recipe::Slot(slot))
    }

    /// A point's home position (base frame; a platform pivot's own frame for `Slots`), by the
    /// recipes the runtime evaluates too.
    pub fn home(&self, p: PointRef) -> [f64; 3] {
        let g: Vec<f64> = self.slots.iter().map(|s| s.default).collect();
        home_of(self.home_pose, &self.auto_points, &g, p)
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
