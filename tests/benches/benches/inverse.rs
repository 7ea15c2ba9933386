//! criterion benches of the numerical inverse kinematics (Levenberg–Marquardt, for the serial
//! arms with no closed form) on the arms the integration tests sweep: a pan-tilt head, a SCARA
//! and a SCARA with a wrist, each near home, far from it, and near a singular pose (the tilt a
//! hair from zero, the arm stretched). The wrist also from its platform's points alone, as its
//! test against the product of exponentials asks. `cargo bench -p linkage-benches --bench inverse`.

use criterion::{criterion_group, criterion_main, Criterion};
use linkage::{arc_length, Mechanism, Options, Start, Status};
use std::hint::black_box;

use linkage_serial_arms::{PanTilt, Scara, ScaraWrist};

/// The unknowns at `x`, by continuation from home (the tests' tolerance).
fn forward<S: Mechanism<N, M>, const N: usize, const M: usize>(
    sys: &S,
    start: &Start<N, M>,
    x: &[f64; M],
) -> [f64; N] {
    let options = Options {
        tolerance: 1e-8,
        ..Options::TIGHT
    };
    let sol = arc_length(sys, start, x, &options).expect("a forward solve");
    assert_eq!(sol.status, Status::Converged, "{}: x = {x:?}", S::NAME);
    sol.v
}

/// One bench per pose: `inverse` from the home inputs. Whether it answered is printed once
/// (a refusal is timed too, and is usually the slowest: every start is tried).
fn bench_arm<S: Mechanism<N, M>, const N: usize, const M: usize>(
    c: &mut Criterion,
    sys: &S,
    start: &Start<N, M>,
    poses: &[(&str, [f64; M])],
    platform_only: bool,
) {
    let home = *start.x();
    let mut g = c.benchmark_group(format!("inverse/{}", S::NAME));
    g.sample_size(10);
    for (name, x) in poses {
        let mut v = forward(sys, start, x);
        let name = if platform_only {
            v[3 * S::POINTS.len()..].fill(0.0);
            format!("{name}, platform only")
        } else {
            (*name).to_string()
        };
        let answered = sys.inverse(&v, &home).is_ok();
        println!("{} {name}: answered {answered}", S::NAME);
        g.bench_function(name.as_str(), |b| {
            b.iter(|| sys.inverse(black_box(&v), black_box(&home)))
        });
    }
    g.finish();
}

fn inverse(c: &mut Criterion) {
    let pt = PanTilt::new();
    let poses = [
        ("near home", [0.1, 0.1]),
        ("far", [2.9, 1.3]),
        ("tilt 1e-6", [-2.1, 1e-6]),
    ];
    bench_arm(c, &pt, &pt.home_start().unwrap(), &poses, false);
    let s4 = Scara::new();
    let poses = [
        ("near home", [0.1, 0.2, 5.0, 0.1]),
        ("far", [2.5, -2.0, -80.0, 2.8]),
        ("stretched", [0.6, 1e-4, -68.0, 2.5]),
    ];
    bench_arm(c, &s4, &s4.home_start().unwrap(), &poses, false);
    let s5 = ScaraWrist::new();
    let start = s5.home_start().unwrap();
    let poses = [
        ("near home", [0.1, 0.2, 5.0, 0.1, 0.1]),
        ("far", [2.5, -2.0, -80.0, 2.8, 1.2]),
        // Refused before the inputs were fitted first and the weights fixed (the tests' sweep, case 78).
        (
            "stretched",
            [
                0.6398859479071535,
                -7.496810347740997e-5,
                -68.05929984736592,
                2.5714128580651985,
                0.6847236974256761,
            ],
        ),
    ];
    bench_arm(c, &s5, &start, &poses, false);
    bench_arm(c, &s5, &start, &poses, true);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = inverse
}
criterion_main!(benches);
