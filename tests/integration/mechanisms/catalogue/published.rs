//! Mechanisms of the literature whose shapes the other files do not declare: the Watt I and
//! Stephenson III six-bars (two loops, ternary links, chains between moving links), a planar
//! 3-PRP driven at its base prismatics and the Agile Eye (the Orthoglide, with its
//! parallelograms of revolute pairs, has `orthoglide.rs`). Each against a reference written
//! here, apart from the library: a closed form where there is one, otherwise Newton's method on
//! this file's own equations in joint angles (not the generated point equations); and every
//! assembly mode `AllModes` finds against the same reference.

use super::{check_inverse, mobility_line, GENERAL_MODEL};
use super::{circles, point};
use linkage::modes::{AllModes, Complex, EndpointKind, ModesOptions, Roots};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Status, Tracker};
use linkage_tests::{check_factorization, check_jacobians, Rng};

fn rot2(p: [f64; 2], a: f64) -> [f64; 2] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

fn add2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn xy(p: [f64; 3]) -> [f64; 2] {
    [p[0], p[1]]
}

// ---------------------------------------------------------------------------------------------
// Watt I six-bar. The Watt chain's two ternary links are joined by a pair (J); the Watt I
// inversion fixes a binary link, so both ternaries move: T1 turns about the base pivot O1 (the
// input), T2 is the coupler of the four-bar O1–J–C–O2 (rocker O2–C), and a dyad E–F–G joins
// the two moving ternaries — a loop that opens and closes at links that are not the base.
// The dimensions are ours (no published figure used).
linkage::mechanism! {
    /// A Watt I six-bar: crank T1 (ternary), coupler T2 (ternary, the platform), rocker O2–C,
    /// and the dyad T1–E–F–G–T2.
    pub struct WattI;
    base { O1 = [0.0, 0.0, 0.0], O1z = [0.0, 0.0, 1.0], O2 = [100.0, 0.0, 0.0], O2z = [100.0, 0.0, 1.0] }
    platform {
        J = [20.0, 50.0, 0.0], Jz = [20.0, 50.0, 1.0],
        C = [110.0, 70.0, 0.0], Cz = [110.0, 70.0, 1.0],
        G = [60.0, 110.0, 0.0], Gz = [60.0, 110.0, 1.0],
    }
    link t1 { E = [-30.0, 40.0, 0.0], Ez = [-30.0, 40.0, 1.0] }
    link rocker { }
    link b3 { F = [-10.0, 110.0, 0.0], Fz = [-10.0, 110.0, 1.0] }
    chain crank = base - R(active q, axis = O1 -> O1z) - t1 - R(passive, axis = J -> Jz) - platform;
    chain follower = base - R(passive, axis = O2 -> O2z) - rocker - R(passive, axis = C -> Cz) - platform;
    chain dyad = t1 - R(passive, axis = E -> Ez) - b3 - R(passive, axis = F -> Fz) - R(passive, axis = G -> Gz) - platform;
}

/// T2's turn, then C, G and F in the plane.
type WattPose = (f64, [f64; 2], [f64; 2], [f64; 2]);

