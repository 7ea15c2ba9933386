//! The resolved declaration, what the model consumes: every name replaced by a typed id
//! ([`crate::front::ids`]), every pair's arguments in the form its kind takes, the spans kept
//! for the later phases' messages. Built by [`lower`] once the resolver's checks pass, so that
//! each id it holds names something that exists.

use crate::front::ast::{ChainItem, Mechanism, PairDecl};
/// The kinds the resolved declaration shares with the syntax tree.
pub use crate::front::ast::{LinkRole, PairKind};
use crate::front::errors::Errors;
use crate::front::ids::{ChainId, InputId, LinkId, PairId, ParamId, PivotId};
use crate::front::value::{BinOp, Coord, Func, Term};
use linkage_geometry::formula::{self, Op};
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;

/// A number of the geometry: a literal, a parameter, or a formula of parameters (the latter
/// two follow the parameters when they change at run time).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Value {
    Literal(f64),
    Param(ParamId),
    /// An index into [`Decl::formulas`].
    Formula(usize),
}

/// A geometry value declared as arithmetic on parameters.
pub struct Formula {
    /// In postfix order, `Op::Slot(i)` reading parameter i.
    pub ops: Vec<Op>,
    /// Its value at the declared parameters, by the interpreter the runtime uses.
    pub value: f64,
    /// The first parameter it names (the one an error message points to).
    pub first: ParamId,
}

pub struct Param {
    pub name: Ident,
    pub value: f64,
}

pub struct Link {
    pub name: Ident,
    pub role: LinkRole,
    pub pivots: Vec<PivotId>,
    pub length: Option<Value>,
}

pub struct Pivot {
    pub name: Ident,
    pub link: LinkId,
    pub coords: [Value; 3],
}

/// A joint input, with the span of every pair variable that names it (more than one only where
/// it is declared `shared`).
pub struct Input {
    pub name: Ident,
    pub uses: Vec<Span>,
}

/// A pivot named in a pair, with the span of the name there.
#[derive(Clone, Copy, Debug)]
pub struct PivotRef {
    pub id: PivotId,
    pub span: Span,
}

pub struct Pair {
    pub id: PairId,
    pub kind: PairKind,
    /// The pair's letter as written, for messages.
    pub token: Ident,
    pub active: bool,
    pub shared: bool,
    /// Its joint inputs when active, in the order declared.
    pub inputs: Vec<InputId>,
    /// The centre of an `S` or `U`.
    pub centre: Option<PivotRef>,
    /// `axis = A -> B`.
    pub axis: Option<[PivotRef; 2]>,
    pub offset: Option<Value>,
    pub lead: Option<Value>,
}

/// A chain with its anonymous links made explicit: `links.len() == pairs.len() + 1`, `None` an
/// unnamed link between two pairs.
pub struct Chain {
    pub name: Ident,
    pub links: Vec<Option<LinkId>>,
    pub pairs: Vec<Pair>,
}

/// The platform's declared rigid-body form (`form = coplanar | general`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Form {
    Coplanar,
    General,
}

/// The platform's options.
pub struct Platform {
    pub frame: Option<[PivotRef; 3]>,
    /// The declared form, with the span of its keyword.
    pub form: Option<(Form, Span)>,
    pub home: Option<(Span, [f64; 6])>,
    /// `home = inputs(...)`: every input's value, by [`InputId`].
    pub home_inputs: Option<(Span, Vec<f64>)>,
}

/// A declaration with every name resolved. Links by [`LinkId`] (base, platform, then the
/// others), pivots by [`PivotId`], inputs by [`InputId`] in chain order, chains by [`ChainId`].
pub struct Decl {
    pub name: Ident,
    pub params: Vec<Param>,
    pub formulas: Vec<Formula>,
    pub links: Vec<Link>,
    pub pivots: Vec<Pivot>,
    pub inputs: Vec<Input>,
    pub chains: Vec<Chain>,
    pub platform: Platform,
}

impl Decl {
    pub fn link(&self, id: LinkId) -> &Link {
        &self.links[id.index()]
    }

