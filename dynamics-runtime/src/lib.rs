//! Runtime of the dynamics toolkit.
//!
//! What generated code and users link against: the [`Scalar`] trait, the validated runtime
//! [`Model`], and the reference algorithms that check the generated code. The reference is
//! written from the textbook, independently of the symbolic expansion, so that the two
//! catch each other's mistakes.
//!
//! | what | items |
//! | --- | --- |
//! | numbers | [`Scalar`] (`f32`, `f64`, [`DoubleDouble`], the SIMD lanes [`F64x4`] and [`F32x8`]), [`Real`] |
//! | many states per call | [`F64x4`], [`F32x8`] ([`Lanes`], contract in [`lanes`]); [`batch`]: a generated function over slices of states, four or eight per call |
//! | a declared mechanism | the [`mechanism!`] macro (its language: [`language`]); the [`Mechanism`], [`Dynamics`], [`Lagrangian`] and [`Energy`] traits its type implements |
//! | the mechanism as data | [`Model`], built and validated by [`ModelBuilder`] |
//! | the reference | [`Reference`]: inverse and forward dynamics, M, C, energies, joint reactions, poses |
//! | simulation | [`integrators`], [`integrate_configuration`], loop closure ([`closure`]) |
//! | force analysis | [`ForceAnalysis`], [`IllConditioned`] |
//! | the generated code's instruction set | [`isa`]: which copy runs, and pinning the baseline one |

extern crate self as dynamics_runtime;

pub mod batch;
pub mod closure;
mod double_double;
mod dynamics;
mod fast_trig;
pub mod integrators;
pub mod isa;
pub mod lanes;
pub mod language;
mod mechanism;
mod model;
mod reference;
mod scalar;
mod statics;

pub use double_double::DoubleDouble;
pub use dynamics::{
    integrate_configuration, try_integrate_configuration, Dynamics, Energy, Lagrangian, LayoutError,
};
pub use dynamics_macros::mechanism;
pub use lanes::{F32x8, F64x4, Lanes};
pub use mechanism::{FunctionCost, JointLimits, Mechanism};
pub use model::{
    BodySpec, FrameSpec, Inertia, JointKind, JointSpec, JointType, Load, LoadFrame, LoadSpec,
    LoadType, Model, ModelBuilder, ModelError, ModelErrors, Placement, SizeError, GROUND,
};
/// The nalgebra version the runtime and the generated `*_na` wrappers use.
pub use nalgebra;
pub use reference::{FrameError, Pose, Reference, Wrench};
pub use scalar::{Real, Scalar};
pub use statics::{ForceAnalysis, IllConditioned};

/// What generated code, the benchmarks and the tests of this workspace need and users do
/// not: not part of the public API, and may change in any release.
#[doc(hidden)]
pub mod __private {
    /// The runtime's own sine and cosine of `f64` (its benchmark compares them with std's).
    pub mod fast_trig {
        pub use crate::fast_trig::{sin_cos, sin_cos_array, sin_cos_mul_add};
    }
}

/// The README's Rust examples, compiled and run as doc tests (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeExamples;
