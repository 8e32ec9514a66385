//! The fusion pass: a product that only one sum or difference uses is folded into it as a
//! multiply-add ([`fusions`]); the printer writes `isa.mul_add(x, y, c)` for it (`isa` the
//! kernel copy's `Isa<WIDE>`).

use crate::ir::Output;
use crate::sym::{Graph, LiveSet, Node, Op};
use std::collections::HashMap;

/// A sum or difference with a product folded in: ±x·y ± c as `T::mul_add(±x, y, ±c)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Fused {
    /// The product's node, no longer computed on its own.
    pub product: Node,
    /// The product's first factor.
    pub x: Node,
    /// The product's second factor.
    pub y: Node,
    /// The addend.
    pub c: Node,
    /// −x·y (for c − x·y).
    pub negate_product: bool,
    /// −c (for x·y − c).
    pub negate_addend: bool,
}

/// The sums and differences that take in a product nothing else uses: `a·b + c`,
/// `a·b − c` and `c − a·b` become `T::mul_add(a, b, c)`, `T::mul_add(a, b, −c)` and
/// `T::mul_add(−a, b, c)`. Without fused multiply-add hardware `mul_add` is `a·b + c`, the
/// same two roundings as before (x + (−y) and x − y are the same IEEE operation); built for
/// a CPU with FMA (`-C target-cpu=native`) it is one instruction and one rounding.
pub(crate) fn fusions(ops: &[Op], live: &LiveSet, outputs: &[Node]) -> HashMap<Node, Fused> {
    let uses = live.use_counts(ops, outputs);
    let product = |n: Node| match ops[n.index()] {
        Op::Mul(x, y) if uses[n.index()] == 1 => Some((n, x, y)),
        _ => None,
    };
    let mut fused = HashMap::new();
    for n in live.nodes() {
        let f = match ops[n.index()] {
            Op::Add(a, b) => product(a)
                .map(|p| (p, b, false, false))
                .or_else(|| product(b).map(|p| (p, a, false, false))),
            Op::Sub(a, b) => product(a)
                .map(|p| (p, b, false, true))
                .or_else(|| product(b).map(|p| (p, a, true, false))),
            _ => None,
        };
        if let Some(((product, x, y), c, negate_product, negate_addend)) = f {
            fused.insert(
                n,
                Fused {
                    product,
                    x,
                    y,
                    c,
                    negate_product,
                    negate_addend,
                },
            );
        }
    }
    fused
}

/// [`fusions`] of the nodes `output` needs in `graph`.
#[must_use]
pub(crate) fn fuse(graph: &Graph, output: &Output) -> HashMap<Node, Fused> {
    let outputs = output.nodes();
    fusions(&graph.ops(), &graph.live(&outputs), &outputs)
}

#[cfg(test)]
mod tests {
    use super::{fuse, Fused};
    use crate::ir::Output;
    use crate::sym::{Array, Graph};

    /// x·y + c, x·c − y and x − y·c each take their product in; a product that is also an
    /// output, or that two sums use, stays on its own.
    #[test]
    fn a_product_folds_into_its_only_sum() {
        let g = Graph::new();
        let [x, y, c] = [0, 1, 2].map(|k| g.input(Array::Q, k));
        let (p1, p2, p3) = (g.mul(x, y), g.mul(x, c), g.mul(y, c));
        let shared = g.mul(c, c);
        let twice = g.mul(x, x);
        let sums = [
            g.add(p1, c),
            g.sub(p2, y),
            g.sub(x, p3),
            g.add(shared, x),
            g.add(twice, y),
            g.add(twice, c),
        ];
        let mut nodes = sums.to_vec();
        nodes.push(shared);
        let fused = fuse(&g, &Output::Vector(nodes));
        let folded = |n| fused.get(&n).copied();
        let expect = |product, x, y, c, negate_product, negate_addend| Fused {
            product,
            x,
            y,
            c,
            negate_product,
            negate_addend,
        };
        assert_eq!(folded(sums[0]), Some(expect(p1, x, y, c, false, false)));
        // x·c − y is built as −(y − x·c): the difference y − x·c takes it in.
        let crate::sym::Op::Neg(inner) = g.op(sums[1]) else {
            panic!("x·c − y is −(y − x·c) in the graph")
        };
        assert_eq!(folded(inner), Some(expect(p2, x, c, y, true, false)));
        assert_eq!(folded(sums[2]), Some(expect(p3, y, c, x, true, false)));
        for n in [sums[3], sums[4], sums[5]] {
            assert_eq!(folded(n), None, "{}", g.op(n));
        }
        assert_eq!(fused.len(), 3);
    }
}