    pub fn pivot(&self, id: PivotId) -> &Pivot {
        &self.pivots[id.index()]
    }

    pub fn param(&self, id: ParamId) -> &Param {
        &self.params[id.index()]
    }

    pub fn chain(&self, id: ChainId) -> &Chain {
        &self.chains[id.index()]
    }

    pub fn pair(&self, id: PairId) -> &Pair {
        &self.chain(id.chain).pairs[id.index]
    }

    /// A value at the declared geometry.
    pub fn value(&self, v: Value) -> f64 {
        match v {
            Value::Literal(x) => x,
            Value::Param(p) => self.param(p).value,
            Value::Formula(f) => self.formulas[f].value,
        }
    }

    /// A pivot's declared coordinates.
    pub fn point(&self, id: PivotId) -> [f64; 3] {
        self.pivot(id).coords.map(|c| self.value(c))
    }

    /// The base's pivots.
    pub fn base_pivots(&self) -> &[PivotId] {
        &self.link(LinkId::BASE).pivots
    }

    /// The platform's pivots.
    pub fn platform_pivots(&self) -> &[PivotId] {
        &self.link(LinkId::PLATFORM).pivots
    }

    /// Every pair, chain by chain.
    pub fn pairs(&self) -> impl Iterator<Item = &Pair> {
        self.chains.iter().flat_map(|c| &c.pairs)
    }

    pub fn links_with_ids(&self) -> impl Iterator<Item = (LinkId, &Link)> {
        self.links
            .iter()
            .enumerate()
            .map(|(i, l)| (LinkId::new(i), l))
    }

    pub fn chain_ids(&self) -> impl Iterator<Item = ChainId> {
        (0..self.chains.len()).map(ChainId::new)
    }
}

/// Name tables of the declaration, for [`lower`].
struct Names {
    links: HashMap<String, LinkId>,
    pivots: HashMap<String, PivotId>,
    params: HashMap<String, ParamId>,
    inputs: HashMap<String, InputId>,
}

