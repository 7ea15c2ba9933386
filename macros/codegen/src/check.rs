//! Name-level validation of a declaration. Never builds tokens; collects every mistake so the
//! user sees them all in one build.

use crate::ast::{ChainItem, Coord, LinkDecl, Mechanism, PairDecl};
use std::collections::HashMap;
use syn::Ident;

#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    pub fn push(&mut self, span: proc_macro2::Span, msg: impl std::fmt::Display) {
        let e = syn::Error::new(span, msg);
        match &mut self.0 {
            Some(all) => all.combine(e),
            None => self.0 = Some(e),
        }
    }

    pub fn finish(self) -> syn::Result<()> {
        match self.0 {
            Some(e) => Err(e),
            None => Ok(()),
        }
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

    pub fn validate(&self) -> syn::Result<()> {
        let mut errors = Errors::default();
        if self.base.is_none() {
            errors.push(self.name.span(), "mechanism has no `base { ... }` link");
        }
        if self.platform.is_none() {
            errors.push(self.name.span(), "mechanism has no `platform { ... }` link");
        }
        if self.chains.is_empty() {
            errors.push(self.name.span(), "mechanism has no `chain`: declare at least one `chain NAME = base - ... - platform;`");
        }
        unique(
            self.params.iter().map(|p| &p.name),
            "parameter",
            &mut errors,
        );
        unique(self.all_links().map(|l| &l.name), "link", &mut errors);
        unique(self.chains.iter().map(|c| &c.name), "chain", &mut errors);
        let variables = self.chains.iter().flat_map(|c| {
            c.items.iter().filter_map(|i| match i {
                ChainItem::Pair(p) => Some(p.variables.iter()),
                ChainItem::Link(_) => None,
            })
        });
        unique(variables.flatten(), "joint variable", &mut errors);

        for link in self.all_links() {
            unique(link.pivots.iter().map(|p| &p.name), "pivot", &mut errors);
            for pivot in &link.pivots {
                for c in &pivot.coords {
                    self.check_coord(c, &mut errors);
                }
            }
            if let Some(c) = &link.length {
                self.check_coord(c, &mut errors);
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
            self.check_chain(chain, &mut errors);
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

    fn check_chain(&self, chain: &crate::ast::ChainDecl, errors: &mut Errors) {
        let items = &chain.items;
        match items.first() {
            Some(ChainItem::Link(l)) if l == "base" => {}
            Some(ChainItem::Link(l)) if self.link(l).is_none() => {}
            Some(ChainItem::Link(l)) => errors.push(
                l.span(),
                format!("chain `{}` must start at `base`, not `{l}`", chain.name),
            ),
            _ => errors.push(
                chain.name.span(),
                format!("chain `{}` must start at `base`", chain.name),
            ),
        }
        match items.last() {
            Some(ChainItem::Link(l)) if l == "platform" => {}
            Some(ChainItem::Link(l)) if self.link(l).is_none() => {}
            Some(ChainItem::Link(l)) => errors.push(l.span(), format!("chain `{}` does not reach the moving platform: it must end at `platform`, not `{l}`", chain.name)),
            _ => errors.push(chain.name.span(), format!("chain `{}` does not reach the moving platform: it must end at `platform`", chain.name)),
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
        chain: &crate::ast::ChainDecl,
        p: &PairDecl,
        before: Option<&Ident>,
        after: Option<&Ident>,
        at_end: bool,
        errors: &mut Errors,
    ) {
        let letter = p.kind.letter();
        match (&p.active, &p.passive) {
            (Some(_), Some(pas)) => errors.push(pas.span(), format!("pair `{letter}` is both `active` and `passive`")),
            (None, None) if matches!(p.kind, crate::ast::PairKind::S | crate::ast::PairKind::U) => {}
            // A bare name instead of `active NAME` gets its own message below.
            (None, None) if !p.pivots.is_empty() => {}
            (None, None) => errors.push(
                p.token.span(),
                format!("pair `{letter}` in chain `{}` is neither `active NAME` nor `passive`: an active pair names its joint variable, e.g. `{letter}(active q1)`", chain.name),
            ),
            _ => {}
        }
        let takes_pivots = matches!(p.kind, crate::ast::PairKind::S | crate::ast::PairKind::U);
        if !takes_pivots {
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
        if let Some((a, b)) = &p.axis {
            let link_before = before.and_then(|l| self.link(l));
            for q in [a, b] {
                if !link_before.is_some_and(|l| l.pivots.iter().any(|r| r.name == *q)) {
                    errors.push(q.span(), format!("the axis of pair `{letter}` names `{q}`, which is not a pivot of the link before the pair"));
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
        if let Some(lead) = &p.lead {
            if p.kind != crate::ast::PairKind::H {
                errors.push(
                    lead.span(),
                    format!("`lead` belongs to a helical pair `H`, not `{letter}`"),
                );
            }
            self.check_coord(lead, errors);
        }
        if let Some(off) = &p.offset {
            self.check_coord(off, errors);
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
