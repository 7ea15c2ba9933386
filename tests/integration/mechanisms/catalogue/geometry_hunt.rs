//! Run-time geometry on the mechanisms of `branch_hunt`: a calibrated machine (every free
//! pivot coordinate, and the lengths its coordinates follow, moved by up to ±0.5 mm) solves as
//! well as the nominal one — the tracker and PH over random input curves, every ok answer held
//! to the *new* geometry's inverse kinematics and to fine continuation on it, none refused on
//! a stretch clear of singularities — and degenerate values (NaN and infinite values, zero
//! coordinates, coincident pivots, a collinear platform frame, a platform three and ten times
//! its size, so that home is out of reach) are typed errors from `from_geometry`,
//! `set_geometry`, `set_pivot` or `home_start`, or else every answer the solvers label ok on
//! the degenerate machine is right on it. Nothing may panic.

use super::branch_hunt::{hunt, newton, Curve, Tally};
use super::five_bar::FiveBar;
use super::linear_delta::LinearDelta;
use super::planar_rpr::PlanarRpr;
use super::prs::Prs;
use super::spherical_wrist::Wrist;
use super::GENERAL_MODEL;
use linkage::modes::{AllModes, ModesOptions};
use linkage::{GeometryError, Options};
use linkage_examples::rps::Rps3;
use linkage_examples::rss_hexapod::RssHexapod;
use linkage_tests::Rng;

/// Whether geometry value `name` is a pivot coordinate (`link.pivot.axis`).
fn coordinate(name: &str) -> bool {
    name.ends_with(".x") || name.ends_with(".y") || name.ends_with(".z")
}

/// The `link.pivot` part of a coordinate's name.
fn pivot_of(name: &str) -> &str {
    &name[..name.len() - 2]
}

/// The offset of pivot coordinate `name` in a calibration: up to ±0.5 mm, the platform's
/// heights all by one offset (a platform generated coplanar stays so), and on a planar
/// mechanism none across its plane, an axis's second point (`A1z` beside `A1`) moved with its
/// first (the axes stay normal to the plane: otherwise the over-constrained planar chains
/// cannot close at all).
fn calibration(rng: &mut Rng, names: &[&str], planar: bool) -> Vec<f64> {
    let lift = rng.uniform(-0.5, 0.5);
    let mut offsets: Vec<f64> = names
        .iter()
        .map(|n| match () {
            _ if planar && n.ends_with(".z") => 0.0,
            _ if n.starts_with("platform.") && n.ends_with(".z") => lift,
            _ => rng.uniform(-0.5, 0.5),
        })
        .collect();
    if planar {
        for (k, n) in names.iter().enumerate() {
            let p = pivot_of(n);
            if let Some(first) = p.strip_suffix('z') {
                let twin = format!("{first}{}", &n[n.len() - 2..]);
                if let Some(j) = names.iter().position(|m| *m == twin) {
                    offsets[k] = offsets[j];
                }
            }
        }
    }
    offsets
}

