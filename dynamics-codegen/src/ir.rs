//! The function IR every stage after the model shares: a [`Function`] is one expression
//! graph ([`crate::sym::Graph`]) and a [`FunctionSpec`] saying what to call it, which input
//! arrays it takes ([`Arg`], in the fixed order q, v, a, tau, p, loads) and which nodes it
//! returns ([`Output`]).
//!
//! The expansion ([`crate::expand`], driven by [`crate::functions`]) writes it, the passes
//! ([`crate::passes`]) rewrite it, the scheduler ([`crate::schedule`]) orders it and the
//! printer ([`crate::print`]) turns it into Rust tokens. Nothing here prints.

use crate::sym::{Array, Graph, Node};
use proc_macro2::{Ident, Span};

/// The default [`FunctionSpec::split_threshold`]: 2500 statements (inputs, constants and
/// operations). Each piece re-creates the constants and inputs it reads, so pieces come out
/// somewhat longer, but below ~3000 `let`s, where rustc (LLVM's debug-info scopes, one per
/// `let`, walked recursively) overflows its stack in debug builds. Each cut costs
/// at run time: the values crossing it go through memory, and the optimizer sees one piece
/// at a time. The quadruped's Coriolis matrix, cut in three at the earlier threshold of
/// 1500 live nodes, took 0.72 of the time whole (paired, `models/tools/generated_ab.sh`),
/// and compiled no slower.
pub(crate) const DEFAULT_SPLIT_THRESHOLD: usize = 2500;

/// One generated function: its graph and how to emit it.
pub(crate) struct Function {
    /// The expression DAG.
    pub graph: Graph,
    /// Name, arguments, outputs, docs.
    pub spec: FunctionSpec,
}

/// One argument of the emitted function: `name: &[T; len]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Arg {
    /// The input array (its [`Array::name`] is the argument's name).
    pub array: Array,
    /// The array's length.
    pub len: usize,
}

/// What the emitted function returns, and from which nodes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Output {
    /// `T`.
    Scalar(Node),
    /// `[T; N]`.
    Vector(Vec<Node>),
    /// `[[T; C]; R]`, given as `R` rows of `C` nodes.
    Matrix(Vec<Vec<Node>>),
    /// A tuple of outputs, e.g. `([[T; 7]; 7], [T; 7])`.
    Tuple(Vec<Output>),
    /// An array of outputs of one shape, e.g. one 6 × nv Jacobian per body:
    /// `[[[T; 7]; 6]; 7]`.
    Stack(Vec<Output>),
}

impl Output {
    /// Every node of the output, in order (repeats kept).
    #[must_use]
    pub fn nodes(&self) -> Vec<Node> {
        let mut nodes = Vec::new();
        self.collect_nodes(&mut nodes);
        nodes
    }

    /// The same output with every node replaced by `f(node)`.
    #[must_use]
    pub fn map(&self, f: &impl Fn(Node) -> Node) -> Output {
        let row = |nodes: &[Node]| nodes.iter().map(|&n| f(n)).collect();
        match self {
            Output::Scalar(n) => Output::Scalar(f(*n)),
            Output::Vector(v) => Output::Vector(row(v)),
            Output::Matrix(rows) => Output::Matrix(rows.iter().map(|r| row(r)).collect()),
            Output::Tuple(items) => Output::Tuple(items.iter().map(|o| o.map(f)).collect()),
            Output::Stack(items) => Output::Stack(items.iter().map(|o| o.map(f)).collect()),
        }
    }

    fn collect_nodes(&self, nodes: &mut Vec<Node>) {
        match self {
            Output::Scalar(n) => nodes.push(*n),
            Output::Vector(v) => nodes.extend(v),
            Output::Matrix(rows) => rows.iter().for_each(|r| nodes.extend(r)),
            Output::Tuple(items) | Output::Stack(items) => {
                items.iter().for_each(|o| o.collect_nodes(nodes));
            }
        }
    }
}

/// Everything the printer needs besides the graph.
#[derive(Clone, Debug)]
pub(crate) struct FunctionSpec {
    /// The function's name.
    pub name: Ident,
    /// Its visibility (`pub` by default).
    pub vis: syn::Visibility,
    /// What it computes, for its doc comment (may span several lines; the op count line is
    /// appended).
    pub doc: String,
    /// The path of the scalar trait, e.g. `::dynamics_runtime::Scalar`.
    pub scalar_trait: syn::Path,
    /// The arguments, in order. Every input the outputs read must be covered.
    pub args: Vec<Arg>,
    /// The return value.
    pub output: Output,
    /// Split into pieces when the body would have more statements than this (see
    /// [`crate::schedule`]).
    pub split_threshold: usize,
    /// Emit the AVX2 + FMA copy and the run-time choice where worth it (the default), or
    /// the baseline copy alone (`isa: baseline;`).
    pub dispatch: bool,
}

impl FunctionSpec {
    /// A public function `name` over `scalar_trait`, with no doc text and the default split
    /// threshold.
    #[must_use]
    pub fn new(name: &str, scalar_trait: syn::Path, args: Vec<Arg>, output: Output) -> Self {
        FunctionSpec {
            name: Ident::new(name, Span::call_site()),
            vis: syn::parse_quote!(pub),
            doc: String::new(),
            scalar_trait,
            args,
            output,
            split_threshold: DEFAULT_SPLIT_THRESHOLD,
            dispatch: true,
        }
    }
}
