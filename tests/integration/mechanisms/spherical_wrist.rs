//! A spherical 3-RRR wrist: every revolute axis passes through one centre O, the platform
//! turns about it. Declared in space, each axis by two points on it; declared twice, with the
//! platform at two orientations the same inputs reach (two assembly modes).

use super::{check_inverse, mobility_line};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Options, Pose, Status};
use linkage_tests::vec3::{cross, dot};
use linkage_tests::{check_factorization, check_jacobians, Rng};

macro_rules! wrist {
    ($name:ident, $yaw:expr) => {
        linkage::mechanism! {
            /// A spherical 3-RRR: base axes u_i, the proximal links' second axes v_i and the
            /// platform's axes w_i, all through the origin, each of elevation eu, ev, ew and
            /// azimuth 120° i (plus dv, dw).
            pub struct $name;
            params {
                eu = -0.6, ev = 0.2, ew = 0.9, dv = 1.2, dw = 0.5,
                p2 = 2.0 * pi / 3.0, p3 = 4.0 * pi / 3.0,
            }
            base {
                A1 = [50.0 * cos(eu), 0.0, 50.0 * sin(eu)],
                B1 = [100.0 * cos(eu), 0.0, 100.0 * sin(eu)],
                A2 = [50.0 * cos(eu) * cos(p2), 50.0 * cos(eu) * sin(p2), 50.0 * sin(eu)],
                B2 = [100.0 * cos(eu) * cos(p2), 100.0 * cos(eu) * sin(p2), 100.0 * sin(eu)],
                A3 = [50.0 * cos(eu) * cos(p3), 50.0 * cos(eu) * sin(p3), 50.0 * sin(eu)],
                B3 = [100.0 * cos(eu) * cos(p3), 100.0 * cos(eu) * sin(p3), 100.0 * sin(eu)],
            }
            platform(home = [$yaw, 0.0, 0.0, 0.0, 0.0, 0.0]) {
                W1 = [70.0 * cos(ew) * cos(dw), 70.0 * cos(ew) * sin(dw), 70.0 * sin(ew)],
                X1 = [120.0 * cos(ew) * cos(dw), 120.0 * cos(ew) * sin(dw), 120.0 * sin(ew)],
                W2 = [70.0 * cos(ew) * cos(p2 + dw), 70.0 * cos(ew) * sin(p2 + dw), 70.0 * sin(ew)],
                X2 = [120.0 * cos(ew) * cos(p2 + dw), 120.0 * cos(ew) * sin(p2 + dw), 120.0 * sin(ew)],
                W3 = [70.0 * cos(ew) * cos(p3 + dw), 70.0 * cos(ew) * sin(p3 + dw), 70.0 * sin(ew)],
                X3 = [120.0 * cos(ew) * cos(p3 + dw), 120.0 * cos(ew) * sin(p3 + dw), 120.0 * sin(ew)],
            }
            link proximal1 {
                C1 = [60.0 * cos(ev) * cos(dv), 60.0 * cos(ev) * sin(dv), 60.0 * sin(ev)],
                D1 = [110.0 * cos(ev) * cos(dv), 110.0 * cos(ev) * sin(dv), 110.0 * sin(ev)],
            }
            link proximal2 {
                C2 = [60.0 * cos(ev) * cos(p2 + dv), 60.0 * cos(ev) * sin(p2 + dv), 60.0 * sin(ev)],
                D2 = [110.0 * cos(ev) * cos(p2 + dv), 110.0 * cos(ev) * sin(p2 + dv), 110.0 * sin(ev)],
            }
            link proximal3 {
                C3 = [60.0 * cos(ev) * cos(p3 + dv), 60.0 * cos(ev) * sin(p3 + dv), 60.0 * sin(ev)],
                D3 = [110.0 * cos(ev) * cos(p3 + dv), 110.0 * cos(ev) * sin(p3 + dv), 110.0 * sin(ev)],
            }
            link distal1 { } link distal2 { } link distal3 { }
            chain leg1 = base - R(active q1, axis = A1 -> B1) - proximal1 - R(passive, axis = C1 -> D1) - distal1 - R(passive, axis = W1 -> X1) - platform;
            chain leg2 = base - R(active q2, axis = A2 -> B2) - proximal2 - R(passive, axis = C2 -> D2) - distal2 - R(passive, axis = W2 -> X2) - platform;
            chain leg3 = base - R(active q3, axis = A3 -> B3) - proximal3 - R(passive, axis = C3 -> D3) - distal3 - R(passive, axis = W3 -> X3) - platform;
        }
    };
}

wrist!(Wrist, 0.0);
// Turned about z by 2 (dv − dw), the platform's axes make the same angles with the proximal
// links' axes: another solution for the same inputs.
wrist!(WristTurned, 1.4);

const EU: f64 = -0.6;
const EV: f64 = 0.2;
const EW: f64 = 0.9;
const DV: f64 = 1.2;
const DW: f64 = 0.5;

