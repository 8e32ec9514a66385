//! Random trees through the macro: `tests/build.rs` writes ten random mechanisms (1 to 30
//! joints; random parents, axes, placements, inertias and mass centres; free roots,
//! armature and damping, loads, a symbolic mass, forward dynamics by both methods) as
//! `mechanism!` declarations, and every output the macro generates for them equals the
//! runtime reference at 30 random states:
//! within 1e-12 · (1 + max |value|) in f64 and 1e-4 · (1 + max |value|) in f32 (the
//! reference at the inputs rounded to f32), forward dynamics within the same times cond(M).
//!
//! Loads enter the reference as the equivalent wrench on each body (force f, moment
//! r × f + n about the body origin); a tree with a parameter is checked at random
//! non-nominal values, its reference built by `model_with_parameters`. Run with
//! `--nocapture` to see the largest errors per output.
//!
//! Shared by both sides: the reference's model is the one the macro emits, from the code
//! generator's resolution of the `rpy(..)` placements and `principal(.., rotation: rpy(..))`
//! inertias that `build.rs` writes; those forms are checked against hand formulas in
//! `shape_inertias.rs` and `generated_vs_reference.rs` (`*_hand_built_reference`).

#[macro_use]
mod generated_support;

use dynamics_runtime::Mechanism;
use generated_support::{arr, check_against_reference, Inputs, UnderTest};

#[macro_use]
mod trees {
    //! The random trees of `tests/build.rs`.
    #![allow(dead_code)]
    include!(concat!(env!("OUT_DIR"), "/random_trees.rs"));
}

/// States per tree.
const STATES: usize = 30;

macro_rules! random_tree_test {
    ($test:ident, $m:ident, p: $p:tt, loads: $l:tt, [$($f:ident),*]) => {
        #[test]
        fn $test() {
            use trees::$m;
            let model = |p: &[f64]| {
                <$m as Mechanism>::model_with_parameters(p)
                    .unwrap_or_else(|e| panic!("{}: {e}", <$m as Mechanism>::NAME))
            };
            let under_test = UnderTest {
                name: <$m as Mechanism>::NAME,
                model: Box::new(model),
                num_parameters: <$m as Mechanism>::PARAMETER_NAMES.len(),
                loads: $m::DECLARED_LOADS,
                num_load_inputs: <$m as Mechanism>::NUM_LOAD_INPUTS,
                f64: generated_functions!(f64, $m, p: $p, loads: $l, [$($f),*]),
                f32: generated_functions!(f32, $m, p: $p, loads: $l, [$($f),*]),
            };
            assert_eq!(under_test.f64.len(), <$m as Mechanism>::FUNCTIONS.len());
            let seed = 0x7ee5 ^ <$m as Mechanism>::NV as u64;
            check_against_reference(&under_test, STATES, seed).print(<$m as Mechanism>::NAME);
        }
    };
}

for_each_random_tree!(random_tree_test);
