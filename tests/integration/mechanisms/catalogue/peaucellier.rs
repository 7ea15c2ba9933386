//! The Peaucellier–Lipkin linkage (1864): seven moving links and ten revolute pairs, three
//! links meeting at four of its joints, whose point P moves on an exact straight line. A crank
//! of radius r about Q, with |OQ| = r, carries C round a circle through O; the arms OA = OB = l
//! and the rhombus ACBP of side s make P the inverse of C in the circle about O of radius
//! √(l² − s²): |OC|·|OP| = l² − s², so P stays on the line x = (l² − s²)/(2r). Checked against
//! that line and the inversion, which no part of the model states, and against the closed form
//! of every joint and P's velocity.

use super::{check_inverse, point, GENERAL_MODEL};
use linkage::velocity::pivot_rates;
use linkage::{arc_length, det_b, Mechanism, Status, Tracker};
use linkage_tests::{check_factorization, check_jacobians, Rng};

const L: f64 = 100.0;
const S: f64 = 50.0;
const R: f64 = 40.0;
/// |OC| at home, and so the crank's angle there (C on the circle of radius R about (R, 0)).
const OC_HOME: f64 = 70.0;

linkage::mechanism! {
    /// Peaucellier–Lipkin: base pivots O (the arms) and Q (the crank); the platform is the
    /// rhombus side P–A.
    pub struct Peaucellier;
    params {
        l = 100.0, s = 50.0,
        ca = 70.0 / 80.0, sa = sqrt(1.0 - ca * ca),
        oc = 70.0, op = (l * l - s * s) / oc,
        m = (oc + op) / 2.0, h = sqrt(s * s - (op - oc) * (op - oc) / 4.0),
    }
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0], Q = [40.0, 0.0, 0.0], Qz = [40.0, 0.0, 1.0] }
    platform { P = [op * ca, op * sa, 0.0], Pz = [op * ca, op * sa, 1.0] }
    link crank { C = [oc * ca, oc * sa, 0.0], Cz = [oc * ca, oc * sa, 1.0] }
    link arm1 { A = [m * ca - h * sa, m * sa + h * ca, 0.0], Az = [m * ca - h * sa, m * sa + h * ca, 1.0] }
    link arm2 { B = [m * ca + h * sa, m * sa - h * ca, 0.0], Bz = [m * ca + h * sa, m * sa - h * ca, 1.0] }
    link bp { }
    chain drive = base - R(active q, axis = Q -> Qz) - crank;
    chain upper = base - R(passive, axis = O -> Oz) - arm1 - R(passive, axis = A -> Az) - platform;
    chain lower = base - R(passive, axis = O -> Oz) - arm2 - R(passive, axis = B -> Bz) - bp - R(passive, axis = P -> Pz) - platform;
    chain ac = crank - R(passive, axis = C -> Cz) - R(passive, axis = A -> Az) - arm1;
    chain cb = crank - R(passive, axis = C -> Cz) - R(passive, axis = B -> Bz) - arm2;
}

/// The point `name` of the solved unknowns.
fn pt<const N: usize>(v: &[f64; N], name: &str) -> [f64; 3]
where
    Peaucellier: Mechanism<N, 1>,
{
    point::<Peaucellier, N, 1>(v, name)
}

/// C, P, A and B in closed form at crank angle q from home: C on the crank's circle, P its
/// inverse, A and B where the circles of radius l about O and s about C meet.
fn closed_form(q: f64) -> [[f64; 2]; 4] {
    let phi = 2.0 * (OC_HOME / (2.0 * R)).acos() + q;
    let c = [R + R * phi.cos(), R * phi.sin()];
    let oc = c[0].hypot(c[1]);
    let u = [c[0] / oc, c[1] / oc];
    let op = (L * L - S * S) / oc;
    let m = 0.5 * (oc + op);
    let h = (S * S - 0.25 * (op - oc) * (op - oc)).sqrt();
    [
        c,
        [u[0] * op, u[1] * op],
        [u[0] * m - h * u[1], u[1] * m + h * u[0]],
        [u[0] * m + h * u[1], u[1] * m - h * u[0]],
    ]
}

#[test]
fn peaucellier_has_one_freedom_and_exact_jacobians() {
    let pl = Peaucellier::new();
    assert_eq!(Peaucellier::INPUTS, ["q"]);
    let line = super::mobility_line(Peaucellier::LISTING);
    assert!(line.contains(" = 1 "), "{line}");
    let s = pl.home_start().unwrap();
    check_jacobians(&pl, s.v(), s.x());
    check_factorization(&pl, s.v(), s.x());
    // The declared configuration is the closed form's at q = 0.
    // C is placed by the input alone: the model keeps P, A and B (with their axes' second
    // points) as its unknowns.
    let [_, p, a, b] = closed_form(0.0);
    for (name, at) in [("P", p), ("A", a), ("B", b)] {
        let v = pt(s.v(), name);
        assert!(
            (v[0] - at[0]).abs() < 1e-9 && (v[1] - at[1]).abs() < 1e-9,
            "{name}"
        );
    }
}

