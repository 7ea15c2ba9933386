//! The `mechanism!` surface syntax, parsed into a tree that keeps every token's span.
//!
//! ```text
//! mechanism   := attrs vis "struct" IDENT ";" section*
//! section     := "params" "{" (IDENT "=" number ","?)* "}"
//!              | "base" "{" pivot* "}"
//!              | "platform" ("(" option ("," option)* ")")? "{" pivot* "}"
//! option      := "frame" "=" "[" IDENT "," IDENT "," IDENT "]" | "form" "=" ("coplanar" | "general")
//!              | "home" "=" home                      (a pose or the joint values, see `home.rs`)
//!              | "link" IDENT "{" (pivot | "length" "=" coord ","?)* "}"
//!              | "chain" IDENT "=" item ("-" item)* ";"
//! pivot       := IDENT "=" "[" coord "," coord "," coord "]" ","?
//! coord       := IDENT | value         (a parameter declared in `params`, or see `value.rs`)
//! item        := IDENT                     (a link: `base`, `platform` or a declared link)
//!              | PAIR "(" arg ("," arg)* ")"
//! PAIR        := "R" | "P" | "C" | "H" | "S" | "U"
//! arg         := "active" "shared"? IDENT+ | "passive" | IDENT (a pivot)
//!              | "axis" "=" IDENT "->" IDENT | "offset" "=" coord | "lead" "=" coord
//! ```

pub use crate::front::value::{Coord, Number};
use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::{bracketed, parenthesized, token, Attribute, Ident, Result, Token, Visibility};

pub struct Mechanism {
    pub attrs: Vec<Attribute>,
    pub vis: Visibility,
    pub name: Ident,
    pub params: Vec<Param>,
    pub base: Option<LinkDecl>,
    pub platform: Option<LinkDecl>,
    pub links: Vec<LinkDecl>,
    pub chains: Vec<ChainDecl>,
}

pub struct Param {
    pub name: Ident,
    pub default: Number,
}