fn unit(elevation: f64, azimuth: f64) -> [f64; 3] {
    [
        elevation.cos() * azimuth.cos(),
        elevation.cos() * azimuth.sin(),
        elevation.sin(),
    ]
}

/// Inverse kinematics in closed form: v_i(q) · R w_i = v_i · w_i (the distal link's angle),
/// with v_i(q) the proximal axis turned by q about u_i; the root nearest `near`.
fn wrist_inverse(pose: &Pose, near: [f64; 3]) -> Option<[f64; 3]> {
    let mut q = [0.0; 3];
    for i in 0..3 {
        let phi = 2.0 * std::f64::consts::PI * i as f64 / 3.0;
        let (u, v, w0) = (unit(EU, phi), unit(EV, phi + DV), unit(EW, phi + DW));
        let r = &pose.rotation;
        let w = [0, 1, 2].map(|k| dot(r[k], w0));
        let along = dot(u, v);
        // v(q) = (v − u(u·v)) cos q + (u × v) sin q + u (u·v)
        let a = dot(v, w) - along * dot(u, w);
        let b = dot(cross(u, v), w);
        let c = dot(v, w0) - along * dot(u, w);
        let r = (a * a + b * b).sqrt();
        if (c / r).abs() > 1.0 {
            return None;
        }
        let (base, spread) = (b.atan2(a), (c / r).acos());
        let wrap = |t: f64| {
            (t + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
        };
        q[i] = [base + spread, base - spread]
            .into_iter()
            .map(wrap)
            .min_by(|x, y| (x - near[i]).abs().total_cmp(&(y - near[i]).abs()))?;
    }
    Some(q)
}

#[test]
fn wrist_models_with_three_freedoms_and_exact_jacobians() {
    let wrist = Wrist::new();
    let line = mobility_line(Wrist::LISTING);
    assert!(
        line.starts_with("mobility: rank of ∂F/∂(v, x) at home: M = 18 + 3 − 18 = 3"),
        "{line}"
    );
    wrist.home_start().unwrap();
    check_jacobians(&wrist, &Wrist::HOME_V, &Wrist::HOME_INPUTS);
    check_factorization(&wrist, &Wrist::HOME_V, &Wrist::HOME_INPUTS);
    assert!(linkage_tests::max_diff(&Wrist::HOME_INPUTS, &[0.0; 3]) < 1e-12);
}

#[test]
fn wrist_forward_kinematics_against_inverse_about_a_fixed_centre() {
    let wrist = Wrist::new();
    let start = wrist.home_start().unwrap();
    let det0 = det_b(&wrist, &Wrist::HOME_V, &Wrist::HOME_INPUTS);
    let mut rng = Rng::new(61);
    let mut first = true;
    for _ in 0..60 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.25, 0.25));
        let sol = arc_length(&wrist, &start, &q, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q:?}");
        if first {
            // The Jacobians away from home too.
            check_jacobians(&wrist, &sol.v, &q);
            first = false;
        }
        let pose = pose_from_unknowns(&wrist, &sol.v).unwrap();
        // The platform turns about the centre of the base's axes.
        assert!(
            pose.translation.iter().all(|t| t.abs() < 1e-8),
            "{:?}",
            pose.translation
        );
        let back = wrist_inverse(&pose, q).unwrap();
        assert!(
            linkage_tests::max_diff(&back, &q) < 1e-9,
            "{back:?} vs {q:?}"
        );
        assert!(det_b(&wrist, &sol.v, &q) * det0 > 0.0);
        check_inverse(&wrist, &sol.v, &q, &Wrist::HOME_INPUTS, 1e-9);
    }
}

#[test]
fn wrist_assembly_modes_from_two_homes() {
    let (a, b) = (Wrist::new(), WristTurned::new());
    assert_eq!(Wrist::DEFAULT_GEOMETRY, WristTurned::DEFAULT_GEOMETRY);
    assert!(linkage_tests::max_diff(&WristTurned::HOME_INPUTS, &[0.0; 3]) < 1e-12);
    let (sa, sb) = (a.home_start().unwrap(), b.home_start().unwrap());
    let mut rng = Rng::new(62);
    for _ in 0..20 {
        let q = [0, 1, 2].map(|_| rng.uniform(-0.2, 0.2));
        let ra = arc_length(&a, &sa, &q, &Options::TIGHT).unwrap();
        let rb = arc_length(&b, &sb, &q, &Options::TIGHT).unwrap();
        assert_eq!(
            (ra.status, rb.status),
            (Status::Converged, Status::Converged)
        );
        let (pa, pb) = (
            pose_from_unknowns(&a, &ra.v).unwrap(),
            pose_from_unknowns(&b, &rb.v).unwrap(),
        );
        assert!(linkage_tests::max_diff(&wrist_inverse(&pa, q).unwrap(), &q) < 1e-9);
        assert!(linkage_tests::max_diff(&wrist_inverse(&pb, q).unwrap(), &q) < 1e-9);
        // Different orientations: the yaw differs by about 1.4 rad.
        let turn = (pb.euler()[0] - pa.euler()[0]).abs();
        assert!(turn > 0.7, "{:?} vs {:?}", pa.euler(), pb.euler());
    }
}

