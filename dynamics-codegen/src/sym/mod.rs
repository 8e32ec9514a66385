//! The expression DAG that the symbolic expansion writes into and the emitter reads from.
//!
//! A [`Graph`] is a list of [`Op`]s in topological order: every operand of a node was
//! created before it, so a node's id is larger than its children's ids, and walking the
//! list front to back evaluates it. Nodes are named by a typed id, [`Node`], displayed as
//! `v12`, which is also the variable name in the generated code.
//!
//! Building is where the optimisation happens (see the rules in [`Graph::add`] and its
//! siblings, module `rules`):
//!
//! - **Hash-consing**: every node is looked up before it is created, so building the same
//!   expression twice yields the same [`Node`]; common subexpressions exist once. In
//!   particular `sin q_i` and `cos q_i` are atoms computed once, however often the
//!   expansion asks for them.
//! - **Constant folding**: an operation on constants is a constant (including `sin`, `cos`
//!   and `sqrt`), computed in `f64`.
//! - **Identities**: x·0 = 0, x·1 = x, x+0 = x, x−0 = x, 0−x = −x, x−x = 0, x/1 = x,
//!   −(−x) = x, and a fixed set of negation rules that move signs outwards so that `0.5·x`
//!   and `−0.5·x` share their product.
//! - **Canonical order**: the operands of `+` and `·` are ordered by id, so `a+b` and
//!   `b+a` are one node.
//!
//! What the builders do not do: reassociate (`(x·2)·3` stays two products), distribute, or
//! anything else that would change the rounding of the textbook's evaluation order. (Once a
//! function's graph is complete, [`Graph::regrouped`] copies it with each sum's terms and
//! each product's factors combined earliest-ready first: the one step that changes the
//! rounding of the textbook's order, for a shorter chain of dependent operations.) The only
//! rules that are not bit-exact in IEEE arithmetic are documented where they live: x·0 = 0
//! and x−x = 0 (differ when x is infinite or NaN), x+0 = x and 0−x = −x and −(a−b) = b−a
//! (may differ in the sign of a zero result).
//!
//! After building, [`Graph::live`] finds what the requested outputs need (everything else
//! is dead and never emitted), [`Graph::op_count`] counts their operations, and
//! [`Graph::eval`] evaluates them in `f64` for tests. [`Vec3`] and [`Mat3`] are small
//! helpers for writing the textbook's vector equations over nodes; zero entries fold away.
//!
//! The graph uses interior mutability (`&self` builders), so that nested calls such as
//! `g.add(a, g.mul(b, c))` read like the formula.

mod analysis;
mod derivative;
mod linalg;
mod pack;
mod rules;

pub use analysis::{LiveSet, OpCount};
pub use linalg::{Mat3, Vec3};

use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt;
use std::hash::{BuildHasherDefault, Hasher};

/// The id of a node of a [`Graph`]; displayed as `v12`, the variable name in emitted code.
///
/// Ids are dense indices into the graph's node list, in creation order, so a node's
/// operands always have smaller ids.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Node(pub(crate) u32);

impl Node {
    /// The position of this node in its graph's node list.
    #[must_use]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl fmt::Display for Node {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "v{}", self.0)
    }
}

/// A named input array of a generated function.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Array {
    /// Joint positions `q`.
    Q,
    /// Joint velocities `v` (q̇).
    V,
    /// Joint accelerations `a` (q̈).
    A,
    /// Joint forces/torques `tau`.
    Tau,
    /// Symbolic model parameters `p` (masses, lengths, ... left as inputs).
    P,
    /// Applied loads `loads` (forces, couples, wrenches), 3 or 6 entries each.
    Loads,
}

impl Array {
    /// The Rust name of the array, used as the argument name in emitted code.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Array::Q => "q",
            Array::V => "v",
            Array::A => "a",
            Array::Tau => "tau",
            Array::P => "p",
            Array::Loads => "loads",
        }
    }
}

/// One element of an input array, e.g. `q[3]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct InputRef {
    /// Which array.
    pub array: Array,
    /// The element's index in the array.
    pub index: u32,
}

impl fmt::Display for InputRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}[{}]", self.array.name(), self.index)
    }
}

/// An `f64` constant compared and hashed by its bit pattern.
///
/// `-0.0` is stored as `0.0` and every NaN as the canonical `f64::NAN`, so that equal
/// values are one node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Const(u64);

impl Const {
    /// The constant `x`, normalised (`-0.0` → `0.0`, any NaN → `f64::NAN`).
    #[must_use]
    pub fn new(x: f64) -> Self {
        let x = if x.is_nan() {
            f64::NAN
        } else if x == 0.0 {
            0.0
        } else {
            x
        };
        Const(x.to_bits())
    }

