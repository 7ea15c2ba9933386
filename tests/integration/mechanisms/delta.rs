//! A delta robot: three cranks on horizontal axes, each carrying a parallelogram of two
//! ball-jointed rods to the platform (one input per arm). Declared twice, with the platform
//! below the base and above it: the two assembly modes of the same machine.

use super::{check_inverse, identity_within, mobility_line};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Options, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

macro_rules! delta {
    ($name:ident, $z:expr) => {
        delta!($name, $z, 100.0);
    };
    ($name:ident, $z:expr, $rb:tt) => {
        linkage::mechanism! {
            /// A delta robot: cranks of 100 mm on tangent axes at radius 100 mm, parallelograms
            /// 60 mm wide of rods `rod`, a platform of radius 40 mm. `Delta` is the README's
            /// delta, declared as there (every coordinate from parameters).
            pub struct $name;
            params {
                rb = $rb, ra = 100.0, rp = 40.0, hw = 30.0, h = 200.0,
                rod = sqrt((rb + ra - rp) * (rb + ra - rp) + h * h),
                c = cos(2.0 * pi / 3.0), s = sin(2.0 * pi / 3.0),
            }
            base {
                A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
                A2 = [rb * c, rb * s, 0.0], B2 = [rb * c - s, rb * s + c, 0.0],
                A3 = [rb * c, -rb * s, 0.0], B3 = [rb * c + s, -rb * s + c, 0.0],
            }
            platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, $z]) {
                F11 = [rp, hw, 0.0], F12 = [rp, -hw, 0.0],
                F21 = [rp * c - hw * s, rp * s + hw * c, 0.0], F22 = [rp * c + hw * s, rp * s - hw * c, 0.0],
                F31 = [rp * c + hw * s, -rp * s + hw * c, 0.0], F32 = [rp * c - hw * s, -rp * s - hw * c, 0.0],
            }
            link arm1 { E11 = [rb + ra, hw, 0.0], E12 = [rb + ra, -hw, 0.0] }
            link arm2 {
                E21 = [(rb + ra) * c - hw * s, (rb + ra) * s + hw * c, 0.0],
                E22 = [(rb + ra) * c + hw * s, (rb + ra) * s - hw * c, 0.0],
            }
            link arm3 {
                E31 = [(rb + ra) * c + hw * s, -(rb + ra) * s + hw * c, 0.0],
                E32 = [(rb + ra) * c - hw * s, -(rb + ra) * s - hw * c, 0.0],
            }
            link rod11 { length = rod } link rod12 { length = rod }
            link rod21 { length = rod } link rod22 { length = rod }
            link rod31 { length = rod } link rod32 { length = rod }
            chain arm1a = base - R(active q1, axis = A1 -> B1) - arm1 - S(E11) - rod11 - S(F11) - platform;
            chain arm1b = arm1 - S(E12) - rod12 - S(F12) - platform;
            chain arm2a = base - R(active q2, axis = A2 -> B2) - arm2 - S(E21) - rod21 - S(F21) - platform;
            chain arm2b = arm2 - S(E22) - rod22 - S(F22) - platform;
            chain arm3a = base - R(active q3, axis = A3 -> B3) - arm3 - S(E31) - rod31 - S(F31) - platform;
            chain arm3b = arm3 - S(E32) - rod32 - S(F32) - platform;
        }
    };
}

delta!(Delta, -200.0);
delta!(DeltaAbove, 200.0);
// The same machine with a base 10 mm wider, declared so.
delta!(DeltaWiderBase, -200.0, 110.0);