pub struct Pivot {
    pub name: Ident,
    pub coords: [Coord; 3],
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum LinkRole {
    Base,
    Platform,
    Intermediate,
}

pub struct LinkDecl {
    pub role: LinkRole,
    pub name: Ident,
    pub pivots: Vec<Pivot>,
    pub length: Option<Coord>,
    pub frame: Option<Vec<Ident>>,
    /// `form = coplanar | general`: the rigid-body form of the platform (default: from the
    /// declared geometry).
    pub form: Option<Ident>,
    /// `home = [yaw, pitch, roll, x, y, z]`: the platform's reference pose, checked at
    /// compile time and offered as `home_start()`.
    pub home: Option<(Span, [f64; 6])>,
    /// `home = inputs(q1 = .., ...)`: the joint values of the reference configuration instead.
    pub home_inputs: Option<(Span, Vec<(Ident, Number)>)>,
}

pub struct ChainDecl {
    pub name: Ident,
    pub items: Vec<ChainItem>,
}

pub enum ChainItem {
    Link(Ident),
    Pair(PairDecl),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum PairKind {
    R,
    P,
    C,
    H,
    S,
    U,
}

impl PairKind {
    pub fn letter(self) -> &'static str {
        match self {
            PairKind::R => "R",
            PairKind::P => "P",
            PairKind::C => "C",
            PairKind::H => "H",
            PairKind::S => "S",
            PairKind::U => "U",
        }
    }
}

pub struct PairDecl {
    pub kind: PairKind,
    pub token: Ident,
    pub active: Option<Ident>,
    /// `active shared NAME`: the input drives other pairs too.
    pub shared: bool,
    pub variables: Vec<Ident>,
    pub passive: Option<Ident>,
    pub pivots: Vec<Ident>,
    pub axis: Option<(Ident, Ident)>,
    pub offset: Option<Coord>,
    pub lead: Option<Coord>,
}

mod kw {
    syn::custom_keyword!(params);
    syn::custom_keyword!(base);
    syn::custom_keyword!(platform);
    syn::custom_keyword!(link);
    syn::custom_keyword!(chain);
    syn::custom_keyword!(frame);
    syn::custom_keyword!(form);
    syn::custom_keyword!(home);
    syn::custom_keyword!(length);
    syn::custom_keyword!(active);
    syn::custom_keyword!(passive);
    syn::custom_keyword!(shared);
    syn::custom_keyword!(axis);
    syn::custom_keyword!(offset);
    syn::custom_keyword!(lead);
}

impl Parse for Mechanism {
    fn parse(input: ParseStream) -> Result<Self> {
        let attrs = input.call(Attribute::parse_outer)?;
        let vis: Visibility = input.parse()?;
        input.parse::<Token![struct]>()?;
        let name: Ident = input.parse()?;
        input.parse::<Token![;]>()?;
        let mut m = Mechanism {
            attrs,
            vis,
            name,
            params: Vec::new(),
            base: None,
            platform: None,
            links: Vec::new(),
            chains: Vec::new(),
        };
        // The parameters declared so far: later values may use them.
        let mut scope: Vec<(String, f64)> = Vec::new();
        while !input.is_empty() {
            let look = input.lookahead1();
            if look.peek(kw::params) {
                input.parse::<kw::params>()?;
                let body;
                syn::braced!(body in input);
                while !body.is_empty() {
                    let name: Ident = body.parse()?;
                    body.parse::<Token![=]>()?;
                    let default = crate::front::value::value(&body, &scope)?;
                    scope.push((name.to_string(), default.value));
                    m.params.push(Param { name, default });
                    if !body.is_empty() {
                        body.parse::<Token![,]>()?;
                    }
                }
            } else if look.peek(kw::base) {
                let kw: kw::base = input.parse()?;
                let link = parse_link_body(
                    input,
                    LinkRole::Base,
                    Ident::new("base", kw.span),
                    None,
                    &scope,
                )?;
                if m.base.is_some() {
                    return Err(syn::Error::new(
                        kw.span,
                        "the `base` link is declared twice",
                    ));
                }
                m.base = Some(link);
            } else if look.peek(kw::platform) {
                let kw: kw::platform = input.parse()?;
                let mut frame = None;
                let mut form = None;
                let mut home = None;
                let mut home_inputs = None;
                if input.peek(token::Paren) {
                    let args;
                    parenthesized!(args in input);
                    while !args.is_empty() {
                        if args.peek(kw::frame) {
                            args.parse::<kw::frame>()?;
                            args.parse::<Token![=]>()?;
                            let list;
                            bracketed!(list in args);
                            let names = list.parse_terminated(Ident::parse, Token![,])?;
                            frame = Some(names.into_iter().collect());
                        } else if args.peek(kw::form) {
                            args.parse::<kw::form>()?;
                            args.parse::<Token![=]>()?;
                            let f: Ident = args.parse()?;
                            if f != "coplanar" && f != "general" {
                                return Err(syn::Error::new(
                                    f.span(),
                                    "expected `form = coplanar` or `form = general`",
                                ));
                            }
                            form = Some(f);
                        } else if args.peek(kw::home) {
                            let kw: kw::home = args.parse()?;
                            args.parse::<Token![=]>()?;
                            if home.is_some() || home_inputs.is_some() {
                                return Err(syn::Error::new(kw.span, "`home` is given twice"));
                            }
                            match crate::front::home::parse(&args, &scope)? {
                                crate::front::home::Home::Pose(p) => home = Some((kw.span, p)),
                                crate::front::home::Home::Inputs(v) => {
                                    home_inputs = Some((kw.span, v))
                                }
                            }
                        } else {
                            return Err(args.error(
                                "expected `frame = [A, B, C]`, `form = coplanar | general` or `home = [yaw, pitch, roll, x, y, z]`",
                            ));
                        }
                        if !args.is_empty() {
                            args.parse::<Token![,]>()?;
                        }
                    }
                }
                let mut link = parse_link_body(
                    input,
                    LinkRole::Platform,
                    Ident::new("platform", kw.span),
                    frame,
                    &scope,
                )?;
                link.form = form;
                link.home = home;
                link.home_inputs = home_inputs;
                if m.platform.is_some() {
                    return Err(syn::Error::new(
                        kw.span,
                        "the `platform` link is declared twice",
                    ));
                }
                m.platform = Some(link);
            } else if look.peek(kw::link) {
                input.parse::<kw::link>()?;
                let name: Ident = input.parse()?;
                m.links.push(parse_link_body(
                    input,
                    LinkRole::Intermediate,
                    name,
                    None,
                    &scope,
                )?);
            } else if look.peek(kw::chain) {
                input.parse::<kw::chain>()?;
                let name: Ident = input.parse()?;
                input.parse::<Token![=]>()?;
                let mut items = vec![parse_item(input, &scope)?];
                while input.peek(Token![-]) {
                    input.parse::<Token![-]>()?;
                    items.push(parse_item(input, &scope)?);
                }
                input.parse::<Token![;]>()?;
                m.chains.push(ChainDecl { name, items });
            } else {
                return Err(look.error());
            }
        }
        Ok(m)
    }
}

fn parse_link_body(
    input: ParseStream,
    role: LinkRole,
    name: Ident,
    frame: Option<Vec<Ident>>,
    scope: &crate::front::value::Scope,
) -> Result<LinkDecl> {
    let body;
    syn::braced!(body in input);
    let mut link = LinkDecl {
        role,
        name,
        pivots: Vec::new(),
        length: None,
        frame,
        form: None,
        home: None,
        home_inputs: None,
    };
    while !body.is_empty() {
        if body.peek(kw::length) && body.peek2(Token![=]) {
            let kw: kw::length = body.parse()?;
            body.parse::<Token![=]>()?;
            if link.length.is_some() {
                return Err(syn::Error::new(kw.span, "`length` is given twice"));
            }
            link.length = Some(crate::front::value::coord(&body, scope)?);
        } else {
            let name: Ident = body.parse()?;
            body.parse::<Token![=]>()?;
            let list;
            let bracket = bracketed!(list in body);
            let mut coords: Vec<Coord> = Vec::new();
            while !list.is_empty() {
                coords.push(crate::front::value::coord(&list, scope)?);
                if !list.is_empty() {
                    list.parse::<Token![,]>()?;
                }
            }
            let count = coords.len();
            let coords: [Coord; 3] = coords.try_into().map_err(|_| {
                syn::Error::new(
                    bracket.span.join(),
                    format!("pivot `{name}` has {count} coordinates; a pivot has exactly three, `[x, y, z]`"),
                )
            })?;
            link.pivots.push(Pivot { name, coords });
        }
        if !body.is_empty() {
            body.parse::<Token![,]>()?;
        }
    }
    Ok(link)
}

fn parse_item(input: ParseStream, scope: &crate::front::value::Scope) -> Result<ChainItem> {
    let name: Ident = input.parse()?;
    if !input.peek(token::Paren) {
        return Ok(ChainItem::Link(name));
    }
    let kind = match name.to_string().as_str() {
        "R" => PairKind::R,
        "P" => PairKind::P,
        "C" => PairKind::C,
        "H" => PairKind::H,
        "S" => PairKind::S,
        "U" => PairKind::U,
        other => {
            return Err(syn::Error::new(
                name.span(),
                format!(
                    "unknown lower pair `{other}`: expected one of `R`, `P`, `C`, `H`, `S`, `U`"
                ),
            ))
        }
    };
    let args;
    parenthesized!(args in input);
    let mut pair = PairDecl {
        kind,
        token: name,
        active: None,
        shared: false,
        variables: Vec::new(),
        passive: None,
        pivots: Vec::new(),
        axis: None,
        offset: None,
        lead: None,
    };
    while !args.is_empty() {
        if args.peek(kw::active) {
            let kw: kw::active = args.parse()?;
            pair.active = Some(Ident::new("active", kw.span));
            // `active shared q1`: one input driving several pairs.
            if args.peek(kw::shared) && args.peek2(Ident) {
                args.parse::<kw::shared>()?;
                pair.shared = true;
            }
            pair.variables.push(args.parse()?);
            // `C` and `H`-like pairs may carry more than one joint variable: `active theta z`.
            while args.peek(Ident) && !args.peek2(Token![=]) {
                pair.variables.push(args.parse()?);
            }
        } else if args.peek(kw::passive) {
            let kw: kw::passive = args.parse()?;
            pair.passive = Some(Ident::new("passive", kw.span));
            // `passive q1` is a mistake the checker explains; keep the name for that.
            if args.peek(Ident) && !args.peek2(Token![=]) {
                pair.pivots.push(args.parse()?);
            }
        } else if args.peek(kw::axis) && args.peek2(Token![=]) {
            args.parse::<kw::axis>()?;
            args.parse::<Token![=]>()?;
            let a: Ident = args.parse()?;
            args.parse::<Token![->]>()?;
            let b: Ident = args.parse()?;
            pair.axis = Some((a, b));
        } else if args.peek(kw::offset) && args.peek2(Token![=]) {
            args.parse::<kw::offset>()?;
            args.parse::<Token![=]>()?;
            pair.offset = Some(crate::front::value::coord(&args, scope)?);
        } else if args.peek(kw::lead) && args.peek2(Token![=]) {
            args.parse::<kw::lead>()?;
            args.parse::<Token![=]>()?;
            pair.lead = Some(crate::front::value::coord(&args, scope)?);
        } else {
            pair.pivots.push(args.parse()?);
        }
        if !args.is_empty() {
            args.parse::<Token![,]>()?;
        }
    }
    Ok(ChainItem::Pair(pair))
}
