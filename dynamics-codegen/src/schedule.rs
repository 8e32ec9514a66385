//! The order of a function's statements, and its pieces.
//!
//! [`Plan::new`] turns the live nodes of a function's graph into statements ([`Step`]): one
//! per operation in the depth-first order of [`depth_first`], the sines and cosines of the
//! inputs gathered into one batch, other `sin x`/`cos x` pairs into one step, the products
//! that the fusion pass ([`crate::passes::fusion`]) folds into a sum left out. Then it cuts
//! them into pieces.
//!
//! # Splitting long functions
//!
//! rustc overflows its stack on very long functions in builds with debug info, and its
//! compile time grows faster than the length in unoptimized ones, so there a body of more
//! than [`FunctionSpec::split_threshold`] statements is cut into pieces of about equal
//! length. An optimized build without debug info takes every function whole
//! ([`crate::build_profile`]), which runs faster. Each piece is a kernel of its own,
//! nested inside the emitted function (so the emitted code stays a single item, usable at
//! module level or in an `impl` block), run by `T::run_piece`, which keeps either copy out
//! of line; the emitted function only chains them:
//!
//! ```text
//! pub fn f<T: Scalar>(q: &[T; 7], v: &[T; 7]) -> [T; 7] {
//!     #[inline(always)]
//!     fn part_1<T: Scalar, const WIDE: bool>(isa: Isa<WIDE>, q: &[T; 7], v: &[T; 7])
//!         -> [T; 40] { … }
//!     #[inline(always)]
//!     fn part_2<T: Scalar, const WIDE: bool>(isa: Isa<WIDE>, q: &[T; 7], carry: &[T; 40])
//!         -> [T; 35] {
//!         let [v12, v17, …] = *carry;
//!         …
//!     }
//!     …
//!     let carry_1 = T::run_piece(
//!         #[inline(always)]
//!         |isa| part_1::<T, true>(isa, q, v),
//!         #[inline(always)]
//!         |isa| part_1::<T, false>(isa, q, v),
//!     );
//!     …
//! }
//! ```
//!
//! The values crossing the boundary before piece `k + 1` — computed in piece `k` or
//! earlier, used by a statement of piece `k + 1` or later or as an output — travel in one
//! array `carry_k: [T; K]`, in id order, passed by reference. A piece returns the values
//! crossing the next boundary: those it computes and those it passes through from its own
//! `carry`; the last piece returns the function's output. Constants and inputs are never
//! carried: each piece re-reads the inputs and re-creates the constants it uses (both are
//! free).
//!
//! A function cut into more than [`HAND_BACK_ABOVE_PIECES`] pieces does not carry its
//! outputs: each piece returns, as a second array, the outputs it computes
//! ([`Piece::outputs`]), which the emitted function binds to their names, creates the
//! outputs that are leaves, and returns the output built from those names. Carried, an
//! output computed early crosses every later boundary, and the code grows as the number of
//! outputs times the number of pieces.

use crate::ir::{Arg, FunctionSpec};
use crate::passes::fusion::Fused;
use crate::sym::{Array, Graph, LiveSet, Node, Op};
use std::collections::{BTreeSet, HashMap};

/// One statement computing a non-leaf node, a `sin`/`cos` pair, or the sines and cosines
/// of several inputs at once.
#[derive(Clone, Debug)]
pub(crate) enum Step {
    One(Node),
    SinCos {
        sin: Node,
        cos: Node,
        arg: Node,
    },
    /// `T::sin_cos_array` of inputs, with the (optional) sine and cosine node of each.
    Batch(Vec<BatchedAngle>),
}

/// One angle of a [`Step::Batch`]: an input leaf and whichever of its sine and cosine is live.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BatchedAngle {
    pub arg: Node,
    pub sin: Option<Node>,
    pub cos: Option<Node>,
}

impl Step {
    pub(crate) fn defines(&self) -> Vec<Node> {
        match self {
            Step::One(n) => vec![*n],
            Step::SinCos { sin, cos, .. } => vec![*sin, *cos],
            Step::Batch(angles) => angles
                .iter()
                .flat_map(|a| a.sin.into_iter().chain(a.cos))
                .collect(),
        }
    }
}

