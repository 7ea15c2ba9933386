//! Stewart platforms whose legs meet in pairs: the 6-3 (six base pivots, three platform
//! pivots) and the octahedral 3-3 (three and three). Their forward kinematics has 16 complex
//! solutions (Innocenti & Parenti-Castelli 1990 for the 6-3; the octahedron likewise): each
//! platform pivot lies on the circle where the spheres of its two legs meet, which gives an
//! independent count of the real assembly modes (a scan of one circle), checked here against
//! every real root that `linkage::modes` returns.

use super::all_modes::check_count;
use super::{check_inverse, GENERAL_MODEL};
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage::{arc_length, Mechanism, Pose, Start, Status};
use linkage_tests::vec3::{add, cross, dot, scaled, sub};
use linkage_tests::{check_factorization, check_jacobians, Rng};

linkage::mechanism! {
    /// A 6-3 Stewart platform: legs 1–2, 3–4 and 5–6 meet at the platform's three pivots.
    pub struct SixThree;
    base {
        D1 = [100.0, 0.0, 0.0], D2 = [80.0, 60.0, 0.0], D3 = [-40.0, 90.0, 0.0],
        D4 = [-90.0, 30.0, 0.0], D5 = [-50.0, -80.0, 0.0], D6 = [60.0, -85.0, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 120.0]) {
        G1 = [50.0, 20.0, 0.0], G2 = [-40.0, 35.0, 0.0], G3 = [-5.0, -50.0, 0.0],
    }
    chain leg1 = base - S(D1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - S(D2) - P(active L2) - S(G1) - platform;
    chain leg3 = base - S(D3) - P(active L3) - S(G2) - platform;
    chain leg4 = base - S(D4) - P(active L4) - S(G2) - platform;
    chain leg5 = base - S(D5) - P(active L5) - S(G3) - platform;
    chain leg6 = base - S(D6) - P(active L6) - S(G3) - platform;
}

linkage::mechanism! {
    /// The octahedral 3-3 Stewart platform: every base and every platform pivot holds two legs.
    pub struct ThreeThree;
    base { D1 = [120.0, 0.0, 0.0], D2 = [-55.0, 100.0, 0.0], D3 = [-65.0, -95.0, 0.0] }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, 110.0]) {
        G1 = [40.0, 35.0, 0.0], G2 = [-50.0, 10.0, 0.0], G3 = [15.0, -45.0, 0.0],
    }
    chain leg1 = base - S(D1) - P(active L1) - S(G1) - platform;
    chain leg2 = base - S(D2) - P(active L2) - S(G1) - platform;
    chain leg3 = base - S(D2) - P(active L3) - S(G2) - platform;
    chain leg4 = base - S(D3) - P(active L4) - S(G2) - platform;
    chain leg5 = base - S(D3) - P(active L5) - S(G3) - platform;
    chain leg6 = base - S(D1) - P(active L6) - S(G3) - platform;
}

/// A platform on six legs meeting in pairs: leg `i` joins base point `base[i]` to platform
/// pivot `i / 2`.
struct Triangle {
    base: [[f64; 3]; 6],
    platform: [[f64; 3]; 3],
}

const SIX_THREE: Triangle = Triangle {
    base: [
        [100.0, 0.0, 0.0],
        [80.0, 60.0, 0.0],
        [-40.0, 90.0, 0.0],
        [-90.0, 30.0, 0.0],
        [-50.0, -80.0, 0.0],
        [60.0, -85.0, 0.0],
    ],
    platform: [[50.0, 20.0, 0.0], [-40.0, 35.0, 0.0], [-5.0, -50.0, 0.0]],
};

const D33: [[f64; 3]; 3] = [[120.0, 0.0, 0.0], [-55.0, 100.0, 0.0], [-65.0, -95.0, 0.0]];
const THREE_THREE: Triangle = Triangle {
    base: [D33[0], D33[1], D33[1], D33[2], D33[2], D33[0]],
    platform: [[40.0, 35.0, 0.0], [-50.0, 10.0, 0.0], [15.0, -45.0, 0.0]],
};