linkage::mechanism! {
    /// The same delta with each crank split in two, one rod on each half, the halves driven by
    /// one input: `active shared`.
    pub struct DeltaSplitCranks;
    params {
        rb = 100.0, ra = 100.0, rp = 40.0, hw = 30.0, h = 200.0,
        rod = sqrt((rb + ra - rp) * (rb + ra - rp) + h * h),
        c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0),
    }
    base {
        A1 = [rb, 0.0, 0.0], B1 = [rb, 1.0, 0.0],
        A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2 - s2, rb * s2 + c2, 0.0],
        A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2 + s2, -rb * s2 + c2, 0.0],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -h]) {
        F11 = [rp, hw, 0.0], F12 = [rp, -hw, 0.0],
        F21 = [rp * c2 - hw * s2, rp * s2 + hw * c2, 0.0], F22 = [rp * c2 + hw * s2, rp * s2 - hw * c2, 0.0],
        F31 = [rp * c2 + hw * s2, -rp * s2 + hw * c2, 0.0], F32 = [rp * c2 - hw * s2, -rp * s2 - hw * c2, 0.0],
    }
    link arm11 { E11 = [rb + ra, hw, 0.0] }
    link arm12 { E12 = [rb + ra, -hw, 0.0] }
    link arm21 { E21 = [(rb + ra) * c2 - hw * s2, (rb + ra) * s2 + hw * c2, 0.0] }
    link arm22 { E22 = [(rb + ra) * c2 + hw * s2, (rb + ra) * s2 - hw * c2, 0.0] }
    link arm31 { E31 = [(rb + ra) * c2 + hw * s2, -(rb + ra) * s2 + hw * c2, 0.0] }
    link arm32 { E32 = [(rb + ra) * c2 - hw * s2, -(rb + ra) * s2 - hw * c2, 0.0] }
    link rod11 { length = rod } link rod12 { length = rod }
    link rod21 { length = rod } link rod22 { length = rod }
    link rod31 { length = rod } link rod32 { length = rod }
    chain a11 = base - R(active shared q1, axis = A1 -> B1) - arm11 - S(E11) - rod11 - S(F11) - platform;
    chain a12 = base - R(active shared q1, axis = A1 -> B1) - arm12 - S(E12) - rod12 - S(F12) - platform;
    chain a21 = base - R(active shared q2, axis = A2 -> B2) - arm21 - S(E21) - rod21 - S(F21) - platform;
    chain a22 = base - R(active shared q2, axis = A2 -> B2) - arm22 - S(E22) - rod22 - S(F22) - platform;
    chain a31 = base - R(active shared q3, axis = A3 -> B3) - arm31 - S(E31) - rod31 - S(F31) - platform;
    chain a32 = base - R(active shared q3, axis = A3 -> B3) - arm32 - S(E32) - rod32 - S(F32) - platform;
}

const RB: f64 = 100.0;
const RA: f64 = 100.0;
const RP: f64 = 40.0;

fn rod() -> f64 {
    ((RB + RA - RP).powi(2) + 200f64.powi(2)).sqrt()
}

/// The platform centre for crank angles `q` by sphere intersection: each parallelogram acts as
/// one rod from the middle of its crank's rods to the middle of the platform's; the two roots,
/// lower first.
pub fn sphere_intersection(q: [f64; 3]) -> Option<[[f64; 3]; 2]> {
    // Crank i turns about its tangent axis; positive q lowers it (right-handed about A → B).
    let centre = |i: usize| {
        let phi = 2.0 * std::f64::consts::PI * i as f64 / 3.0;
        let (c, s) = (phi.cos(), phi.sin());
        let radial = RB + RA * q[i].cos() - RP;
        [radial * c, radial * s, -RA * q[i].sin()]
    };
    let [p1, p2, p3] = [centre(0), centre(1), centre(2)];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let scale = |a: [f64; 3], k: f64| [a[0] * k, a[1] * k, a[2] * k];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    // Trilateration in the frame (ex, ey, ez) of the three centres.
    let d = dot(sub(p2, p1), sub(p2, p1)).sqrt();
    let ex = scale(sub(p2, p1), 1.0 / d);
    let i = dot(ex, sub(p3, p1));
    let ey_raw = sub(sub(p3, p1), scale(ex, i));
    let ey = scale(ey_raw, 1.0 / dot(ey_raw, ey_raw).sqrt());
    let ez = cross(ex, ey);
    let j = dot(ey, sub(p3, p1));
    let x = d / 2.0;
    let y = (i * i + j * j) / (2.0 * j) - i * x / j;
    let z2 = rod().powi(2) - x * x - y * y;
    if z2 < 0.0 {
        return None;
    }
    let base = [0, 1, 2].map(|k| p1[k] + x * ex[k] + y * ey[k]);
    let mut roots = [1.0, -1.0].map(|sign| [0, 1, 2].map(|k| base[k] + sign * z2.sqrt() * ez[k]));
    if roots[0][2] > roots[1][2] {
        roots.swap(0, 1);
    }
    Some(roots)
}

