//! The generator and the file readers on mangled input: an error, never a panic. A stable,
//! deterministic cousin of the cargo-fuzz targets in `tests/fuzz`.

use linkage_examples::cli::{geometry, legs_csv};
use linkage_tests::Rng;
use proc_macro2::{TokenStream, TokenTree};

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
    let base: TokenStream = DECLARATION.parse().unwrap();
    if let Err(e) = linkage_codegen::model(base.clone()) {
        panic!("the unmangled declaration is valid: {e}");
    }
    let mut tokens = Vec::new();
    flatten(base, &mut tokens);
    let vocabulary = [
        "-", "->", ",", ";", "=", "base", "platform", "S", "P", "R", "H", "C", "U", "active",
        "passive", "axis", "G1", "A1", "0.0", "-1e3", "1e400", "crank1", "rod1", "frame", "length",
        "lead", "offset", "chain", "link", "[", "]", "(", ")", "{", "}",
    ];
    let mut rng = Rng::new(99);
    let mut rejected = 0;
    for _ in 0..3000 {
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
    assert!(rejected > 1000, "{rejected}");
}

#[test]
fn the_file_readers_survive_mangled_input() {
    let toml = "base = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\nplatform = [[0,0,0],[1,0,0],[2,0,0],[3,0,0],[4,0,0],[5,0,0]]\n[start]\nlegs = [1,1,1,1,1,1]\npose = [0,0,0,0,0,1]\n";
    let csv = "t,L1,L2,L3,L4,L5,L6\n0,170,170,170,170,170,170\n1,\"a\",2,3,4,5,6\n";
    let mut rng = Rng::new(7);
    for _ in 0..3000 {
        for (text, is_toml) in [(toml, true), (csv, false)] {
            let mut bytes = text.as_bytes().to_vec();
            for _ in 0..1 + rng.next_u64() % 6 {
                let i = (rng.next_u64() as usize) % bytes.len();
                match rng.next_u64() % 3 {
                    0 => bytes[i] = (rng.next_u64() % 256) as u8,
                    1 => {
                        bytes.remove(i);
                    }
                    _ => bytes.insert(i, b"[],=\"\n-e9."[(rng.next_u64() % 10) as usize]),
                }
            }
            if is_toml {
                let _ = geometry::parse(&String::from_utf8_lossy(&bytes));
            } else {
                let _ = legs_csv::read_from(bytes.as_slice());
            }
        }
    }
}
