//! The compiler of the dynamics toolkit. Data flows one way (see DESIGN.md):
//!
//! ```text
//! DSL tokens / URDF file -> syntax -> model (validated) -> expand (symbolic Newton–Euler)
//!   -> sym (optimized DAG) -> emit (straight-line Rust)
//! ```
//!
//! [`compile`] runs the pipeline up to the expression graphs, [`to_tokens`] emits them, and
//! [`expand_mechanism`] is the whole thing as the `mechanism!` macro uses it. Each stage is
//! a module usable on its own (from the macro, a `build.rs` or the CLI).

pub mod declare;
pub mod emit;
pub mod expand;
pub mod model;
pub mod sym;
pub mod syntax;
pub mod urdf;

use proc_macro2::TokenStream;
use quote::quote;
use std::path::Path;

/// The path under which generated code finds the runtime crate.
pub fn runtime_path() -> TokenStream {
    quote!(::dynamics_runtime)
}

/// A compiled mechanism: the validated model and one expression graph per function.
pub struct Compiled {
    /// The validated model.
    pub model: model::Model,
    /// The generated functions, in a fixed order.
    pub functions: Vec<expand::Function>,
}

/// Imports the URDF file (if any, relative to `manifest_dir`), validates the mechanism and
/// expands its requested functions.
pub fn compile(mut mechanism: syntax::Mechanism, manifest_dir: &Path) -> syn::Result<Compiled> {
    let source = urdf::import(&mut mechanism, manifest_dir)?;
    let mut model = model::lower(&mechanism)?;
    model
        .source_files
        .extend(source.map(|p| p.display().to_string()));
    let scalar: syn::Path = syn::parse_quote!(::dynamics_runtime::Scalar);
    let mut functions = expand::expand(&model, scalar);
    if mechanism.isa == Some(syntax::Isa::Baseline) {
        for f in &mut functions {
            f.spec.dispatch = false;
        }
    }
    Ok(Compiled { model, functions })
}

