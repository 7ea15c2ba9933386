//! A planar five-bar declared in space, whose output is a point: against circle intersection.

use super::check_inverse;
use linkage::{arc_length, det_b, Mechanism, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, max_diff, Rng};

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
        // The output point is a link too: where it is, by the convention of a point's pose.
        let i = FiveBar::LINKS
            .iter()
            .position(|l| *l == "platform")
            .unwrap();
        let output = fb
            .link_pose(i, &sol.v, &q)
            .expect("a point platform has a pose");
        assert_eq!(Some(output), linkage::pose_from_unknowns(&fb, &sol.v));
        assert!(max_diff(&output.apply(fb.point_local(0)), &sol.v[..3]) < 1e-12);
        assert!(det_b(&fb, &sol.v, &q) * start.det() > 0.0);
        // The numerical inverse (Newton on the chains, from home).
        check_inverse(&fb, &sol.v, &q, &FiveBar::HOME_INPUTS, 1e-9);
    }
    assert!(solved >= 50, "{solved} of 60 solved");
}

/// The numerical inverse (`linkage::__private::numerical_inverse` behind `FiveBar::inverse`) on
/// points the five-bar can and cannot take: whatever it returns puts P where asked (by circle
/// intersection), and a point off its plane by more than its tolerance, out of reach, or not
/// finite is refused with the matching error, never answered.
#[test]
fn five_bar_inverse_answers_only_points_it_reaches() {
    let fb = FiveBar::new();
    let home = [FiveBar::HOME_V[0], FiveBar::HOME_V[1]];
    let mut rng = Rng::new(12);
    let mut reached = 0;
    for _ in 0..60 {
        // Points in and around the workspace (cranks 100, distal links 150, A at ±40).
        let p = [rng.uniform(-260.0, 260.0), rng.uniform(-60.0, 280.0)];
        let reachable = [-40.0f64, 40.0].iter().all(|a| {
            let d = (p[0] - a).hypot(p[1]);
            (50.0..=250.0).contains(&d)
        });
        match fb.inverse(&[p[0], p[1], 0.0], &FiveBar::HOME_INPUTS) {
            Ok(q) => {
                // Either assembly of the output point: P is one of the two intersections.
                reached += 1;
                let near = five_bar_point(q, p).expect("the returned inputs assemble");
                assert!(
                    (near[0] - p[0]).abs() < 1e-7 && (near[1] - p[1]).abs() < 1e-7,
                    "{p:?}: inputs {q:?} put P at {near:?}"
                );
            }
            Err(linkage::InverseError::Unreachable { .. }) => {
                assert!(
                    !reachable,
                    "{p:?} is within both cranks' reach and was refused"
                );
            }
            Err(e) => panic!("{p:?}: {e:?}"),
        }
    }
    assert!(reached >= 20, "{reached} of 60 reached");
    // Off the plane: 1 µm is far beyond the tolerance (1e-9 of the scale), 1e-12 mm within it.
    let [x, y] = home;
    assert!(matches!(
        fb.inverse(&[x, y, 1e-3], &FiveBar::HOME_INPUTS),
        Err(linkage::InverseError::Unreachable { .. })
    ));
    let q = fb.inverse(&[x, y, 1e-12], &FiveBar::HOME_INPUTS).unwrap();
    assert!(linkage_tests::max_diff(&q, &FiveBar::HOME_INPUTS) < 1e-9);
    // Not finite, or so large that the equations overflow: an error, not a panic or an answer.
    for bad in [[f64::NAN, y, 0.0], [x, f64::INFINITY, 0.0]] {
        assert_eq!(
            fb.inverse(&bad, &FiveBar::HOME_INPUTS),
            Err(linkage::InverseError::NonFinite)
        );
    }
    assert!(fb
        .inverse(&[1e200, -1e200, 0.0], &FiveBar::HOME_INPUTS)
        .is_err());
    assert_eq!(
        fb.inverse(&[x, y, 0.0], &[f64::NAN, 0.0]),
        Err(linkage::InverseError::NonFinite)
    );
}

