//! The sign-settling pass: a sign that the builders' orientation rule left on an output is
//! folded into the operation under it, −(a − b) as b − a and −(c·x) as (−c)·x for a
//! constant c, where nothing else uses that operation ([`settle`]). A shared product or
//! difference keeps its negation (one sign flip) rather than being computed a second time.

use crate::ir::Output;
use crate::sym::{Graph, Node, Op};

/// The same output with each negated output node settled ([`Graph::settled`]) where the
/// node under the sign has no other use.
#[must_use]
pub(crate) fn settle(graph: &Graph, output: &Output) -> Output {
    let nodes = output.nodes();
    let uses = graph.live(&nodes).use_counts(&graph.ops(), &nodes);
    output.map(&|n| match graph.op(n) {
        Op::Neg(x) if uses[x.index()] == 1 => graph.settled(n),
        _ => n,
    })
}

impl Graph {
    /// `node` computed without a trailing negation where one costs nothing: −(a − b) as
    /// b − a and −(c·x) as (−c)·x for a constant c; any other node as it is. For outputs
    /// only, after the graph is built: the nodes it makes are outside the canonical forms
    /// the builders produce, so the builders never reuse them.
    pub(crate) fn settled(&self, node: Node) -> Node {
        let Op::Neg(x) = self.op(node) else {
            return node;
        };
        match self.op(x) {
            Op::Sub(a, b) => self.intern(Op::Sub(b, a)),
            Op::Mul(a, b) => match (self.constant_value(a), self.constant_value(b)) {
                (Some(c), _) => self.intern(Op::Mul(self.constant(-c), b)),
                (None, Some(c)) => self.intern(Op::Mul(a, self.constant(-c))),
                (None, None) => node,
            },
            _ => node,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::settle;
    use crate::ir::Output;
    use crate::sym::{Array, Graph, Op};

    /// A sign on an output folds into the operation under it when nothing else uses that
    /// operation, and stays a negation when something does (no product computed twice).
    #[test]
    fn output_signs_fold_only_into_unshared_operations() {
        let g = Graph::new();
        let (x, y) = (g.input(Array::Q, 0), g.input(Array::Q, 1));
        let half = g.constant(0.5);
        let alone = g.neg(g.mul(x, half)); // −(x·0.5), the product used only here
        let shared = g.mul(y, half);
        let difference = g.sub(y, x); // −(x − y) in the graph's orientation
        let out = Output::Vector(vec![alone, g.neg(shared), shared, difference]);
        let Output::Vector(settled) = settle(&g, &out) else {
            unreachable!("a vector stays a vector")
        };
        assert_eq!(g.op(settled[0]), Op::Mul(x, g.constant(-0.5)));
        assert_eq!(
            g.op(settled[1]),
            Op::Neg(shared),
            "the shared product is not redone"
        );
        assert_eq!(settled[2], shared);
        assert_eq!(g.op(settled[3]), Op::Sub(y, x));
        let before = g.eval(|r| [0.3, -1.7][r.index as usize], &out.nodes());
        let after = g.eval(|r| [0.3, -1.7][r.index as usize], &settled);
        assert_eq!(before, after);
    }
}
