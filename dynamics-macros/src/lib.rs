//! The `mechanism!` procedural macro: a thin shell around `dynamics_codegen`.
//!
//! All the work (parsing, validation, expansion, emission) happens in the ordinary library
//! crate `dynamics_codegen`, where it is unit-tested; this crate only converts token types.

use proc_macro::TokenStream;

/// Declares a mechanism and generates its type, its runtime model and its dynamics.
///
/// See the `dynamics_runtime` crate documentation for the language.
#[proc_macro]
pub fn mechanism(input: TokenStream) -> TokenStream {
    dynamics_codegen::expand_mechanism(input.into()).into()
}