/// One piece of the body: a range of steps, the leaves they read, the arrays those leaves
/// come from, and the values carried in from earlier pieces.
#[derive(Debug, Default)]
pub(crate) struct Piece {
    pub steps: Vec<Step>,
    pub leaves: BTreeSet<Node>,
    /// Arrays read in place by a [`Step::Batch`].
    pub batch_arrays: BTreeSet<Array>,
    pub arrays: BTreeSet<Array>,
    pub carry_in: Vec<Node>,
    /// The outputs this piece computes, in id order, handed back to the emitted function
    /// ([`Plan::hands_back`] only).
    pub outputs: Vec<Node>,
}

/// The schedule of the whole function: steps in order, cut into pieces.
pub(crate) struct Plan {
    /// The pieces, in order (one when the function is not split).
    pub pieces: Vec<Piece>,
    /// The sums and differences that take a product in
    /// ([`crate::passes::fusion::fusions`]).
    pub fused: HashMap<Node, Fused>,
    /// Whether the pieces hand their outputs back to the emitted function (more than
    /// [`HAND_BACK_ABOVE_PIECES`] pieces) rather than carry them to the last piece, which
    /// then returns the output.
    pub hands_back: bool,
    /// The outputs that are leaves (inputs and constants), in id order: read by the last
    /// piece, or by the emitted function itself when the pieces hand their outputs back.
    pub output_leaves: BTreeSet<Node>,
    /// Whether each node of the graph is packed (four lanes, `Graph::pack`).
    pub packed: Vec<bool>,
}

/// The most pieces whose outputs are carried to the last piece; a function cut into more
/// hands each output back from the piece that computes it. Carrying costs a copy per
/// boundary crossed, so it grows as outputs times pieces (a 200-joint chain's Coriolis
/// matrix, 240 pieces: 181 MB of Rust for its default outputs, 68 MB handed back); for a
/// few pieces it is the faster shape: handing back made the quadruped's 6-piece ∂q̈ 13 %
/// slower (3.30 → 3.75 µs) and the Panda's 3-piece one 8 % faster (1.17 → 1.08 µs), two
/// alternating runs of `cargo bench -p models --bench dynamics` each.
pub(crate) const HAND_BACK_ABOVE_PIECES: usize = 8;

/// What a statement on packed values counts for against [`FunctionSpec::split_threshold`]:
/// four, one per lane. Counted as one, the 30-link chain's mass matrix in a debug build
/// overflowed a test thread's 2 MB stack (its pieces' frames hold four lanes a value).
const PACKED_STATEMENT_WEIGHT: usize = 4;

impl Plan {
    /// The statements of the function `spec` describes over `graph`, with the products
    /// `fused` folds into sums left out, cut into pieces of at most about
    /// `spec.split_threshold` statements.
    ///
    /// # Panics
    /// If a live input is not covered by `spec.args` (array missing or index out of range):
    /// that is a bug of the caller, not of the user's model.
    pub(crate) fn new(graph: &Graph, spec: &FunctionSpec, fused: HashMap<Node, Fused>) -> Self {
        Self::build(graph, spec, fused, &spec.output.nodes(), false)
    }

    /// [`Plan::new`] for a `_into` or `_sparse_into` function, which writes each output
    /// node of `written` where it is computed (every node of the output for `_into`; for
    /// `_sparse_into` the rest is not computed for it, and a constant output not written is
    /// not defined): cut into pieces, it hands every output back ([`Plan::hands_back`])
    /// instead of carrying them to the last piece.
    pub(crate) fn writing(
        graph: &Graph,
        spec: &FunctionSpec,
        fused: HashMap<Node, Fused>,
        written: &[Node],
    ) -> Self {
        Self::build(graph, spec, fused, written, true)
    }

