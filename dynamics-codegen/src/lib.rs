//! The compiler of the dynamics toolkit. Data flows one way (see DESIGN.md):
//!
//! ```text
//! DSL tokens / URDF file -> syntax -> model (validated) -> expand (symbolic Newton–Euler)
//!   -> sym (optimized DAG) -> emit (straight-line Rust)
//! ```
//!
//! [`expand_mechanism`] runs the whole pipeline; each stage is a module usable on its own
//! (from the macro, a `build.rs` or a CLI).

pub mod declare;
pub mod emit;
pub mod expand;
pub mod model;
pub mod sym;
pub mod syntax;
pub mod urdf;

use proc_macro2::TokenStream;
use quote::quote;

/// The path under which generated code finds the runtime crate.
pub fn runtime_path() -> TokenStream {
    quote!(::dynamics_runtime)
}

/// Runs the pipeline on the tokens of a `mechanism!` invocation. On error, returns the
/// errors as `compile_error!`s, each at its span, plus a stub of the declared type so that
/// the user sees the real errors rather than a cascade of "type not found".
pub fn expand_mechanism(input: TokenStream) -> TokenStream {
    let mut mechanism: syntax::Mechanism = match syn::parse2(input) {
        Ok(m) => m,
        Err(e) => return e.to_compile_error(),
    };
    let lowered = urdf::import(&mut mechanism, &urdf::manifest_dir()).and_then(|source| {
        let mut model = model::lower(&mechanism)?;
        model
            .source_files
            .extend(source.map(|p| p.display().to_string()));
        Ok(model)
    });
    match lowered {
        Ok(model) => {
            let runtime = runtime_path();
            let scalar: syn::Path = syn::parse_quote!(::dynamics_runtime::Scalar);
            let name = &model.name;
            let functions = expand::expand(&model, scalar)
                .iter()
                .map(|f| emit::emit_function(&f.graph, &f.spec))
                .collect::<Vec<_>>();
            let declaration = declare::declare(&model, &runtime);
            quote! {
                #declaration
                impl #name {
                    #(#functions)*
                }
            }
        }
        Err(e) => {
            let errors = e.to_compile_error();
            let (vis, name) = (&mechanism.visibility, &mechanism.name);
            quote! {
                #errors
                #vis struct #name;
            }
        }
    }
}
