//! The general model on mechanisms no closed-form shape covers: system sizes, mobility by rank,
//! dropped dependent equations, and the residual at home.

use linkage_codegen::model;
use quote::quote;

fn build(tokens: proc_macro2::TokenStream) -> linkage_codegen::model::Model {
    match model(tokens) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn delta_with_parallelograms_is_square_and_compact() {
    let m = build(quote! {
        pub struct Delta;
        params { rod = 250.0 }
        base {
            A1 = [100.0, 0.0, 0.0], B1 = [100.0, 1.0, 0.0],
            A2 = [-50.0, 86.60254037844386, 0.0], B2 = [-50.866025403784439, 86.10254037844386, 0.0],
            A3 = [-50.0, -86.60254037844386, 0.0], B3 = [-49.133974596215561, -87.10254037844386, 0.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -200.0]) {
            F11 = [40.0, 30.0, 0.0], F12 = [40.0, -30.0, 0.0],
            F21 = [-45.98076211353316, 19.641016151377545, 0.0], F22 = [5.980762113533162, 49.64101615137754, 0.0],
            F31 = [5.980762113533162, -49.64101615137754, 0.0], F32 = [-45.98076211353316, -19.641016151377545, 0.0],
        }
        link arm1 { E11 = [200.0, 30.0, 0.0], E12 = [200.0, -30.0, 0.0] }
        link arm2 { E21 = [-125.98076211353316, 158.20508075688772, 0.0], E22 = [-74.01923788646684, 188.20508075688772, 0.0] }
        link arm3 { E31 = [-74.01923788646684, -188.20508075688772, 0.0], E32 = [-125.98076211353316, -158.20508075688772, 0.0] }
        link rod11 { length = rod } link rod12 { length = rod }
        link rod21 { length = rod } link rod22 { length = rod }
        link rod31 { length = rod } link rod32 { length = rod }
        chain a1 = base - R(active q1, axis = A1 -> B1) - arm1 - S(E11) - rod11 - S(F11) - platform;
        chain a1b = arm1 - S(E12) - rod12 - S(F12) - platform;
        chain a2 = base - R(active q2, axis = A2 -> B2) - arm2 - S(E21) - rod21 - S(F21) - platform;
        chain a2b = arm2 - S(E22) - rod22 - S(F22) - platform;
        chain a3 = base - R(active q3, axis = A3 -> B3) - arm3 - S(E31) - rod31 - S(F31) - platform;
        chain a3b = arm3 - S(E32) - rod32 - S(F32) - platform;
    });
    eprintln!("{}", m.equations.len());
    for e in &m.equations {
        eprintln!("{}", m.render(e));
    }
    eprintln!("{:?}", m.mobility);
    assert_eq!(m.unknowns.len(), 18);
    assert_eq!(m.equations.len(), 18);
    assert_eq!(m.inputs, ["q1", "q2", "q3"]);
}
