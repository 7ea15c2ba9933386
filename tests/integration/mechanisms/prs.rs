//! A 3-PRS machine-tool head: sliders driven along vertical rails, each carrying a leg on a
//! passive revolute pair tangent to the base circle, joined to the platform by a spherical pair.
//! Declared twice: the platform above its sliders and below them (two assembly modes).

use super::{check_inverse, mobility_line};
use linkage::{arc_length, det_b, pose_from_unknowns, Mechanism, Options, Pose, Status};
use linkage_tests::{check_factorization, check_jacobians, Rng};

macro_rules! prs {
    ($name:ident, $z:expr) => {
        linkage::mechanism! {
            /// A 3-PRS: rails at radius 100 mm, legs of 150 mm, a platform of radius 50 mm;
            /// each input is its slider's height (the slide from home plus the home height).
            pub struct $name;
            params {
                rb = 100.0, rp = 50.0, l = 150.0, h = 250.0,
                hc = h - sqrt(l * l - (rb - rp) * (rb - rp)),
                c2 = cos(2.0 * pi / 3.0), s2 = sin(2.0 * pi / 3.0),
            }
            base {
                A1 = [rb, 0.0, 0.0], B1 = [rb, 0.0, 1.0],
                A2 = [rb * c2, rb * s2, 0.0], B2 = [rb * c2, rb * s2, 1.0],
                A3 = [rb * c2, -rb * s2, 0.0], B3 = [rb * c2, -rb * s2, 1.0],
            }
            platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, $z]) {
                G1 = [rp, 0.0, 0.0], G2 = [rp * c2, rp * s2, 0.0], G3 = [rp * c2, -rp * s2, 0.0],
            }
            link slider1 { C1 = [rb, 0.0, hc], D1 = [rb, 1.0, hc] }
            link slider2 { C2 = [rb * c2, rb * s2, hc], D2 = [rb * c2 - s2, rb * s2 + c2, hc] }
            link slider3 { C3 = [rb * c2, -rb * s2, hc], D3 = [rb * c2 + s2, -rb * s2 + c2, hc] }
            link leg1 { } link leg2 { } link leg3 { }
            chain c1 = base - P(active s1, axis = A1 -> B1, offset = hc) - slider1 - R(passive, axis = C1 -> D1) - leg1 - S(G1) - platform;
            chain c2 = base - P(active s2, axis = A2 -> B2, offset = hc) - slider2 - R(passive, axis = C2 -> D2) - leg2 - S(G2) - platform;
            chain c3 = base - P(active s3, axis = A3 -> B3, offset = hc) - slider3 - R(passive, axis = C3 -> D3) - leg3 - S(G3) - platform;
        }
    };
}

prs!(Prs, 250.0);
// The sliders' plane is at hc = 250 − √(150² − 50²): the platform mirrored through it.
prs!(PrsBelow, 2.0 * (250.0 - 141.42135623730951) - 250.0);

const RB: f64 = 100.0;
const RP: f64 = 50.0;
const LEG: f64 = 150.0;

fn rails() -> [[f64; 2]; 3] {
    std::array::from_fn(|i| {
        let phi = 2.0 * std::f64::consts::PI * i as f64 / 3.0;
        [phi.cos(), phi.sin()]
    })
}

/// Inverse kinematics in closed form: each slider's height, below (`below = true`) or above
/// its platform pivot; and how far each pivot is from its leg's plane (zero when the pose is
/// one the mechanism can take).
fn prs_inverse(pose: &Pose, below: bool) -> ([f64; 3], [f64; 3]) {
    let r = rails();
    let mut heights = [0.0; 3];
    let mut off_plane = [0.0; 3];
    for i in 0..3 {
        let g = pose.apply([RP * r[i][0], RP * r[i][1], 0.0]);
        let (dx, dy) = (g[0] - RB * r[i][0], g[1] - RB * r[i][1]);
        let rise = (LEG * LEG - dx * dx - dy * dy).sqrt();
        heights[i] = if below { g[2] - rise } else { g[2] + rise };
        // The leg turns in the plane through the rail and the base's axis.
        off_plane[i] = -r[i][1] * g[0] + r[i][0] * g[1];
    }
    (heights, off_plane)
}

