//! A planar 3-RPR with true R–P–R legs: against closed-form inverse kinematics.

use super::{check_inverse, GENERAL_MODEL};
use linkage::{arc_length, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

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
        check_inverse(&rpr, &sol.v, &legs, &PlanarRpr::HOME_INPUTS, 1e-8);
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

/// A revolute axis given by two pivots of a moving link is refused at run time when they
/// coincide, as it is at compile time: moved so by `set_pivot` (or in `from_geometry`), the
/// 3-RPR's third platform hinge has no axis, and the equations the generator left out as
/// dependent fail at home (the start was accepted and every solve refused).
#[test]
fn a_platform_axis_given_by_coincident_pivots_is_refused() {
    let nominal = PlanarRpr::new();
    let g3 = [-30.0, -51.96152422706632, 0.0];
    let mut rpr = nominal.clone();
    assert_eq!(
        rpr.set_pivot("platform", "G3z", g3),
        Err(linkage::GeometryError::DegenerateAxis)
    );
    assert_eq!(rpr, nominal, "unchanged on error");
    // A hair apart, relative to the mechanism's size: still refused; half a millimetre apart
    // (half the declared lever): kept, and the machine starts.
    let mut near = g3;
    near[2] = 1e-11;
    assert!(rpr.set_pivot("platform", "G3z", near).is_err());
    near[2] = 0.5;
    assert!(rpr.set_pivot("platform", "G3z", near).is_ok());
    assert!(rpr.home_start().is_ok(), "{:?}", rpr.home_start().err());
    // The base's axes too, through `from_geometry`.
    let names = PlanarRpr::GEOMETRY_NAMES;
    let mut g = PlanarRpr::DEFAULT_GEOMETRY;
    let at = |n: &str| names.iter().position(|m| *m == n).unwrap();
    g[at("base.A1z.z")] = g[at("base.A1.z")];
    assert_eq!(
        PlanarRpr::from_geometry(g),
        Err(linkage::GeometryError::DegenerateAxis)
    );
}

/// Axes declared by points 1 mm apart sense the platform's rotation through 1 mm levers: the
/// `f64` residual's rounding then hides errors of about 1e-10 mm. Answers were labelled ok at
/// a tolerance of 1e-11 mm while up to 1.4e-10 mm from the root of the same `f64` equations
/// (and from the closed form). Every answer that meets the tolerance must be within it of that
/// root, found in double-double arithmetic; near the floor the solvers now measure their
/// correction the same way, and refine by it, so that most answers do meet it.
#[test]
fn planar_rpr_answers_within_a_tolerance_below_its_rounding_floor_are_so() {
    let rpr = PlanarRpr::new();
    let start = rpr.home_start().unwrap();
    let mut rng = Rng::new(11);
    let (mut met, cases) = (0, 40);
    for _ in 0..cases {
        let pose = [
            0.3 + rng.uniform(-0.2, 0.2),
            10.0 + rng.uniform(-30.0, 30.0),
            5.0 + rng.uniform(-30.0, 30.0),
        ];
        let legs = rpr_legs(pose);
        let posed = linkage::unknowns_from_pose(
            &rpr,
            &linkage::Pose::from_euler(pose[0], 0.0, 0.0, [pose[1], pose[2], 0.0]),
        );
        for tol in [1e-10, 1e-11] {
            let options = linkage::Options {
                tolerance: tol,
                ..GENERAL_MODEL
            };
            for sol in [
                arc_length(&rpr, &start, &legs, &options).unwrap(),
                linkage::newton_raphson(&rpr, &start, &legs, &options).unwrap(),
            ] {
                if !sol.status.meets_tolerance() {
                    continue;
                }
                met += 1;
                // The link points between are not posed: the platform's are compared.
                let platform = 3 * <PlanarRpr as linkage::Mechanism<27, 3>>::POINTS.len();
                let root = linkage_tests::exact_root::exact_root(&rpr, &sol.v, &legs).unwrap();
                let err = (0..sol.v.len())
                    .map(|i| (sol.v[i] - root[i]).powi(2))
                    .sum::<f64>()
                    .sqrt();
                assert!(
                    err <= 1.02 * tol,
                    "{pose:?}: ok at {tol:e} but {err:e} from the root"
                );
                assert!(linkage_tests::max_diff(&sol.v[..platform], &posed[..platform]) < 1e-9);
            }
        }
    }
    assert!(
        met >= cases * 4 * 3 / 4,
        "{met} of {} answers met the tolerance",
        cases * 4
    );
}

linkage::mechanism! {
    /// A planar 3-RPR whose base and platform triangles are not similar (the generic case).
    pub struct PlanarRprGeneric;
    base {
        A1 = [0.0, 0.0, 0.0], A1z = [0.0, 0.0, 1.0],
        A2 = [250.0, 20.0, 0.0], A2z = [250.0, 20.0, 1.0],
        A3 = [90.0, 210.0, 0.0], A3z = [90.0, 210.0, 1.0],
    }
    platform(home = [0.2, 0.0, 0.0, 100.0, 70.0, 0.0]) {
        G1 = [-30.0, -20.0, 0.0], G1z = [-30.0, -20.0, 1.0],
        G2 = [45.0, -10.0, 0.0], G2z = [45.0, -10.0, 1.0],
        G3 = [5.0, 40.0, 0.0], G3z = [5.0, 40.0, 1.0],
    }
    chain leg1 = base - R(passive, axis = A1 -> A1z) - P(active L1) - R(passive, axis = G1 -> G1z) - platform;
    chain leg2 = base - R(passive, axis = A2 -> A2z) - P(active L2) - R(passive, axis = G2 -> G2z) - platform;
    chain leg3 = base - R(passive, axis = A3 -> A3z) - P(active L3) - R(passive, axis = G3 -> G3z) - platform;
}

/// A planar 3-RPR's pivots: base `a`, platform `g` (its own frame). Also the closed form of
/// any planar mechanism whose platform hangs from three fixed points by three rigid bars.
pub(super) struct Rpr {
    pub(super) a: [[f64; 2]; 3],
    pub(super) g: [[f64; 2]; 3],
}

const GENERIC: Rpr = Rpr {
    a: [[0.0, 0.0], [250.0, 20.0], [90.0, 210.0]],
    g: [[-30.0, -20.0], [45.0, -10.0], [5.0, 40.0]],
};

fn rotate(phi: f64, g: [f64; 2]) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    [c * g[0] - s * g[1], s * g[0] + c * g[1]]
}

