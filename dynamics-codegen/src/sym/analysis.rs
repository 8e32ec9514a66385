//! What is computed from a finished graph: the live set of some outputs, their operation
//! count, their value in `f64`, and a readable dump.

use super::{Graph, InputRef, Node, Op};
use std::fmt;
#[cfg(test)]
use std::fmt::Write as _;

/// The nodes that some outputs need, directly or through operands. Everything else in the
/// graph is dead code and is not emitted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LiveSet {
    live: Vec<bool>,
}

impl LiveSet {
    /// Whether `node` is live.
    #[cfg(test)]
    #[must_use]
    pub fn contains(&self, node: Node) -> bool {
        self.live.get(node.index()).copied().unwrap_or(false)
    }

    /// The number of live nodes.
    #[must_use]
    pub fn count(&self) -> usize {
        self.live.iter().filter(|&&l| l).count()
    }

    /// The live nodes in topological (id) order.
    pub fn nodes(&self) -> impl Iterator<Item = Node> + '_ {
        self.live
            .iter()
            .enumerate()
            .filter(|(_, &l)| l)
            .map(|(i, _)| Node(u32::try_from(i).expect("node ids fit in u32")))
    }

    /// How many times each node of `ops` (the graph's operations) is read: as an operand
    /// of a live node, or as one of `outputs`.
    #[must_use]
    pub fn use_counts(&self, ops: &[Op], outputs: &[Node]) -> Vec<u32> {
        let mut uses = vec![0_u32; ops.len()];
        for n in self.nodes() {
            for c in ops[n.index()].children() {
                uses[c.index()] += 1;
            }
        }
        for n in outputs {
            uses[n.index()] += 1;
        }
        uses
    }
}

/// How many operations of each kind a set of outputs costs (each live node once).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Multiplications.
    pub mul: usize,
    /// Additions and subtractions.
    pub add: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Sines and cosines, each counted (a `sin_cos` pair counts 2).
    pub trig: usize,
    /// How many of the operations above are on packed values (four lanes in one SIMD
    /// instruction; `Graph::pack`).
    pub packed: usize,
}

/// `47 mul, 39 add, 0 div, 2 trig`; negations and square roots are listed (before `trig`)
/// only when there are some.
impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} mul, {} add, {} div", self.mul, self.add, self.div)?;
        if self.neg > 0 {
            write!(f, ", {} neg", self.neg)?;
        }
        if self.sqrt > 0 {
            write!(f, ", {} sqrt", self.sqrt)?;
        }
        write!(f, ", {} trig", self.trig)?;
        if self.packed > 0 {
            write!(f, " ({} of them on 4 lanes)", self.packed)?;
        }
        Ok(())
    }
}

impl OpCount {
    /// All operations, each counted once (a sine or cosine as one).
    #[must_use]
    pub fn total(&self) -> usize {
        self.mul + self.add + self.div + self.neg + self.sqrt + self.trig
    }
}

impl Graph {
    /// The nodes needed to compute `outputs`.
    ///
    /// One backward pass: the list is topologically ordered, so when a node is reached all
    /// of its users have been seen.
    ///
    /// # Panics
    /// If an output is not a node of this graph.
    #[must_use]
    pub fn live(&self, outputs: &[Node]) -> LiveSet {
        let nodes = self.inner.borrow();
        let mut live = vec![false; nodes.ops.len()];
        for &out in outputs {
            live[out.index()] = true;
        }
        for i in (0..nodes.ops.len()).rev() {
            if live[i] {
                for child in nodes.ops[i].children() {
                    live[child.index()] = true;
                }
            }
        }
        LiveSet { live }
    }

    /// The operations that computing `outputs` costs, each live node counted once.
    /// Constants and inputs are free.
    #[must_use]
    pub fn op_count(&self, outputs: &[Node]) -> OpCount {
        let mut count = OpCount::default();
        for node in self.live(outputs).nodes() {
            match self.op(node) {
                Op::Const(_) | Op::Input(_) | Op::Pack(..) | Op::Lane(..) => {}
                Op::Add(..) | Op::Sub(..) => count.add += 1,
                Op::Mul(..) => count.mul += 1,
                Op::Div(..) => count.div += 1,
                Op::Neg(_) => count.neg += 1,
                Op::Sqrt(_) => count.sqrt += 1,
                Op::Sin(_) | Op::Cos(_) => count.trig += 1,
            }
            if self.is_packed(node) && !matches!(self.op(node), Op::Pack(..)) {
                count.packed += 1;
            }
        }
        count
    }

