//! Every integration test in one binary: one link instead of one per file, which is most of
//! what a clean `cargo test` used to spend. Each file is a module named for what it checks.

mod case_study;
mod certified_tracking;
mod certify;
mod certify_adversarial;
mod cli_regressions;
mod dispatch;
mod file_readers_robustness;
mod generated_systems;
mod hostile_api;
mod jacobians;
mod mechanisms;
mod modes;
mod no_alloc;
mod other_mechanisms;
mod properties;
mod regressions;
mod scale;
mod solvers;
mod stale_start;
mod start_report;
mod stewart_cli;
mod stress;
mod tracking;
mod velocity;
