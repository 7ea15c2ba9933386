//! The 6-RSS rotary hexapod: its generated equations, then a forward-kinematics solve.
//!
//! `cargo run --release --example rss_hexapod`

use linkage::{arc_length, pose_from_unknowns, Options};
use linkage_examples::rss_hexapod::{home_start, RssHexapod};

fn main() {
    let hexapod = RssHexapod::new();
    println!("{}", RssHexapod::LISTING);
    let start = match home_start(&hexapod) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    let target = start.x.map(|q| q + 0.1);
    match arc_length(&hexapod, &start, &target, &Options::TIGHT) {
        Ok(sol) => {
            let pose = pose_from_unknowns(&hexapod, &sol.v);
            println!(
                "cranks {target:.4?} -> {} ({:?})",
                sol.status,
                pose.map(|p| (p.euler(), p.translation))
            );
        }
        Err(e) => eprintln!("error: {e}"),
    }
}
