//! Theo Jansen's leg (the Strandbeest, 1990, with his published "holy numbers"): a crank,
//! seven moving links, ten R pairs, two ternary links and four loops, one freedom. Checked
//! against its closed form, five circle intersections in turn, over whole turns of the crank,
//! by the tracker and by continuation from home.

use super::{check_inverse, circles, point, GENERAL_MODEL};
use linkage::{arc_length, det_b, Mechanism, Status, Tracker};
use linkage_tests::{check_factorization, check_jacobians, Rng};

// The holy numbers: frame offsets a and l, crank m, couplers j and k, the upper rocker's
// triangle b, d, e, the lower rocker c, the link f, the foot's triangle g, h, i.
const A: f64 = 38.0;
const B: f64 = 41.5;
const C: f64 = 39.3;
const D: f64 = 40.1;
const E: f64 = 55.8;
const F: f64 = 39.4;
const G: f64 = 36.7;
const H: f64 = 65.7;
const I: f64 = 49.0;
const J: f64 = 50.0;
const K: f64 = 61.9;
const L: f64 = 7.8;
const M: f64 = 15.0;

linkage::mechanism! {
    /// Jansen's leg at crank angle 0 (the crank along +x): the crank turns about O, both
    /// rockers about Z; the platform is the foot's triangle U–V–Foot.
    pub struct Jansen;
    base { O = [0.0, 0.0, 0.0], Oz = [0.0, 0.0, 1.0], Z = [-38.0, -7.8, 0.0], Zz = [-38.0, -7.8, 1.0] }
    platform {
        U = [-59.231514961415, -28.052930230747755, 0.0], Uz = [-59.231514961415, -28.052930230747755, 1.0],
        Foot = [-43.160110524104724, -91.75693292612323, 0.0],
    }
    link crank { X = [15.0, 0.0, 0.0], Xz = [15.0, 0.0, 1.0] }
    link upper {
        Y = [-24.013535097127793, 31.272097454842683, 0.0], Yz = [-24.013535097127793, 31.272097454842683, 1.0],
        W = [-74.79436538093606, 8.143170205896146, 0.0], Wz = [-74.79436538093606, 8.143170205896146, 1.0],
    }
    link lower { V = [-26.952107031572965, -45.51517017008116, 0.0], Vz = [-26.952107031572965, -45.51517017008116, 1.0] }
    chain drive = base - R(active q, axis = O -> Oz) - crank;
    chain upper_coupler = crank - R(passive, axis = X -> Xz) - R(passive, axis = Y -> Yz) - upper;
    chain upper_rocker = base - R(passive, axis = Z -> Zz) - upper;
    chain lower_coupler = crank - R(passive, axis = X -> Xz) - R(passive, axis = V -> Vz) - lower;
    chain lower_rocker = base - R(passive, axis = Z -> Zz) - lower;
    chain foot = lower - R(passive, axis = V -> Vz) - platform;
    chain tie = upper - R(passive, axis = W -> Wz) - R(passive, axis = U -> Uz) - platform;
}

/// Where two circles of the leg meet ([`circles`]): always, for this leg, over whole turns.
fn meet(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64, side: f64) -> [f64; 2] {
    circles(a, ra, b, rb, side).expect("the leg's circles meet")
}

/// X, Y, V, W, U and the foot at crank angle q, on the sides they are at home.
fn closed_form(q: f64) -> [[f64; 2]; 6] {
    let z = [-A, -L];
    let x = [M * q.cos(), M * q.sin()];
    let y = meet(x, J, z, B, -1.0);
    let v = meet(x, K, z, C, 1.0);
    let w = meet(z, D, y, E, 1.0);
    let u = meet(w, F, v, G, -1.0);
    let foot = meet(v, I, u, H, 1.0);
    [x, y, v, w, u, foot]
}

const NAMES: [&str; 5] = ["Y", "V", "W", "U", "Foot"];

fn pt<const N: usize>(v: &[f64; N], name: &str) -> [f64; 3]
where
    Jansen: Mechanism<N, 1>,
{
    point::<Jansen, N, 1>(v, name)
}

fn check_against_closed_form<const N: usize>(v: &[f64; N], q: f64, what: &str)
where
    Jansen: Mechanism<N, 1>,
{
    for (name, at) in NAMES.into_iter().zip(closed_form(q)[1..].iter()) {
        let p = pt(v, name);
        assert!(
            (p[0] - at[0]).abs() < 1e-7 && (p[1] - at[1]).abs() < 1e-7 && p[2].abs() < 1e-9,
            "{what}, q = {q}: {name} at {p:?}, closed form {at:?}"
        );
    }
}