    /// [`Plan::new`] for the output nodes `outputs`, the pieces handing their outputs back
    /// whenever there are several when `always_hand_back`.
    fn build(
        graph: &Graph,
        spec: &FunctionSpec,
        fused: HashMap<Node, Fused>,
        outputs: &[Node],
        always_hand_back: bool,
    ) -> Self {
        let live = &graph.live(outputs);
        let ops = &graph.ops();
        check_inputs(ops, live, &spec.args);
        let threshold = spec.split_threshold;
        let steps = schedule(ops, live, outputs, &fused);
        // The inputs and constants read count too: the whole body's statements.
        let leaves = live.nodes().filter(|n| ops[n.index()].is_leaf()).count();
        // A packed statement weighs four: its values take four lanes' room in an
        // unoptimized build's stack frame, which the threshold also bounds.
        let weight = |step: &Step| match step {
            Step::One(n) if graph.is_packed(*n) => PACKED_STATEMENT_WEIGHT,
            _ => 1,
        };
        let total: usize = steps.iter().map(weight).sum();
        let n_pieces = (total + leaves).div_ceil(threshold.max(1)).max(1);
        let per_piece = total.div_ceil(n_pieces).max(1);
        let mut pieces: Vec<Piece> = Vec::new();
        let mut filled = 0;
        for step in steps {
            if pieces.is_empty() || filled >= per_piece {
                pieces.push(Piece::default());
                filled = 0;
            }
            filled += weight(&step);
            if let Some(piece) = pieces.last_mut() {
                piece.steps.push(step);
            }
        }
        if pieces.is_empty() {
            pieces.push(Piece::default());
        }
        let last = pieces.len() - 1;

        // Where each non-leaf node is defined and last read by a statement.
        let mut defined_in = HashMap::new();
        let mut last_use: HashMap<Node, usize> = HashMap::new();
        for (p, piece) in pieces.iter_mut().enumerate() {
            for step in &piece.steps {
                defined_in.extend(step.defines().into_iter().map(|n| (n, p)));
                let operands: Vec<Node> = match step {
                    Step::One(n) => match fused.get(n) {
                        Some(f) => vec![f.x, f.y, f.c],
                        None => ops[n.index()].children().collect(),
                    },
                    Step::SinCos { arg, .. } => vec![*arg],
                    Step::Batch(angles) => {
                        // Read in place, not through a `let` of the leaf: only the array.
                        piece.batch_arrays.extend(angles.iter().filter_map(|a| {
                            match ops[a.arg.index()] {
                                Op::Input(r) => Some(r.array),
                                _ => None,
                            }
                        }));
                        Vec::new()
                    }
                };
                for child in operands {
                    if ops[child.index()].is_leaf() {
                        piece.leaves.insert(child);
                    } else {
                        let l = last_use.entry(child).or_insert(p);
                        *l = (*l).max(p);
                    }
                }
            }
        }
        let hands_back =
            pieces.len() > HAND_BACK_ABOVE_PIECES || (always_hand_back && pieces.len() > 1);
        let mut output_leaves = BTreeSet::new();
        for &out in outputs {
            if ops[out.index()].is_leaf() {
                output_leaves.insert(out);
            } else if hands_back {
                pieces[defined_in[&out]].outputs.push(out);
            } else {
                // Carried to the last piece, which returns the output.
                last_use.insert(out, last);
            }
        }
        if !hands_back {
            pieces[last].leaves.extend(output_leaves.iter().copied());
        }
        // Each value crosses the boundaries from its piece to its last reader's.
        for (&node, &l) in &last_use {
            for piece in &mut pieces[defined_in[&node] + 1..=l] {
                piece.carry_in.push(node);
            }
        }
        for piece in &mut pieces {
            piece.arrays = piece
                .leaves
                .iter()
                .filter_map(|n| match ops[n.index()] {
                    Op::Input(r) => Some(r.array),
                    _ => None,
                })
                .chain(piece.batch_arrays.iter().copied())
                .collect();
            piece.carry_in.sort_unstable();
            piece.outputs.sort_unstable();
            piece.outputs.dedup();
        }
        Plan {
            pieces,
            fused,
            hands_back,
            output_leaves,
            packed: graph.packed_flags(),
        }
    }
}

