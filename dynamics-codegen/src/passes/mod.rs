//! The passes between the expansion and the printer. Each rewrites or annotates a
//! function's graph without changing what it computes (up to the rounding of regrouped
//! sums), and each is one module:
//!
//! | pass | what | when |
//! | --- | --- | --- |
//! | [`base_parameters`] | the bodies' inertias regrouped into base inertial parameters, chosen per function | before expanding a function of the Lagrangian alone (M, C, g, the bias, q̈, τ) |
//! | [`latency`] | sums and products combined earliest-ready first, in a new graph | after expansion |
//! | [`signs`] | a sign left on an output folded into the operation under it | after latency |
//! | [`fusion`] | a product that one sum alone uses folded into it as a multiply-add | before scheduling |
//!
//! The first runs inside [`crate::functions`], because it chooses inertias by expanding the
//! function with candidates; the others run in order in [`crate::compile`] and
//! [`crate::to_tokens`].

pub(crate) mod base_parameters;
pub(crate) mod fusion;
pub(crate) mod latency;
pub(crate) mod signs;
