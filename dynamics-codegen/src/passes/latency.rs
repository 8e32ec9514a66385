//! The latency pass: sums and products regrouped so that the same terms combine
//! earliest-ready first ([`regroup`], over a function's output; [`Graph::regrouped`]).
//!
//! The expansion writes a sum in the textbook's order, e.g. the forward sweep's
//! α_i = Eᵀα_λ + s q̈ + (Eᵀω_λ) × s q̇ as ((c α_x − s α_y) + q̈) − q̇ ω_y: the term that waits
//! for the parent body (α_λ) enters first, so every later addition waits for it too, and
//! each body of the recursion adds those additions to the chain's length. A processor runs
//! independent operations side by side, so what bounds the straight-line code is that
//! chain: a sum of terms t_k, ready at times r_k, is ready soonest when the two
//! earliest-ready terms are added first and their sum goes back among the rest (Huffman's
//! rule with max(r_a, r_b) + latency in place of r_a + r_b; it gives the least depth for
//! an associative operation).
//!
//! [`Graph::regrouped`] rebuilds every maximal sum — a tree of `+`, `−` and sign flips
//! whose inner nodes nothing else uses — from its signed terms that way, with ready times
//! estimated from the latencies below. Shared partial sums stay as they are (they are
//! leaves), so no common subexpression is lost, and the number of operations does not
//! grow: n terms still take n − 1 additions or subtractions, and a sign flip is needed only
//! when every term is negative (the tree had one then). The result differs from the
//! textbook's order only by the rounding of the additions (an error bound of the same
//! size, not the same bits), which is why it is the last step before emission and why the
//! builders themselves never reassociate.
//!
//! Products are regrouped the same way (a tree of products whose inner products nothing
//! else uses, e.g. c·(s·x) with x late becomes (c·s)·x), and two constant terms or factors
//! that end up combined fold into one constant, so a regrouped function may need fewer
//! operations than the textbook's order.

use crate::ir::Output;
use crate::sym::{Const, Graph, Node, Op};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::collections::HashMap;

/// Estimated latencies in cycles (a current x86-64 core; only their ratios matter): an
/// addition, subtraction or product takes 4, a sign flip 1 (an `xor`), a division 14, a
/// square root 18; a sine or cosine is taken as ready at 40 (the batched evaluation at the
/// top of a function), inputs and constants at 0.
fn latency(op: Op) -> u32 {
    match op {
        Op::Const(_) | Op::Input(_) => 0,
        Op::Add(..) | Op::Sub(..) | Op::Mul(..) => 4,
        Op::Neg(_) => 1,
        Op::Div(..) => 14,
        Op::Sqrt(_) => 18,
        Op::Sin(_) | Op::Cos(_) => 40,
        Op::Pack(..) => 3,
        Op::Lane(..) => 1,
    }
}

/// When `op` is ready, its operands' times given by `ready`.
fn ready_after(op: Op, ready: &[u32]) -> u32 {
    let start = op.children().map(|c| ready[c.index()]).max().unwrap_or(0);
    start + latency(op)
}

/// What a node is part of: a sum (`+`, `−`, sign flip), a product, or neither.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Sum,
    Product,
    Other,
}

fn kind(op: Op) -> Kind {
    match op {
        Op::Add(..) | Op::Sub(..) | Op::Neg(_) => Kind::Sum,
        Op::Mul(..) => Kind::Product,
        _ => Kind::Other,
    }
}

/// A term of a sum or a factor of a product: its node in the new graph, its sign (always
/// positive for a factor), when it is ready, and its place among the terms (ties go to the
/// earlier term, so terms ready at once keep their order).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Term {
    ready: u32,
    place: usize,
    negative: bool,
    node: Node,
}

/// The copy being built: the new graph and each new node's estimated ready time.
///
/// Each new node also gets a place in the emitted code: a node copied from the old graph
/// keeps the place of its old node (`current`, the old node being copied), and a partial
/// sum or product that regrouping makes goes right after the later of its operands, as
/// the builders would have placed it. (Placed at its sum's end instead, every term of a
/// sum would stay in a register until then.)
struct Regrouping {
    graph: Graph,
    ready: Vec<u32>,
    place: Vec<(usize, u32, usize)>,
    current: usize,
}

impl Regrouping {
    /// The node computing `op`; `partial` for a partial sum or product made by regrouping.
    fn intern(&mut self, op: Op, partial: bool) -> Node {
        let node = self.graph.intern(op);
        if node.index() == self.ready.len() {
            self.ready.push(ready_after(op, &self.ready));
            let after = op
                .children()
                .map(|c| self.place[c.index()])
                .max()
                .unwrap_or((0, 0, 0));
            self.place.push(if partial {
                (after.0, after.1 + 1, node.index())
            } else {
                (self.current, 0, node.index())
            });
        }
        node
    }

