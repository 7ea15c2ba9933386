//! Serial arms of four and five freedoms, one chain each: a SCARA (R, R, a vertical P, R) and
//! the same SCARA with a wrist that tilts the tool (R). Against the product of exponentials:
//! each joint's motion about (or along) its axis as declared at home, composed from the tool
//! back to the base — what the pairs' conventions promise (the link after a pair moves
//! relative to the link before it, from home). Declared in `examples/serial-arms`, which the
//! inverse's benchmark and the no-panic proof share.

use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Pose, Status};
use linkage_tests::{check_factorization, check_jacobians, max_diff, Rng};

pub use linkage_serial_arms::{Scara, ScaraWrist};

/// A turn by `angle` about the line through `centre` along `axis` ('z' or 'x').
fn turn(p: [f64; 3], centre: [f64; 3], axis: char, angle: f64) -> [f64; 3] {
    let r = match axis {
        'z' => Pose::from_euler(angle, 0.0, 0.0, [0.0; 3]),
        _ => Pose::from_euler(0.0, 0.0, angle, [0.0; 3]),
    };
    let d = r.apply([p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]]);
    [centre[0] + d[0], centre[1] + d[1], centre[2] + d[2]]
}

/// Where the joint values `x` (q1, q2, d, q4 and, with a wrist, q5) take the tool's point `p`
/// (declared at home).
fn product_of_exponentials(x: &[f64], p: [f64; 3]) -> [f64; 3] {
    let t = [350.0, 0.0, -50.0];
    let mut p = p;
    if let Some(&q5) = x.get(4) {
        p = turn(p, t, 'x', q5);
    }
    p = turn(p, t, 'z', x[3]);
    p[2] += x[2];
    p = turn(p, [200.0, 0.0, 0.0], 'z', x[1]);
    turn(p, [0.0; 3], 'z', x[0])
}

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

#[test]
fn serial_arms_have_four_and_five_freedoms_by_rank_and_exact_jacobians() {
    for (listing, m) in [(Scara::LISTING, 4), (ScaraWrist::LISTING, 5)] {
        let line = super::mobility_line(listing);
        assert!(line.contains("rank of ∂F/∂(v, x) at home"), "{line}");
        assert!(
            line.contains(&format!(" = {m} (Grübler–Kutzbach")),
            "{line}"
        );
    }
    let (s4, s5) = (Scara::new(), ScaraWrist::new());
    let a = s4.home_start().unwrap();
    check_jacobians(&s4, a.v(), a.x());
    check_factorization(&s4, a.v(), a.x());
    let b = s5.home_start().unwrap();
    check_jacobians(&s5, b.v(), b.x());
    check_factorization(&s5, b.v(), b.x());
    let x = [0.4, -1.1, 30.0, 0.7, -0.5];
    let sol = arc_length(&s5, &b, &x, &super::GENERAL_MODEL).unwrap();
    assert_eq!(sol.status, Status::Converged);
    check_jacobians(&s5, &sol.v, &x);
}

#[test]
fn scara_against_the_product_of_exponentials() {
    let s4 = Scara::new();
    let start = s4.home_start().unwrap();
    let tool = [
        [350.0, 0.0, -50.0],
        [360.0, 0.0, -50.0],
        [350.0, 0.0, -49.0],
    ];
    let mut rng = Rng::new(45);
    for _ in 0..60 {
        let x = [
            rng.uniform(-3.0, 3.0),
            rng.uniform(-2.5, 2.5),
            rng.uniform(-100.0, 100.0),
            rng.uniform(-3.0, 3.0),
        ];
        let sol = arc_length(&s4, &start, &x, &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "x = {x:?}");
        let pose = pose_from_unknowns(&s4, &sol.v).unwrap();
        for p in tool {
            let (at, truth) = (pose.apply(p), product_of_exponentials(&x, p));
            assert!(
                max_diff(&at, &truth) < 1e-7,
                "x = {x:?}: {at:?} vs {truth:?}"
            );
        }
        let [yaw, pitch, roll] = pose.euler();
        assert!(
            wrap(yaw - x[0] - x[1] - x[3]).abs() < 1e-9 && pitch.abs() < 1e-9 && roll.abs() < 1e-9
        );
        assert!(det_b(&s4, &sol.v, &x) * start.det() > 0.0);
        // The unknowns hold no point of the upper arm off the quill's axis (the elbow is
        // placed by q1 and q2 in closed form), so they fix the arm only up to its mirror image
        // in the line from the shoulder to the quill: the inverse returns either elbow, the
        // slide exactly, and puts the tool back.
        let back = s4.inverse(&sol.v, &Scara::HOME_INPUTS).unwrap();
        let same = (0..4).all(|j| wrap(back[j] - x[j]).abs() < 1e-7);
        let mirrored = wrap(back[1] + x[1]).abs() < 1e-7;
        assert!(same || mirrored, "x = {x:?}: inverse {back:?}");
        assert!((back[2] - x[2]).abs() < 1e-7, "x = {x:?}: inverse {back:?}");
        for p in tool {
            let (at, again) = (pose.apply(p), product_of_exponentials(&back, p));
            assert!(
                max_diff(&at, &again) < 1e-6,
                "x = {x:?}: inverse {back:?} puts {p:?} at {again:?}, not {at:?}"
            );
        }
    }
}

