//! The builders of [`Graph`] and the simplification rules they apply at construction.
//!
//! Every builder first folds constants, then applies its identities, then the negation
//! rules, and finally hash-conses the operation in canonical form. The negation rules treat
//! a negative constant `−c` like the negation of the constant `c` (see [`Graph::negated`]),
//! so the same rule that turns `x·(−y)` into `−(x·y)` also turns `x·(−0.5)` into
//! `−(x·0.5)`, and `x + (−3)` into `x − 3`.
//!
//! Subtractions are kept in one orientation, `a − b` with `a` the older node (smaller id);
//! `b − a` is built as `−(a − b)`. The sign then travels outwards through products and is
//! absorbed by the first sum or difference that takes it (`x + (−y) = x − y`), so a
//! difference and its opposite, which the Newton–Euler terms produce in pairs (a cross
//! product and its transpose), cost one operation, not two. A sign that reaches an output
//! is settled there by [`Graph::settled`].
//!
//! All negation rules are exact in IEEE arithmetic (round-to-nearest is symmetric under a
//! change of sign), except in the sign of a zero result: `−(a − b)` is `−0` where `b − a`
//! would be `+0`.

use super::{Array, Const, Graph, InputRef, Node, Op};

impl Graph {
    /// The constant `x` (`-0.0` is stored as `0.0`).
    pub fn constant(&self, x: f64) -> Node {
        self.intern(Op::Const(Const::new(x)))
    }

    /// The constant 0.
    pub fn zero(&self) -> Node {
        self.constant(0.0)
    }

    /// The constant 1.
    pub fn one(&self) -> Node {
        self.constant(1.0)
    }

    /// Element `index` of the input array `array`, e.g. `q[3]`.
    ///
    /// # Panics
    /// If `index` does not fit in a `u32`.
    pub fn input(&self, array: Array, index: usize) -> Node {
        let index = u32::try_from(index).expect("input index fits in u32");
        self.intern(Op::Input(InputRef { array, index }))
    }

    /// Whether `node` is the constant `value`.
    fn is_const(&self, node: Node, value: f64) -> bool {
        self.constant_value(node) == Some(value)
    }

    /// The values of `a` and `b` if both are constants.
    fn both_const(&self, a: Node, b: Node) -> Option<(f64, f64)> {
        Some((self.constant_value(a)?, self.constant_value(b)?))
    }

    /// `x` if `node` is `−x`; `c` if `node` is a negative constant `−c`; else `None`.
    ///
    /// This is the single notion of "a negated value" that the negation rules use.
    pub(super) fn negated(&self, node: Node) -> Option<Node> {
        match self.op(node) {
            Op::Neg(x) => Some(x),
            Op::Const(c) if c.value() < 0.0 => Some(self.constant(-c.value())),
            _ => None,
        }
    }

    /// `a + b`.
    ///
    /// Rules, in order:
    /// 1. c₁ + c₂ folds.
    /// 2. x + 0 = 0 + x = x (exact except that −0 + 0 is +0).
    /// 3. (−a) + (−b) = −(a + b); a + (−b) = a − b; (−a) + b = b − a (exact). With
    ///    negative constants: x + (−3) = x − 3.
    /// 4. Operands are ordered by id, so a + b and b + a are one node.
    pub fn add(&self, a: Node, b: Node) -> Node {
        if let Some((x, y)) = self.both_const(a, b) {
            return self.constant(x + y);
        }
        if self.is_const(a, 0.0) {
            return b;
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => self.neg(self.add(x, y)),
            (None, Some(y)) => self.sub(a, y),
            (Some(x), None) => self.sub(b, x),
            (None, None) => self.intern(Op::Add(a.min(b), a.max(b))),
        }
    }

