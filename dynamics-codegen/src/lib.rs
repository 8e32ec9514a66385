//! The compiler of the dynamics toolkit: a declared mechanism (the `mechanism!` language or
//! a URDF file) to straight-line Rust. Data flows one way, through one function,
//! [`compile`] then [`to_tokens`]:
//!
//! ```text
//! tokens ──parse──▶ syntax::Mechanism ──urdf::import──▶ (URDF links and joints added)
//!   ──model::lower──▶ validated Model (every rule checked, errors at their spans)
//!   ──determinacy::check──▶ the force analysis and loop closures of full rank, M(q)
//!                           positive definite, at random configurations (evaluated
//!                           through `expand`)
//!   ──functions::CATALOG + expand──▶ one graph per requested function (textbook recursions;
//!                                    base-parameter pass for the functions of the Lagrangian)
//!   ──passes::latency, passes::signs──▶ the graphs regrouped for latency, signs settled
//!   ──passes::fusion, schedule──▶ multiply-adds, statement order, pieces
//!   ──print──▶ Rust tokens (the functions, their nalgebra wrappers, the type and its traits)
//! ```
//!
//! The stages are private modules; the entry points are [`expand_mechanism`] (what the
//! `mechanism!` macro calls), [`compile`] and [`to_tokens`] (for a `build.rs` or the
//! command-line compiler), with [`Mechanism`] the parsed declaration and [`Compiled`] the
//! result ([`Compiled::evaluate`] evaluates one of its functions in `f64`, for tests).
//! `docs/ARCHITECTURE.md` in the repository describes each stage.

mod build_profile;
mod declare;
mod determinacy;
mod expand;
mod functions;
mod ir;
mod model;
mod passes;
mod print;
mod schedule;
mod sym;
mod syntax;
mod urdf;

pub use model::RotationResidues;
pub use sym::OpCount;
pub use syntax::Mechanism;
pub use urdf::manifest_dir;

use proc_macro2::TokenStream;
use quote::quote;
use std::path::Path;

/// The path under which generated code finds the runtime crate.
pub(crate) fn runtime_path() -> TokenStream {
    quote!(::dynamics_runtime)
}

/// A compiled mechanism: the validated model and one expression graph per function, after
/// the passes, ready to print.
pub struct Compiled {
    model: model::Model,
    functions: Vec<ir::Function>,
}

/// One generated function of a [`Compiled`] mechanism, for reports.
#[derive(Clone, Debug)]
pub struct FunctionSummary {
    /// Its name in the generated code.
    pub name: String,
    /// The operations it computes.
    pub ops: OpCount,
    /// The longest chain of dependent operations, in estimated cycles.
    pub longest_chain: u32,
}

impl Compiled {
    /// Prints every function whole, however long, instead of cutting the long ones into
    /// pieces: faster code, for a crate built optimized and without debug info, as the
    /// `mechanism!` macro decides from rustc's command line (`build_profile`). rustc
    /// overflows its stack on such functions with debug info. A `build.rs` reads the same
    /// from Cargo's `OPT_LEVEL` and `DEBUG` environment variables.
    pub fn take_functions_whole(&mut self) {
        for function in &mut self.functions {
            function.spec.split_threshold = usize::MAX;
        }
    }

    /// The mechanism's type name.
    #[must_use]
    pub fn name(&self) -> String {
        self.model.name.to_string()
    }

    /// Its number of velocity coordinates.
    #[must_use]
    pub fn nv(&self) -> usize {
        self.model.nv
    }

    /// Its generated functions, in the order they are emitted.
    #[must_use]
    pub fn functions(&self) -> Vec<FunctionSummary> {
        self.functions
            .iter()
            .map(|f| {
                let nodes = f.spec.output.nodes();
                FunctionSummary {
                    name: f.spec.name.to_string(),
                    ops: f.op_count(),
                    longest_chain: f.graph.longest_chain(&nodes),
                }
            })
            .collect()
    }