    /// The value.
    #[must_use]
    pub fn value(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// What a node computes. Operands are nodes created earlier.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// A numeric constant.
    Const(Const),
    /// An element of an input array.
    Input(InputRef),
    /// `a + b`, operands ordered by id.
    Add(Node, Node),
    /// `a − b`.
    Sub(Node, Node),
    /// `a · b`, operands ordered by id.
    Mul(Node, Node),
    /// `a / b`.
    Div(Node, Node),
    /// `−a`.
    Neg(Node),
    /// `sin a`.
    Sin(Node),
    /// `cos a`.
    Cos(Node),
    /// `√a`.
    Sqrt(Node),
    /// Four scalar values side by side, one per lane (a packed value; arithmetic with a
    /// packed operand is packed, a scalar operand taking part in every lane).
    Pack(Node, Node, Node, Node),
    /// Lane `k` of a packed value.
    Lane(Node, u8),
}

impl Op {
    /// The operands, in order.
    pub fn children(self) -> Operands {
        let (nodes, len) = match self {
            Op::Const(_) | Op::Input(_) => ([Node(0); 4], 0),
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => ([a, b, a, a], 2),
            Op::Neg(a) | Op::Sin(a) | Op::Cos(a) | Op::Sqrt(a) | Op::Lane(a, _) => ([a; 4], 1),
            Op::Pack(a, b, c, d) => ([a, b, c, d], 4),
        };
        Operands {
            nodes,
            len,
            next: 0,
        }
    }

    /// The same operation on the operands `f` gives for its own (commutative operands put
    /// back in id order).
    #[must_use]
    pub fn with_children(self, f: impl Fn(Node) -> Node) -> Op {
        match self {
            Op::Const(_) | Op::Input(_) => self,
            Op::Add(a, b) => Op::Add(f(a).min(f(b)), f(a).max(f(b))),
            Op::Mul(a, b) => Op::Mul(f(a).min(f(b)), f(a).max(f(b))),
            Op::Sub(a, b) => Op::Sub(f(a), f(b)),
            Op::Div(a, b) => Op::Div(f(a), f(b)),
            Op::Neg(a) => Op::Neg(f(a)),
            Op::Sin(a) => Op::Sin(f(a)),
            Op::Cos(a) => Op::Cos(f(a)),
            Op::Sqrt(a) => Op::Sqrt(f(a)),
            Op::Pack(a, b, c, d) => Op::Pack(f(a), f(b), f(c), f(d)),
            Op::Lane(a, k) => Op::Lane(f(a), k),
        }
    }

    /// Whether this is a leaf (a constant or an input): leaves cost nothing to recompute.
    #[must_use]
    pub fn is_leaf(self) -> bool {
        matches!(self, Op::Const(_) | Op::Input(_))
    }
}

/// The operands of an [`Op`], in order ([`Op::children`]): a plain array and a count, which
/// an unoptimized build (the tests compile the compiler without optimization) walks
/// several times faster than a chain of iterator adaptors.
#[derive(Clone, Copy, Debug)]
pub struct Operands {
    nodes: [Node; 4],
    len: u8,
    next: u8,
}

impl Iterator for Operands {
    type Item = Node;

    #[inline]
    fn next(&mut self) -> Option<Node> {
        if self.next < self.len {
            let node = self.nodes[usize::from(self.next)];
            self.next += 1;
            Some(node)
        } else {
            None
        }
    }
}

/// Formats the operation with its operands' names, e.g. `v3 * v7` or `q[2]`.
impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Op::Const(c) => write!(f, "{:?}", c.value()),
            Op::Input(r) => write!(f, "{r}"),
            Op::Add(a, b) => write!(f, "{a} + {b}"),
            Op::Sub(a, b) => write!(f, "{a} - {b}"),
            Op::Mul(a, b) => write!(f, "{a} * {b}"),
            Op::Div(a, b) => write!(f, "{a} / {b}"),
            Op::Neg(a) => write!(f, "-{a}"),
            Op::Sin(a) => write!(f, "sin({a})"),
            Op::Cos(a) => write!(f, "cos({a})"),
            Op::Sqrt(a) => write!(f, "sqrt({a})"),
            Op::Pack(a, b, c, d) => write!(f, "[{a}, {b}, {c}, {d}]"),
            Op::Lane(a, k) => write!(f, "{a}[{k}]"),
        }
    }
}

/// The most nodes one graph holds (every candidate a search tried included): about
/// 200 MB for the graph, and a function of some millions of operations, which rustc would
/// take many minutes to compile. Past it the graph is [exhausted](Graph::is_exhausted): a
/// new operation yields the constant 0 instead of a node (so the expansion runs on to its
/// end in bounded time and memory, with meaningless results), and the compiler reports the
/// function as too large instead of generating it.
pub const NODE_BUDGET: usize = 4_000_000;

thread_local! {
    /// The budget of the graphs this thread creates: [`NODE_BUDGET`], lowered by tests.
    static BUDGET: std::cell::Cell<usize> = const { std::cell::Cell::new(NODE_BUDGET) };
}

