//! The generator on mangled declarations: an error, never a panic. A stable, deterministic
//! cousin of the cargo-fuzz targets in `tests/fuzz`. (The file readers' half is in the
//! integration tests, `file_readers_robustness.rs`: it needs the CLI, this half only this crate;
//! here it keeps the generator out of the integration binary's dependencies.)

use proc_macro2::{TokenStream, TokenTree};

mod common;

use common::Rng;

const DECLARATION: &str = r#"
    pub struct M;
    params { rod = 170.0, h = 5.0 }
    base {
        A1 = [0.0, 100.0, 0.0], B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, h], B3 = [91.603, -41.340, 0.0],
        D1 = [1.0, 2.0, 3.0],
    }
    platform(frame = [G1, G2, G3]) { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
    link crank1 { C1 = [10.0, 10.0, 0.0] }
    link rod1 { length = rod }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1, offset = 2.0) - S(G1) - platform;
    chain leg2 = base - R(active q2, axis = A2 -> B2) - crank1 - S(C1) - rod1 - S(G2) - platform;
    chain leg3 = base - U(D1) - P(active L3) - S(G3) - platform;
    chain leg4 = base - S(D1) - P(active L4) - S(G1) - platform;
    chain leg5 = base - S(A3) - P(active L5) - S(G2) - platform;
"#;

/// Mechanisms of the general model: a five-bar with a point output, a 3-UPU, a 3-RPR, a
/// delta-like parallelogram on a crank.
const GENERAL: [&str; 4] = [
    r#"
    pub struct FiveBar;
    params { crank = 100.0 }
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, crank * sin(pi / 3.0) + 120.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
    "#,
    r#"
    pub struct Upu;
    base {
        A1 = [150.0, 0.0, 0.0], A1a = [150.0, 1.0, 0.0],
        A2 = [-75.0, 129.9038105676658, 0.0], A2a = [-75.86602540378444, 129.4038105676658, 0.0],
        A3 = [-75.0, -129.9038105676658, 0.0], A3a = [-74.13397459621556, -130.4038105676658, 0.0],
    }
    platform(home = quaternion([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 200.0])) {
        G1 = [60.0, 0.0, 0.0], G1a = [60.0, 1.0, 0.0],
        G2 = [-30.0, 51.96152422706632, 0.0], G2a = [-30.86602540378444, 51.46152422706632, 0.0],
        G3 = [-30.0, -51.96152422706632, 0.0], G3a = [-29.13397459621556, -52.46152422706632, 0.0],
    }
    chain leg1 = base - U(A1, axis = A1 -> A1a) - P(active L1) - U(G1, axis = G1 -> G1a) - platform;
    chain leg2 = base - U(A2, axis = A2 -> A2a) - P(active L2) - U(G2, axis = G2 -> G2a) - platform;
    chain leg3 = base - U(A3, axis = A3 -> A3a) - P(active L3) - U(G3, axis = G3 -> G3a) - platform;
    "#,
    r#"
    pub struct Rpr;
    params { a = 200.0, g = 60.0 }
    base {
        A1 = [a, 0.0, 0.0], A1z = [a, 0.0, 1.0],
        A2 = [-a / 2.0, a * sqrt(3.0) / 2.0, 0.0], A2z = [-a / 2.0, a * sqrt(3.0) / 2.0, 1.0],
        A3 = [-a / 2.0, -a * sqrt(3.0) / 2.0, 0.0], A3z = [-a / 2.0, -a * sqrt(3.0) / 2.0, 1.0],
    }
    platform(home = [0.3, 0.0, 0.0, 10.0, 5.0, 0.0]) {
        G1 = [g, 0.0, 0.0], G1z = [g, 0.0, 1.0],
        G2 = [-g / 2.0, g * sqrt(3.0) / 2.0, 0.0], G2z = [-g / 2.0, g * sqrt(3.0) / 2.0, 1.0],
        G3 = [-g / 2.0, -g * sqrt(3.0) / 2.0, 0.0], G3z = [-g / 2.0, -g * sqrt(3.0) / 2.0, 1.0],
    }
    link lower1 { }
    chain leg1 = base - R(passive, axis = A1 -> A1z) - lower1 - P(active L1) - R(passive, axis = G1 -> G1z) - platform;
    chain leg2 = base - R(passive, axis = A2 -> A2z) - P(active L2, offset = 1.0) - R(passive, axis = G2 -> G2z) - platform;
    chain leg3 = base - R(passive, axis = A3 -> A3z) - P(active L3) - R(passive, axis = G3 -> G3z) - platform;
    "#,
    r#"
    pub struct Parallelogram;
    params { rod = 250.0 }
    base { A1 = [100.0, 0.0, 0.0], B1 = [100.0, 1.0, 0.0], A2 = [0.0, 100.0, 0.0], B2 = [1.0, 100.0, 0.0], A3 = [0.0, -100.0, 0.0], B3 = [-1.0, -100.0, 0.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -200.0]) { F11 = [40.0, 30.0, 0.0], F12 = [40.0, -30.0, 0.0], F2 = [0.0, 40.0, 0.0], F3 = [0.0, -40.0, 0.0] }
    link arm1 { E11 = [200.0, 30.0, 0.0], E12 = [200.0, -30.0, 0.0] }
    link rod11 { length = rod } link rod12 { length = rod }
    chain a1 = base - R(active q1, axis = A1 -> B1) - arm1 - S(E11) - rod11 - S(F11) - platform;
    chain a1b = arm1 - S(E12) - rod12 - S(F12) - platform;
    chain a2 = base - S(A2) - P(active L2) - S(F2) - platform;
    chain a3 = base - S(A3) - P(active L3) - S(F3) - platform;
    chain a4 = base - S(B2) - P(active L4) - S(F11) - platform;
    chain a5 = base - S(B3) - P(active L5) - S(F12) - platform;
    "#,
];