#[test]
fn delta_models_with_three_freedoms_and_exact_jacobians() {
    let delta = Delta::new();
    assert_eq!(Delta::INPUTS, ["q1", "q2", "q3"]);
    // q = 0 at the declared configuration.
    assert!(linkage_tests::max_diff(&Delta::HOME_INPUTS, &[0.0; 3]) < 1e-12);
    assert_eq!(
        mobility_line(Delta::LISTING),
        "mobility: rank of ∂F/∂(v, x) at home: M = 18 + 3 − 18 = 3 (Grübler–Kutzbach says 3)"
    );
    delta.home_start().unwrap();
    check_jacobians(&delta, &Delta::HOME_V, &Delta::HOME_INPUTS);
    check_factorization(&delta, &Delta::HOME_V, &Delta::HOME_INPUTS);
    // Inverse kinematics in closed form (each crank against the rod it carries).
    let x = delta.inverse(&Delta::HOME_V, &[0.1; 3]).unwrap();
    assert!(linkage_tests::max_diff(&x, &[0.0; 3]) < 1e-12, "{x:?}");
}

#[test]
fn delta_forward_kinematics_matches_sphere_intersection_and_keeps_orientation() {
    let delta = Delta::new();
    let start = delta.home_start().unwrap();
    let det0 = det_b(&delta, &Delta::HOME_V, &Delta::HOME_INPUTS);
    let mut rng = Rng::new(31);
    let mut first = true;
    for _ in 0..60 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.5, 0.5));
        let sol = arc_length(&delta, &start, &q, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q:?}");
        let pose = pose_from_unknowns(&delta, &sol.v).unwrap();
        if first {
            // The Jacobians away from home too.
            check_jacobians(&delta, &sol.v, &q);
            first = false;
        }
        identity_within(&pose.rotation, 1e-9);
        let [below, _] = sphere_intersection(q).unwrap();
        assert!(
            linkage_tests::max_diff(&pose.translation, &below) < 1e-8,
            "q = {q:?}: {:?} vs {below:?}",
            pose.translation
        );
        assert!(det_b(&delta, &sol.v, &q) * det0 > 0.0);
        // The closed-form inverse gives the inputs back.
        check_inverse(&delta, &sol.v, &q, &[0.0; 3], 1e-9);
    }
}

#[test]
fn delta_assembly_modes_below_and_above_the_base() {
    let (below, above) = (Delta::new(), DeltaAbove::new());
    // The same machine: every dimension equal.
    assert_eq!(Delta::DEFAULT_GEOMETRY, DeltaAbove::DEFAULT_GEOMETRY);
    let (s_below, s_above) = (below.home_start().unwrap(), above.home_start().unwrap());
    let mut rng = Rng::new(32);
    for _ in 0..20 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.4, 0.4));
        let a = arc_length(&below, &s_below, &q, &Options::TIGHT).unwrap();
        let b = arc_length(&above, &s_above, &q, &Options::TIGHT).unwrap();
        assert_eq!((a.status, b.status), (Status::Converged, Status::Converged));
        let [low, high] = sphere_intersection(q).unwrap();
        let pa = pose_from_unknowns(&below, &a.v).unwrap().translation;
        let pb = pose_from_unknowns(&above, &b.v).unwrap().translation;
        assert!(linkage_tests::max_diff(&pa, &low) < 1e-8);
        assert!(linkage_tests::max_diff(&pb, &high) < 1e-8);
        assert!(
            pb[2] - pa[2] > 100.0,
            "two distinct solutions: {pa:?} {pb:?}"
        );
    }
}