    /// The graph with its nodes in the order of their places, and where each old node went.
    fn into_ordered(self) -> (Graph, Vec<Node>) {
        let ops = self.graph.ops();
        let mut order: Vec<usize> = (0..ops.len()).collect();
        order.sort_by_key(|&i| self.place[i]);
        let ordered = Graph::new();
        let mut moved = vec![Node(0); ops.len()];
        for i in order {
            moved[i] = ordered.intern(ops[i].with_children(|n| moved[n.index()]));
        }
        (ordered, moved)
    }

    fn term(&self, node: Node, negative: bool, place: usize) -> Term {
        Term {
            ready: self.ready[node.index()],
            place,
            negative,
            node,
        }
    }

    /// Two terms of a sum as one: a + b, a − b, b − a, or −(a + b) kept as a negative term;
    /// two constants fold.
    fn add(&mut self, a: Term, b: Term, place: usize) -> Term {
        let signed = |t: Term, x: f64| if t.negative { -x } else { x };
        if let (Some(x), Some(y)) = (
            self.graph.constant_value(a.node),
            self.graph.constant_value(b.node),
        ) {
            let node = self.intern(Op::Const(Const::new(signed(a, x) + signed(b, y))), true);
            return self.term(node, false, place);
        }
        let (lo, hi) = (a.node.min(b.node), a.node.max(b.node));
        let (op, negative) = match (a.negative, b.negative) {
            (false, false) => (Op::Add(lo, hi), false),
            (true, true) => (Op::Add(lo, hi), true),
            (false, true) => (Op::Sub(a.node, b.node), false),
            (true, false) => (Op::Sub(b.node, a.node), false),
        };
        let node = self.intern(op, true);
        self.term(node, negative, place)
    }

    /// Two factors of a product as one; two constants fold.
    fn mul(&mut self, a: Term, b: Term, place: usize) -> Term {
        let op = match (
            self.graph.constant_value(a.node),
            self.graph.constant_value(b.node),
        ) {
            (Some(x), Some(y)) => Op::Const(Const::new(x * y)),
            _ => Op::Mul(a.node.min(b.node), a.node.max(b.node)),
        };
        let node = self.intern(op, true);
        self.term(node, false, place)
    }

    /// The terms combined two at a time, the two earliest-ready first (Huffman's rule).
    fn combine(
        &mut self,
        terms: Vec<Term>,
        mut pair: impl FnMut(&mut Self, Term, Term, usize) -> Term,
    ) -> Term {
        let mut place = terms.len();
        let mut heap: BinaryHeap<Reverse<Term>> = terms.into_iter().map(Reverse).collect();
        loop {
            match (heap.pop(), heap.pop()) {
                (Some(Reverse(a)), Some(Reverse(b))) => {
                    heap.push(Reverse(pair(self, a, b, place)));
                    place += 1;
                }
                (Some(Reverse(last)), None) => return last,
                _ => unreachable!("a sum or product has a term"),
            }
        }
    }
}

/// The same output in a new graph whose sums and products combine their earliest-ready
/// terms first ([`Graph::regrouped`]).
#[must_use]
pub(crate) fn regroup(graph: &Graph, output: &Output) -> (Graph, Output) {
    let old = output.nodes();
    let (graph, new) = graph.regrouped(&old);
    let map: HashMap<Node, Node> = old.into_iter().zip(new).collect();
    (graph, output.map(&|n| map[&n]))
}

impl Graph {
    /// A new graph holding what `outputs` need, with every sum and product regrouped so
    /// that its earliest-ready terms are combined first (module documentation), and the
    /// outputs' nodes in it. Nodes keep the order of the old graph, so the emitted code
    /// keeps its order (partial sums and products: see `Regrouping`).
    #[must_use]
    pub fn regrouped(&self, outputs: &[Node]) -> (Graph, Vec<Node>) {
        let ops = self.ops();
        let live = self.live(outputs);
        let uses = live.use_counts(&ops, outputs);
        let mut user = vec![None; ops.len()];
        for node in live.nodes() {
            for child in ops[node.index()].children() {
                user[child.index()] = Some(node);
            }
        }
        // Inner nodes: a sum that one sum alone uses, a product that one product alone uses
        // (read once, and that once by an operation: so not an output).
        let inner: Vec<bool> = (0..ops.len())
            .map(|i| {
                kind(ops[i]) != Kind::Other
                    && uses[i] == 1
                    && user[i].is_some_and(|u| kind(ops[u.index()]) == kind(ops[i]))
            })
            .collect();

        let mut copy = Regrouping {
            graph: Graph::new(),
            ready: Vec::new(),
            place: Vec::new(),
            current: 0,
        };
        let mut map: Vec<Option<Node>> = vec![None; ops.len()];
        for old in live.nodes() {
            let i = old.index();
            if inner[i] {
                continue;
            }
            copy.current = i;
            let m = |n: Node| map[n.index()].expect("operands are mapped before their users");
            let op = ops[i];
            let node = if kind(op) == Kind::Other {
                copy.intern(op.with_children(m), false)
            } else {
                let mut leaves = Vec::new();
                collect_terms(&ops, &inner, old, false, &mut leaves, true);
                let terms = leaves
                    .iter()
                    .enumerate()
                    .map(|(place, &(negative, leaf))| copy.term(m(leaf), negative, place))
                    .collect();
                if kind(op) == Kind::Product {
                    copy.combine(terms, Regrouping::mul).node
                } else {
                    let last = copy.combine(terms, Regrouping::add);
                    if last.negative {
                        copy.intern(Op::Neg(last.node), false)
                    } else {
                        last.node
                    }
                }
            };
            map[i] = Some(node);
        }
        let (graph, moved) = copy.into_ordered();
        let outputs = outputs
            .iter()
            .map(|o| moved[map[o.index()].expect("outputs are live").index()])
            .collect();
        (graph, outputs)
    }
}