    /// The values of `outputs` in `f64`, with `input` giving each input element's value.
    /// Only live nodes are evaluated, in the graph's order, as the emitted code computes
    /// them for `T = f64` (but for its multiply-adds, fused on a CPU with FMA, and its
    /// sines and cosines, which may differ from `f64::sin` and `f64::cos` in the last bit):
    /// the tests' reference values, the compile-time rank checks of the force analysis and
    /// the loop closures, and [`crate::Compiled::evaluate`].
    #[must_use]
    pub fn eval(&self, input: impl Fn(InputRef) -> f64, outputs: &[Node]) -> Vec<f64> {
        let live = self.live(outputs);
        let ops = self.inner.borrow();
        // Four lanes a node: a scalar's value in every lane.
        let mut value = vec![[f64::NAN; 4]; ops.ops.len()];
        for node in live.nodes() {
            let v = |n: Node| value[n.index()];
            let lanes = |f: &dyn Fn(usize) -> f64| std::array::from_fn(f);
            value[node.index()] = match ops.ops[node.index()] {
                Op::Const(c) => [c.value(); 4],
                Op::Input(r) => [input(r); 4],
                Op::Add(a, b) => lanes(&|k| v(a)[k] + v(b)[k]),
                Op::Sub(a, b) => lanes(&|k| v(a)[k] - v(b)[k]),
                Op::Mul(a, b) => lanes(&|k| v(a)[k] * v(b)[k]),
                Op::Div(a, b) => lanes(&|k| v(a)[k] / v(b)[k]),
                Op::Neg(a) => lanes(&|k| -v(a)[k]),
                Op::Sin(a) => lanes(&|k| v(a)[k].sin()),
                Op::Cos(a) => lanes(&|k| v(a)[k].cos()),
                Op::Sqrt(a) => lanes(&|k| v(a)[k].sqrt()),
                Op::Pack(a, b, c, d) => [v(a)[0], v(b)[0], v(c)[0], v(d)[0]],
                Op::Lane(a, k) => [v(a)[usize::from(k)]; 4],
            };
        }
        outputs.iter().map(|n| value[n.index()][0]).collect()
    }

    /// The live part of the graph for `outputs`, one `vN = …` line per node, then the
    /// outputs; for debugging and test failure messages.
    #[must_use]
    #[cfg(test)]
    pub fn dump(&self, outputs: &[Node]) -> String {
        let mut text = String::new();
        for node in self.live(outputs).nodes() {
            let _ = writeln!(text, "{node} = {}", self.op(node));
        }
        let names: Vec<String> = outputs.iter().map(Node::to_string).collect();
        let _ = writeln!(text, "outputs: [{}]", names.join(", "));
        text
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Array, Graph, InputRef, Node};
    use super::OpCount;

    fn input_values(r: InputRef) -> f64 {
        match r.array {
            Array::Q => [0.3, -1.2][r.index as usize],
            Array::V => [2.0, 0.5][r.index as usize],
            _ => panic!("unexpected input {r}"),
        }
    }

    #[test]
    fn liveness_keeps_only_what_outputs_need() {
        let g = Graph::new();
        let x = g.input(Array::Q, 0);
        let y = g.input(Array::Q, 1);
        let dead = g.sin(g.add(x, y));
        let used = g.mul(x, g.cos(x));
        let live = g.live(&[used]);
        assert!(live.contains(x) && live.contains(used) && live.contains(g.cos(x)));
        assert!(!live.contains(y) && !live.contains(dead));
        assert_eq!(live.count(), 3);
        let nodes: Vec<Node> = live.nodes().collect();
        assert_eq!(nodes, vec![x, g.cos(x), used]);
        assert_eq!(g.live(&[]).count(), 0);
    }

    #[test]
    fn op_count_counts_each_live_node_once() {
        let g = Graph::new();
        let q0 = g.input(Array::Q, 0);
        let v0 = g.input(Array::V, 0);
        let (s, c) = (g.sin(q0), g.cos(q0));
        let sv = g.mul(s, v0);
        let a = g.sub(sv, c); // sv used twice below, counted once
        let b = g.add(sv, g.constant(2.0));
        let d = g.div(a, g.sqrt(b));
        let n = g.neg(g.mul(d, g.constant(3.0)));
        let _dead = g.mul(c, c);
        let count = g.op_count(&[n, a]);
        assert_eq!(
            count,
            OpCount {
                mul: 2,
                add: 2,
                div: 1,
                neg: 1,
                sqrt: 1,
                trig: 2,
                packed: 0,
            }
        );
        assert_eq!(
            count.to_string(),
            "2 mul, 2 add, 1 div, 1 neg, 1 sqrt, 2 trig"
        );
        let plain = OpCount {
            mul: 47,
            add: 39,
            trig: 2,
            ..OpCount::default()
        };
        assert_eq!(plain.to_string(), "47 mul, 39 add, 0 div, 2 trig");
        let packed = OpCount {
            packed: 80,
            ..plain
        };
        assert_eq!(
            packed.to_string(),
            "47 mul, 39 add, 0 div, 2 trig (80 of them on 4 lanes)"
        );
    }

    #[test]
    fn eval_matches_hand_computed_values() {
        let g = Graph::new();
        let q0 = g.input(Array::Q, 0);
        let q1 = g.input(Array::Q, 1);
        let v0 = g.input(Array::V, 0);
        // l·cos(q0)·v0 − sin(q1)/√(v0 + 2), and a constant and an input as outputs.
        let l = g.constant(0.75);
        let e = g.sub(
            g.mul(g.mul(l, g.cos(q0)), v0),
            g.div(g.sin(q1), g.sqrt(g.add(v0, g.constant(2.0)))),
        );
        let out = g.eval(input_values, &[e, l, q1, g.neg(q0)]);
        let expected = 0.75 * 0.3_f64.cos() * 2.0 - (-1.2_f64).sin() / 4.0_f64.sqrt();
        assert_eq!(out, vec![expected, 0.75, -1.2, -0.3]);
    }

    #[test]
    fn dump_lists_live_nodes() {
        let g = Graph::new();
        let x = g.input(Array::Q, 0);
        let y = g.mul(x, g.constant(-0.5)); // v1 = −0.5 is created, and dead
        assert_eq!(
            g.dump(&[y]),
            "v0 = q[0]\nv2 = 0.5\nv3 = v0 * v2\nv4 = -v3\noutputs: [v4]\n"
        );
    }
}
