//! The 3-RPS: its generated equations, then a forward-kinematics solve (legs + 5 mm).
//!
//! `cargo run --release --example rps`

use linkage_examples::rps::Rps3;

fn main() -> std::process::ExitCode {
    let rps = Rps3::new();
    linkage_examples::demo::show(Rps3::LISTING, &rps, rps.home_start(), 5.0)
}
