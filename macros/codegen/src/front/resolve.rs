//! Name resolution, the one pass after parsing: links, pivots and joint variables are entered
//! in one table ([`Symbols`]), parameters and every name a declaration uses are checked against
//! it, and every pair's arguments against the one table of what each pair kind takes
//! (`Accepts`). Never builds tokens; collects every mistake into the shared [`Errors`] so that
//! the user sees them all in one build. Once they pass, the declaration is lowered to its
//! resolved form ([`crate::front::resolved`]): names become typed ids, and no later phase looks
//! anything up by name.
//!
//! Pivot names are global: an axis `A -> B` names its pivots without their links, so one name
//! on two links is an error here rather than a silent choice later. A joint variable names one
//! input; several pairs may share it only where each declares it `active shared NAME`, and
//! only if it means the same quantity (an angle, or a length) in each.

use crate::front::ast::{ChainDecl, ChainItem, Coord, LinkDecl, Mechanism, PairDecl, PairKind};
pub use crate::front::errors::Errors;
use crate::front::resolved::Decl;
use proc_macro2::Span;
use std::collections::HashMap;
use syn::Ident;

/// What a joint variable measures.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Quantity {
    /// A rotation (R, H, a C's first variable), radians.
    Angle,
    /// A slide (P, a C's second variable), the base frame's length unit.
    Length,
}

impl Quantity {
    fn describe(self) -> &'static str {
        match self {
            Quantity::Angle => "an angle",
            Quantity::Length => "a length",
        }
    }

    /// What the `k`-th joint variable of an active pair of this kind measures.
    fn of(kind: PairKind, k: usize) -> Quantity {
        match (kind, k) {
            (PairKind::P, _) | (PairKind::C, 1) => Quantity::Length,
            _ => Quantity::Angle,
        }
    }
}

/// A pivot: its name and the link (index into [`Symbols::links`]) that declares it.
pub struct PivotSymbol {
    pub name: Ident,
    pub link: usize,
}

/// A joint input: the pairs it drives (chain name and the variable's token).
pub struct InputSymbol {
    pub name: Ident,
    pub quantity: Quantity,
    pub shared: bool,
    pub uses: Vec<(String, Span)>,
}

/// The resolved names of a declaration: links (base, platform, then the others, in declaration
/// order), pivots, and inputs in chain order (the order of `x`).
#[derive(Default)]
pub struct Symbols {
    pub links: Vec<Ident>,
    pub pivots: Vec<PivotSymbol>,
    pub inputs: Vec<InputSymbol>,
    pivot_index: HashMap<String, usize>,
}

impl Symbols {
    /// The pivot called `name`, if one is declared.
    pub fn pivot(&self, name: &Ident) -> Option<&PivotSymbol> {
        self.pivot_index
            .get(&name.to_string())
            .and_then(|&i| self.pivots.get(i))
    }

    /// Whether any input drives several pairs.
    pub fn has_shared_inputs(&self) -> bool {
        self.inputs.iter().any(|i| i.uses.len() > 1)
    }
}

impl Mechanism {
    pub fn all_links(&self) -> impl Iterator<Item = &LinkDecl> {
        self.base
            .iter()
            .chain(self.platform.iter())
            .chain(self.links.iter())
    }

    pub fn link(&self, name: &Ident) -> Option<&LinkDecl> {
        self.all_links().find(|l| l.name == *name)
    }

    /// Resolves every name and checks every pair; the mistakes go to `errors`. The resolved
    /// declaration when there are none.
    pub fn resolve(&self, errors: &mut Errors) -> Option<Decl> {
        let symbols = self.symbols(errors);
        if !errors.is_empty() {
            return None;
        }
        let inputs: Vec<Ident> = symbols.inputs.iter().map(|i| i.name.clone()).collect();
        crate::front::resolved::lower(self, &inputs, errors)
    }