impl Rpr {
    /// Closed-form inverse kinematics at the planar pose (φ, x, y).
    pub(super) fn legs(&self, pose: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            let g = rotate(pose[0], self.g[i]);
            (g[0] + pose[1] - self.a[i][0]).hypot(g[1] + pose[2] - self.a[i][1])
        })
    }

    /// An independent count of the real assembly modes: for each orientation φ (a fine scan
    /// of the circle), legs 1 and 2 put the platform origin on two circles, met in up to two
    /// points; leg 3's length error changes sign at every real mode.
    pub(super) fn scanned_real_modes(&self, legs: [f64; 3]) -> usize {
        let samples = 200_000;
        let mut count = 0;
        let mut previous: [Option<f64>; 2] = [None, None];
        for k in 0..=samples {
            let phi = -std::f64::consts::PI + std::f64::consts::TAU * k as f64 / samples as f64;
            // Origin t with |R g_i + t − a_i| = L_i: circles about c_i = a_i − R g_i.
            let c: [[f64; 2]; 2] = std::array::from_fn(|i| {
                let g = rotate(phi, self.g[i]);
                [self.a[i][0] - g[0], self.a[i][1] - g[1]]
            });
            let (dx, dy) = (c[1][0] - c[0][0], c[1][1] - c[0][1]);
            let d = dx.hypot(dy);
            let a = (legs[0] * legs[0] - legs[1] * legs[1] + d * d) / (2.0 * d);
            let h2 = legs[0] * legs[0] - a * a;
            for (b, sign) in [1.0, -1.0].into_iter().enumerate() {
                let f = (h2 >= 0.0).then(|| {
                    let h = sign * h2.sqrt();
                    let t = [
                        c[0][0] + (a * dx - h * dy) / d,
                        c[0][1] + (a * dy + h * dx) / d,
                    ];
                    let g = rotate(phi, self.g[2]);
                    (g[0] + t[0] - self.a[2][0]).hypot(g[1] + t[1] - self.a[2][1]) - legs[2]
                });
                if let (Some(p), Some(q)) = (previous[b], f) {
                    if p * q < 0.0 {
                        count += 1;
                    }
                }
                previous[b] = f;
            }
        }
        count
    }

    /// Every real root a query returned: planar, and giving the legs back.
    pub(super) fn check_real_roots<const N: usize>(
        &self,
        roots: &[linkage::modes::RealRoot<N>],
        legs: [f64; 3],
    ) {
        for r in roots {
            let p = r.pose.unwrap();
            let [yaw, pitch, roll] = p.euler();
            assert!(pitch.abs() < 1e-8 && roll.abs() < 1e-8 && p.translation[2].abs() < 1e-8);
            let back = self.legs([yaw, p.translation[0], p.translation[1]]);
            for i in 0..3 {
                assert!((back[i] - legs[i]).abs() < 1e-8, "{back:?} vs {legs:?}");
            }
        }
    }
}