/// Watt I in closed form at crank angle q: T1 turned by q about O1; C where the coupler's
/// circle about J meets the rocker's about O2; T2 placed by J and C; F where the dyad's two
/// circles (about E and G) meet. Sides as at home. Returns (T2's turn, C, G, F).
fn watt_closed_form(q: f64) -> Option<WattPose> {
    let (o2, j0, c0, g0, e0, f0) = (
        [100.0, 0.0],
        [20.0, 50.0],
        [110.0, 70.0],
        [60.0, 110.0],
        [-30.0, 40.0],
        [-10.0, 110.0],
    );
    let j = rot2(j0, q);
    let e = rot2(e0, q);
    let side_c = cross2(sub2(o2, j0), sub2(c0, j0));
    let c = circles(j, dist2(j0, c0), o2, dist2(o2, c0), side_c)?;
    let turn = (c[1] - j[1]).atan2(c[0] - j[0]) - (c0[1] - j0[1]).atan2(c0[0] - j0[0]);
    let g = add2(j, rot2(sub2(g0, j0), turn));
    let side_f = cross2(sub2(g0, e0), sub2(f0, e0));
    let f = circles(e, dist2(e0, f0), g, dist2(g0, f0), side_f)?;
    Some((turn, c, g, f))
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

#[test]
fn watt_i_declares_one_freedom_with_exact_jacobians() {
    let w = WattI::new();
    assert_eq!(WattI::INPUTS, ["q"]);
    let line = mobility_line(WattI::LISTING);
    assert!(line.contains(" = 1 "), "{line}");
    let s = w.home_start().unwrap();
    check_jacobians(&w, s.v(), s.x());
    check_factorization(&w, s.v(), s.x());
    let sol = arc_length(&w, &s, &[0.7], &GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&w, &sol.v, &[0.7]);
    let closed = watt_closed_form(0.0).unwrap();
    assert!(closed.0.abs() < 1e-12 && dist2(closed.3, [-10.0, 110.0]) < 1e-12);
}

/// Checks a solved Watt I configuration against the closed form.
fn watt_matches<const N: usize>(w: &WattI, v: &[f64; N], q: f64, at: &str)
where
    WattI: Mechanism<N, 1>,
{
    let (turn, c, g, f) = watt_closed_form(q).unwrap_or_else(|| panic!("{at}: closed form"));
    let pose = pose_from_unknowns(w, v).unwrap();
    let [yaw, pitch, roll] = pose.euler();
    assert!(
        wrap(yaw - turn).abs() < 1e-8,
        "{at}: T2 turned {yaw}, closed form {turn}"
    );
    assert!(
        pitch.abs() < 1e-9 && roll.abs() < 1e-9,
        "{at}: T2 left the plane"
    );
    for (name, truth) in [("C", c), ("G", g), ("F", f)] {
        let p = point::<WattI, N, 1>(v, name);
        assert!(
            dist2(xy(p), truth) < 1e-7 && p[2].abs() < 1e-9,
            "{at}: {name} at {p:?}, closed form {truth:?}"
        );
    }
    check_inverse(w, v, &[q], &WattI::HOME_INPUTS, 1e-8);
}

#[test]
fn watt_i_forward_kinematics_against_the_closed_form() {
    let w = WattI::new();
    let start = w.home_start().unwrap();
    let mut rng = Rng::new(601);
    let mut checked = 0;
    for case in 0..12 {
        let q = rng.uniform(-1.2, 1.2);
        // Only inputs the closed form reaches on the home branches without a fold between.
        let sol = arc_length(&w, &start, &[q], &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "case {case}: q = {q}");
        watt_matches(&w, &sol.v, q, &format!("arc_length, q = {q}"));
        assert!(
            det_b(&w, &sol.v, &[q]) * start.det() > 0.0,
            "q = {q}: another branch"
        );
        checked += 1;
    }
    // The tracker along a sweep there and back.
    let mut tracker = Tracker::new(w.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let q = 1.1 * (k as f64 * 0.157).sin();
        let sample = tracker
            .update(&[q])
            .unwrap_or_else(|e| panic!("tracker at q = {q}: {e:?}"));
        watt_matches(&w, &sample.v, q, &format!("tracker, q = {q}"));
        checked += 1;
    }
    assert_eq!(checked, 52);
}

// ---------------------------------------------------------------------------------------------
// Stephenson III six-bar. The Stephenson chain's ternary links are not adjacent; the
// Stephenson III inversion fixes a binary link next to only one ternary, so the ground
// carries the ternary T1 (passive, about O1) and the binary crank O2–K (the input). The
// crank carries the ternary coupler T2 (the platform), which hangs from T1 by two binary
// links A1–Q1 and A2–Q2: a four-bar loop between two moving ternaries. Its position problem is
// the Stephenson's sextic. Dimensions ours.
linkage::mechanism! {
    /// A Stephenson III six-bar: crank O2–K driving the coupler T2, which two binary links
    /// join to the ternary T1 turning about O1.
    pub struct StephensonIII;
    base { O1 = [0.0, 0.0, 0.0], O1z = [0.0, 0.0, 1.0], O2 = [120.0, 0.0, 0.0], O2z = [120.0, 0.0, 1.0] }
    platform {
        K = [130.0, 40.0, 0.0], Kz = [130.0, 40.0, 1.0],
        Q1 = [60.0, 90.0, 0.0], Q1z = [60.0, 90.0, 1.0],
        Q2 = [110.0, 110.0, 0.0], Q2z = [110.0, 110.0, 1.0],
    }
    link crank { }
    link t1 { A1 = [-10.0, 60.0, 0.0], A1z = [-10.0, 60.0, 1.0], A2 = [40.0, 70.0, 0.0], A2z = [40.0, 70.0, 1.0] }
    chain drive = base - R(active q, axis = O2 -> O2z) - crank - R(passive, axis = K -> Kz) - platform;
    chain ternary = base - R(passive, axis = O1 -> O1z) - t1;
    chain link1 = t1 - R(passive, axis = A1 -> A1z) - R(passive, axis = Q1 -> Q1z) - platform;
    chain link2 = t1 - R(passive, axis = A2 -> A2z) - R(passive, axis = Q2 -> Q2z) - platform;
}

const ST_O2: [f64; 2] = [120.0, 0.0];
const ST_K: [f64; 2] = [130.0, 40.0];
const ST_Q: [[f64; 2]; 2] = [[60.0, 90.0], [110.0, 110.0]];
const ST_A: [[f64; 2]; 2] = [[-10.0, 60.0], [40.0, 70.0]];

/// The Stephenson III's loop equations in the two angles it leaves free at crank angle q:
/// φ (T1 about O1) and ψ (T2's turn), each binary link at its length.
fn stephenson_loops(q: f64, z: [f64; 2]) -> [f64; 2] {
    let k = add2(ST_O2, rot2(sub2(ST_K, ST_O2), q));
    std::array::from_fn(|i| {
        let qi = add2(k, rot2(sub2(ST_Q[i], ST_K), z[1]));
        let ai = rot2(ST_A[i], z[0]);
        let l = dist2(ST_Q[i], ST_A[i]);
        dist2(qi, ai).powi(2) - l * l
    })
}

/// Newton's method on [`stephenson_loops`] (central-difference Jacobian), from `z`.
fn stephenson_newton(q: f64, mut z: [f64; 2]) -> Option<[f64; 2]> {
    for _ in 0..30 {
        let f = stephenson_loops(q, z);
        if f[0].abs().max(f[1].abs()) < 1e-10 {
            return Some(z);
        }
        let h = 1e-6;
        let mut j = [[0.0; 2]; 2];
        for c in 0..2 {
            let (mut zp, mut zm) = (z, z);
            zp[c] += h;
            zm[c] -= h;
            let (fp, fm) = (stephenson_loops(q, zp), stephenson_loops(q, zm));
            for r in 0..2 {
                j[r][c] = (fp[r] - fm[r]) / (2.0 * h);
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.abs() < 1e-9 {
            return None;
        }
        z[0] -= (j[1][1] * f[0] - j[0][1] * f[1]) / det;
        z[1] -= (-j[1][0] * f[0] + j[0][0] * f[1]) / det;
    }
    None
}

/// (φ, ψ) at crank angle q, continued from home in steps of at most 0.01 rad.
fn stephenson_reference(q: f64) -> [f64; 2] {
    let steps = (q.abs() / 0.01).ceil().max(1.0) as usize;
    let mut z = [0.0; 2];
    for k in 1..=steps {
        z = stephenson_newton(q * k as f64 / steps as f64, z).expect("the reference met a fold");
    }
    z
}

fn stephenson_matches<const N: usize>(s: &StephensonIII, v: &[f64; N], q: f64, at: &str)
where
    StephensonIII: Mechanism<N, 1>,
{
    let [phi, psi] = stephenson_reference(q);
    let pose = pose_from_unknowns(s, v).unwrap();
    let [yaw, pitch, roll] = pose.euler();
    assert!(
        wrap(yaw - psi).abs() < 1e-8,
        "{at}: T2 turned {yaw}, reference {psi}"
    );
    assert!(
        pitch.abs() < 1e-9 && roll.abs() < 1e-9,
        "{at}: T2 left the plane"
    );
    for i in 0..2 {
        let a = point::<StephensonIII, N, 1>(v, ["A1", "A2"][i]);
        let truth = rot2(ST_A[i], phi);
        assert!(
            dist2(xy(a), truth) < 1e-7 && a[2].abs() < 1e-9,
            "{at}: A{} at {a:?}, reference {truth:?}",
            i + 1
        );
    }
    check_inverse(s, v, &[q], &StephensonIII::HOME_INPUTS, 1e-8);
}

#[test]
fn stephenson_iii_declares_one_freedom_with_exact_jacobians() {
    let s = StephensonIII::new();
    let line = mobility_line(StephensonIII::LISTING);
    assert!(line.contains(" = 1 "), "{line}");
    let start = s.home_start().unwrap();
    check_jacobians(&s, start.v(), start.x());
    check_factorization(&s, start.v(), start.x());
    let sol = arc_length(&s, &start, &[-1.3], &GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&s, &sol.v, &[-1.3]);
    assert_eq!(stephenson_loops(0.0, [0.0; 2]), [0.0; 2]);
}

#[test]
fn stephenson_iii_forward_kinematics_against_newton_on_its_loops() {
    let s = StephensonIII::new();
    let start = s.home_start().unwrap();
    let mut rng = Rng::new(602);
    for _ in 0..12 {
        let q = rng.uniform(-2.0, 2.0);
        let sol = arc_length(&s, &start, &[q], &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        stephenson_matches(&s, &sol.v, q, &format!("arc_length, q = {q}"));
    }
    let mut tracker = Tracker::new(s.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let q = 1.8 * (k as f64 * 0.157).sin();
        let sample = tracker
            .update(&[q])
            .unwrap_or_else(|e| panic!("tracker at q = {q}: {e:?}"));
        stephenson_matches(&s, &sample.v, q, &format!("tracker, q = {q}"));
    }
}

/// Every real (φ, ψ) of the Stephenson III at crank angle q, apart from the library: a scan of
/// φ over the circle, ψ where Q1's circle about K meets the binary link's about A1 (two
/// sides), the sign changes of the second loop's residual refined by bisection.
fn stephenson_real_modes(q: f64) -> Vec<[f64; 2]> {
    let k = add2(ST_O2, rot2(sub2(ST_K, ST_O2), q));
    let (r1, l1, l2) = (
        dist2(ST_Q[0], ST_K),
        dist2(ST_Q[0], ST_A[0]),
        dist2(ST_Q[1], ST_A[1]),
    );
    // ψ for a given φ on `side`, and the second loop's residual there.
    let g = |phi: f64, side: f64| -> Option<(f64, f64)> {
        let a1 = rot2(ST_A[0], phi);
        let q1 = circles(k, r1, a1, l1, side)?;
        let psi =
            (q1[1] - k[1]).atan2(q1[0] - k[0]) - (ST_Q[0][1] - ST_K[1]).atan2(ST_Q[0][0] - ST_K[0]);
        let q2 = add2(k, rot2(sub2(ST_Q[1], ST_K), psi));
        let a2 = rot2(ST_A[1], phi);
        Some((psi, dist2(q2, a2).powi(2) - l2 * l2))
    };
    let mut found = Vec::new();
    let n = 20000;
    let tau = 2.0 * std::f64::consts::PI;
    for side in [1.0, -1.0] {
        for i in 0..n {
            let (p0, p1) = (tau * i as f64 / n as f64, tau * (i + 1) as f64 / n as f64);
            let (Some((_, g0)), Some((_, g1))) = (g(p0, side), g(p1, side)) else {
                continue;
            };
            if g0 * g1 > 0.0 {
                continue;
            }
            let (mut lo, mut hi, mut glo) = (p0, p1, g0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let gm = g(mid, side).unwrap().1;
                if gm * glo <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                    glo = gm;
                }
            }
            let phi = 0.5 * (lo + hi);
            found.push([phi, g(phi, side).unwrap().0]);
        }
    }
    found
}

// ---------------------------------------------------------------------------------------------
// Planar 3-PRP driven at its base prismatics: each leg a slider on a rail tangent to a circle
// of radius 150 mm (the input, the slide from home), a revolute pair on the slider, and a
// passive prismatic pair along a line fixed in the platform. Dimensions ours. Its forward
// kinematics is linear in (cos φ, sin φ) and the platform-frame position, so of two solutions.
linkage::mechanism! {
    /// A planar 3-PRP: active rails, passive R on each slider, passive P along a platform line.
    pub struct Prp3;
    params {
        a1 = pi / 2.0, a2 = pi / 2.0 + 2.0 * pi / 3.0, a3 = pi / 2.0 + 4.0 * pi / 3.0,
        rb = 150.0, rp = 40.0, t = 0.3,
    }
    base {
        S1 = [rb * cos(a1) + 50.0 * sin(a1), rb * sin(a1) - 50.0 * cos(a1), 0.0],
        T1 = [rb * cos(a1) - 50.0 * sin(a1), rb * sin(a1) + 50.0 * cos(a1), 0.0],
        S2 = [rb * cos(a2) + 50.0 * sin(a2), rb * sin(a2) - 50.0 * cos(a2), 0.0],
        T2 = [rb * cos(a2) - 50.0 * sin(a2), rb * sin(a2) + 50.0 * cos(a2), 0.0],
        S3 = [rb * cos(a3) + 50.0 * sin(a3), rb * sin(a3) - 50.0 * cos(a3), 0.0],
        T3 = [rb * cos(a3) - 50.0 * sin(a3), rb * sin(a3) + 50.0 * cos(a3), 0.0],
    }
    platform {
        G1 = [rp * cos(a1 + t), rp * sin(a1 + t), 0.0],
        G2 = [rp * cos(a2 + t), rp * sin(a2 + t), 0.0],
        G3 = [rp * cos(a3 + t), rp * sin(a3 + t), 0.0],
    }
    link slider1 { C1 = [rb * cos(a1), rb * sin(a1), 0.0], C1z = [rb * cos(a1), rb * sin(a1), 1.0] }
    link slider2 { C2 = [rb * cos(a2), rb * sin(a2), 0.0], C2z = [rb * cos(a2), rb * sin(a2), 1.0] }
    link slider3 { C3 = [rb * cos(a3), rb * sin(a3), 0.0], C3z = [rb * cos(a3), rb * sin(a3), 1.0] }
    link guide1 { D1 = [rp * cos(a1 + t), rp * sin(a1 + t), 0.0], D1z = [rp * cos(a1 + t), rp * sin(a1 + t), 1.0] }
    link guide2 { D2 = [rp * cos(a2 + t), rp * sin(a2 + t), 0.0], D2z = [rp * cos(a2 + t), rp * sin(a2 + t), 1.0] }
    link guide3 { D3 = [rp * cos(a3 + t), rp * sin(a3 + t), 0.0], D3z = [rp * cos(a3 + t), rp * sin(a3 + t), 1.0] }
    chain leg1 = base - P(active s1, axis = S1 -> T1) - slider1 - R(passive, axis = C1 -> C1z) - guide1 - P(passive, axis = D1 -> C1) - platform;
    chain leg2 = base - P(active s2, axis = S2 -> T2) - slider2 - R(passive, axis = C2 -> C2z) - guide2 - P(passive, axis = D2 -> C2) - platform;
    chain leg3 = base - P(active s3, axis = S3 -> T3) - slider3 - R(passive, axis = C3 -> C3z) - guide3 - P(passive, axis = D3 -> C3) - platform;
}

/// The 3-PRP's rail point at home, rail direction, platform point and platform line direction.
fn prp_leg(i: usize) -> ([f64; 2], [f64; 2], [f64; 2], [f64; 2]) {
    let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * i as f64 / 3.0;
    let c0 = [150.0 * a.cos(), 150.0 * a.sin()];
    let u = [-a.sin(), a.cos()];
    let g = [40.0 * (a + 0.3).cos(), 40.0 * (a + 0.3).sin()];
    let d = sub2(c0, g);
    let n = d[0].hypot(d[1]);
    (c0, u, g, [d[0] / n, d[1] / n])
}

/// Both planar poses (φ, x, y) of the 3-PRP at slides `s`, in closed form: with
/// c = cos φ, s = sin φ and q = Rᵀp, leg i's point lies on its platform line when
/// d × (Rᵀ Cᵢ − q − g) = 0, linear in (c, s, q); c² + s² = 1 closes it.
fn prp_closed_form(s: [f64; 3]) -> Vec<[f64; 3]> {
    // Rows over (c, s, qx, qy) and right-hand sides.
    let mut a = [[0.0; 4]; 3];
    let mut b = [0.0; 3];
    for (i, si) in s.iter().enumerate() {
        let (c0, u, g, d) = prp_leg(i);
        let c = add2(c0, [si * u[0], si * u[1]]);
        a[i] = [
            d[0] * c[1] - d[1] * c[0],
            -(d[0] * c[0] + d[1] * c[1]),
            d[1],
            -d[0],
        ];
        b[i] = d[0] * g[1] - d[1] * g[0];
    }
    // (s, qx, qy) = m + c n from the three rows' last three columns.
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let sub: [[f64; 3]; 3] = std::array::from_fn(|r| [a[r][1], a[r][2], a[r][3]]);
    let d = det3(sub);
    let cramer = |rhs: [f64; 3]| -> [f64; 3] {
        std::array::from_fn(|k| {
            let mut m = sub;
            for r in 0..3 {
                m[r][k] = rhs[r];
            }
            det3(m) / d
        })
    };
    let m = cramer(b);
    let n = cramer(std::array::from_fn(|r| -a[r][0]));
    // c² + (m0 + c n0)² = 1.
    let (qa, qb, qc) = (1.0 + n[0] * n[0], 2.0 * m[0] * n[0], m[0] * m[0] - 1.0);
    let disc = qb * qb - 4.0 * qa * qc;
    if disc < 0.0 {
        return Vec::new();
    }
    [1.0, -1.0]
        .iter()
        .map(|sign| {
            let c = (-qb + sign * disc.sqrt()) / (2.0 * qa);
            let sn = m[0] + c * n[0];
            let q = [m[1] + c * n[1], m[2] + c * n[2]];
            let phi = sn.atan2(c);
            let p = rot2(q, phi);
            [phi, p[0], p[1]]
        })
        .collect()
}

/// The 3-PRP's pose at slides `s` on the branch of home: the closed form's solution nearest
/// the previous one along the straight segment from home, in 200 steps.
fn prp_reference(s: [f64; 3]) -> [f64; 3] {
    let mut pose = [0.0; 3];
    for k in 1..=200 {
        let t = k as f64 / 200.0;
        let sols = prp_closed_form(s.map(|x| x * t));
        pose = *sols
            .iter()
            .min_by(|a, b| {
                let da = wrap(a[0] - pose[0]).abs() + dist2([a[1], a[2]], [pose[1], pose[2]]);
                let db = wrap(b[0] - pose[0]).abs() + dist2([b[1], b[2]], [pose[1], pose[2]]);
                da.total_cmp(&db)
            })
            .expect("the reference lost its real solutions");
    }
    pose
}

fn prp_matches<const N: usize>(p: &Prp3, v: &[f64; N], s: [f64; 3], at: &str)
where
    Prp3: Mechanism<N, 3>,
{
    prp_pose_matches(p, v, s, at);
    check_inverse(p, v, &s, &Prp3::HOME_INPUTS, 1e-8);
}

/// [`prp_matches`] without the inverse check (the numerical inverse costs far more than the
/// pose).
fn prp_pose_matches<const N: usize>(p: &Prp3, v: &[f64; N], s: [f64; 3], at: &str)
where
    Prp3: Mechanism<N, 3>,
{
    let truth = prp_reference(s);
    let pose = pose_from_unknowns(p, v).unwrap();
    let [yaw, pitch, roll] = pose.euler();
    assert!(
        wrap(yaw - truth[0]).abs() < 1e-8,
        "{at}: φ {yaw}, closed form {}",
        truth[0]
    );
    assert!(
        pitch.abs() < 1e-9 && roll.abs() < 1e-9,
        "{at}: left the plane"
    );
    let t = pose.translation;
    assert!(
        (t[0] - truth[1]).abs() < 1e-7 && (t[1] - truth[2]).abs() < 1e-7 && t[2].abs() < 1e-9,
        "{at}: at {t:?}, closed form {truth:?}"
    );
}

#[test]
fn prp3_declares_three_freedoms_with_exact_jacobians() {
    let p = Prp3::new();
    assert_eq!(Prp3::INPUTS, ["s1", "s2", "s3"]);
    let line = mobility_line(Prp3::LISTING);
    assert!(line.contains(" = 3 "), "{line}");
    let start = p.home_start().unwrap();
    check_jacobians(&p, start.v(), start.x());
    check_factorization(&p, start.v(), start.x());
    let x = [20.0, -35.0, 10.0];
    let sol = arc_length(&p, &start, &x, &GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&p, &sol.v, &x);
    let home = prp_closed_form([0.0; 3]);
    assert!(
        home.iter().any(|h| h.iter().all(|c| c.abs() < 1e-12)),
        "{home:?}"
    );
}

/// Every answer labelled converged is the closed form's, and every segment is solved.
#[test]
fn prp3_forward_kinematics_against_the_closed_form() {
    let p = Prp3::new();
    let start = p.home_start().unwrap();
    let mut rng = Rng::new(603);
    for _ in 0..12 {
        let s = [0; 3].map(|_| rng.uniform(-50.0, 50.0));
        let sol = arc_length(&p, &start, &s, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "s = {s:?}");
        prp_matches(&p, &sol.v, s, &format!("arc_length, s = {s:?}"));
    }
    let mut tracker = Tracker::new(p.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let t = k as f64 * 0.157;
        let s = [
            40.0 * t.sin(),
            30.0 * (1.3 * t).sin(),
            -35.0 * (0.7 * t).sin(),
        ];
        let sample = tracker
            .update(&s)
            .unwrap_or_else(|e| panic!("tracker at {s:?}: {e:?}"));
        prp_matches(&p, &sample.v, s, &format!("tracker, s = {s:?}"));
    }
}

// ---------------------------------------------------------------------------------------------
// The Agile Eye (Gosselin & Hamel 1994): a spherical 3-RRR whose every pair of adjacent axes
// is orthogonal. Its geometry is its angles, all 90°: base axes u₁, u₂, u₃ along x, y, z; at
// home the proximal links' second axes v₁, v₂, v₃ along y, z, x and the platform's axes
// w₁, w₂, w₃ along z, x, y (the isotropic reference configuration). Each axis is declared by
// two points on it, at radii ours.
linkage::mechanism! {
    /// The Agile Eye: three orthogonal base motors, every adjacent pair of axes orthogonal.
    pub struct AgileEye;
    base {
        A1 = [50.0, 0.0, 0.0], B1 = [100.0, 0.0, 0.0],
        A2 = [0.0, 50.0, 0.0], B2 = [0.0, 100.0, 0.0],
        A3 = [0.0, 0.0, 50.0], B3 = [0.0, 0.0, 100.0],
    }
    platform {
        W1 = [0.0, 0.0, 70.0], X1 = [0.0, 0.0, 120.0],
        W2 = [70.0, 0.0, 0.0], X2 = [120.0, 0.0, 0.0],
        W3 = [0.0, 70.0, 0.0], X3 = [0.0, 120.0, 0.0],
    }
    link proximal1 { C1 = [0.0, 60.0, 0.0], D1 = [0.0, 110.0, 0.0] }
    link proximal2 { C2 = [0.0, 0.0, 60.0], D2 = [0.0, 0.0, 110.0] }
    link proximal3 { C3 = [60.0, 0.0, 0.0], D3 = [110.0, 0.0, 0.0] }
    link distal1 { } link distal2 { } link distal3 { }
    chain leg1 = base - R(active q1, axis = A1 -> B1) - proximal1 - R(passive, axis = C1 -> D1) - distal1 - R(passive, axis = W1 -> X1) - platform;
    chain leg2 = base - R(active q2, axis = A2 -> B2) - proximal2 - R(passive, axis = C2 -> D2) - distal2 - R(passive, axis = W2 -> X2) - platform;
    chain leg3 = base - R(active q3, axis = A3 -> B3) - proximal3 - R(passive, axis = C3 -> D3) - distal3 - R(passive, axis = W3 -> X3) - platform;
}

type M3 = [[f64; 3]; 3];

const E: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn mul3(r: &M3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| dot3(r[i], v))
}

/// The rotation by |w| about w (Rodrigues).
fn exp3(w: [f64; 3]) -> M3 {
    let t = dot3(w, w).sqrt();
    if t == 0.0 {
        return E;
    }
    let k = w.map(|c| c / t);
    let (s, c) = t.sin_cos();
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let skew = match (i, j) {
                (0, 1) => -k[2],
                (0, 2) => k[1],
                (1, 0) => k[2],
                (1, 2) => -k[0],
                (2, 0) => -k[1],
                (2, 1) => k[0],
                _ => 0.0,
            };
            E[i][j] * c + s * skew + (1.0 - c) * k[i] * k[j]
        })
    })
}

