//! A translational 3-PUU (Li & Xu, *Kinematic analysis of a 3-PUU parallel mechanism*, 2006;
//! Tsai & Joshi's 3-PUU family): three sliders on rails inclined 60° inward, each carrying a
//! rod between two U joints whose outer axes (on the slider and on the platform) are parallel
//! and tangent, so the platform only translates. The U joints' axes are declared by points
//! 100 mm apart, at the mechanism's scale. Against the closed-form inverse (each slide puts its
//! rod's far end on a sphere about the platform joint), and tracked with a proof of every
//! sample.

use super::all_modes::is_identity;
use super::{check_inverse, mobility_line, GENERAL_MODEL};
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage::{arc_length, pose_from_unknowns, Mechanism, Pose, StepProof, Tracker};
use linkage_tests::vec3::{add, cross, dot, scaled, sub};
use linkage_tests::{check_jacobians, max_diff, Rng};

linkage::mechanism! {
    /// 3-PUU translational, rails inclined 60° inward.
    pub struct Puu;
    params { rb = 150.0, rp = 50.0, ce = cos(pi / 3.0), se = sin(pi / 3.0), h = 250.0, w = 100.0 }
    base {
        A1 = [rb * cos(0.0 * pi / 180.0), rb * sin(0.0 * pi / 180.0), 0.0], E1 = [(rb - ce) * cos(0.0 * pi / 180.0), (rb - ce) * sin(0.0 * pi / 180.0), se],
        A2 = [rb * cos(120.0 * pi / 180.0), rb * sin(120.0 * pi / 180.0), 0.0], E2 = [(rb - ce) * cos(120.0 * pi / 180.0), (rb - ce) * sin(120.0 * pi / 180.0), se],
        A3 = [rb * cos(240.0 * pi / 180.0), rb * sin(240.0 * pi / 180.0), 0.0], E3 = [(rb - ce) * cos(240.0 * pi / 180.0), (rb - ce) * sin(240.0 * pi / 180.0), se],
    }
    platform(home = [0.0, 0.0, 0.0, 0.0, 0.0, h]) {
        G1 = [rp * cos(0.0 * pi / 180.0), rp * sin(0.0 * pi / 180.0), 0.0], T1 = [rp * cos(0.0 * pi / 180.0) - w * sin(0.0 * pi / 180.0), rp * sin(0.0 * pi / 180.0) + w * cos(0.0 * pi / 180.0), 0.0],
        G2 = [rp * cos(120.0 * pi / 180.0), rp * sin(120.0 * pi / 180.0), 0.0], T2 = [rp * cos(120.0 * pi / 180.0) - w * sin(120.0 * pi / 180.0), rp * sin(120.0 * pi / 180.0) + w * cos(120.0 * pi / 180.0), 0.0],
        G3 = [rp * cos(240.0 * pi / 180.0), rp * sin(240.0 * pi / 180.0), 0.0], T3 = [rp * cos(240.0 * pi / 180.0) - w * sin(240.0 * pi / 180.0), rp * sin(240.0 * pi / 180.0) + w * cos(240.0 * pi / 180.0), 0.0],
    }
    link slider1 { C1 = [(rb - 100.0 * ce) * cos(0.0 * pi / 180.0), (rb - 100.0 * ce) * sin(0.0 * pi / 180.0), 100.0 * se], D1 = [(rb - 100.0 * ce) * cos(0.0 * pi / 180.0) - w * sin(0.0 * pi / 180.0), (rb - 100.0 * ce) * sin(0.0 * pi / 180.0) + w * cos(0.0 * pi / 180.0), 100.0 * se] }
    link slider2 { C2 = [(rb - 100.0 * ce) * cos(120.0 * pi / 180.0), (rb - 100.0 * ce) * sin(120.0 * pi / 180.0), 100.0 * se], D2 = [(rb - 100.0 * ce) * cos(120.0 * pi / 180.0) - w * sin(120.0 * pi / 180.0), (rb - 100.0 * ce) * sin(120.0 * pi / 180.0) + w * cos(120.0 * pi / 180.0), 100.0 * se] }
    link slider3 { C3 = [(rb - 100.0 * ce) * cos(240.0 * pi / 180.0), (rb - 100.0 * ce) * sin(240.0 * pi / 180.0), 100.0 * se], D3 = [(rb - 100.0 * ce) * cos(240.0 * pi / 180.0) - w * sin(240.0 * pi / 180.0), (rb - 100.0 * ce) * sin(240.0 * pi / 180.0) + w * cos(240.0 * pi / 180.0), 100.0 * se] }
    chain leg1 = base - P(active s1, axis = A1 -> E1, offset = 100.0) - slider1 - U(C1, axis = C1 -> D1) - U(G1, axis = G1 -> T1) - platform;
    chain leg2 = base - P(active s2, axis = A2 -> E2, offset = 100.0) - slider2 - U(C2, axis = C2 -> D2) - U(G2, axis = G2 -> T2) - platform;
    chain leg3 = base - P(active s3, axis = A3 -> E3, offset = 100.0) - slider3 - U(C3, axis = C3 -> D3) - U(G3, axis = G3 -> T3) - platform;
}