    /// The entries of the joints' rotations that lie near 0 or ±1 without being exactly
    /// that (see [`RotationResidues`]), `None` when there are none.
    #[must_use]
    pub fn rotation_residues(&self) -> Option<RotationResidues> {
        self.model.rotation_residues()
    }

    /// Evaluates the generated function `function` in `f64` without compiling it: the
    /// values its expression graph computes from `inputs`, the arrays it takes by name
    /// (`q`, `v`, `a`, `tau`, `p`, `loads`; others are ignored), in the order of its return
    /// value flattened (a matrix by rows, a tuple or an array of matrices item after item).
    /// The arithmetic is the generated code's for `T = f64` but for its multiply-adds
    /// (one rounding on a CPU with FMA, two here) and its sines and cosines (which may
    /// differ from `f64::sin` and `f64::cos` in the last bit).
    ///
    /// For tests that compare a mechanism compiled at run time (through [`compile`]) with
    /// a reference, where building the generated code would take a `rustc` run
    /// (`tests/fuzz.rs` in the repository).
    ///
    /// Returns `None` when the mechanism has no function `function`, or when an array the
    /// function takes is missing from `inputs` or does not have the function's length for
    /// it.
    #[must_use]
    pub fn evaluate(&self, function: &str, inputs: &[(&str, &[f64])]) -> Option<Vec<f64>> {
        let f = self.functions.iter().find(|f| f.spec.name == function)?;
        let mut arrays: Vec<(sym::Array, &[f64])> = Vec::with_capacity(f.spec.args.len());
        for arg in &f.spec.args {
            let &(_, values) = inputs.iter().find(|(name, _)| *name == arg.array.name())?;
            if values.len() != arg.len {
                return None;
            }
            arrays.push((arg.array, values));
        }
        // Every input the graph reads is an argument of the function (`FunctionSpec`).
        let value = |r: sym::InputRef| {
            arrays
                .iter()
                .find(|(array, _)| *array == r.array)
                .and_then(|(_, values)| values.get(r.index as usize).copied())
                .unwrap_or(f64::NAN)
        };
        Some(f.spec.output.values(|nodes| f.graph.eval(value, nodes)))
    }
}

/// The pipeline up to the optimized graphs: imports the URDF file (if any, relative to
/// `manifest_dir`), lowers and validates the mechanism, expands each requested function
/// and runs the graph passes on it.
///
/// # Errors
/// Every error of the declaration (or of the URDF file), each at the span of the offending
/// tokens.
pub fn compile(mut mechanism: Mechanism, manifest_dir: &Path) -> syn::Result<Compiled> {
    let source = urdf::import(&mut mechanism, manifest_dir)?;
    let mut model = model::lower(&mechanism)?;
    determinacy::check(&mechanism, &model)?;
    model
        .source_files
        .extend(source.map(|p| p.display().to_string()));
    let scalar: syn::Path = syn::parse_quote!(::dynamics_runtime::Scalar);
    let dispatch = mechanism.isa != Some(syntax::Isa::Baseline);
    let mut functions = Vec::new();
    let mut too_large: Option<syn::Error> = None;
    let unpacking = model::Model {
        packs: false,
        ..model.clone()
    };
    for entry in functions::CATALOG.iter().filter(|e| (e.wanted)(&model)) {
        let ir::Function { graph, spec, .. } = entry.function(&model, &scalar);
        if graph.is_exhausted() {
            let error = too_large_error(&mechanism, entry.name);
            match &mut too_large {
                Some(first) => first.combine(error),
                None => too_large = Some(error),
            }
            continue;
        }
        let mut function = finished(graph, spec, dispatch);
        if mechanism.lanes {
            function.unpacked =
                unpacked_twin(entry, &function.graph, &unpacking, &scalar, dispatch);
        }
        functions.push(function);
    }
    if let Some(error) = too_large {
        return Err(error);
    }
    Ok(Compiled { model, functions })
}