/// The live non-leaf nodes as statements, in [`depth_first`] order: the sines and cosines
/// of two or more inputs merged into one [`Step::Batch`] at the first of them, other
/// `sin x`/`cos x` pairs into one `sin_cos` step at the first of the two.
fn schedule(
    ops: &[Op],
    live: &LiveSet,
    outputs: &[Node],
    fused: &HashMap<Node, Fused>,
) -> Vec<Step> {
    let folded: BTreeSet<Node> = fused.values().map(|f| f.product).collect();
    let mut sin_of = HashMap::new();
    let mut cos_of = HashMap::new();
    for node in live.nodes() {
        match ops[node.index()] {
            Op::Sin(x) => {
                sin_of.insert(x, node);
            }
            Op::Cos(x) => {
                cos_of.insert(x, node);
            }
            _ => {}
        }
    }
    let is_input = |x: &Node| matches!(ops[x.index()], Op::Input(_));
    let batched: BTreeSet<Node> = sin_of
        .keys()
        .chain(cos_of.keys())
        .copied()
        .filter(is_input)
        .collect();
    let batch = (batched.len() >= 2).then(|| {
        batched
            .iter()
            .map(|&arg| BatchedAngle {
                arg,
                sin: sin_of.get(&arg).copied(),
                cos: cos_of.get(&arg).copied(),
            })
            .collect::<Vec<_>>()
    });

    let mut steps = Vec::new();
    let mut batch_done = false;
    let mut paired = BTreeSet::new();
    for node in depth_first(ops, live, outputs) {
        let op = ops[node.index()];
        if let (Op::Sin(x) | Op::Cos(x), Some(angles)) = (op, &batch) {
            if batched.contains(&x) {
                if !batch_done {
                    batch_done = true;
                    steps.push(Step::Batch(angles.clone()));
                }
                continue; // computed by the batch
            }
        }
        let pair = match op {
            Op::Sin(x) | Op::Cos(x) => sin_of.get(&x).zip(cos_of.get(&x)).map(|(&s, &c)| (x, s, c)),
            _ => None,
        };
        match pair {
            Some((arg, sin, cos)) if paired.insert(arg) => {
                steps.push(Step::SinCos { sin, cos, arg });
            }
            Some(_) => {} // the second of a pair, computed with the first
            None if !op.is_leaf() && !folded.contains(&node) => steps.push(Step::One(node)),
            None => {}
        }
    }
    steps
}

/// The order of the statements: depth-first from the outputs, last output first, each
/// node right after its operands, the operand that needs more registers (its Sethi–Ullman
/// number) first. A value is then computed close to where it is used, so fewer values are
/// live at once, fewer spill to the stack and fewer cross from one piece to the next.
/// Measured in one process against the order of node creation, alternating, 41 rounds
/// (`models/tools/generated_ab.sh`): the quadruped's Coriolis matrix 0.80 of the time
/// (values carried between its pieces 377 + 492 → 244 + 373) and its forward dynamics
/// 0.82; its other functions and the Panda's within the run-to-run spread (±5 %). Both
/// choices count:
/// taking the first output first gave the Coriolis matrix only 0.95, and the operand order
/// gave most of the forward dynamics' gain.
fn depth_first(ops: &[Op], live: &LiveSet, outputs: &[Node]) -> Vec<Node> {
    let mut need = vec![0_u32; ops.len()];
    for node in live.nodes() {
        let mut needs: Vec<u32> = ops[node.index()]
            .children()
            .map(|c| need[c.index()])
            .collect();
        needs.sort_unstable_by(|a, b| b.cmp(a));
        need[node.index()] = match needs.as_slice() {
            [] => 1,
            [a] => *a,
            [a, b, ..] if a == b => a + 1,
            [a, ..] => *a,
        };
    }
    let mut placed = vec![false; ops.len()];
    let mut order = Vec::with_capacity(live.count());
    let mut stack: Vec<(Node, bool)> = Vec::new();
    for &out in outputs.iter().rev() {
        stack.push((out, false));
        while let Some((node, operands_placed)) = stack.pop() {
            if placed[node.index()] {
                continue;
            }
            if operands_placed {
                placed[node.index()] = true;
                order.push(node);
                continue;
            }
            stack.push((node, true));
            let mut operands: Vec<Node> = ops[node.index()]
                .children()
                .filter(|c| !placed[c.index()])
                .collect();
            // The most demanding operand first (ties in operand order); pushed last, popped first.
            operands.sort_by_key(|c| std::cmp::Reverse(need[c.index()]));
            stack.extend(operands.into_iter().rev().map(|c| (c, false)));
        }
    }
    order
}

/// Asserts that every live input is an element of one of the arguments.
fn check_inputs(ops: &[Op], live: &LiveSet, args: &[Arg]) {
    for node in live.nodes() {
        if let Op::Input(r) = ops[node.index()] {
            let arg = args.iter().find(|a| a.array == r.array);
            assert!(
                arg.is_some_and(|a| (r.index as usize) < a.len),
                "input {r} is not covered by the function's arguments {args:?}"
            );
        }
    }
}