/// Leg i's axes at home: base u, proximal v, platform w.
fn eye_axes(i: usize) -> ([f64; 3], [f64; 3], [f64; 3]) {
    (E[i], E[(i + 1) % 3], E[(i + 2) % 3])
}

/// The Agile Eye's leg constraints at inputs q and platform rotation r: the proximal axis
/// (v turned by qᵢ about uᵢ) orthogonal to the platform's axis r wᵢ.
fn eye_constraints(q: [f64; 3], r: &M3) -> ([f64; 3], M3) {
    let mut f = [0.0; 3];
    let mut jac = [[0.0; 3]; 3];
    for i in 0..3 {
        let (u, v0, w0) = eye_axes(i);
        let v = mul3(&exp3(u.map(|c| c * q[i])), v0);
        let w = mul3(r, w0);
        f[i] = dot3(v, w);
        // d/dδ of v · (exp(δ) r w) at δ = 0 is v · (δ × w) = δ · (w × v).
        jac[i] = cross3(w, v);
    }
    (f, jac)
}

/// The platform's rotation at inputs q, continued from home along the straight segment in
/// steps of at most 0.01 rad, Newton's method on SO(3) at each.
fn eye_reference(q: [f64; 3]) -> M3 {
    let steps = (q.iter().fold(0.0f64, |m, x| m.max(x.abs())) / 0.01)
        .ceil()
        .max(1.0) as usize;
    let mut r = E;
    for k in 1..=steps {
        let qk = q.map(|x| x * k as f64 / steps as f64);
        let mut done = false;
        for _ in 0..30 {
            let (f, j) = eye_constraints(qk, &r);
            if f.iter().all(|x| x.abs() < 1e-14) {
                done = true;
                break;
            }
            let d = dot3(j[0], cross3(j[1], j[2]));
            assert!(d.abs() > 1e-9, "the reference met a singularity");
            // δ = −J⁻¹ f by the cross-product inverse of a 3×3.
            let inv_rows = [cross3(j[1], j[2]), cross3(j[2], j[0]), cross3(j[0], j[1])];
            let delta: [f64; 3] =
                std::array::from_fn(|c| -(0..3).map(|k| inv_rows[k][c] * f[k]).sum::<f64>() / d);
            r = linkage_tests::vec3::matmul(&exp3(delta), &r);
        }
        assert!(done, "the reference did not converge at {qk:?}");
    }
    r
}

