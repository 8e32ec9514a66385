//! Packed values: four scalar values side by side in one node, for code that does the same
//! work on four columns of a matrix or four isomorphic limbs at once.
//!
//! [`Graph::pack`] makes a packed node of four scalar lanes; arithmetic with a packed
//! operand is packed, a scalar operand taking part in every lane (a broadcast), so the
//! expansions' vector helpers ([`super::Vec3`], [`super::Mat3`]) work on packed values
//! unchanged; [`Graph::lane`] reads one lane back as a scalar. A packed operation costs one
//! SIMD instruction where the four scalar ones cost four (the printer emits
//! `dynamics_runtime::pack::P4`), and lane k of every packed operation is the scalar
//! operation on lane k: the values are bit for bit those of the four scalar expressions.
//!
//! [`Graph::zip`] turns four lanes' expressions of the same shape (the same operations on
//! different constants and inputs, as a left and a right leg's transforms are) into one
//! packed expression: packs at the leaves, one packed operation above them.

use super::{Graph, Node, Op};
use std::collections::HashMap;

impl Graph {
    /// Four scalar values as one packed value: `a` itself when the four are `a`, and
    /// −pack(x₀, …, x₃) when every lane is a negation −x_k (so that signs keep moving
    /// outwards, as the builders' negation rules move them).
    ///
    /// # Panics
    /// If a lane is itself packed.
    pub fn pack(&self, lanes: [Node; 4]) -> Node {
        assert!(
            lanes.iter().all(|&n| !self.is_packed(n)),
            "the lanes of a pack are scalars"
        );
        if lanes.iter().all(|&n| n == lanes[0]) {
            return lanes[0];
        }
        if lanes.iter().all(|&n| self.negated(n).is_some()) {
            let positive = lanes.map(|n| self.negated(n).unwrap_or(n));
            return self.neg(self.pack(positive));
        }
        let [a, b, c, d] = lanes;
        self.intern(Op::Pack(a, b, c, d))
    }

    /// Lane `k` of `x` as a scalar: `x` itself when it is a scalar (the same in every
    /// lane), the lane's own node when `x` is a [`Graph::pack`].
    ///
    /// # Panics
    /// If `k` is not 0 to 3.
    pub fn lane(&self, x: Node, k: usize) -> Node {
        assert!(k < 4, "lane {k} of four");
        if !self.is_packed(x) {
            return x;
        }
        match self.op(x) {
            Op::Pack(a, b, c, d) => [a, b, c, d][k],
            _ => self.intern(Op::Lane(x, u8::try_from(k).unwrap_or(0))),
        }
    }

    /// `f` of scalar `operands`, computed on the packs they are lanes of: where every
    /// operand read from a pack is lane k of it (`Graph::lane`), lane k of `f` over the packs
    /// (the other operands, scalars, taking part in every lane), so that the rows of a
    /// matrix whose entries are the lanes of one pack share one packed evaluation of `f`;
    /// otherwise `f` of the operands. `f` must treat its operands lane by lane (sums,
    /// products): lane k of the packed value is then `f` of the operands, bit for bit.
    pub fn lanewise(&self, operands: &[Node], f: impl Fn(&[Node]) -> Node) -> Node {
        let lanes: Vec<(Node, u8)> = operands
            .iter()
            .filter_map(|&n| match self.op(n) {
                Op::Lane(pack, k) => Some((pack, k)),
                _ => None,
            })
            .collect();
        let Some(&(_, k)) = lanes.first() else {
            return f(operands);
        };
        if lanes.iter().any(|&(_, other)| other != k) {
            return f(operands);
        }
        let packs: Vec<Node> = operands
            .iter()
            .map(|&n| match self.op(n) {
                Op::Lane(pack, _) => pack,
                _ => n,
            })
            .collect();
        self.lane(f(&packs), usize::from(k))
    }

    /// The four lanes' scalar expressions as one packed expression of the same shape: where
    /// the four apply the same operation, that operation on their zipped operands (the
    /// operands of a sum or product matched by kind, as the builders order them by id);
    /// where they agree, the common node; elsewhere the [`Graph::pack`] of the lanes.
    pub fn zip(&self, lanes: [Node; 4]) -> Node {
        self.zip_memo(lanes, &mut HashMap::new())
    }

    fn zip_memo(&self, lanes: [Node; 4], memo: &mut HashMap<[Node; 4], Node>) -> Node {
        if lanes.iter().all(|&n| n == lanes[0]) {
            return lanes[0];
        }
        if let Some(&n) = memo.get(&lanes) {
            return n;
        }
        let ops = lanes.map(|n| self.op(n));
        let zipped = match ops[0] {
            Op::Add(..) | Op::Sub(..) | Op::Mul(..) => self.binary_operands(ops).map(|(a, b)| {
                let (a, b) = (self.zip_memo(a, memo), self.zip_memo(b, memo));
                match ops[0] {
                    Op::Add(..) => self.add(a, b),
                    Op::Sub(..) => self.sub(a, b),
                    _ => self.mul(a, b),
                }
            }),
            Op::Neg(_) => {
                let operands = ops.map(|op| match op {
                    Op::Neg(a) => Some(a),
                    _ => None,
                });
                match operands {
                    [Some(a), Some(b), Some(c), Some(d)] => {
                        Some(self.neg(self.zip_memo([a, b, c, d], memo)))
                    }
                    _ => None,
                }
            }
            _ => None,
        };
        let n = zipped.unwrap_or_else(|| self.pack(lanes));
        memo.insert(lanes, n);
        n
    }

