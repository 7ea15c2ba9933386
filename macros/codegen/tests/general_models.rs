//! The general model on mechanisms no closed-form shape covers: system sizes, mobility by rank,
//! dropped dependent equations, and the residual at home.

use linkage_codegen::model;
use proc_macro2::{Literal, TokenStream};
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

#[test]
fn planar_five_bar_with_a_point_output_has_two_freedoms() {
    // Cranks 100 mm, distal links 150 mm, base joints 80 mm apart; vertical axes.
    let m = build(quote! {
        pub struct FiveBar;
        base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
        platform(home = [0.0, 0.0, 0.0, 0.0, 170.0, 0.0]) { P = [0.0, 0.0, 0.0] }
        link crank1 { C1 = [-100.0, 80.0, 0.0], C1z = [-100.0, 80.0, 1.0] }
        link crank2 { C2 = [100.0, 80.0, 0.0], C2z = [100.0, 80.0, 1.0] }
        link distal1 { }
        link distal2 { }
        chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
        chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
    });
    for e in &m.equations {
        eprintln!("{}", m.render(e));
    }
    eprintln!("{:?} dropped {:?}", m.mobility, m.dropped);
    assert_eq!(m.unknowns.len(), 3);
    assert_eq!(m.equations.len(), 3);
    assert_eq!(m.dropped.len(), 1);
}

#[test]
fn three_prs_is_square() {
    let m = build(quote! {
        pub struct Prs;
        params { leg = 150.0 }
        base {
            A1 = [100.0, 0.0, 0.0], B1 = [100.0, 0.0, 1.0],
            A2 = [-50.0, 86.60254037844386, 0.0], B2 = [-50.0, 86.60254037844386, 1.0],
            A3 = [-50.0, -86.60254037844386, 0.0], B3 = [-50.0, -86.60254037844386, 1.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 250.0]) {
            G1 = [50.0, 0.0, 0.0], G2 = [-25.0, 43.30127018922193, 0.0], G3 = [-25.0, -43.30127018922193, 0.0],
        }
        link slider1 { C1 = [100.0, 0.0, 129.8915], D1 = [100.0, 1.0, 129.8915] }
        link slider2 { C2 = [-50.0, 86.60254037844386, 129.8915], D2 = [-50.86602540378444, 86.10254037844386, 129.8915] }
        link slider3 { C3 = [-50.0, -86.60254037844386, 129.8915], D3 = [-49.13397459621556, -87.10254037844386, 129.8915] }
        link leg1 { } link leg2 { } link leg3 { }
        chain c1 = base - P(active s1, axis = A1 -> B1) - slider1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
        chain c2 = base - P(active s2, axis = A2 -> B2) - slider2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
        chain c3 = base - P(active s3, axis = A3 -> B3) - slider3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
    });
    for e in &m.equations {
        eprintln!("{}", m.render(e));
    }
    eprintln!("{:?} dropped {:?}", m.mobility, m.dropped);
    assert_eq!(m.unknowns.len(), 9);
    assert_eq!(m.equations.len(), 9);
}

#[test]
fn coordinates_take_arithmetic_and_parameters_derive_from_others() {
    let m = build(quote! {
        pub struct Tripod;
        params { r = 100.0, h = r * sqrt(3.0) / 2.0, l = 2.0 * (r - 10.0) }
        base { A1 = [r, 0.0, 0.0], A2 = [-r / 2.0, h, 0.0], A3 = [-r / 2.0, -h, 0.0] }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 120.0]) { G = [0.0, 0.0, 0.0] }
        chain leg1 = base - S(A1) - P(active L1) - S(G) - platform;
        chain leg2 = base - S(A2) - P(active L2) - S(G) - platform;
        chain leg3 = base - S(A3) - P(active L3) - S(G) - platform;
    });
    let slot = |name: &str| m.slots.iter().find(|s| s.name == name).unwrap().default;
    assert_eq!(slot("h"), 100.0 * 3f64.sqrt() / 2.0);
    assert_eq!(slot("l"), 180.0);
    assert_eq!(slot("base.A2.x"), -50.0);
    // A bare parameter stays linked: A1's x is the slot `r` itself.
    assert!(!m.slots.iter().any(|s| s.name == "base.A1.x"));
    assert_eq!(m.unknowns.len(), 3);
}

