//! Section 5 of the paper, reproduced: test points (`sampling`), Table V (`table_v`) and the
//! joint-space maps of Figs. 5–6 (`joint_map`), judged against ground truth (`truth`).

pub mod joint_map;
pub mod path_dependence;
pub mod sampling;
pub mod table_v;
mod truth;

pub use truth::{straight_segment, straight_segment_from};