/// The resolved declaration of a mechanism the resolver's checks passed; `None` (with the
/// reason in `errors`) if a name is still unresolved, which those checks report first.
pub fn lower(m: &Mechanism, inputs: &[Ident], errors: &mut Errors) -> Option<Decl> {
    let (Some(base), Some(platform)) = (&m.base, &m.platform) else {
        errors.push(
            m.name.span(),
            "mechanism has no `base` or no `platform` link",
        );
        return None;
    };
    let declared = [base, platform].into_iter().chain(&m.links);
    let mut names = Names {
        links: HashMap::new(),
        pivots: HashMap::new(),
        params: HashMap::new(),
        inputs: HashMap::new(),
    };
    let mut out = Decl {
        name: m.name.clone(),
        params: Vec::new(),
        formulas: Vec::new(),
        links: Vec::new(),
        pivots: Vec::new(),
        inputs: Vec::new(),
        chains: Vec::new(),
        platform: Platform {
            frame: None,
            // The parser admits `coplanar` and `general` only.
            form: platform.form.as_ref().map(|f| {
                let form = if f == "general" {
                    Form::General
                } else {
                    Form::Coplanar
                };
                (form, f.span())
            }),
            home: platform.home,
            home_inputs: None,
        },
    };
    for p in &m.params {
        names
            .params
            .insert(p.name.to_string(), ParamId::new(out.params.len()));
        out.params.push(Param {
            name: p.name.clone(),
            value: p.default.value,
        });
    }
    let mut ok = true;
    let param_values: Vec<f64> = out.params.iter().map(|p| p.value).collect();
    let mut formulas = Vec::new();
    let mut value = |c: &Coord, errors: &mut Errors| -> Value {
        match c {
            Coord::Literal(n) => Value::Literal(n.value),
            Coord::Formula(f) => {
                let (n, term) = &**f;
                let mut ops = Vec::new();
                let mut first = None;
                postfix(term, &names.params, &mut ops, &mut first);
                let value = formula::evaluate(&ops, &param_values);
                let fits = formula::depth(&ops).is_some_and(|d| d <= formula::DEPTH);
                match first {
                    Some(first) if fits && value.is_finite() => {
                        formulas.push(Formula { ops, value, first });
                        Value::Formula(formulas.len() - 1)
                    }
                    _ => {
                        errors.push(
                            n.span,
                            if fits {
                                "a coordinate must be a finite number".to_string()
                            } else {
                                format!(
                                    "expression too deeply nested (at most {} pending values)",
                                    formula::DEPTH
                                )
                            },
                        );
                        ok = false;
                        Value::Literal(f64::NAN)
                    }
                }
            }
            Coord::Param(p) => match names.params.get(&p.to_string()) {
                Some(&id) => Value::Param(id),
                None => {
                    errors.push(p.span(), format!("unknown parameter `{p}`"));
                    ok = false;
                    Value::Literal(f64::NAN)
                }
            },
        }
    };
    for l in declared {
        let link = LinkId::new(out.links.len());
        names.links.insert(l.name.to_string(), link);
        let mut pivots = Vec::new();
        for p in &l.pivots {
            let id = PivotId::new(out.pivots.len());
            names.pivots.insert(p.name.to_string(), id);
            pivots.push(id);
            let coords = [0, 1, 2].map(|k| value(&p.coords[k], errors));
            out.pivots.push(Pivot {
                name: p.name.clone(),
                link,
                coords,
            });
        }
        let length = l.length.as_ref().map(|c| {
            let v = value(c, errors);
            let n = match (v, c) {
                (Value::Param(id), _) => out.params[id.index()].value,
                (_, Coord::Literal(n)) => n.value,
                (_, Coord::Formula(f)) => f.0.value,
                (_, Coord::Param(_)) => f64::NAN,
            };
            // A length enters the equations squared: a negative one would be taken for its
            // magnitude, silently.
            if !(n > 0.0) && !n.is_nan() {
                errors.push(
                    c.span(),
                    format!("link `{}`: `length` must be positive, found {n}", l.name),
                );
            }
            v
        });
        out.links.push(Link {
            name: l.name.clone(),
            role: l.role,
            pivots,
            length,
        });
    }
    for (i, name) in inputs.iter().enumerate() {
        names.inputs.insert(name.to_string(), InputId::new(i));
        out.inputs.push(Input {
            name: name.clone(),
            uses: Vec::new(),
        });
    }
    let pivot = |q: &Ident, errors: &mut Errors| -> Option<PivotRef> {
        let found = names
            .pivots
            .get(&q.to_string())
            .map(|&id| PivotRef { id, span: q.span() });
        if found.is_none() {
            errors.push(q.span(), format!("`{q}` is not a declared pivot"));
        }
        found
    };
    for (c, chain) in m.chains.iter().enumerate() {
        let chain_id = ChainId::new(c);
        let mut links = Vec::new();
        let mut pairs = Vec::new();
        let mut last_was_link = false;
        for item in &chain.items {
            match item {
                ChainItem::Link(l) => {
                    match names.links.get(&l.to_string()) {
                        Some(&id) => links.push(Some(id)),
                        None => {
                            errors.push(l.span(), format!("unknown link `{l}`"));
                            return None;
                        }
                    }
                    last_was_link = true;
                }
                ChainItem::Pair(p) => {
                    if !last_was_link {
                        links.push(None);
                    }
                    let id = PairId {
                        chain: chain_id,
                        index: pairs.len(),
                    };
                    let mut pair = lower_pair(id, p, &pivot, &mut value, errors)?;
                    for v in &p.variables {
                        let Some(&input) = names.inputs.get(&v.to_string()) else {
                            errors.push(v.span(), format!("unknown input `{v}`"));
                            return None;
                        };
                        out.inputs[input.index()].uses.push(v.span());
                        pair.inputs.push(input);
                    }
                    pairs.push(pair);
                    last_was_link = false;
                }
            }
        }
        if !last_was_link {
            links.push(None);
        }
        out.chains.push(Chain {
            name: chain.name.clone(),
            links,
            pairs,
        });
    }
    if let Some(frame) = &platform.frame {
        let refs: Vec<PivotRef> = frame.iter().filter_map(|f| pivot(f, errors)).collect();
        match <[PivotRef; 3]>::try_from(refs) {
            Ok(f) => out.platform.frame = Some(f),
            Err(_) => {
                errors.push(platform.name.span(), "`frame` names three pivots");
                return None;
            }
        }
    }
    if let Some((span, values)) = &platform.home_inputs {
        let mut by_input = vec![f64::NAN; out.inputs.len()];
        for (name, v) in values {
            match names.inputs.get(&name.to_string()) {
                Some(&i) => by_input[i.index()] = v.value,
                None => {
                    errors.push(name.span(), format!("`{name}` is not an input"));
                    return None;
                }
            }
        }
        if let Some(i) = by_input.iter().position(|v| v.is_nan()) {
            errors.push(
                *span,
                format!("`home = inputs(...)` gives no value to `{}`", inputs[i]),
            );
            return None;
        }
        out.platform.home_inputs = Some((*span, by_input));
    }
    out.formulas = formulas;
    ok.then_some(out)
}

