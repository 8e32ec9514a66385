//! The functions `mechanism!` generates when a declaration lists no `outputs:`, in the order
//! it emits them. One file for the `dynamics-tests` library
//! (`dynamics_tests::DEFAULT_FUNCTIONS`, the fuzzer's random trees) and `tests/build.rs`
//! (the random trees it writes), which cannot link the library and includes this file.

/// The default outputs, as the generated functions' names.
pub const DEFAULT_FUNCTIONS: [&str; 9] = [
    "inverse_dynamics",
    "gravity",
    "bias",
    "mass_matrix",
    "coriolis_matrix",
    "forward_dynamics",
    "kinetic_energy",
    "potential_energy",
    "joint_reactions",
];
