//! The model's own levers on short passive revolute axes (`model::general::topology`'s
//! `levers`): a lever changes how the equations read an axis, never which mechanism they
//! describe. Each case is declared twice, with the hinge's axis pivots 1 mm apart (a lever) and
//! 150 mm apart (none: above a quarter of the mechanism's size), and both must get the same
//! verdict.

use linkage_codegen::model;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// A 3-RRS (cranks of 100 mm at radius 200 mm, legs of 150 mm, upright at home) whose first
/// hinge's second pivot `D1`, `spacing` from `C1` along the hinge, the platform declares: the
/// platform holds a point on that hinge's axis, which ties it to crank 1 (mobility 1, not 3).
fn rrs_with_d1_on_the_platform(spacing: f64) -> TokenStream {
    let d = Literal::f64_unsuffixed(spacing);
    quote! {
        pub struct Rrs;
        base {
            A1 = [200.0, 0.0, 0.0], B1 = [200.0, 1.0, 0.0],
            A2 = [-100.0, 173.20508075688772, 0.0], B2 = [-100.8660254037844386, 172.70508075688772, 0.0],
            A3 = [-100.0, -173.20508075688772, 0.0], B3 = [-99.1339745962155614, -173.70508075688772, 0.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0]) {
            G1 = [100.0, 0.0, 0.0], G2 = [-50.0, 86.60254037844386, 0.0], G3 = [-50.0, -86.60254037844386, 0.0],
            D1 = [100.0, #d, -150.0],
        }
        link crank1 { C1 = [100.0, 0.0, 0.0] }
        link crank2 { C2 = [-50.0, 86.60254037844386, 0.0], D2 = [-50.866025403784439, 86.10254037844386, 0.0] }
        link crank3 { C3 = [-50.0, -86.60254037844386, 0.0], D3 = [-49.133974596215561, -87.10254037844386, 0.0] }
        link leg1 { } link leg2 { } link leg3 { }
        chain c1 = base - R(active q1, axis = A1 -> B1) - crank1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
        chain c2 = base - R(active q2, axis = A2 -> B2) - crank2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
        chain c3 = base - R(active q3, axis = A3 -> B3) - crank3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
    }
}

/// An axis pivot that a third link declares (neither of the two the hinge joins) is that
/// link's point on the axis: the hinge's sharing of it is what holds the third link there. The
/// lever once took it from both of the hinge's links and left it to the third alone, so that
/// with the axis declared 1 mm long the platform was free of crank 1's hinge (rank at home
/// M = 12 + 3 − 12 = 3, a model of another mechanism, solved and answered ok), while declared
/// 150 mm long it is refused as the mechanism of mobility 1 it is.
#[test]
fn an_axis_pivot_a_third_link_declares_still_holds_that_link_on_the_axis() {
    for spacing in [150.0, 1.0] {
        let refused = match model(rrs_with_d1_on_the_platform(spacing)) {
            Ok(m) => panic!(
                "D1 {spacing} mm from C1: modelled with mobility {:?}, unknowns {:?}",
                m.mobility, m.unknowns
            ),
            Err(e) => e.to_string(),
        };
        assert!(
            refused.contains("mobility 1"),
            "D1 {spacing} mm from C1: {refused}"
        );
    }
}