/// The five-bar declared in space is over-constrained: the sphere of the right distal link
/// about the right crank's upper axis point is left out as dependent at home (see its
/// listing). `dependent_offset` measures how far a configuration is from it: 0 at home, the
/// distance to that sphere (to first order) elsewhere, infinite for NaN — and the solvers
/// refuse an answer off it (`Status::BranchChanged`).
#[test]
fn five_bar_measures_its_left_out_equation() {
    let five = FiveBar::new();
    assert!(FiveBar::LISTING.contains("dependent at home"));
    let (v0, x0) = (FiveBar::HOME_V, FiveBar::HOME_INPUTS);
    assert!(five.dependent_offset(&v0, &x0) < 1e-12);
    let r = 100.0;
    let centre = [
        40.0 + r * (std::f64::consts::PI / 3.0).cos(),
        r * (std::f64::consts::PI / 3.0).sin(),
        1.0,
    ];
    let dist = |p: &[f64; 3]| {
        (0..3)
            .map(|k| (p[k] - centre[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let d = dist(&v0);
    let mut rng = Rng::new(5);
    for _ in 0..50 {
        let p = [0, 1, 2].map(|k| v0[k] + rng.uniform(-2.0, 2.0));
        let off = five.dependent_offset(&p, &x0);
        let exact = (dist(&p) - d).abs();
        assert!(
            (off - exact).abs() <= 0.05 * exact + 1e-12,
            "{off} vs {exact}"
        );
    }
    assert_eq!(
        five.dependent_offset(&[f64::NAN, 0.0, 0.0], &x0),
        f64::INFINITY
    );
}

/// A point platform's velocity is the point's (ω zero: no pair turns a point), checked against
/// central differences of the circle intersection; the inverse and the statics through the same
/// Jacobian; a turn or a moment asked of the point is left over or takes no effort.
#[test]
fn a_five_bar_has_the_velocity_of_its_output_point() {
    use linkage::velocity::{input_efforts, input_rates, platform_jacobian, twist, Twist, Wrench};
    use linkage::velocity::{pivot_rates, VelocityError};
    let fb = FiveBar::new();
    let start = fb.home_start().unwrap();
    let home = [start.v()[0], start.v()[1]];
    let mut rng = Rng::new(29);
    let mut checked = 0;
    for _ in 0..20 {
        let q = [rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)];
        let sol = arc_length(&fb, &start, &q, &Options::TIGHT).unwrap();
        if sol.status != Status::Converged {
            continue;
        }
        checked += 1;
        // The reference: ∂P/∂q by central differences of the circle intersection.
        let h = 1e-6;
        let reference: [[f64; 2]; 2] = std::array::from_fn(|j| {
            let (mut up, mut down) = (q, q);
            up[j] += h;
            down[j] -= h;
            let (a, b) = (
                five_bar_point(up, home).unwrap(),
                five_bar_point(down, home).unwrap(),
            );
            [(a[0] - b[0]) / (2.0 * h), (a[1] - b[1]) / (2.0 * h)]
        });
        let j = platform_jacobian(&fb, &sol.v, &q).unwrap();
        for (input, column) in reference.iter().enumerate() {
            for axis in 0..3 {
                assert_eq!(j[axis][input], 0.0, "ω of input {input}");
            }
            let scale = column[0].abs().max(column[1].abs());
            for axis in 0..2 {
                let d = (j[3 + axis][input] - column[axis]).abs();
                assert!(
                    d < 1e-6 * scale,
                    "q = {q:?}, input {input}: {:?} vs {column:?}",
                    j
                );
            }
            assert!(
                j[5][input].abs() < 1e-9 * scale,
                "the point stays in its plane"
            );
        }
        // The twist of some rates is the point's rate.
        let xdot = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)];
        let t = twist(&fb, &sol.v, &q, &xdot).unwrap();
        let vdot = pivot_rates(&fb, &sol.v, &q, &xdot).unwrap();
        assert_eq!(t.angular, [0.0; 3]);
        assert!(
            linkage_tests::max_diff(&t.linear, &vdot) < 1e-12,
            "{t:?} vs {vdot:?}"
        );
        // Back from that velocity, with a turn and a rise asked besides: the rates again, the
        // turn and the rise left over.
        let wanted = Twist {
            angular: [0.3, -0.2, 0.5],
            linear: [t.linear[0], t.linear[1], 0.7],
        };
        let back = input_rates(&fb, &sol.v, &q, &wanted).unwrap();
        assert!(
            linkage_tests::max_diff(&back.rates, &xdot) < 1e-9,
            "{:?} vs {xdot:?}",
            back.rates
        );
        assert!(linkage_tests::max_diff(&back.left_over.angular, &[-0.3, 0.2, -0.5]) < 1e-12);
        assert!(linkage_tests::max_diff(&back.left_over.linear, &[0.0, 0.0, -0.7]) < 1e-9);
        // A force in the plane: τ = Jᵀ f by the reference Jacobian; a moment: no effort.
        let force = [rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0), 3.0];
        let tau = input_efforts(
            &fb,
            &sol.v,
            &q,
            &Wrench {
                moment: [1.0, 2.0, 3.0],
                force,
            },
        )
        .unwrap();
        for (input, column) in reference.iter().enumerate() {
            let expected = column[0] * force[0] + column[1] * force[1];
            assert!(
                (tau[input] - expected).abs() < 1e-5 * (1.0 + expected.abs()),
                "{tau:?}"
            );
        }
    }
    assert!(checked >= 15, "{checked} of 20 solved");
    let mut bad = *start.v();
    bad[1] = f64::NAN;
    assert_eq!(
        twist(&fb, &bad, start.x(), &[1.0, 0.0]),
        Err(VelocityError::NonFinite)
    );
}
