//! Section 5 of the paper, reproduced: test points (`sampling`), Table V (`table_v`) and the
//! joint-space maps of Figs. 5–6 (`joint_map`), judged against ground truth
//! ([`linkage::reference`]).

pub mod joint_map;
pub mod path_dependence;
pub mod sampling;
pub mod table_v;