/// The closed-form singularity measure of a spherical 3-RRR: det of the rows w_i × v_i(q_i),
/// zero where the distal links' planes share a line (the platform can turn infinitesimally).
fn wrist_det(pose: &Pose, q: [f64; 3]) -> f64 {
    let r = &pose.rotation;
    let rows: [[f64; 3]; 3] = std::array::from_fn(|i| {
        let phi = 2.0 * std::f64::consts::PI * i as f64 / 3.0;
        let (u, v, w0) = (unit(EU, phi), unit(EV, phi + DV), unit(EW, phi + DW));
        let (along, uxv) = (dot(u, v), cross(u, v));
        let (c, s) = (q[i].cos(), q[i].sin());
        let vq = [0, 1, 2].map(|k| (v[k] - u[k] * along) * c + uxv[k] * s + u[k] * along);
        let w = [0, 1, 2].map(|k| dot(r[k], w0));
        cross(w, vq)
    });
    dot(rows[0], cross(rows[1], rows[2]))
}

#[test]
fn wrist_folds_only_where_the_mechanism_is_singular() {
    // Nine equations are left out as dependent at home: the folds PH stops at must still be
    // the mechanism's own singularities, not the reduced system's.
    let wrist = Wrist::new();
    let start = wrist.home_start().unwrap();
    let home = pose_from_unknowns(&wrist, &Wrist::HOME_V).unwrap();
    let det0 = wrist_det(&home, [0.0; 3]);
    let q = [
        -0.19531263951072725,
        -0.36569668223207263,
        -0.2982054567623917,
    ];
    let sol = arc_length(&wrist, &start, &q, &Options::TIGHT).unwrap();
    let Status::Fold { lambda } = sol.status else {
        panic!("{:?}", sol.status)
    };
    // The closed-form measure vanishes there: near a fold it goes as √(λf − λ), so its square
    // just before the fold, extrapolated linearly, reaches zero at λf.
    let square = |k: f64| {
        let qk = q.map(|a| a * k);
        let s = arc_length(&wrist, &start, &qk, &Options::TIGHT).unwrap();
        assert_eq!(s.status, Status::Converged);
        let p = pose_from_unknowns(&wrist, &s.v).unwrap();
        wrist_det(&p, qk).powi(2)
    };
    let (k1, k2) = (lambda - 0.012, lambda - 0.006);
    let (d1, d2) = (square(k1), square(k2));
    let zero = k2 + d2 * (k2 - k1) / (d1 - d2);
    assert!((zero - lambda).abs() < 0.002, "{zero} vs {lambda}");
    assert!(d2 < 0.05 * det0 * det0);
    // On the way, both measures keep their signs.
    let b0 = det_b(&wrist, &Wrist::HOME_V, &Wrist::HOME_INPUTS);
    for k in [0.3, 0.6, 0.8, 0.87] {
        let qk = q.map(|a| a * k);
        let s = arc_length(&wrist, &start, &qk, &Options::TIGHT).unwrap();
        assert_eq!(s.status, Status::Converged);
        let p = pose_from_unknowns(&wrist, &s.v).unwrap();
        assert!(det_b(&wrist, &s.v, &qk) * b0 > 0.0 && wrist_det(&p, qk) * det0 > 0.0);
    }
}

#[test]
fn wrist_inverse_refuses_a_pose_off_the_centre() {
    let wrist = Wrist::new();
    // The home orientation with the centre moved 1 mm: no inputs put the platform there.
    let pose = Pose::from_euler(0.0, 0.0, 0.0, [1.0, 0.0, 0.0]);
    let v = linkage::unknowns_from_pose(&wrist, &pose);
    assert!(matches!(
        wrist.inverse(&v, &Wrist::HOME_INPUTS),
        Err(linkage::InverseError::Unreachable { .. })
    ));
    // A turned platform about the centre is reached, and its inputs put it there.
    let pose = Pose::from_euler(0.1, -0.05, 0.08, [0.0; 3]);
    let v = linkage::unknowns_from_pose(&wrist, &pose);
    let q = wrist.inverse(&v, &Wrist::HOME_INPUTS).unwrap();
    assert!(linkage_tests::max_diff(&wrist_inverse(&pose, q).unwrap(), &q) < 1e-9);
    let mut nan = v;
    nan[4] = f64::NAN;
    assert_eq!(
        wrist.inverse(&nan, &Wrist::HOME_INPUTS),
        Err(linkage::InverseError::NonFinite)
    );
}