const H: f64 = 250.0;

/// Joint `i`'s direction from the centre, in the base plane.
fn radial(i: usize) -> [f64; 3] {
    let p = (120.0 * i as f64).to_radians();
    [p.cos(), p.sin(), 0.0]
}

/// Rail `i`'s unit direction: inward and up at 60°.
fn rail(i: usize) -> [f64; 3] {
    let a = std::f64::consts::PI / 3.0;
    add(scaled(radial(i), -a.cos()), [0.0, 0.0, a.sin()])
}

/// The rods' common length: from the slider 100 mm up its rail to the platform joint at home.
fn rod() -> f64 {
    let c = add(scaled(radial(0), 150.0), scaled(rail(0), 100.0));
    let d = sub(add(scaled(radial(0), 50.0), [0.0, 0.0, H]), c);
    dot(d, d).sqrt()
}

/// The slides for the platform translated to `t`: each the root, nearer the rail's start, of
/// |A + s e − G(t)| = rod (the root home is on). `None` out of reach.
fn slides(t: [f64; 3]) -> Option<[f64; 3]> {
    let mut s = [0.0; 3];
    for (i, s) in s.iter_mut().enumerate() {
        let d = sub(add(scaled(radial(i), 50.0), t), scaled(radial(i), 150.0));
        let ed = dot(rail(i), d);
        let q = ed * ed - dot(d, d) + rod() * rod();
        if !(q >= 0.0) {
            return None;
        }
        *s = ed - q.sqrt();
    }
    Some(s)
}

/// The platform at `v`: unturned (to 1e-9) and translated to the returned point.
fn translation(sys: &Puu, v: &[f64; 36]) -> [f64; 3] {
    let pose = pose_from_unknowns(sys, v).unwrap();
    let turned = Pose::from_euler(0.0, 0.0, 0.0, [0.0; 3]);
    for r in 0..3 {
        assert!(
            max_diff(&pose.rotation[r], &turned.rotation[r]) < 1e-9,
            "{:?}",
            pose.euler()
        );
    }
    pose.translation
}

#[test]
fn a_3_puu_translates_its_platform() {
    let sys = Puu::new();
    assert!(
        mobility_line(Puu::LISTING).contains("= 3 "),
        "{}",
        mobility_line(Puu::LISTING)
    );
    let start = sys.home_start().unwrap();
    assert!(max_diff(start.x(), &slides([0.0, 0.0, H]).unwrap()) < 1e-9);
    check_jacobians(&sys, start.v(), start.x());
    let mut rng = Rng::new(2006);
    for case in 0..30 {
        let t = random_translation(&mut rng);
        let x = slides(t).unwrap();
        let sol = arc_length(&sys, &start, &x, &GENERAL_MODEL).unwrap();
        assert!(sol.is_ok(), "case {case}: {:?}", sol.status);
        let got = translation(&sys, &sol.v);
        assert!(max_diff(&got, &t) < 1e-6, "case {case}: {got:?} vs {t:?}");
        if case < 3 {
            check_jacobians(&sys, &sol.v, &x);
            check_inverse(&sys, &sol.v, &x, start.x(), 1e-7);
        }
    }
}

/// The certified tracker at 1 kHz along a smooth path of about 0.1 mm a sample: every sample
/// proven and the platform where it was asked to be. With the U joints' second-axis points one
/// unit (1 mm) from their centres, as the model placed them before, the Krawczyk radius at home
/// was 5.4e-3 mm and every sample was refused (`NotContracting`).
#[test]
fn a_3_puu_is_tracked_with_a_proof_of_every_sample() {
    let sys = Puu::new();
    let start = sys.home_start().unwrap();
    let mut tracker = Tracker::new(sys.clone(), start, GENERAL_MODEL).certified();
    for k in 1..=100 {
        let t = k as f64 * 5e-3;
        let want = [20.0 * (1.1 * t).sin(), 10.0 * t, H + 20.0 * (1.7 * t).sin()];
        let sample = tracker
            .update(&slides(want).unwrap())
            .unwrap_or_else(|e| panic!("sample {k}: {e:?}"));
        assert!(matches!(sample.proof, Some(StepProof::Proven { .. })));
        let got = translation(&sys, &sample.v);
        assert!(
            max_diff(&got, &want) < 1e-6,
            "sample {k}: {got:?} vs {want:?}"
        );
    }
}

