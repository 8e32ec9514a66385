//! Forward-mode differentiation over the DAG: for outputs y(x) and a tangent ẋ of the
//! inputs, the directional derivative ẏ = (∂y/∂x) ẋ, built as new nodes of the same graph.
//!
//! Each live node gets its derivative by the chain rule, in topological order:
//! (a ± b)˙ = ȧ ± ḃ, (a b)˙ = ȧ b + a ḃ, (a / b)˙ = (ȧ − (a/b) ḃ) / b, (−a)˙ = −ȧ,
//! (sin a)˙ = cos a · ȧ, (cos a)˙ = −sin a · ȧ, (√a)˙ = ȧ / (2 √a). A constant tangent
//! (a unit vector e_j gives the column ∂y/∂x_j) folds most terms away at construction.
//!
//! [`Graph::substitute`] rebuilds outputs with some inputs replaced by nodes: y(x) with
//! x_k := z_k, e.g. a derivative taken at a free input `a` then evaluated at a computed q̈.

use super::{Graph, InputRef, Node, Op};

impl Graph {
    /// The directional derivative of each output along `tangent`, which gives ẋ for each
    /// input element (zero for inputs that do not vary).
    pub fn derivative(&self, outputs: &[Node], tangent: impl Fn(InputRef) -> Node) -> Vec<Node> {
        let live = self.live(outputs);
        let ops = self.ops();
        let mut dot: Vec<Option<Node>> = vec![None; ops.len()];
        for node in live.nodes() {
            let d = |n: Node| dot[n.index()].unwrap_or_else(|| self.zero());
            let derivative = match ops[node.index()] {
                Op::Const(_) => self.zero(),
                Op::Input(r) => tangent(r),
                Op::Add(a, b) => self.add(d(a), d(b)),
                Op::Sub(a, b) => self.sub(d(a), d(b)),
                Op::Mul(a, b) => self.add(self.mul(d(a), b), self.mul(a, d(b))),
                Op::Div(a, b) => self.div(self.sub(d(a), self.mul(node, d(b))), b),
                Op::Neg(a) => self.neg(d(a)),
                Op::Sin(a) => self.mul(self.cos(a), d(a)),
                Op::Cos(a) => self.neg(self.mul(self.sin(a), d(a))),
                Op::Sqrt(a) => self.div(d(a), self.mul(self.constant(2.0), node)),
                Op::Pack(a, b, c, e) => self.pack([d(a), d(b), d(c), d(e)]),
                Op::Lane(a, k) => self.lane(d(a), usize::from(k)),
            };
            dot[node.index()] = Some(derivative);
        }
        outputs
            .iter()
            .map(|n| dot[n.index()].unwrap_or_else(|| self.zero()))
            .collect()
    }
}

impl Graph {
    /// The outputs rebuilt with each input for which `replace` gives a node replaced by
    /// that node (the others kept), through the same folding rules.
    pub fn substitute(
        &self,
        outputs: &[Node],
        replace: impl Fn(InputRef) -> Option<Node>,
    ) -> Vec<Node> {
        let live = self.live(outputs);
        let ops = self.ops();
        let mut new: Vec<Option<Node>> = vec![None; ops.len()];
        for node in live.nodes() {
            let n = |x: Node| new[x.index()].unwrap_or(x);
            let rebuilt = match ops[node.index()] {
                Op::Const(_) => node,
                Op::Input(r) => replace(r).unwrap_or(node),
                Op::Add(a, b) => self.add(n(a), n(b)),
                Op::Sub(a, b) => self.sub(n(a), n(b)),
                Op::Mul(a, b) => self.mul(n(a), n(b)),
                Op::Div(a, b) => self.div(n(a), n(b)),
                Op::Neg(a) => self.neg(n(a)),
                Op::Sin(a) => self.sin(n(a)),
                Op::Cos(a) => self.cos(n(a)),
                Op::Sqrt(a) => self.sqrt(n(a)),
                Op::Pack(a, b, c, d) => self.pack([n(a), n(b), n(c), n(d)]),
                Op::Lane(a, k) => self.lane(n(a), usize::from(k)),
            };
            new[node.index()] = Some(rebuilt);
        }
        outputs
            .iter()
            .map(|x| new[x.index()].unwrap_or(*x))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::sym::{Array, Graph};

    #[test]
    fn derivatives_follow_the_chain_rule() {
        // y = sin(q0) q1 / √q0 + cos(q1): check ∂y/∂q0 and ∂y/∂q1 against finite differences.
        let g = Graph::new();
        let (q0, q1) = (g.input(Array::Q, 0), g.input(Array::Q, 1));
        let y = g.add(g.div(g.mul(g.sin(q0), q1), g.sqrt(q0)), g.cos(g.neg(q1)));
        let columns: Vec<_> = (0..2)
            .map(|j| {
                g.derivative(&[y], |r| {
                    if r.array == Array::Q && r.index as usize == j {
                        g.one()
                    } else {
                        g.zero()
                    }
                })[0]
            })
            .collect();
        let at = |x: [f64; 2]| move |r: crate::sym::InputRef| x[r.index as usize];
        let x = [0.7, -1.3];
        let exact = g.eval(at(x), &columns);
        let h = 1e-6;
        for j in 0..2 {
            let (mut plus, mut minus) = (x, x);
            plus[j] += h;
            minus[j] -= h;
            let fd = (g.eval(at(plus), &[y])[0] - g.eval(at(minus), &[y])[0]) / (2.0 * h);
            assert!(
                (exact[j] - fd).abs() < 1e-8,
                "column {j}: {} vs {fd}",
                exact[j]
            );
        }
    }

    #[test]
    fn constants_and_unrelated_inputs_have_zero_derivative() {
        let g = Graph::new();
        let v = g.input(Array::V, 0);
        let y = g.mul(g.constant(3.0), v);
        let d = g.derivative(&[y, g.constant(2.0)], |r| {
            if r.array == Array::Q {
                g.one()
            } else {
                g.zero()
            }
        });
        assert_eq!(g.constant_value(d[0]), Some(0.0));
        assert_eq!(g.constant_value(d[1]), Some(0.0));
    }

    #[test]
    fn substitution_replaces_inputs_and_keeps_the_rest() {
        // y = q0 a0 + sin(a0); with a0 := q1², y = q0 q1² + sin(q1²).
        let g = Graph::new();
        let (q0, q1, a0) = (
            g.input(Array::Q, 0),
            g.input(Array::Q, 1),
            g.input(Array::A, 0),
        );
        let y = g.add(g.mul(q0, a0), g.sin(a0));
        let square = g.mul(q1, q1);
        let z = g.substitute(&[y], |r| (r.array == Array::A).then_some(square))[0];
        let x = [0.7, -1.3];
        let value = g.eval(|r: crate::sym::InputRef| x[r.index as usize], &[z])[0];
        let expected = 0.7 * 1.69 + 1.69_f64.sin();
        assert!((value - expected).abs() < 1e-15, "{value} vs {expected}");
    }
}