#[test]
fn scara_with_a_wrist_against_the_product_of_exponentials() {
    let s5 = ScaraWrist::new();
    let start = s5.home_start().unwrap();
    let tool = [
        [350.0, 0.0, -50.0],
        [360.0, 0.0, -50.0],
        [350.0, 30.0, -80.0],
    ];
    let mut rng = Rng::new(46);
    // Inverses not found, from the unknowns and from the platform alone.
    let mut unreached = [0, 0];
    let mut worst = 0.0f64;
    for _ in 0..60 {
        let x = [
            rng.uniform(-3.0, 3.0),
            rng.uniform(-2.5, 2.5),
            rng.uniform(-100.0, 100.0),
            rng.uniform(-3.0, 3.0),
            rng.uniform(-1.4, 1.4),
        ];
        let sol = arc_length(&s5, &start, &x, &super::GENERAL_MODEL).unwrap();
        assert_eq!(sol.status, Status::Converged, "x = {x:?}");
        let pose = pose_from_unknowns(&s5, &sol.v).unwrap();
        for p in tool {
            let (at, truth) = (pose.apply(p), product_of_exponentials(&x, p));
            assert!(
                max_diff(&at, &truth) < 1e-7,
                "x = {x:?}: {at:?} vs {truth:?}"
            );
        }
        assert!(det_b(&s5, &sol.v, &x) * start.det() > 0.0);
        // From the solved unknowns, and from the platform's points alone (the elbow may then
        // come back mirrored): whatever the inverse returns must put the tool where it is.
        let mut platform_only = sol.v;
        for q in platform_only[3 * ScaraWrist::POINTS.len()..].iter_mut() {
            *q = 0.0;
        }
        for (from, v) in [("unknowns", &sol.v), ("platform", &platform_only)] {
            let Ok(back) = s5.inverse(v, &ScaraWrist::HOME_INPUTS) else {
                unreached[usize::from(from == "platform")] += 1;
                continue;
            };
            for p in tool {
                let (at, again) = (pose.apply(p), product_of_exponentials(&back, p));
                // The numerical inverse leaves each equation within 1e-9 of the scale of
                // holding (a few 1e-7 mm at 350 mm).
                worst = worst.max(max_diff(&at, &again));
                assert!(
                    max_diff(&at, &again) < 2e-6,
                    "x = {x:?}: inverse from the {from} {back:?} puts {p:?} at {again:?}, not {at:?}"
                );
            }
        }
    }
    // From the solved unknowns every inverse is found; from the platform's points alone the
    // numerical inverse does not find every configuration (five inputs, the links' points
    // guessed): counted, not hidden. Measured [0, 0] (before the inputs were fitted first and
    // the weights fixed, [0, 1]).
    eprintln!("scara with a wrist: inverse unreached at {unreached:?} of 60 (from the unknowns, from the platform); tool off by up to {worst:.1e} mm");
    assert!(
        unreached[0] == 0 && unreached[1] <= 3,
        "{unreached:?} of 60"
    );
}
