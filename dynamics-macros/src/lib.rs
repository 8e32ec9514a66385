//! The `mechanism!` macro (a thin shell over `dynamics_codegen`).