fn eye_matches<const N: usize>(eye: &AgileEye, v: &[f64; N], q: [f64; 3], at: &str)
where
    AgileEye: Mechanism<N, 3>,
{
    let r = eye_reference(q);
    let pose = pose_from_unknowns(eye, v).unwrap();
    for i in 0..3 {
        let (_, _, w) = eye_axes(i);
        let truth = mul3(&r, w.map(|c| 120.0 * c));
        let got = pose.apply(w.map(|c| 120.0 * c));
        let d = (0..3).fold(0.0f64, |m, k| m.max((got[k] - truth[k]).abs()));
        assert!(
            d < 1e-7,
            "{at}: platform axis {i} at {got:?}, reference {truth:?}"
        );
    }
    assert!(
        pose.translation.iter().all(|c| c.abs() < 1e-8),
        "{at}: the centre moved"
    );
    check_inverse(eye, v, &q, &AgileEye::HOME_INPUTS, 1e-8);
}

#[test]
fn agile_eye_declares_three_freedoms_with_exact_jacobians() {
    let eye = AgileEye::new();
    let line = mobility_line(AgileEye::LISTING);
    assert!(line.contains(" = 3 "), "{line}");
    let start = eye.home_start().unwrap();
    check_jacobians(&eye, start.v(), start.x());
    check_factorization(&eye, start.v(), start.x());
    let x = [0.4, -0.3, 0.2];
    let sol = arc_length(&eye, &start, &x, &GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&eye, &sol.v, &x);
}

