//! Simplification of the modelled system (Fig. 2): repeated equations removed
//! ([`duplicates`]), and, at the home configuration, the mobility decided by rank and the
//! equations the others imply left out ([`rank`]).

pub mod duplicates;
pub mod rank;