/// The circle where two legs' spheres meet: centre, radius and two unit vectors spanning its
/// plane. `None` where the spheres do not meet.
struct Circle {
    centre: [f64; 3],
    radius: f64,
    e1: [f64; 3],
    e2: [f64; 3],
}

impl Circle {
    fn new(p: [f64; 3], lp: f64, q: [f64; 3], lq: f64) -> Option<Circle> {
        let axis = sub(q, p);
        let d = dot(axis, axis).sqrt();
        let u = scaled(axis, 1.0 / d);
        let a = (lp * lp - lq * lq + d * d) / (2.0 * d);
        let r2 = lp * lp - a * a;
        if r2 <= 0.0 {
            return None;
        }
        // Any vector not along u gives the plane's first direction.
        let helper = if u[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let e1 = cross(u, helper);
        let e1 = scaled(e1, 1.0 / dot(e1, e1).sqrt());
        Some(Circle {
            centre: add(p, scaled(u, a)),
            radius: r2.sqrt(),
            e1,
            e2: cross(u, e1),
        })
    }

    fn at(&self, theta: f64) -> [f64; 3] {
        let (s, c) = theta.sin_cos();
        add(
            self.centre,
            add(
                scaled(self.e1, self.radius * c),
                scaled(self.e2, self.radius * s),
            ),
        )
    }

    /// The (up to two) points of the circle at distance `e` from `g`.
    fn at_distance(&self, g: [f64; 3], e: f64) -> Option<[[f64; 3]; 2]> {
        // |w + r(cos θ e1 + sin θ e2)|² = e², w = centre − g: A cos θ + B sin θ = C.
        let w = sub(self.centre, g);
        let (a, b) = (
            2.0 * self.radius * dot(w, self.e1),
            2.0 * self.radius * dot(w, self.e2),
        );
        let c = e * e - dot(w, w) - self.radius * self.radius;
        let h = a.hypot(b);
        if h == 0.0 || c.abs() > h {
            return None;
        }
        let (base, spread) = (b.atan2(a), (c / h).acos());
        Some([self.at(base + spread), self.at(base - spread)])
    }
}

impl Triangle {
    /// Closed-form inverse kinematics.
    fn legs(&self, pose: &Pose) -> [f64; 6] {
        std::array::from_fn(|i| {
            let d = sub(pose.apply(self.platform[i / 2]), self.base[i]);
            dot(d, d).sqrt()
        })
    }