#[test]
fn delta_with_shared_inputs_is_the_same_machine() {
    let (delta, split) = (Delta::new(), DeltaSplitCranks::new());
    assert_eq!(DeltaSplitCranks::INPUTS, ["q1", "q2", "q3"]);
    // Grübler–Kutzbach counts six driven pairs; the rank sees three freedoms.
    assert_eq!(
        mobility_line(DeltaSplitCranks::LISTING),
        "mobility: rank of ∂F/∂(v, x) at home: M = 18 + 3 − 18 = 3 (Grübler–Kutzbach says 6)"
    );
    let split_start = split.home_start().unwrap();
    check_jacobians(
        &split,
        &DeltaSplitCranks::HOME_V,
        &DeltaSplitCranks::HOME_INPUTS,
    );
    let start = delta.home_start().unwrap();
    let mut rng = Rng::new(33);
    for _ in 0..20 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.5, 0.5));
        let a = arc_length(&delta, &start, &q, &Options::TIGHT).unwrap();
        let b = arc_length(&split, &split_start, &q, &Options::TIGHT).unwrap();
        assert_eq!((a.status, b.status), (Status::Converged, Status::Converged));
        let pa = pose_from_unknowns(&delta, &a.v).unwrap();
        let pb = pose_from_unknowns(&split, &b.v).unwrap();
        assert!(linkage_tests::max_diff(&pa.translation, &pb.translation) < 1e-9);
        identity_within(&pb.rotation, 1e-9);
        // Both halves of a crank read the same input back.
        check_inverse(&split, &b.v, &q, &[0.0; 3], 1e-9);
    }
}

/// A rod's length enters the equations squared: set at run time to zero or a negative value
/// it is refused with the parameter's name (it used to be taken for its magnitude), and the
/// mechanism is left as it was.
#[test]
fn a_non_positive_rod_length_is_refused() {
    let mut d = Delta::new();
    let before = *d.constants();
    for bad in [-368.8, 0.0, -0.0] {
        assert_eq!(
            d.set_geometry("rod", bad),
            Err(linkage::GeometryError::NonPositiveLength { name: "rod" })
        );
        assert_eq!(d.constants(), &before);
    }
    let mut g = *d.geometry();
    let rod = Delta::GEOMETRY_NAMES
        .iter()
        .position(|n| *n == "rod")
        .unwrap();
    g[rod] = -1.0;
    assert!(Delta::from_geometry(g).is_err());
    assert!(d.set_geometry("rod", 370.0).is_ok());
}

/// A parameter read only where another is declared (`h` in `rod = sqrt(... + h * h)`) is not
/// a run-time value: the parameters are independent at run time, so a calibrated `h` would
/// change nothing. It is refused, by name, and the mechanism kept; so is a parameter nothing
/// reads at all (the five-bar's `distal`, which its author meant as the distal links' length:
/// those are the declared distances), and a `from_geometry` array that changes one. Before,
/// each was accepted and ignored (the geometry hunt "calibrated" the 3-PRS's `l` and `h`).
#[test]
fn a_parameter_read_only_at_compile_time_cannot_be_calibrated() {
    use super::five_bar::FiveBar;
    use super::prs::Prs;
    use linkage::GeometryError;
    let mut d = Delta::new();
    let kept = d.clone();
    assert_eq!(
        d.set_geometry("h", 210.0),
        Err(GeometryError::CompileTimeOnly { name: "h" })
    );
    assert_eq!(d, kept, "unchanged on error");
    // Setting it to its declared value changes nothing and is no error.
    assert_eq!(d.set_geometry("h", 200.0), Ok(()));
    let mut g = Delta::DEFAULT_GEOMETRY;
    g[Delta::GEOMETRY_NAMES
        .iter()
        .position(|n| *n == "h")
        .unwrap()] += 1.0;
    assert_eq!(
        Delta::from_geometry(g),
        Err(GeometryError::CompileTimeOnly { name: "h" })
    );
    let mut fb = FiveBar::new();
    assert_eq!(
        fb.set_geometry("distal", 140.0),
        Err(GeometryError::CompileTimeOnly { name: "distal" })
    );
    let mut prs = Prs::new();
    for name in ["l", "h"] {
        assert_eq!(
            prs.set_geometry(name, 160.0),
            Err(GeometryError::CompileTimeOnly { name })
        );
    }
    // What they were declared for is calibrated through what reads them.
    assert!(prs.set_geometry("hc", 110.0).is_ok() && d.set_geometry("rod", 270.0).is_ok());
    assert!(GeometryError::CompileTimeOnly { name: "h" }
        .to_string()
        .contains("compile time"));
}