macro_rules! calibrated {
    ($calibrated:ident, $ty:ty, $n:expr, $options:expr, $reach:expr, $lengths:expr, $planar:expr, $seed:expr) => {
        #[test]
        fn $calibrated() {
            let mut rng = Rng::new(linkage_tests::sweep_seed($seed));
            let mut tally = Tally::default();
            let lengths: &[&str] = &$lengths;
            let names = <$ty>::GEOMETRY_NAMES;
            let nominal = <$ty>::new().home_start().unwrap();
            for case in 0..linkage_tests::sweep(2, 30) {
                let mut g = <$ty>::DEFAULT_GEOMETRY;
                let offsets = calibration(&mut rng, &names, $planar);
                for (k, name) in names.iter().enumerate() {
                    if coordinate(name) || lengths.contains(name) {
                        g[k] += offsets[k];
                    }
                }
                let sys = <$ty>::from_geometry(g).unwrap();
                // The declared home pose may be off the calibrated machine's motion (a 3-RPS
                // has three freedoms): then `home_start` is the configuration at the declared
                // home inputs. Where the model's B is ill-conditioned (the planar 3-RPR's, its
                // axes declared by points 1 mm apart: equilibrated rcond 1.6e-7 at home, just
                // above `Start::new`'s 1e-7), a calibration can push it under at the declared
                // configuration, and `home_start` says `SingularStart`; then the start is
                // refined from the nominal one by Newton, as this hunt did before `home_start`
                // followed calibrations.
                let start = sys.home_start().or_else(|e| match e {
                    linkage::SolveError::SingularStart => {
                        let v = newton(&sys, *nominal.v(), nominal.x()).unwrap();
                        linkage::Start::new(&sys, v, *nominal.x())
                    }
                    e => Err(e),
                });
                let start = start.unwrap_or_else(|e| panic!("case {case}: calibrated home: {e}"));
                // The home pose (where the closed forms place it), or the home inputs.
                let home_pose = linkage::Pose::from_euler(
                    <$ty>::HOME[0],
                    <$ty>::HOME[1],
                    <$ty>::HOME[2],
                    [<$ty>::HOME[3], <$ty>::HOME[4], <$ty>::HOME[5]],
                );
                let posed = linkage::unknowns_from_pose(&sys, &home_pose);
                assert!(
                    start.x() == nominal.x() || linkage_tests::max_diff(start.v(), &posed) < 1e-6,
                    "case {case}: neither the home pose nor the home inputs"
                );
                let mut curve = Curve::random(&mut rng, *start.x(), $reach);
                // Without `LINKAGE_STRESS`, at most 100 samples a curve (within two seconds).
                if std::env::var("LINKAGE_STRESS").is_err() {
                    curve.rate = curve.rate.min(100.0);
                }
                let at = format!("{} calibrated, case {case}", stringify!($ty));
                hunt(&sys, start, $options, &curve, &mut tally, &at);
            }
            eprintln!("{} calibrated: {tally:?}", stringify!($ty));
            assert!(tally.clean_with_inverse() && tally.ok() > 0, "{tally:?}");
        }
    };
}

calibrated!(
    five_bar_calibrated,
    FiveBar,
    3,
    Options::TIGHT,
    [2.5; 2],
    [],
    true,
    0x6E01
);
calibrated!(
    planar_rpr_calibrated,
    PlanarRpr,
    9,
    GENERAL_MODEL,
    [160.0; 3],
    [],
    true,
    0x6E02
);
calibrated!(
    prs_calibrated,
    Prs,
    15,
    GENERAL_MODEL,
    [200.0; 3],
    // `l` and `h` are read only where `hc` is declared: not run-time values.
    ["rb", "rp", "hc"],
    false,
    0x6E04
);
calibrated!(
    linear_delta_calibrated,
    LinearDelta,
    18,
    GENERAL_MODEL,
    [400.0; 3],
    ["rb", "rp", "hw", "hc"],
    false,
    0x6E05
);
calibrated!(
    rss_hexapod_calibrated,
    RssHexapod,
    18,
    GENERAL_MODEL,
    [3.0; 6],
    ["rod"],
    false,
    0x6E06
);
calibrated!(
    rps_calibrated,
    Rps3,
    9,
    Options::TIGHT,
    [120.0; 3],
    [],
    false,
    0x6E07
);