/// The Rust items of a compiled mechanism: its type, its `Mechanism` implementation and its
/// dynamics functions as inherent associated functions.
pub fn to_tokens(compiled: &Compiled) -> TokenStream {
    let name = &compiled.model.name;
    let runtime = runtime_path();
    let nalgebra = quote!(#runtime::nalgebra);
    let functions = compiled.functions.iter().map(|f| {
        let function = emit::emit_function(&f.graph, &f.spec);
        let wrapper = emit::emit_nalgebra_wrapper(&f.spec, &nalgebra);
        quote!(#function #wrapper)
    });
    let costs: Vec<declare::Cost> = compiled
        .functions
        .iter()
        .map(|f| declare::Cost {
            name: f.spec.name.to_string(),
            ops: f.graph.op_count(&f.spec.output.nodes()),
        })
        .collect();
    let declaration = declare::declare(&compiled.model, &costs, &runtime);
    let traits = declare::dynamics_traits(&compiled.model, &runtime);
    let statics = declare::statics_constants(&compiled.model);
    quote! {
        #declaration
        #traits
        impl #name {
            #statics
            #(#functions)*
        }
    }
}

/// Runs the pipeline on the tokens of a `mechanism!` invocation. On error, returns the
/// errors as `compile_error!`s, each at its span, plus a stub of the declared type so that
/// the user sees the real errors rather than a cascade of "type not found".
pub fn expand_mechanism(input: TokenStream) -> TokenStream {
    let mechanism: syntax::Mechanism = match syn::parse2(input) {
        Ok(m) => m,
        Err(e) => return e.to_compile_error(),
    };
    let (vis, name) = (mechanism.visibility.clone(), mechanism.name.clone());
    match compile(mechanism, &urdf::manifest_dir()) {
        Ok(compiled) => to_tokens(&compiled),
        Err(e) => {
            let errors = e.to_compile_error();
            quote! {
                #errors
                #vis struct #name;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `isa: baseline;` leaves out the AVX2 + FMA copies and the run-time choice.
    #[test]
    fn isa_baseline_emits_one_copy() {
        let text = |isa: TokenStream| {
            let mechanism: syntax::Mechanism = syn::parse2(quote! {
                pub struct Arm;
                #isa
                gravity: [0.0, -9.81, 0.0];
                body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
                body lower { mass: 0.5, com: [0.2, 0.0, 0.0], shape: point }
                joint shoulder: revolute(ground -> upper) { axis: z }
                joint elbow: revolute(upper -> lower) { axis: z, at: [0.4, 0.0, 0.0] }
            })
            .expect("parses");
            let compiled = compile(mechanism, Path::new(".")).expect("compiles");
            to_tokens(&compiled).to_string()
        };
        let two = text(quote!());
        let one = text(quote!(isa: baseline;));
        assert!(two.contains("run_kernel"), "{two}");
        assert!(
            !one.contains("run_kernel") && !one.contains("run_piece"),
            "{one}"
        );
        assert!(!one.contains("kernel :: < T , true >"), "{one}");
    }

    #[test]
    fn doc_comments_reach_the_generated_type() {
        let mechanism: syntax::Mechanism = syn::parse2(quote! {
            /// A test arm.
            pub struct Arm;
            /// The upper arm.
            body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
            /// The tool, welded on.
            body tool { mass: 0.2, shape: point }
            /// The shoulder.
            joint shoulder: revolute(ground -> upper) { axis: z }
            joint weld: fixed(upper -> tool) { at: [0.4, 0.0, 0.0] }
        })
        .expect("parses");
        let compiled = compile(mechanism, Path::new(".")).expect("valid");
        let file: syn::File = syn::parse2(to_tokens(&compiled)).expect("valid Rust");
        let text = prettyplease::unparse(&file);
        for expected in [
            "/// A test arm.",
            "| `shoulder` | `upper` (with `tool`) | revolute about [0, 0, 1] | q[0] | v[0] |",
            "`shoulder`: The shoulder.",
            "`upper`: The upper arm.",
            "pub fn inverse_dynamics_na<",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
    }

    /// Statements in the body of every function (and nested piece) of the emitted code.
    fn body_lengths(items: &[syn::Item], out: &mut Vec<usize>) {
        for item in items {
            match item {
                syn::Item::Fn(f) => {
                    out.push(f.block.stmts.len());
                    let nested: Vec<syn::Item> = f
                        .block
                        .stmts
                        .iter()
                        .filter_map(|s| match s {
                            syn::Stmt::Item(i) => Some(i.clone()),
                            _ => None,
                        })
                        .collect();
                    body_lengths(&nested, out);
                }
                syn::Item::Impl(i) => {
                    let fns: Vec<syn::Item> = i
                        .items
                        .iter()
                        .filter_map(|ii| match ii {
                            syn::ImplItem::Fn(f) => Some(syn::Item::Fn(syn::ItemFn {
                                attrs: f.attrs.clone(),
                                vis: f.vis.clone(),
                                sig: f.sig.clone(),
                                block: Box::new(f.block.clone()),
                            })),
                            _ => None,
                        })
                        .collect();
                    body_lengths(&fns, out);
                }
                _ => {}
            }
        }
    }

    #[test]
    fn long_expansions_are_split_below_rustc_limits() {
        // rustc overflows its stack on debug builds of functions with more than about 3000
        // `let`s; every emitted body must stay well below that.
        let mechanism: syntax::Mechanism = syn::parse2(expand::tests::chain(
            30,
            true,
            quote!([mass_matrix, coriolis, forward_dynamics]),
        ))
        .expect("parses");
        let compiled = compile(mechanism, Path::new(".")).expect("valid");
        let file: syn::File = syn::parse2(to_tokens(&compiled)).expect("valid Rust");
        let mut lengths = Vec::new();
        body_lengths(&file.items, &mut lengths);
        let longest = lengths.iter().copied().max().unwrap_or(0);
        assert!(
            lengths.len() > 10,
            "expected split pieces, found {} bodies",
            lengths.len()
        );
        assert!(longest <= 2500, "a body of {longest} statements");
    }
}
