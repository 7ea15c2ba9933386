//! The Goldberg 5R linkage (M. Goldberg, *New five-bar and six-bar linkages in three
//! dimensions*, Trans. ASME 65, 1943): two Bennett linkages that share a link, the shared link
//! taken away and the two links that leave one of its joints fused. Five R pairs on skew axes:
//! Grübler–Kutzbach counts 6·4 − 5·5 = −1, it moves with one freedom. Against the closed form
//! of its two Bennett loops (`bennett.rs`): the first of links a, α, b, β (joints J1–J4), the
//! second of c, γ, b, β (joints J1, J5, J6, J4), a / sin α = b / sin β = c / sin γ; at J1, the
//! second loop's angle is the first's plus a constant δ (the fused links).

use super::bennett::{carry, dh, mul, next, next_unwrapped, tracked_over_turns, M4};
use super::{check_inverse, mobility_line, point, GENERAL_MODEL};
use linkage::{arc_length, Mechanism, Status};
use linkage_tests::{check_jacobians, max_diff};

/// The model's unknowns.
const N: usize = 21;

// a = 100, α = 60°, b = 70, β = asin(0.7 sin 60°) ≈ 37.3°, γ = 80°, c = a sin γ / sin α, at
// θ1 = 1 rad and δ = 1 rad, the base the fused link with its frame at J1 (x along the first
// loop's link to J2, z along J1's axis). Each axis's point is its Denavit–Hartenberg frame's
// origin, the second point 50 along its z; the platform is the link from J3 to J4 and carries
// three points of its own, in J4's frame (−20, 30, 10), (25, −15, 20) and (10, 40, −25).
linkage::mechanism! {
    /// The Goldberg 5R linkage driven at J2.
    pub struct Goldberg;
    base {
        A = [100.0, 0.0, 0.0], Az = [100.0, -43.30127018922193, 25.000000000000007],
        E = [61.44091125550404, 95.68854979915832, 0.0],
        Ez = [102.87526874418576, 69.08385480969245, 8.68240888334652],
    }
    platform {
        P1 = [-33.31891398794735, 28.981074814928164, 22.00931667085499],
        P2 = [-37.91398546996885, 92.36026888309006, 11.428056001852198],
        P3 = [-77.27039166866064, 31.648297727035807, 5.093243497127883],
    }
    link l23 {
        B = [32.80928667011649, -9.81590599768324, -17.001647910307437],
        Bz = [24.308462714962772, -29.706133122053814, 28.077336739132466],
    }
    link l56 {
        F = [56.172006737943796, 66.7526315028697, -63.52126634077238],
        Fz = [72.31343426666011, 23.196664335267293, -45.01904913769265],
    }
    link l64 {
        C = [-37.821161410769776, 58.902968936552774, -3.552713678800501e-15],
        Cz = [-12.315427682079608, 75.28001222773193, 39.764934301467164],
    }
    chain driven = base - R(active q, axis = A -> Az) - l23 - R(passive, axis = B -> Bz) - platform;
    chain close = base - R(passive, axis = E -> Ez) - l56 - R(passive, axis = F -> Fz) - l64 - R(passive, axis = C -> Cz) - platform;
}

const A: f64 = 100.0;
const ALPHA: f64 = std::f64::consts::FRAC_PI_3;
const B: f64 = 70.0;
const GAMMA: f64 = 80.0 * std::f64::consts::PI / 180.0;
const THETA1_HOME: f64 = 1.0;
const DELTA: f64 = 1.0;

fn beta() -> f64 {
    (B * ALPHA.sin() / A).asin()
}

fn c() -> f64 {
    A * GAMMA.sin() / ALPHA.sin()
}

/// The frames at J2, J3 and J4 of the first loop and at J5, J6 and J4 of the second, in the
/// fused link's frame, at θ1.
fn frames(theta1: f64) -> [M4; 6] {
    use std::f64::consts::TAU;
    let j2 = dh(0.0, A, ALPHA);
    let j3 = mul(&j2, &dh(next(theta1, ALPHA, beta()), B, beta()));
    let j4 = mul(&j3, &dh(TAU - theta1, A, ALPHA));
    let psi1 = theta1 + DELTA;
    let j5 = dh(DELTA, c(), GAMMA);
    let j6 = mul(&j5, &dh(next(psi1, GAMMA, beta()), B, beta()));
    let j4_again = mul(&j6, &dh(TAU - psi1, c(), GAMMA));
    [j2, j3, j4, j5, j6, j4_again]
}

/// Where the platform (fixed in J4's frame of the first loop) carries `p` (its position at
/// home) at θ1.
fn carried(theta1: f64, p: [f64; 3]) -> [f64; 3] {
    carry(&frames(theta1)[2], &frames(THETA1_HOME)[2], p)
}

/// The driven joint's angle (J2's, the first loop's θ2) less its value at home, at θ1:
/// continuous in θ1, whole turns and all.
fn input(theta1: f64) -> f64 {
    next_unwrapped(theta1, ALPHA, beta()) - next_unwrapped(THETA1_HOME, ALPHA, beta())
}

