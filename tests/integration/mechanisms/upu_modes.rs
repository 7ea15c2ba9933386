//! Every assembly mode of Tsai's translational 3-UPU: its roots come in octets (each leg
//! turned half a turn about its own axis), which the generated candidate symmetries
//! (`Mechanism::symmetry`) let monodromy add as whole orbits.
use super::translational_upu::TranslationalUpu;
use linkage::modes::{AllModes, ModesOptions};
use std::time::Instant;

/// Capacity of the measurements below.
const WIDE: usize = 2048;

/// Start counts for the seeds in `UPU_SEEDS` (comma-separated; default 2015,7,99), under the
/// default stopping rule or, with `UPU_STRICT=k`, k times it; prints count, report and time.
/// `cargo test -p linkage-tests --test integration upu_seeds -- --ignored --nocapture`
#[test]
#[ignore = "a measurement (minutes): the counts over seeds behind the count test"]
fn upu_seeds() {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(|| {
            let seeds: Vec<u64> = std::env::var("UPU_SEEDS")
                .unwrap_or_else(|_| "2015,7,99".into())
                .split(',')
                .map(|s| s.trim().parse().unwrap())
                .collect();
            let strict: usize = std::env::var("UPU_STRICT").map_or(1, |s| s.parse().unwrap());
            for seed in seeds {
                let d = ModesOptions::default();
                let options = ModesOptions {
                    seed,
                    stable_loops: strict * d.stable_loops,
                    stable_seeds: strict * d.stable_seeds,
                    max_loops: strict * d.max_loops,
                    ..d
                };
                let t = Instant::now();
                let modes = AllModes::<_, 45, 3, WIDE>::new(TranslationalUpu::new(), &options)
                    .map(Box::new);
                let secs = t.elapsed().as_secs_f64();
                match modes {
                    Ok(m) => println!(
                        "3-UPU seed {seed} rule x{strict}: {} roots ({:?}) in {secs:.1} s",
                        m.start_count(),
                        m.report()
                    ),
                    Err(e) => println!("3-UPU seed {seed} rule x{strict}: {e} after {secs:.1} s"),
                }
            }
        })
        .unwrap()
        .join()
        .unwrap();
}
