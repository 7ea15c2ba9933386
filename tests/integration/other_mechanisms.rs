//! The chain shapes the other examples do not use: a prismatic driver (a 6-PSS hexaglide)
//! and helical and cylindrical drivers, through the same checks as every mechanism.

use linkage::{arc_length, Mechanism, Options, Pose, Start, Status};
use linkage_tests::{check_factorization, check_jacobians, max_diff, Rng};

/// Six drivers on vertical axes at the base, each carrying a rod (S–S) to the platform: the
/// drivers differ, the geometry is shared.
macro_rules! rod_hexapod {
    ($(#[$doc:meta])* $name:ident, ($($platform:tt)*), [$k1:ident($($a1:tt)*) $k2:ident($($a2:tt)*) $k3:ident($($a3:tt)*) $k4:ident($($a4:tt)*) $k5:ident($($a5:tt)*) $k6:ident($($a6:tt)*)]) => {
        linkage::mechanism! {
            $(#[$doc])*
            pub struct $name;
            params { rod = 162.7108 }
            base {
                A1 = [118.177, 20.838, 0.0], B1 = [118.177, 20.838, 10.0],
                A2 = [77.135, 91.925, 0.0], B2 = [77.135, 91.925, 10.0],
                A3 = [-77.135, 91.925, 0.0], B3 = [-77.135, 91.925, 10.0],
                A4 = [-118.177, 20.838, 0.0], B4 = [-118.177, 20.838, 10.0],
                A5 = [-41.042, -112.763, 0.0], B5 = [-41.042, -112.763, 10.0],
                A6 = [41.042, -112.763, 0.0], B6 = [41.042, -112.763, 10.0],
            }
            platform $($platform)* {
                G1 = [45.315, 21.131, 0.0],
                G2 = [40.958, 28.679, 0.0],
                G3 = [-40.958, 28.679, 0.0],
                G4 = [-45.315, 21.131, 0.0],
                G5 = [-4.358, -49.810, 0.0],
                G6 = [4.358, -49.810, 0.0],
            }
            link carriage1 { C1 = [108.329, 19.101, 0.0] }
            link carriage2 { C2 = [70.707, 84.265, 0.0] }
            link carriage3 { C3 = [-70.707, 84.265, 0.0] }
            link carriage4 { C4 = [-108.329, 19.101, 0.0] }
            link carriage5 { C5 = [-37.622, -103.366, 0.0] }
            link carriage6 { C6 = [37.622, -103.366, 0.0] }
            link rod1 { length = rod }
            link rod2 { length = rod }
            link rod3 { length = rod }
            link rod4 { length = rod }
            link rod5 { length = rod }
            link rod6 { length = rod }
            chain arm1 = base - $k1($($a1)*) - carriage1 - S(C1) - rod1 - S(G1) - platform;
            chain arm2 = base - $k2($($a2)*) - carriage2 - S(C2) - rod2 - S(G2) - platform;
            chain arm3 = base - $k3($($a3)*) - carriage3 - S(C3) - rod3 - S(G3) - platform;
            chain arm4 = base - $k4($($a4)*) - carriage4 - S(C4) - rod4 - S(G4) - platform;
            chain arm5 = base - $k5($($a5)*) - carriage5 - S(C5) - rod5 - S(G5) - platform;
            chain arm6 = base - $k6($($a6)*) - carriage6 - S(C6) - rod6 - S(G6) - platform;
        }
    };
}

mod hexaglide {
    rod_hexapod!(
        /// Six vertical linear actuators (P) carrying rods (S–S) to the platform.
        Hexaglide,
        ((home = [0.0, 0.0, 0.0, 0.0, 0.0, 150.0])),
        [
            P(active z1, axis = A1 -> B1) P(active z2, axis = A2 -> B2) P(active z3, axis = A3 -> B3)
            P(active z4, axis = A4 -> B4) P(active z5, axis = A5 -> B5) P(active z6, axis = A6 -> B6)
        ]
    );
}

mod screws {
    rod_hexapod!(
        /// Six rotating lead screws (H, lead 5 mm) whose nuts carry rods to the platform.
        Screws,
        (),
        [
            H(active q1, axis = A1 -> B1, lead = 5.0) H(active q2, axis = A2 -> B2, lead = 5.0)
            H(active q3, axis = A3 -> B3, lead = 5.0) H(active q4, axis = A4 -> B4, lead = 5.0)
            H(active q5, axis = A5 -> B5, lead = 5.0) H(active q6, axis = A6 -> B6, lead = 5.0)
        ]
    );
}

mod cylinders {
    rod_hexapod!(
        /// Three cylindrical drivers (C: rotation and slide) and three prismatic ones.
        Cylinders,
        (),
        [
            C(active q1 z1, axis = A1 -> B1) C(active q2 z2, axis = A2 -> B2) C(active q3 z3, axis = A3 -> B3)
            P(active z4, axis = A4 -> B4) P(active z5, axis = A5 -> B5) P(active z6, axis = A6 -> B6)
        ]
    );
}

use cylinders::Cylinders;
use hexaglide::Hexaglide;
use screws::Screws;

fn home_v<S: Mechanism<18, M>, const M: usize>(sys: &S) -> [f64; 18] {
    linkage::unknowns_from_pose(sys, &Pose::from_euler(0.0, 0.0, 0.0, [0.0, 0.0, 150.0]))
}

fn around<S: Mechanism<18, M>, const M: usize>(sys: &S, v: [f64; 18], x: [f64; M]) {
    let mut rng = Rng::new(3);
    for k in 0..20 {
        let dv: [f64; 18] = std::array::from_fn(|i| {
            v[i] + if k == 0 {
                0.0
            } else {
                rng.uniform(-20.0, 20.0)
            }
        });
        let dx: [f64; M] =
            std::array::from_fn(|j| x[j] + if k == 0 { 0.0 } else { rng.uniform(-0.5, 0.5) });
        check_jacobians(sys, &dv, &dx);
        check_factorization(sys, &dv, &dx);
    }
}

#[test]
fn hexaglide_jacobians_and_fk_against_ik() {
    let h = Hexaglide::new();
    let start = h.home_start().unwrap();
    assert!(
        start.x().iter().all(|z| z.abs() < 1e-2),
        "home at zero slide: {:?}",
        *start.x()
    );
    around(&h, *start.v(), *start.x());
    let mut rng = Rng::new(4);
    for _ in 0..50 {
        let pose = Pose::from_euler(
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            rng.uniform(-0.1, 0.1),
            [
                rng.uniform(-10.0, 10.0),
                rng.uniform(-10.0, 10.0),
                150.0 + rng.uniform(-15.0, 15.0),
            ],
        );
        let v = linkage::unknowns_from_pose(&h, &pose);
        let x = h.inverse(&v, start.x()).unwrap();
        let sol = arc_length(&h, &start, &x, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged);
        assert!(max_diff(&sol.v, &v) < 1e-6, "{}", max_diff(&sol.v, &v));
    }
}

#[test]
fn helical_and_cylindrical_drivers_have_exact_jacobians_and_solve() {
    let s = Screws::new();
    let v = home_v(&s);
    around(&s, v, [0.0; 6]);
    let start = Start::new(&s, v, [0.0; 6]).unwrap();
    // H and C drivers have no closed-form inverse: the numerical one finds the start's inputs.
    let back = s.inverse(start.v(), &[0.05; 6]).unwrap();
    assert!(max_diff(&back, &[0.0; 6]) < 1e-9, "{back:?}");
    let sol = arc_length(&s, &start, &[0.2; 6], &Options::TIGHT).unwrap();
    assert_eq!(sol.status, Status::Converged);
    let mut f = [0.0; 18];
    s.residual(&sol.v, &[0.2; 6], &mut f);
    assert!(f.iter().all(|r| r.abs() < 1e-6));

    let c = Cylinders::new();
    let v = home_v(&c);
    around(&c, v, [0.0; 9]);
    assert_eq!(Cylinders::INPUTS.len(), 9);
}

/// Every assembly mode of the screw-driven hexapod: at given screw angles its rods make a 6-6
/// platform, 40 complex roots. A screw's angle enters as cos θ and sin θ and again through its
/// slide 5θ/2π, so F is not 2π-periodic in it: `AllModes` took the angles for lengths and drew
/// them complex at the mechanism's size, where cos θ is beyond 10⁸⁰. Its start set stopped
/// short (on a 3-HRS, 1 root of 16, every monodromy loop failed), and a query near home
/// answered complete without the real root PH reaches there.
#[test]
fn all_modes_samples_screw_angles_as_angles() {
    use linkage::modes::{AllModes, ModesOptions, Roots};
    let s = Screws::new();
    let start = Start::new(&s, home_v(&s), [0.0; 6]).unwrap();
    let modes = AllModes::<Screws, 18, 6, 64>::new(s.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.start_count(), 40, "{:?}", modes.report());
    let x = [0.2, -0.1, 0.15, 0.05, -0.2, 0.1];
    let sol = arc_length(&s, &start, &x, &Options::TIGHT).unwrap();
    assert_eq!(sol.status, Status::Converged);
    let mut roots = Box::new(Roots::<18, 64>::new());
    modes.solve(&x, &mut roots).unwrap();
    assert!(roots.is_complete());
    assert!(
        roots.real().iter().any(|r| max_diff(&r.v, &sol.v) < 1e-6),
        "PH's answer is not among the {} real roots",
        roots.real().len()
    );
}