    /// The name tables, every check run.
    fn symbols(&self, errors: &mut Errors) -> Symbols {
        let mut symbols = Symbols::default();
        for link in self.all_links() {
            let id = symbols.links.len();
            symbols.links.push(link.name.clone());
            for p in &link.pivots {
                match symbols.pivot_index.get(&p.name.to_string()) {
                    // The same name twice on one link is reported below.
                    Some(&first) if symbols.pivots[first].link != id => errors.push(
                        p.name.span(),
                        format!(
                            "pivot `{}` is declared on `{}` and on `{}`: pivot names are global (an axis `A -> B` names its pivots without their links); rename one",
                            p.name, symbols.links[symbols.pivots[first].link], link.name
                        ),
                    ),
                    Some(_) => {}
                    None => {
                        symbols.pivot_index.insert(p.name.to_string(), symbols.pivots.len());
                        symbols.pivots.push(PivotSymbol {
                            name: p.name.clone(),
                            link: id,
                        });
                    }
                }
            }
        }
        if self.base.is_none() {
            errors.push(self.name.span(), "mechanism has no `base { ... }` link");
        }
        if self.platform.is_none() {
            errors.push(self.name.span(), "mechanism has no `platform { ... }` link");
        }
        if self.chains.is_empty() {
            errors.push(self.name.span(), "mechanism has no `chain`: declare at least one `chain NAME = base - ... - platform;`");
        }
        unique(self.params.iter().map(|p| &p.name), "parameter", errors);
        unique(self.all_links().map(|l| &l.name), "link", errors);
        unique(self.chains.iter().map(|c| &c.name), "chain", errors);
        symbols.inputs = inputs(&self.chains, errors);
        if let Some((span, values)) = self.platform.as_ref().and_then(|p| p.home_inputs.as_ref()) {
            home_inputs(*span, values, &symbols.inputs, errors);
        }

        for link in self.all_links() {
            unique(link.pivots.iter().map(|p| &p.name), "pivot", errors);
            for pivot in &link.pivots {
                for c in &pivot.coords {
                    self.check_coord(c, errors);
                }
            }
            if let Some(c) = &link.length {
                self.check_coord(c, errors);
            }
            if let Some(frame) = &link.frame {
                if frame.len() != 3 {
                    errors.push(
                        link.name.span(),
                        format!("`frame` names three pivots, found {}", frame.len()),
                    );
                }
                for f in frame {
                    if !link.pivots.iter().any(|p| p.name == *f) {
                        errors.push(
                            f.span(),
                            format!("`frame` names unknown pivot `{f}` of link `{}`", link.name),
                        );
                    }
                }
            }
        }
        for chain in &self.chains {
            self.check_chain(chain, errors);
        }
        for link in &self.links {
            let used = self.chains.iter().any(|c| {
                c.items
                    .iter()
                    .any(|i| matches!(i, ChainItem::Link(l) if *l == link.name))
            });
            if !used {
                errors.push(
                    link.name.span(),
                    format!(
                        "link `{}` is not connected to the base: no chain passes through it",
                        link.name
                    ),
                );
            }
        }
        symbols
    }

    /// [`Mechanism::resolve`] on its own, for callers that only want the verdict.
    pub fn validate(&self) -> syn::Result<()> {
        let mut errors = Errors::default();
        self.resolve(&mut errors);
        errors.finish()
    }

    fn check_coord(&self, c: &Coord, errors: &mut Errors) {
        if let Coord::Param(p) = c {
            if !self.params.iter().any(|q| q.name == *p) {
                errors.push(
                    p.span(),
                    format!("unknown parameter `{p}`: declare it in `params {{ {p} = ... }}`"),
                );
            }
        }
    }

