//! Straight-line Rust from the expression DAG.
//!
//! [`function`] writes one function, generic over `T: Scalar` (the trait's path is
//! given by the caller), taking fixed-size array references in a caller-given order and
//! returning a fixed-size array, a matrix `[[T; C]; R]`, a scalar or a tuple of those
//! ([`Output`]). Its body is one `let vN = …;` per live node of the graph: the inputs and
//! constants, then the operations in a depth-first order from the outputs that keeps few
//! values live at once (`depth_first`), then the output expression:
//!
//! ```text
//! /// Bias torque of the pendulum.
//! ///
//! /// Op count: 2 mul, 0 add, 0 div, 1 trig.
//! pub fn bias<T: Scalar>(q: &[T; 1], _v: &[T; 1]) -> [T; 1] {
//!     let v0 = q[0];
//!     let v1 = T::sin(v0);
//!     let v2 = T::from_f64(9.81_f64);
//!     ...
//!     [v4]
//! }
//! ```
//!
//! - Constants are `T::from_f64(lit_f64)` with the shortest literal that round-trips
//!   (Rust's `{:?}` formatting of `f64`); negative values as `-lit`; NaN and infinities as
//!   `f64::NAN`, `f64::INFINITY`, `f64::NEG_INFINITY`.
//! - Inputs are `q[3]`: constant indices into fixed-size arrays, checked at compile time.
//! - When both `sin x` and `cos x` are live they are computed together by one
//!   `let (vS, vC) = T::sin_cos(vX);` at the position of the first of them.
//! - When sines or cosines of two or more inputs are live (the joint angles, in every
//!   function of a model with revolute joints), they are computed by one call,
//!   `let ([vS0, _, vS2], [vC0, vC1, vC2]) = T::sin_cos_array_for::<WIDE, 3>([q[0], q[1], q[2]]);`,
//!   at the position of the first of them, the inputs read in place (so no input is needed
//!   earlier than its turn) and `_` for a value no one reads. For `f64` the runtime
//!   evaluates the angles two per SSE2 instruction, or four per AVX one in the wide copy;
//!   a scalar type without such a routine gets one `sin_cos` each.
//! - A product that only one sum or difference uses is written into it:
//!   `let vN = isa.mul_add(vA, vB, vC);` for `vA·vB + vC` (with `-vA` or `-vC` for the
//!   two differences), `isa` the kernel's copy (`dynamics_runtime::isa::Isa<WIDE>`, below).
//!   In the baseline copy it is `Scalar::mul_add`: `a·b + c` with two roundings, bit for
//!   bit the separate operations, unless the build targets a CPU with fused multiply-add
//!   (`-C target-cpu=native`); in the wide copy of `f32`/`f64` it is one FMA instruction,
//!   one rounding, and of `F64x4` one AVX FMA instruction for the four lanes.
//! - A packed value (four lanes, `crate::sym`'s `Graph::pack`) is a
//!   `dynamics_runtime::pack::P4<T>`: `let vN = P4([vA, vB, vC, vD]);` packs four scalars,
//!   `let vN = vP.0[2];` reads a lane, a scalar operand of a packed operation is
//!   `P4::splat(vA)`, and a packed multiply-add `P4::mul_add_on(vA, vB, vC, isa)`. Carried
//!   from one piece to the next, a packed value travels as its four lanes.
//! - An argument the function does not read is named with a leading underscore.
//! - No allocation, no branch on data, no panic.
//!
//! # Two copies of each kernel, chosen at run time
//!
//! The statements above are the body of a nested `#[inline(always)]` function
//! `kernel<T, const WIDE: bool>`, and the emitted function hands both instantiations to
//! the scalar type, which calls one with its copy's `Isa` value:
//!
//! ```text
//! pub fn mass_matrix<T: Scalar>(q: &[T; 6]) -> [[T; 6]; 6] {
//!     #[inline(always)]
//!     fn kernel<T: Scalar, const WIDE: bool>(
//!         isa: ::dynamics_runtime::isa::Isa<WIDE>,
//!         q: &[T; 6],
//!     ) -> [[T; 6]; 6] { … }
//!     T::run_kernel(
//!         #[inline(always)]
//!         |isa| kernel::<T, true>(isa, q),
//!         #[inline(always)]
//!         |isa| kernel::<T, false>(isa, q),
//!     )
//! }
//! ```
//!
//! For `f32`, `f64` and the default build's `F64x4`, `run_kernel` (`dynamics_runtime::isa`)
//! runs the `WIDE` copy compiled for AVX2 and FMA when the CPU has them (one relaxed load
//! and a branch that never changes), the baseline copy otherwise; other scalar types run
//! the baseline copy and never instantiate the other. Only the runtime can make the wide
//! copy's `Isa<true>`, after detecting the features, so holding one proves the CPU has
//! them: that is what lets `F64x4` fuse its products in one AVX instruction with no check
//! per operation and no `unsafe` in generated code (`_isa` when the kernel has neither a
//! fused product nor a solve loop, `dynamics_runtime::tree_ldlt`, which fuses the same
//! way). A function with fewer than [`MIN_DISPATCHED_OPS`] operations and at most one
//! angle's sine and cosine is emitted as the baseline body alone, after
//! `const WIDE: bool = false;` and `let isa = ::dynamics_runtime::isa::Isa::BASELINE;` if
//! the body reads them: the choice would cost more than it saves. So is every function of
//! a spec with [`FunctionSpec::dispatch`] off (a mechanism declared with `isa: baseline;`),
//! its pieces then `#[inline(never)]` functions called in turn.
//!
//! # A packed body and an unpacked one
//!
//! With `lanes: true;`, a function expanded with packed values (isomorphic limbs, or partly
//! filled columns, side by side: `crate::expand::slots`) is printed twice, from its graph and from its
//! unpacked twin's (the same function expanded with `Model::packs` off, the cheapest
//! expansion with no packed value: `crate::ir::Function::unpacked`), as nested functions
//! `packed` and `unpacked` of one emitted function ([`packed_or_unpacked`]), which runs
//! `T::run_packed((), |()| packed(q, ..), |()| unpacked(q, ..))` (an `_into` twin hands `out`
//! to the body instead of `()`). `f32` and `f64` (and every type by
//! default) run the packed body, where four limbs fill one AVX register; the lane types
//! `F64x4` and `F32x8`, whose every operation already fills one with four or eight states,
//! run the unpacked body, where a packed value would take four registers. The body a type
//! does not run is never instantiated for it. The docs give both op counts.
//!
//! # Writing into the caller's storage
//!
//! An output asked for as `<name>_into` also gets [`function_into`]: the same arguments and
//! `out: &mut R`, `R` the function's result type, nothing returned. Its kernel follows each
//! statement with the writes of the value it defines into that value's places in `out`
//! (`(*out)[i][j] = vN;`, a value in as many places as it fills), so that `out` holds, bit
//! for bit, what the function returns, every entry written once; it is run by
//! `T::run_kernel_into(out, |isa, out| kernel::<T, true>(isa, q, out), ..)`. Cut into
//! pieces, each piece takes `out` and writes the outputs it computes (none is carried);
//! finished by a solve loop, the right-hand sides are written into `out` and solved there.
//!

use crate::ir::{FunctionSpec, Output, Sweeps, TreeSolve};
use crate::passes::fusion::Fused;
use crate::schedule::{Plan, Step};
use crate::sym::{Array, Graph, Node, Op, OpCount};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};
use std::collections::{BTreeSet, HashMap};