impl Graph {
    /// The estimated time from the inputs to the last of `outputs`, in cycles of the
    /// latencies above: the longest chain of dependent operations, which bounds straight-line
    /// code however many operations the processor runs side by side.
    #[must_use]
    pub fn longest_chain(&self, outputs: &[Node]) -> u32 {
        let ops = self.ops();
        let mut ready = vec![0_u32; ops.len()];
        for node in self.live(outputs).nodes() {
            ready[node.index()] = ready_after(ops[node.index()], &ready);
        }
        outputs.iter().map(|o| ready[o.index()]).max().unwrap_or(0)
    }
}

/// The signed terms of the sum, or the factors of the product, rooted at `node`: descends
/// through the root and through `inner` nodes of its kind (`+`, `−` and sign flips, or
/// products), and stops at anything else.
fn collect_terms(
    ops: &[Op],
    inner: &[bool],
    node: Node,
    negative: bool,
    terms: &mut Vec<(bool, Node)>,
    root: bool,
) {
    if !root && !inner[node.index()] {
        terms.push((negative, node));
        return;
    }
    match ops[node.index()] {
        Op::Add(a, b) | Op::Mul(a, b) => {
            collect_terms(ops, inner, a, negative, terms, false);
            collect_terms(ops, inner, b, negative, terms, false);
        }
        Op::Sub(a, b) => {
            collect_terms(ops, inner, a, negative, terms, false);
            collect_terms(ops, inner, b, !negative, terms, false);
        }
        Op::Neg(a) => collect_terms(ops, inner, a, !negative, terms, false),
        _ => terms.push((negative, node)),
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::{Array, Graph, Node};

    /// `depth` nested square roots of x: ready late.
    fn late(g: &Graph, x: Node, depth: usize) -> Node {
        (0..depth).fold(x, |acc, _| g.sqrt(acc))
    }

    /// ((late − a) + b) − c regrouped adds the late term last, with the same operations
    /// and a value equal up to rounding.
    #[test]
    fn the_latest_term_is_added_last() {
        let g = Graph::new();
        let [x, a, b, c] = [0, 1, 2, 3].map(|k| g.input(Array::Q, k));
        let slow = late(&g, x, 3);
        let sum = g.sub(g.add(g.sub(slow, a), b), c);
        let (new, outs) = g.regrouped(&[sum]);
        let (before, after) = (g.op_count(&[sum]), new.op_count(&outs));
        assert_eq!((after.add, after.mul), (before.add, before.mul));
        // The builders' orientation rule wrote slow − a as −(a − slow); the sign folds away.
        assert_eq!((before.neg, after.neg), (1, 0));
        let root = outs[0];
        let crate::sym::Op::Add(p, q) = new.op(root) else {
            panic!("root is {}", new.op(root))
        };
        assert!(
            [p, q]
                .iter()
                .any(|&n| matches!(new.op(n), crate::sym::Op::Sqrt(..))),
            "the square root enters at the root: {}",
            new.op(root)
        );
        let input = |r: crate::sym::InputRef| [1.1, 0.3, -2.0, 0.7][r.index as usize];
        let before = g.eval(input, &[sum])[0];
        let after = new.eval(input, &outs)[0];
        assert!(
            (before - after).abs() <= 1e-15 * before.abs(),
            "{before} vs {after}"
        );
    }

    /// A shared partial sum is a term of each sum using it, computed once; a sum of only
    /// negative terms keeps its one sign flip, and a sign flip over a sum with a positive
    /// term disappears.
    #[test]
    fn shared_sums_stay_and_signs_do_not_add_operations() {
        let g = Graph::new();
        let [a, b, c, d] = [0, 1, 2, 3].map(|k| g.input(Array::V, k));
        let shared = g.add(a, b);
        let one = g.add(shared, c);
        let two = g.sub(shared, d);
        let all_negative = g.neg(g.add(c, d));
        let flipped = g.neg(g.sub(c, g.mul(a, d)));
        let outputs = [one, two, all_negative, flipped];
        let (new, outs) = g.regrouped(&outputs);
        let before = g.op_count(&outputs);
        let after = new.op_count(&outs);
        assert_eq!((after.add, after.mul), (before.add, before.mul));
        // Before: −(d − shared) for shared − d (the builders' orientation rule), −(c + d) and
        // −(c − a·d). After: shared − d and a·d − c need none; −(c + d) keeps its one.
        assert_eq!((before.neg, after.neg), (3, 1), "{after} vs {before}");
        let input = |r: crate::sym::InputRef| [0.5, -1.25, 3.0, 0.75][r.index as usize];
        assert_eq!(g.eval(input, &outputs), new.eval(input, &outs));
    }

    /// Random DAGs of sums, differences, sign flips and products with shared nodes (every
    /// node is an output in turn): the regrouped graph needs no more operations and agrees
    /// with the original up to the rounding of the regrouped additions.
    #[test]
    fn random_dags_keep_their_values_and_operation_counts() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        for case in 0..300 {
            let g = Graph::new();
            let mut nodes: Vec<Node> = (0..4).map(|k| g.input(Array::A, k)).collect();
            for _ in 0..30 {
                let len = nodes.len() as u64;
                let a = nodes[next(len) as usize];
                let b = nodes[next(len) as usize];
                nodes.push(match next(5) {
                    0 | 1 => g.add(a, b),
                    2 => g.sub(a, b),
                    3 => g.neg(a),
                    _ => g.mul(a, b),
                });
            }
            let outputs: Vec<Node> = nodes.iter().rev().step_by(3).copied().collect();
            let (new, outs) = g.regrouped(&outputs);
            let (before, after) = (g.op_count(&outputs), new.op_count(&outs));
            assert!(
                after.add <= before.add && after.mul <= before.mul && after.neg <= before.neg,
                "case {case}: {after} vs {before}"
            );
            let input = |r: crate::sym::InputRef| [0.3, -1.7, 2.2, 0.9][r.index as usize];
            let (x, y) = (g.eval(input, &outputs), new.eval(input, &outs));
            for (k, (x, y)) in x.iter().zip(&y).enumerate() {
                let scale = x.abs().max(1.0);
                assert!(
                    (x - y).abs() <= 1e-9 * scale,
                    "case {case}, output {k}: {x} vs {y}"
                );
            }
        }
    }

    /// c·(y·late) becomes (c·y)·late, and 2·(3·late) becomes 6·late: one product fewer.
    #[test]
    fn products_take_the_late_factor_last_and_fold_constants() {
        let g = Graph::new();
        let [x, y] = [0, 1].map(|k| g.input(Array::Q, k));
        let slow = late(&g, x, 2);
        let scaled = g.mul(g.constant(0.5), g.mul(y, slow));
        let folded = g.mul(g.constant(2.0), g.mul(g.constant(3.0), slow));
        let (new, outs) = g.regrouped(&[scaled, folded]);
        let crate::sym::Op::Mul(p, q) = new.op(outs[0]) else {
            panic!("{}", new.op(outs[0]))
        };
        assert!(
            [p, q]
                .iter()
                .any(|&n| matches!(new.op(n), crate::sym::Op::Sqrt(..))),
            "the square root is the last factor: {}",
            new.op(outs[0])
        );
        let crate::sym::Op::Mul(p, q) = new.op(outs[1]) else {
            panic!("{}", new.op(outs[1]))
        };
        assert!([p, q].iter().any(|&n| new.constant_value(n) == Some(6.0)));
        assert_eq!(g.op_count(&[folded]).mul, 2);
        assert_eq!(new.op_count(&outs[1..]).mul, 1);
    }

    /// a + b + c + d with d late: the chain is d's time plus one addition once regrouped,
    /// three additions after a before.
    #[test]
    fn longest_chain_counts_the_dependent_operations() {
        let g = Graph::new();
        let [a, b, c, x] = [0, 1, 2, 3].map(|k| g.input(Array::V, k));
        let d = late(&g, x, 2);
        let sum = g.add(g.add(g.add(d, a), b), c);
        assert_eq!(g.longest_chain(&[sum]), 2 * 18 + 3 * 4);
        let (new, outs) = g.regrouped(&[sum]);
        assert_eq!(new.longest_chain(&outs), 2 * 18 + 4);
    }
}
