//! Snapshots of the emitted Rust (formatted by prettyplease) for a few mechanisms: a
//! closed-form chain shape (a 3-RPS, with its inverse kinematics in closed form), the general
//! model with links placed by the inputs (a 3-RRS) and a point platform with the numerical
//! inverse (a planar five-bar). A change to the generated code shows up here as a diff.

use quote::quote;

fn emitted(tokens: proc_macro2::TokenStream) -> String {
    let out = linkage_codegen::expand(tokens);
    let file: syn::File = match syn::parse2(out) {
        Ok(f) => f,
        Err(e) => panic!("the emitted code does not parse: {e}"),
    };
    let text = prettyplease::unparse(&file);
    assert!(!text.contains("compile_error"), "{text}");
    text
}

#[test]
fn three_rps() {
    insta::assert_snapshot!(emitted(quote! {
        /// A 3-RPS.
        pub struct Rps;
        base {
            A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
            A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
            A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
        }
        platform { G1 = [0.0, 50.0, 0.0], G2 = [-43.301, -25.0, 0.0], G3 = [43.301, -25.0, 0.0] }
        chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
        chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
        chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
    }));
}

#[test]
fn three_rrs() {
    insta::assert_snapshot!(emitted(quote! {
        /// A 3-RRS with upright legs at home.
        pub struct Rrs;
        params { rb = 200.0, rc = 100.0, rp = 100.0, c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0) }
        base {
            A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
            A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2 - s2, rb * s2 + c2, 0.0],
            A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2 + s2, -rb * s2 + c2, 0.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
            G1 = [rp, 0.0, 0.0], G2 = [rp * c2, rp * s2, 0.0], G3 = [rp * c2, -rp * s2, 0.0],
        }
        link crank1 { C1 = [rb - rc, 0.0, 0.0], D1 = [rb - rc, 1.0, 0.0] }
        link crank2 { C2 = [(rb - rc) * c2, (rb - rc) * s2, 0.0], D2 = [(rb - rc) * c2 - s2, (rb - rc) * s2 + c2, 0.0] }
        link crank3 { C3 = [(rb - rc) * c2, -(rb - rc) * s2, 0.0], D3 = [(rb - rc) * c2 + s2, -(rb - rc) * s2 + c2, 0.0] }
        link leg1 { } link leg2 { } link leg3 { }
        chain c1 = base - R(active q1, axis = A1 -> B1) - crank1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
        chain c2 = base - R(active q2, axis = A2 -> B2) - crank2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
        chain c3 = base - R(active q3, axis = A3 -> B3) - crank3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
    }));
}

#[test]
fn planar_five_bar() {
    insta::assert_snapshot!(emitted(quote! {
        /// A planar five-bar whose output is a point.
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
    }));
}