macro_rules! geometry_hunt {
    ($degenerate:ident, $ty:ty, $options:expr, $reach:expr, $seed:expr) => {
        #[test]
        fn $degenerate() {
            let names = <$ty>::GEOMETRY_NAMES;
            let nominal = <$ty>::new();
            let mut tally = Tally::default();
            let (mut refused, mut tried) = (0, 0);
            let mut rng = Rng::new(linkage_tests::sweep_seed($seed ^ 0xBAD));
            // Solves on a degenerate machine: either a typed error at home, or every answer
            // labelled ok is right on it (one short curve, PH to four of its points).
            // Returns whether the geometry was refused. Without `LINKAGE_STRESS` every sixteenth
            // accepted geometry is solved on (each is still built and started).
            let every = linkage_tests::sweep(16, 1);
            let mut seen = 0;
            let mut check = |g: [f64; <$ty>::DEFAULT_GEOMETRY.len()], what: &str| -> bool {
                let Ok(sys) = <$ty>::from_geometry(g) else {
                    return true;
                };
                let Ok(start) = sys.home_start() else {
                    return true;
                };
                seen += 1;
                if seen % every != 0 {
                    return false;
                }
                let mut curve = Curve::random(&mut rng, *start.x(), $reach);
                curve.rate = 25.0;
                let at = format!("{} with {what}", stringify!($ty));
                hunt(&sys, start, $options, &curve, &mut tally, &at);
                false
            };
            for (k, name) in names.iter().enumerate() {
                // A value declared as a formula of parameters is set through them, not by name.
                let follows = matches!(
                    nominal.clone().set_geometry(name, 1.0),
                    Err(GeometryError::FollowsParameter { .. })
                );
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let mut sys = nominal.clone();
                    let r = sys.set_geometry(name, bad);
                    let named = match r {
                        Err(GeometryError::NonFinite { name: n }) => n == *name,
                        Err(GeometryError::FollowsParameter { name: n, .. }) => follows && n == *name,
                        _ => false,
                    };
                    assert!(named, "{name} = {bad}: {r:?}");
                    assert_eq!(sys.geometry(), nominal.geometry(), "unchanged on error");
                }
                if coordinate(name) && !follows {
                    let mut g = <$ty>::DEFAULT_GEOMETRY;
                    g[k] = 0.0;
                    tried += 1;
                    refused += usize::from(check(g, &format!("{name} = 0")));
                }
            }
            // Each pivot moved onto another of the same link (set_pivot, as a user would).
            let pivots: Vec<&str> = {
                let mut p: Vec<&str> = names.iter().filter(|n| coordinate(n)).map(|n| pivot_of(n)).collect();
                p.dedup();
                p
            };
            for a in &pivots {
                for b in &pivots {
                    let (la, _) = a.split_once('.').unwrap();
                    let (lb, pivot_b) = b.split_once('.').unwrap();
                    if a == b || la != lb {
                        continue;
                    }
                    // Pivots whose coordinates follow parameters are not moved.
                    let at = |p: &str| -> Option<[f64; 3]> {
                        let g = nominal.geometry();
                        let k = ["x", "y", "z"]
                            .map(|c| names.iter().position(|n| *n == format!("{p}.{c}")));
                        Some([g[k[0]?], g[k[1]?], g[k[2]?]])
                    };
                    let (Some(pa), Some(pb)) = (at(a), at(b)) else {
                        continue;
                    };
                    let mut sys = nominal.clone();
                    match sys.set_pivot(lb, pivot_b, pa) {
                        Ok(()) => {
                            tried += 1;
                            refused += usize::from(check(*sys.geometry(), &format!("{b} on {a}")));
                        }
                        Err(e) => {
                            tried += 1;
                            refused += 1;
                            assert_eq!(sys.geometry(), nominal.geometry(), "{b} on {a}: {e}");
                        }
                    }
                    // Halfway: three pivots of a link collinear when it has three.
                    let (p, q) = (pa, pb);
                    let others: Vec<&&str> = pivots.iter().filter(|c| c.starts_with(la) && *c != a && *c != b).collect();
                    if let Some(c) = others.first() {
                        let (lc, pc) = c.split_once('.').unwrap();
                        let mut sys = nominal.clone();
                        let mid = [0, 1, 2].map(|i| 0.5 * (p[i] + q[i]));
                        match sys.set_pivot(lc, pc, mid) {
                            Ok(()) => {
                                tried += 1;
                                refused += usize::from(check(
                                    *sys.geometry(),
                                    &format!("{c} between {a} and {b}"),
                                ));
                            }
                            Err(_) => {
                                tried += 1;
                                refused += 1;
                            }
                        }
                    }
                }
            }
            // The platform three and ten times its size.
            for k in [3.0, 10.0] {
                let mut g = <$ty>::DEFAULT_GEOMETRY;
                for (i, name) in names.iter().enumerate() {
                    if name.starts_with("platform.") && coordinate(name) {
                        g[i] *= k;
                    }
                }
                tried += 1;
                refused += usize::from(check(g, &format!("the platform {k} times its size")));
            }
            eprintln!(
                "{}: {tried} degenerate geometries, {refused} refused as typed errors; on the rest {tally:?}",
                stringify!($ty)
            );
        }
    };
}

