//! The trait that every `mechanism!` type implements.
//!
//! It carries what is known at compile time (sizes, names, nominal parameter values) and
//! rebuilds the same mechanism as a runtime `Model`, so the reference algorithms can run on
//! exactly the numbers the generated code was expanded from. The generated dynamics functions
//! themselves are inherent associated functions of the type, with fixed-size array arguments.
//!
//! Without the `std` feature the trait keeps its constants and loses `model` and
//! `model_with_parameters` (the runtime `Model` allocates); the generated implementation
//! drops them with it (`__if_std!`, in lib.rs).

#[cfg(feature = "std")]
use crate::model::{Model, ModelErrors};

/// What one generated function costs: its operation counts, as the macro counted them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FunctionCost {
    /// The function's name (`inverse_dynamics`, `mass_matrix`, ...).
    pub name: &'static str,
    /// Multiplications.
    pub mul: usize,
    /// Additions and subtractions.
    pub add: usize,
    /// Divisions.
    pub div: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Sines and cosines.
    pub trig: usize,
}

/// A mechanism declared with `mechanism!`.
pub trait Mechanism {
    /// The type's name.
    const NAME: &'static str;
    /// Length of the configuration vector q.
    const NQ: usize;
    /// Length of the velocity vector v (degrees of freedom).
    const NV: usize;
    /// Names of the moving bodies of the tree (bodies merged through fixed joints excluded),
    /// parents first.
    const BODY_NAMES: &'static [&'static str];
    /// Names of the joints that move those bodies, in the same order.
    const JOINT_NAMES: &'static [&'static str];
    /// Names of the symbolic parameters (the generated code's `p` input).
    const PARAMETER_NAMES: &'static [&'static str];
    /// The parameters' nominal values, as declared.
    const NOMINAL_PARAMETERS: &'static [f64];
    /// Names of the applied loads (the generated code's `loads` input, in this order).
    const LOAD_NAMES: &'static [&'static str];
    /// Length of the loads input: 3 per force or couple, 6 per wrench.
    const NUM_LOAD_INPUTS: usize;
    /// Names of the operational frames, in the order of the frame outputs
    /// (`frame_placements`, `frame_jacobians`, ...): every body welded to another through a
    /// fixed joint (URDF end effectors, flanges, feet), then every declared `frame`, or those
    /// `frames: [..]` lists. `Robot::FRAME_<NAME>` is each one's index.
    const FRAME_NAMES: &'static [&'static str] = &[];

    /// The generated functions and their operation counts.
    const FUNCTIONS: &'static [FunctionCost];

    /// The runtime model with the parameters at their nominal values (with the `std`
    /// feature).
    ///
    /// # Panics
    /// Never for a mechanism that compiled: the macro checked the same rules at compile time.
    #[cfg(feature = "std")]
    fn model() -> Model;

    /// The runtime model with the given parameter values, validated again (a parameter
    /// value can make the mechanism ill-posed, e.g. a negative mass). With the `std`
    /// feature.
    #[cfg(feature = "std")]
    fn model_with_parameters(parameters: &[f64]) -> Result<Model, ModelErrors>;
}
