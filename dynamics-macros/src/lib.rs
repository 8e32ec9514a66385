//! The `mechanism!` procedural macro: a thin shell around `dynamics_codegen`.
//!
//! All the work (parsing, validation, expansion, emission) happens in the ordinary library
//! crate `dynamics_codegen`, where it is unit-tested; this crate only converts token types.

use proc_macro::TokenStream;

/// Declares a mechanism and generates its type, its runtime model and its dynamics.
///
/// The language (settings, bodies, joints, loads, constraints, the functions generated and
/// their signatures) is documented, with tested examples, in the module
/// `dynamics_runtime::language`.
///
/// ```rust,ignore
/// mechanism! {
///     pub struct Pendulum;
///     body bob { mass: 2.0, com: [0.0, 0.0, -0.5], shape: point }
///     joint pivot: revolute(ground -> bob) { axis: y }
/// }
/// ```
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    dynamics_codegen::expand_mechanism(input.into()).into()
}
