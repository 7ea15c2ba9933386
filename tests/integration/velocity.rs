//! Velocity kinematics against finite differences of forward kinematics, against the dense
//! Jacobians, and against each other (the twist's rigid motion at every platform pivot; the
//! input rates back from a twist).

use linkage::velocity::{
    input_efforts, input_rates, pivot_rates, platform_jacobian, twist, Twist, VelocityError, Wrench,
};
use linkage::{newton_raphson, pose_from_unknowns, Mechanism, Options, Pose, Start};
use linkage_examples::{rps, rss_hexapod, stewart};
use linkage_tests::{stewart_pose_samples, Rng};

/// FK at `x + h·xdot`, Newton from the solution `(v, x)`.
fn fk_along<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    xdot: &[f64; M],
    h: f64,
) -> [f64; N] {
    let x: [f64; M] = std::array::from_fn(|j| start.x()[j] + h * xdot[j]);
    let sol = newton_raphson(sys, start, &x, &Options::TIGHT).unwrap();
    assert!(sol.status.meets_tolerance(), "{:?}", sol.status);
    sol.v
}

/// Checks the rates at the solution `(v, x)` for `xdot`: central differences of FK (step `h`),
/// B v̇ + (∂F/∂x) ẋ = 0 with the dense Jacobians, the twist's rigid motion at every platform
/// pivot, the twist against differences of the pose, and the platform Jacobian's columns.
/// Returns the twist.
fn check_rates<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    v: &[f64; N],
    x: &[f64; M],
    xdot: &[f64; M],
    h: f64,
) -> Twist {
    let start = Start::new(sys, *v, *x).unwrap();
    let (v, x) = (start.v(), start.x());
    let vdot = pivot_rates(sys, v, x, xdot).unwrap();
    let scale = vdot.iter().fold(0.0f64, |m, r| m.max(r.abs())).max(1e-12);

    // Central differences of FK: truncation O(h²), the solves' 1e-9 over 2h.
    let plus = fk_along(sys, &start, xdot, h);
    let minus = fk_along(sys, &start, xdot, -h);
    for i in 0..N {
        let fd = (plus[i] - minus[i]) / (2.0 * h);
        assert!(
            (fd - vdot[i]).abs() <= 1e-5 * scale,
            "{}: {} by differences, {} by the rates",
            S::UNKNOWNS[i],
            fd,
            vdot[i]
        );
    }

    // B v̇ + (∂F/∂x) ẋ = 0 with the dense matrices, independent of the sparse factorisation.
    let mut b = [[0.0; N]; N];
    sys.jacobian_dense(v, x, &mut b);
    let mut a = [[0.0; M]; N];
    sys.input_jacobian(v, x, &mut a);
    // Backward error against the whole system's size (a row of exact zeros, as an R pair's
    // axis rows are here, is rounding of that size).
    let size = (0..N)
        .map(|i| {
            (0..N).map(|k| (b[i][k] * vdot[k]).abs()).sum::<f64>()
                + (0..M).map(|j| (a[i][j] * xdot[j]).abs()).sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    for i in 0..N {
        let row: f64 = (0..N).map(|k| b[i][k] * vdot[k]).sum::<f64>()
            + (0..M).map(|j| a[i][j] * xdot[j]).sum::<f64>();
        assert!(row.abs() <= 1e-12 * size, "row {i}: {row} of {size}");
    }

    // The twist moves every platform pivot as v̇ does, not only the frame's three.
    let t = twist(sys, v, x, xdot).unwrap();
    let pose = pose_from_unknowns(sys, v).unwrap();
    let k = S::POINTS.len();
    let platform_pivots = (0..k).filter(|&p| {
        let local = sys.point_local(p);
        local.iter().all(|c| c.is_finite())
            && (0..3).all(|axis| (pose.apply(local)[axis] - v[axis * k + p]).abs() < 1e-6)
    });
    let mut checked = 0;
    for p in platform_pivots {
        let at = t.at(pose.translation, [v[p], v[k + p], v[2 * k + p]]);
        for axis in 0..3 {
            let r = vdot[axis * k + p];
            assert!(
                (at[axis] - r).abs() <= 1e-9 * scale,
                "{}: {at:?} vs {r}",
                S::POINTS[p]
            );
        }
        checked += 1;
    }
    assert!(checked >= 3, "{checked} platform pivots");

    // The twist against the pose's differences: Ṫ, and Ṙ Rᵀ = [ω]×.
    let pp = pose_from_unknowns(sys, &plus).unwrap();
    let pm = pose_from_unknowns(sys, &minus).unwrap();
    let tscale = t
        .angular
        .iter()
        .chain(&t.linear)
        .fold(0.0f64, |m, c| m.max(c.abs()));
    for i in 0..3 {
        let fd = (pp.translation[i] - pm.translation[i]) / (2.0 * h);
        assert!(
            (fd - t.linear[i]).abs() <= 1e-5 * tscale,
            "origin {i}: {fd} vs {}",
            t.linear[i]
        );
    }
    let r = pose.rotation;
    let w = |i: usize, j: usize| {
        (0..3)
            .map(|c| (pp.rotation[i][c] - pm.rotation[i][c]) / (2.0 * h) * r[j][c])
            .sum::<f64>()
    };
    let omega = [w(2, 1), w(0, 2), w(1, 0)];
    for i in 0..3 {
        assert!(
            (omega[i] - t.angular[i]).abs() <= 1e-5 * tscale,
            "ω: {omega:?} vs {:?}",
            t.angular
        );
    }

    // The platform Jacobian's columns are the twists of unit rates, and J ẋ is this twist.
    let j = platform_jacobian(sys, v, x).unwrap();
    let combined: Vec<f64> = (0..6)
        .map(|r| (0..M).map(|c| j[r][c] * xdot[c]).sum())
        .collect();
    let expected = [t.angular, t.linear].concat();
    for r in 0..6 {
        assert!(
            (combined[r] - expected[r]).abs() <= 1e-9 * tscale,
            "J ẋ row {r}"
        );
    }
    t
}

#[test]
fn stewart_rates_agree_with_differences_and_give_the_legs_back() {
    let s = stewart::Stewart::new();
    let mut rng = Rng::new(17);
    for sample in stewart_pose_samples(2026, 6, 0.2, 20.0, 8) {
        let xdot: [f64; 6] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let t = check_rates(&s, &sample.v, &sample.x, &xdot, 1e-3);
        // Six legs move a platform of six freedoms: any twist, exactly.
        let back = input_rates(&s, &sample.v, &sample.x, &t).unwrap();
        for j in 0..6 {
            assert!(
                (back.rates[j] - xdot[j]).abs() < 1e-9,
                "{:?} vs {xdot:?}",
                back.rates
            );
        }
        let left = back.left_over.angular.iter().chain(&back.left_over.linear);
        assert!(left.clone().all(|e| e.abs() < 1e-9), "{:?}", back.left_over);
    }
}

#[test]
fn rotary_hexapod_rates_agree_with_differences() {
    let h = rss_hexapod::RssHexapod::new();
    let start = rss_hexapod::home_start(&h).unwrap();
    let mut rng = Rng::new(5);
    for _ in 0..4 {
        // A configuration near home, then crank rates.
        let x: [f64; 6] = std::array::from_fn(|j| start.x()[j] + rng.uniform(-0.1, 0.1));
        let v = newton_raphson(&h, &start, &x, &Options::TIGHT).unwrap().v;
        let xdot: [f64; 6] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
        let t = check_rates(&h, &v, &x, &xdot, 1e-5);
        let back = input_rates(&h, &v, &x, &t).unwrap();
        for j in 0..6 {
            assert!(
                (back.rates[j] - xdot[j]).abs() < 1e-8,
                "{:?} vs {xdot:?}",
                back.rates
            );
        }
    }
}

#[test]
fn three_rps_makes_some_twists_and_says_what_it_cannot() {
    let r = rps::Rps3::new();
    let start = rps::home_start(&r).unwrap();
    let (v, x) = (*start.v(), *start.x());
    let xdot = [1.0, -0.5, 0.25];
    let t = check_rates(&r, &v, &x, &xdot, 1e-3);
    // A twist the legs made: their rates back, nothing left over.
    let back = input_rates(&r, &v, &x, &t).unwrap();
    assert!(
        back.rates
            .iter()
            .zip(&xdot)
            .all(|(a, b)| (a - b).abs() < 1e-9),
        "{back:?}"
    );
    // A sideways slide the 3-RPS cannot make: rates still, and a left-over part to show it.
    let slide = Twist {
        angular: [0.0; 3],
        linear: [1.0, 0.0, 0.0],
    };
    let back = input_rates(&r, &v, &x, &slide).unwrap();
    let left = back.left_over.angular.iter().chain(&back.left_over.linear);
    assert!(left.fold(0.0f64, |m, e| m.max(e.abs())) > 0.1, "{back:?}");
    // Least squares: the left-over part is orthogonal to what the inputs can do.
    let j = platform_jacobian(&r, &v, &x).unwrap();
    // The weight of the angular rows: the distance between the first two frame pivots.
    let size = {
        let k = rps::Rps3::POINTS.len();
        let f = rps::Rps3::FRAME;
        let d: Vec<f64> = (0..3).map(|a| v[a * k + f[1]] - v[a * k + f[0]]).collect();
        d.iter().map(|c| c * c).sum::<f64>().sqrt()
    };
    let l = [back.left_over.angular, back.left_over.linear].concat();
    for c in 0..3 {
        let dot: f64 = (0..6)
            .map(|row| {
                let w = if row < 3 { size * size } else { 1.0 };
                w * j[row][c] * l[row]
            })
            .sum();
        assert!(dot.abs() < 1e-9, "column {c}: {dot}");
    }
}

#[test]
fn bad_configurations_are_typed_errors() {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let (v, x) = (*st.v(), *st.x());
    let xdot = [1.0; 6];
    let k = stewart::Stewart::POINTS.len();

    // A leg of length zero (G1 on D1): B has a zero row.
    let mut zero = v;
    let d1 = [200.764, 53.795, 0.0];
    for axis in 0..3 {
        zero[axis * k] = d1[axis];
    }
    assert_eq!(
        pivot_rates(&s, &zero, &x, &xdot),
        Err(VelocityError::Singular)
    );
    assert_eq!(twist(&s, &zero, &x, &xdot), Err(VelocityError::Singular));

    // Inputs that are not the configuration's: a leg 10 mm longer than v has it.
    let mut other = x;
    other[2] += 10.0;
    assert!(matches!(
        pivot_rates(&s, &v, &other, &xdot),
        Err(VelocityError::NotASolution { error }) if error > 1.0
    ));
    // Within the solvers' loosest tolerance (1e-3 of ‖v‖), a solution still.
    other[2] = x[2] + 1e-6;
    assert!(pivot_rates(&s, &v, &other, &xdot).is_ok());

    // NaN anywhere.
    let mut nan = xdot;
    nan[3] = f64::NAN;
    assert_eq!(pivot_rates(&s, &v, &x, &nan), Err(VelocityError::NonFinite));
    let mut vnan = v;
    vnan[7] = f64::INFINITY;
    assert_eq!(
        pivot_rates(&s, &vnan, &x, &xdot),
        Err(VelocityError::NonFinite)
    );
    let wanted = Twist {
        angular: [f64::NAN, 0.0, 0.0],
        linear: [0.0; 3],
    };
    assert_eq!(
        input_rates(&s, &v, &x, &wanted).unwrap_err(),
        VelocityError::NonFinite
    );

    // The frame pivots on one line: no angular velocity to speak of.
    let f = stewart::Stewart::FRAME;
    let mut collinear = v;
    for axis in 0..3 {
        let (a, b) = (v[axis * k + f[0]], v[axis * k + f[1]]);
        collinear[axis * k + f[2]] = 2.0 * b - a;
    }
    assert_eq!(
        twist(&s, &collinear, &x, &xdot),
        Err(VelocityError::NoFrame)
    );
    assert_eq!(
        platform_jacobian(&s, &collinear, &x),
        Err(VelocityError::NoFrame)
    );
}

#[test]
fn a_pure_rotation_about_the_origin_moves_pivots_around_it() {
    // Independent of the solver: the twist of a known rigid motion, built from poses.
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    let home = pose_from_unknowns(&s, st.v()).unwrap();
    let [y, p, r] = home.euler();
    let h = 1e-6;
    let at = |t: f64| {
        let pose = Pose::from_euler(y + t, p, r, home.translation);
        let (x, v) = stewart::legs_for_pose(&s, &pose).unwrap();
        (x, v)
    };
    let (xp, _) = at(h);
    let (xm, _) = at(-h);
    let (x0, v0) = at(0.0);
    let xdot: [f64; 6] = std::array::from_fn(|j| (xp[j] - xm[j]) / (2.0 * h));
    let t = twist(&s, &v0, &x0, &xdot).unwrap();
    // A yaw rate of 1 about the frame origin: ω = (0, 0, 1), the origin still.
    assert!((t.angular[2] - 1.0).abs() < 1e-6, "{t:?}");
    assert!(
        t.angular[0].abs() < 1e-6 && t.angular[1].abs() < 1e-6,
        "{t:?}"
    );
    assert!(t.linear.iter().all(|c| c.abs() < 1e-4), "{t:?}");
}

#[test]
fn stewart_leg_forces_hold_the_platform_in_equilibrium() {
    // Independent statics: the legs push the platform along their own lines (u_i from base to
    // platform, from B's leg rows 2 (G_i − D_i)) with forces −τ_i; with the load they must sum
    // to zero force and zero moment about the frame origin.
    let s = stewart::Stewart::new();
    let mut rng = Rng::new(99);
    for sample in stewart_pose_samples(7, 4, 0.2, 20.0, 8) {
        let (v, x) = (sample.v, sample.x);
        let load = Wrench {
            moment: std::array::from_fn(|_| rng.uniform(-500.0, 500.0)),
            force: std::array::from_fn(|_| rng.uniform(-20.0, 20.0)),
        };
        let tau = input_efforts(&s, &v, &x, &load).unwrap();
        let mut b = [[0.0; 18]; 18];
        s.jacobian_dense(&v, &x, &mut b);
        let origin = pose_from_unknowns(&s, &v).unwrap().translation;
        let (mut force, mut moment) = (load.force, load.moment);
        for leg in 0..6 {
            let row = [b[leg][leg], b[leg][6 + leg], b[leg][12 + leg]];
            let len = row.iter().map(|c| c * c).sum::<f64>().sqrt();
            let f: [f64; 3] = std::array::from_fn(|a| -tau[leg] * row[a] / len);
            let r: [f64; 3] = std::array::from_fn(|a| v[6 * a + leg] - origin[a]);
            let m = [
                r[1] * f[2] - r[2] * f[1],
                r[2] * f[0] - r[0] * f[2],
                r[0] * f[1] - r[1] * f[0],
            ];
            for a in 0..3 {
                force[a] += f[a];
                moment[a] += m[a];
            }
        }
        assert!(force.iter().all(|c| c.abs() < 1e-9), "{force:?}");
        assert!(moment.iter().all(|c| c.abs() < 1e-7), "{moment:?}");
    }
}

#[test]
fn efforts_and_rates_agree_by_virtual_work() {
    // τ · ẋ = moment · ω + force · v_o for any rates: on the rotary hexapod (torques at the
    // cranks) and the 3-RPS (fewer inputs than freedoms).
    fn check<S: Mechanism<N, M>, const N: usize, const M: usize>(
        sys: &S,
        v: &[f64; N],
        x: &[f64; M],
        rng: &mut Rng,
    ) {
        let load = Wrench {
            moment: std::array::from_fn(|_| rng.uniform(-100.0, 100.0)),
            force: std::array::from_fn(|_| rng.uniform(-10.0, 10.0)),
        };
        let tau = input_efforts(sys, v, x, &load).unwrap();
        for _ in 0..5 {
            let xdot: [f64; M] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
            let t = twist(sys, v, x, &xdot).unwrap();
            let input: f64 = tau.iter().zip(&xdot).map(|(a, b)| a * b).sum();
            let platform: f64 = (0..3)
                .map(|i| load.moment[i] * t.angular[i] + load.force[i] * t.linear[i])
                .sum();
            assert!(
                (input - platform).abs() <= 1e-10 * input.abs().max(platform.abs()).max(1.0),
                "{input} vs {platform}"
            );
        }
    }
    let mut rng = Rng::new(3);
    let h = rss_hexapod::RssHexapod::new();
    let hs = rss_hexapod::home_start(&h).unwrap();
    check(&h, hs.v(), hs.x(), &mut rng);
    let r = rps::Rps3::new();
    let rs = rps::home_start(&r).unwrap();
    check(&r, rs.v(), rs.x(), &mut rng);
    let bad = Wrench {
        moment: [0.0; 3],
        force: [f64::INFINITY, 0.0, 0.0],
    };
    assert_eq!(
        input_efforts(&r, rs.v(), rs.x(), &bad),
        Err(VelocityError::NonFinite)
    );
}
