//! The solvers' x86-64-v3 twin (`runtime/src/dispatch.rs`) against the code as built: the same
//! answers, bit for bit (`linkage_examples::twins`). In this profile (debug assertions) the
//! generated kernels are not inlined and the twin is the solvers' own loops; CI also runs the
//! release build (`cargo run --release --example twins`).

#[test]
fn the_x86_64_v3_twin_gives_the_same_answers_bit_for_bit() {
    match linkage_examples::twins::compare_twins() {
        Ok(report) => {
            assert!(report.answers > 1000, "{report:?}");
            if !report.twin {
                eprintln!("this CPU has no x86-64-v3: both runs took the code as built");
            }
        }
        Err(e) => panic!("the twin and the code as built differ:\n{e}"),
    }
}