/// Every assembly mode (`linkage::modes`) of a generic planar 3-RPR: 6 complex roots (the
/// closed form is a sextic); at legs from random poses the real ones are exactly those an
/// independent scan finds, the pose the legs came from among them, and each one's legs those
/// asked for (closed-form inverse kinematics). (The similar-triangle [`PlanarRpr`] above is not
/// generic: monodromy finds 4 complex roots for it.)
#[test]
fn generic_planar_rpr_has_six_assembly_modes() {
    use linkage::modes::{AllModes, ModesOptions, Roots};
    let rpr = PlanarRprGeneric::new();
    let modes = AllModes::<_, 27, 3, 16>::new(rpr.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 6, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<27, 16>::new());
    let mut rng = Rng::new(36);
    let mut real_total = 0;
    for _ in 0..20 {
        let pose = [
            0.2 + rng.uniform(-0.5, 0.5),
            100.0 + rng.uniform(-30.0, 30.0),
            70.0 + rng.uniform(-30.0, 30.0),
        ];
        let legs = GENERIC.legs(pose);
        modes.solve(&legs, &mut roots).unwrap();
        assert!(roots.is_complete(), "{pose:?}");
        let scanned = GENERIC.scanned_real_modes(legs);
        assert_eq!(roots.real().len(), scanned, "{pose:?}");
        real_total += scanned;
        GENERIC.check_real_roots(roots.real(), legs);
        let mut truth = false;
        for r in roots.real() {
            let p = r.pose.unwrap();
            let [yaw, _, _] = p.euler();
            truth |= (yaw - pose[0]).abs() < 1e-8
                && (p.translation[0] - pose[1]).abs() < 1e-7
                && (p.translation[1] - pose[2]).abs() < 1e-7;
        }
        assert!(
            truth,
            "{pose:?}: the generating pose is not among the real modes"
        );
    }
    println!("generic 3-RPR: 20 random poses, {real_total} real modes, as the scan found");
}

/// The 3-RPR example used since Gosselin, Sefrioui & Richard (1992) to show that a planar
/// 3-RPR can have six real assembly modes, the most its sextic allows: base pivots (0, 0),
/// (15.91, 0), (0, 10); platform sides 17.04 and 16.54 from its first pivot, 0.8843 rad
/// apart; legs 14.98, 15.38 and 12. Set on [`PlanarRprGeneric`] as runtime geometry: all six
/// roots real, as the independent scan finds, each giving the legs back.
#[test]
fn published_planar_rpr_has_six_real_assembly_modes() {
    use linkage::modes::{AllModes, ModesOptions, Roots};
    let (l2, l3, theta) = (17.04, 16.54, 0.8843f64);
    let published = Rpr {
        a: [[0.0, 0.0], [15.91, 0.0], [0.0, 10.0]],
        g: [[0.0, 0.0], [l2, 0.0], [l3 * theta.cos(), l3 * theta.sin()]],
    };
    let legs = [14.98, 15.38, 12.0];
    assert_eq!(published.scanned_real_modes(legs), 6);
    // All pivots at once (one at a time, the platform's pivots would pass through
    // non-coplanar placements, which its rigid-body form refuses).
    let mut geometry = *PlanarRprGeneric::new().geometry();
    let mut set = |link: &str, pivot: String, p: [f64; 3]| {
        for (axis, value) in ["x", "y", "z"].iter().zip(p) {
            let name = format!("{link}.{pivot}.{axis}");
            let i = PlanarRprGeneric::GEOMETRY_NAMES
                .iter()
                .position(|n| *n == name);
            geometry[i.unwrap_or_else(|| panic!("{name}"))] = value;
        }
    };
    for (k, (a, g)) in published.a.iter().zip(&published.g).enumerate() {
        let (base, platform) = (format!("A{}", k + 1), format!("G{}", k + 1));
        set("base", format!("{base}z"), [a[0], a[1], 1.0]);
        set("base", base, [a[0], a[1], 0.0]);
        set("platform", format!("{platform}z"), [g[0], g[1], 1.0]);
        set("platform", platform, [g[0], g[1], 0.0]);
    }
    let rpr = PlanarRprGeneric::from_geometry(geometry).unwrap();
    let modes = AllModes::<_, 27, 3, 16>::new(rpr, &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 6, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<27, 16>::new());
    modes.solve(&legs, &mut roots).unwrap();
    assert!(roots.is_complete());
    assert_eq!(roots.real().len(), 6);
    published.check_real_roots(roots.real(), legs);
    let mut yaws: Vec<f64> = roots
        .real()
        .iter()
        .map(|r| r.pose.unwrap().euler()[0])
        .collect();
    yaws.sort_by(f64::total_cmp);
    println!("published 3-RPR: six real assembly modes at platform angles {yaws:.4?}");
}
