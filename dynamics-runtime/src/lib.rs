//! Runtime of the dynamics toolkit.
//!
//! What generated code and users link against: the [`Scalar`] trait, the validated runtime
//! [`Model`], and the reference algorithms that check the generated code. The reference is
//! written from the textbook, independently of the symbolic expansion, so that the two
//! catch each other's mistakes.
//!
//! | what | items |
//! | --- | --- |
//! | numbers | [`Scalar`] (`f32`, `f64`, [`DoubleDouble`], the SIMD lanes [`F64x4`] and [`F32x8`], [`Dual`] numbers for forward-mode derivatives of any generated function), [`Real`] |
//! | many states per call | [`F64x4`], [`F32x8`] ([`Lanes`], contract in [`lanes`]); [`batch`]: a generated function over slices of states, four or eight per call |
//! | a declared mechanism | the [`mechanism!`] macro (its language: [`language`]); the [`Mechanism`], [`Dynamics`], [`Lagrangian`] and [`Energy`] traits its type implements |
//! | the mechanism as data | [`Model`], built and validated by [`ModelBuilder`] |
//! | the reference | [`Reference`]: inverse and forward dynamics, M, C, energies, joint reactions, poses |
//! | simulation | [`integrators`], [`integrate_configuration`], loop closure ([`closure`]) |
//! | force analysis | [`ForceAnalysis`], [`IllConditioned`] |
//! | the generated code's instruction set | [`isa`]: which copy runs, and pinning the baseline one |
//!
//! # Without std
//!
//! The default feature `std` brings everything above. Without it
//! (`default-features = false`) the crate is `#![no_std]`, allocates nothing, and keeps what
//! generated code and a controller on a microcontroller need: [`Scalar`] and [`Real`] for
//! `f32`, `f64`, [`DoubleDouble`] and the lanes, the [`mechanism!`] macro (every generated
//! function), the [`Mechanism`], [`Dynamics`], [`Lagrangian`] and [`Energy`] traits,
//! [`integrators`], [`closure`], [`batch`] (not `par_map*`), [`ForceAnalysis`] and
//! [`isa`] (baseline copies only). The sines, cosines and square roots that std's float
//! methods give come from the `libm` crate there. What needs std: the runtime [`Model`] and
//! [`ModelBuilder`] (and so `Mechanism::model()`), the [`Reference`] algorithms on nalgebra,
//! the generated `*_na` wrappers, the `rayon` feature, run-time ISA detection, and the
//! [`language`] documentation.

#![cfg_attr(not(feature = "std"), no_std)]

extern crate self as dynamics_runtime;

pub mod batch;
pub mod closure;
mod double_double;
mod dual;
mod dynamics;
mod fast_trig;
mod float;
pub mod integrators;
pub mod isa;
pub mod lanes;
#[cfg(feature = "std")]
pub mod language;
mod mechanism;
#[cfg(feature = "std")]
mod model;
#[doc(hidden)]
pub mod pack;
#[cfg(feature = "std")]
mod reference;
mod scalar;
mod statics;
pub mod tree_ldlt;

pub use double_double::DoubleDouble;
pub use dual::Dual;
pub use dynamics::{
    integrate_configuration, try_integrate_configuration, Dynamics, Energy, Lagrangian, LayoutError,
};
pub use dynamics_macros::mechanism;
pub use lanes::{F32x8, F64x4, Lanes};
pub use mechanism::{FunctionCost, JointLimits, Mechanism};
#[cfg(feature = "std")]
pub use model::{
    BodySpec, FrameSpec, Inertia, JointKind, JointSpec, JointType, Load, LoadFrame, LoadSpec,
    LoadType, Model, ModelBuilder, ModelError, ModelErrors, Placement, SizeError, GROUND,
};
/// The nalgebra version the runtime and the generated `*_na` wrappers use.
#[cfg(feature = "std")]
pub use nalgebra;
#[cfg(feature = "std")]
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
    /// `vec!` for the generated `Mechanism::model_with_parameters`, which may expand in a
    /// `#![no_std]` crate that has no `std` path of its own (this crate built with `std`).
    #[cfg(feature = "std")]
    pub use std::vec;
}

/// For generated code (hidden from the docs): expands to its input when this crate is built
/// with its `std` feature, to nothing without it. The `mechanism!` macro wraps in it what
/// needs std (`Mechanism::model`, the `*_na` wrappers), so that those items follow *this*
/// crate's feature; a `#[cfg(feature = "std")]` in generated code would test the user's
/// crate's features instead.
#[cfg(feature = "std")]
#[doc(hidden)]
#[macro_export]
macro_rules! __if_std {
    ($($item:tt)*) => {
        $($item)*
    };
}

/// Without `std`: nothing (see the `std` version).
#[cfg(not(feature = "std"))]
#[doc(hidden)]
#[macro_export]
macro_rules! __if_std {
    ($($item:tt)*) => {};
}

// The crate's unit tests use std (the test harness needs it anyway) in either build: its
// macros here, its prelude in each test module (`use std::prelude::rust_2021::*`).
#[cfg(all(test, not(feature = "std")))]
#[macro_use]
extern crate std;

/// The README's Rust examples, compiled and run as doc tests (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
struct ReadmeExamples;