#[test]
fn a_pivot_coordinate_declared_as_a_parameter_names_the_parameter_to_set() {
    use linkage::GeometryError;
    let mut d = Delta::new();
    let kept = d.clone();
    // E11 = [rb + ra, hw, 0.0]: its x follows `rb` (and `ra`), its y is the parameter `hw`,
    // which the other arms' pivots follow too; a rod's length is `rod`.
    assert_eq!(
        d.set_pivot("arm1", "E11", [200.0, 35.0, 0.0]),
        Err(GeometryError::FollowsParameter {
            name: "arm1.E11.x",
            parameter: "rb"
        })
    );
    assert_eq!(
        d.set_geometry("rod11.length", 370.0),
        Err(GeometryError::FollowsParameter {
            name: "rod11.length",
            parameter: "rod"
        })
    );
    assert_eq!(d, kept, "unchanged on error");
    // A name nobody declared is still just unknown.
    assert_eq!(
        d.set_pivot("arm1", "E19", [0.0; 3]),
        Err(GeometryError::UnknownName)
    );
    assert_eq!(d.set_geometry("hx", 1.0), Err(GeometryError::UnknownName));
    // The parameter itself is set by its name.
    d.set_geometry("hw", 35.0).unwrap();
    assert_ne!(d, kept);
}

/// A coordinate declared as arithmetic on parameters follows them at run time: the delta's
/// base, arms and platform are declared from `rb`, `ra`, `rp` and `hw` (`A2 = [rb * c, rb * s,
/// 0.0]`, `E21 = [(rb + ra) * c - hw * s, …]`). Set `rb` at run time, the delta is the one
/// declared with that `rb`, bit for bit — every pivot declared from it moved, not only those
/// declared as `rb` alone — and solves as that one does. (The rods' length `rod` is a parameter
/// of its own: its declared value was computed from `rb`, but it is a dimension in its own
/// right at run time, so it is set too.)
#[test]
fn coordinates_declared_from_parameters_follow_them_at_run_time() {
    let wider = DeltaWiderBase::new();
    let slot = |name: &str| {
        Delta::GEOMETRY_NAMES
            .iter()
            .position(|n| *n == name)
            .unwrap_or_else(|| panic!("no geometry value {name}"))
    };
    let mut d = Delta::new();
    d.set_geometry("rb", 110.0).unwrap();
    d.set_geometry("rod", wider.geometry()[slot("rod")])
        .unwrap();
    assert_eq!(Delta::GEOMETRY_NAMES, DeltaWiderBase::GEOMETRY_NAMES);
    for (k, name) in Delta::GEOMETRY_NAMES.iter().enumerate() {
        assert_eq!(d.geometry()[k], wider.geometry()[k], "{name}");
    }
    assert_eq!(d.constants(), wider.constants());
    // A pivot declared from `rb` moved with it: at rb = 100 it was elsewhere.
    let a2x = slot("base.A2.x");
    assert!((Delta::new().geometry()[a2x] - d.geometry()[a2x]).abs() > 4.9);
    // And it solves as the one declared so: the same configuration at the same cranks.
    let start = d.home_start().unwrap();
    let start_wider = wider.home_start().unwrap();
    for q in [[0.1, -0.2, 0.3], [-0.3, 0.2, 0.1]] {
        let a = arc_length(&d, &start, &q, &Options::TIGHT).unwrap();
        let b = arc_length(&wider, &start_wider, &q, &Options::TIGHT).unwrap();
        assert_eq!((a.status, b.status), (Status::Converged, Status::Converged));
        assert!(linkage_tests::max_diff(&a.v, &b.v) < 1e-9, "at {q:?}");
    }
    // Such a coordinate is not set by itself (the formula would overwrite it): the error names
    // the parameter it follows, and the mechanism is left as it was.
    let kept = d.clone();
    assert_eq!(
        d.set_pivot("base", "A2", [90.0, 40.0, 0.0]),
        Err(linkage::GeometryError::FollowsParameter {
            name: "base.A2.x",
            parameter: "rb"
        })
    );
    assert_eq!(
        d.set_geometry("arm2.E21.y", 1.0),
        Err(linkage::GeometryError::FollowsParameter {
            name: "arm2.E21.y",
            parameter: "rb"
        })
    );
    assert_eq!(d, kept);
    // `from_geometry` computes them from the parameters, whatever the array held for them.
    let mut g = *d.geometry();
    g[a2x] = 0.0;
    assert_eq!(Delta::from_geometry(g).unwrap(), d);
    // A parameter that makes a formula non-finite is refused with the coordinate's name.
    assert!(d.set_geometry("rb", 1e308).is_err());
    assert_eq!(d, kept);
}