#[test]
fn prs_models_with_three_freedoms_and_exact_jacobians() {
    let prs = Prs::new();
    assert_eq!(Prs::INPUTS, ["s1", "s2", "s3"]);
    assert_eq!(
        mobility_line(Prs::LISTING),
        "mobility: rank of ∂F/∂(v, x) at home: M = 9 + 3 − 9 = 3 (Grübler–Kutzbach says 3)"
    );
    let start = prs.home_start().unwrap();
    check_jacobians(&prs, &Prs::HOME_V, &Prs::HOME_INPUTS);
    check_factorization(&prs, &Prs::HOME_V, &Prs::HOME_INPUTS);
    // The inputs read the sliders' heights.
    let hc = 250.0 - (LEG * LEG - (RB - RP) * (RB - RP)).sqrt();
    assert!(linkage_tests::max_diff(&Prs::HOME_INPUTS, &[hc; 3]) < 1e-12);
    let _ = start;
}

#[test]
fn prs_forward_kinematics_against_inverse() {
    let prs = Prs::new();
    let start = prs.home_start().unwrap();
    let det0 = det_b(&prs, &Prs::HOME_V, &Prs::HOME_INPUTS);
    let mut rng = Rng::new(41);
    let mut first = true;
    for _ in 0..60 {
        let s = Prs::HOME_INPUTS.map(|h| h + rng.uniform(-20.0, 20.0));
        let sol = arc_length(&prs, &start, &s, &Options::TIGHT).unwrap();
        assert_eq!(sol.status, Status::Converged, "s = {s:?}");
        if first {
            // The Jacobians away from home too.
            check_jacobians(&prs, &sol.v, &s);
            first = false;
        }
        let pose = pose_from_unknowns(&prs, &sol.v).unwrap();
        let (heights, off_plane) = prs_inverse(&pose, true);
        assert!(
            linkage_tests::max_diff(&heights, &s) < 1e-8,
            "{heights:?} vs {s:?}"
        );
        assert!(off_plane.iter().all(|d| d.abs() < 1e-9), "{off_plane:?}");
        assert!(det_b(&prs, &sol.v, &s) * det0 > 0.0);
        check_inverse(&prs, &sol.v, &s, &Prs::HOME_INPUTS, 1e-8);
    }
}

#[test]
fn prs_assembly_modes_above_and_below_the_sliders() {
    let (above, below) = (Prs::new(), PrsBelow::new());
    assert_eq!(Prs::DEFAULT_GEOMETRY, PrsBelow::DEFAULT_GEOMETRY);
    assert!(linkage_tests::max_diff(&Prs::HOME_INPUTS, &PrsBelow::HOME_INPUTS) < 1e-12);
    let (sa, sb) = (above.home_start().unwrap(), below.home_start().unwrap());
    let mut rng = Rng::new(42);
    for _ in 0..20 {
        let s = Prs::HOME_INPUTS.map(|h| h + rng.uniform(-15.0, 15.0));
        let a = arc_length(&above, &sa, &s, &Options::TIGHT).unwrap();
        let b = arc_length(&below, &sb, &s, &Options::TIGHT).unwrap();
        assert_eq!((a.status, b.status), (Status::Converged, Status::Converged));
        let (pa, pb) = (
            pose_from_unknowns(&above, &a.v).unwrap(),
            pose_from_unknowns(&below, &b.v).unwrap(),
        );
        // Both are solutions for the same inputs, with the platform on either side.
        assert!(linkage_tests::max_diff(&prs_inverse(&pa, true).0, &s) < 1e-8);
        assert!(linkage_tests::max_diff(&prs_inverse(&pb, false).0, &s) < 1e-8);
        assert!(pa.translation[2] - pb.translation[2] > 100.0);
    }
}