/// Runs `f` with graphs of at most `budget` nodes (tests of what an exhausted graph does).
#[cfg(test)]
pub(crate) fn with_node_budget<R>(budget: usize, f: impl FnOnce() -> R) -> R {
    let before = BUDGET.with(|b| b.replace(budget));
    let result = f();
    BUDGET.with(|b| b.set(before));
    result
}

/// The hash-consed expression DAG; see the [module documentation](self).
///
/// Builders take `&self` (the node list sits in a [`RefCell`]), so expressions nest.
#[derive(Debug)]
pub struct Graph {
    inner: RefCell<Nodes>,
}

/// The node list and the hash-consing index.
#[derive(Debug)]
struct Nodes {
    ops: Vec<Op>,
    /// Whether each node is packed ([`Op::Pack`], or arithmetic on a packed operand).
    packed: Vec<bool>,
    index: HashMap<Op, Node, BuildHasherDefault<OpHasher>>,
    /// The most operations (not counting leaves) the graph takes ([`NODE_BUDGET`]).
    budget: usize,
    /// Whether an operation was refused for want of budget.
    exhausted: bool,
}

impl Default for Graph {
    fn default() -> Self {
        Graph {
            inner: RefCell::new(Nodes {
                ops: Vec::new(),
                packed: Vec::new(),
                index: HashMap::default(),
                budget: BUDGET.with(std::cell::Cell::get),
                exhausted: false,
            }),
        }
    }
}

/// The hash of the hash-consing index: FxHash's multiply-rotate over the operation's words
/// (an `Op` is a tag and at most two 32-bit ids or one 64-bit constant). Every node is
/// looked up once when it is built, so this hash is the expansion's inner loop; std's
/// SipHash (built against adversarial keys, which node ids are not) cost half of
/// expanding a body of thousands of welded parts. The index is only looked up, never
/// iterated, so the hash decides nothing but speed.
#[derive(Default)]
struct OpHasher(u64);

impl OpHasher {
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
}

impl Hasher for OpHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
    }

    fn write_u8(&mut self, x: u8) {
        self.add(u64::from(x));
    }

    fn write_u32(&mut self, x: u32) {
        self.add(u64::from(x));
    }

    fn write_u64(&mut self, x: u64) {
        self.add(x);
    }

    fn write_usize(&mut self, x: usize) {
        self.add(x as u64);
    }

    fn write_isize(&mut self, x: isize) {
        self.add(x as u64);
    }
}

impl Graph {
    /// An empty graph, with room for [`NODE_BUDGET`] nodes.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether the graph ran out of room ([`NODE_BUDGET`]): its nodes then mean nothing.
    #[must_use]
    pub fn is_exhausted(&self) -> bool {
        self.inner.borrow().exhausted
    }

    /// The number of nodes (live or not).
    #[cfg(test)]
    #[must_use]
    pub fn len(&self) -> usize {
        self.inner.borrow().ops.len()
    }

    /// What `node` computes.
    ///
    /// # Panics
    /// If `node` belongs to another, larger graph.
    #[must_use]
    pub fn op(&self, node: Node) -> Op {
        self.inner.borrow().ops[node.index()]
    }

    /// All nodes' operations in topological order (a snapshot).
    #[must_use]
    pub fn ops(&self) -> Vec<Op> {
        self.inner.borrow().ops.clone()
    }

    /// Whether `node` is a packed value (four lanes).
    #[must_use]
    pub fn is_packed(&self, node: Node) -> bool {
        self.inner.borrow().packed[node.index()]
    }

    /// Whether each node, in id order, is packed.
    #[must_use]
    pub fn packed_flags(&self) -> Vec<bool> {
        self.inner.borrow().packed.clone()
    }

    /// The value of `node` if it is a constant.
    #[must_use]
    pub fn constant_value(&self, node: Node) -> Option<f64> {
        match self.op(node) {
            Op::Const(c) => Some(c.value()),
            _ => None,
        }
    }

    /// The node computing `op`: the existing one if there is one (hash-consing), else a new
    /// node at the end of the list. No rule is applied here; the public builders apply the
    /// rules and then call this with an operation in canonical form.
    pub(crate) fn intern(&self, op: Op) -> Node {
        let mut nodes = self.inner.borrow_mut();
        if let Some(&node) = nodes.index.get(&op) {
            return node;
        }
        // Leaves (constants and inputs) are few and always taken: the constant 0 that stands
        // for a refused operation is one.
        if nodes.ops.len() >= nodes.budget && !op.is_leaf() {
            nodes.exhausted = true;
            drop(nodes);
            return self.zero();
        }
        debug_assert!(
            op.children().all(|c| c.index() < nodes.ops.len()),
            "operand of {op:?} is not in this graph"
        );
        let id = u32::try_from(nodes.ops.len()).expect("more than 2^32 nodes in a graph");
        let node = Node(id);
        let packed = match op {
            Op::Pack(..) => true,
            Op::Lane(..) => false,
            _ => op.children().any(|c| nodes.packed[c.index()]),
        };
        nodes.packed.push(packed);
        nodes.ops.push(op);
        nodes.index.insert(op, node);
        node
    }
}
