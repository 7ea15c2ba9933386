//! A delta robot whose carriage carries a tool on one active pair: R (a turning tool), C (a
//! turning and sliding spindle), H (a screw), S (a three-axis wrist: yaw, pitch, roll) or U
//! (two axes). The delta's carriage is a link solved for, not the platform: each tool pair
//! joins two moving links. Against the closed form: the carriage where three spheres meet
//! (the parallelograms keep it level), the tool the pair's motion from there.

use super::delta::sphere_intersection;
use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

macro_rules! delta_tool {
    ($(#[$doc:meta])* $name:ident, $($tool:tt)*) => {
        linkage::mechanism! {
            $(#[$doc])*
            pub struct $name;
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
            // The tool: its tip P0 50 mm below the carriage's centre T0.
            platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, -h - 50.0]) {
                P0 = [0.0, 0.0, 0.0], P1 = [30.0, 0.0, 0.0], P2 = [0.0, 20.0, 0.0],
            }
            link carriage {
                F11 = [rp, hw, -h], F12 = [rp, -hw, -h],
                F21 = [rp * c2 - hw * s2, rp * s2 + hw * c2, -h], F22 = [rp * c2 + hw * s2, rp * s2 - hw * c2, -h],
                F31 = [rp * c2 + hw * s2, -rp * s2 + hw * c2, -h], F32 = [rp * c2 - hw * s2, -rp * s2 - hw * c2, -h],
                T0 = [0.0, 0.0, -h], T1 = [0.0, 0.0, -h - 1.0],
            }
            link arm1 { E11 = [rb + ra, hw, 0.0], E12 = [rb + ra, -hw, 0.0] }
            link arm2 {
                E21 = [(rb + ra) * c2 - hw * s2, (rb + ra) * s2 + hw * c2, 0.0],
                E22 = [(rb + ra) * c2 + hw * s2, (rb + ra) * s2 - hw * c2, 0.0],
            }
            link arm3 {
                E31 = [(rb + ra) * c2 + hw * s2, -(rb + ra) * s2 + hw * c2, 0.0],
                E32 = [(rb + ra) * c2 - hw * s2, -(rb + ra) * s2 - hw * c2, 0.0],
            }
            link rod11 { length = rod } link rod12 { length = rod }
            link rod21 { length = rod } link rod22 { length = rod }
            link rod31 { length = rod } link rod32 { length = rod }
            chain arm1a = base - R(active q1, axis = A1 -> B1) - arm1 - S(E11) - rod11 - S(F11) - carriage;
            chain arm1b = arm1 - S(E12) - rod12 - S(F12) - carriage;
            chain arm2a = base - R(active q2, axis = A2 -> B2) - arm2 - S(E21) - rod21 - S(F21) - carriage;
            chain arm2b = arm2 - S(E22) - rod22 - S(F22) - carriage;
            chain arm3a = base - R(active q3, axis = A3 -> B3) - arm3 - S(E31) - rod31 - S(F31) - carriage;
            chain arm3b = arm3 - S(E32) - rod32 - S(F32) - carriage;
            chain tool = carriage - $($tool)* - platform;
        }
    };
}

delta_tool!(
    /// A turning tool on the vertical axis T0 -> T1 (pointing down).
    DeltaR, R(active th, axis = T0 -> T1)
);
delta_tool!(
    /// A spindle that turns and slides along T0 -> T1.
    DeltaC, C(active th z, axis = T0 -> T1)
);
delta_tool!(
    /// A screw of lead 10 mm along T0 -> T1.
    DeltaH, H(active th, axis = T0 -> T1, lead = 10.0)
);
delta_tool!(
    /// A three-axis wrist at T0: yaw, pitch, roll of the tool relative to the carriage.
    DeltaS, S(T0, active yaw pitch roll)
);
delta_tool!(
    /// Two axes at T0: the first T0 -> T1 on the carriage, the second perpendicular to it
    /// and to the line from T0 to the tool's farthest pivot P1 at home.
    DeltaU, U(T0, axis = T0 -> T1, active a b)
);

type Matrix = [[f64; 3]; 3];

/// Rodrigues: the turn by `t` about the unit axis `e`.
fn turn(e: [f64; 3], t: f64) -> Matrix {
    let (c, s) = (t.cos(), t.sin());
    let k = [[0.0, -e[2], e[1]], [e[2], 0.0, -e[0]], [-e[1], e[0], 0.0]];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let id = if i == j { 1.0 } else { 0.0 };
            c * id + s * k[i][j] + (1.0 - c) * e[i] * e[j]
        })
    })
}

