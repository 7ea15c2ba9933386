//! Mechanisms only the general model declares, end to end: the generated code's Jacobians
//! against finite differences, forward kinematics from home against an independent closed form.

use linkage::{arc_length, det_b, Mechanism, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// A planar five-bar: two cranks driven about vertical axes, two distal links meeting at the
    /// output point P (the platform is that point).
    pub struct FiveBar;
    params { crank = 100.0, distal = 150.0 }
    base { A1 = [-40.0, 0.0, 0.0], A1z = [-40.0, 0.0, 1.0], A2 = [40.0, 0.0, 0.0], A2z = [40.0, 0.0, 1.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, crank * sin(pi / 3.0) + 120.0, 0.0]) { P = [0.0, 0.0, 0.0] }
    link crank1 { C1 = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C1z = [-40.0 - crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link crank2 { C2 = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 0.0], C2z = [40.0 + crank * cos(pi / 3.0), crank * sin(pi / 3.0), 1.0] }
    link distal1 { }
    link distal2 { }
    chain left = base - R(active q1, axis = A1 -> A1z) - crank1 - R(passive, axis = C1 -> C1z) - distal1 - S(P) - platform;
    chain right = base - R(active q2, axis = A2 -> A2z) - crank2 - R(passive, axis = C2 -> C2z) - distal2 - S(P) - platform;
}

/// The output point by circle intersection: the root on the same side of C1C2 as `near`.
fn five_bar_point(q: [f64; 2], near: [f64; 2]) -> Option<[f64; 2]> {
    let (r, l) = (100.0, 150.0);
    let a1 = -40.0 - r * (std::f64::consts::PI / 3.0).cos();
    let s = r * (std::f64::consts::PI / 3.0).sin();
    // C_i at home, rotated by q_i about A_i.
    let rot = |c: [f64; 2], a: [f64; 2], t: f64| {
        let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
        [
            a[0] + dx * t.cos() - dy * t.sin(),
            a[1] + dx * t.sin() + dy * t.cos(),
        ]
    };
    let c1 = rot([a1, s], [-40.0, 0.0], q[0]);
    let c2 = rot([-a1, s], [40.0, 0.0], q[1]);
    let d = ((c2[0] - c1[0]).powi(2) + (c2[1] - c1[1]).powi(2)).sqrt();
    if d > 2.0 * l {
        return None;
    }
    let h = (l * l - d * d / 4.0).sqrt();
    let m = [(c1[0] + c2[0]) / 2.0, (c1[1] + c2[1]) / 2.0];
    let n = [-(c2[1] - c1[1]) / d, (c2[0] - c1[0]) / d];
    let p1 = [m[0] + h * n[0], m[1] + h * n[1]];
    let p2 = [m[0] - h * n[0], m[1] - h * n[1]];
    let dist = |p: [f64; 2]| (p[0] - near[0]).powi(2) + (p[1] - near[1]).powi(2);
    Some(if dist(p1) <= dist(p2) { p1 } else { p2 })
}

#[test]
fn five_bar_has_two_inputs_and_exact_jacobians() {
    let fb = FiveBar::new();
    assert_eq!(FiveBar::INPUTS, ["q1", "q2"]);
    let start = fb.home_start().unwrap();
    check_jacobians(&fb, start.v(), start.x());
    check_factorization(&fb, start.v(), start.x());
    assert!(FiveBar::LISTING.contains("rank of ∂F/∂(v, x) at home"));
}

#[test]
fn five_bar_forward_kinematics_matches_circle_intersection() {
    let fb = FiveBar::new();
    let start = fb.home_start().unwrap();
    let home = [start.v()[0], start.v()[1]];
    let mut rng = Rng::new(11);
    let mut solved = 0;
    for _ in 0..60 {
        let q = [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)];
        let sol = arc_length(&fb, &start, &q, &Options::TIGHT).unwrap();
        if sol.status != Status::Converged {
            continue;
        }
        solved += 1;
        let truth = five_bar_point(q, home).unwrap();
        assert!(
            (sol.v[0] - truth[0]).abs() < 1e-7 && (sol.v[1] - truth[1]).abs() < 1e-7,
            "q = {q:?}: {:?} vs {truth:?}",
            &sol.v[..2]
        );
        assert!(sol.v[2].abs() < 1e-9, "the output stays in its plane");
        // Each crank has turned by its input about its vertical axis.
        for (link, angle) in [("crank1", q[0]), ("crank2", q[1])] {
            let i = FiveBar::LINKS.iter().position(|l| *l == link).unwrap();
            let pose = fb
                .link_pose(i, &sol.v, &q)
                .expect("a crank has three points");
            assert!(
                (pose.euler()[0] - angle).abs() < 1e-9,
                "{link}: {:?}",
                pose.euler()
            );
        }
        assert!(det_b(&fb, &sol.v, &q) * start.det() > 0.0);
    }
    assert!(solved >= 50, "{solved} of 60 solved");
}

