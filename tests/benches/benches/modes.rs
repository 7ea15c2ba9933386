//! criterion bench of every assembly mode (`linkage::modes`) of the general 6-6 platform in
//! `examples/data/general_6_6.toml`: one query (40 paths, all complex roots, the real ones
//! refined) per leg row of `examples/data/general_6_6_legs.csv`, cycling through the first 20.
//! `cargo bench -p linkage-tests --bench modes`.

use criterion::{criterion_group, criterion_main, Criterion};
use linkage::modes::{AllModes, ModesOptions, Roots};
use linkage_examples::cli::{geometry, legs_csv};
use linkage_examples::stewart::{SixSix, StewartGeneral};
use std::hint::black_box;
use std::path::Path;

fn all_modes(c: &mut Criterion) {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/data");
    let (base, platform) = geometry::load_joints(&data.join("general_6_6.toml")).unwrap();
    let rows: Vec<[f64; 6]> = legs_csv::read(&data.join("general_6_6_legs.csv"))
        .unwrap()
        .into_iter()
        .filter_map(Result::ok)
        .collect();
    let sys = StewartGeneral::with_joints(&base, &platform).unwrap();
    let mut modes = Box::new(AllModes::<_, 18, 6, 64>::new(sys, &ModesOptions::default()).unwrap());
    // As `stewart modes` does: the start set moved near the mean of the rows.
    let mut centre = [0.0; 6];
    for x in &rows {
        for i in 0..6 {
            centre[i] += x[i] / rows.len() as f64;
        }
    }
    modes.recenter(&centre, 0.1, 1).unwrap();
    assert_eq!(modes.start_count(), 40);
    let mut roots = Box::new(Roots::<18, 64>::new());
    let mut k = 0;
    let mut g = c.benchmark_group("stewart_general");
    g.bench_function("all_modes_40_paths", |b| {
        b.iter(|| {
            k = (k + 1) % 20;
            modes.solve(black_box(&rows[k]), &mut roots).unwrap();
            roots.real().len()
        })
    });
    g.finish();
}

criterion_group!(benches, all_modes);
criterion_main!(benches);
