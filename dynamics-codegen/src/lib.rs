//! The compiler of the dynamics toolkit (see DESIGN.md for its stages).

pub mod emit;
pub mod sym;
