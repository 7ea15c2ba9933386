//! `home = inputs(...)`: the home configuration given by joint values, solved at compile time
//! from the declared geometry's configuration. Against the same machine declared with a `home`
//! pose and solved at run time to the same inputs.

use linkage::{arc_length, pose_from_unknowns, Mechanism, Options, Status};

linkage::mechanism! {
    /// The README's 3-RPS with its platform pivots declared 150 mm up (so that the declared
    /// geometry is assembled with the platform's frame at the base frame), home at leg lengths
    /// 165, 150, 160.
    pub struct RpsByInputs;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform(home = inputs(L1 = 165.0, L2 = 150.0, L3 = 160.0)) {
        G1 = [0.0, 50.0, 150.0],
        G2 = [-43.301, -25.0, 150.0],
        G3 = [43.301, -25.0, 150.0],
    }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

linkage::mechanism! {
    /// The same 3-RPS with the identity as its `home` pose.
    pub struct RpsByPose;
    base {
        A1 = [0.0, 100.0, 0.0],     B1 = [-10.0, 100.0, 0.0],
        A2 = [-86.603, -50.0, 0.0], B2 = [-81.603, -58.660, 0.0],
        A3 = [86.603, -50.0, 0.0],  B3 = [91.603, -41.340, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]) {
        G1 = [0.0, 50.0, 150.0],
        G2 = [-43.301, -25.0, 150.0],
        G3 = [43.301, -25.0, 150.0],
    }
    chain leg1 = base - R(passive, axis = A1 -> B1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - R(passive, axis = A2 -> B2) - P(active L2) - S(G2) - platform;
    chain leg3 = base - R(passive, axis = A3 -> B3) - P(active L3) - S(G3) - platform;
}

linkage::mechanism! {
    /// The README's five-bar with its output point declared where it is at the declared
    /// configuration (the platform's frame at the base frame), home at q = (0.3, −0.2).
    pub struct FiveBarByInputs;
    params { crank = 100.0 }
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = inputs(q2 = -0.2, q1 = 0.3)) { P = [0.0, crank * sin(pi / 3.0) + 120.0, 0.0] }
    link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
}

linkage::mechanism! {
    /// The same five-bar, home where it is declared.
    pub struct FiveBarDeclared;
    params { crank = 100.0 }
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform { P = [0.0, crank * sin(pi / 3.0) + 120.0, 0.0] }
    link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
}

#[test]
fn rps_home_from_leg_lengths_is_where_forward_kinematics_goes() {
    assert_eq!(RpsByInputs::HOME_INPUTS, [165.0, 150.0, 160.0]);
    let (by_inputs, by_pose) = (RpsByInputs::new(), RpsByPose::new());
    let start = by_pose.home_start().unwrap();
    let sol = arc_length(&by_pose, &start, &[165.0, 150.0, 160.0], &Options::TIGHT).unwrap();
    assert_eq!(sol.status, Status::Converged);
    assert!(linkage_tests::max_diff(&RpsByInputs::HOME_V, &sol.v) < 1e-9);
    // HOME is the platform's pose there, and home_start() (which rebuilds the pivots from it)
    // starts at the same configuration.
    let pose = pose_from_unknowns(&by_pose, &sol.v).unwrap();
    let home = RpsByInputs::HOME;
    assert!(linkage_tests::max_diff(&home[..3], &pose.euler()) < 1e-12);
    assert!(linkage_tests::max_diff(&home[3..], &pose.translation) < 1e-9);
    let s = by_inputs.home_start().unwrap();
    assert!(linkage_tests::max_diff(s.v(), &sol.v) < 1e-9);
    assert!(linkage_tests::max_diff(s.x(), &[165.0, 150.0, 160.0]) < 1e-9);
}

#[test]
fn five_bar_home_from_crank_angles_is_where_forward_kinematics_goes() {
    assert_eq!(FiveBarByInputs::INPUTS, ["q1", "q2"]);
    assert_eq!(FiveBarByInputs::HOME_INPUTS, [0.3, -0.2]);
    let declared = FiveBarDeclared::new();
    let start = declared.home_start().unwrap();
    let sol = arc_length(&declared, &start, &[0.3, -0.2], &Options::TIGHT).unwrap();
    assert_eq!(sol.status, Status::Converged);
    assert!(linkage_tests::max_diff(&FiveBarByInputs::HOME_V, &sol.v) < 1e-9);
    let five_bar = FiveBarByInputs::new();
    let s = five_bar.home_start().unwrap();
    assert!(linkage_tests::max_diff(s.v(), &sol.v) < 1e-9);
    // And from there, forward kinematics back to the declared configuration.
    let back = arc_length(&five_bar, &s, &[0.0, 0.0], &Options::TIGHT).unwrap();
    assert_eq!(back.status, Status::Converged);
    assert!(linkage_tests::max_diff(&back.v, start.v()) < 1e-9);
    let residual = linkage_tests::residual_norm(&five_bar, &FiveBarByInputs::HOME_V, &[0.3, -0.2]);
    assert!(residual < 1e-9, "{residual}");
}