/// `entry`'s function expanded for `unpacking` (the model with [`model::Model::packs`]
/// off), if its `graph` as expanded for the model has packed values: the body lane types
/// run ([`ir::Function::unpacked`]), the cheapest expansion with no packed value.
fn unpacked_twin(
    entry: &functions::Entry,
    graph: &sym::Graph,
    unpacking: &model::Model,
    scalar: &syn::Path,
    dispatch: bool,
) -> Option<Box<ir::Function>> {
    if !graph.packed_flags().contains(&true) {
        return None;
    }
    let ir::Function { graph, spec, .. } = entry.function(unpacking, scalar);
    if graph.is_exhausted() {
        return None;
    }
    Some(Box::new(finished(graph, spec, dispatch)))
}

/// An expanded function made ready to print: its additions regrouped for latency
/// ([`passes::latency::regroup`]), the signs of its outputs settled, its copies chosen.
fn finished(graph: sym::Graph, mut spec: ir::FunctionSpec, dispatch: bool) -> ir::Function {
    let (graph, output) = passes::latency::regroup(&graph, &spec.output);
    spec.output = passes::signs::settle(&graph, &output);
    spec.dispatch = dispatch;
    ir::Function {
        graph,
        spec,
        unpacked: None,
    }
}

/// The error for a function whose expansion passed [`sym::NODE_BUDGET`] nodes: at the
/// output name that asked for it, or at the mechanism's name when the outputs are the
/// default ones.
fn too_large_error(mechanism: &Mechanism, function: &str) -> syn::Error {
    // The output name whose flag is the function's (`energy` asks for `potential_energy`,
    // `constraints` for `constraint_jacobian`, ...).
    let flag = |name: &str| {
        let mut outputs = model::Outputs::default();
        outputs.enable(name).then_some(model::Outputs {
            into: 0,
            sparse_into: 0,
            ..outputs
        })
    };
    let span = mechanism
        .outputs
        .iter()
        .flatten()
        .find(|name| flag(&name.text).is_some() && flag(&name.text) == flag(function))
        .map_or(mechanism.name.span(), |name| name.span);
    syn::Error::new(
        span,
        format!(
            "`{function}` is too large to generate for this mechanism: its expansion passed \
             {} nodes, the most one function may take (the time and memory of the \
             expansion, and rustc's, grow with it). Leave `{function}` out of `outputs: [..]`; \
             the functions of linear size (`inverse_dynamics`, `forward_dynamics`, `gravity`, \
             `bias`, the kinematics of single frames) stay within the limit on far larger \
             mechanisms than the quadratic ones (mass matrix, Coriolis matrix, M⁻¹, Jacobians, \
             derivatives)",
            sym::NODE_BUDGET
        ),
    )
}

/// The Rust items of a compiled mechanism: its type, its `Mechanism` implementation and its
/// functions as inherent associated functions, each with its nalgebra wrapper.
#[must_use]
pub fn to_tokens(compiled: &Compiled) -> TokenStream {
    let name = &compiled.model.name;
    let runtime = runtime_path();
    let nalgebra = quote!(#runtime::nalgebra);
    let functions = compiled.functions.iter().map(|f| {
        let packed = printed(f, &compiled.model.outputs);
        let Some(unpacked) = &f.unpacked else {
            return quote!(#(#packed)*);
        };
        let count = unpacked.op_count();
        let both = packed
            .into_iter()
            .zip(printed(unpacked, &compiled.model.outputs))
            .map(|(packed, unpacked)| {
                print::packed_or_unpacked(packed, unpacked, &count)
                    .unwrap_or_else(|e| e.to_compile_error())
            });
        quote!(#(#both)*)
    });
    let wrappers = compiled
        .functions
        .iter()
        .map(|f| print::nalgebra_wrapper(&f.spec, &nalgebra));
    let costs: Vec<declare::Cost> = compiled
        .functions
        .iter()
        .map(|f| declare::Cost {
            name: f.spec.name.to_string(),
            ops: f.op_count(),
        })
        .collect();
    let declaration = declare::declare(&compiled.model, &costs, &runtime);
    let traits = declare::dynamics_traits(&compiled.model, &runtime);
    let statics = declare::statics_constants(&compiled.model);
    let frames = declare::frame_constants(&compiled.model);
    quote! {
        #declaration
        #traits
        impl #name {
            #frames
            #statics
            #(#functions)*
        }
        // The `*_na` twins take nalgebra types, which the runtime has with `std` only.
        #runtime::__if_std! {
            impl #name {
                #(#wrappers)*
            }
        }
    }
}

