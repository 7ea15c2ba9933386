//! criterion benches of the Krawczyk certificates on the Stewart platform of Table III: one
//! solution, one 1 kHz tracking step, and the certified tracker's 1 kHz sample (solve and
//! proof). `cargo bench -p linkage-tests --bench certify`.

use criterion::{criterion_group, criterion_main, Criterion};
use linkage::{arc_length, certify, certify_step, Options, Start, Tracker};
use linkage_examples::stewart::{home_start, legs_for_pose, Stewart};
use linkage_tests::manoeuvre;
use std::hint::black_box;

fn certificates(c: &mut Criterion) {
    let s = Stewart::new();
    let start = home_start(&s).unwrap();
    let target = [175.0, 168.0, 172.0, 165.0, 171.0, 169.0];
    let sol = arc_length(&s, &start, &target, &Options::TIGHT).unwrap();
    // A 1 kHz sample: legs moving at about 20 mm/s.
    let next: [f64; 6] = std::array::from_fn(|j| target[j] + 0.02 * (1.0 + j as f64) / 6.0);
    let from = Start::new(&s, sol.v, target).unwrap();
    let step = arc_length(&s, &from, &next, &Options::TIGHT).unwrap();
    let mut g = c.benchmark_group("stewart");
    g.bench_function("certify", |b| {
        b.iter(|| certify(&s, black_box(&sol.v), black_box(&target)))
    });
    g.bench_function("certify_step_1khz", |b| {
        b.iter(|| {
            certify_step(
                &s,
                (black_box(&sol.v), &target),
                (black_box(&step.v), &next),
            )
        })
    });
    // The tracker with every step proven, replaying the manoeuvre; a refused sample would
    // be timed too, so the count of refusals is checked after.
    let legs: Vec<[f64; 6]> = (0..2000)
        .map(|k| legs_for_pose(&s, &manoeuvre(k as f64 * 1e-3)).unwrap().0)
        .collect();
    let mut tracker = Tracker::new(s.clone(), start, Options::TIGHT).certified();
    let (mut k, mut refused) = (0, 0usize);
    g.bench_function("tracker_certified_1khz", |b| {
        b.iter(|| {
            k = (k + 1) % legs.len();
            refused += usize::from(tracker.update(black_box(&legs[k])).is_err());
        })
    });
    assert_eq!(refused, 0, "samples refused while timing");
    g.finish();
}

criterion_group!(benches, certificates);
criterion_main!(benches);
