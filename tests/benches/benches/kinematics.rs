//! criterion benches: residual, Jacobian, factorisation, one NR solve, one PH path, the
//! platform's twist and Jacobian, and one trajectory update, for every example mechanism. `cargo bench -p linkage-tests`.

use criterion::{criterion_group, criterion_main, Criterion};
use linkage::{arc_length, newton_raphson, Mechanism, Options, Start, Tracker};
use linkage_examples::{rps, rss_hexapod, stewart};
// Not criterion's `black_box`: without its nightly-only `real_blackbox` feature that is a
// volatile read of the value, which for a reference hides only the address, not the data
// behind it, and does not keep the results' stores (the residual timed at 3 ns for about
// 130 instructions). The standard one is an optimisation barrier on the data it is given.
use std::hint::black_box;

fn bench_mechanism<S: Mechanism<N, M> + Clone, const N: usize, const M: usize>(
    c: &mut Criterion,
    name: &str,
    sys: &S,
    start: Start<N, M>,
    target: [f64; M],
    step: [f64; M],
) {
    let mut g = c.benchmark_group(name);
    let mut f = [0.0; N];
    g.bench_function("residual", |b| {
        // Inputs by value and the output through black_box too: otherwise the work can be
        // hoisted out of the timing loop or its stores dropped as never read.
        b.iter(|| {
            sys.residual(&black_box(*start.v()), &black_box(*start.x()), &mut f);
            black_box(&mut f);
        })
    });
    let mut values = vec![0.0; S::NNZ];
    g.bench_function("jacobian_sparse", |b| {
        b.iter(|| {
            sys.jacobian(&black_box(*start.v()), &black_box(*start.x()), &mut values);
            black_box(&mut values);
        })
    });
    let mut fac = sys.new_factor();
    g.bench_function("factor_generated", |b| {
        b.iter(|| sys.factor(black_box(start.v()), black_box(start.x()), &mut fac))
    });
    g.bench_function("factor_solve_generated", |b| {
        b.iter(|| {
            sys.factor(black_box(start.v()), black_box(start.x()), &mut fac);
            let mut y = black_box(*start.v());
            sys.solve(&fac, &mut y);
            y
        })
    });
    g.bench_function("factor_solve_dense", |b| {
        b.iter(|| {
            let mut m = [[0.0; N]; N];
            sys.jacobian_dense(black_box(start.v()), black_box(start.x()), &mut m);
            let lu = linkage::lu::Lu::new(m);
            let mut y = black_box(*start.v());
            if let Some(lu) = lu {
                lu.solve(&mut y);
            }
            y
        })
    });
    g.bench_function("nr_solve", |b| {
        b.iter(|| newton_raphson(sys, &start, black_box(&target), &Options::TIGHT))
    });
    g.bench_function("ph_path", |b| {
        b.iter(|| arc_length(sys, &start, black_box(&target), &Options::TIGHT))
    });
    g.bench_function("twist", |b| {
        b.iter(|| linkage::velocity::twist(sys, black_box(start.v()), start.x(), black_box(&step)))
    });
    g.bench_function("platform_jacobian", |b| {
        b.iter(|| linkage::velocity::platform_jacobian(sys, black_box(start.v()), start.x()))
    });
    let mut tracker = Tracker::new(sys.clone(), start, Options::TIGHT);
    let mut k = 0u64;
    g.bench_function("trajectory_update", |b| {
        b.iter(|| {
            // Oscillate around the start in small steps, as 1 kHz samples would.
            k += 1;
            let s = ((k % 200) as f64 - 100.0).abs() / 100.0;
            let x: [f64; M] = std::array::from_fn(|j| start.x()[j] + s * step[j]);
            tracker.update(black_box(&x))
        })
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    let s = stewart::Stewart::new();
    let st = stewart::home_start(&s).unwrap();
    bench_mechanism(
        c,
        "stewart",
        &s,
        st,
        [190.0, 200.0, 190.0, 180.0, 190.0, 210.0],
        [2.0, -1.0, 1.5, 0.5, -2.0, 1.0],
    );
    let h = rss_hexapod::RssHexapod::new();
    let hs = rss_hexapod::home_start(&h).unwrap();
    bench_mechanism(
        c,
        "rss_hexapod",
        &h,
        hs,
        hs.x().map(|q| q + 0.1),
        [0.02, -0.01, 0.015, 0.005, -0.02, 0.01],
    );
    let r = rps::Rps3::new();
    let rs = rps::home_start(&r).unwrap();
    bench_mechanism(c, "rps", &r, rs, rs.x().map(|l| l + 5.0), [1.0, -0.5, 0.7]);
}

criterion_group! {
    name = kinematics;
    config = Criterion::default().warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(1));
    targets = benches
}
criterion_main!(kinematics);