fn flatten(ts: TokenStream, out: &mut Vec<String>) {
    for t in ts {
        match t {
            TokenTree::Group(g) => {
                let (open, close) = match g.delimiter() {
                    proc_macro2::Delimiter::Brace => ("{", "}"),
                    proc_macro2::Delimiter::Bracket => ("[", "]"),
                    proc_macro2::Delimiter::Parenthesis => ("(", ")"),
                    proc_macro2::Delimiter::None => ("", ""),
                };
                out.push(open.into());
                flatten(g.stream(), out);
                out.push(close.into());
            }
            other => out.push(other.to_string()),
        }
    }
}

#[test]
fn the_generator_survives_mangled_declarations() {
    mangle(DECLARATION, 99, true);
}

// One test per declaration of the general model, so that the harness runs them side by side.
#[test]
fn the_general_model_survives_a_mangled_five_bar() {
    mangle(GENERAL[0], 0, true);
}

#[test]
fn the_general_model_survives_a_mangled_3_upu() {
    mangle(GENERAL[1], 1, true);
}

#[test]
fn the_general_model_survives_a_mangled_3_rpr() {
    mangle(GENERAL[2], 2, true);
}

#[test]
fn the_general_model_survives_a_mangled_parallelogram() {
    mangle(GENERAL[3], 3, true);
}

/// Random edits of a declaration: each one is expanded or is a `compile_error!`, never a panic.
fn mangle(declaration: &str, seed: u64, valid: bool) {
    let base: TokenStream = declaration.parse().unwrap();
    match linkage_codegen::model(base.clone()) {
        Err(e) if valid => panic!("the unmangled declaration is valid: {e}"),
        _ => {}
    }
    let mut tokens = Vec::new();
    flatten(base, &mut tokens);
    let vocabulary = [
        "-", "->", ",", ";", "=", "base", "platform", "S", "P", "R", "H", "C", "U", "active",
        "passive", "axis", "G1", "A1", "0.0", "-1e3", "1e400", "crank1", "rod1", "frame", "length",
        "lead", "offset", "chain", "link", "[", "]", "(", ")", "{", "}", "*", "/", "sqrt", "pi",
        "home", "arm1", "P", "E12", "G1z", "A1z", "lower1", "distal1", "0", "1.0",
    ];
    let rounds: usize = std::env::var("LINKAGE_MANGLE_ROUNDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3000);
    let mut rng = Rng::new(seed);
    let mut rejected = 0;
    for _ in 0..rounds {
        let mut t = tokens.clone();
        for _ in 0..1 + rng.next_u64() % 4 {
            let i = (rng.next_u64() as usize) % t.len();
            match rng.next_u64() % 4 {
                0 => {
                    t.remove(i);
                }
                1 => t.insert(
                    i,
                    vocabulary[(rng.next_u64() as usize) % vocabulary.len()].to_string(),
                ),
                2 => t[i] = vocabulary[(rng.next_u64() as usize) % vocabulary.len()].to_string(),
                _ => {
                    let j = (rng.next_u64() as usize) % t.len();
                    t.swap(i, j);
                }
            }
        }
        // Unbalanced delimiters do not even lex: nothing reaches the macro then.
        let Ok(ts) = t.join(" ").parse::<TokenStream>() else {
            continue;
        };
        let expanded = linkage_codegen::expand(ts.clone()).to_string();
        if linkage_codegen::model(ts).is_err() {
            rejected += 1;
            assert!(expanded.contains("compile_error"));
        }
    }
    assert!(rejected > rounds / 3, "{rejected}");
}

/// A declaration in error expands to its errors and, in place of the type, an alias of the
/// declared visibility whose definition holds the first error (so that uses of the name add
/// no errors: `tests/ui`'s `a_mistake_adds_no_errors_where_the_type_is_used`); every error is
/// reported once.
#[test]
fn a_declaration_in_error_leaves_an_alias_holding_its_first_error() {
    // Two mistakes: an unknown pivot in one chain, a chain that misses the platform.
    let declaration = DECLARATION
        .replace("pub struct M;", "pub(crate) struct M;")
        .replace("S(G3) - platform;", "S(G9) - platform;")
        .replacen("S(G2) - platform;\n", "S(G2);\n", 1);
    let ts: TokenStream = declaration.parse().unwrap();
    let expanded = linkage_codegen::expand(ts).to_string();
    assert_eq!(expanded.matches("compile_error").count(), 2, "{expanded}");
    assert!(
        expanded.contains("pub (crate) type M = [() ; :: core :: compile_error !"),
        "{expanded}"
    );
    assert!(!expanded.contains("struct M"), "{expanded}");
}
