//! Forward dynamics by a tree-sparse LDLᵀ factorization of M (Featherstone, *Rigid Body
//! Dynamics Algorithms*, §6.5): M = Lᵀ D L with L unit lower triangular and nonzero only
//! where the row's coordinate descends from the column's, so the factorization and the
//! solves cost nothing between branches of the tree.
//!
//! ```text
//! for k = n−1 … 0:  for i = λ(k), λ(λ(k)), …:  a = M_ki / M_kk
//!                       for j = i, λ(i), …: M_ij −= a M_kj
//!                       M_ki = a
//! solve Lᵀ z = y, z ← D⁻¹ z, solve L x = z.
//! ```
//!
//! M⁻¹ = L⁻¹ D⁻¹ L⁻ᵀ comes from the same factorization ([`inverse`]).
//!
//! λ(k) is the coordinate k descends from: the previous coordinate of the same free joint,
//! or the last coordinate of the parent body's joint. Each pivot is inverted once.

use crate::model::Model;
use crate::sym::{Graph, Node};

/// The parent coordinate of every velocity coordinate (`None` for the first coordinate of a
/// body attached to the ground).
pub fn coordinate_parents(model: &Model) -> Vec<Option<usize>> {
    let mut parents = vec![None; model.nv];
    for body in &model.bodies {
        let first = body.joint.idx_v;
        parents[first] = body.parent.map(|p| {
            let pj = &model.bodies[p].joint;
            pj.idx_v + pj.kind.dofs() - 1
        });
        for k in first + 1..first + body.joint.kind.dofs() {
            parents[k] = Some(k - 1);
        }
    }
    parents
}

/// Solves M x = y by the tree-sparse LDLᵀ factorization of M (consumes M).
pub fn solve(g: &Graph, model: &Model, m: Vec<Vec<Node>>, y: Vec<Node>) -> Vec<Node> {
    solve_with_parents(g, &coordinate_parents(model), m, y)
}

/// The factorization M = Lᵀ D L for solving by a loop over many right-hand sides: the
/// coordinate parents, L_ki row after row (each row's entries from k's parent towards the
/// root) and 1 / D_k (consumes M).
pub fn factor_rows(
    g: &Graph,
    model: &Model,
    mut m: Vec<Vec<Node>>,
) -> (Vec<Option<usize>>, Vec<Node>, Vec<Node>) {
    let parents = coordinate_parents(model);
    let inverse_pivot = factor(g, &parents, &mut m);
    let rows = factor_by_rows(&parents, &m);
    (parents, rows, inverse_pivot)
}

/// L_ki from the factorization in `m`, row after row, each row's entries from k's parent
/// towards the root: the layout of `dynamics_runtime::tree_ldlt`'s factor.
fn factor_by_rows(parents: &[Option<usize>], m: &[Vec<Node>]) -> Vec<Node> {
    (0..m.len())
        .flat_map(|k| std::iter::successors(parents[k], |&i| parents[i]).map(move |i| (k, i)))
        .map(|(k, i)| m[k][i])
        .collect()
}

/// Solves a dense symmetric system M x = y (a chain: every coordinate descends from the
/// previous one), as the articulated-body algorithm needs for a multi-dof joint.
pub fn solve_dense(g: &Graph, m: Vec<Vec<Node>>, y: Vec<Node>) -> Vec<Node> {
    let parents: Vec<Option<usize>> = (0..y.len()).map(|k| k.checked_sub(1)).collect();
    solve_with_parents(g, &parents, m, y)
}

/// The factorization M = Lᵀ D L in place: `m[k][i]` for i an ancestor of k becomes L_ki,
/// and the returned vector holds 1 / D_k.
fn factor(g: &Graph, parents: &[Option<usize>], m: &mut [Vec<Node>]) -> Vec<Node> {
    let ancestors = |k: usize| std::iter::successors(parents[k], |&i| parents[i]);
    let n = m.len();
    let mut inverse_pivot = vec![g.zero(); n];
    for k in (0..n).rev() {
        inverse_pivot[k] = g.div(g.one(), m[k][k]);
        for i in ancestors(k) {
            let a = g.mul(m[k][i], inverse_pivot[k]);
            for j in std::iter::once(i).chain(ancestors(i)) {
                m[i][j] = g.sub(m[i][j], g.mul(a, m[k][j]));
            }
            m[k][i] = a;
        }
    }
    inverse_pivot
}

