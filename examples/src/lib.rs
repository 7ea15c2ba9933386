//! Mechanisms declared with `linkage::mechanism!`, shared by the examples and the tests.

pub mod case_study;
pub mod cli;
pub mod demo;
pub mod rps;
pub mod rss_hexapod;
pub mod start_sets;
pub mod twins;
/// Gao & Wu's Stewart platform, in a crate of its own that the C interface shares.
pub use linkage_stewart as stewart;
