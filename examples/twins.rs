//! Checks that the solvers' x86-64-v3 twin gives the answers of the code as built, bit for
//! bit. Meant for a release build, where the generated kernels are inlined into the twins:
//!
//! ```sh
//! cargo run --release --example twins
//! ```

fn main() -> std::process::ExitCode {
    match linkage_examples::twins::compare_twins() {
        Ok(report) if report.twin => {
            println!(
                "x86-64-v3 twin: {} answers, the same bit for bit",
                report.answers
            );
            std::process::ExitCode::SUCCESS
        }
        Ok(report) => {
            println!(
                "this CPU has no x86-64-v3: both runs of {} answers took the code as built",
                report.answers
            );
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("the x86-64-v3 twin and the code as built differ:\n{e}");
            std::process::ExitCode::FAILURE
        }
    }
}
