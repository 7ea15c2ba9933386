//! The resolved declaration: names become typed ids in a fixed order (base, platform, then the
//! declared links; pivots link by link; inputs in chain order), every pair's arguments refer
//! to those ids, and the resolver's mistakes and the model's come back together.

use linkage_codegen::front::ast::{LinkRole, Mechanism, PairKind};
use linkage_codegen::front::errors::Errors;
use linkage_codegen::front::ids::LinkId;
use linkage_codegen::front::resolved::{Decl, Form, Value};
use quote::quote;

fn resolve(tokens: proc_macro2::TokenStream) -> Result<Decl, String> {
    let mech: Mechanism = syn::parse2(tokens).map_err(|e| e.to_string())?;
    let mut errors = Errors::default();
    match mech.resolve(&mut errors) {
        Some(d) if errors.is_empty() => Ok(d),
        _ => Err(errors
            .into_error()
            .into_iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join("\n")),
    }
}

#[test]
fn names_become_ids_in_declaration_order() {
    let d = resolve(quote! {
        pub struct Crank;
        params { r = 50.0, off = 5.0 }
        link arm { E1 = [r, 0.0, 0.0], E2 = [r, 10.0, 0.0] }
        platform(form = coplanar, home = inputs(q = 0.0, s = 0.0)) { G = [0.0, 0.0, 100.0], H = [10.0, 0.0, 100.0] }
        base { A = [0.0, 0.0, 0.0], B = [0.0, 1.0, 0.0] }
        link rod { length = 120.0 }
        chain c1 = base - R(active q, axis = A -> B) - arm - S(E1) - rod - S(G) - platform;
        chain c2 = arm - S(E2) - P(active s, offset = off) - S(H) - platform;
    })
    .unwrap();
    // Base and platform first whatever the order written, then the links as declared.
    let names: Vec<String> = d.links.iter().map(|l| l.name.to_string()).collect();
    assert_eq!(names, ["base", "platform", "arm", "rod"]);
    assert_eq!(d.link(LinkId::BASE).role, LinkRole::Base);
    assert_eq!(d.link(LinkId::PLATFORM).role, LinkRole::Platform);
    // Pivots link by link; each knows its link; a parameter stays a parameter.
    let pivots: Vec<String> = d.pivots.iter().map(|p| p.name.to_string()).collect();
    assert_eq!(pivots, ["A", "B", "G", "H", "E1", "E2"]);
    for (id, link) in d.links_with_ids() {
        assert!(link.pivots.iter().all(|&p| d.pivot(p).link == id));
    }
    let e1 = d.pivot(d.links[2].pivots[0]);
    assert!(matches!(e1.coords[0], Value::Param(p) if d.param(p).name == "r"));
    assert_eq!(d.point(d.links[2].pivots[0]), [50.0, 0.0, 0.0]);
    assert_eq!(d.links[3].length, Some(Value::Literal(120.0)));
    // Chains with their unnamed links explicit, and pairs by id.
    let c1 = &d.chains[0];
    assert_eq!(c1.links.len(), c1.pairs.len() + 1);
    assert_eq!(c1.links[0], Some(LinkId::BASE));
    assert_eq!(c1.links.last(), Some(&Some(LinkId::PLATFORM)));
    let r = &c1.pairs[0];
    assert_eq!(r.kind, PairKind::R);
    assert!(r.active);
    let [a, b] = r.axis.unwrap();
    assert_eq!(
        (
            d.pivot(a.id).name.to_string(),
            d.pivot(b.id).name.to_string()
        ),
        ("A".into(), "B".into())
    );
    let slider = &d.chains[1].pairs[1];
    assert_eq!(slider.kind, PairKind::P);
    assert!(matches!(slider.offset, Some(Value::Param(p)) if d.param(p).name == "off"));
    // Unnamed link between S(E2) and P, and between P and S(H).
    let arm = d
        .links_with_ids()
        .find(|(_, l)| l.name == "arm")
        .map(|(id, _)| id);
    assert_eq!(
        d.chains[1].links,
        vec![arm, None, None, Some(LinkId::PLATFORM)]
    );
    // Inputs in chain order, each pair pointing at its own.
    let inputs: Vec<String> = d.inputs.iter().map(|i| i.name.to_string()).collect();
    assert_eq!(inputs, ["q", "s"]);
    assert_eq!(r.inputs.iter().map(|i| i.index()).collect::<Vec<_>>(), [0]);
    assert_eq!(
        slider.inputs.iter().map(|i| i.index()).collect::<Vec<_>>(),
        [1]
    );
    assert_eq!(d.platform.form.map(|f| f.0), Some(Form::Coplanar));
    assert_eq!(
        d.platform.home_inputs.as_ref().map(|h| h.1.clone()),
        Some(vec![0.0, 0.0])
    );
}

