//! Derivatives of expanded functions with respect to the state, by forward-mode
//! differentiation of the graph ([`crate::sym::Graph::derivative`]), one column per
//! velocity coordinate.
//!
//! A column ∂y/∂q_j is the directional derivative of y along the tangent of the
//! configuration q ⊕ t e_j at t = 0, q ⊕ δ being Pinocchio's integration of a tangent
//! increment δ ∈ R^nv. For a revolute or prismatic joint the tangent is e_j itself. For a
//! free joint, q = [p; quaternion (x, y, z, w)] and δ = [δv; δω] in the base's own frame:
//!
//! ```text
//! ṗ = R δv,    (ẋ, ẏ, ż, ẇ) = ½ (x, y, z, w) ⊗ (δω, 0)
//!                           = ½ (w δω + (x, y, z) × δω,  −(x, y, z) · δω)
//! ```
//!
//! (the first-order motion of q ⊕ δ). Columns with respect to v, a or τ are plain partial
//! derivatives. Unit tangents fold at construction: a column of a joint that cannot
//! influence an output is a constant zero, so the tree's structural zeros cost nothing.

use super::geometry::quaternion_rotation;
use crate::model::{JointKind, Model};
use crate::sym::{Array, Graph, InputRef, Node};

/// The tangent of q along δ = e_col (a velocity coordinate): ẋ for each element of q (zero
/// for the other arrays).
fn configuration_tangent(g: &Graph, model: &Model, col: usize) -> impl Fn(InputRef) -> Node {
    let zero = g.zero();
    // The q elements that move and their rates, for this column.
    let mut rates: Vec<(usize, Node)> = Vec::new();
    for body in &model.bodies {
        let joint = &body.joint;
        let dofs = joint.kind.dofs();
        if !(joint.idx_v..joint.idx_v + dofs).contains(&col) {
            continue;
        }
        let k = col - joint.idx_v;
        match joint.kind {
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => {
                rates.push((joint.idx_q, g.one()));
            }
            JointKind::Free => {
                let q = |i: usize| g.input(Array::Q, joint.idx_q + i);
                let (x, y, z, w) = (q(3), q(4), q(5), q(6));
                if k < 3 {
                    // ṗ = R e_k: the k-th column of the base's rotation.
                    let rotation = quaternion_rotation(g, x, y, z, w);
                    for row in 0..3 {
                        rates.push((joint.idx_q + row, rotation.get(row, k)));
                    }
                } else {
                    // ½ quat ⊗ (e_m, 0), m = k − 3.
                    let half = g.constant(0.5);
                    let m = k - 3;
                    let vector = [x, y, z];
                    // w e_m + (x, y, z) × e_m, then −(x, y, z) · e_m.
                    let mut dot = [g.zero(); 4];
                    dot[m] = w;
                    let (a, b) = ((m + 1) % 3, (m + 2) % 3);
                    // (u × e_m)_a = u_b, (u × e_m)_b = −u_a for (m, a, b) cyclic.
                    dot[a] = g.add(dot[a], vector[b]);
                    dot[b] = g.sub(dot[b], vector[a]);
                    dot[3] = g.neg(vector[m]);
                    for (i, d) in dot.into_iter().enumerate() {
                        rates.push((joint.idx_q + 3 + i, g.mul(half, d)));
                    }
                }
            }
        }
    }
    move |r: InputRef| {
        if r.array != Array::Q {
            return zero;
        }
        rates
            .iter()
            .find(|(index, _)| *index == r.index as usize)
            .map_or(zero, |(_, rate)| *rate)
    }
}

/// The derivative of `outputs` along q̇ = v with every other input held: Σ_j ∂y/∂q_j v_j,
/// q moving along q ⊕ t v (for a free joint v is the twist in the base's own frame), the
/// inputs `v` standing for the velocity. For y = M(q) v this is Ṁ v.
pub fn along_velocity(g: &Graph, model: &Model, outputs: &[Node]) -> Vec<Node> {
    let tangents: Vec<_> = (0..model.nv)
        .map(|col| configuration_tangent(g, model, col))
        .collect();
    g.derivative(outputs, |r| {
        tangents
            .iter()
            .enumerate()
            .fold(g.zero(), |sum, (col, tangent)| {
                g.add(sum, g.mul(tangent(r), g.input(Array::V, col)))
            })
    })
}

/// What a column differentiates with respect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum With {
    /// The configuration, in the tangent space (nv columns).
    Configuration,
    /// One of the input arrays (v, a, τ: nv columns; the loads: one per load input): plain
    /// partial derivatives.
    Array(Array),
}

/// ∂outputs/∂x as rows (one per output), x the configuration (tangent space, nv columns) or
/// an input array (a column per element).
pub fn jacobian(g: &Graph, model: &Model, outputs: &[Node], with: With) -> Vec<Vec<Node>> {
    let count = match with {
        With::Array(Array::Loads) => model.load_inputs,
        With::Array(Array::P) => model.parameters.len(),
        With::Configuration | With::Array(_) => model.nv,
    };
    let columns: Vec<Vec<Node>> = (0..count)
        .map(|col| column(g, model, outputs, with, col))
        .collect();
    (0..outputs.len())
        .map(|row| columns.iter().map(|column| column[row]).collect())
        .collect()
}

/// Column `col` of [`jacobian`]: ∂outputs/∂x_col, one entry per output.
pub fn column(g: &Graph, model: &Model, outputs: &[Node], with: With, col: usize) -> Vec<Node> {
    match with {
        With::Configuration => g.derivative(outputs, configuration_tangent(g, model, col)),
        With::Array(array) => g.derivative(outputs, |r| {
            if r.array == array && r.index as usize == col {
                g.one()
            } else {
                g.zero()
            }
        }),
    }
}