    fn check_chain(&self, chain: &crate::front::ast::ChainDecl, errors: &mut Errors) {
        let items = &chain.items;
        if let [ChainItem::Link(_)] = items.as_slice() {
            errors.push(
                chain.name.span(),
                format!("chain `{}` has no pair: a chain is links joined by pairs, `FIRST - PAIR(...) - ... - LAST`", chain.name),
            );
            return;
        }
        // A chain begins at the base or at any declared link (e.g. the second rod of a
        // parallelogram on a crank) and ends at a link.
        match items.first() {
            Some(ChainItem::Link(l)) if l == "platform" => errors.push(
                l.span(),
                format!("chain `{}` begins at `platform`: chains run from the base (or a link) to the platform", chain.name),
            ),
            Some(ChainItem::Link(_)) => {}
            _ => errors.push(
                chain.name.span(),
                format!("chain `{}` must start at `base` (or at a declared link)", chain.name),
            ),
        }
        match items.last() {
            Some(ChainItem::Link(_)) => {}
            _ => errors.push(
                chain.name.span(),
                format!(
                    "chain `{}` does not reach the moving platform: it must end at `platform`",
                    chain.name
                ),
            ),
        }
        if let (Some(ChainItem::Link(a)), Some(ChainItem::Link(b))) = (items.first(), items.last())
        {
            if a == "base" && b != "platform" && self.link(b).is_some() {
                // Another chain goes on from `b`: it begins there (a tool on a carriage) or
                // passes through it (a four-bar's rocker closing on the coupler).
                let reaches = self.chains.iter().any(|c| {
                    let Some((_, before_end)) = c.items.split_last() else {
                        return false;
                    };
                    before_end
                        .iter()
                        .any(|i| matches!(i, ChainItem::Link(f) if f == b))
                });
                if !reaches {
                    errors.push(b.span(), format!("chain `{}` does not reach the moving platform: it must end at `platform`, or at a link another chain begins at or passes through, not `{b}`", chain.name));
                }
            }
        }
        for (k, item) in items.iter().enumerate() {
            match item {
                ChainItem::Link(l) => {
                    let missing_role = (l == "platform" && self.platform.is_none())
                        || (l == "base" && self.base.is_none());
                    if self.link(l).is_none() && !missing_role {
                        errors.push(
                            l.span(),
                            format!("unknown link `{l}` in chain `{}`", chain.name),
                        );
                    }
                    if let Some(ChainItem::Link(next)) = items.get(k + 1) {
                        if next == l {
                            errors.push(next.span(), format!("a pair between link `{l}` and itself: put a pair between the two links"));
                        } else {
                            errors.push(
                                next.span(),
                                format!("links `{l}` and `{next}` are joined without a pair"),
                            );
                        }
                    }
                }
                ChainItem::Pair(p) => {
                    // A chain end with no link after it is reported already.
                    let at_end = k + 1 == items.len();
                    let before = neighbour(items, k, false);
                    let after = neighbour(items, k, true);
                    if let (Some(a), Some(b)) = (&before, &after) {
                        if a == b {
                            errors.push(
                                p.token.span(),
                                format!("pair `{}` joins link `{a}` to itself", p.kind.letter()),
                            );
                        }
                    }
                    self.check_pair(chain, p, before, after, at_end, errors);
                }
            }
        }
    }

