//! The function IR every stage after the model shares: a [`Function`] is one expression
//! graph ([`crate::sym::Graph`]) and a [`FunctionSpec`] saying what to call it, which input
//! arrays it takes ([`Arg`], in the fixed order q, v, a, tau, p, loads) and which nodes it
//! returns ([`Output`]).
//!
//! The expansion ([`crate::expand`], driven by [`crate::functions`]) writes it, the passes
//! ([`crate::passes`]) rewrite it, the scheduler ([`crate::schedule`]) orders it and the
//! printer ([`crate::print`]) turns it into Rust tokens. Nothing here prints.

use crate::sym::{Array, Graph, Node, OpCount};
use proc_macro2::{Ident, Span};

/// The default [`FunctionSpec::split_threshold`]: 2500 statements (inputs, constants and
/// operations). Each piece re-creates the constants and inputs it reads, so pieces come out
/// somewhat longer, but below ~3000 `let`s, where rustc (LLVM's debug-info scopes, one per
/// `let`, walked recursively) overflows its stack in debug builds. Each cut costs
/// at run time: the values crossing it go through memory, and the optimizer sees one piece
/// at a time. The quadruped's Coriolis matrix, cut in three at the earlier threshold of
/// 1500 live nodes, took 0.72 of the time whole (paired, `models/tools/generated_ab.sh`),
/// and compiled no slower. Only builds with debug info or without optimization cut; the
/// others take every function whole ([`crate::build_profile`]).
pub(crate) const DEFAULT_SPLIT_THRESHOLD: usize = 2500;

/// One generated function: its graph and how to emit it.
pub(crate) struct Function {
    /// The expression DAG.
    pub graph: Graph,
    /// Name, arguments, outputs, docs.
    pub spec: FunctionSpec,
    /// For a graph with packed values and a mechanism declared with `lanes: true;`, the same
    /// function expanded with none (`Model::packs` off): the body that scalar types holding
    /// several states side by side run (`dynamics_runtime::Scalar::run_packed`).
    pub unpacked: Option<Box<Function>>,
}

impl Function {
    /// Its operations: see [`op_count`].
    #[must_use]
    pub fn op_count(&self) -> OpCount {
        op_count(&self.graph, &self.spec.output)
    }
}

/// The operations of a function returning `output`: its graph's, and the loop's of an
/// [`Output::Solved`] ([`TreeSolve::loop_ops`]).
#[must_use]
pub(crate) fn op_count(graph: &Graph, output: &Output) -> OpCount {
    let mut count = graph.op_count(&output.nodes());
    if let Output::Solved(s) = output {
        let (mul, add) = s.loop_ops();
        count.mul += mul;
        count.add += add;
    }
    count
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
    /// A tuple of matrices X solving M X = B by a tree-sparse factorization of M that the
    /// graph computes along with the B's (the matrix itself when there is one B): the
    /// emitted code runs the solve as a loop over the columns (`dynamics_runtime::tree_ldlt`),
    /// not as straight-line code.
    Solved(TreeSolve),
}

/// The tree-sparse solves of an [`Output::Solved`]: M = Lᵀ D L, L_ki nonzero only for i an
/// ancestor of k in `parents` (coordinates numbered depth first).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct TreeSolve {
    /// Each coordinate's parent coordinate.
    pub parents: Vec<Option<usize>>,
    /// L_ki, row after row, each row's entries from the parent towards the root.
    pub factor: Vec<Node>,
    /// 1 / D_k.
    pub inverse_pivot: Vec<Node>,
    /// The right-hand sides B, each nv rows of the same number of columns.
    pub rhs: Vec<Vec<Vec<Node>>>,
    /// Which of the solve's sweeps the loop runs.
    pub sweeps: Sweeps,
}

/// The sweeps of a [`TreeSolve`]'s loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Sweeps {
    /// Lᵀ Z = B, Y = D⁻¹ Z, L X = Y: B is the right-hand side.
    All,
    /// M⁻¹ = L⁻¹ (D⁻¹ L⁻ᵀ): L X = B alone, B = D⁻¹ L⁻ᵀ computed by the graph, where the
    /// zeros of L⁻ᵀ (upper triangular and tree-sparse) make it cheap in straight-line
    /// code; then X's upper triangle mirrored onto the lower, so that X is exactly
    /// symmetric.
    LastOfInverse,
}

impl TreeSolve {
    /// The multiplications and the additions of the loop (no zero skipped): a multiply-add
    /// for each column and each factor entry in each sweep run, a product for each column
    /// and pivot when the loop scales by them.
    #[must_use]
    pub fn loop_ops(&self) -> (usize, usize) {
        let columns: usize = self.rhs.iter().map(|b| b.first().map_or(0, Vec::len)).sum();
        let row_updates = columns * self.factor.len();
        match self.sweeps {
            Sweeps::All => (
                2 * row_updates + columns * self.inverse_pivot.len(),
                2 * row_updates,
            ),
            Sweeps::LastOfInverse => (row_updates, row_updates),
        }
    }

    /// The right-hand sides grouped as the loop takes them, those of one width together:
    /// (C, the indices of the K matrices of C columns), in increasing C.
    #[must_use]
    pub fn width_groups(&self) -> Vec<(usize, Vec<usize>)> {
        let width = |b: &Vec<Vec<Node>>| b.first().map_or(0, Vec::len);
        let widths: std::collections::BTreeSet<usize> = self.rhs.iter().map(width).collect();
        widths
            .into_iter()
            .map(|w| {
                let members = (0..self.rhs.len()).filter(|&k| width(&self.rhs[k]) == w);
                (w, members.collect())
            })
            .collect()
    }