#[test]
fn planar_three_rpr_with_true_r_p_r_legs() {
    // Base triangle of circumradius 200, platform of 60; vertical axes; platform 10 mm up so
    // that the legs are not degenerate (all in one horizontal plane).
    let m = build(quote! {
        pub struct Rpr;
        base {
            A1 = [200.0, 0.0, 0.0], A1z = [200.0, 0.0, 1.0],
            A2 = [-100.0, 173.20508075688772, 0.0], A2z = [-100.0, 173.20508075688772, 1.0],
            A3 = [-100.0, -173.20508075688772, 0.0], A3z = [-100.0, -173.20508075688772, 1.0],
        }
        platform(home = [0.3, 0.0, 0.0, 10.0, 5.0, 0.0]) {
            G1 = [60.0, 0.0, 0.0], G1z = [60.0, 0.0, 1.0],
            G2 = [-30.0, 51.96152422706632, 0.0], G2z = [-30.0, 51.96152422706632, 1.0],
            G3 = [-30.0, -51.96152422706632, 0.0], G3z = [-30.0, -51.96152422706632, 1.0],
        }
        chain leg1 = base - R(passive, axis = A1 -> A1z) - P(active L1) - R(passive, axis = G1 -> G1z) - platform;
        chain leg2 = base - R(passive, axis = A2 -> A2z) - P(active L2) - R(passive, axis = G2 -> G2z) - platform;
        chain leg3 = base - R(passive, axis = A3 -> A3z) - P(active L3) - R(passive, axis = G3 -> G3z) - platform;
    });
    for e in &m.equations {
        eprintln!("{}", m.render(e));
    }
    eprintln!("{:?} dropped {}", m.mobility, m.dropped.len());
    assert_eq!(m.inputs, ["L1", "L2", "L3"]);
    assert_eq!(m.unknowns.len(), m.equations.len());
}

#[test]
fn translational_three_upu() {
    // Tsai's 3-UPU: at each leg the base U's first axis and the platform U's last axis are
    // parallel (tangent to the circles), so the intermediate axes are parallel too.
    let m = build(quote! {
        pub struct Upu;
        base {
            A1 = [150.0, 0.0, 0.0], A1a = [150.0, 1.0, 0.0],
            A2 = [-75.0, 129.9038105676658, 0.0], A2a = [-75.86602540378444, 129.4038105676658, 0.0],
            A3 = [-75.0, -129.9038105676658, 0.0], A3a = [-74.13397459621556, -130.4038105676658, 0.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 200.0]) {
            G1 = [60.0, 0.0, 0.0], G1a = [60.0, 1.0, 0.0],
            G2 = [-30.0, 51.96152422706632, 0.0], G2a = [-30.86602540378444, 51.46152422706632, 0.0],
            G3 = [-30.0, -51.96152422706632, 0.0], G3a = [-29.13397459621556, -52.46152422706632, 0.0],
        }
        chain leg1 = base - U(A1, axis = A1 -> A1a) - P(active L1) - U(G1, axis = G1 -> G1a) - platform;
        chain leg2 = base - U(A2, axis = A2 -> A2a) - P(active L2) - U(G2, axis = G2 -> G2a) - platform;
        chain leg3 = base - U(A3, axis = A3 -> A3a) - P(active L3) - U(G3, axis = G3 -> G3a) - platform;
    });
    for e in &m.equations {
        eprintln!("{}", m.render(e));
    }
    eprintln!("{:?} dropped {}", m.mobility, m.dropped.len());
    assert_eq!(m.unknowns.len(), m.equations.len());
}