/// The function `f` and the `_into` and `_sparse_into` twins `outputs` asks of it.
fn printed(f: &ir::Function, outputs: &model::Outputs) -> Vec<TokenStream> {
    let fused = passes::fusion::fuse(&f.graph, &f.spec.output);
    let name = f.spec.name.to_string();
    // The twins: the same printer over the nodes each writes.
    let twin = |writes: print::Writes| {
        let written = print::written_nodes(&f.graph, &f.spec.output, writes);
        let plan = schedule::Plan::writing(&f.graph, &f.spec, fused.clone(), &written);
        print::function_into(&f.graph, &f.spec, &plan, writes)
    };
    let into = outputs
        .wants_into(&name)
        .then(|| twin(print::Writes::Every));
    let sparse_into = outputs.wants_sparse_into(&name).then(|| {
        twin(print::Writes::Sparse {
            upper_triangle: functions::is_symmetric(&name),
        })
    });
    let plan = schedule::Plan::new(&f.graph, &f.spec, fused);
    let function = print::function(&f.graph, &f.spec, &plan);
    [Some(function), into, sparse_into]
        .into_iter()
        .flatten()
        .collect()
}

/// Replaces each `__if_std! { .. }` of the generated code (an item, or an item of an
/// `impl`) by its contents, as the runtime built with `std` expands it, so that the printed
/// code is formatted throughout instead of showing those items as one token run (the
/// command-line compiler prints this view).
///
/// # Errors
/// If a wrapped token run does not parse as items (never for [`to_tokens`]'s output).
pub fn expand_if_std(file: &mut syn::File) -> syn::Result<()> {
    let is_if_std = |mac: &syn::Macro| {
        mac.path
            .segments
            .last()
            .is_some_and(|s| s.ident == "__if_std")
    };
    let mut items = Vec::with_capacity(file.items.len());
    for item in std::mem::take(&mut file.items) {
        match item {
            syn::Item::Macro(m) if is_if_std(&m.mac) => {
                items.extend(syn::parse2::<syn::File>(m.mac.tokens)?.items);
            }
            syn::Item::Impl(mut block) => {
                let mut inner = Vec::with_capacity(block.items.len());
                for item in std::mem::take(&mut block.items) {
                    match item {
                        syn::ImplItem::Macro(m) if is_if_std(&m.mac) => {
                            let tokens = m.mac.tokens;
                            let wrapped: syn::ItemImpl =
                                syn::parse2(quote::quote!(impl X { #tokens }))?;
                            inner.extend(wrapped.items);
                        }
                        other => inner.push(other),
                    }
                }
                block.items = inner;
                items.push(syn::Item::Impl(block));
            }
            other => items.push(other),
        }
    }
    file.items = items;
    Ok(())
}

/// Runs the pipeline on the tokens of a `mechanism!` invocation. On error, returns the
/// errors as `compile_error!`s, each at its span, plus a stub of the declared type so that
/// the user sees the real errors rather than a cascade of "type not found".
#[must_use]
pub fn expand_mechanism(input: TokenStream) -> TokenStream {
    let mechanism: Mechanism = match syn::parse2(input) {
        Ok(m) => m,
        Err(e) => return e.to_compile_error(),
    };
    let (vis, name) = (mechanism.visibility.clone(), mechanism.name.clone());
    match compile(mechanism, &urdf::manifest_dir()) {
        Ok(mut compiled) => {
            // The macro runs inside rustc: its command line is the build's.
            if build_profile::takes_whole_functions(std::env::args()) {
                compiled.take_functions_whole();
            }
            to_tokens(&compiled)
        }
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
    use quote::ToTokens;

    /// A function whose expansion passes the node budget is reported as too large (at the
    /// output name that asked for it), not generated; the other functions of the same
    /// mechanism stay within it, and `forward_dynamics` falls back to the method that does.
    #[test]
    fn a_function_past_the_node_budget_is_an_error_naming_its_output() {
        let chain = |outputs: TokenStream| {
            let tokens = functions::tests::chain(12, true, outputs);
            compile(syn::parse2(tokens).expect("parses"), Path::new("."))
        };
        // 29 000 nodes: enough for a 12-link spatial chain's inverse dynamics and its
        // articulated-body forward dynamics (27 000 do), not for its M⁻¹ (32 000 do) or its
        // LDLᵀ forward dynamics.
        sym::with_node_budget(29_000, || {
            assert!(chain(quote!([inverse_dynamics])).is_ok());
            let error = chain(quote!([inverse_dynamics, mass_matrix_inverse]))
                .err()
                .expect("M⁻¹ passes the budget");
            let message = error.to_string();
            assert!(
                message.contains("`mass_matrix_inverse` is too large to generate")
                    && message.contains("Leave `mass_matrix_inverse` out of `outputs: [..]`")
                    && !message.contains("  "),
                "{message}"
            );
            assert_eq!(error.into_iter().count(), 1, "one error, for M⁻¹ alone");
            assert!(chain(quote!([forward_dynamics_ldlt])).is_err());
            assert!(
                chain(quote!([forward_dynamics])).is_ok(),
                "the ABA, within the budget"
            );
        });
    }

    /// With `lanes: true;`, a function expanded with packed values (the humanoid's legs and
    /// arms side by side) has an unpacked twin with none, of the same values, which the printed function runs
    /// for lane types (`T::run_packed`, handed `out` in its `_into` twin); a function
    /// with no packed value has none.
    #[test]
    fn packed_functions_have_an_unpacked_twin_of_the_same_values() {
        let declaration = |lanes: TokenStream| {
            expand::tests::humanoid_declaration(quote!(
                outputs: [inverse_dynamics, mass_matrix_into, coriolis_matrix, forward_dynamics];
                #lanes
            ))
        };
        let without = compile(
            syn::parse2(declaration(quote!())).expect("parses"),
            Path::new("."),
        );
        let without = without.expect("valid");
        assert!(
            without.functions.iter().all(|f| f.unpacked.is_none()),
            "only when asked"
        );
        let tokens = declaration(quote!(lanes: true;));
        let compiled =
            compile(syn::parse2(tokens).expect("parses"), Path::new(".")).expect("valid");
        let state = expand::tests::state(&compiled.model);
        let mut twins = Vec::new();
        for f in &compiled.functions {
            let packed = f.graph.packed_flags().contains(&true);
            let name = f.spec.name.to_string();
            assert_eq!(f.unpacked.is_some(), packed, "{name}");
            let Some(unpacked) = &f.unpacked else {
                continue;
            };
            assert!(!unpacked.graph.packed_flags().contains(&true), "{name}");
            let want = f.graph.eval(&state, &f.spec.output.nodes());
            let got = unpacked.graph.eval(&state, &unpacked.spec.output.nodes());
            for (w, x) in want.iter().zip(&got) {
                assert!(
                    (w - x).abs() <= 1e-12 * (1.0 + w.abs()),
                    "{name}: {x} against {w}"
                );
            }
            twins.push(name);
        }
        assert_eq!(
            twins,
            ["mass_matrix", "coriolis_matrix", "forward_dynamics"]
        );
        let text: String = to_tokens(&compiled)
            .to_string()
            .split_whitespace()
            .collect();
        assert_eq!(text.matches("T::run_packed(").count(), 4, "{text}");
        assert_eq!(text.matches("T::run_packed(out,").count(), 1);
    }

    /// A sparse twin of an output that is zero at every state writes nothing and names its
    /// `out` `_out`: read by nothing, `out` would warn in code the CLI writes out.
    #[test]
    fn a_sparse_twin_with_nothing_to_write_leaves_out_unread() {
        let text = expand_mechanism(quote! {
            pub struct Floater;
            gravity: [0.0, 0.0, 0.0];
            outputs: [gravity_sparse_into, mass_matrix_sparse_into];
            body a { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
            joint j: revolute(ground -> a) { axis: z }
        })
        .to_string();
        let text: String = text.split_whitespace().collect();
        assert!(
            text.contains(
                "fngravity_sparse_into<T:::dynamics_runtime::Scalar>(_q:&[T;1],_out:&mut[T;1]){}"
            ),
            "{text}"
        );
        assert!(text.contains("(*out)[0][0]="), "{text}");
    }

    /// A graph past its budget takes no new operation: it hands back the constant 0 and
    /// says it is exhausted; leaves are still taken.
    #[test]
    fn an_exhausted_graph_refuses_operations() {
        sym::with_node_budget(3, || {
            let g = sym::Graph::new();
            let (x, y) = (g.input(sym::Array::Q, 0), g.input(sym::Array::Q, 1));
            let sum = g.add(x, y);
            assert!(!g.is_exhausted());
            assert_eq!(g.len(), 3);
            assert_eq!(g.add(x, y), sum, "an existing node is found");
            assert_eq!(g.mul(x, y), g.zero());
            assert!(g.is_exhausted());
            assert_eq!(g.constant_value(g.mul(sum, x)), Some(0.0));
        });
    }

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

    /// `evaluate` gives the values of the generated functions, and `None` for an unknown
    /// function or a missing or wrong-sized input.
    #[test]
    fn evaluate_gives_the_functions_values() {
        let mechanism: Mechanism = syn::parse2(quote! {
            pub struct Arm;
            parameters: [m = 2.0];
            outputs: [gravity, mass_matrix, kinetic_energy];
            body upper { mass: m, com: [0.5, 0.0, 0.0], shape: point }
            body lower { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
            joint shoulder: revolute(ground -> upper) { axis: y }
            joint elbow: revolute(upper -> lower) { axis: y, at: [1.0, 0.0, 0.0] }
        })
        .expect("parses");
        let compiled = compile(mechanism, Path::new(".")).expect("valid");
        let (q, v, p) = ([0.3, -0.4], [1.5, 0.5], [3.0]);
        let inputs: [(&str, &[f64]); 3] = [("q", &q), ("v", &v), ("p", &p)];
        // M by rows: M₀₀ = m l₁² + m₂ (l² + l₂² + 2 l l₂ cos q₁), M₀₁ = m₂ (l₂² + l l₂ cos q₁),
        // M₁₁ = m₂ l₂² with l₁ = l₂ = 0.5, l = 1.
        let c = q[1].cos();
        let m = [3.0 * 0.25 + 1.25 + c, 0.25 + 0.5 * c, 0.25 + 0.5 * c, 0.25];
        let got = compiled
            .evaluate("mass_matrix", &inputs)
            .expect("generated");
        assert_eq!(got.len(), 4);
        for (g, e) in got.iter().zip(m) {
            assert!((g - e).abs() < 1e-14, "{got:?} against {m:?}");
        }
        let energy = compiled
            .evaluate("kinetic_energy", &inputs)
            .expect("generated");
        let expected = 0.5 * (m[0] * v[0] * v[0] + 2.0 * m[1] * v[0] * v[1] + m[3] * v[1] * v[1]);
        assert!((energy[0] - expected).abs() < 1e-14, "{energy:?}");
        // Gravity along −z, the arm along x turning about y: positive q lowers the arm
        // (z = −l sin q), so V = −m g l sin q and g = ∂V/∂q = −m g l cos q.
        let g = compiled.evaluate("gravity", &inputs).expect("generated");
        let (g0, g1) = (q[0].cos(), (q[0] + q[1]).cos());
        let expected = [
            -9.81 * (3.0 * 0.5 * g0 + 1.0 * (g0 + 0.5 * g1)),
            -9.81 * 0.5 * g1,
        ];
        assert!((g[0] - expected[0]).abs() < 1e-12 && (g[1] - expected[1]).abs() < 1e-12);
        assert_eq!(compiled.evaluate("coriolis_matrix", &inputs), None);
        assert_eq!(compiled.evaluate("gravity", &[("q", &q)]), None);
        assert_eq!(
            compiled.evaluate("gravity", &[("q", &q[..1]), ("p", &p)]),
            None
        );
    }

    /// The generated code of a declaration, pretty-printed as a runtime with `std` expands
    /// it.
    fn generated(tokens: TokenStream) -> String {
        let mechanism: Mechanism = syn::parse2(tokens).expect("parses");
        let compiled = compile(mechanism, Path::new(".")).expect("valid");
        let mut file: syn::File = syn::parse2(to_tokens(&compiled)).expect("valid Rust");
        expand_if_std(&mut file).expect("items");
        prettyplease::unparse(&file)
    }

    /// What needs the runtime's `std` (the runtime `Model`, nalgebra) is inside
    /// `__if_std!`, and nothing else is: the generated functions and the traits stay in
    /// every build. `expand_if_std` leaves no `__if_std!` and the same items otherwise.
    #[test]
    fn std_items_are_wrapped_and_expand() {
        let mechanism: Mechanism = syn::parse2(quote! {
            pub struct Arm;
            body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
            joint shoulder: revolute(ground -> upper) { axis: z }
        })
        .expect("parses");
        let compiled = compile(mechanism, Path::new(".")).expect("valid");
        let mut file: syn::File = syn::parse2(to_tokens(&compiled)).expect("valid Rust");
        let is_if_std = |mac: &syn::Macro| {
            mac.path
                .segments
                .last()
                .is_some_and(|s| s.ident == "__if_std")
        };
        let mut wrapped = Vec::new();
        for item in &file.items {
            match item {
                syn::Item::Macro(m) if is_if_std(&m.mac) => wrapped.push(m.mac.tokens.to_string()),
                syn::Item::Impl(block) => {
                    for item in &block.items {
                        if let syn::ImplItem::Macro(m) = item {
                            assert!(is_if_std(&m.mac), "{}", m.mac.path.to_token_stream());
                            wrapped.push(m.mac.tokens.to_string());
                        }
                    }
                }
                _ => {}
            }
        }
        assert_eq!(wrapped.len(), 2, "{wrapped:?}");
        assert!(wrapped[0].starts_with("fn model ()"), "{}", wrapped[0]);
        assert!(wrapped[0].contains("fn model_with_parameters"));
        assert!(wrapped[1].contains("fn inverse_dynamics_na"));
        let outside = file.to_token_stream().to_string();
        for gone in ["std ::", "nalgebra", "Model"] {
            let without: String = wrapped
                .iter()
                .fold(outside.clone(), |s, w| s.replace(w, ""));
            assert!(
                !without.contains(gone),
                "`{gone}` outside __if_std!: {without}"
            );
        }
        expand_if_std(&mut file).expect("items");
        let text = prettyplease::unparse(&file);
        assert!(!text.contains("__if_std"), "{text}");
        for expected in [
            "fn model()",
            "fn model_with_parameters(",
            "pub fn inverse_dynamics_na<",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
    }

    #[test]
    fn doc_comments_reach_the_generated_type() {
        let text = generated(quote! {
            /// A test arm.
            pub struct Arm;
            /// The upper arm.
            body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
            /// The tool, welded on.
            body tool { mass: 0.2, shape: point }
            /// The shoulder.
            joint shoulder: revolute(ground -> upper) { axis: z, limits: { lower: -1.0 } }
            /// The weld.
            joint weld: fixed(upper -> tool) { at: [0.4, 0.0, 0.0] }
            /// The stand, welded to the ground.
            body stand { mass: 1.0, shape: point }
            joint bolt: fixed(ground -> stand);
            frames: [upper];
        });
        for expected in [
            "/// A test arm.",
            "| `shoulder` | `upper` (with `tool`) | revolute about [0, 0, 1] | q[0] | v[0] |",
            "| `shoulder` | v[0] | [-1, ∞] | ∞ | ∞ | 0 |",
            // The bodies and fixed joints merged, into the ground or a moving body, too (the
            // frames, which would list them too, are chosen otherwise).
            "/// # Bodies and joints\n///\n/// `stand`: The stand, welded to the ground.\n///\n\
             /// `shoulder`: The shoulder.\n///\n/// `upper`: The upper arm.\n///\n\
             /// `weld`: The weld.\n///\n/// `tool`: The tool, welded on.\n",
            "pub fn inverse_dynamics_na<",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
    }

    /// A load's doc comment, body, point, axes and input layout reach the type's docs.
    #[test]
    fn loads_are_documented_with_their_inputs_and_frame() {
        let text = generated(quote! {
            pub struct Arm;
            body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
            body tool { mass: 0.2, shape: point }
            joint shoulder: revolute(ground -> upper) { axis: z }
            joint weld: fixed(upper -> tool) { at: [0.4, 0.0, 0.0] }
            /// A push at the tip.
            load push: force on tool at [0.1, 0.0, 0.0];
            load grip: wrench on upper in world;
        });
        for expected in [
            "/// # Loads",
            "| `push` | `tool` | [0.1, 0, 0] | body | [0..3] = F |",
            "| `grip` | `upper` | [0, 0, 0] | world | [3..6] = F, [6..9] = M |",
            "`push`: A push at the tip.",
            "/// # Functions",
            "/// - [`Self::inverse_dynamics`]: ",
            "`outputs: [..];` to get it): `forward_dynamics_aba`, `forward_dynamics_ldlt`,",
        ] {
            assert!(text.contains(expected), "missing {expected:?} in\n{text}");
        }
    }

    /// The function names are output names; the short forms stand for the same outputs.
    #[test]
    fn outputs_are_named_as_the_functions_they_generate() {
        let names = |outputs: TokenStream| -> Vec<String> {
            let mechanism: Mechanism = syn::parse2(quote! {
                pub struct P;
                outputs: #outputs;
                body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
                joint j: revolute(ground -> b) { axis: z }
            })
            .expect("parses");
            let compiled = compile(mechanism, Path::new(".")).expect("valid");
            compiled.functions().into_iter().map(|f| f.name).collect()
        };
        let full = names(quote!([coriolis_matrix, joint_reactions, kinetic_energy]));
        assert_eq!(
            full,
            [
                "coriolis_matrix",
                "kinetic_energy",
                "potential_energy",
                "joint_reactions"
            ]
        );
        assert_eq!(names(quote!([coriolis, reactions, energy])), full);
        let unknown: Mechanism = syn::parse2(quote! {
            pub struct P;
            outputs: [coriolis_matrx];
            body b { mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }
            joint j: revolute(ground -> b) { axis: z }
        })
        .expect("parses");
        let message = compile(unknown, Path::new("."))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(
            message.contains("unknown output `coriolis_matrx`")
                && message.contains("coriolis_matrix"),
            "{message}"
        );
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
        let mechanism: syntax::Mechanism = syn::parse2(functions::tests::chain(
            30,
            true,
            quote!([mass_matrix, coriolis, forward_dynamics]),
        ))
        .expect("parses");
        let mut compiled = compile(mechanism, Path::new(".")).expect("valid");
        let lengths = |compiled: &Compiled| {
            let file: syn::File = syn::parse2(to_tokens(compiled)).expect("valid Rust");
            let mut lengths = Vec::new();
            body_lengths(&file.items, &mut lengths);
            lengths
        };
        let split = lengths(&compiled);
        let longest = split.iter().copied().max().unwrap_or(0);
        assert!(
            split.len() > 10,
            "expected split pieces, found {} bodies",
            split.len()
        );
        assert!(longest <= 2500, "a body of {longest} statements");
        // What an optimized build without debug info gets: the same functions, uncut.
        compiled.take_functions_whole();
        let whole = lengths(&compiled);
        let longest = whole.iter().copied().max().unwrap_or(0);
        assert!(whole.len() < split.len(), "{} bodies whole", whole.len());
        assert!(
            longest > 2500,
            "the longest whole body has {longest} statements"
        );
    }
}