#[test]
fn jansen_leg_has_one_freedom_and_exact_jacobians() {
    let leg = Jansen::new();
    let line = super::mobility_line(Jansen::LISTING);
    assert!(line.contains(" = 1 "), "{line}");
    let s = leg.home_start().unwrap();
    check_jacobians(&leg, s.v(), s.x());
    check_factorization(&leg, s.v(), s.x());
    check_against_closed_form(s.v(), 0.0, "home");
}

#[test]
fn jansen_leg_tracked_over_two_turns_each_way() {
    let leg = Jansen::new();
    let start = leg.home_start().unwrap();
    for sense in [1.0, -1.0] {
        let mut tracker = Tracker::new(leg.clone(), start, GENERAL_MODEL);
        for k in 0..=1300 {
            let q = sense * k as f64 * 0.01;
            let sol = tracker
                .update(&[q])
                .unwrap_or_else(|e| panic!("sample {k}, q = {q}: {e:?}"));
            check_against_closed_form(&sol.v, q, "tracked");
        }
    }
}

#[test]
fn jansen_leg_by_continuation_from_home() {
    let leg = Jansen::new();
    let start = leg.home_start().unwrap();
    let mut rng = Rng::new(1990);
    for _ in 0..30 {
        let q = rng.uniform(-3.1, 3.1);
        let sol = arc_length(&leg, &start, &[q], &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "q = {q}");
        check_against_closed_form(&sol.v, q, "continuation");
        assert!(det_b(&leg, &sol.v, &[q]) * start.det() > 0.0, "q = {q}");
        check_inverse(&leg, &sol.v, &[q], &Jansen::HOME_INPUTS, 1e-8);
    }
}

/// Eight isolated assemblies at every crank angle: each coupler's far joint (Y, V) and the
/// tie's (U) on either side, the two triangles' third points where their shape puts them (a
/// rigid triangle in the plane cannot turn over: its hinge to the base stays vertical).
#[test]
fn jansen_leg_has_eight_assembly_modes_and_a_capped_start_set_is_no_complete_list() {
    use linkage::modes::{AllModes, Ended, ModesOptions, Roots};
    let leg = Jansen::new();
    // With a cap of 200 loops (the default until 2026-12-02) monodromy stops short of the 32
    // roots: the lists tracked from that start set do not call themselves complete.
    let cap = ModesOptions {
        max_loops: 200,
        ..ModesOptions::default()
    };
    let capped = AllModes::<Jansen, 27, 1, 64>::new(leg.clone(), &cap).unwrap();
    let mut roots = Box::new(Roots::<27, 64>::new());
    assert_eq!(
        capped.report().ended,
        Ended::LoopCap,
        "{:?}",
        capped.report()
    );
    assert!(capped.start_count() < 32);
    capped.solve(&[0.0], &mut roots).unwrap();
    assert!(roots.start_set_capped() && !roots.is_complete());
    let modes = AllModes::<Jansen, 27, 1, 64>::new(leg.clone(), &ModesOptions::default()).unwrap();
    assert_eq!(modes.report().ended, Ended::Stable, "{:?}", modes.report());
    assert_eq!(modes.start_count(), 32, "{:?}", modes.report());
    for q in [0.0, 1.0, 2.5, -2.0] {
        modes.solve(&[q], &mut roots).unwrap();
        assert!(roots.is_complete() && !roots.start_set_capped(), "q = {q}");
        let z = [-A, -L];
        let x = [M * q.cos(), M * q.sin()];
        let mut want = Vec::new();
        for sy in [1.0, -1.0] {
            for sv in [1.0, -1.0] {
                for su in [1.0, -1.0] {
                    let y = meet(x, J, z, B, sy);
                    let v = meet(x, K, z, C, sv);
                    let w = meet(z, D, y, E, 1.0);
                    let u = meet(w, F, v, G, su);
                    want.push([y, v, w, u, meet(v, I, u, H, 1.0)]);
                }
            }
        }
        assert_eq!(roots.real().len(), 8, "q = {q}");
        for r in roots.real() {
            assert!(r.residual < 1e-7, "q = {q}: residual {}", r.residual);
            let got = NAMES.map(|n| pt(&r.v, n));
            let k = want
                .iter()
                .position(|m| {
                    m.iter().zip(&got).all(|(m, g)| {
                        (m[0] - g[0]).abs() < 1e-6
                            && (m[1] - g[1]).abs() < 1e-6
                            && g[2].abs() < 1e-6
                    })
                })
                .unwrap_or_else(|| panic!("q = {q}: a real root {got:?} is no assembly"));
            want.swap_remove(k);
        }
    }
}
