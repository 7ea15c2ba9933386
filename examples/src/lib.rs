//! Mechanisms declared with `linkage::mechanism!`, shared by the examples and the tests.

pub mod case_study;
pub mod cli;
pub mod demo;
pub mod rps;
pub mod rss_hexapod;
pub mod start_sets;
pub mod stewart;