#[test]
fn agile_eye_forward_kinematics_against_newton_on_so3() {
    let eye = AgileEye::new();
    let start = eye.home_start().unwrap();
    let mut rng = Rng::new(604);
    for _ in 0..12 {
        let q = [0; 3].map(|_| rng.uniform(-0.8, 0.8));
        let sol = arc_length(&eye, &start, &q, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q:?}");
        eye_matches(&eye, &sol.v, q, &format!("arc_length, q = {q:?}"));
    }
    let mut tracker = Tracker::new(eye.clone(), start, GENERAL_MODEL);
    for k in 1..=40 {
        let t = k as f64 * 0.157;
        let q = [0.7 * t.sin(), 0.5 * (1.3 * t).sin(), -0.6 * (0.7 * t).sin()];
        let sample = tracker
            .update(&q)
            .unwrap_or_else(|e| panic!("tracker at {q:?}: {e:?}"));
        eye_matches(&eye, &sample.v, q, &format!("tracker, q = {q:?}"));
    }
}

// ---------------------------------------------------------------------------------------------
// Every assembly mode.

/// The mechanism's roots among a solve's endpoints: for a planar mechanism declared in space,
/// those whose every z is where it is at home (real part) and real (imaginary part) — the
/// square system the generator leaves can also have roots folded out of the plane, which are
/// not assemblies of the mechanism (`Spurious` where real).
fn in_plane<S: Mechanism<N, M>, const N: usize, const M: usize>(
    home: &[f64; N],
    v: &[Complex; N],
) -> bool {
    S::UNKNOWNS
        .iter()
        .enumerate()
        .filter(|(_, u)| u.starts_with("z_"))
        .all(|(i, _)| (v[i].re - home[i]).abs() < 1e-6 && v[i].im.abs() < 1e-6)
}

