//! Numbers in a declaration: literals, parameters, and arithmetic on them.
//!
//! ```text
//! value   := term (("+" | "-") term)*
//! term    := factor (("*" | "/") factor)*
//! factor  := "-" factor | number | "pi" | IDENT | FUNC "(" value ")" | "(" value ")"
//! FUNC    := sqrt | sin | cos | tan | asin | acos | atan
//! ```
//!
//! A bare parameter name stays linked to its parameter (changing the parameter at run time
//! moves the coordinate); any other expression is evaluated where it is declared, with the
//! parameters' declared values.

use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{parenthesized, token, Ident, LitFloat, LitInt, Result, Token};

/// A number as written, evaluated, with its span.
#[derive(Clone)]
pub struct Number {
    pub value: f64,
    pub span: Span,
}

/// A coordinate: a bare parameter (linked to it at run time) or a value.
#[derive(Clone)]
pub enum Coord {
    Literal(Number),
    Param(Ident),
}

impl Coord {
    pub fn span(&self) -> Span {
        match self {
            Coord::Literal(n) => n.span,
            Coord::Param(i) => i.span(),
        }
    }
}

/// The parameters declared so far, with their values.
pub type Scope = [(String, f64)];

/// A coordinate: a bare parameter, or a value.
pub fn coord(input: ParseStream, scope: &Scope) -> Result<Coord> {
    let bare = input.peek(Ident)
        && !input.peek2(token::Paren)
        && (input.peek2(Token![,]) || is_end_after_ident(input));
    if bare {
        let name: Ident = input.fork().parse()?;
        if name != "pi" {
            return Ok(Coord::Param(input.parse()?));
        }
    }
    Ok(Coord::Literal(value(input, scope)?))
}

fn is_end_after_ident(input: ParseStream) -> bool {
    let fork = input.fork();
    let _ = fork.parse::<Ident>();
    fork.is_empty()
}

/// A finite value.
pub fn value(input: ParseStream, scope: &Scope) -> Result<Number> {
    let span = input.span();
    let v = sum(input, scope)?;
    if !v.is_finite() {
        return Err(syn::Error::new(
            span,
            "a coordinate must be a finite number",
        ));
    }
    Ok(Number { value: v, span })
}

fn sum(input: ParseStream, scope: &Scope) -> Result<f64> {
    let mut v = product(input, scope)?;
    loop {
        if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            v += product(input, scope)?;
        } else if input.peek(Token![-]) && !input.peek(Token![->]) {
            input.parse::<Token![-]>()?;
            v -= product(input, scope)?;
        } else {
            return Ok(v);
        }
    }
}

fn product(input: ParseStream, scope: &Scope) -> Result<f64> {
    let mut v = factor(input, scope)?;
    loop {
        if input.peek(Token![*]) {
            input.parse::<Token![*]>()?;
            v *= factor(input, scope)?;
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            v /= factor(input, scope)?;
        } else {
            return Ok(v);
        }
    }
}

fn factor(input: ParseStream, scope: &Scope) -> Result<f64> {
    if input.peek(Token![-]) {
        input.parse::<Token![-]>()?;
        return Ok(-factor(input, scope)?);
    }
    if input.peek(token::Paren) {
        let inner;
        parenthesized!(inner in input);
        let v = sum(&inner, scope)?;
        if !inner.is_empty() {
            return Err(inner.error("expected `)`"));
        }
        return Ok(v);
    }
    if input.peek(LitFloat) {
        return input.parse::<LitFloat>()?.base10_parse::<f64>();
    }
    if input.peek(LitInt) {
        return input.parse::<LitInt>()?.base10_parse::<f64>();
    }
    if input.peek(Ident) {
        let name: Ident = input.parse()?;
        if input.peek(token::Paren) {
            let arg;
            parenthesized!(arg in input);
            let x = sum(&arg, scope)?;
            return function(&name, x);
        }
        if name == "pi" {
            return Ok(std::f64::consts::PI);
        }
        return scope
            .iter()
            .find(|(n, _)| name == n)
            .map(|(_, v)| *v)
            .ok_or_else(|| unknown(&name));
    }
    Err(input.error("expected a number, a parameter name or an expression"))
}

fn function(name: &Ident, x: f64) -> Result<f64> {
    Ok(match name.to_string().as_str() {
        "sqrt" => x.sqrt(),
        "sin" => x.sin(),
        "cos" => x.cos(),
        "tan" => x.tan(),
        "asin" => x.asin(),
        "acos" => x.acos(),
        "atan" => x.atan(),
        other => {
            return Err(syn::Error::new(
                name.span(),
                format!("unknown function `{other}`: expected one of `sqrt`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan`"),
            ))
        }
    })
}

fn unknown(name: &Ident) -> syn::Error {
    syn::Error::new(
        name.span(),
        format!(
            "unknown parameter `{name}`: declare it in `params {{ {name} = ... }}` before its use"
        ),
    )
}