#[test]
fn home_as_matrix_and_quaternion_agree_with_euler_angles() {
    let (yaw, pitch, roll) = (0.3f64, -0.2f64, 0.1f64);
    let r = linkage_geometry::rotation(yaw, pitch, roll);
    let [r0, r1, r2] = r.map(|row| {
        let [a, b, c] = row;
        quote!([#a, #b, #c])
    });
    // The quaternion of the same rotation (Shepperd's method is not needed here: w is large).
    let w = (1.0 + r[0][0] + r[1][1] + r[2][2]).sqrt() / 2.0;
    let (x, y, z) = (
        (r[2][1] - r[1][2]) / (4.0 * w),
        (r[0][2] - r[2][0]) / (4.0 * w),
        (r[1][0] - r[0][1]) / (4.0 * w),
    );
    let declare = |home: proc_macro2::TokenStream| {
        build(quote! {
            pub struct Tripod;
            base { A1 = [100.0, 0.0, 0.0], A2 = [-50.0, 86.6, 0.0], A3 = [-50.0, -86.6, 0.0] }
            platform(home = #home) { G = [0.0, 0.0, 0.0], H = [10.0, 0.0, 0.0] }
            chain leg1 = base - S(A1) - P(active L1) - S(G) - platform;
            chain leg2 = base - S(A2) - P(active L2) - S(G) - platform;
            chain leg3 = base - S(A3) - P(active L3) - S(G) - platform;
        })
        .home_pose
    };
    let euler = declare(quote!([#yaw, #pitch, #roll, 1.0, 2.0, 120.0]));
    let matrix = declare(quote!(rotation([#r0, #r1, #r2], [1.0, 2.0, 120.0])));
    let quaternion = declare(quote!(quaternion([#w, #x, #y, #z], [1.0, 2.0, 120.0])));
    for (a, b) in euler
        .iter()
        .zip(&matrix)
        .chain(euler.iter().zip(&quaternion))
    {
        assert!((a - b).abs() < 1e-12, "{euler:?} {matrix:?} {quaternion:?}");
    }
}

#[test]
fn a_passive_slide_on_a_base_rail_is_modelled_not_a_panic() {
    // The rail's added axis point is on the base: a constant like the base pivots. (This
    // declaration has five freedoms for two inputs, which is the error it must get.)
    let e = match model(quote! {
        pub struct Pb;
        base { A1 = [200.0, 0.0, 0.0], A1x = [201.0, 0.0, 0.0], A2 = [-100.0, 173.2, 0.0], A3 = [-100.0, -173.2, 0.0] }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 50.0]) { G1 = [40.0, 0.0, 0.0], G2 = [-20.0, 34.64, 0.0], G3 = [-20.0, -34.64, 0.0] }
        link s1 { C1 = [200.0, 0.0, 0.0], C1y = [200.0, 1.0, 0.0] }
        link l1 {}
        chain c1 = base - P(passive, axis = A1 -> A1x) - s1 - R(passive, axis = C1 -> C1y) - l1 - S(G1) - platform;
        chain c2 = base - S(A2) - P(active L2) - S(G2) - platform;
        chain c3 = base - S(A3) - P(active L3) - S(G3) - platform;
    }) {
        Ok(_) => panic!("five freedoms, two inputs"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("2 active joint variables but mobility 5"), "{e}");
}

/// Sliders placed from the base with literal offsets, one different value each: every pair
/// keeps its own (one slot per pair, named for its chain), and the declared configuration
/// assembles with each input at its own offset. Before, all such pairs shared the first
/// pair's slot, `P.offset`, and the others read a wrong offset.
#[test]
fn literal_offsets_of_sliders_from_the_base_are_per_pair() {
    let m = build(quote! {
        pub struct Prs;
        params {
            rb = 100.0, rp = 50.0, l = 150.0, h = 250.0,
            hc = h - sqrt(l * l - (rb - rp) * (rb - rp)),
            c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0),
        }
        base {
            A1 = [rb, 0.0, 0.0], B1 = [rb, 0.0, 1.0],
            A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2, rb * s2, 1.0],
            A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2, -rb * s2, 1.0],
        }
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 250.0]) {
            G1 = [rp, 0.0, 0.0], G2 = [rp * c2, rp * s2, 0.0], G3 = [rp * c2, -rp * s2, 0.0],
        }
        link slider1 { C1 = [rb, 0.0, hc], D1 = [rb, 1.0, hc] }
        link slider2 { C2 = [rb * c2, rb * s2, hc], D2 = [rb * c2 - s2, rb * s2 + c2, hc] }
        link slider3 { C3 = [rb * c2, -rb * s2, hc], D3 = [rb * c2 + s2, -rb * s2 + c2, hc] }
        link leg1 { } link leg2 { } link leg3 { }
        chain c1 = base - P(active s1, axis = A1 -> B1, offset = 100.0) - slider1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
        chain c2 = base - P(active s2, axis = A2 -> B2, offset = 101.0) - slider2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
        chain c3 = base - P(active s3, axis = A3 -> B3, offset = 102.0) - slider3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
    });
    let offsets: Vec<(&str, f64)> = m
        .slots
        .iter()
        .filter(|s| s.name.ends_with(".offset"))
        .map(|s| (s.name.as_str(), s.default))
        .collect();
    assert_eq!(
        offsets,
        [
            ("c1.offset", 100.0),
            ("c2.offset", 101.0),
            ("c3.offset", 102.0)
        ]
    );
    let mut home = m.general_home_inputs.clone();
    home.sort_by_key(|h| h.0);
    home.dedup();
    assert_eq!(home, [(0, 100.0), (1, 101.0), (2, 102.0)]);
}

/// A U at the end of a chain, its first axis on the leg: the second axis is perpendicular to
/// it and to the line from its centre to the platform's farthest *declared* pivot. The
/// platform also shares an R's axis pivots (K, Kz) declared on the arm, farther from the
/// centre; before, the model took K, so another chain's pair decided this U's axis.
#[test]
fn a_u_at_a_chain_end_takes_its_second_axis_from_its_own_links_pivots() {
    let m = build(quote! {
        pub struct Swivel;
        base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0], A = [300.0, 300.0, 0.0], Ax = [301.0, 300.0, 0.0] }
        platform { G = [300.0, 100.0, 0.0], G2 = [300.0, 100.0, 20.0] }
        link arm { K = [500.0, 0.0, 0.0], Kz = [500.0, 0.0, 1.0] }
        link leg { Q = [300.0, 150.0, 0.0], Qx = [301.0, 150.0, 0.0] }
        chain a = base - R(passive, axis = O -> Oz) - arm - R(passive, axis = K -> Kz) - platform;
        chain b = base - U(A, axis = A -> Ax) - P(active l) - leg - U(G, axis = Q -> Qx) - platform;
    });
    let g = m.default_slots();
    let seconds: Vec<[f64; 3]> = m
        .auto_points
        .iter()
        .enumerate()
        .filter(|(_, a)| matches!(a, linkage_geometry::recipe::Auto::Normal { .. }))
        .map(|(i, _)| {
            linkage_codegen::model::home_of(
                m.home_pose,
                &m.auto_points,
                &g,
                linkage_geometry::recipe::PointRef::Auto(i),
            )
        })
        .collect();
    assert_eq!(seconds.len(), 2, "{:?}", m.auto_points);
    // (Qx − Q) × (G2 − G) = x × 20 z = −20 y: the second axis point along −y from G, as far
    // from it as G2 is (the lever of the line that gave the direction).
    let s = seconds[1];
    let expected = [300.0, 80.0, 0.0];
    assert!(
        s.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-12),
        "the second axis point at {s:?}, expected {expected:?}"
    );
}

/// A U whose first axis is declared on the link after it (here the platform), first in its
/// chain on a base with no pivots: nothing gives its second axis's direction (square to the
/// first and to the line to the joint before, of which there is none). Refused, naming the
/// link that lacks a pivot: the base, not "the link after it" as the message used to say.
#[test]
fn a_u_with_nothing_to_set_its_second_axis_names_the_link_that_lacks_a_pivot() {
    let e = match model(quote! {
        pub struct M;
        base { }
        platform { A = [0.0, 0.0, 0.0], B = [0.0, 30.0, 0.0], P = [25.0, 10.0, 5.0] }
        chain c = base - U(A, axis = A -> B, active a b) - platform;
    }) {
        Ok(_) => panic!("a U with no second axis accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("no joint precedes it and `base` has no other pivot of its own"),
        "{e}"
    );
}

/// Grübler–Kutzbach counts every link once, wherever the chains meet it: a serial R–R arm
/// declared in one chain, split in two at its declared upper link, or with that link reached by
/// two chains (a closed loop) — the count once missed a link that chains only start or end at
/// (−4 and "not a tree" for the split arm) and counted twice one that two chains pass through.
#[test]
fn gruebler_counts_each_link_once_however_the_chains_meet_it() {
    let arm = |chains: proc_macro2::TokenStream| {
        build(quote! {
            pub struct Arm;
            base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0], K = [0.0, -50.0, 0.0], Kz = [0.0, -50.0, 1.0] }
            platform { P = [100.0, 0.0, 0.0], Q = [100.0, 10.0, 0.0], J = [50.0, 0.0, 0.0], Jz = [50.0, 0.0, 1.0] }
            link upper { U = [25.0, 10.0, 0.0], W = [20.0, -5.0, 0.0] }
            #chains
        })
    };
    let inside = arm(quote! {
        chain a = base - R(active q1, axis = O -> Oz) - upper - R(active q2, axis = J -> Jz) - platform;
    });
    let split = arm(quote! {
        chain a = base - R(active q1, axis = O -> Oz) - upper;
        chain b = upper - R(active q2, axis = J -> Jz) - platform;
    });
    let expected =
        "Grübler–Kutzbach: M = 6(L − 1 − J) + Σf = 6(3 − 1 − 2) + 2 = 2, less 0 idle spins = 2";
    for m in [&inside, &split] {
        assert_eq!(m.counted, expected);
        assert!(m.open, "a serial arm is a tree");
    }
    // A second chain through `upper` (a passive hinge on the first one's axis, a ball on the
    // second's): the same three links, four pairs — a closed loop, redundant by rank.
    let looped = arm(quote! {
        chain a = base - R(active q1, axis = O -> Oz) - upper - R(active q2, axis = J -> Jz) - platform;
        chain b = base - R(passive, axis = O -> Oz) - upper - S(J) - platform;
    });
    eprintln!("{}", looped.counted);
    assert_eq!(
        looped.counted,
        "Grübler–Kutzbach: M = 6(L − 1 − J) + Σf = 6(3 − 1 − 4) + 6 = -6, less 0 idle spins = -6"
    );
    assert!(!looped.open);
}

// The model's own levers on short passive revolute axes (`model::general::topology`'s
// `levers`): a lever changes how the equations read an axis, never which mechanism they
// describe. Each case is declared twice, with the hinge's axis pivots 1 mm apart (a lever) and
// 150 mm apart (none: above a quarter of the mechanism's size), and both must get the same
// verdict.
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

/// A 6-PUS after the Hexaglide, each slider's U on an unnamed rod to a joint on the platform,
/// leg k's of kind `ends[k]` (`"S"`, or `"U"` with its first axis along x on the platform; legs
/// past the end of `ends` left out); the U's first axis from `A` to `A{first}`: `"x"` along the
/// rail, `"g"` towards the ball at home (along the rod). Leg 1's rod is declared, as `link rod1
/// { <rod1> }`, where `rod1` is given.
fn pus(first: &str, ends: &[&str], rod1: Option<&str>) -> TokenStream {
    let (rp, h) = (60.0f64, 250.0);
    let at = [-1.4f64, -1.9, 0.3, 2.9, 1.2, 2.0];
    let g = |i: usize| {
        [
            rp * at[i].cos(),
            rp * at[i].sin(),
            if i == 5 { 10.0 } else { 0.0 },
        ]
    };
    let a = [
        [160.0, -150.0, 0.0],
        [-170.0, -150.0, 0.0],
        [210.0, 0.0, 60.0],
        [-210.0, 0.0, 60.0],
        [170.0, 150.0, 0.0],
        [-175.0, 150.0, 0.0],
    ];
    let v = |p: [f64; 3]| format!("[{:?}, {:?}, {:?}]", p[0], p[1], p[2]);
    let (mut platform, mut links, mut chains) = (String::new(), String::new(), String::new());
    for (i, &end) in ends.iter().enumerate() {
        let (n, rail) = (i + 1, i / 2 + 1);
        let gi = g(i);
        let ball = [gi[0] - a[i][0], gi[1] - a[i][1], gi[2] - h - a[i][2]];
        platform += &format!("G{n} = {},", v(gi));
        if end == "U" {
            platform += &format!("G{n}x = {},", v([gi[0] + 1.0, gi[1], gi[2]]));
        }
        links += &format!(
            "link s{n} {{ A{n} = {}, A{n}x = {}, A{n}g = {} }}\n",
            v(a[i]),
            v([a[i][0] + 100.0, a[i][1], a[i][2]]),
            v([0, 1, 2].map(|k| a[i][k] + 0.5 * ball[k]))
        );
        let end_axis = if end == "U" {
            format!(", axis = G{n} -> G{n}x")
        } else {
            String::new()
        };
        let rod = match rod1 {
            Some(body) if n == 1 => {
                links += &format!("link rod1 {{ {body} }}\n");
                "rod1 -"
            }
            _ => "",
        };
        chains += &format!(
            "chain leg{n} = base - P(active d{n}, axis = R{rail} -> R{rail}x) - s{n} - U(A{n}, axis = A{n} -> A{n}{first}) - {rod} {end}(G{n}{end_axis}) - platform;\n"
        );
    }
    format!(
        "pub struct Pus;
        base {{
            R1 = [-200.0, -150.0, 0.0], R1x = [200.0, -150.0, 0.0],
            R2 = [-200.0, 0.0, 60.0], R2x = [200.0, 0.0, 60.0],
            R3 = [-200.0, 150.0, 0.0], R3x = [200.0, 150.0, 0.0],
        }}
        platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -{h:?}]) {{ {platform} }}
        {links}
        {chains}"
    )
    .parse()
    .unwrap()
}

/// A passive U on an unnamed rod whose other end is a ball holds only the rod's spin, which
/// nothing else sees: the rod is reduced to its length as between two S, and the 6-PUS has the
/// 18 unknowns of a 6-6 platform (it had 36: each rod's second-axis point). A U at the rod's
/// other end turns with the spin, so there the points stay; and a first axis along the rod at
/// home is still refused, as the README says.
#[test]
fn a_u_on_a_rod_to_a_ball_is_reduced_to_the_rods_length() {
    let m = build(pus("x", &["S"; 6], None));
    assert_eq!(m.unknowns.len(), 18, "{:?}", m.unknowns);
    assert!(
        m.unknowns.iter().all(|u| u.contains("_G")),
        "{:?}",
        m.unknowns
    );
    assert_eq!(m.equations.len(), 18);
    assert!(
        !m.auto_points
            .iter()
            .any(|a| matches!(a, linkage_geometry::recipe::Auto::Normal { .. })),
        "{:?}",
        m.auto_points
    );
    // A U–U rod holds the platform by its length and by the spin the two U's share: four
    // legs to balls and one such (five slides) are square, and the rod's points stay.
    let both = build(pus("x", &["S", "S", "S", "S", "U"], None));
    let seconds: Vec<&String> = both.unknowns.iter().filter(|u| u.contains("_u")).collect();
    assert_eq!(seconds.len(), 6, "{:?}", both.unknowns);
    // A rod declared by name only is a rod; one that carries a pivot of its own turns it with
    // the spin, and keeps the point.
    let named = build(pus("x", &["S"; 6], Some("")));
    assert_eq!(named.unknowns.len(), 18, "{:?}", named.unknowns);
    let carrying = build(pus("x", &["S"; 6], Some("Q1 = [150.0, -120.0, -100.0]")));
    assert!(
        carrying.unknowns.iter().any(|u| u.ends_with("A1_u")),
        "{:?}",
        carrying.unknowns
    );
    let e = match model(pus("g", &["S"; 6], None)) {
        Ok(_) => panic!("a U whose first axis lies along its rod was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("second axis is undefined"), "{e}");
}