#[test]
fn peaucellier_point_moves_on_a_straight_line() {
    let pl = Peaucellier::new();
    let start = pl.home_start().unwrap();
    let line_x = (L * L - S * S) / (2.0 * R);
    let mut rng = Rng::new(1864);
    for _ in 0..40 {
        let q = rng.uniform(-0.7, 0.6);
        let sol = arc_length(&pl, &start, &[q], &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        let p = pt(&sol.v, "P");
        let [c, ..] = closed_form(q);
        // The straight line and the inversion, which the equations do not state.
        assert!((p[0] - line_x).abs() < 1e-7, "q = {q}: P at {p:?}");
        let (oc, op) = (c[0].hypot(c[1]), p[0].hypot(p[1]));
        assert!(
            (oc * op - (L * L - S * S)).abs() < 1e-6,
            "q = {q}: {oc} · {op}"
        );
        assert!(
            (c[0] * p[1] - c[1] * p[0]).abs() < 1e-6,
            "q = {q}: O, C, P not aligned"
        );
        for (name, at) in ["P", "A", "B"]
            .into_iter()
            .zip(closed_form(q)[1..].iter().copied())
        {
            let v = pt(&sol.v, name);
            assert!(
                (v[0] - at[0]).abs() < 1e-7 && (v[1] - at[1]).abs() < 1e-7 && v[2].abs() < 1e-9,
                "q = {q}: {name} at {v:?}, closed form {at:?}"
            );
        }
        // P's velocity is along the line, and its rate the closed form's.
        let rates = pivot_rates(&pl, &sol.v, &[q], &[1.0]).unwrap();
        let pdot = pt(&rates, "P");
        let h = 1e-6;
        let fd = (closed_form(q + h)[1][1] - closed_form(q - h)[1][1]) / (2.0 * h);
        assert!(
            pdot[0].abs() < 1e-6 && pdot[2].abs() < 1e-9,
            "q = {q}: Ṗ = {pdot:?}"
        );
        assert!(
            (pdot[1] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
            "q = {q}: Ṗ = {pdot:?}, {fd}"
        );
        assert!(det_b(&pl, &sol.v, &[q]) * start.det() > 0.0, "q = {q}");
        check_inverse(&pl, &sol.v, &[q], &Peaucellier::HOME_INPUTS, 1e-8);
    }
}

#[test]
fn peaucellier_tracked_along_a_sweep_stays_on_the_line() {
    let pl = Peaucellier::new();
    let mut tracker = Tracker::new(pl.clone(), pl.home_start().unwrap(), GENERAL_MODEL);
    let line_x = (L * L - S * S) / (2.0 * R);
    for k in 0..=600 {
        // Down to −0.7 rad, up to 0.6 and back, 1 kHz-like steps of about 4 mrad.
        let t = k as f64 / 600.0;
        let q = -0.7 * (std::f64::consts::TAU * t).sin().max(0.0)
            + 0.6 * (-(std::f64::consts::TAU * t).sin()).max(0.0);
        let sol = tracker
            .update(&[q])
            .unwrap_or_else(|e| panic!("sample {k}, q = {q}: {e:?}"));
        let p = pt(&sol.v, "P");
        assert!((p[0] - line_x).abs() < 1e-7, "q = {q}: P at {p:?}");
    }
}

/// Four isolated assemblies at every crank angle: A above or below OC, and P at the
/// inverse of C or at C itself (the rhombus folded onto its diagonal, P's links on C's). Where
/// A and B meet at one point, P may turn about it: a curve of roots, not an isolated
/// assembly, which `AllModes` does not list.
#[test]
fn peaucellier_has_four_isolated_assembly_modes() {
    use linkage::modes::{AllModes, ModesOptions, Roots};
    let pl = Peaucellier::new();
    let modes = AllModes::<Peaucellier, 18, 1, 64>::new(pl.clone(), &ModesOptions::default())
        .expect("a start set");
    assert_eq!(modes.start_count(), 4, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<18, 64>::new());
    for q in [0.0, 0.3, -0.5] {
        modes.solve(&[q], &mut roots).unwrap();
        assert!(roots.is_complete(), "q = {q}");
        let [c, p, a, b] = closed_form(q);
        let mut want = vec![(p, a, b), (p, b, a), (c, a, b), (c, b, a)];
        for r in roots.real() {
            assert!(r.residual < 1e-7, "q = {q}: residual {}", r.residual);
            let [gp, ga, gb] = ["P", "A", "B"].map(|n| pt(&r.v, n));
            let near = |u: [f64; 3], w: [f64; 2]| {
                (u[0] - w[0]).hypot(u[1] - w[1]) < 1e-6 && u[2].abs() < 1e-6
            };
            let k = want
                .iter()
                .position(|&(wp, wa, wb)| near(gp, wp) && near(ga, wa) && near(gb, wb))
                .unwrap_or_else(|| {
                    panic!("q = {q}: a real root P {gp:?} A {ga:?} B {gb:?} is no assembly")
                });
            want.swap_remove(k);
        }
        assert!(want.is_empty(), "q = {q}: assemblies not found: {want:?}");
    }
}