    fn check_pair(
        &self,
        chain: &crate::front::ast::ChainDecl,
        p: &PairDecl,
        before: Option<&Ident>,
        after: Option<&Ident>,
        at_end: bool,
        errors: &mut Errors,
    ) {
        let letter = p.kind.letter();
        let accepts = Accepts::of(p.kind);
        match (&p.active, &p.passive) {
            (Some(_), Some(pas)) => errors.push(pas.span(), format!("pair `{letter}` is both `active` and `passive`")),
            (None, None) if accepts.centre => {}
            // A bare name instead of `active NAME` gets its own message below.
            (None, None) if !p.pivots.is_empty() => {}
            (None, None) => errors.push(
                p.token.span(),
                format!("pair `{letter}` in chain `{}` is neither `active NAME` nor `passive`: an active pair names its joint variable, e.g. `{letter}(active q1)`", chain.name),
            ),
            (Some(active), None) => match accepts.variables {
                None => errors.push(active.span(), format!("an active `{letter}` pair is not modelled: make it `passive` and drive the chain with another pair")),
                Some(n) if p.variables.len() != n => errors.push(
                    p.token.span(),
                    format!("an active `{letter}` pair has {n} joint variable{}, found {}", if n == 1 { "" } else { "s" }, p.variables.len()),
                ),
                Some(_) => {}
            },
            (None, Some(pas)) => {
                if !accepts.passive {
                    errors.push(pas.span(), format!("a passive `{letter}` pair is not modelled: its constraint is not polynomial of degree ≤ 2 (Section 2.2); make it active"));
                }
            }
        }
        // Arguments the pair kind does not take.
        if let Some((a, _)) = &p.axis {
            if accepts.axis == Need::No {
                errors.push(a.span(), format!("pair `{letter}` takes no `axis`"));
            }
        } else if p.kind == PairKind::U && p.active.is_some() {
            errors.push(p.token.span(), format!("an active `U` in chain `{}` needs its first axis, `U(C, axis = P -> Q, active a b)`: its first input turns about P -> Q, its second about the axis perpendicular to it", chain.name));
        } else if accepts.axis == Need::Required {
            errors.push(p.token.span(), format!("pair `{letter}` in chain `{}` needs its axis: `axis = A -> B`, two pivots on the axis", chain.name));
        }
        if let Some(off) = &p.offset {
            if accepts.offset {
                self.check_coord(off, errors);
            } else {
                errors.push(
                    off.span(),
                    format!("`offset` belongs to a prismatic pair `P`, not `{letter}`"),
                );
            }
        }
        if let Some(lead) = &p.lead {
            if accepts.lead == Need::No {
                errors.push(
                    lead.span(),
                    format!("`lead` belongs to a helical pair `H`, not `{letter}`"),
                );
            } else {
                self.check_coord(lead, errors);
            }
        } else if accepts.lead == Need::Required {
            errors.push(
                p.token.span(),
                format!("a helical pair `{letter}` needs its `lead = ...`"),
            );
        }
        if let Some((a, b)) = &p.axis {
            for q in [a, b] {
                if self.pivot_link(q).is_none() {
                    errors.push(q.span(), format!("the axis of pair `{letter}` names `{q}`, which is not a declared pivot"));
                }
            }
            if a == b {
                errors.push(
                    b.span(),
                    format!(
                        "the axis of pair `{letter}` is given by coincident points `{a}` and `{b}`"
                    ),
                );
            }
        }
        if !accepts.centre {
            for extra in &p.pivots {
                let msg = if p.passive.is_some() {
                    format!("a passive pair has no joint variable: remove `{extra}` or write `{letter}(active {extra})`")
                } else if p.active.is_none() {
                    format!("`{extra}` is not an argument of pair `{letter}`: an active pair names its joint variable, `{letter}(active {extra})`")
                } else {
                    format!("pair `{letter}` takes no pivot: `{extra}` is out of place (its axis is `axis = A -> B`)")
                };
                errors.push(extra.span(), msg);
            }
            return;
        }
        if p.pivots.len() != 1 {
            errors.push(p.token.span(), format!("pair `{letter}` in chain `{}` names its centre: one pivot, e.g. `{letter}(G1)`", chain.name));
        }
        // An unknown neighbour link, or a chain that stops at a pair, is reported already;
        // resolving pivots against it would only add noise.
        let unknown = |l: Option<&Ident>| l.is_some_and(|l| self.link(l).is_none());
        if at_end || unknown(before) || unknown(after) {
            return;
        }
        let adjacent: Vec<&LinkDecl> = [before, after]
            .into_iter()
            .flatten()
            .filter_map(|l| self.link(l))
            .collect();
        for pivot in &p.pivots {
            if !adjacent
                .iter()
                .any(|l| l.pivots.iter().any(|q| q.name == *pivot))
            {
                let names: Vec<String> = adjacent.iter().map(|l| format!("`{}`", l.name)).collect();
                errors.push(pivot.span(), format!("pair `{letter}` in chain `{}` references unknown pivot `{pivot}`: it is on neither of the links it joins ({})", chain.name, names.join(", ")));
            }
        }
    }