    /// What the loop costs, in straight-line operations of about the same time: the
    /// right-hand sides of one width go through the loop together ([`Self::width_groups`]),
    /// K matrices of C columns, so each row update is ⌈C K / 4⌉ AVX2 multiply-adds and about
    /// two more instructions; the 2 P row updates of the sweeps (P the factor's length; P
    /// alone for [`Sweeps::LastOfInverse`]) and the N rows scaled by 1 / D_k (none for
    /// [`Sweeps::LastOfInverse`]) cost 1.5 operations per such step, plus 480 for the call
    /// (fitted to the UR5's, the Panda's and the quadruped's forward-dynamics derivatives
    /// timed against their straight-line solves: about 70 ns plus 0.21 ns a step, at about
    /// 7 straight-line operations a nanosecond). The fit predates the solve in place, which
    /// saves two copies of the columns (2 to 5 % of the quadruped's ∂q̈), so it now
    /// overstates the loop's cost by about that; not refitted.
    #[must_use]
    pub fn loop_cost(&self) -> usize {
        let (pairs, n) = (self.factor.len(), self.inverse_pivot.len());
        let steps: usize = self
            .width_groups()
            .iter()
            .map(|(width, members)| {
                let vectors = (width * members.len()).div_ceil(4);
                match self.sweeps {
                    Sweeps::All => 2 * pairs * (vectors + 2) + n * vectors,
                    Sweeps::LastOfInverse => pairs * (vectors + 2),
                }
            })
            .sum();
        480 + steps * 3 / 2
    }

    /// What the emitted function returns, in the shape of the other outputs: a tuple of
    /// the solutions' matrices, or the matrix itself when there is one right-hand side.
    #[must_use]
    pub fn returned(&self) -> Output {
        let mut matrices: Vec<Output> = self.rhs.iter().cloned().map(Output::Matrix).collect();
        match matrices.len() {
            1 => matrices.swap_remove(0),
            _ => Output::Tuple(matrices),
        }
    }

    /// The solves in `f64`, from the values of [`Output::nodes`] of the output (factor,
    /// pivots, then the right-hand sides by rows): the solutions, one matrix after the
    /// other by rows, in the order of a straight-line solve of each column (M⁻¹'s upper
    /// triangle mirrored, for [`Sweeps::LastOfInverse`]).
    #[must_use]
    pub fn solve_f64(&self, values: &[f64]) -> Vec<f64> {
        let (factor, rest) = values.split_at(self.factor.len().min(values.len()));
        let (pivot, mut rest) = rest.split_at(self.inverse_pivot.len().min(rest.len()));
        let n = self.parents.len();
        let ancestors = |k: usize| std::iter::successors(self.parents[k], |&i| self.parents[i]);
        // Where row k of L starts in the factor.
        let mut row_start = vec![0; n + 1];
        for k in 0..n {
            row_start[k + 1] = row_start[k] + ancestors(k).count();
        }
        let l = |k: usize, nth: usize| factor.get(row_start[k] + nth).copied().unwrap_or(0.0);
        let solve = |mut y: Vec<f64>| {
            if self.sweeps == Sweeps::All {
                for k in (0..n).rev() {
                    for (nth, i) in ancestors(k).enumerate() {
                        y[i] -= l(k, nth) * y[k];
                    }
                }
                for (x, d) in y.iter_mut().zip(pivot) {
                    *x *= d;
                }
            }
            for k in 0..n {
                for (nth, i) in ancestors(k).enumerate() {
                    y[k] -= l(k, nth) * y[i];
                }
            }
            y
        };
        let mut out = Vec::new();
        for b in &self.rhs {
            let width = b.first().map_or(0, Vec::len);
            let (here, next) = rest.split_at((n * width).min(rest.len()));
            rest = next;
            let at = |r: usize, c: usize| here.get(r * width + c).copied().unwrap_or(0.0);
            let columns: Vec<Vec<f64>> = (0..width)
                .map(|c| solve((0..n).map(|r| at(r, c)).collect()))
                .collect();
            // M⁻¹'s lower triangle is its upper one, mirrored.
            let mirrored = self.sweeps == Sweeps::LastOfInverse;
            let entry = |r: usize, c: usize| match mirrored && c < r {
                true => columns[r][c],
                false => columns[c][r],
            };
            out.extend((0..n).flat_map(|r| (0..width).map(move |c| entry(r, c))));
        }
        out
    }
}

impl Output {
    /// The values the emitted function returns, flattened (a matrix by rows, a tuple item
    /// after item), given the values `eval` computes for nodes.
    #[must_use]
    pub fn values(&self, eval: impl Fn(&[Node]) -> Vec<f64>) -> Vec<f64> {
        let values = eval(&self.nodes());
        match self {
            Output::Solved(s) => s.solve_f64(&values),
            _ => values,
        }
    }

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
            Output::Solved(s) => Output::Solved(TreeSolve {
                parents: s.parents.clone(),
                factor: row(&s.factor),
                inverse_pivot: row(&s.inverse_pivot),
                rhs: s
                    .rhs
                    .iter()
                    .map(|b| b.iter().map(|r| row(r)).collect())
                    .collect(),
                sweeps: s.sweeps,
            }),
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
            Output::Solved(s) => {
                nodes.extend(&s.factor);
                nodes.extend(&s.inverse_pivot);
                s.rhs.iter().flatten().for_each(|r| nodes.extend(r));
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