/// The sphere about which leg `i` holds the platform's translation at slides `s`: its centre
/// (the slider's joint less the platform joint's offset); the radius is [`rod`].
fn sphere_centre(i: usize, s: f64) -> [f64; 3] {
    sub(
        add(scaled(radial(i), 150.0), scaled(rail(i), s)),
        scaled(radial(i), 50.0),
    )
}

/// The other translation at the same slides: the three spheres meet at `t` and at its mirror
/// image through the plane of their centres.
fn mirror(t: [f64; 3], s: &[f64; 3]) -> [f64; 3] {
    let c: [[f64; 3]; 3] = std::array::from_fn(|i| sphere_centre(i, s[i]));
    let (u, w) = (sub(c[1], c[0]), sub(c[2], c[0]));
    let n = cross(u, w);
    let n = scaled(n, 1.0 / dot(n, n).sqrt());
    sub(t, scaled(n, 2.0 * dot(sub(t, c[0]), n)))
}

/// Every assembly mode of the 3-PUU: 672 complex roots, in octets (each leg's rod spun half a
/// turn about its own axis: the generated candidate symmetries, all three kept), found by
/// every seed tried (2015, 7, 99, 12345) under the default stopping rule, in 4.5-5.7 s each.
/// The count and its queries run with `LINKAGE_STRESS` set, as `.ci/run` does; a catalogue
/// run without it checks the symmetries only (monodromy stopped at 64 roots, eight octets).
/// At the slides of three random translations: every path ends at a root; both translations
/// the three spheres allow (the platform unturned) are among the real roots, each with the 8
/// spins of its rods; every real root has a tiny residual and gives its slides back (128 real
/// roots at each of the three: the other real ones turn the platform). Before the U joints'
/// second-axis points were placed at the leg's length (5c4e42b), ten loops took 75 s and found
/// 408 roots, 913 of their paths failing (six loops lost every path).
/// A translation of the platform within the workspace the tests sample: ±30 mm across, 40 mm
/// below and 30 above home.
fn random_translation(rng: &mut Rng) -> [f64; 3] {
    [
        rng.uniform(-30.0, 30.0),
        rng.uniform(-30.0, 30.0),
        H + rng.uniform(-40.0, 30.0),
    ]
}

#[test]
fn a_3_puu_has_672_assembly_modes_in_octets() {
    // A solver of capacity 1024 for 36 unknowns is about 1.2 MB, moved by value.
    linkage_tests::on_big_stack(256, puu_modes);
}

fn puu_modes() {
    let sys = Puu::new();
    if std::env::var_os("LINKAGE_STRESS").is_none() {
        let few = ModesOptions {
            expected: Some(64),
            ..ModesOptions::default()
        };
        let modes = Box::new(AllModes::<_, 36, 3, 1024>::new(sys, &few).unwrap());
        assert_eq!(modes.report().symmetries, 3, "{:?}", modes.report());
        assert_eq!(modes.start_count(), 64, "{:?}", modes.report());
        return;
    }
    let modes =
        Box::new(AllModes::<_, 36, 3, 1024>::new(sys.clone(), &ModesOptions::default()).unwrap());
    assert_eq!(modes.report().symmetries, 3, "{:?}", modes.report());
    assert_eq!(modes.start_count(), 672, "{:?}", modes.report());
    let mut roots = Box::new(Roots::<36, 1024>::new());
    let mut rng = Rng::new(672);
    let mut real = 0;
    for _ in 0..3 {
        let t = random_translation(&mut rng);
        let s = slides(t).unwrap();
        modes.solve(&s, &mut roots).unwrap();
        assert!(
            roots.is_complete(),
            "at {s:?}: not every path ended at a root"
        );
        for centre in [t, mirror(t, &s)] {
            let at = roots
                .real()
                .iter()
                .filter(|r| {
                    let p = pose_from_unknowns(&sys, &r.v).unwrap();
                    max_diff(&p.translation, &centre) < 1e-7 && is_identity(&p.rotation, 1e-9)
                })
                .count();
            assert_eq!(at, 8, "at {s:?}: spins of the translation to {centre:?}");
        }
        for r in roots.real() {
            assert!(r.residual < 1e-7, "at {s:?}: residual {}", r.residual);
            let back = sys.inverse(&r.v, &s).unwrap();
            assert!(max_diff(&back, &s) < 1e-7, "{back:?} vs {s:?}");
        }
        real += roots.real().len();
    }
    println!(
        "3-PUU: 672 complex roots ({:?}); 3 inputs: {real} real roots, both translations with 8 spins each among them",
        modes.report()
    );
}
