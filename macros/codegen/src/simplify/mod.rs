//! Simplification of the modelled system (Fig. 2): repeated equations removed
//! ([`duplicates`]), and, at the home configuration, the mobility decided by rank and the
//! equations the others imply left out ([`rank`]), the square system kept checked along the
//! motion from home (`motion` follows it, `along` checks and chooses again).

mod along;
mod derivatives;
pub mod duplicates;
mod motion;
pub mod rank;
mod tape;
