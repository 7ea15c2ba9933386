//! The 6-RSS rotary hexapod: its generated equations, then a forward-kinematics solve
//! (cranks + 0.1 rad).
//!
//! `cargo run --release --example rss_hexapod`

use linkage_examples::rss_hexapod::RssHexapod;

fn main() -> std::process::ExitCode {
    let hexapod = RssHexapod::new();
    linkage_examples::demo::show(RssHexapod::LISTING, &hexapod, hexapod.home_start(), 0.1)
}