    /// The link declaring pivot `q`.
    pub fn pivot_link(&self, q: &Ident) -> Option<&LinkDecl> {
        self.all_links()
            .find(|l| l.pivots.iter().any(|p| p.name == *q))
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Need {
    No,
    Optional,
    Required,
}

/// What each pair kind takes: the one table every argument is checked against.
struct Accepts {
    /// Names its centre pivot (`S(C)`, `U(C, ...)`).
    centre: bool,
    axis: Need,
    offset: bool,
    lead: Need,
    /// Joint variables when active; `None`: no active form is modelled.
    variables: Option<usize>,
    /// Whether a passive form is modelled (degree ≤ 2).
    passive: bool,
}

impl Accepts {
    fn of(kind: PairKind) -> Accepts {
        let base = Accepts {
            centre: false,
            axis: Need::Required,
            offset: false,
            lead: Need::No,
            variables: Some(1),
            passive: true,
        };
        match kind {
            // Active: yaw, pitch and roll of the link after it relative to the link before.
            PairKind::S => Accepts {
                centre: true,
                axis: Need::No,
                variables: Some(3),
                ..base
            },
            // Active: the turns about its first and its second axis.
            PairKind::U => Accepts {
                centre: true,
                axis: Need::Optional,
                variables: Some(2),
                ..base
            },
            PairKind::R => base,
            PairKind::P => Accepts {
                axis: Need::Optional,
                offset: true,
                ..base
            },
            PairKind::C => Accepts {
                variables: Some(2),
                ..base
            },
            PairKind::H => Accepts {
                lead: Need::Required,
                passive: false,
                ..base
            },
        }
    }
}

fn neighbour(items: &[ChainItem], k: usize, forward: bool) -> Option<&Ident> {
    let idx = if forward {
        k.checked_add(1)?
    } else {
        k.checked_sub(1)?
    };
    match items.get(idx)? {
        ChainItem::Link(l) => Some(l),
        ChainItem::Pair(_) => None,
    }
}

/// The inputs in chain order, each with the pairs it drives; a name used by several pairs must
/// be `shared` at each, and mean the same quantity.
fn inputs(chains: &[ChainDecl], errors: &mut Errors) -> Vec<InputSymbol> {
    let mut out: Vec<InputSymbol> = Vec::new();
    let mut shared_at: Vec<Vec<bool>> = Vec::new();
    for c in chains {
        for item in &c.items {
            let ChainItem::Pair(p) = item else { continue };
            if p.active.is_none() {
                continue;
            }
            for (k, v) in p.variables.iter().enumerate() {
                let quantity = Quantity::of(p.kind, k);
                let shared = p.shared;
                match out.iter().position(|i| i.name == *v) {
                    None => {
                        out.push(InputSymbol {
                            name: v.clone(),
                            quantity,
                            shared,
                            uses: vec![(c.name.to_string(), v.span())],
                        });
                        shared_at.push(vec![shared]);
                    }
                    Some(i) => {
                        let first = &out[i];
                        let letter = p.kind.letter();
                        if !(shared && first.shared) {
                            errors.push(v.span(), format!(
                                "duplicate joint variable `{v}`: it drives a pair in chain `{}` already; an input that drives several pairs is declared `shared` at each, e.g. `{letter}(active shared {v}, ...)`",
                                first.uses[0].0
                            ));
                        } else if quantity != first.quantity {
                            errors.push(v.span(), format!(
                                "shared input `{v}` is {} in chain `{}` but {} here: an input shared by several pairs measures the same quantity in each",
                                first.quantity.describe(), first.uses[0].0, quantity.describe()
                            ));
                        }
                        out[i].uses.push((c.name.to_string(), v.span()));
                        shared_at[i].push(shared);
                    }
                }
            }
        }
    }
    for i in &out {
        if i.shared && i.uses.len() == 1 {
            errors.push(i.uses[0].1, format!(
                "input `{}` is declared `shared` but drives one pair only: `shared` is for an input that several pairs share (declare it at each of them)",
                i.name
            ));
        }
    }
    out
}

/// `home = inputs(...)` names every input once, and nothing else.
fn home_inputs(
    span: Span,
    values: &[(Ident, crate::front::ast::Number)],
    inputs: &[InputSymbol],
    errors: &mut Errors,
) {
    for (k, (name, _)) in values.iter().enumerate() {
        if values[..k].iter().any(|(n, _)| n == name) {
            errors.push(
                name.span(),
                format!("input `{name}` is given twice in `home`"),
            );
        } else if !inputs.iter().any(|i| i.name == *name) {
            let known: Vec<String> = inputs.iter().map(|i| format!("`{}`", i.name)).collect();
            errors.push(
                name.span(),
                format!(
                    "`home` gives a value to `{name}`, which is not an input; the inputs are {}",
                    known.join(", ")
                ),
            );
        }
    }
    let missing: Vec<String> = inputs
        .iter()
        .filter(|i| !values.iter().any(|(n, _)| *n == i.name))
        .map(|i| format!("`{}`", i.name))
        .collect();
    if !missing.is_empty() {
        errors.push(
            span,
            format!(
                "`home = inputs(...)` gives every input its value; missing: {}",
                missing.join(", ")
            ),
        );
    }
}

fn unique<'a>(names: impl Iterator<Item = &'a Ident>, what: &str, errors: &mut Errors) {
    let mut seen: HashMap<String, &Ident> = HashMap::new();
    for n in names {
        if let Some(first) = seen.get(&n.to_string()) {
            let _ = first;
            errors.push(n.span(), format!("duplicate {what} `{n}`"));
        } else {
            seen.insert(n.to_string(), n);
        }
    }
}