/// What `AllModes` finds at each of `inputs`.
struct Found<const N: usize> {
    /// The square system's generic number of roots.
    count: usize,
    /// Per input: the real roots that are assemblies (not `Spurious`).
    real: Vec<Vec<[f64; N]>>,
    /// Per input: the endpoints `genuine` accepts (real or complex).
    genuine: Vec<usize>,
}

/// `AllModes` at each of `inputs`: every path ends at a distinct nonsingular root (a real one
/// off the mechanism is `Spurious`, never an assembly), and every real root has a tiny
/// residual and gives its inputs back by `Mechanism::inverse`.
fn real_modes<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    sys: &S,
    inputs: &[[f64; M]],
    genuine: impl Fn(&[Complex; N]) -> bool,
) -> Found<N> {
    let modes = AllModes::<S, N, M, 64>::new(sys.clone(), &ModesOptions::default())
        .unwrap_or_else(|e| panic!("{}: {e}", S::NAME));
    let mut roots = Box::new(Roots::<N, 64>::new());
    let mut found = Found {
        count: modes.start_count(),
        real: Vec::new(),
        genuine: Vec::new(),
    };
    for x in inputs {
        modes.solve(x, &mut roots).unwrap();
        for e in roots.endpoints() {
            assert!(
                e.is_root() || e.kind == EndpointKind::Spurious,
                "{} at {x:?}: a path ended {:?}",
                S::NAME,
                e.kind
            );
            // A real root off the mechanism is refused (`genuine` is necessary, not sufficient:
            // a root can be in the plane and still miss an equation left out).
            if e.kind != EndpointKind::Complex && !genuine(&e.v) {
                assert_eq!(e.kind, EndpointKind::Spurious, "{} at {x:?}", S::NAME);
            }
        }
        let mut real = Vec::new();
        for r in roots.real() {
            assert!(
                r.residual < 1e-7,
                "{} at {x:?}: residual {}",
                S::NAME,
                r.residual
            );
            let back = sys.inverse(&r.v, x).unwrap();
            assert!(
                linkage_tests::max_diff(&back, x) < 1e-7,
                "{} at {x:?}: a real root gives {back:?} back",
                S::NAME
            );
            real.push(r.v);
        }
        let genuine_here = roots.endpoints().iter().filter(|e| genuine(&e.v)).count();
        println!(
            "{}: {} roots at {x:?}, {genuine_here} of the mechanism, {} real; {:?}",
            S::NAME,
            modes.start_count(),
            real.len(),
            modes.report()
        );
        found.real.push(real);
        found.genuine.push(genuine_here);
    }
    found
}