/// `term` in postfix order, each parameter `Op::Slot` of its index; `first` the first one named.
fn postfix(
    term: &Term,
    params: &HashMap<String, ParamId>,
    ops: &mut Vec<Op>,
    first: &mut Option<ParamId>,
) {
    // A part that names no parameter is one number, computed here by the interpreter the
    // runtime uses (so the declared value and a run-time one agree to the bit).
    if !term.has_param() {
        let mut part = Vec::new();
        postfix_all(term, params, &mut part, first);
        ops.push(Op::Num(formula::evaluate(&part, &[])));
        return;
    }
    postfix_all(term, params, ops, first);
}

fn postfix_all(
    term: &Term,
    params: &HashMap<String, ParamId>,
    ops: &mut Vec<Op>,
    first: &mut Option<ParamId>,
) {
    match term {
        Term::Num(x) => ops.push(Op::Num(*x)),
        Term::Param(p) => match params.get(&p.to_string()) {
            Some(&id) => {
                first.get_or_insert(id);
                ops.push(Op::Slot(id.index()));
            }
            // The parser admits declared parameters only; NaN if one slipped through.
            None => ops.push(Op::Num(f64::NAN)),
        },
        Term::Neg(a) => {
            postfix(a, params, ops, first);
            ops.push(Op::Neg);
        }
        Term::Bin(op, a, b) => {
            postfix(a, params, ops, first);
            postfix(b, params, ops, first);
            ops.push(match op {
                BinOp::Add => Op::Add,
                BinOp::Sub => Op::Sub,
                BinOp::Mul => Op::Mul,
                BinOp::Div => Op::Div,
            });
        }
        Term::Call(f, a) => {
            postfix(a, params, ops, first);
            ops.push(match f {
                Func::Sqrt => Op::Sqrt,
                Func::Sin => Op::Sin,
                Func::Cos => Op::Cos,
                Func::Tan => Op::Tan,
                Func::Asin => Op::Asin,
                Func::Acos => Op::Acos,
                Func::Atan => Op::Atan,
            });
        }
    }
}

fn lower_pair(
    id: PairId,
    p: &PairDecl,
    pivot: &dyn Fn(&Ident, &mut Errors) -> Option<PivotRef>,
    value: &mut dyn FnMut(&Coord, &mut Errors) -> Value,
    errors: &mut Errors,
) -> Option<Pair> {
    let centre = match p.kind {
        PairKind::S | PairKind::U => match p.pivots.as_slice() {
            [c] => Some(pivot(c, errors)?),
            _ => {
                errors.push(p.token.span(), "a pair names one centre");
                return None;
            }
        },
        _ => None,
    };
    let axis = match &p.axis {
        Some((a, b)) => Some([pivot(a, errors)?, pivot(b, errors)?]),
        None => None,
    };
    Some(Pair {
        id,
        kind: p.kind,
        token: p.token.clone(),
        active: p.active.is_some(),
        shared: p.shared,
        inputs: Vec::new(),
        centre,
        axis,
        offset: p.offset.as_ref().map(|c| value(c, errors)),
        lead: p.lead.as_ref().map(|c| value(c, errors)),
    })
}