    /// `a − b`.
    ///
    /// Rules, in order:
    /// 1. c₁ − c₂ folds.
    /// 2. x − 0 = x (exact); 0 − x = −x (exact except the sign of a zero result);
    ///    x − x = 0 (not IEEE-exact when x is infinite or NaN, which the dynamics never
    ///    produce from finite inputs).
    /// 3. (−a) − (−b) = b − a; a − (−b) = a + b; (−a) − b = −(a + b) (exact). With
    ///    negative constants: x − (−3) = x + 3, (−3) − x = −(3 + x).
    /// 4. Orientation: a − b with a older than b is a node; b − a is −(a − b) (see the
    ///    module documentation; the sign of a zero result may differ).
    pub fn sub(&self, a: Node, b: Node) -> Node {
        if let Some((x, y)) = self.both_const(a, b) {
            return self.constant(x - y);
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        if self.is_const(a, 0.0) {
            return self.neg(b);
        }
        if a == b {
            return self.zero();
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => self.sub(y, x),
            (None, Some(y)) => self.add(a, y),
            (Some(x), None) => self.neg(self.add(x, b)),
            (None, None) if a < b => self.intern(Op::Sub(a, b)),
            (None, None) => self.neg(self.intern(Op::Sub(b, a))),
        }
    }

    /// `a · b`.
    ///
    /// Rules, in order:
    /// 1. c₁ · c₂ folds.
    /// 2. x · 0 = 0 · x = 0. This is intentional and **not** IEEE-exact: if x is infinite or
    ///    NaN the product would be NaN, and if x is negative it would be −0. Zero entries of
    ///    the model's matrices must cost nothing, and the dynamics of finite states are
    ///    finite, so the rule is taken.
    /// 3. x · 1 = 1 · x = x (exact).
    /// 4. (−a)·(−b) = a·b; (−a)·b = a·(−b) = −(a·b) (exact). With negative constants:
    ///    x·(−1) = −x and x·(−0.5) = −(x·0.5), which shares its product with x·0.5.
    /// 5. Operands are ordered by id, so a·b and b·a are one node.
    pub fn mul(&self, a: Node, b: Node) -> Node {
        if let Some((x, y)) = self.both_const(a, b) {
            return self.constant(x * y);
        }
        if self.is_const(a, 0.0) || self.is_const(b, 0.0) {
            return self.zero();
        }
        if self.is_const(a, 1.0) {
            return b;
        }
        if self.is_const(b, 1.0) {
            return a;
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => self.mul(x, y),
            (Some(x), None) => self.neg(self.mul(x, b)),
            (None, Some(y)) => self.neg(self.mul(a, y)),
            (None, None) => self.intern(Op::Mul(a.min(b), a.max(b))),
        }
    }

    /// `a / b`.
    ///
    /// Rules, in order:
    /// 1. c₁ / c₂ folds.
    /// 2. x / 1 = x (exact). 0 / x is deliberately **not** folded to 0: it is NaN for
    ///    x = 0, and a zero numerator is rare enough not to matter.
    /// 3. (−a)/(−b) = a/b; (−a)/b = a/(−b) = −(a/b) (exact), negative constants included.
    /// 4. x / c = x · (1/c) only when c is a power of two (then 1/c is exact and both forms
    ///    round the same real number, so the result is bit-identical). Division by any
    ///    other constant stays a division, to keep the textbook's rounding.
    pub fn div(&self, a: Node, b: Node) -> Node {
        if let Some((x, y)) = self.both_const(a, b) {
            return self.constant(x / y);
        }
        if self.is_const(b, 1.0) {
            return a;
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => return self.div(x, y),
            (Some(x), None) => return self.neg(self.div(x, b)),
            (None, Some(y)) => return self.neg(self.div(a, y)),
            (None, None) => {}
        }
        match self.constant_value(b) {
            Some(c) if is_power_of_two(c) => self.mul(a, self.constant(1.0 / c)),
            _ => self.intern(Op::Div(a, b)),
        }
    }

    /// `−a`.
    ///
    /// Rules: −c folds; −(−x) = x (exact). A negated difference stays −(a − b) (see
    /// [`Graph::sub`]'s orientation rule); [`Graph::settled`] turns it into b − a where it
    /// is an output.
    pub fn neg(&self, a: Node) -> Node {
        match self.op(a) {
            Op::Const(c) => self.constant(-c.value()),
            Op::Neg(x) => x,
            _ => self.intern(Op::Neg(a)),
        }
    }

    /// `sin a`; folds constants.
    pub fn sin(&self, a: Node) -> Node {
        match self.constant_value(a) {
            Some(x) => self.constant(x.sin()),
            None => self.intern(Op::Sin(a)),
        }
    }

    /// `cos a`; folds constants.
    pub fn cos(&self, a: Node) -> Node {
        match self.constant_value(a) {
            Some(x) => self.constant(x.cos()),
            None => self.intern(Op::Cos(a)),
        }
    }

    /// `√a`; folds constants.
    pub fn sqrt(&self, a: Node) -> Node {
        match self.constant_value(a) {
            Some(x) => self.constant(x.sqrt()),
            None => self.intern(Op::Sqrt(a)),
        }
    }

    /// `terms[0] + terms[1] + …`, summed left to right; 0 for no terms.
    pub fn sum(&self, terms: &[Node]) -> Node {
        terms
            .iter()
            .fold(self.zero(), |acc, &term| self.add(acc, term))
    }
}

/// Whether `c` is ±2^k with 2^−k also a finite, exactly representable number.
fn is_power_of_two(c: f64) -> bool {
    const MANTISSA: u64 = (1 << 52) - 1;
    c.is_normal() && c.to_bits() & MANTISSA == 0
}

#[cfg(test)]
mod tests {
    use super::super::{Array, Graph, Node, Op};

