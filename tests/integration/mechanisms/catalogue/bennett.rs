//! The Bennett linkage (G. T. Bennett, *A new mechanism*, Engineering 76, 1903): four R pairs
//! on skew axes, a loop that Grübler–Kutzbach counts as a structure (6·3 − 4·5 = −2) but that
//! moves with one freedom where opposite links are equal in length and twist and
//! a / sin α = b / sin β. A spatial overconstrained mechanism: the model's equations are
//! dependent at every configuration, and only the rank can tell its mobility. Against the
//! closed form (Denavit–Hartenberg frames, a and α then b and β): θ3 = 2π − θ1,
//! θ4 = 2π − θ2 and tan(θ1/2) tan(θ2/2) = sin((β + α)/2) / sin((β − α)/2).

use super::{check_inverse, mobility_line, point, GENERAL_MODEL};
use linkage::{arc_length, Mechanism, Status, Tracker};
use linkage_tests::{check_jacobians, max_diff};

// a = 100, α = 60°, b = 70, β = asin(0.7 sin 60°) ≈ 37.3°, at θ1 = 1 rad: each axis's point
// is its DH frame's origin, the point 50 along its z. Link 1 (J1 to J2) and link 2 (J2 to J3)
// between; link 3, the platform, carries three points of its own besides.
linkage::mechanism! {
    /// The Bennett linkage driven at its first joint.
    pub struct Bennett;
    base {
        A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 50.0],
        D = [-70.0, 1.4210854715202004e-14, -3.552713678800501e-15],
        Dz = [-70.0, 30.31088913245536, 39.764934301467164],
    }
    platform {
        P1 = [-108.394693331362, -8.921802448165723, 6.800659164122969],
        P2 = [-61.58636628770009, -10.777081214716691, 33.36263311320991],
        P3 = [-34.192618574561905, -12.393178886958053, 9.446721787426974],
    }
    link l1 { B = [54.03023058681398, 84.14709848078965, 0.0], Bz = [90.46699305637136, 60.7513223505337, 25.000000000000007] }
    link l2 { C = [25.986733328405016, 22.30450612041436, -17.001647910307437], Cz = [38.13076755005318, 4.4045738356541655, 28.077336739132466] }
    chain driven = base - R(active q, axis = A -> Az) - l1 - R(passive, axis = B -> Bz) - l2 - R(passive, axis = C -> Cz) - platform;
    chain close = base - R(passive, axis = D -> Dz) - platform;
}

// The same linkage with each axis's second point declared 250 along its z instead of 50:
// the same motion, other equations. Both greedy orders of the rank test kept, of these, a
// square system whose det vanished about 1 rad of θ1 from home, where the linkage is regular
// (continuation stopped with a fold there); the swap search of `simplify/along.rs` finds one
// that stays regular.
linkage::mechanism! {
    /// The Bennett linkage driven at its first joint, its axes declared by points 250 apart.
    pub struct BennettFarAxes;
    base {
        A = [0.0, 0.0, 0.0], Az = [0.0, 0.0, 250.0],
        D = [-70.0, 1.4210854715202004e-14, -3.552713678800501e-15],
        Dz = [-70.0, 151.55444566227675, 198.82467150733584],
    }
    platform {
        P1 = [-108.394693331362, -8.921802448165723, 6.800659164122969],
        P2 = [-61.58636628770009, -10.777081214716691, 33.36263311320991],
        P3 = [-34.192618574561905, -12.393178886958053, 9.446721787426974],
    }
    link l1 { B = [54.03023058681398, 84.14709848078965, 0.0], Bz = [236.2140429346009, -32.831782170490115, 125.00000000000003] }
    link l2 { C = [25.986733328405016, 22.30450612041436, -17.001647910307437], Cz = [86.70690443664583, -67.19515530338661, 208.3932753368921] }
    chain driven = base - R(active q, axis = A -> Az) - l1 - R(passive, axis = B -> Bz) - l2 - R(passive, axis = C -> Cz) - platform;
    chain close = base - R(passive, axis = D -> Dz) - platform;
}

/// A rigid motion as a 4×4 homogeneous matrix.
pub(super) type M4 = [[f64; 4]; 4];

