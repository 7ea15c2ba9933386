//! Name resolution, the one pass after parsing: links, pivots and joint variables are entered
//! in one table ([`Symbols`]), parameters and every name a declaration uses are checked against
//! it, and every pair's arguments against the one table of what each pair kind takes
//! ([`crate::front::accepts`]); the inputs in [`crate::front::inputs`]. Never builds tokens; collects every mistake into the shared [`Errors`] so that
//! the user sees them all in one build. Once they pass, the declaration is lowered to its
//! resolved form ([`crate::front::resolved`]): names become typed ids, and no later phase looks
//! anything up by name.
//!
//! Pivot names are global: an axis `A -> B` names its pivots without their links, so one name
//! on two links is an error here rather than a silent choice later. A joint variable names one
//! input; several pairs may share it only where each declares it `active shared NAME`, and
//! only if it means the same quantity (an angle, or a length) in each.

use crate::front::accepts::{Accepts, Need};
use crate::front::ast::{ChainItem, Coord, LinkDecl, Mechanism, PairDecl, PairKind};
pub use crate::front::errors::Errors;
use crate::front::inputs::{home_inputs, inputs, InputSymbol};
use crate::front::resolved::Decl;
use std::collections::HashMap;
use syn::Ident;

/// A pivot: its name and the link (index into [`Symbols::links`]) that declares it.
pub struct PivotSymbol {
    pub name: Ident,
    pub link: usize,
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
                // A cylinder with one freedom driven is two pairs: say how to write them.
                Some(_) if p.variables.len() == 1 && letter == "C" => errors.push(
                    p.token.span(),
                    format!("an active `C` pair has 2 joint variables (`active theta z`), found 1; to drive only one of its freedoms, declare its two pairs on one axis with a link between: the turn, `R(active {v}, axis = A -> B) - sleeve - P(passive, axis = S -> Sx)`, or the slide, `P(active {v}, axis = A -> B) - slider - R(passive, axis = S -> Sx)`", v = p.variables[0]),
                ),
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