    fn inputs(g: &Graph) -> (Node, Node, Node) {
        (
            g.input(Array::Q, 0),
            g.input(Array::Q, 1),
            g.input(Array::V, 0),
        )
    }

    #[test]
    fn hash_consing_returns_the_same_node() {
        let g = Graph::new();
        let (x, y, _) = inputs(&g);
        let e1 = g.sin(g.mul(x, y));
        let len = g.len();
        let e2 = g.sin(g.mul(x, y));
        assert_eq!(e1, e2);
        assert_eq!(g.len(), len, "no node created the second time");
        assert_eq!(g.input(Array::Q, 0), x);
        assert_ne!(g.input(Array::V, 0), x, "arrays are distinguished");
        assert_eq!(g.constant(2.5), g.constant(2.5));
    }

    #[test]
    fn nodes_are_in_topological_order() {
        let g = Graph::new();
        let (x, y, z) = inputs(&g);
        let _ = g.div(g.add(g.mul(x, y), g.cos(z)), g.sqrt(g.sub(x, z)));
        for (i, op) in g.ops().into_iter().enumerate() {
            assert!(op.children().all(|c| c.index() < i), "v{i} = {op}");
        }
    }

    #[test]
    fn commutative_operands_are_canonical() {
        let g = Graph::new();
        let (x, y, _) = inputs(&g);
        assert_eq!(g.add(x, y), g.add(y, x));
        assert_eq!(g.mul(x, y), g.mul(y, x));
        assert_eq!(g.op(g.add(y, x)), Op::Add(x, y));
        assert_ne!(g.sub(x, y), g.sub(y, x));
        assert_ne!(g.div(x, y), g.div(y, x));
    }

    #[test]
    fn constants_fold_for_every_operation() {
        let g = Graph::new();
        let c = |v: f64| g.constant(v);
        assert_eq!(g.add(c(1.5), c(2.0)), c(3.5));
        assert_eq!(g.sub(c(1.5), c(2.0)), c(-0.5));
        assert_eq!(g.mul(c(1.5), c(2.0)), c(3.0));
        assert_eq!(g.div(c(1.0), c(3.0)), c(1.0 / 3.0));
        assert_eq!(g.neg(c(1.5)), c(-1.5));
        assert_eq!(g.sin(c(0.3)), c(0.3_f64.sin()));
        assert_eq!(g.cos(c(0.3)), c(0.3_f64.cos()));
        assert_eq!(g.sqrt(c(2.0)), c(2.0_f64.sqrt()));
        assert!(g.ops().iter().all(|op| op.is_leaf()), "only constants");
    }

    #[test]
    fn constants_are_normalised() {
        let g = Graph::new();
        assert_eq!(g.constant(-0.0), g.zero());
        assert_eq!(g.neg(g.zero()), g.zero());
        assert_eq!(g.constant(f64::NAN), g.constant(-f64::NAN));
        assert_eq!(g.sqrt(g.constant(-1.0)), g.constant(f64::NAN));
    }