    /// The operands of four binary operations of one kind, lane by lane, when all four
    /// are of the kind of `ops[0]`; for a sum or product, each lane's two operands put in
    /// the order whose operations' kinds match lane 0's.
    fn binary_operands(&self, ops: [Op; 4]) -> Option<([Node; 4], [Node; 4])> {
        let kind = std::mem::discriminant(&ops[0]);
        let pair = |op: Op| match op {
            Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) => (a, b),
            _ => unreachable!("binary operations only"),
        };
        if ops.iter().any(|op| std::mem::discriminant(op) != kind) {
            return None;
        }
        let commutes = !matches!(ops[0], Op::Sub(..));
        let first = pair(ops[0]);
        let kind_of = |n: Node| std::mem::discriminant(&self.op(n));
        let mut a = [first.0; 4];
        let mut b = [first.1; 4];
        for k in 1..4 {
            let (x, y) = pair(ops[k]);
            let swap = commutes
                && kind_of(x) != kind_of(first.0)
                && kind_of(y) == kind_of(first.0)
                && kind_of(x) == kind_of(first.1);
            (a[k], b[k]) = if swap { (y, x) } else { (x, y) };
        }
        Some((a, b))
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::{Array, Graph, InputRef, Op};

    fn q(g: &Graph, k: usize) -> crate::sym::Node {
        g.input(Array::Q, k)
    }

    #[test]
    fn a_lane_of_a_pack_is_its_own_node_and_a_scalar_is_every_lane() {
        let g = Graph::new();
        let lanes = [q(&g, 0), q(&g, 1), q(&g, 2), q(&g, 3)];
        let p = g.pack(lanes);
        assert!(g.is_packed(p));
        for (k, &l) in lanes.iter().enumerate() {
            assert_eq!(g.lane(p, k), l);
            assert_eq!(g.lane(lanes[0], k), lanes[0]);
        }
        assert_eq!(g.pack([lanes[1]; 4]), lanes[1]);
        // Arithmetic on a pack is packed; its lanes read back through `Lane`.
        let s = g.add(p, lanes[0]);
        assert!(g.is_packed(s));
        assert!(matches!(g.op(g.lane(s, 2)), Op::Lane(_, 2)));
    }

    #[test]
    fn a_pack_of_negations_is_the_negation_of_a_pack() {
        let g = Graph::new();
        let lanes = [q(&g, 0), q(&g, 1), q(&g, 2), q(&g, 3)];
        let negated = g.pack(lanes.map(|x| g.neg(x)));
        assert_eq!(g.op(negated), Op::Neg(g.pack(lanes)));
    }

    #[test]
    fn zipping_four_expressions_of_one_shape_packs_their_leaves_only() {
        let g = Graph::new();
        // c_k · q_k + q_4 − 2 q_k, with different constants c_k (operands created in
        // different orders, so sorted differently by id).
        let lanes: [_; 4] = std::array::from_fn(|k| {
            let (c, x) = if k % 2 == 0 {
                (g.constant(1.5 + k as f64), q(&g, k))
            } else {
                let x = q(&g, k);
                (g.constant(1.5 + k as f64), x)
            };
            g.sub(g.add(g.mul(c, x), q(&g, 4)), g.mul(g.constant(2.0), x))
        });
        let zipped = g.zip(lanes);
        let packs = g
            .ops()
            .iter()
            .filter(|op| matches!(op, Op::Pack(..)))
            .count();
        assert_eq!(
            packs,
            2,
            "one pack of constants, one of inputs:\n{}",
            g.dump(&[zipped])
        );
        let ops = g.op_count(&[zipped]);
        assert_eq!(ops.mul + ops.add, 4, "four packed operations: {ops}");
        let input = |r: InputRef| 0.25 + f64::from(r.index);
        for (k, &lane) in lanes.iter().enumerate() {
            let expected = g.eval(input, &[lane]);
            assert_eq!(g.eval(input, &[g.lane(zipped, k)]), expected);
        }
    }

    /// Rows whose entries are lanes of the same packs share one packed evaluation: four
    /// rows of Σ_b m_b u_b cost one packed product and sum, not four; an operand in another
    /// lane falls back to the scalar expression. The values are the scalar expression's.
    #[test]
    fn rows_of_lanes_of_one_pack_share_a_packed_evaluation() {
        let g = Graph::new();
        // Computed packs (a pack's own lanes read back as its scalars, not as lanes).
        let packs: [_; 2] = std::array::from_fn(|b| {
            g.mul(g.pack(std::array::from_fn(|k| q(&g, 4 * b + k))), q(&g, 10))
        });
        let (u, w) = (q(&g, 8), q(&g, 9));
        let sum = |m: &[crate::sym::Node]| g.add(g.mul(m[0], u), g.mul(m[1], w));
        let rows: Vec<_> = (0..4)
            .map(|k| g.lanewise(&[g.lane(packs[0], k), g.lane(packs[1], k)], sum))
            .collect();
        let ops = g.op_count(&rows);
        assert_eq!((ops.total(), ops.packed), (5, 5), "two packs and Σ: {ops}");
        let mixed = g.lanewise(&[g.lane(packs[0], 1), g.lane(packs[1], 2)], sum);
        assert!(!g.is_packed(mixed) && !matches!(g.op(mixed), Op::Lane(..)));
        let input = |r: InputRef| 0.5 + f64::from(r.index);
        for (k, &row) in rows.iter().enumerate() {
            let scalar = sum(&[g.mul(q(&g, k), q(&g, 10)), g.mul(q(&g, 4 + k), q(&g, 10))]);
            assert_eq!(g.eval(input, &[row]), g.eval(input, &[scalar]));
        }
    }
}
