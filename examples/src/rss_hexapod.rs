//! A 6-RSS rotary hexapod: six motors on the base turn cranks (active revolute pairs), and
//! rods with spherical joints at both ends carry the platform. Declared in its own `no_std`
//! crate (`linkage-rss-hexapod`), which the no-panic proof links too.

pub use linkage_rss_hexapod::{home_pose, home_start, RssHexapod};
