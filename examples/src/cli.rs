//! The `stewart` command line's pieces: file formats and streaming.

pub mod geometry;
pub mod legs_csv;
pub mod results_csv;
pub mod stream;