    /// An independent count of the real assembly modes: pivot 1 runs round its circle; pivots
    /// 2 and 3 sit where their circles meet the spheres of the platform's sides about pivot 1
    /// (two points each); the third side's length error changes sign at every real mode.
    fn scanned_real_modes(&self, legs: &[f64; 6]) -> usize {
        let circle = |k: usize| {
            Circle::new(
                self.base[2 * k],
                legs[2 * k],
                self.base[2 * k + 1],
                legs[2 * k + 1],
            )
        };
        let (Some(c1), Some(c2), Some(c3)) = (circle(0), circle(1), circle(2)) else {
            return 0;
        };
        let side = |i: usize, j: usize| {
            let d = sub(self.platform[i], self.platform[j]);
            dot(d, d).sqrt()
        };
        let (e12, e13, e23) = (side(0, 1), side(0, 2), side(1, 2));
        let samples = 400_000;
        let mut previous = [None; 4];
        let mut count = 0;
        for k in 0..=samples {
            let theta = std::f64::consts::TAU * k as f64 / samples as f64;
            let g1 = c1.at(theta);
            let g2 = c2.at_distance(g1, e12);
            let g3 = c3.at_distance(g1, e13);
            for (b, slot) in previous.iter_mut().enumerate() {
                let f = match (g2, g3) {
                    (Some(g2), Some(g3)) => {
                        let d = sub(g2[b / 2], g3[b % 2]);
                        Some(dot(d, d).sqrt() - e23)
                    }
                    _ => None,
                };
                if let (Some(p), Some(q)) = (*slot, f) {
                    if p * q < 0.0 {
                        count += 1;
                    }
                }
                *slot = f;
            }
        }
        count
    }
}

/// Forward kinematics by continuation from home against the closed-form inverse, then every
/// assembly mode at legs from random poses: 16 complex roots, the real ones exactly those the
/// circle scan finds, each giving its legs back, the pose the legs came from among them.
fn check_triangle<S: Mechanism<9, 6> + Clone>(
    sys: S,
    start: Start<9, 6>,
    geometry: &Triangle,
    height: f64,
) {
    check_jacobians(&sys, start.v(), start.x());
    check_factorization(&sys, start.v(), start.x());
    let modes = AllModes::<_, 9, 6, 32>::new(sys.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 16, "{}: {:?}", S::NAME, modes.report());
    let mut roots = Box::new(Roots::<9, 32>::new());
    let mut rng = Rng::new(63);
    let (mut real_total, mut continued) = (0, 0);
    for _ in 0..20 {
        let pose = Pose::from_euler(
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.2, 0.2),
            rng.uniform(-0.2, 0.2),
            [
                rng.uniform(-20.0, 20.0),
                rng.uniform(-20.0, 20.0),
                height + rng.uniform(-20.0, 20.0),
            ],
        );
        let legs = geometry.legs(&pose);
        let sol = arc_length(&sys, &start, &legs, &GENERAL_MODEL).unwrap();
        if sol.status == Status::Converged {
            check_inverse(&sys, &sol.v, &legs, start.x(), 1e-8);
            continued += 1;
        }
        modes.solve(&legs, &mut roots).unwrap();
        assert!(roots.is_complete(), "{}: {pose:?}", S::NAME);
        let scanned = geometry.scanned_real_modes(&legs);
        assert_eq!(roots.real().len(), scanned, "{}: {pose:?}", S::NAME);
        real_total += scanned;
        let mut truth = false;
        for r in roots.real() {
            let p = r.pose.unwrap();
            let back = geometry.legs(&p);
            assert!(
                linkage_tests::max_diff(&back, &legs) < 1e-7,
                "{}: {back:?} vs {legs:?}",
                S::NAME
            );
            truth |= (0..3).all(|k| {
                let (a, b) = (
                    p.apply(geometry.platform[k]),
                    pose.apply(geometry.platform[k]),
                );
                linkage_tests::max_diff(&a, &b) < 1e-6
            });
        }
        assert!(
            truth,
            "{}: the generating pose is not among the real modes",
            S::NAME
        );
    }
    assert!(continued >= 15, "{}: {continued} of 20 continued", S::NAME);
    println!(
        "{}: 16 complex roots; 20 random poses, {real_total} real modes, as the circle scan found; {continued} reached by continuation from home",
        S::NAME
    );
}

#[test]
fn six_three_platform_has_sixteen_assembly_modes() {
    let sys = SixThree::new();
    let start = sys.home_start().unwrap();
    check_triangle(sys, start, &SIX_THREE, 120.0);
}

#[test]
fn octahedral_platform_has_sixteen_assembly_modes() {
    let sys = ThreeThree::new();
    let start = sys.home_start().unwrap();
    check_triangle(sys, start, &THREE_THREE, 110.0);
}

#[test]
fn triangle_platforms_pass_the_newton_check() {
    for (name, sys_count) in [
        (
            "6-3",
            check_count(
                "6-3",
                SixThree::new(),
                &[SIX_THREE.legs(&Pose::from_euler(0.1, -0.05, 0.08, [5.0, -3.0, 118.0]))],
                300.0,
                |_| false,
            ),
        ),
        (
            "3-3",
            check_count(
                "3-3",
                ThreeThree::new(),
                &[THREE_THREE.legs(&Pose::from_euler(-0.1, 0.07, 0.04, [-4.0, 6.0, 108.0]))],
                300.0,
                |_| false,
            ),
        ),
    ] {
        assert_eq!(sys_count.0, 16, "{name}");
        assert!(sys_count.1 <= 16, "{name}");
    }
}