#[test]
fn a_shared_input_is_one_id_with_a_use_per_pair() {
    let d = resolve(quote! {
        pub struct Twin;
        base { A1 = [0.0, 0.0, 0.0], B1 = [0.0, 1.0, 0.0], A2 = [100.0, 0.0, 0.0], B2 = [100.0, 1.0, 0.0] }
        platform { G1 = [0.0, 0.0, 100.0], G2 = [100.0, 0.0, 100.0] }
        link l1 { C1 = [0.0, 0.0, 50.0] } link l2 { C2 = [100.0, 0.0, 50.0] }
        link r1 { length = 50.0 } link r2 { length = 50.0 }
        chain a = base - R(active shared q, axis = A1 -> B1) - l1 - S(C1) - r1 - S(G1) - platform;
        chain b = base - R(active shared q, axis = A2 -> B2) - l2 - S(C2) - r2 - S(G2) - platform;
    })
    .unwrap();
    assert_eq!(d.inputs.len(), 1);
    assert_eq!(d.inputs[0].uses.len(), 2);
    assert_eq!(d.chains[0].pairs[0].inputs, d.chains[1].pairs[0].inputs);
}

#[test]
fn resolver_mistakes_come_together_and_stop_before_the_model() {
    let e = resolve(quote! {
        pub struct Bad;
        base { A = [0.0, 0.0, 0.0] }
        platform { G = [0.0, 0.0, nope] }
        chain c = base - S(A) - P(active L, lead = 5.0) - S(Q) - platform;
    })
    .err()
    .expect("three mistakes");
    assert!(e.contains("unknown parameter `nope`"), "{e}");
    assert!(e.contains("`lead` belongs to a helical pair"), "{e}");
    assert!(e.contains("unknown pivot `Q`"), "{e}");
}

#[test]
fn model_mistakes_in_independent_pairs_come_together() {
    let e = linkage_codegen::model(quote! {
        pub struct Upu;
        base {
            A1 = [150.0, 0.0, 0.0], A1a = [150.0, 1.0, 0.0],
            A2 = [-75.0, 129.9, 0.0], A2a = [-75.866, 129.4, 0.0],
            A3 = [-75.0, -129.9, 0.0], A3a = [-74.134, -130.4, 0.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 200.0]) {
            G1 = [60.0, 0.0, 0.0], G1a = [60.0, 1.0, 0.0],
            G2 = [-30.0, 51.96, 0.0], G2a = [-30.866, 51.46, 0.0],
            G3 = [-30.0, -51.96, 0.0], G3a = [-29.134, -52.46, 0.0],
        }
        chain leg1 = base - U(A1, axis = A1 -> A1a) - P(active L1) - U(G1, axis = A1 -> A1a) - platform;
        chain leg2 = base - U(A2, axis = A2 -> A2a) - P(active L2) - U(G2, axis = G2 -> G2a) - platform;
        chain leg3 = base - U(A3, axis = G3 -> G3a) - P(active L3) - U(G3, axis = G3 -> G3a) - platform;
    })
    .err()
    .expect("two misplaced U axes");
    let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(messages[0].contains("`A1 -> A1a`") && messages[1].contains("`G3 -> G3a`"));
}
