//! The `mechanism!` language: its syntax tree and parser.
//!
//! ```text
//! mechanism! {
//!     /// Docs on the mechanism.
//!     pub struct FallingRod;
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [inverse_dynamics, mass_matrix, forward_dynamics];
//!     parameters: [payload = 0.5];
//!
//!     /// A uniform rod, 0.6 m long, hanging along −y from its pivot.
//!     body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }
//!
//!     /// The frictionless pivot.
//!     joint pivot: revolute(ground -> rod) { axis: z }
//!
//!     load tip_force: force on rod at [0.0, -0.6, 0.0];
//! }
//! ```
//!
//! Every node keeps the span of the tokens it came from, so that later stages can point the
//! user at them: a [`SpanRange`] (first and last token) for anything that may be more than one
//! token, so that an error covers all of `-2.0` or `diag([..])` on stable Rust too. Numbers are small constant expressions (`0.6 / 2.0`, `-pi / 2`, `1e-3`) or a
//! declared parameter scaled by a constant (`payload`, `0.5 * payload`).

mod ast;
mod parse;
mod suggest;

pub use ast::*;
pub(crate) use suggest::closest;
