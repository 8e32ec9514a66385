//! The input generators of `fuzz.rs`: mutations of declarations and URDF files
//! ([`mutate`]) and random mechanisms described for both the compiler and the runtime
//! ([`trees`]), and the runtime model a compiled declaration's generated code builds
//! ([`model`]).

pub mod model;
pub mod mutate;
pub mod trees;