const A: f64 = 100.0;
const ALPHA: f64 = std::f64::consts::FRAC_PI_3;
const B: f64 = 70.0;
const THETA1_HOME: f64 = 1.0;

fn beta() -> f64 {
    (B * ALPHA.sin() / A).asin()
}

pub(super) fn mul(x: &M4, y: &M4) -> M4 {
    let mut z = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            z[i][j] = (0..4).map(|k| x[i][k] * y[k][j]).sum();
        }
    }
    z
}

/// Rz(θ) · Tx(a) · Rx(α).
pub(super) fn dh(theta: f64, a: f64, alpha: f64) -> M4 {
    let (st, ct) = theta.sin_cos();
    let (sa, ca) = alpha.sin_cos();
    [
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [0.0, sa, ca, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]
}

/// A Bennett loop's next angle: from a joint turned by θ, with links (a, α) then (b, β).
pub(super) fn next(theta: f64, alpha: f64, beta: f64) -> f64 {
    let k = ((beta + alpha) / 2.0).sin() / ((beta - alpha) / 2.0).sin();
    2.0 * (k / (theta / 2.0).tan()).atan()
}

/// [`next`] continuous in θ (whole turns added): near ±(π − θ), the sign that of
/// sin((β − α)/2), from which it differs by less than π (twice the angle between
/// (sin(θ/2), k cos(θ/2)) and (sin(θ/2), ±cos(θ/2)), one quadrant; k the ratio of sines in
/// [`next`]).
pub(super) fn next_unwrapped(theta: f64, alpha: f64, beta: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let wrapped = next(theta, alpha, beta);
    let near = ((beta - alpha) / 2.0).sin().signum() * (PI - theta);
    wrapped + TAU * ((near - wrapped) / TAU).round()
}

/// θ2 at θ1, on the branch of home.
fn theta2(theta1: f64) -> f64 {
    next(theta1, ALPHA, beta())
}

/// The platform's (link 3's) frame at θ1.
fn platform_frame(theta1: f64) -> M4 {
    let f2 = mul(&dh(theta1, A, ALPHA), &dh(theta2(theta1), B, beta()));
    mul(&f2, &dh(std::f64::consts::TAU - theta1, A, ALPHA))
}

/// Where a link whose frame moves from `h` to `f` carries `p` (its position at `h`): into the
/// frame at `h` (a rigid motion: its inverse is the transpose), then out of it at `f`.
pub(super) fn carry(f: &M4, h: &M4, p: [f64; 3]) -> [f64; 3] {
    let d = [0, 1, 2].map(|i| p[i] - h[i][3]);
    let local = [0, 1, 2].map(|j| (0..3).map(|i| h[i][j] * d[i]).sum::<f64>());
    [0, 1, 2].map(|i| f[i][3] + (0..3).map(|j| f[i][j] * local[j]).sum::<f64>())
}

/// Where the platform carries `p` (its position at home) at θ1.
fn carried(theta1: f64, p: [f64; 3]) -> [f64; 3] {
    carry(&platform_frame(theta1), &platform_frame(THETA1_HOME), p)
}

const PLATFORM: [(&str, [f64; 3]); 3] = [
    (
        "P1",
        [-108.394693331362, -8.921802448165723, 6.800659164122969],
    ),
    (
        "P2",
        [-61.58636628770009, -10.777081214716691, 33.36263311320991],
    ),
    (
        "P3",
        [-34.192618574561905, -12.393178886958053, 9.446721787426974],
    ),
];

#[test]
fn the_closed_form_closes_the_loop() {
    for theta1 in [0.3, 1.0, 1.7, 2.9, 4.0, 5.5] {
        let f3 = platform_frame(theta1);
        let back = mul(&f3, &dh(std::f64::consts::TAU - theta2(theta1), B, beta()));
        for i in 0..4 {
            for j in 0..4 {
                let id = if i == j { 1.0 } else { 0.0 };
                assert!((back[i][j] - id).abs() < 1e-12, "θ1 {theta1}: {back:?}");
            }
        }
    }
    // The declared platform points are the closed form's at home.
    for (name, at) in PLATFORM {
        assert!(max_diff(&carried(THETA1_HOME, at), &at) < 1e-12, "{name}");
    }
}

#[test]
fn the_bennett_linkage_has_one_freedom_by_rank_and_exact_jacobians() {
    let bennett = Bennett::new();
    assert_eq!(Bennett::INPUTS, ["q"]);
    let mobility = mobility_line(Bennett::LISTING);
    assert!(
        mobility.contains("rank of ∂F/∂(v, x) at home: M = 15 + 1 − 15 = 1")
            && mobility.contains("Grübler–Kutzbach says -2"),
        "{mobility}"
    );
    let start = bennett.home_start().unwrap();
    check_jacobians(&bennett, start.v(), start.x());
}

/// Driven over two whole turns, θ1 from −5.3 to 7.3 rad, each answer by continuation from
/// home against the closed form. The loop lies flat at θ1 = 0 and π (θ2 = π, 0): regular
/// there all the same (tan(θ1/2) tan(θ2/2) is smooth through them, and the three passive
/// joints' twists keep full rank all round), so continuation goes through.
#[test]
fn bennett_forward_kinematics_against_the_closed_form() {
    let bennett = Bennett::new();
    against_the_closed_form(&bennett, &bennett.home_start().unwrap());
}

#[test]
fn bennett_with_its_axes_declared_far_out_against_the_closed_form() {
    let far = BennettFarAxes::new();
    assert!(
        mobility_line(BennettFarAxes::LISTING).contains("M = 15 + 1 − 15 = 1"),
        "{}",
        BennettFarAxes::LISTING
    );
    against_the_closed_form(&far, &far.home_start().unwrap());
}

fn against_the_closed_form<S: Mechanism<15, 1>>(bennett: &S, start: &linkage::Start<15, 1>) {
    for k in 0..=63 {
        let theta1 = -5.3 + 0.2 * k as f64;
        let x = [theta1 - THETA1_HOME];
        let sol = arc_length(bennett, start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "θ1 {theta1}");
        for (name, at) in PLATFORM {
            let got = point::<S, 15, 1>(&sol.v, name);
            let want = carried(theta1, at);
            assert!(
                max_diff(&got, &want) < 1e-7,
                "θ1 {theta1}, {name}: {got:?} vs {want:?}"
            );
        }
        check_inverse(bennett, &sol.v, &x, &[x[0] + 0.05], 1e-8);
    }
}

/// θ1 at time `t` (s) of a trajectory that turns a loop's first joint back and forth over
/// about three turns either way from home, at up to 13 rad/s.
pub(super) fn turning(t: f64) -> f64 {
    THETA1_HOME + 7.0 * (0.9 * t).sin() + 3.0 * (2.3 * t).sin()
}

/// The tracker from `start` at 1 kHz for 8 s along [`turning`], the input at each sample
/// `input(θ1)`:
/// every sample answered, its platform points (`platform`, at home) where `carried` puts
/// them at θ1, to 1e-7.
pub(super) fn tracked_over_turns<S: Mechanism<N, 1> + Clone, const N: usize>(
    sys: &S,
    start: linkage::Start<N, 1>,
    input: impl Fn(f64) -> f64,
    carried: impl Fn(f64, [f64; 3]) -> [f64; 3],
    platform: &[(&str, [f64; 3])],
) {
    let mut tracker = Tracker::new(sys.clone(), start, GENERAL_MODEL);
    for k in 0..=8000 {
        let theta1 = turning(k as f64 * 1e-3);
        let sample = tracker
            .update(&[input(theta1)])
            .unwrap_or_else(|e| panic!("sample {k}, θ1 {theta1}: {e:?}"));
        for (name, at) in platform {
            let got = point::<S, N, 1>(&sample.v, name);
            let want = carried(theta1, *at);
            assert!(
                max_diff(&got, &want) < 1e-7,
                "sample {k}, θ1 {theta1}, {name}: {got:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn bennett_is_tracked_over_whole_turns_both_ways() {
    let bennett = Bennett::new();
    tracked_over_turns(
        &bennett,
        bennett.home_start().unwrap(),
        |theta1| theta1 - THETA1_HOME,
        carried,
        &PLATFORM,
    );
}