/// The printed form of an output: its type and the expression that builds it.
impl Output {
    /// The Rust type, with `T` the scalar.
    fn ty(&self) -> TokenStream {
        match self {
            Output::Scalar(_) => quote!(T),
            Output::Vector(v) => {
                let n = Literal::usize_unsuffixed(v.len());
                quote!([T; #n])
            }
            Output::Matrix(rows) => {
                let r = rows.len();
                let c = rows.first().map_or(0, Vec::len);
                assert!(
                    rows.iter().all(|row| row.len() == c),
                    "matrix output rows differ in length"
                );
                let (r, c) = (Literal::usize_unsuffixed(r), Literal::usize_unsuffixed(c));
                quote!([[T; #c]; #r])
            }
            Output::Tuple(items) => {
                let tys = items.iter().map(Output::ty);
                quote!((#(#tys,)*))
            }
            Output::Stack(items) => {
                let n = Literal::usize_unsuffixed(items.len());
                let item = items.first().map_or_else(|| quote!(T), Output::ty);
                assert!(
                    items.iter().all(|i| i.ty().to_string() == item.to_string()),
                    "stacked outputs differ in shape"
                );
                quote!([#item; #n])
            }
            Output::Solved(s) => s.returned().ty(),
        }
    }

    /// The expression building the output from the nodes' variables.
    fn expr(&self) -> TokenStream {
        match self {
            Output::Scalar(n) => {
                let v = var(*n);
                quote!(#v)
            }
            Output::Vector(v) => {
                let vs = v.iter().map(|&n| var(n));
                quote!([#(#vs),*])
            }
            Output::Matrix(rows) => {
                let rows = rows.iter().map(|row| {
                    let vs = row.iter().map(|&n| var(n));
                    quote!([#(#vs),*])
                });
                quote!([#(#rows),*])
            }
            Output::Tuple(items) => {
                let exprs = items.iter().map(Output::expr);
                quote!((#(#exprs,)*))
            }
            Output::Stack(items) => {
                let exprs = items.iter().map(Output::expr);
                quote!([#(#exprs),*])
            }
            Output::Solved(s) => tree_solve_expr(s, false),
        }
    }

    /// [`Output::expr`] at the end of a kernel, which may use its `WIDE` copy's choice.
    fn expr_in_kernel(&self) -> TokenStream {
        match self {
            Output::Solved(s) => tree_solve_expr(s, true),
            _ => self.expr(),
        }
    }
}

/// The block that solves an [`Output::Solved`]: the factor and the pivots bound to arrays,
/// the right-hand sides to the tuple the block returns, then `tree_ldlt::solve_columns` on
/// that tuple's matrices in place, those of one width together. Inside a kernel
/// (`in_kernel`) it runs in the kernel's copy (`WIDE`); outside, in the copy
/// `T::run_kernel` chooses.
fn tree_solve_expr(s: &TreeSolve, in_kernel: bool) -> TokenStream {
    let header = tree_solve_header(s);
    let rhs: Vec<TokenStream> = s
        .rhs
        .iter()
        .map(|b| Output::Matrix(b.clone()).expr())
        .collect();
    let target = |k: usize| {
        let k = syn::Index::from(k);
        quote!(&mut solved.#k)
    };
    let returned = if s.rhs.len() == 1 {
        quote!(solved.0)
    } else {
        quote!(solved)
    };
    let solves = |wide: TokenStream| {
        let calls = tree_solve_calls(s, &wide, &target);
        quote! {
            let mut solved = (#(#rhs,)*);
            #calls
            #returned
        }
    };
    let run = if in_kernel {
        solves(quote!(WIDE))
    } else {
        let (wide, narrow) = (solves(quote!(true)), solves(quote!(false)));
        quote! {
            T::run_kernel(
                #[inline(always)]
                |isa| { #wide },
                #[inline(always)]
                |isa| { #narrow },
            )
        }
    };
    quote!({
        #header
        #run
    })
}

/// The solve of an [`Output::Solved`] in place in a `_into` function's `out`, whose
/// right-hand sides the statements before it have written there: in the kernel's copy
/// (`in_kernel`), or, after the pieces of a split function, in the copy
/// `T::run_kernel_into` chooses (the baseline copy alone without `dispatch`).
fn tree_solve_into(s: &TreeSolve, in_kernel: bool, dispatch: bool) -> TokenStream {
    let header = tree_solve_header(s);
    let single = s.rhs.len() == 1;
    let target = |k: usize| {
        if single {
            quote!(&mut *out)
        } else {
            let k = syn::Index::from(k);
            quote!(&mut out.#k)
        }
    };
    let run = if in_kernel {
        tree_solve_calls(s, &quote!(WIDE), &target)
    } else if dispatch {
        let wide = tree_solve_calls(s, &quote!(true), &target);
        let narrow = tree_solve_calls(s, &quote!(false), &target);
        quote! {
            T::run_kernel_into(
                out,
                #[inline(always)]
                |isa, out| { #wide },
                #[inline(always)]
                |isa, out| { #narrow },
            );
        }
    } else {
        let runtime = crate::runtime_path();
        let calls = tree_solve_calls(s, &quote!(WIDE), &target);
        quote! {
            const WIDE: bool = false;
            let isa = #runtime::isa::Isa::BASELINE;
            #calls
        }
    };
    quote!({
        #header
        #run
    })
}

/// The constants of a solve block: the coordinate tree, the factor and the pivots.
fn tree_solve_header(s: &TreeSolve) -> TokenStream {
    let runtime = crate::runtime_path();
    let n = Literal::usize_unsuffixed(s.parents.len());
    let p = Literal::usize_unsuffixed(s.factor.len());
    let parents = s.parents.iter().map(|parent| match parent {
        Some(i) => {
            let i = Literal::usize_unsuffixed(*i);
            quote!(::core::option::Option::Some(#i))
        }
        None => quote!(::core::option::Option::None),
    });
    let factor = s.factor.iter().map(|&x| var(x));
    let pivots = s.inverse_pivot.iter().map(|&x| var(x));
    // The last sweep alone does not scale by the pivots (its right-hand sides hold D⁻¹).
    let pivots = (s.sweeps == Sweeps::All).then(|| {
        quote! {
            let inverse_pivot: [T; #n] = [#(#pivots),*];
        }
    });
    quote! {
        const TREE: #runtime::tree_ldlt::CoordinateTree<#n, #p> =
            #runtime::tree_ldlt::CoordinateTree::new([#(#parents),*]);
        let factor: [T; #p] = [#(#factor),*];
        #pivots
    }
}

/// The `tree_ldlt` calls that solve the right-hand sides in place, those of one width in
/// one call, `target(k)` the `&mut` of the k-th.
fn tree_solve_calls(
    s: &TreeSolve,
    wide: &TokenStream,
    target: &dyn Fn(usize) -> TokenStream,
) -> TokenStream {
    let runtime = crate::runtime_path();
    let n = Literal::usize_unsuffixed(s.parents.len());
    let p = Literal::usize_unsuffixed(s.factor.len());
    let calls = s.width_groups().into_iter().map(|(width, members)| {
        let targets: Vec<TokenStream> = members.iter().map(|&k| target(k)).collect();
        let c = Literal::usize_unsuffixed(width);
        let k = Literal::usize_unsuffixed(members.len());
        match s.sweeps {
            Sweeps::All => quote! {
                #runtime::tree_ldlt::solve_columns::<T, #wide, #n, #p, #c, #k>(
                    isa, &TREE, &factor, &inverse_pivot, [#(#targets),*],
                );
            },
            Sweeps::LastOfInverse => quote! {
                #runtime::tree_ldlt::solve_lower_columns::<T, #wide, #n, #p, #c, #k>(
                    isa, &TREE, &factor, [#(#targets),*],
                );
                #(#runtime::tree_ldlt::mirror_upper_triangle(#targets);)*
            },
        }
    });
    quote!(#(#calls)*)
}

/// The function described by `spec`, its statements in the order and pieces of `plan`
/// (made for this graph and spec by [`Plan::new`]); see the module documentation for its
/// shape.
#[must_use]
pub(crate) fn function(graph: &Graph, spec: &FunctionSpec, plan: &Plan) -> TokenStream {
    let ops = graph.ops();
    let trait_ = &spec.scalar_trait;
    let name = &spec.name;
    let vis = &spec.vis;
    let ret = spec.output.ty();
    let count = crate::ir::op_count(graph, &spec.output);
    let docs = doc_attrs(&spec.doc, &count, &spec.output);

    let params = function_params(&ops, spec, plan);

    let body = if plan.pieces.len() > 1 {
        plan.chained_pieces(&ops, spec)
    } else if !spec.dispatch || !worth_dispatching(&count) {
        plan.baseline_body(&ops, 0, &spec.output)
    } else {
        let (mut kernel_params, args) = array_params(&plan.pieces[0].arrays, spec);
        kernel_params.insert(0, plan.isa_param(0, &spec.output));
        let body = plan.piece_body(&ops, 0, &spec.output);
        quote! {
            #[inline(always)]
            fn kernel<T: #trait_, const WIDE: bool>(#(#kernel_params),*) -> #ret {
                #body
            }
            T::run_kernel(
                #[inline(always)]
                |isa| kernel::<T, true>(isa #(, #args)*),
                #[inline(always)]
                |isa| kernel::<T, false>(isa #(, #args)*),
            )
        }
    };

    let allows = generated_allows();
    quote! {
        #(#docs)*
        #allows
        #[must_use]
        #vis fn #name<T: #trait_>(#(#params),*) -> #ret {
            #body
        }
    }
}

/// Which entries of `out` a `_into` twin writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Writes {
    /// Every entry: `out` holds, bit for bit, what the function returns (`<name>_into`).
    Every,
    /// Only the entries that can be nonzero (not a constant 0 of the graph), and of a
    /// symmetric matrix (`upper_triangle`) only those on and above the diagonal
    /// (`<name>_sparse_into`): the rest of `out` is left as it is, as Pinocchio's `crba`
    /// fills the upper triangle of `data.M`, which holds zeros elsewhere. An output
    /// finished by a solve loop writes every entry.
    Sparse { upper_triangle: bool },
}

/// The `<name>_into` twin of a function (asked for as `<name>_into` in `outputs:`): the
/// same arguments and an `out: &mut` of the output's type, into which each entry is
/// written as soon as it is computed, so that the result is neither held until the end
/// nor copied out (for the quadruped's 18 × 18 mass matrix 0.74 of the time in `f64`,
/// 0.61 on `F64x4`). Cut into pieces, each piece writes the outputs it computes (the plan
/// hands them back, [`Plan::writing`]) and the function the outputs that are leaves.
/// A function finished by a solve loop writes its right-hand sides into `out` and solves
/// them there, in place. With [`Writes::Sparse`], the `<name>_sparse_into` twin, which
/// writes only some entries: its plan is [`Plan::writing`] over [`written_nodes`].
#[must_use]
pub(crate) fn function_into(
    graph: &Graph,
    spec: &FunctionSpec,
    plan: &Plan,
    writes: Writes,
) -> TokenStream {
    let ops = graph.ops();
    let trait_ = &spec.scalar_trait;
    let name = &spec.name;
    let vis = &spec.vis;
    let ret = spec.output.ty();
    let count = crate::ir::op_count(graph, &spec.output);
    let suffix = match writes {
        Writes::Every => "into",
        Writes::Sparse { .. } => "sparse_into",
    };
    let name_into = format_ident!("{}_{}", name, suffix);
    let writes = effective_writes(&spec.output, writes);
    let places = output_places(&spec.output, &ops, writes);
    let link = match writes {
        Writes::Every => format!(
            "As [`{name}`](Self::{name}), its result written into `out`, every entry of which \
             is overwritten."
        ),
        Writes::Sparse { upper_triangle } => {
            let written: usize = places.values().map(Vec::len).sum();
            let which = if upper_triangle {
                "the entries on and above the diagonal that can be nonzero"
            } else {
                "the entries that can be nonzero"
            };
            format!(
                "As [`{name}`](Self::{name}), writing into `out` only {which} ({written} of its \
                 {total}) and leaving the others as they are: pass a matrix that holds zeros \
                 there (zeroed once and reused, as Pinocchio's `data.M` for `crba`), and it \
                 holds the result{upper}.",
                total = spec.output.nodes().len(),
                upper = if upper_triangle {
                    " in its upper triangle"
                } else {
                    ""
                },
            )
        }
    };
    let docs = doc_attrs(&link, &count, &spec.output);
    let params = function_params(&ops, spec, plan);
    if places.is_empty() {
        // A sparse twin of an output that is zero whatever the state (gravity without
        // gravity): nothing to write, and `out` unused.
        let allows = generated_allows();
        return quote! {
            #(#docs)*
            #allows
            #vis fn #name_into<T: #trait_>(#(#params,)* _out: &mut #ret) {}
        };
    }
    let body = if plan.pieces.len() > 1 {
        plan.chained_pieces_into(&ops, spec, &places)
    } else {
        let statements = plan.piece_body_into(&ops, 0, &places, &[]);
        let solve = match &spec.output {
            Output::Solved(s) => Some(tree_solve_into(s, true, spec.dispatch)),
            _ => None,
        };
        if !spec.dispatch || !worth_dispatching(&count) {
            let prelude = plan.baseline_prelude(0, &spec.output);
            quote!(#prelude #statements #solve)
        } else {
            let (mut kernel_params, args) = array_params(&plan.pieces[0].arrays, spec);
            kernel_params.insert(0, plan.isa_param(0, &spec.output));
            quote! {
                #[inline(always)]
                fn kernel<T: #trait_, const WIDE: bool>(#(#kernel_params,)* out: &mut #ret) {
                    #statements
                    #solve
                }
                T::run_kernel_into(
                    out,
                    #[inline(always)]
                    |isa, out| kernel::<T, true>(isa #(, #args)*, out),
                    #[inline(always)]
                    |isa, out| kernel::<T, false>(isa #(, #args)*, out),
                );
            }
        }
    };
    let allows = generated_allows();
    quote! {
        #(#docs)*
        #allows
        #vis fn #name_into<T: #trait_>(#(#params,)* out: &mut #ret) {
            #body
        }
    }
}

/// One function (or `_into` twin) with two bodies, `packed` and `unpacked` (the printed
/// function of a graph with packed values and of its unpacked copy, the same name and
/// arguments): the packed function's docs and signature, the two as nested functions
/// `packed` and `unpacked`, and `T::run_packed` (handed `out` for an `_into` twin) choosing one for the scalar type, at compile time: `f32` and `f64` run the
/// packed body, lane types the unpacked one, whose op count is added to the docs.
///
/// # Errors
/// If either is not a function (never for [`function`]'s and [`function_into`]'s output).
pub(crate) fn packed_or_unpacked(
    packed: TokenStream,
    unpacked: TokenStream,
    unpacked_count: &OpCount,
) -> syn::Result<TokenStream> {
    let mut outer: syn::ItemFn = syn::parse2(packed)?;
    let inner = |mut f: syn::ItemFn, name: &str| {
        f.attrs.retain(|a| !a.path().is_ident("doc"));
        f.attrs.insert(0, syn::parse_quote!(#[inline(always)]));
        f.sig.ident = format_ident!("{}", name);
        f.vis = syn::Visibility::Inherited;
        f
    };
    let packed = inner(outer.clone(), "packed");
    let unpacked = inner(syn::parse2(unpacked)?, "unpacked");
    // Every argument is passed on (to one body or the other), so none is unused.
    let mut args = Vec::new();
    for input in &mut outer.sig.inputs {
        if let syn::FnArg::Typed(arg) = input {
            if let syn::Pat::Ident(pat) = &mut *arg.pat {
                let name = pat.ident.to_string();
                pat.ident = format_ident!("{}", name.strip_prefix('_').unwrap_or(&name));
                args.push(pat.ident.clone());
            }
        }
    }
    // An `_into` function's `out` is handed to the body that runs; `()` to one that returns.
    let handed = if args.iter().any(|a| a == "out") {
        quote!(out)
    } else {
        quote!(())
    };
    let body = quote! {
        T::run_packed(
            #handed,
            #[inline(always)]
            |#handed| packed(#(#args),*),
            #[inline(always)]
            |#handed| unpacked(#(#args),*),
        )
    };
    let line = format!(
        " Lane types (`F64x4`, `F32x8`: several states side by side) run it with no packed \
         value, one limb or column at a time: op count {unpacked_count}."
    );
    let at = outer
        .attrs
        .iter()
        .rposition(|a| a.path().is_ident("doc"))
        .map_or(0, |k| k + 1);
    outer.attrs.insert(at, syn::parse_quote!(#[doc = #line]));
    outer.block = syn::parse2(quote!({ #packed #unpacked #body }))?;
    Ok(quote!(#outer))
}

/// [`Writes::Every`] for an output finished by a solve loop (which solves in the whole of
/// `out`), else `writes`.
fn effective_writes(output: &Output, writes: Writes) -> Writes {
    match output {
        Output::Solved(_) => Writes::Every,
        _ => writes,
    }
}

/// The output nodes a `_into` twin writes with `writes`, each once, in the output's order
/// (every node of an output that writes every entry): what [`Plan::writing`] schedules.
#[must_use]
pub(crate) fn written_nodes(graph: &Graph, output: &Output, writes: Writes) -> Vec<Node> {
    let writes = effective_writes(output, writes);
    if writes == Writes::Every {
        // Besides what it writes, a solve loop reads its factor and pivots.
        return output.nodes();
    }
    let mut seen = std::collections::HashSet::new();
    output_writes(output, &graph.ops(), writes)
        .into_iter()
        .map(|(n, _)| n)
        .filter(|n| seen.insert(*n))
        .collect()
}

/// Where each node of `output` goes in `out` (`(*out)[i][j]`, `(*out).0[i][j]`, ...), a node
/// in as many places as it fills, of those `writes` asks for; for an output finished by a
/// solve loop, where its right-hand sides go, to be solved there in place.
fn output_places(output: &Output, ops: &[Op], writes: Writes) -> HashMap<Node, Vec<TokenStream>> {
    let mut places: HashMap<Node, Vec<TokenStream>> = HashMap::new();
    for (n, place) in output_writes(output, ops, writes) {
        places.entry(n).or_default().push(place);
    }
    places
}

/// Each written node of `output` with its place in `out`, in the output's order.
fn output_writes(output: &Output, ops: &[Op], writes: Writes) -> Vec<(Node, TokenStream)> {
    fn walk(output: &Output, place: &TokenStream, acc: &mut Vec<(Node, TokenStream)>) {
        let mut at = |n: Node, place: TokenStream| acc.push((n, place));
        match output {
            Output::Scalar(n) => at(*n, place.clone()),
            Output::Vector(v) => {
                for (i, &n) in v.iter().enumerate() {
                    let i = Literal::usize_unsuffixed(i);
                    at(n, quote!(#place[#i]));
                }
            }
            Output::Matrix(rows) => {
                for (i, row) in rows.iter().enumerate() {
                    for (j, &n) in row.iter().enumerate() {
                        let (i, j) = (Literal::usize_unsuffixed(i), Literal::usize_unsuffixed(j));
                        at(n, quote!(#place[#i][#j]));
                    }
                }
            }
            Output::Tuple(items) => {
                for (k, item) in items.iter().enumerate() {
                    let k = syn::Index::from(k);
                    walk(item, &quote!(#place.#k), acc);
                }
            }
            Output::Stack(items) => {
                for (k, item) in items.iter().enumerate() {
                    let k = Literal::usize_unsuffixed(k);
                    walk(item, &quote!(#place[#k]), acc);
                }
            }
            Output::Solved(s) => walk(&s.returned(), place, acc),
        }
    }
    let mut all = Vec::new();
    walk(output, &quote!((*out)), &mut all);
    let Writes::Sparse { upper_triangle } = writes else {
        return all;
    };
    // The entries below the diagonal of a symmetric matrix: the output is one matrix,
    // walked row by row.
    let below_diagonal: Vec<bool> = match output {
        Output::Matrix(rows) if upper_triangle => rows
            .iter()
            .enumerate()
            .flat_map(|(i, row)| (0..row.len()).map(move |j| j < i))
            .collect(),
        _ => vec![false; all.len()],
    };
    let zero = Op::Const(crate::sym::Const::new(0.0));
    all.into_iter()
        .zip(below_diagonal)
        .filter(|((n, _), below)| !below && ops[n.index()] != zero)
        .map(|(write, _)| write)
        .collect()
}

/// The lints a generated function allows: it is long, its constants are printed to the
/// last digit, and its names are `v0`, `v1`, ...
fn generated_allows() -> TokenStream {
    quote! {
        #[allow(
            clippy::too_many_lines,
            clippy::approx_constant,
            clippy::excessive_precision,
            clippy::unreadable_literal,
            clippy::similar_names,
            clippy::many_single_char_names,
            clippy::eq_op
        )]
    }
}

/// The emitted function's parameters, `name: &[T; len]` for each of `spec.args`, with a
/// leading underscore for an array that no piece reads, nor any output that is a leaf (read
/// by the function itself when the pieces hand their outputs back).
fn function_params(ops: &[Op], spec: &FunctionSpec, plan: &Plan) -> Vec<TokenStream> {
    let used = |array: Array| {
        plan.pieces.iter().any(|p| p.arrays.contains(&array))
            || plan
                .output_leaves
                .iter()
                .any(|n| matches!(ops[n.index()], Op::Input(r) if r.array == array))
    };
    spec.args
        .iter()
        .map(|arg| {
            let ident = if used(arg.array) {
                format_ident!("{}", arg.array.name())
            } else {
                format_ident!("_{}", arg.array.name())
            };
            let len = Literal::usize_unsuffixed(arg.len);
            quote!(#ident: &[T; #len])
        })
        .collect()
}

/// Functions with fewer operations than this, and sines and cosines of at most one
/// angle, run their baseline copy only: the run-time choice and the call it costs (a
/// nanosecond or two) would outweigh what the wide copy saves.
pub(crate) const MIN_DISPATCHED_OPS: usize = 32;

/// Whether a function of `count` operations gets the AVX2 + FMA copy and the run-time
/// choice between the two: from [`MIN_DISPATCHED_OPS`] operations, or with two angles'
/// sines and cosines (the wide copy takes four angles per instruction).
fn worth_dispatching(count: &OpCount) -> bool {
    count.total() >= MIN_DISPATCHED_OPS || count.trig > 2
}

/// `name: &[T; len]` parameters for the input arrays `arrays` (lengths from `spec.args`),
/// and the names as arguments.
fn array_params(arrays: &BTreeSet<Array>, spec: &FunctionSpec) -> (Vec<TokenStream>, Vec<Ident>) {
    arrays
        .iter()
        .map(|&array| {
            let a = format_ident!("{}", array.name());
            let len = spec
                .args
                .iter()
                .find(|arg| arg.array == array)
                .map_or(0, |arg| arg.len);
            let len = Literal::usize_unsuffixed(len);
            (quote!(#a: &[T; #len]), a)
        })
        .unzip()
}

/// `#[doc]` attributes: the description, a blank line, and the op count (with the loop's
/// share for an [`Output::Solved`]).
fn doc_attrs(doc: &str, count: &OpCount, output: &Output) -> Vec<TokenStream> {
    let mut lines: Vec<String> = doc.lines().map(|l| format!(" {l}")).collect();
    if !lines.is_empty() {
        lines.push(String::new());
    }
    let of_which = match output {
        Output::Solved(s) => {
            let (mul, add) = s.loop_ops();
            format!(" ({mul} mul and {add} add of them in the loop over columns)")
        }
        _ => String::new(),
    };
    lines.push(format!(" Op count: {count}{of_which}."));
    lines.iter().map(|l| quote!(#[doc = #l])).collect()
}

/// What a piece returns (a value, its type, or the pattern binding it): the next piece's
/// carry and the outputs it hands back, a pair when there are both.
fn carry_and_outputs(carry: Option<TokenStream>, outputs: Option<TokenStream>) -> TokenStream {
    match (carry, outputs) {
        (Some(carry), Some(outputs)) => quote!((#carry, #outputs)),
        (Some(one), None) | (None, Some(one)) => one,
        (None, None) => quote!(()),
    }
}

/// `[vA, vB, …]`: the variables of `nodes`, as an array expression or pattern.
fn node_array(nodes: &[Node]) -> TokenStream {
    let names = nodes.iter().map(|&n| var(n));
    quote!([#(#names),*])
}

/// The variable holding `node`'s value.
fn var(node: Node) -> Ident {
    format_ident!("{}", node.to_string())
}

/// The printed pieces of a [`Plan`].
impl Plan {
    /// The number of scalars carrying `nodes` between pieces: four for a packed value.
    fn carry_len(&self, nodes: &[Node]) -> usize {
        nodes
            .iter()
            .map(|n| if self.packed[n.index()] { 4 } else { 1 })
            .sum()
    }

    /// `[vA, vB.0[0], vB.0[1], vB.0[2], vB.0[3], …]`: `nodes` as the carry array, a packed
    /// value as its four lanes.
    fn carry_value(&self, nodes: &[Node]) -> TokenStream {
        let entries = nodes.iter().flat_map(|&n| {
            let v = var(n);
            if self.packed[n.index()] {
                (0..4_usize)
                    .map(|k| {
                        let k = Literal::usize_unsuffixed(k);
                        quote!(#v.0[#k])
                    })
                    .collect()
            } else {
                vec![quote!(#v)]
            }
        });
        quote!([#(#entries),*])
    }

    /// `let [vA, vB_0, …] = *carry;`, then each packed value rebuilt from its lanes.
    fn carry_bindings(&self, nodes: &[Node]) -> Vec<TokenStream> {
        let runtime = crate::runtime_path();
        let mut names = Vec::new();
        let mut packs = Vec::new();
        for &n in nodes {
            let v = var(n);
            if self.packed[n.index()] {
                let lanes: Vec<Ident> = (0..4).map(|k| format_ident!("{v}_{k}")).collect();
                names.extend(lanes.iter().map(|l| quote!(#l)));
                packs.push(quote!(let #v = #runtime::pack::P4([#(#lanes),*]);));
            } else {
                names.push(quote!(#v));
            }
        }
        let mut stmts = vec![quote!(let [#(#names),*] = *carry;)];
        stmts.extend(packs);
        stmts
    }

    /// The statements of piece `p` and its result: the next piece's carry, or `output`.
    fn piece_body(&self, ops: &[Op], p: usize, output: &Output) -> TokenStream {
        let piece = &self.pieces[p];
        let stmts = self.piece_statements(ops, p, &HashMap::new());
        let result = if self.returns_output(p) {
            output.expr_in_kernel()
        } else {
            let carry = self
                .pieces
                .get(p + 1)
                .map(|next| self.carry_value(&next.carry_in));
            let outputs = (!piece.outputs.is_empty()).then(|| node_array(&piece.outputs));
            carry_and_outputs(carry, outputs)
        };
        quote!(#(#stmts)* #result)
    }

    /// The statements of piece `p`: its carry bound to names, the leaves (inputs and
    /// constants, in id order), then the steps in schedule order, each followed by the
    /// writes of the values it defines into their `places` in a `_into` function's `out`
    /// (none for a function that returns its output).
    fn piece_statements(
        &self,
        ops: &[Op],
        p: usize,
        places: &HashMap<Node, Vec<TokenStream>>,
    ) -> Vec<TokenStream> {
        let piece = &self.pieces[p];
        let writes = |n: Node| {
            let v = var(n);
            places
                .get(&n)
                .into_iter()
                .flatten()
                .map(move |place| quote!(#place = #v;))
        };
        let mut stmts = Vec::new();
        if !piece.carry_in.is_empty() {
            stmts.extend(self.carry_bindings(&piece.carry_in));
        }
        for &n in &piece.leaves {
            stmts.push(let_node(n, ops[n.index()], &self.packed));
            stmts.extend(writes(n));
        }
        for step in &piece.steps {
            stmts.push(let_step(step, ops, &self.fused, &self.packed));
            for n in step.defines() {
                stmts.extend(writes(n));
            }
        }
        stmts
    }

    /// The statements of piece `p` of a `_into` function: those of [`Plan::piece_body`],
    /// each followed by the writes of the values it defines into their `places` in `out`,
    /// then the next piece's carry (the plan hands its outputs back, so none is carried)
    /// and the outputs in `kept` (a solve's factor and pivots, which the function reads).
    fn piece_body_into(
        &self,
        ops: &[Op],
        p: usize,
        places: &HashMap<Node, Vec<TokenStream>>,
        kept: &[Node],
    ) -> TokenStream {
        let stmts = self.piece_statements(ops, p, places);
        // A piece before the last returns the values the next one reads, and each piece
        // the outputs it computes that the function needs after the pieces (`kept`).
        let carry = self
            .pieces
            .get(p + 1)
            .map(|next| self.carry_value(&next.carry_in));
        let kept = (!kept.is_empty()).then(|| node_array(kept));
        let result = match (&carry, &kept) {
            (None, None) => None,
            _ => Some(carry_and_outputs(carry, kept)),
        };
        quote!(#(#stmts)* #result)
    }

    /// Whether piece `p` returns the function's output: the last piece, unless the pieces
    /// hand their outputs back ([`Plan::hands_back`]).
    fn returns_output(&self, p: usize) -> bool {
        !self.hands_back && p + 1 == self.pieces.len()
    }

    /// What piece `p` of a split function returns (see [`Plan::piece_body`]): the output
    /// ([`Plan::returns_output`]), or the next piece's carry and the outputs it computes,
    /// each `[T; K]`, as a pair when it has both.
    fn piece_return_type(&self, p: usize, spec: &FunctionSpec) -> TokenStream {
        if self.returns_output(p) {
            return spec.output.ty();
        }
        let array = |k: usize| {
            let k = Literal::usize_unsuffixed(k);
            quote!([T; #k])
        };
        let carry = self
            .pieces
            .get(p + 1)
            .map(|next| array(self.carry_len(&next.carry_in)));
        let outputs = self.pieces[p].outputs.len();
        let outputs = (outputs > 0).then(|| array(outputs));
        carry_and_outputs(carry, outputs)
    }

    /// The pattern that binds what piece `p` returns in the emitted function: `carry_{p+1}`
    /// and the names of the outputs it computes.
    fn piece_result_pattern(&self, p: usize) -> TokenStream {
        let carry = self.pieces.get(p + 1).map(|_| {
            let next = format_ident!("carry_{}", p + 1);
            quote!(#next)
        });
        let outputs = &self.pieces[p].outputs;
        let outputs = (!outputs.is_empty()).then(|| node_array(outputs));
        carry_and_outputs(carry, outputs)
    }

    /// [`Plan::piece_body`] as the baseline copy alone: after `const WIDE: bool = false;`
    /// when a sine-cosine batch or a solve loop reads it, and after
    /// `let isa = dynamics_runtime::isa::Isa::BASELINE;` when a fused product or a solve
    /// loop does.
    fn baseline_body(&self, ops: &[Op], p: usize, output: &Output) -> TokenStream {
        let body = self.piece_body(ops, p, output);
        let prelude = self.baseline_prelude(p, output);
        quote!(#prelude #body)
    }

    /// What [`Plan::baseline_body`] puts before the statements of piece `p`.
    fn baseline_prelude(&self, p: usize, output: &Output) -> TokenStream {
        let reads_wide = self.solves(p, output)
            || self.pieces[p]
                .steps
                .iter()
                .any(|s| matches!(s, Step::Batch(_)));
        let runtime = crate::runtime_path();
        let wide = reads_wide.then(|| {
            quote!(
                const WIDE: bool = false;
            )
        });
        let isa = self
            .reads_isa(p, output)
            .then(|| quote!(let isa = #runtime::isa::Isa::BASELINE;));
        quote!(#wide #isa)
    }

    /// Whether piece `p` hands its kernel's `dynamics_runtime::isa::Isa` value to anything:
    /// a fused product, or the solve loop of an [`Output::Solved`] it returns.
    fn reads_isa(&self, p: usize, output: &Output) -> bool {
        self.solves(p, output)
            || self.pieces[p]
                .steps
                .iter()
                .any(|s| matches!(s, Step::One(n) if self.fused.contains_key(n)))
    }

    /// Whether piece `p` runs the solve loop of an [`Output::Solved`]: it returns the output.
    fn solves(&self, p: usize, output: &Output) -> bool {
        self.returns_output(p) && matches!(output, Output::Solved(_))
    }

    /// The first parameter of piece `p`'s kernel: its copy's `dynamics_runtime::isa::Isa`
    /// value, `_isa` when the piece has nothing to hand it to.
    fn isa_param(&self, p: usize, output: &Output) -> TokenStream {
        let runtime = crate::runtime_path();
        let name = if self.reads_isa(p, output) {
            format_ident!("isa")
        } else {
            format_ident!("_isa")
        };
        quote!(#name: #runtime::isa::Isa<WIDE>)
    }

    /// The parameters of piece `p`'s kernel after its `isa` (the arrays it reads, then its
    /// `carry`), and the arguments the emitted function passes for them.
    fn piece_params(&self, p: usize, spec: &FunctionSpec) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let piece = &self.pieces[p];
        let (mut params, args) = array_params(&piece.arrays, spec);
        let mut args: Vec<TokenStream> = args.iter().map(|a| quote!(#a)).collect();
        if !piece.carry_in.is_empty() {
            let carry = format_ident!("carry_{p}");
            let k = Literal::usize_unsuffixed(self.carry_len(&piece.carry_in));
            params.push(quote!(carry: &[T; #k]));
            args.push(quote!(&#carry));
        }
        (params, args)
    }

    /// The body of a split function: the pieces as nested kernels, then their chain, each
    /// piece run by `T::run_piece` (or, with `spec.dispatch` off, the baseline copies as
    /// `#[inline(never)]` functions called in turn).
    fn chained_pieces(&self, ops: &[Op], spec: &FunctionSpec) -> TokenStream {
        let trait_ = &spec.scalar_trait;
        let n = self.pieces.len();
        let mut fns = Vec::new();
        let mut calls = Vec::new();
        for p in 0..n {
            let part = format_ident!("part_{}", p + 1);
            let (mut params, args) = self.piece_params(p, spec);
            let ret = self.piece_return_type(p, spec);
            let doc = format!(" Piece {} of {n}.", p + 1);
            let run = if spec.dispatch {
                let body = self.piece_body(ops, p, &spec.output);
                params.insert(0, self.isa_param(p, &spec.output));
                fns.push(quote! {
                    #[doc = #doc]
                    #[inline(always)]
                    fn #part<T: #trait_, const WIDE: bool>(#(#params),*) -> #ret {
                        #body
                    }
                });
                quote! {
                    T::run_piece(
                        #[inline(always)]
                        |isa| #part::<T, true>(isa #(, #args)*),
                        #[inline(always)]
                        |isa| #part::<T, false>(isa #(, #args)*),
                    )
                }
            } else {
                let body = self.baseline_body(ops, p, &spec.output);
                fns.push(quote! {
                    #[doc = #doc]
                    #[inline(never)]
                    fn #part<T: #trait_>(#(#params),*) -> #ret {
                        #body
                    }
                });
                quote!(#part(#(#args),*))
            };
            if self.returns_output(p) {
                calls.push(run);
            } else {
                let pattern = self.piece_result_pattern(p);
                calls.push(quote!(let #pattern = #run;));
            }
        }
        if !self.hands_back {
            return quote!(#(#fns)* #(#calls)*);
        }
        let leaves = self
            .output_leaves
            .iter()
            .map(|&n| let_node(n, ops[n.index()], &self.packed));
        // Built outside the kernels: a solve loop runs in the copy `T::run_kernel` chooses,
        // or in the baseline copy when the function has only that one.
        let output = match &spec.output {
            Output::Solved(_) if !spec.dispatch => {
                let solved = spec.output.expr_in_kernel();
                let runtime = crate::runtime_path();
                quote!({
                    const WIDE: bool = false;
                    let isa = #runtime::isa::Isa::BASELINE;
                    #solved
                })
            }
            _ => spec.output.expr(),
        };
        quote!(#(#fns)* #(#calls)* #(#leaves)* #output)
    }
}

impl Plan {
    /// The body of a split `_into` function (a plan that hands its outputs back): each
    /// piece a kernel taking `out` too, writing the outputs it computes and returning the
    /// next piece's carry (and a solve's factor and pivots it computes), then the outputs
    /// that are leaves written by the function itself, then the solve in `out`, if any.
    fn chained_pieces_into(
        &self,
        ops: &[Op],
        spec: &FunctionSpec,
        places: &HashMap<Node, Vec<TokenStream>>,
    ) -> TokenStream {
        let trait_ = &spec.scalar_trait;
        let ret = spec.output.ty();
        let n = self.pieces.len();
        // What the solve after the pieces reads besides `out`: its factor and pivots.
        let solve_reads: BTreeSet<Node> = match &spec.output {
            Output::Solved(s) => s.factor.iter().chain(&s.inverse_pivot).copied().collect(),
            _ => BTreeSet::new(),
        };
        // The outputs that are leaves are written once, by the function after the pieces:
        // a piece that reads one as an operand does not write it too.
        let piece_places: HashMap<Node, Vec<TokenStream>> = places
            .iter()
            .filter(|(node, _)| !self.output_leaves.contains(node))
            .map(|(&node, writes)| (node, writes.clone()))
            .collect();
        let mut fns = Vec::new();
        let mut calls = Vec::new();
        for (p, piece) in self.pieces.iter().enumerate() {
            let part = format_ident!("part_{}", p + 1);
            let (mut params, args) = self.piece_params(p, spec);
            params.push(quote!(out: &mut #ret));
            let kept: Vec<Node> = piece
                .outputs
                .iter()
                .copied()
                .filter(|n| solve_reads.contains(n))
                .collect();
            let array = |k: usize| {
                let k = Literal::usize_unsuffixed(k);
                quote!([T; #k])
            };
            let carry_type = self
                .pieces
                .get(p + 1)
                .map(|next| array(self.carry_len(&next.carry_in)));
            let kept_type = (!kept.is_empty()).then(|| array(kept.len()));
            let returned = carry_and_outputs(carry_type, kept_type);
            let doc = format!(" Piece {} of {n}.", p + 1);
            let body = self.piece_body_into(ops, p, &piece_places, &kept);
            let run = if spec.dispatch {
                params.insert(0, self.isa_param(p, &spec.output));
                fns.push(quote! {
                    #[doc = #doc]
                    #[inline(always)]
                    fn #part<T: #trait_, const WIDE: bool>(#(#params),*) -> #returned {
                        #body
                    }
                });
                quote! {
                    T::run_piece_into(
                        out,
                        #[inline(always)]
                        |isa, out| #part::<T, true>(isa #(, #args)*, out),
                        #[inline(always)]
                        |isa, out| #part::<T, false>(isa #(, #args)*, out),
                    )
                }
            } else {
                let prelude = self.baseline_prelude(p, &spec.output);
                fns.push(quote! {
                    #[doc = #doc]
                    #[inline(never)]
                    fn #part<T: #trait_>(#(#params),*) -> #returned {
                        #prelude
                        #body
                    }
                });
                quote!(#part(#(#args,)* out))
            };
            let next = self.pieces.get(p + 1).map(|_| {
                let next = format_ident!("carry_{}", p + 1);
                quote!(#next)
            });
            let kept = (!kept.is_empty()).then(|| node_array(&kept));
            calls.push(match (&next, &kept) {
                (None, None) => quote!(#run;),
                _ => {
                    let pattern = carry_and_outputs(next, kept);
                    quote!(let #pattern = #run;)
                }
            });
        }
        let mut leaves = Vec::new();
        for &node in &self.output_leaves {
            leaves.push(let_node(node, ops[node.index()], &self.packed));
            let v = var(node);
            let writes = places.get(&node).into_iter().flatten();
            leaves.extend(writes.map(|place| quote!(#place = #v;)));
        }
        let solve = match &spec.output {
            Output::Solved(s) => Some(tree_solve_into(s, false, spec.dispatch)),
            _ => None,
        };
        quote!(#(#fns)* #(#calls)* #(#leaves)* #solve)
    }
}

/// `vN`, or `P4::splat(vN)` when the operation is `packed` and `vN` a scalar.
fn operand(n: Node, packed: bool, is_packed: &[bool]) -> TokenStream {
    let v = var(n);
    if packed && !is_packed[n.index()] {
        let runtime = crate::runtime_path();
        quote!(#runtime::pack::P4::splat(#v))
    } else {
        quote!(#v)
    }
}

/// The live non-leaf nodes as statements, in [`crate::schedule`]'s depth-first order: the
/// sines and cosines of two or more inputs merged into one [`Step::Batch`] at the first of
/// them, other `let vN = …;` for a single node.
fn let_node(node: Node, op: Op, is_packed: &[bool]) -> TokenStream {
    let v = var(node);
    let expr = match op {
        Op::Const(c) => {
            let lit = f64_literal(c.value());
            quote!(T::from_f64(#lit))
        }
        Op::Input(_) => input_expr(op),
        Op::Add(a, b) => bin(a, quote!(+), b, is_packed),
        Op::Sub(a, b) => bin(a, quote!(-), b, is_packed),
        Op::Mul(a, b) => bin(a, quote!(*), b, is_packed),
        Op::Div(a, b) => bin(a, quote!(/), b, is_packed),
        Op::Neg(a) => {
            let a = var(a);
            quote!(-#a)
        }
        Op::Sin(a) => call("sin", a),
        Op::Cos(a) => call("cos", a),
        Op::Sqrt(a) => call("sqrt", a),
        Op::Pack(a, b, c, d) => {
            let runtime = crate::runtime_path();
            let (a, b, c, d) = (var(a), var(b), var(c), var(d));
            quote!(#runtime::pack::P4([#a, #b, #c, #d]))
        }
        Op::Lane(a, k) => {
            let a = var(a);
            let k = Literal::u8_unsuffixed(k);
            quote!(#a.0[#k])
        }
    };
    quote!(let #v = #expr;)
}

/// The statement of a step.
fn let_step(
    step: &Step,
    ops: &[Op],
    fused: &HashMap<Node, Fused>,
    is_packed: &[bool],
) -> TokenStream {
    match step {
        Step::One(n) => match fused.get(n) {
            Some(f) => {
                let v = var(*n);
                let packed = is_packed[n.index()];
                let (x, y, c) = (
                    operand(f.x, packed, is_packed),
                    operand(f.y, packed, is_packed),
                    operand(f.c, packed, is_packed),
                );
                let x = if f.negate_product {
                    quote!(-#x)
                } else {
                    quote!(#x)
                };
                let c = if f.negate_addend {
                    quote!(-#c)
                } else {
                    quote!(#c)
                };
                if packed {
                    let runtime = crate::runtime_path();
                    quote!(let #v = #runtime::pack::P4::mul_add_on(#x, #y, #c, isa);)
                } else {
                    quote!(let #v = isa.mul_add(#x, #y, #c);)
                }
            }
            None => let_node(*n, ops[n.index()], is_packed),
        },
        Step::SinCos { sin, cos, arg } => {
            let (s, c, x) = (var(*sin), var(*cos), var(*arg));
            quote!(let (#s, #c) = T::sin_cos(#x);)
        }
        Step::Batch(angles) => {
            let name = |n: Option<Node>| {
                n.map_or_else(
                    || quote!(_),
                    |n| {
                        let v = var(n);
                        quote!(#v)
                    },
                )
            };
            let sins = angles.iter().map(|a| name(a.sin));
            let coss = angles.iter().map(|a| name(a.cos));
            let args = angles.iter().map(|a| input_expr(ops[a.arg.index()]));
            let n = Literal::usize_unsuffixed(angles.len());
            quote!(let ([#(#sins),*], [#(#coss),*]) = T::sin_cos_array_for::<WIDE, #n>([#(#args),*]);)
        }
    }
}

/// `q[3]` for an input leaf.
fn input_expr(op: Op) -> TokenStream {
    match op {
        Op::Input(r) => {
            let array = format_ident!("{}", r.array.name());
            let index = Literal::u32_unsuffixed(r.index);
            quote!(#array[#index])
        }
        other => unreachable!("only inputs are batched, not {other:?}"),
    }
}

fn bin(a: Node, op: TokenStream, b: Node, is_packed: &[bool]) -> TokenStream {
    let packed = is_packed[a.index()] || is_packed[b.index()];
    let (a, b) = (operand(a, packed, is_packed), operand(b, packed, is_packed));
    quote!(#a #op #b)
}

fn call(f: &str, a: Node) -> TokenStream {
    let f = format_ident!("{f}");
    let a = var(a);
    quote!(T::#f(#a))
}

/// An `f64` literal that round-trips exactly: Rust's `{:?}` formatting is the shortest
/// decimal that parses back to the same value. Negative values are emitted as `-lit`;
/// non-finite values as the `f64` associated constants.
fn f64_literal(x: f64) -> TokenStream {
    if x.is_nan() {
        quote!(f64::NAN)
    } else if x == f64::INFINITY {
        quote!(f64::INFINITY)
    } else if x == f64::NEG_INFINITY {
        quote!(f64::NEG_INFINITY)
    } else {
        let lit = syn::LitFloat::new(&format!("{:?}_f64", x.abs()), Span::call_site());
        if x.is_sign_negative() {
            quote!(-#lit)
        } else {
            quote!(#lit)
        }
    }
}

/// A wrapper of the function `spec` describes taking and returning nalgebra types:
/// `SVector<T, N>` for vector arguments and results, `SMatrix<T, R, C>` for matrix results,
/// named `<name>_na`. Arguments are borrowed without copying (an `SVector`'s storage is the
/// array the straight-line function takes); results are moved into nalgebra storage.
/// `nalgebra` is the path of the nalgebra crate as the generated code sees it.
#[must_use]
pub(crate) fn nalgebra_wrapper(spec: &FunctionSpec, nalgebra: &TokenStream) -> TokenStream {
    let name = &spec.name;
    let wrapper = format_ident!("{}_na", spec.name);
    let vis = &spec.vis;
    let trait_ = &spec.scalar_trait;
    let params = spec.args.iter().map(|arg| {
        let ident = format_ident!("{}", arg.array.name());
        let len = Literal::usize_unsuffixed(arg.len);
        quote!(#ident: &#nalgebra::SVector<T, #len>)
    });
    let forwarded = spec.args.iter().map(|arg| {
        let ident = format_ident!("{}", arg.array.name());
        quote!(&#ident.data.0[0])
    });
    let call = quote!(Self::#name(#(#forwarded),*));
    // A solve loop returns its matrix, or a tuple of them, as the straight-line code would.
    let returned = match &spec.output {
        Output::Solved(s) => s.returned(),
        other => other.clone(),
    };
    let (ret, body) = match &returned {
        Output::Scalar(_) => (quote!(T), call),
        Output::Vector(v) => {
            let n = Literal::usize_unsuffixed(v.len());
            (
                quote!(#nalgebra::SVector<T, #n>),
                quote!(#nalgebra::SVector::from(#call)),
            )
        }
        Output::Matrix(rows) => {
            let r = Literal::usize_unsuffixed(rows.len());
            let c = Literal::usize_unsuffixed(rows.first().map_or(0, Vec::len));
            // The rows array, read as column-major storage, is the transpose.
            (
                quote!(#nalgebra::SMatrix<T, #r, #c>),
                quote!(#nalgebra::SMatrix::<T, #c, #r>::from_array_storage(#nalgebra::ArrayStorage(#call)).transpose()),
            )
        }
        Output::Tuple(_) | Output::Stack(_) | Output::Solved(_) => return TokenStream::new(),
    };
    let doc = format!(" [`Self::{name}`] with nalgebra vectors and matrices.");
    quote! {
        #[doc = #doc]
        #[inline]
        #[must_use]
        #vis fn #wrapper<T: #trait_>(#(#params),*) -> #ret {
            #body
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{f64_literal, function_into, written_nodes, Writes};
    use crate::ir::{Arg, FunctionSpec, Output, Sweeps, TreeSolve};
    use crate::passes::{fusion, signs};
    use crate::schedule::Plan;
    use crate::sym::{Array, Graph, InputRef, Node};
    use proc_macro2::TokenStream;
    use std::fmt::Write as _;

    /// The function as the pipeline prints it: fusion, schedule, print.
    fn emit_function(g: &Graph, spec: &FunctionSpec) -> TokenStream {
        let plan = Plan::new(g, spec, fusion::fuse(g, &spec.output));
        super::function(g, spec, &plan)
    }

    fn pretty(tokens: TokenStream) -> String {
        let item: syn::ItemFn = syn::parse2(tokens).expect("emitted code parses as a function");
        prettyplease::unparse(&syn::File {
            shebang: None,
            attrs: Vec::new(),
            items: vec![syn::Item::Fn(item)],
        })
    }

    fn spec(name: &str, args: &[(Array, usize)], output: Output) -> FunctionSpec {
        let args = args
            .iter()
            .map(|&(array, len)| Arg { array, len })
            .collect();
        FunctionSpec::new(name, syn::parse_quote!(Scalar), args, output)
    }

    /// A product that one sum or difference alone uses is folded into it, in each of the
    /// three forms; a product used twice is computed once and not folded.
    #[test]
    fn products_fold_into_their_only_sum() {
        let g = Graph::new();
        let (x, y, c) = (
            g.input(Array::Q, 0),
            g.input(Array::Q, 1),
            g.input(Array::Q, 2),
        );
        let (p1, p2, p3) = (g.mul(x, y), g.mul(x, c), g.mul(y, c));
        let shared = g.mul(c, c);
        let outputs = vec![
            g.add(p1, c),     // x·y + c
            g.sub(p2, y),     // x·c − y
            g.sub(x, p3),     // x − y·c
            g.add(shared, x), // c·c + x, but c·c is an output too
            shared,
        ];
        // settled as the expansion's functions are (x·c − y is built as −(y − x·c))
        let output = signs::settle(&g, &Output::Vector(outputs));
        let spec = spec("f", &[(Array::Q, 3)], output);
        let text = pretty(emit_function(&g, &spec));
        for line in [
            "isa.mul_add(v0, v1, v2)",
            "isa.mul_add(v0, v2, -v1)",
            "isa.mul_add(-v1, v2, v0)",
        ] {
            assert!(text.contains(line), "{line} missing in\n{text}");
        }
        assert_eq!(text.matches("mul_add").count(), 3, "{text}");
        assert!(text.contains("v2 * v2"), "{text}");
    }

    /// Pendulum-like: τ = m·l²·a + m·g·l·sin q, plus cos q·v as a second output.
    #[test]
    fn golden_tiny_function() {
        let g = Graph::new();
        let q = g.input(Array::Q, 0);
        let v = g.input(Array::V, 0);
        let a = g.input(Array::A, 0);
        let (s, c) = (g.sin(q), g.cos(q));
        let tau = g.add(
            g.mul(g.constant(0.5), a),
            g.mul(g.constant(-9.81), s), // negative constant: shares nothing, emits a neg
        );
        let second = g.mul(c, v);
        let mut spec = spec(
            "pendulum",
            &[(Array::Q, 1), (Array::V, 1), (Array::A, 1), (Array::Tau, 1)],
            Output::Vector(vec![tau, second, q, g.constant(0.1)]),
        );
        spec.doc = "Inverse dynamics of a pendulum.\nSecond line.".to_string();
        let text = pretty(emit_function(&g, &spec));
        let expected = r"/// Inverse dynamics of a pendulum.
/// Second line.
///
/// Op count: 3 mul, 1 add, 0 div, 2 trig.
#[allow(
    clippy::too_many_lines,
    clippy::approx_constant,
    clippy::excessive_precision,
    clippy::unreadable_literal,
    clippy::similar_names,
    clippy::many_single_char_names,
    clippy::eq_op
)]
#[must_use]
pub fn pendulum<T: Scalar>(q: &[T; 1], v: &[T; 1], a: &[T; 1], _tau: &[T; 1]) -> [T; 4] {
    let isa = ::dynamics_runtime::isa::Isa::BASELINE;
    let v0 = q[0];
    let v1 = v[0];
    let v2 = a[0];
    let v5 = T::from_f64(0.5_f64);
    let v8 = T::from_f64(9.81_f64);
    let v13 = T::from_f64(0.1_f64);
    let (v3, v4) = T::sin_cos(v0);
    let v12 = v1 * v4;
    let v9 = v3 * v8;
    let v11 = isa.mul_add(v2, v5, -v9);
    [v11, v12, v0, v13]
}
";
        assert_eq!(text, expected, "got:\n{text}");
    }

    /// Statements come depth first from the last output: one output's chain of products is
    /// computed whole before the next one's starts (not interleaved, as in creation order),
    /// and of two operands the one that needs more registers comes first.
    #[test]
    fn statements_are_ordered_depth_first_from_the_last_output() {
        let g = Graph::new();
        let q: Vec<Node> = (0..4).map(|k| g.input(Array::Q, k)).collect();
        // Created interleaved: a1, b1, a2, b2, a3, b3.
        let (mut a, mut b) = (q[0], q[1]);
        for _ in 0..3 {
            a = g.mul(a, q[2]);
            b = g.mul(b, q[3]);
        }
        // (q0 + q1) is shallower than the chain b, so b comes first among c's operands.
        let c = g.mul(g.add(q[0], q[1]), b);
        let s = spec("f", &[(Array::Q, 4)], Output::Vector(vec![a, c]));
        let text = pretty(emit_function(&g, &s));
        let position = |n: Node| {
            text.find(&format!("let {} =", super::var(n)))
                .unwrap_or_else(|| panic!("{} defined:\n{text}", super::var(n)))
        };
        let b_chain = [b, c].map(position);
        let a_chain = position(a);
        let sum = position(g.add(q[0], q[1]));
        assert!(b_chain.iter().all(|&p| p < a_chain), "{text}");
        assert!(position(b) < sum, "{text}");
        // a's chain is consecutive: a1, a2, a3 with nothing between them.
        let a1 = position(g.mul(q[0], q[2]));
        let between = &text[a1..a_chain];
        assert_eq!(between.matches("let ").count(), 2, "{text}");
    }

    /// The sines and cosines of several inputs come from one `sin_cos_array`, the inputs
    /// read in place, `_` for the values no one reads, at the position of the first of them.
    #[test]
    fn sines_and_cosines_of_inputs_are_batched() {
        let g = Graph::new();
        let v0 = g.input(Array::V, 0);
        let (q0, q1, q2) = (
            g.input(Array::Q, 0),
            g.input(Array::Q, 1),
            g.input(Array::Q, 2),
        );
        let first = g.mul(v0, g.sin(q2));
        let rest = [g.cos(q0), g.sin(q1), g.cos(q1), g.sin(g.add(q0, q1))];
        let mut outputs = vec![first];
        outputs.extend(rest);
        let s = spec(
            "f",
            &[(Array::Q, 3), (Array::V, 1)],
            Output::Vector(outputs),
        );
        let text = pretty(emit_function(&g, &s));
        let body: Vec<&str> = text
            .lines()
            .skip_while(|l| !l.starts_with("pub fn"))
            .collect();
        assert_eq!(
            body[1..17],
            [
                "    #[inline(always)]",
                "    fn kernel<T: Scalar, const WIDE: bool>(",
                "        _isa: ::dynamics_runtime::isa::Isa<WIDE>,",
                "        q: &[T; 3],",
                "        v: &[T; 1],",
                "    ) -> [T; 5] {",
                "        let v0 = v[0];",
                "        let v1 = q[0];",
                "        let v2 = q[1];",
                "        let v9 = v1 + v2;",
                "        let v10 = T::sin(v9);",
                "        let ([_, v7, v4], [v6, v8, _]) = T::sin_cos_array_for::<",
                "            WIDE,",
                "            3,",
                "        >([q[0], q[1], q[2]]);",
                "        let v5 = v0 * v4;",
            ][..],
            "got:\n{text}"
        );
        // Three angles: worth the AVX2 + FMA copy and the run-time choice.
        assert!(
            text.contains("|isa| kernel::<T, true>(isa, q, v),")
                && text.contains("|isa| kernel::<T, false>(isa, q, v),"),
            "{text}"
        );
        assert!(
            text.contains("let v10 = T::sin(v9);"),
            "a sum's sine is not batched:\n{text}"
        );

        let one = spec(
            "g",
            &[(Array::Q, 3)],
            Output::Vector(vec![g.sin(q0), g.cos(q0)]),
        );
        let text = pretty(emit_function(&g, &one));
        assert!(
            text.contains("T::sin_cos(v1)"),
            "one angle is not batched:\n{text}"
        );
    }

    #[test]
    fn every_output_shape_parses() {
        let g = Graph::new();
        let x = g.input(Array::Q, 0);
        let y = g.input(Array::P, 2);
        let f = g.input(Array::Loads, 5);
        let xy = g.mul(x, g.add(y, f));
        let shapes = [
            Output::Scalar(xy),
            Output::Scalar(x),
            Output::Scalar(g.constant(-2.0)),
            Output::Vector(vec![]),
            Output::Matrix(vec![vec![xy, x], vec![y, g.zero()]]),
            Output::Tuple(vec![
                Output::Matrix(vec![vec![xy]]),
                Output::Vector(vec![x, x]),
                Output::Scalar(y),
            ]),
            Output::Tuple(vec![Output::Scalar(xy)]),
            Output::Stack(vec![
                Output::Tuple(vec![
                    Output::Matrix(vec![vec![xy]]),
                    Output::Vector(vec![x]),
                ]),
                Output::Tuple(vec![Output::Matrix(vec![vec![y]]), Output::Vector(vec![f])]),
            ]),
        ];
        for output in shapes {
            let s = spec(
                "f",
                &[(Array::Q, 1), (Array::P, 3), (Array::Loads, 6)],
                output.clone(),
            );
            let text = pretty(emit_function(&g, &s));
            syn::parse_str::<syn::ItemFn>(&text).expect("pretty text parses again");
        }
        let m = spec(
            "m",
            &[(Array::Q, 1), (Array::P, 3), (Array::Loads, 6)],
            Output::Matrix(vec![vec![xy, x]]),
        );
        assert!(pretty(emit_function(&g, &m)).contains("-> [[T; 2]; 1]"));
        let t = spec(
            "t",
            &[(Array::Q, 1)],
            Output::Tuple(vec![Output::Scalar(x)]),
        );
        assert!(pretty(emit_function(&g, &t)).contains("-> (T,)"));
        let stack = spec(
            "s",
            &[(Array::Q, 1), (Array::P, 3), (Array::Loads, 6)],
            Output::Stack(vec![
                Output::Matrix(vec![vec![xy, x]]),
                Output::Matrix(vec![vec![y, x]]),
            ]),
        );
        assert!(pretty(emit_function(&g, &stack)).contains("-> [[[T; 2]; 1]; 2]"));
    }

    #[test]
    #[should_panic(expected = "not covered")]
    fn an_input_outside_the_arguments_is_a_bug() {
        let g = Graph::new();
        let x = g.input(Array::Q, 3);
        let _ = emit_function(&g, &spec("f", &[(Array::Q, 3)], Output::Scalar(x)));
    }

    #[test]
    fn literals_round_trip_exactly() {
        let mut values = vec![
            0.0,
            1.0,
            -1.0,
            0.1,
            -9.81,
            1.0 / 3.0,
            std::f64::consts::PI,
            1e-7,
            6.02214076e23,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -123_456_789.123_456_79,
        ];
        let mut bits: u64 = 0x0123_4567_89AB_CDEF;
        for _ in 0..1000 {
            bits = bits.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let x = f64::from_bits(bits);
            if x.is_finite() {
                values.push(x);
            }
        }
        for x in values {
            let tokens = f64_literal(x);
            let expr: syn::Expr = syn::parse2(tokens).expect("literal parses");
            let (negative, lit) = match expr {
                syn::Expr::Unary(u) => (true, *u.expr),
                e => (false, e),
            };
            let syn::Expr::Lit(syn::ExprLit {
                lit: syn::Lit::Float(lit),
                ..
            }) = lit
            else {
                panic!("not a float literal: {x:?}");
            };
            assert_eq!(lit.suffix(), "f64");
            let parsed: f64 = lit.base10_parse().expect("parses as f64");
            let parsed = if negative { -parsed } else { parsed };
            assert_eq!(parsed.to_bits(), x.to_bits(), "{x:?} -> {lit}");
        }
        assert_eq!(f64_literal(f64::NAN).to_string(), "f64 :: NAN");
        assert_eq!(
            f64_literal(f64::NEG_INFINITY).to_string(),
            "f64 :: NEG_INFINITY"
        );
    }

    /// A chain that needs values across many statements: x_{i+1} = x_i·cos q_i + sin q_i·x_{i−3}.
    fn long_chain(g: &Graph, n: usize) -> Vec<Node> {
        let mut xs = vec![
            g.input(Array::V, 0),
            g.input(Array::V, 1),
            g.input(Array::V, 2),
        ];
        for i in 0..n {
            let q = g.input(Array::Q, i % 8);
            let k = g.constant(1.0 + i as f64 / 16.0);
            let prev = xs[xs.len() - 1];
            let back = xs[xs.len() - 3];
            let next = g.add(g.mul(prev, g.cos(q)), g.div(g.mul(g.sin(q), back), k));
            xs.push(g.sub(next, g.mul(k, g.sqrt(g.mul(q, q)))));
        }
        vec![
            xs[xs.len() - 1],
            xs[n / 2],
            xs[3],
            g.input(Array::V, 1),
            g.constant(2.5),
        ]
    }

    #[test]
    fn long_functions_are_split_into_pieces() {
        let g = Graph::new();
        let outputs = long_chain(&g, 200);
        let mut s = spec(
            "chain",
            &[(Array::Q, 8), (Array::V, 3)],
            Output::Vector(outputs.clone()),
        );
        s.split_threshold = usize::MAX;
        let whole = pretty(emit_function(&g, &s));
        let statements = whole
            .lines()
            .filter(|l| l.trim_start().starts_with("let "))
            .count();
        s.split_threshold = 300;
        let text = pretty(emit_function(&g, &s));
        let pieces = statements.div_ceil(300);
        assert!(pieces >= 3, "{statements} statements");
        for p in 1..=pieces {
            assert!(
                text.contains(&format!("fn part_{p}<T: Scalar, const WIDE: bool>")),
                "{text}"
            );
        }
        assert!(!text.contains(&format!("fn part_{}", pieces + 1)));
        assert_eq!(text.matches("T::run_piece(").count(), pieces, "{text}");
        assert!(text.contains("let [v"), "later pieces unpack their carry");
        assert!(text.contains("let carry_1 = T::run_piece("), "{text}");
        assert!(
            text.contains("|isa| part_1::<T, true>(isa, q, v),"),
            "{text}"
        );
        assert!(
            text.contains("|isa| part_1::<T, false>(isa, q, v),"),
            "{text}"
        );
        assert!(text.contains(&format!(
            "|isa| part_{pieces}::<T, false>(isa, v, &carry_{}),",
            pieces - 1
        )));
        syn::parse_str::<syn::File>(&text).expect("pretty text parses again");

        s.dispatch = false; // one copy: the pieces as functions of their own, called in turn
        let one = pretty(emit_function(&g, &s));
        assert_eq!(one.matches("#[inline(never)]").count(), pieces, "{one}");
        assert!(one.contains("fn part_1<T: Scalar>("), "{one}");
        assert!(one.contains("let carry_1 = part_1(q, v);"), "{one}");
        assert!(!one.contains("run_piece"), "{one}");

        s.split_threshold = statements; // exactly at the threshold: not split
        assert!(!pretty(emit_function(&g, &s)).contains("fn part_"));
        s.split_threshold = statements - 1;
        assert!(pretty(emit_function(&g, &s)).contains("fn part_2"));
    }

    /// A split `_into` twin writes each entry of `out` once: an output that is a leaf and
    /// also an operand in a piece (`v[1]`, which the chain reads), by the function after
    /// the pieces only.
    #[test]
    fn into_twins_write_each_entry_once() {
        let g = Graph::new();
        let chain = long_chain(&g, 200);
        let zero = g.constant(0.0);
        let at = |i: usize, j: usize| i == 0 && j < chain.len();
        let rows: Vec<Vec<Node>> = (0..6)
            .map(|i| {
                (0..6)
                    .map(|j| if at(i, j) { chain[j] } else { zero })
                    .collect()
            })
            .collect();
        let mut s = spec(
            "chain",
            &[(Array::Q, 8), (Array::V, 3)],
            Output::Matrix(rows),
        );
        s.split_threshold = 300;
        for writes in [
            Writes::Every,
            Writes::Sparse {
                upper_triangle: false,
            },
        ] {
            let written = written_nodes(&g, &s.output, writes);
            let plan = Plan::writing(&g, &s, fusion::fuse(&g, &s.output), &written);
            assert!(plan.pieces.len() > 1);
            let text = pretty(function_into(&g, &s, &plan, writes));
            for i in 0..6 {
                for j in 0..6 {
                    let place = format!("(*out)[{i}][{j}] =");
                    let once = usize::from(at(i, j) || writes == Writes::Every);
                    assert_eq!(text.matches(&place).count(), once, "{place}\n{text}");
                }
            }
            syn::parse_str::<syn::File>(&text).expect("pretty text parses again");
        }
    }

    /// Cut into more than `HAND_BACK_ABOVE_PIECES` pieces, each piece hands back the outputs
    /// it computes and the emitted function builds the output; none is carried.
    #[test]
    fn many_pieces_hand_their_outputs_back() {
        let g = Graph::new();
        let outputs = long_chain(&g, 200);
        let mut s = spec(
            "chain",
            &[(Array::Q, 8), (Array::V, 3)],
            Output::Vector(outputs.clone()),
        );
        s.split_threshold = 100;
        let text = pretty(emit_function(&g, &s));
        let pieces = text.matches("T::run_piece(").count();
        assert!(
            pieces > crate::schedule::HAND_BACK_ABOVE_PIECES,
            "{pieces} pieces"
        );
        // xs[3] (early), xs[n / 2], xs[n - 1] (last piece), then v[1] and 2.5, leaves.
        let [last, middle, early, ..] = outputs[..] else {
            unreachable!()
        };
        assert!(
            text.contains(&format!("let (carry_1, [{early}]) = T::run_piece(")),
            "{text}"
        );
        assert!(
            text.contains(&format!("let [{last}] = T::run_piece(")),
            "{text}"
        );
        assert!(text.contains("let v1 = v[1];"), "{text}");
        assert!(
            text.contains(&format!("[{last}, {middle}, {early}, v1, v")),
            "{text}"
        );
        let carried = text
            .lines()
            .filter(|l| l.contains("= *carry;") && l.contains(&format!("{early},")))
            .count();
        assert_eq!(carried, 0, "an output handed back is not carried: {text}");
        syn::parse_str::<syn::File>(&text).expect("pretty text parses again");
        s.dispatch = false;
        let one = pretty(emit_function(&g, &s));
        assert!(
            one.contains(&format!("let (carry_1, [{early}]) = part_1(q, v);")),
            "{one}"
        );
    }

    /// A solve over a tree of two coordinates (the second the first's child), its factor
    /// and pivots from the chain `xs`, with the right-hand sides `rhs` (one per coordinate).
    fn two_coordinate_solve(xs: &[Node], rhs: Vec<Vec<Node>>, sweeps: Sweeps) -> Output {
        Output::Solved(TreeSolve {
            parents: vec![None, Some(0)],
            factor: vec![xs[1]],
            inverse_pivot: vec![xs[2], xs[4]],
            rhs: vec![rhs],
            sweeps,
        })
    }

    /// A solve loop (`Output::Solved`) runs in the kernel's own copy when a kernel builds
    /// the output, through `T::run_kernel` when a split function builds it outside its
    /// pieces, and in the baseline copy only when the function has no other.
    #[test]
    fn a_solve_loop_runs_in_the_copy_of_its_caller() {
        let g = Graph::new();
        let xs = long_chain(&g, 200);
        let solved = two_coordinate_solve(&xs, vec![vec![xs[0]], vec![xs[3]]], Sweeps::All);
        let mut s = spec("solved", &[(Array::Q, 8), (Array::V, 3)], solved);
        // The text without white space, where the pretty printer may break lines.
        let text = |s: &FunctionSpec| {
            let text = pretty(emit_function(&g, s));
            syn::parse_str::<syn::File>(&text).expect("pretty text parses again");
            text.split_whitespace().collect::<String>()
        };
        let solve_in = |copy: &str| format!("solve_columns::<T,{copy},2,1,1,1");
        s.split_threshold = usize::MAX;
        let whole = text(&s);
        assert!(whole.contains(&solve_in("WIDE")), "{whole}");
        assert_eq!(whole.matches("run_kernel(").count(), 1, "{whole}");
        s.split_threshold = 100;
        let split = text(&s);
        assert!(split.contains(&solve_in("true")), "{split}");
        assert!(split.contains(&solve_in("false")), "{split}");
        s.dispatch = false;
        let one_copy = text(&s);
        assert!(!one_copy.contains("run_kernel("), "{one_copy}");
        assert!(one_copy.contains("constWIDE:bool=false;"), "{one_copy}");
        assert!(one_copy.contains(&solve_in("WIDE")), "{one_copy}");
        assert!(whole.contains("letinverse_pivot:[T;2]"), "{whole}");
    }

    /// The last sweep of M⁻¹ alone reads no pivot (its right-hand sides hold D⁻¹), so no
    /// `inverse_pivot` is bound: unused, it would warn in code written out by the CLI.
    #[test]
    fn the_last_sweep_binds_no_pivots() {
        let g = Graph::new();
        let xs = long_chain(&g, 200);
        let rhs = vec![vec![xs[0], xs[3]], vec![xs[3], xs[4]]];
        let solved = two_coordinate_solve(&xs, rhs, Sweeps::LastOfInverse);
        let mut s = spec("inverse", &[(Array::Q, 8), (Array::V, 3)], solved);
        s.split_threshold = usize::MAX;
        let text = pretty(emit_function(&g, &s));
        assert!(text.contains("solve_lower_columns"), "{text}");
        assert!(text.contains("mirror_upper_triangle"), "{text}");
        assert!(!text.contains("inverse_pivot"), "{text}");
    }

    /// `Scalar` as the runtime defines it, reduced to what generated code uses.
    const SCALAR_STUB: &str = r"
#[allow(dead_code)]
mod rt {
    pub trait Scalar:
        Copy
        + std::ops::Add<Output = Self>
        + std::ops::Sub<Output = Self>
        + std::ops::Mul<Output = Self>
        + std::ops::Div<Output = Self>
        + std::ops::Neg<Output = Self>
    {
        fn from_f64(x: f64) -> Self;
        fn sin(self) -> Self;
        fn cos(self) -> Self;
        fn sqrt(self) -> Self;
        fn sin_cos(self) -> (Self, Self) {
            (self.sin(), self.cos())
        }
        fn sin_cos_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
            let (mut sin, mut cos) = (x, x);
            for i in 0..N {
                (sin[i], cos[i]) = x[i].sin_cos();
            }
            (sin, cos)
        }
        fn mul_add(self, a: Self, b: Self) -> Self {
            self * a + b
        }
        fn sin_cos_array_for<const WIDE: bool, const N: usize>(
            x: [Self; N],
        ) -> ([Self; N], [Self; N]) {
            Self::sin_cos_array(x)
        }
        fn mul_add_on<const WIDE: bool>(
            self,
            a: Self,
            b: Self,
            _isa: crate::dynamics_runtime::isa::Isa<WIDE>,
        ) -> Self {
            self.mul_add(a, b)
        }
        // The stub runs the `WIDE = true` copies, so that both instantiations compile and
        // one of them runs.
        fn run_kernel<R>(
            wide: impl FnOnce(crate::dynamics_runtime::isa::Isa<true>) -> R,
            _narrow: impl FnOnce(crate::dynamics_runtime::isa::Isa<false>) -> R,
        ) -> R {
            wide(crate::dynamics_runtime::isa::Isa::STUB)
        }
        fn run_piece<R>(
            wide: impl FnOnce(crate::dynamics_runtime::isa::Isa<true>) -> R,
            _narrow: impl FnOnce(crate::dynamics_runtime::isa::Isa<false>) -> R,
        ) -> R {
            wide(crate::dynamics_runtime::isa::Isa::STUB)
        }
    }
    impl Scalar for f64 {
        fn from_f64(x: f64) -> Self { x }
        fn sin(self) -> Self { f64::sin(self) }
        fn cos(self) -> Self { f64::cos(self) }
        fn sqrt(self) -> Self { f64::sqrt(self) }
        fn sin_cos(self) -> (Self, Self) { f64::sin_cos(self) }
    }
}
/// `dynamics_runtime::isa::Isa` as generated code uses it (the emitted `::dynamics_runtime`
/// paths are rewritten to `crate::dynamics_runtime`).
#[allow(dead_code)]
mod dynamics_runtime {
    pub mod isa {
        #[derive(Clone, Copy)]
        pub struct Isa<const WIDE: bool>(());
        impl Isa<false> {
            pub const BASELINE: Self = Isa(());
        }
        impl Isa<true> {
            pub const STUB: Self = Isa(());
        }
        impl<const WIDE: bool> Isa<WIDE> {
            pub fn mul_add<T: crate::rt::Scalar>(self, a: T, b: T, c: T) -> T {
                a.mul_add_on(b, c, self)
            }
        }
    }
}
";

    /// Compiles emitted functions with rustc (`-D warnings`) next to a `Scalar` stub, runs
    /// them for `T = f64` and compares every output bit for bit with [`Graph::eval`]. This
    /// is the one test that needs a Rust toolchain at test time (it always has one).
    #[test]
    fn emitted_code_compiles_cleanly_and_matches_eval() {
        let g = Graph::new();
        let chain = long_chain(&g, 120);
        let q1 = g.input(Array::Q, 1);
        let odd = [
            g.constant(f64::NAN),
            g.constant(f64::NEG_INFINITY),
            g.constant(-0.1),
            g.neg(g.sin(q1)),
            g.cos(q1),
        ];
        let q: Vec<f64> = (0..8).map(|i| 0.3 * i as f64 - 1.1).collect();
        let v = [0.7, -1.3, 2.1];
        let input = |r: InputRef| match r.array {
            Array::Q => q[r.index as usize],
            _ => v[r.index as usize],
        };

        let args = [(Array::Q, 8), (Array::V, 3), (Array::Tau, 2)];
        let mut split = spec("split", &args, Output::Vector(chain.clone()));
        split.split_threshold = 200;
        let whole = spec("whole", &args, Output::Vector(chain.clone()));
        let matrix = spec(
            "shaped",
            &args,
            Output::Tuple(vec![
                Output::Matrix(vec![chain[..2].to_vec(), odd[..2].to_vec()]),
                Output::Scalar(odd[2]),
                Output::Vector(odd[3..].to_vec()),
            ]),
        );
        let (q0, q2) = (g.input(Array::Q, 0), g.input(Array::Q, 2));
        let angles = [g.sin(q0), g.cos(q1), g.cos(q2), g.sin(q2), g.mul(q2, q0)];
        let batched = spec("angles", &args, Output::Vector(angles.to_vec()));
        // Two functions too small for two copies: one with a fused product (it reads
        // `WIDE`), one without (no `WIDE` to leave unused).
        let small = [g.add(g.mul(q0, q2), q1), g.sub(q2, q0)];
        let small_fused = spec("small_fused", &args, Output::Vector(small[..1].to_vec()));
        let small_plain = spec("small_plain", &args, Output::Vector(small[1..].to_vec()));
        let split_text = emit_function(&g, &split).to_string();
        assert!(
            split_text.contains("part_3"),
            "split into at least 3 pieces"
        );
        let mut split_one_copy = split.clone();
        split_one_copy.name = quote::format_ident!("split_one_copy");
        split_one_copy.dispatch = false;
        let mut whole_one_copy = whole.clone();
        whole_one_copy.name = quote::format_ident!("whole_one_copy");
        whole_one_copy.dispatch = false;
        let mut program = SCALAR_STUB.to_string();
        for s in [
            &split,
            &whole,
            &matrix,
            &batched,
            &small_fused,
            &small_plain,
            &split_one_copy,
            &whole_one_copy,
        ] {
            let mut s = s.clone();
            s.scalar_trait = syn::parse_quote!(crate::rt::Scalar);
            program += &emit_function(&g, &s)
                .to_string()
                .replace(":: dynamics_runtime ::", "crate :: dynamics_runtime ::");
            program += "\n";
        }
        let mut main = String::from("fn main() {\n");
        writeln!(
            main,
            "    let q = {q:?};\n    let v = {v:?};\n    let tau = [0.0; 2];"
        )
        .ok();
        writeln!(
            main,
            "    for x in split(&q, &v, &tau) {{ println!(\"{{x:?}}\"); }}"
        )
        .ok();
        writeln!(
            main,
            "    for x in whole(&q, &v, &tau) {{ println!(\"{{x:?}}\"); }}"
        )
        .ok();
        main += "    let (m, s, w) = shaped(&q, &v, &tau);\n";
        main += "    for x in m.iter().flatten().chain([&s]).chain(&w) { println!(\"{x:?}\"); }\n";
        main += "    for x in angles(&q, &v, &tau) { println!(\"{x:?}\"); }\n";
        main += "    for x in small_fused(&q, &v, &tau) { println!(\"{x:?}\"); }\n";
        main += "    for x in small_plain(&q, &v, &tau) { println!(\"{x:?}\"); }\n";
        main += "    for x in split_one_copy(&q, &v, &tau) { println!(\"{x:?}\"); }\n";
        main += "    for x in whole_one_copy(&q, &v, &tau) { println!(\"{x:?}\"); }\n}\n";
        program += &main;

        let mut expected = g.eval(input, &chain);
        expected.extend(g.eval(input, &chain));
        expected.extend(g.eval(input, &[chain[0], chain[1], odd[0], odd[1]]));
        expected.extend(g.eval(input, &odd[2..]));
        expected.extend(g.eval(input, &angles));
        expected.extend(g.eval(input, &small));
        expected.extend(g.eval(input, &chain));
        expected.extend(g.eval(input, &chain));

        let dir = std::env::temp_dir().join(format!("dynamics-emit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let source = dir.join("emitted.rs");
        let binary = dir.join("emitted");
        std::fs::write(&source, &program).expect("write source");
        let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".to_string());
        let compiled = std::process::Command::new(rustc)
            .args([
                "--edition",
                "2021",
                "-D",
                "warnings",
                "-C",
                "opt-level=0",
                "-o",
            ])
            .arg(&binary)
            .arg(&source)
            .output()
            .expect("run rustc");
        assert!(
            compiled.status.success(),
            "rustc failed:\n{}\nsource: {}",
            String::from_utf8_lossy(&compiled.stderr),
            source.display()
        );
        let run = std::process::Command::new(&binary)
            .output()
            .expect("run binary");
        assert!(run.status.success());
        let printed: Vec<f64> = String::from_utf8_lossy(&run.stdout)
            .lines()
            .map(|l| l.parse().expect("an f64"))
            .collect();
        assert_eq!(printed.len(), expected.len());
        for (i, (p, e)) in printed.iter().zip(&expected).enumerate() {
            assert_eq!(p.to_bits(), e.to_bits(), "output {i}: {p} vs {e}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }
}