/// Watt I's configurations at crank angle q, all four side choices (C about J–O2, F about
/// E–G) that exist: (C, F).
fn watt_all(q: f64) -> Vec<([f64; 2], [f64; 2])> {
    let (o2, j0, c0, g0, e0, f0) = (
        [100.0, 0.0],
        [20.0, 50.0],
        [110.0, 70.0],
        [60.0, 110.0],
        [-30.0, 40.0],
        [-10.0, 110.0],
    );
    let (j, e) = (rot2(j0, q), rot2(e0, q));
    let mut out = Vec::new();
    for sc in [1.0, -1.0] {
        let Some(c) = circles(j, dist2(j0, c0), o2, dist2(o2, c0), sc) else {
            continue;
        };
        let turn = (c[1] - j[1]).atan2(c[0] - j[0]) - (c0[1] - j0[1]).atan2(c0[0] - j0[0]);
        let g = add2(j, rot2(sub2(g0, j0), turn));
        for sf in [1.0, -1.0] {
            if let Some(f) = circles(e, dist2(e0, f0), g, dist2(g0, f0), sf) {
                out.push((c, f));
            }
        }
    }
    out
}

/// Asserts that the real roots are exactly the reference's configurations: as many, each
/// root within `tol` of a distinct one (by `distance`).
fn same_modes<T, const N: usize>(
    name: &str,
    roots: &[[f64; N]],
    reference: &[T],
    distance: impl Fn(&[f64; N], &T) -> f64,
    tol: f64,
) {
    assert_eq!(
        roots.len(),
        reference.len(),
        "{name}: real roots vs the reference's"
    );
    let mut used = vec![false; reference.len()];
    for r in roots {
        let k = (0..reference.len())
            .filter(|&k| !used[k])
            .min_by(|&a, &b| distance(r, &reference[a]).total_cmp(&distance(r, &reference[b])))
            .unwrap();
        assert!(
            distance(r, &reference[k]) < tol,
            "{name}: a root matches no reference mode"
        );
        used[k] = true;
    }
}

