//! File formats of the `stewart` command line: geometry TOML and leg-length CSV.

pub mod geometry;
pub mod legs_csv;
