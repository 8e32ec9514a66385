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

/// The limits of one velocity coordinate, as declared (`limits: { .. }`) or read from a
/// URDF `<limit>`: ±∞ ([`f64::INFINITY`]) where none is given, as for a URDF `continuous`
/// joint's position or a free joint's six coordinates. No generated function enforces
/// them; they are there for controllers, planners and simulators.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lowest position (rad or m); −∞ when unbounded.
    pub lower: f64,
    /// Highest position (rad or m); +∞ when unbounded.
    pub upper: f64,
    /// Largest |velocity| (rad/s or m/s); +∞ when unbounded.
    pub velocity: f64,
    /// Largest |effort| (N·m or N); +∞ when unbounded.
    pub effort: f64,
}

impl JointLimits {
    /// No limit at all.
    pub const UNBOUNDED: JointLimits = JointLimits {
        lower: f64::NEG_INFINITY,
        upper: f64::INFINITY,
        velocity: f64::INFINITY,
        effort: f64::INFINITY,
    };

    /// Whether `position` lies within [lower, upper].
    #[must_use]
    pub fn contains_position(&self, position: f64) -> bool {
        (self.lower..=self.upper).contains(&position)
    }
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
    /// The limits of each velocity coordinate, in the order of v (`NV` entries): a revolute
    /// or prismatic joint's from its `limits: { .. }` or URDF `<limit>`, ±∞ where none is
    /// given; a free joint's six unbounded.
    const JOINT_LIMITS: &'static [JointLimits];
    /// The Coulomb (dry) friction of each velocity coordinate, in the order of v (`NV`
    /// entries; 0 where none is given): a joint's `friction:` or URDF `<dynamics
    /// friction>`. No generated function includes it (as in Pinocchio, which also only
    /// carries it); viscous damping, which the dynamics do include, is in [`Self::model`].
    const JOINT_FRICTION: &'static [f64];

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