#[test]
fn six_bars_and_the_prp_have_their_generic_root_counts() {
    let inputs = [[0.3], [-0.9], [1.7], [2.6]];
    let w = WattI::new();
    let home = *w.home_start().unwrap().v();
    let found = real_modes(&w, &inputs, |v| in_plane::<WattI, 24, 1>(&home, v));
    assert_eq!(found.count, 4, "Watt I");
    assert_eq!(found.genuine, [4; 4], "Watt I");
    for (x, real) in inputs.iter().zip(&found.real) {
        same_modes(
            "Watt I",
            real,
            &watt_all(x[0]),
            |v, (c, f)| {
                let pc = point::<WattI, 24, 1>(v, "C");
                let pf = point::<WattI, 24, 1>(v, "F");
                dist2(xy(pc), *c).max(dist2(xy(pf), *f))
            },
            1e-6,
        );
    }

    // Six assemblies, as the Stephenson six-bar's sextic has; the square system has six more
    // roots folded out of the plane, refused as `Spurious` where real.
    let s = StephensonIII::new();
    let home = *s.home_start().unwrap().v();
    let found = real_modes(&s, &inputs, |v| in_plane::<StephensonIII, 30, 1>(&home, v));
    assert_eq!(found.count, 12, "Stephenson III");
    assert_eq!(found.genuine, [6; 4], "Stephenson III");
    for (x, real) in inputs.iter().zip(&found.real) {
        same_modes(
            "Stephenson III",
            real,
            &stephenson_real_modes(x[0]),
            |v, z| {
                (0..2)
                    .map(|i| {
                        let a = point::<StephensonIII, 30, 1>(v, ["A1", "A2"][i]);
                        dist2(xy(a), rot2(ST_A[i], z[0]))
                    })
                    .fold(0.0, f64::max)
            },
            1e-6,
        );
    }
}

/// The 3-PRP's assembly modes: the real roots are exactly the closed form's two (or none).
/// Monodromy once stopped at 1 root: its loops reached 50 times past the mechanism's size,
/// where 9 of 10 ran out of steps, and those failed loops counted as fruitless.
#[test]
fn prp3_real_modes_are_the_closed_forms() {
    let p = Prp3::new();
    let home = *p.home_start().unwrap().v();
    let xs = [[10.0, -20.0, 30.0], [-45.0, 5.0, 25.0], [60.0, 70.0, -80.0]];
    let found = real_modes(&p, &xs, |v| in_plane::<Prp3, 39, 3>(&home, v));
    println!(
        "3-PRP: {} roots of the square system, {:?} in the plane",
        found.count, found.genuine
    );
    for (x, real) in xs.iter().zip(&found.real) {
        let poses: Vec<[f64; 3]> = real
            .iter()
            .map(|v| {
                let pose = pose_from_unknowns(&p, v).unwrap();
                [pose.euler()[0], pose.translation[0], pose.translation[1]]
            })
            .collect();
        same_modes(
            "3-PRP",
            &poses,
            &prp_closed_form(*x),
            |a, b| {
                wrap(a[0] - b[0])
                    .abs()
                    .max(dist2([a[1], a[2]], [b[1], b[2]]))
            },
            1e-6,
        );
    }
}

/// Four assembly modes, as Bonev, Chablat & Wenger (2006) show for the Agile Eye's direct
/// kinematics; here all four real at each input.
#[test]
fn agile_eye_has_four_assembly_modes() {
    let eye = AgileEye::new();
    let xs = [[0.3, -0.2, 0.5], [-0.7, 0.4, 0.1], [1.1, 0.9, -0.6]];
    let found = real_modes(&eye, &xs, |_| true);
    assert_eq!(found.count, 4);
    assert_eq!(found.genuine, [4; 3]);
    for (x, real) in xs.iter().zip(&found.real) {
        assert_eq!(real.len(), 4, "at {x:?}");
        // Each gives orthogonal proximal and platform axes, as the legs require.
        for v in real {
            let pose = pose_from_unknowns(&eye, v).unwrap();
            for i in 0..3 {
                let (u, v0, w0) = eye_axes(i);
                let vi = mul3(&exp3(u.map(|c| c * x[i])), v0);
                let w = pose.apply(w0);
                let o = pose.apply([0.0; 3]);
                let wi: [f64; 3] = std::array::from_fn(|k| w[k] - o[k]);
                assert!(dot3(vi, wi).abs() < 1e-9, "leg {i} at {x:?}");
            }
        }
    }
}

/// The square system the generator leaves for the 3-PRP is regular wherever the mechanism is:
/// Newton on it (dense, this file's LU) along a straight segment of the slides, det B keeps
/// its sign while the closed form's own Jacobian stays clear of zero. The rank pass used to
/// keep the three guides' placements of the platform before the guides' own distances, and
/// det B changed sign at 57.5 % of this segment, a regular configuration, where `arc_length`
/// stopped with `Fold` (2 of the 12 random segments of the test above).
#[test]
fn prp3_square_system_is_regular_where_the_mechanism_is() {
    use linkage_tests::dense::Lu;
    let p = Prp3::new();
    let start = p.home_start().unwrap();
    let target = [26.80668658223898, 18.711899018282892, 37.44434972405699];
    let dense = |v: &[f64; 39], x: &[f64; 3]| {
        let mut values = vec![0.0; Prp3::NNZ];
        p.jacobian(v, x, &mut values);
        let mut b = [[0.0; 39]; 39];
        for (&(r, c), &value) in Prp3::PATTERN.iter().zip(&values) {
            b[r][c] = value;
        }
        Lu::new(b)
    };
    let mut v = *start.v();
    let det0 = dense(&v, &[0.0; 3]).unwrap().det;
    for k in 1..=200 {
        let x = target.map(|c| c * k as f64 / 200.0);
        // Newton to the rounding floor (a few iterations from the last step's answer).
        for _ in 0..20 {
            let mut f = [0.0; 39];
            p.residual(&v, &x, &mut f);
            dense(&v, &x).expect("B singular").solve(&mut f);
            for (vi, fi) in v.iter_mut().zip(&f) {
                *vi -= fi;
            }
            if f.iter().all(|d| d.abs() <= 1e-13) {
                break;
            }
        }
        // The pose at every step; the inputs back from it at every twentieth.
        if k % 20 == 0 {
            prp_matches(&p, &v, x, &format!("Newton at {x:?}"));
        } else {
            prp_pose_matches(&p, &v, x, &format!("Newton at {x:?}"));
        }
        let det = dense(&v, &x).expect("B singular").det;
        assert!(
            det * det0 > 0.0,
            "det B changed sign at {x:?} (step {k} of 200)"
        );
    }
}