linkage::mechanism! {
    /// A planar 3-RPR with true R–P–R legs: vertical revolute axes at the base and on the
    /// platform, leg lengths driven.
    pub struct PlanarRpr;
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
}

/// Leg lengths of the 3-RPR at a planar pose (φ, x, y): |R(φ) g + t − a|.
fn rpr_legs(pose: [f64; 3]) -> [f64; 3] {
    let s3 = 3f64.sqrt();
    let a = [[200.0, 0.0], [-100.0, 100.0 * s3], [-100.0, -100.0 * s3]];
    let g = [[60.0, 0.0], [-30.0, 30.0 * s3], [-30.0, -30.0 * s3]];
    let (c, s) = (pose[0].cos(), pose[0].sin());
    std::array::from_fn(|i| {
        let p = [
            c * g[i][0] - s * g[i][1] + pose[1],
            s * g[i][0] + c * g[i][1] + pose[2],
        ];
        ((p[0] - a[i][0]).powi(2) + (p[1] - a[i][1]).powi(2)).sqrt()
    })
}

/// The general model's rows (unit axis vectors beside 200 mm coordinates) leave a rounding
/// floor of 1e-10 to 2e-9 mm on the Newton correction at regular points: below it a solve ends
/// `ToleranceNotMet`, so these tests ask for a tolerance above it.
const GENERAL_MODEL: Options = Options {
    tolerance: 1e-8,
    ..Options::TIGHT
};

#[test]
fn planar_rpr_forward_kinematics_against_inverse() {
    let rpr = PlanarRpr::new();
    let start = rpr.home_start().unwrap();
    for (i, l) in rpr_legs([0.3, 10.0, 5.0]).iter().enumerate() {
        assert!(
            (start.x()[i] - l).abs() < 1e-9,
            "home legs: {:?}",
            *start.x()
        );
    }
    check_jacobians(&rpr, start.v(), start.x());
    check_factorization(&rpr, start.v(), start.x());
    let mut rng = Rng::new(5);
    for _ in 0..60 {
        let pose = [
            0.3 + rng.uniform(-0.2, 0.2),
            10.0 + rng.uniform(-30.0, 30.0),
            5.0 + rng.uniform(-30.0, 30.0),
        ];
        let legs = rpr_legs(pose);
        let sol = arc_length(&rpr, &start, &legs, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{pose:?}");
        let got = linkage::pose_from_unknowns(&rpr, &sol.v).unwrap();
        let platform = rpr.link_pose(0, &sol.v, &legs).unwrap();
        assert_eq!(PlanarRpr::LINKS[0], "platform");
        assert!(linkage_tests::max_diff(&platform.translation, &got.translation) < 1e-9);
        let [yaw, pitch, roll] = got.euler();
        assert!((yaw - pose[0]).abs() < 1e-8, "{yaw} vs {}", pose[0]);
        assert!(pitch.abs() < 1e-9 && roll.abs() < 1e-9, "stays planar");
        let t = got.translation;
        assert!(
            (t[0] - pose[1]).abs() < 1e-7 && (t[1] - pose[2]).abs() < 1e-7 && t[2].abs() < 1e-9
        );
    }
}

linkage::mechanism! {
    /// Tsai's translational 3-UPU.
    pub struct TranslationalUpu;
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
}

#[test]
fn translational_upu_keeps_its_orientation() {
    let upu = TranslationalUpu::new();
    let start = upu.home_start().unwrap();
    check_jacobians(&upu, start.v(), start.x());
    check_factorization(&upu, start.v(), start.x());
    let a = [
        [150.0, 0.0],
        [-75.0, 75.0 * 3f64.sqrt()],
        [-75.0, -75.0 * 3f64.sqrt()],
    ];
    let g = [
        [60.0, 0.0],
        [-30.0, 30.0 * 3f64.sqrt()],
        [-30.0, -30.0 * 3f64.sqrt()],
    ];
    let mut rng = Rng::new(6);
    for _ in 0..60 {
        let t = [
            rng.uniform(-40.0, 40.0),
            rng.uniform(-40.0, 40.0),
            200.0 + rng.uniform(-40.0, 40.0),
        ];
        let legs: [f64; 3] = std::array::from_fn(|i| {
            ((t[0] + g[i][0] - a[i][0]).powi(2) + (t[1] + g[i][1] - a[i][1]).powi(2) + t[2].powi(2))
                .sqrt()
        });
        let sol = arc_length(&upu, &start, &legs, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{t:?}");
        let got = linkage::pose_from_unknowns(&upu, &sol.v).unwrap();
        for (r, row) in got.rotation.iter().enumerate() {
            for (c, x) in row.iter().enumerate() {
                let id = if r == c { 1.0 } else { 0.0 };
                assert!(
                    (x - id).abs() < 1e-8,
                    "the platform turned: {:?}",
                    got.rotation
                );
            }
        }
        for k in 0..3 {
            assert!(
                (got.translation[k] - t[k]).abs() < 1e-7,
                "{:?} vs {t:?}",
                got.translation
            );
        }
    }
}
