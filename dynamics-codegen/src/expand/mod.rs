//! The symbolic expansion: the textbook's recursions written over DAG nodes. Each module is
//! one algorithm, reads like the book and takes the inertias it is given (the declared
//! ones, or base inertial parameters chosen by [`crate::passes::base_parameters`]); which
//! functions are built from them, with which inputs, is [`crate::functions`]'s list. The
//! code mirrors the recursion (never a closed-form Lagrangian), so its size grows linearly
//! with the number of joints for inverse and forward dynamics and quadratically for the mass
//! matrix.
//!
//! | module | what |
//! | --- | --- |
//! | [`geometry`] | each body's joint transform (E, r) and inertia (m, h = m c, I_P) |
//! | [`spatial`] | six-vectors, the symmetric 3×3 helpers, a joint's motion subspace |
//! | [`rnea`] | the Newton–Euler sweeps: motions, body equations about P, joint wrenches and τ |
//! | [`slots`] | isomorphic sibling limbs grouped side by side, one per lane of packed values |
//! | [`slot_columns`] | a tree matrix's columns carried up by slots, packed four to a value |
//! | [`crba`] | composite inertias and the mass matrix (by slots, packed) |
//! | [`coriolis`] | the Christoffel-consistent Coriolis matrix (by slots, packed) |
//! | [`aba`] | the articulated-body algorithm |
//! | [`ldlt`] | the tree-sparse LDLᵀ solve of M q̈ = τ − bias |
//! | [`energy`] | kinetic and potential energy |
//! | [`kinematics`] | body poses, point Jacobians, the centre of mass, its Jacobian, the centroidal momentum matrix and its rate |
//! | [`derivatives`] | forward-mode derivatives of an expanded function with respect to q (tangent space), v, a or τ |
//! | [`free_joint_derivatives`] | a free joint's columns of ∂τ/∂q̇ and ∂τ/∂q from M and C |
//! | [`rnea_derivatives`] | ∂τ/∂q by the analytical recursion over the Coriolis matrix's composite terms |
//! | [`frames`] | operational frames: poses, Jacobians (world-aligned and local), J̇ q̇ |
//! | [`statics`] | the balance equations of the force analysis and the loop closures |
//! | [`qr`] | a Givens QR solve for the force analysis |

pub(crate) mod aba;
pub(crate) mod coriolis;
pub(crate) mod crba;
pub(crate) mod derivatives;
pub(crate) mod energy;
pub(crate) mod frames;
pub(crate) mod free_joint_derivatives;
pub(crate) mod geometry;
pub(crate) mod kinematics;
pub(crate) mod ldlt;
pub(crate) mod qr;
pub(crate) mod rnea;
pub(crate) mod rnea_derivatives;
pub(crate) mod slot_columns;
pub(crate) mod slots;
pub(crate) mod spatial;
pub(crate) mod statics;

use crate::model::Model;
use crate::sym::{Array, Graph, Node};

/// A new graph with the joint transforms and body inertias (as declared) every expansion
/// starts from.
pub(crate) fn fresh_graph(
    model: &Model,
) -> (
    Graph,
    Vec<geometry::JointTransform>,
    Vec<geometry::BodyInertia>,
) {
    let g = Graph::new();
    let transforms = geometry::joint_transforms(&g, model);
    let inertias = model
        .bodies
        .iter()
        .map(|b| geometry::body_inertia(&g, b))
        .collect();
    (g, transforms, inertias)
}

/// The first `n` elements of the input array `array`.
pub(crate) fn inputs(g: &Graph, array: Array, n: usize) -> Vec<Node> {
    (0..n).map(|k| g.input(array, k)).collect()
}