const PLATFORM: [(&str, [f64; 3]); 3] = [
    (
        "P1",
        [-33.31891398794735, 28.981074814928164, 22.00931667085499],
    ),
    (
        "P2",
        [-37.91398546996885, 92.36026888309006, 11.428056001852198],
    ),
    (
        "P3",
        [-77.27039166866064, 31.648297727035807, 5.093243497127883],
    ),
];

#[test]
fn the_two_bennett_loops_meet_at_j4_and_the_declaration_is_the_closed_form_at_home() {
    for theta1 in [0.4, 1.0, 2.2, 3.4, 4.4] {
        let [_, _, j4, _, _, j4_again] = frames(theta1);
        // One axis: the same origin (the feet of both loops' common normals) and direction.
        for i in 0..3 {
            assert!((j4[i][3] - j4_again[i][3]).abs() < 1e-11, "θ1 {theta1}");
            assert!((j4[i][2] - j4_again[i][2]).abs() < 1e-13, "θ1 {theta1}");
        }
    }
    // The moving links' declared axis points (C on the link from J6 to J4, F on the one from
    // J5 to J6: unknowns of the model) are the closed form's frames' origins at home.
    let [_, _, j4, _, j6, _] = frames(THETA1_HOME);
    let goldberg = Goldberg::new();
    let start = goldberg.home_start().unwrap();
    for (f, name) in [(j4, "C"), (j6, "F")] {
        let want = [0, 1, 2].map(|i| f[i][3]);
        let got = point::<Goldberg, N, 1>(start.v(), name);
        assert!(max_diff(&got, &want) < 1e-9, "{name}: {got:?} vs {want:?}");
    }
    for (name, at) in PLATFORM {
        assert!(max_diff(&carried(THETA1_HOME, at), &at) < 1e-12, "{name}");
    }
}

#[test]
fn the_goldberg_linkage_has_one_freedom_by_rank_and_exact_jacobians() {
    let goldberg = Goldberg::new();
    assert_eq!(Goldberg::INPUTS, ["q"]);
    let mobility = mobility_line(Goldberg::LISTING);
    assert!(
        mobility.contains("rank of ∂F/∂(v, x) at home: M = 21 + 1 − 21 = 1")
            && mobility.contains("Grübler–Kutzbach says -1"),
        "{mobility}"
    );
    let start = goldberg.home_start().unwrap();
    check_jacobians(&goldberg, start.v(), start.x());
}

/// Continuation from home to θ1 (its input), against the closed form: `true` where the answer
/// is ok and the closed form's, `false` where it is refused (not ok), and a panic where an
/// answer labelled ok is not the closed form's.
fn solved(goldberg: &Goldberg, start: &linkage::Start<N, 1>, theta1: f64) -> bool {
    let x = [input(theta1)];
    let sol = arc_length(goldberg, start, &x, &GENERAL_MODEL).unwrap();
    if sol.status != Status::Converged {
        assert!(!sol.is_ok(), "θ1 {theta1}: {:?} labelled ok", sol.status);
        return false;
    }
    for (name, at) in PLATFORM {
        let got = point::<Goldberg, N, 1>(&sol.v, name);
        let want = carried(theta1, at);
        assert!(
            max_diff(&got, &want) < 1e-7,
            "θ1 {theta1}, {name}: {got:?} vs {want:?}"
        );
    }
    check_inverse(goldberg, &sol.v, &x, &[x[0] + 0.05], 1e-8);
    true
}

/// Driven over two whole turns, θ1 from −5.3 to 7.3 rad, each answer by continuation from
/// home: every answer is ok and the closed form's. The first loop lies flat at θ1 = 0, the
/// second at θ1 = 2π − δ, regular there as a Bennett loop is (`bennett.rs`). Finely from 1.0
/// to 1.4: the 21 equations the rank test kept at home, by their order alone, turned singular
/// at θ1 ≈ 1.158, where the mechanism is regular (its four passive joints' twists keep full
/// rank, and the closed form satisfies every equation), and continuation stopped there with a
/// fold. The rank test now follows the motion from home and keeps equations that stay regular
/// along it.
#[test]
fn goldberg_is_followed_over_its_whole_motion() {
    let goldberg = Goldberg::new();
    let start = goldberg.home_start().unwrap();
    for k in 0..=63 {
        let theta1 = -5.3 + 0.2 * k as f64;
        assert!(solved(&goldberg, &start, theta1), "θ1 {theta1}: refused");
    }
    for k in 0..=40 {
        let theta1 = 1.0 + 0.01 * k as f64;
        assert!(solved(&goldberg, &start, theta1), "θ1 {theta1}: refused");
    }
}

#[test]
fn goldberg_is_tracked_over_whole_turns_both_ways() {
    let goldberg = Goldberg::new();
    let start = goldberg.home_start().unwrap();
    tracked_over_turns(&goldberg, start, input, carried, &PLATFORM);
}