geometry_hunt!(
    five_bar_degenerate,
    FiveBar,
    Options::TIGHT,
    [2.5; 2],
    0x6E01
);
geometry_hunt!(
    planar_rpr_degenerate,
    PlanarRpr,
    GENERAL_MODEL,
    [160.0; 3],
    0x6E02
);
geometry_hunt!(wrist_degenerate, Wrist, GENERAL_MODEL, [2.5; 3], 0x6E03);
geometry_hunt!(prs_degenerate, Prs, GENERAL_MODEL, [200.0; 3], 0x6E04);
geometry_hunt!(
    linear_delta_degenerate,
    LinearDelta,
    GENERAL_MODEL,
    [400.0; 3],
    0x6E05
);
geometry_hunt!(
    rss_hexapod_degenerate,
    RssHexapod,
    GENERAL_MODEL,
    [3.0; 6],
    0x6E06
);
geometry_hunt!(rps_degenerate, Rps3, Options::TIGHT, [120.0; 3], 0x6E07);

/// The all-modes query on degenerate 6-RSS geometries: a typed error or a result, no panic.
#[test]
fn all_modes_on_degenerate_hexapods() {
    let nominal = RssHexapod::new();
    let names = RssHexapod::GEOMETRY_NAMES;
    let mut outcomes = Vec::new();
    let mut variants: Vec<(String, [f64; RssHexapod::DEFAULT_GEOMETRY.len()])> = Vec::new();
    let mut put = |what: &str, f: &dyn Fn(&mut [f64; RssHexapod::DEFAULT_GEOMETRY.len()])| {
        let mut g = *nominal.geometry();
        f(&mut g);
        variants.push((what.to_string(), g));
    };
    let k = |n: &str| names.iter().position(|m| *m == n).unwrap();
    put("A2 on A1", &|g| {
        for c in ["x", "y", "z"] {
            g[k(&format!("base.A2.{c}"))] = g[k(&format!("base.A1.{c}"))];
        }
    });
    put("G2 on G1", &|g| {
        for c in ["x", "y", "z"] {
            g[k(&format!("platform.G2.{c}"))] = g[k(&format!("platform.G1.{c}"))];
        }
    });
    put("the platform on a line", &|g| {
        for i in 1..=6 {
            g[k(&format!("platform.G{i}.y"))] = 0.0;
        }
    });
    put("the platform ten times its size", &|g| {
        for (i, n) in names.iter().enumerate() {
            if n.starts_with("platform.") {
                g[i] *= 10.0;
            }
        }
    });
    put("every crank of zero length", &|g| {
        for i in 1..=6 {
            for c in ["x", "y", "z"] {
                g[k(&format!("crank{i}.C{i}.{c}"))] = g[k(&format!("base.A{i}.{c}"))];
            }
        }
    });
    for (what, g) in variants {
        let outcome = match RssHexapod::from_geometry(g) {
            Err(e) => format!("from_geometry: {e}"),
            Ok(sys) => match AllModes::<_, 18, 6, 64>::new(sys, &ModesOptions::default()) {
                Err(e) => format!("AllModes::new: {e:?}"),
                Ok(m) => format!("{} starts", m.start_count()),
            },
        };
        outcomes.push(format!("{what}: {outcome}"));
    }
    eprintln!("{outcomes:#?}");
}
