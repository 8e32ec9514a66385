//! Runtime of the dynamics toolkit.
//!
//! What generated code and users link against: the [`Scalar`] trait, the validated runtime
//! [`Model`], and the reference algorithms that check the generated code. The reference is
//! written from the textbook, independently of the symbolic expansion, so that the two
//! catch each other's mistakes.

extern crate self as dynamics_runtime;

pub mod closure;
pub mod double_double;
pub mod dynamics;
pub mod fast_trig;
pub mod integrators;
pub mod isa;
pub mod mechanism;
pub mod model;
pub mod reference;
pub mod scalar;
pub mod statics;

pub use double_double::DoubleDouble;
pub use dynamics::{Dynamics, Energy, Lagrangian};
pub use dynamics_macros::mechanism;
pub use mechanism::{FunctionCost, Mechanism};
pub use model::{
    BodySpec, Inertia, JointKind, JointSpec, JointType, Model, ModelBuilder, ModelError,
    ModelErrors, Placement, SizeError, GROUND,
};
/// The nalgebra version the runtime and the generated `*_na` wrappers use.
pub use nalgebra;
pub use reference::{Pose, Reference, Wrench};
pub use scalar::{Real, Scalar};
pub use statics::{ForceAnalysis, IllConditioned};
