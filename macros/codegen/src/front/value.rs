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
//! moves the coordinate), and so does an expression that names parameters: it is kept
//! ([`Term`]) and the generated `from_geometry` evaluates it again. An expression of numbers
//! alone is a number. A parameter's own value may be an expression of the ones before it; it
//! is evaluated where it is declared (the parameters are independent at run time).

use proc_macro2::Span;
use syn::parse::ParseStream;
use syn::{parenthesized, token, Ident, LitFloat, LitInt, Result, Token};

/// A number as written, evaluated, with its span.
#[derive(Clone)]
pub struct Number {
    pub value: f64,
    pub span: Span,
}

/// A coordinate: a bare parameter (linked to it at run time), a formula of parameters (kept,
/// so that the coordinate follows them at run time; its value as declared), or a value.
#[derive(Clone)]
pub enum Coord {
    Literal(Number),
    Param(Ident),
    /// Boxed: a coordinate is mostly a number, and pairs hold several.
    Formula(Box<(Number, Term)>),
}

impl Coord {
    /// Calls `f` on every parameter it follows at run time.
    pub fn each_param(&self, f: &mut impl FnMut(&Ident)) {
        match self {
            Coord::Literal(_) => {}
            Coord::Param(p) => f(p),
            Coord::Formula(formula) => formula.1.each_param(f),
        }
    }

    pub fn span(&self) -> Span {
        match self {
            Coord::Literal(n) => n.span,
            Coord::Formula(f) => f.0.span,
            Coord::Param(i) => i.span(),
        }
    }
}

/// An expression as written.
#[derive(Clone, Debug)]
pub enum Term {
    Num(f64),
    Param(Ident),
    Neg(Box<Term>),
    Bin(BinOp, Box<Term>, Box<Term>),
    Call(Func, Box<Term>),
}

#[derive(Clone, Copy, Debug)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

#[derive(Clone, Copy, Debug)]
pub enum Func {
    Sqrt,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
}

impl Term {
    /// Its value, the parameters at their values in `scope` (every name in it is there: the
    /// parser checked).
    pub fn eval(&self, scope: &Scope) -> f64 {
        match self {
            Term::Num(x) => *x,
            Term::Param(p) => scope
                .iter()
                .find(|(n, _)| p == n)
                .map_or(f64::NAN, |(_, v)| *v),
            Term::Neg(a) => -a.eval(scope),
            Term::Bin(op, a, b) => {
                let (a, b) = (a.eval(scope), b.eval(scope));
                match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    BinOp::Div => a / b,
                }
            }
            Term::Call(f, a) => {
                let x = a.eval(scope);
                match f {
                    Func::Sqrt => x.sqrt(),
                    Func::Sin => x.sin(),
                    Func::Cos => x.cos(),
                    Func::Tan => x.tan(),
                    Func::Asin => x.asin(),
                    Func::Acos => x.acos(),
                    Func::Atan => x.atan(),
                }
            }
        }
    }

    /// Calls `f` on every parameter it names.
    pub fn each_param(&self, f: &mut impl FnMut(&Ident)) {
        match self {
            Term::Num(_) => {}
            Term::Param(p) => f(p),
            Term::Neg(a) | Term::Call(_, a) => a.each_param(f),
            Term::Bin(_, a, b) => {
                a.each_param(f);
                b.each_param(f);
            }
        }
    }

    /// Whether it names a parameter.
    pub fn has_param(&self) -> bool {
        match self {
            Term::Num(_) => false,
            Term::Param(_) => true,
            Term::Neg(a) | Term::Call(_, a) => a.has_param(),
            Term::Bin(_, a, b) => a.has_param() || b.has_param(),
        }
    }
}

/// The parameters declared so far, with their values.
pub type Scope = [(String, f64)];

/// A coordinate: a bare parameter, a formula of parameters, or a value.
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
    let (number, term) = parsed(input, scope)?;
    Ok(if term.has_param() {
        Coord::Formula(Box::new((number, term)))
    } else {
        Coord::Literal(number)
    })
}

fn is_end_after_ident(input: ParseStream) -> bool {
    let fork = input.fork();
    let _ = fork.parse::<Ident>();
    fork.is_empty()
}

/// A finite value.
pub fn value(input: ParseStream, scope: &Scope) -> Result<Number> {
    parsed(input, scope).map(|(n, _)| n)
}

/// An expression and its value, which must be finite.
fn parsed(input: ParseStream, scope: &Scope) -> Result<(Number, Term)> {
    let span = input.span();
    let term = sum(input, scope)?;
    let v = term.eval(scope);
    if !v.is_finite() {
        return Err(syn::Error::new(
            span,
            "a coordinate must be a finite number",
        ));
    }
    Ok((Number { value: v, span }, term))
}

fn sum(input: ParseStream, scope: &Scope) -> Result<Term> {
    let mut v = product(input, scope)?;
    loop {
        let op = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinOp::Add
        } else if input.peek(Token![-]) && !input.peek(Token![->]) {
            input.parse::<Token![-]>()?;
            BinOp::Sub
        } else {
            return Ok(v);
        };
        v = Term::Bin(op, Box::new(v), Box::new(product(input, scope)?));
    }
}

fn product(input: ParseStream, scope: &Scope) -> Result<Term> {
    let mut v = factor(input, scope)?;
    loop {
        let op = if input.peek(Token![*]) {
            input.parse::<Token![*]>()?;
            BinOp::Mul
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinOp::Div
        } else {
            return Ok(v);
        };
        v = Term::Bin(op, Box::new(v), Box::new(factor(input, scope)?));
    }
}

fn factor(input: ParseStream, scope: &Scope) -> Result<Term> {
    if input.peek(Token![-]) {
        input.parse::<Token![-]>()?;
        return Ok(Term::Neg(Box::new(factor(input, scope)?)));
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
        return Ok(Term::Num(input.parse::<LitFloat>()?.base10_parse::<f64>()?));
    }
    if input.peek(LitInt) {
        return Ok(Term::Num(input.parse::<LitInt>()?.base10_parse::<f64>()?));
    }
    if input.peek(Ident) {
        let name: Ident = input.parse()?;
        if input.peek(token::Paren) {
            let arg;
            parenthesized!(arg in input);
            let x = sum(&arg, scope)?;
            return Ok(Term::Call(function(&name)?, Box::new(x)));
        }
        if name == "pi" {
            return Ok(Term::Num(std::f64::consts::PI));
        }
        if !scope.iter().any(|(n, _)| name == n) {
            return Err(unknown(&name));
        }
        return Ok(Term::Param(name));
    }
    Err(input.error("expected a number, a parameter name or an expression"))
}

fn function(name: &Ident) -> Result<Func> {
    Ok(match name.to_string().as_str() {
        "sqrt" => Func::Sqrt,
        "sin" => Func::Sin,
        "cos" => Func::Cos,
        "tan" => Func::Tan,
        "asin" => Func::Asin,
        "acos" => Func::Acos,
        "atan" => Func::Atan,
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
