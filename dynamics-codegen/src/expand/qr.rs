//! A x = b by Givens QR in straight-line code, for the force analysis.
//!
//! Column by column, each entry below the diagonal that is not a structural zero (a
//! constant 0 node) is rotated into the diagonal row: with a = A_jj, b = A_ij,
//! r = √(a² + b²), c = a/r, s = b/r,
//!
//! ```text
//! [A_j·]   [ c  s] [A_j·]
//! [A_i·] ← [−s  c] [A_i·],   likewise for the right-hand side,
//! ```
//!
//! so A = Qᵀ R with Q orthogonal: no pivoting (no branch on data), and the rotation keeps
//! the conditioning of A. Back substitution gives x = R⁻¹ Q b. The diagonal of R is
//! returned too: min |R_jj| / max |R_jj| ≥ 1/κ₂(A) is the conditioning figure (σ_min ≤
//! |R_jj| ≤ σ_max), and a zero pivot means A is singular. An exactly singular column makes
//! r = 0 and the results NaN or infinite, never a panic.
//!
//! Structure known at compile time costs nothing: a structurally zero diagonal is filled
//! by swapping rows (free, exact), and a zero below the diagonal needs no rotation.

use crate::sym::{Graph, Node};

/// Solves A x = b (A square, by rows); returns x and the diagonal of R.
pub fn solve(g: &Graph, mut a: Vec<Vec<Node>>, mut b: Vec<Node>) -> (Vec<Node>, Vec<Node>) {
    let n = b.len();
    let is_zero = |node: Node| g.constant_value(node) == Some(0.0);
    for j in 0..n {
        for i in j + 1..n {
            if is_zero(a[i][j]) {
                continue;
            }
            if is_zero(a[j][j]) {
                a.swap(i, j);
                b.swap(i, j);
                continue;
            }
            let (top, bottom) = (a[j][j], a[i][j]);
            let r = g.sqrt(g.add(g.mul(top, top), g.mul(bottom, bottom)));
            let inverse = g.div(g.one(), r);
            let (c, s) = (g.mul(top, inverse), g.mul(bottom, inverse));
            let rotate = |x: Node, y: Node| {
                (
                    g.add(g.mul(c, x), g.mul(s, y)),
                    g.sub(g.mul(c, y), g.mul(s, x)),
                )
            };
            a[j][j] = r;
            a[i][j] = g.zero();
            for k in j + 1..n {
                (a[j][k], a[i][k]) = rotate(a[j][k], a[i][k]);
            }
            (b[j], b[i]) = rotate(b[j], b[i]);
        }
    }
    let mut x = vec![g.zero(); n];
    for j in (0..n).rev() {
        let mut sum = b[j];
        for k in j + 1..n {
            sum = g.sub(sum, g.mul(a[j][k], x[k]));
        }
        x[j] = g.div(sum, a[j][j]);
    }
    let diagonal = (0..n).map(|j| a[j][j]).collect();
    (x, diagonal)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sym::Array;

    #[test]
    fn solves_a_system_with_structural_zeros() {
        // A has a zero diagonal entry that a row swap fills; compare with the known solution.
        let g = Graph::new();
        let p = |k: usize| g.input(Array::P, k);
        let a = vec![
            vec![g.zero(), p(0), g.one()],
            vec![p(1), g.zero(), p(2)],
            vec![g.one(), p(3), g.zero()],
        ];
        let values = [2.0, -1.5, 0.5, 3.0];
        let matrix = [[0.0, 2.0, 1.0], [-1.5, 0.0, 0.5], [1.0, 3.0, 0.0]];
        let x_true = [0.3, -0.7, 1.1];
        let b: Vec<Node> = matrix
            .iter()
            .map(|row| g.constant(row.iter().zip(x_true).map(|(m, x)| m * x).sum()))
            .collect();
        let (x, r) = solve(&g, a, b);
        let at = |i: crate::sym::InputRef| values[i.index as usize];
        let x = g.eval(at, &x);
        for (got, want) in x.iter().zip(x_true) {
            assert!((got - want).abs() < 1e-14, "{got} vs {want}");
        }
        // |det R| = |det A|.
        let det: f64 = g.eval(at, &r).iter().product();
        assert!((det.abs() - 3.5).abs() < 1e-13, "{det}");
    }

    #[test]
    fn a_singular_system_gives_a_zero_pivot_or_non_finite_values() {
        let g = Graph::new();
        let p = g.input(Array::P, 0);
        let a = vec![
            vec![p, g.one()],
            vec![g.mul(g.constant(2.0), p), g.constant(2.0)],
        ];
        let (x, r) = solve(&g, a, vec![g.one(), g.one()]);
        let out = g.eval(|_| 1.0, &[x[0], x[1], r[0], r[1]]);
        assert!(!out[0].is_finite() && !out[1].is_finite(), "{out:?}");
        assert!(out[3].abs() < 1e-15, "{out:?}");
    }
}