fn mul(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn apply(a: &Matrix, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

const DOWN: [f64; 3] = [0.0, 0.0, -1.0];

/// The tool's pose for the carriage's inputs and the tool's relative turn and slide (along
/// T0 -> T1): the carriage centre by sphere intersection (below the base), the tip 50 mm
/// below it turned with the tool.
fn tool_pose(q: [f64; 3], turn: Matrix, slide: f64) -> Option<(Matrix, [f64; 3])> {
    let [centre, _] = sphere_intersection(q)?;
    let tip = apply(&turn, [0.0, 0.0, -50.0]);
    Some((
        turn,
        std::array::from_fn(|k| centre[k] + tip[k] + slide * DOWN[k]),
    ))
}

/// Every check on one delta with a tool: the mobility, Jacobians at home and away, forward
/// kinematics from home to 60 random inputs against the closed form, the branch kept, and the
/// numerical inverse.
fn check_tool<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &linkage::Start<N, M>,
    listing: &str,
    unique: bool,
    seed: u64,
    tool_range: [f64; M],
    expected: impl Fn(&[f64; M]) -> Option<(Matrix, [f64; 3])>,
) {
    let line = mobility_line(listing);
    let want = format!("M = {N} + {M} − {N} = {M}");
    assert!(line.contains(&want), "{line}");
    assert!(linkage_tests::max_diff(start.x(), &[0.0; M]) < 1e-12);
    check_jacobians(sys, start.v(), start.x());
    check_factorization(sys, start.v(), start.x());
    let det0 = det_b(sys, start.v(), start.x());
    let mut rng = Rng::new(seed);
    for k in 0..60 {
        let x: [f64; M] = std::array::from_fn(|i| {
            let r = if i < 3 { 0.4 } else { tool_range[i] };
            rng.uniform(-r, r)
        });
        let sol = arc_length(sys, start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{}: x = {x:?}", S::NAME);
        if k == 0 {
            check_jacobians(sys, &sol.v, &x);
        }
        let pose = pose_from_unknowns(sys, &sol.v).unwrap();
        let (rotation, translation) = expected(&x).unwrap();
        for i in 0..3 {
            assert!(
                linkage_tests::max_diff(&pose.rotation[i], &rotation[i]) < 1e-9,
                "{}: x = {x:?}: {:?} vs {rotation:?}",
                S::NAME,
                pose.rotation
            );
        }
        assert!(
            linkage_tests::max_diff(&pose.translation, &translation) < 1e-8,
            "{}: x = {x:?}: {:?} vs {translation:?}",
            S::NAME,
            pose.translation
        );
        assert!(
            det_b(sys, &sol.v, &x) * det0 > 0.0,
            "{}: x = {x:?}",
            S::NAME
        );
        if unique {
            check_inverse(sys, &sol.v, &x, start.x(), 1e-8);
        } else {
            places_the_tool(sys, start, &sol.v);
        }
    }
}

/// Where the tool's pose does not fix every input (a spindle's slide trades with the carriage's
/// height; a screw's turn is the tool's yaw up to whole turns), the inverse's inputs, whichever
/// it returns, must put the tool where it is: forward kinematics from home to them.
fn places_the_tool<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &linkage::Start<N, M>,
    v: &[f64; N],
) {
    let want = pose_from_unknowns(sys, v).unwrap();
    let mut platform_only = *v;
    for q in platform_only[3 * S::POINTS.len()..].iter_mut() {
        *q = 0.0;
    }
    for given in [v, &platform_only] {
        let x = sys.inverse(given, start.x()).unwrap();
        let sol = arc_length(sys, start, &x, &GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "{}: x = {x:?}", S::NAME);
        let got = pose_from_unknowns(sys, &sol.v).unwrap();
        assert!(
            linkage_tests::max_diff(&got.translation, &want.translation) < 1e-7,
            "{}: {:?} vs {:?}",
            S::NAME,
            got.translation,
            want.translation
        );
        for i in 0..3 {
            assert!(linkage_tests::max_diff(&got.rotation[i], &want.rotation[i]) < 1e-9);
        }
    }
}

#[test]
fn delta_with_a_turning_tool() {
    let sys = DeltaR::new();
    check_tool(
        &sys,
        &sys.home_start().unwrap(),
        DeltaR::LISTING,
        true,
        81,
        [0.0, 0.0, 0.0, 1.0],
        |x| tool_pose([x[0], x[1], x[2]], turn(DOWN, x[3]), 0.0),
    );
}

#[test]
fn delta_with_a_spindle() {
    let sys = DeltaC::new();
    check_tool(
        &sys,
        &sys.home_start().unwrap(),
        DeltaC::LISTING,
        false,
        82,
        [0.0, 0.0, 0.0, 1.0, 20.0],
        |x| tool_pose([x[0], x[1], x[2]], turn(DOWN, x[3]), x[4]),
    );
}

#[test]
fn delta_with_a_screw() {
    let sys = DeltaH::new();
    check_tool(
        &sys,
        &sys.home_start().unwrap(),
        DeltaH::LISTING,
        false,
        83,
        [0.0, 0.0, 0.0, 2.0],
        |x| {
            let rise = 10.0 * x[3] / (2.0 * std::f64::consts::PI);
            tool_pose([x[0], x[1], x[2]], turn(DOWN, x[3]), rise)
        },
    );
}

#[test]
fn delta_with_a_three_axis_wrist() {
    let sys = DeltaS::new();
    assert_eq!(DeltaS::INPUTS, ["q1", "q2", "q3", "yaw", "pitch", "roll"]);
    check_tool(
        &sys,
        &sys.home_start().unwrap(),
        DeltaS::LISTING,
        true,
        84,
        [0.0, 0.0, 0.0, 1.0, 0.6, 0.6],
        |x| {
            // Rz(yaw)·Ry(pitch)·Rx(roll), as `Pose::from_euler`: the carriage does not turn,
            // so the relative turn is the tool's.
            let r = linkage::Pose::from_euler(x[3], x[4], x[5], [0.0; 3]).rotation;
            tool_pose([x[0], x[1], x[2]], r, 0.0)
        },
    );
}

#[test]
fn delta_with_two_axes() {
    let sys = DeltaU::new();
    check_tool(
        &sys,
        &sys.home_start().unwrap(),
        DeltaU::LISTING,
        true,
        85,
        [0.0, 0.0, 0.0, 0.8, 0.8],
        |x| {
            // The second axis: DOWN × (P1 − T0) at home, P1 − T0 = (30, 0, −50).
            let second = [0.0, -1.0, 0.0];
            let r = mul(&turn(DOWN, x[3]), &turn(second, x[4]));
            tool_pose([x[0], x[1], x[2]], r, 0.0)
        },
    );
}