/// Solves M x = y where M is nonzero only between a coordinate and its ancestors in
/// `parents`.
fn solve_with_parents(
    g: &Graph,
    parents: &[Option<usize>],
    mut m: Vec<Vec<Node>>,
    mut y: Vec<Node>,
) -> Vec<Node> {
    let ancestors = |k: usize| std::iter::successors(parents[k], |&i| parents[i]);
    let n = y.len();
    let inverse_pivot = factor(g, parents, &mut m);
    for i in (0..n).rev() {
        for j in ancestors(i) {
            y[j] = g.sub(y[j], g.mul(m[i][j], y[i]));
        }
    }
    for i in 0..n {
        y[i] = g.mul(y[i], inverse_pivot[i]);
    }
    for i in 0..n {
        for j in ancestors(i) {
            y[i] = g.sub(y[i], g.mul(m[i][j], y[j]));
        }
    }
    y
}

/// M⁻¹ from the same factorization, one triangle computed and mirrored:
/// M⁻¹ = Wᵀ D⁻¹ W with W = L⁻ᵀ, whose column j is nonzero only on j and its ancestors, so
/// (M⁻¹)_ij = Σ_k W_ki W_kj / D_k over the common ancestors k of i and j (themselves
/// included).
pub fn inverse(g: &Graph, model: &Model, mut m: Vec<Vec<Node>>) -> Vec<Vec<Node>> {
    let parents = coordinate_parents(model);
    let with_ancestors =
        |k: usize| std::iter::once(k).chain(std::iter::successors(parents[k], |&i| parents[i]));
    let n = m.len();
    let inverse_pivot = factor(g, &parents, &mut m);
    let w = inverse_of_transposed_factor(g, &parents, &m);
    let mut out = vec![vec![g.zero(); n]; n];
    for i in 0..n {
        let own: Vec<usize> = with_ancestors(i).collect();
        for j in i..n {
            let terms: Vec<Node> = with_ancestors(j)
                .filter(|k| own.contains(k))
                .map(|k| g.mul(g.mul(w[k][i], inverse_pivot[k]), w[k][j]))
                .collect();
            let entry = g.sum(&terms);
            out[i][j] = entry;
            out[j][i] = entry;
        }
    }
    out
}

/// M⁻¹ = L⁻¹ (D⁻¹ W) from the same factorization, for a loop to finish with L X = D⁻¹ W
/// (`dynamics_runtime::tree_ldlt::solve_lower_columns`, SIMD across the columns): the
/// coordinate parents, L_ki row after row (each row's entries from k's parent towards the
/// root), 1 / D_k, and D⁻¹ W by rows, row k nonzero only on k's subtree (consumes M).
pub fn inverse_halfway(g: &Graph, model: &Model, mut m: Vec<Vec<Node>>) -> InverseHalfway {
    let parents = coordinate_parents(model);
    let inverse_pivot = factor(g, &parents, &mut m);
    let w = inverse_of_transposed_factor(g, &parents, &m);
    let scaled = w
        .iter()
        .zip(&inverse_pivot)
        .map(|(row, &d)| row.iter().map(|&x| g.mul(x, d)).collect())
        .collect();
    let factor = factor_by_rows(&parents, &m);
    InverseHalfway {
        parents,
        factor,
        inverse_pivot,
        scaled,
    }
}

/// What [`inverse_halfway`] returns.
pub struct InverseHalfway {
    /// The parent coordinate of each coordinate.
    pub parents: Vec<Option<usize>>,
    /// L_ki, row after row, each row's entries from k's parent towards the root.
    pub factor: Vec<Node>,
    /// 1 / D_k.
    pub inverse_pivot: Vec<Node>,
    /// D⁻¹ W = D⁻¹ L⁻ᵀ, by rows.
    pub scaled: Vec<Vec<Node>>,
}

/// W = L⁻ᵀ from the factorization in `m` (`w[k][j]` = W_kj), solving Lᵀ w = e_j for each
/// column j from j towards the root: column j is nonzero only on j and its ancestors.
fn inverse_of_transposed_factor(
    g: &Graph,
    parents: &[Option<usize>],
    m: &[Vec<Node>],
) -> Vec<Vec<Node>> {
    let with_ancestors =
        |k: usize| std::iter::once(k).chain(std::iter::successors(parents[k], |&i| parents[i]));
    let n = m.len();
    let mut w = vec![vec![g.zero(); n]; n];
    for j in 0..n {
        w[j][j] = g.one();
        let chain: Vec<usize> = with_ancestors(j).collect();
        for &i in &chain {
            for a in with_ancestors(i).skip(1) {
                w[a][j] = g.sub(w[a][j], g.mul(m[i][a], w[i][j]));
            }
        }
    }
    w
}
