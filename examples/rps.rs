//! The 3-RPS: its generated equations, then a forward-kinematics solve.
//!
//! `cargo run --release --example rps`

use linkage::{arc_length, pose_from_unknowns, Options};
use linkage_examples::rps::{home_start, Rps3};

fn main() {
    let hexapod = Rps3::new();
    println!("{}", Rps3::LISTING);
    let start = match home_start(&hexapod) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let target = start.x.map(|q| q + 5.0);
    match arc_length(&hexapod, &start, &target, &Options::TIGHT) {
        Ok(sol) => {
            let pose = pose_from_unknowns(&hexapod, &sol.v);
            println!(
                "legs {target:.4?} -> {} ({:?})",
                sol.status,
                pose.map(|p| (p.euler(), p.translation))
            );
        }
        Err(e) => eprintln!("error: {e}"),
    }
}