    #[test]
    fn additive_identities() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        let zero = g.zero();
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.add(zero, x), x);
        assert_eq!(g.sub(x, zero), x);
        assert_eq!(g.sub(zero, x), g.neg(x));
        assert_eq!(g.op(g.sub(zero, x)), Op::Neg(x));
        assert_eq!(g.sub(x, x), zero);
    }

    #[test]
    fn multiplicative_identities() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        assert_eq!(g.mul(x, g.zero()), g.zero());
        assert_eq!(g.mul(g.zero(), x), g.zero());
        assert_eq!(g.mul(x, g.one()), x);
        assert_eq!(g.mul(g.one(), x), x);
        assert_eq!(g.mul(x, g.constant(-1.0)), g.neg(x));
        assert_eq!(g.op(g.mul(g.constant(-1.0), x)), Op::Neg(x));
        assert_eq!(g.div(x, g.one()), x);
    }

    #[test]
    fn double_negation_cancels() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        assert_eq!(g.neg(g.neg(x)), x);
    }

    #[test]
    fn zero_numerator_is_not_folded() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        let q = g.div(g.zero(), x);
        assert_eq!(g.op(q), Op::Div(g.zero(), x));
    }

    #[test]
    fn negation_rules() {
        let g = Graph::new();
        let (a, b, _) = inputs(&g);
        let (na, nb) = (g.neg(a), g.neg(b));
        let ab = g.mul(a, b);
        // (−a)·b = a·(−b) = −(a·b); (−a)·(−b) = a·b
        assert_eq!(g.mul(na, b), g.neg(ab));
        assert_eq!(g.mul(a, nb), g.neg(ab));
        assert_eq!(g.op(g.mul(na, b)), Op::Neg(ab));
        assert_eq!(g.mul(na, nb), ab);
        // a + (−b) = a − b; (−a) + b = b − a; (−a) + (−b) = −(a + b)
        assert_eq!(g.op(g.add(a, nb)), Op::Sub(a, b));
        assert_eq!(g.add(na, b), g.sub(b, a));
        assert_eq!(g.op(g.add(na, nb)), Op::Neg(g.add(a, b)));
        // a − (−b) = a + b; (−a) − b = −(a + b); (−a) − (−b) = b − a
        assert_eq!(g.sub(a, nb), g.add(a, b));
        assert_eq!(g.op(g.sub(na, b)), Op::Neg(g.add(a, b)));
        assert_eq!(g.sub(na, nb), g.neg(g.sub(a, b)));
        // b − a is −(a − b): one subtraction serves both orientations
        assert_eq!(g.op(g.sub(b, a)), Op::Neg(g.sub(a, b)));
        assert_eq!(g.neg(g.sub(a, b)), g.sub(b, a));
        assert_eq!(g.add(g.sub(b, a), g.sub(a, b)), g.zero());
        // settling an output folds the sign into its last operation
        let ba = g.sub(b, a);
        assert_eq!(g.op(g.settled(ba)), Op::Sub(b, a));
        assert_eq!(
            g.op(g.settled(g.mul(a, g.constant(-0.5)))),
            Op::Mul(a, g.constant(-0.5))
        );
        assert_eq!(
            g.settled(g.neg(ab)),
            g.neg(ab),
            "no constant factor: stays negated"
        );
        assert_eq!(g.settled(ab), ab);
        // (−a)/b = a/(−b) = −(a/b); (−a)/(−b) = a/b
        let q = g.div(a, b);
        assert_eq!(g.op(g.div(na, b)), Op::Neg(q));
        assert_eq!(g.op(g.div(a, nb)), Op::Neg(q));
        assert_eq!(g.div(na, nb), q);
    }

    #[test]
    fn negative_constants_share_with_positive_ones() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        let half = g.constant(0.5);
        let p = g.mul(x, half);
        assert_eq!(g.op(g.mul(x, g.constant(-0.5))), Op::Neg(p));
        assert_eq!(g.op(g.mul(g.constant(-0.5), x)), Op::Neg(p));
        let three = g.constant(3.0);
        assert_eq!(g.op(g.add(x, g.constant(-3.0))), Op::Sub(x, three));
        assert_eq!(
            g.op(g.sub(x, g.constant(-3.0))),
            Op::Add(x.min(three), x.max(three))
        );
        assert_eq!(g.op(g.sub(g.constant(-3.0), x)), Op::Neg(g.add(three, x)));
    }

    #[test]
    fn division_by_power_of_two_becomes_a_product() {
        let g = Graph::new();
        let (x, _, _) = inputs(&g);
        assert_eq!(g.div(x, g.constant(2.0)), g.mul(x, g.constant(0.5)));
        assert_eq!(g.div(x, g.constant(0.25)), g.mul(x, g.constant(4.0)));
        assert_eq!(
            g.div(x, g.constant(-8.0)),
            g.neg(g.mul(x, g.constant(0.125)))
        );
        let three = g.constant(3.0);
        assert_eq!(g.op(g.div(x, three)), Op::Div(x, three));
        let tiny = g.constant(f64::MIN_POSITIVE / 4.0); // subnormal: 1/c overflows
        assert_eq!(g.op(g.div(x, tiny)), Op::Div(x, tiny));
        let huge = g.constant(2.0_f64.powi(1023)); // 1/c is subnormal but exact
        assert_eq!(g.div(x, huge), g.mul(x, g.constant(2.0_f64.powi(-1023))));
        assert_eq!(g.op(g.div(x, g.zero())), Op::Div(x, g.zero()));
    }

    #[test]
    fn sin_and_cos_of_a_joint_are_atoms() {
        let g = Graph::new();
        let (q0, _, _) = inputs(&g);
        let s = g.sin(q0);
        let c = g.cos(q0);
        assert_eq!(g.sin(q0), s);
        assert_eq!(g.cos(q0), c);
        assert_eq!(g.op(s), Op::Sin(q0));
    }

    #[test]
    fn sum_adds_left_to_right() {
        let g = Graph::new();
        let (x, y, z) = inputs(&g);
        assert_eq!(g.sum(&[x, y, z]), g.add(g.add(x, y), z));
        assert_eq!(g.sum(&[]), g.zero());
        assert_eq!(g.sum(&[x]), x);
    }

    /// A random expression tree, evaluated directly and built into a graph.
    #[derive(Clone, Debug)]
    enum Tree {
        Leaf(Leaf),
        Un(u8, Box<Tree>),
        Bin(u8, Box<Tree>, Box<Tree>),
    }

    #[derive(Clone, Copy, Debug)]
    enum Leaf {
        Input(usize),
        Const(f64),
    }

    /// xorshift64*: enough randomness for a property test, no dependency.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
        }
        fn below(&mut self, n: u64) -> u64 {
            self.next() % n
        }
    }

    const CONSTANTS: [f64; 9] = [0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -3.0, 0.25, 1.7];

    fn random_tree(rng: &mut Rng, depth: u32) -> Tree {
        if depth == 0 || rng.below(4) == 0 {
            return Tree::Leaf(if rng.below(3) == 0 {
                Leaf::Const(CONSTANTS[rng.below(CONSTANTS.len() as u64) as usize])
            } else {
                Leaf::Input(rng.below(4) as usize)
            });
        }
        let kind = rng.below(10) as u8;
        if kind < 6 {
            Tree::Bin(
                kind % 4,
                Box::new(random_tree(rng, depth - 1)),
                Box::new(random_tree(rng, depth - 1)),
            )
        } else {
            Tree::Un(kind - 6, Box::new(random_tree(rng, depth - 1)))
        }
    }

    /// Direct evaluation with the tree's own operation order.
    fn eval_tree(t: &Tree, x: &[f64]) -> f64 {
        match t {
            Tree::Leaf(Leaf::Input(i)) => x[*i],
            Tree::Leaf(Leaf::Const(c)) => *c,
            Tree::Un(k, a) => {
                let a = eval_tree(a, x);
                [-a, a.sin(), a.cos(), a.sqrt()][*k as usize]
            }
            Tree::Bin(k, a, b) => {
                let (a, b) = (eval_tree(a, x), eval_tree(b, x));
                [a + b, a - b, a * b, a / b][*k as usize]
            }
        }
    }

    /// Builds the tree; with `mirror`, the operands of `+` and `·` are swapped (and the
    /// swapped operand is built first).
    fn build(g: &Graph, t: &Tree, mirror: bool) -> Node {
        match t {
            Tree::Leaf(Leaf::Input(i)) => g.input(Array::Q, *i),
            Tree::Leaf(Leaf::Const(c)) => g.constant(*c),
            Tree::Un(k, a) => {
                let a = build(g, a, mirror);
                match k {
                    0 => g.neg(a),
                    1 => g.sin(a),
                    2 => g.cos(a),
                    _ => g.sqrt(a),
                }
            }
            Tree::Bin(k, a, b) => {
                let commutative = *k == 0 || *k == 2;
                let (a, b) = if mirror && commutative {
                    let b = build(g, b, mirror);
                    (build(g, a, mirror), b)
                } else {
                    (build(g, a, mirror), build(g, b, mirror))
                };
                let (a, b) = if mirror && commutative {
                    (b, a)
                } else {
                    (a, b)
                };
                match k {
                    0 => g.add(a, b),
                    1 => g.sub(a, b),
                    2 => g.mul(a, b),
                    _ => g.div(a, b),
                }
            }
        }
    }

    #[test]
    fn random_expressions_fold_exactly_and_share_across_operand_orders() {
        let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
        let mut compared = 0;
        for case in 0..2000 {
            let tree = random_tree(&mut rng, 6);
            let x: Vec<f64> = (0..4)
                .map(|_| (rng.below(2001) as f64 - 1000.0) / 250.0)
                .collect();

            // Mirrored first, in a fresh graph, so that ids are assigned in the other order.
            let g = Graph::new();
            let mirrored = build(&g, &tree, true);
            let straight = build(&g, &tree, false);
            assert_eq!(straight, mirrored, "case {case}: {tree:?}");

            let direct = eval_tree(&tree, &x);
            let via_graph = g.eval(|r| x[r.index as usize], &[straight])[0];
            if direct.is_finite() {
                // The documented non-exact rules only change NaN/∞ and the sign of zero.
                assert!(
                    direct == via_graph,
                    "case {case}: {direct} vs {via_graph}, {tree:?}"
                );
                compared += 1;
            }
        }
        assert!(compared > 1000, "only {compared} finite cases");
    }
}
