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
//! | [`rnea_derivatives`] | ∂τ/∂q by the analytical recursion over the Coriolis matrix's composite terms (body by body, or by slots, packed) |
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

#[cfg(test)]
pub(crate) mod tests {
    use proc_macro2::TokenStream;
    use quote::quote;

    /// A small humanoid: legs in a pair off the pelvis (two lanes), a waist chain of single
    /// joints (whose columns meet and travel packed), arms in a pair off the chest.
    pub(crate) fn humanoid() -> crate::model::Model {
        let mechanism: crate::syntax::Mechanism =
            syn::parse2(humanoid_declaration(quote!())).expect("parses");
        crate::model::lower(&mechanism).expect("valid")
    }

    /// [`humanoid`]'s declaration, with `settings` (such as `outputs: [..];`) after its name.
    pub(crate) fn humanoid_declaration(settings: TokenStream) -> TokenStream {
        quote! {
            struct Humanoid;
            #settings
            body pelvis { mass: 3.0, inertia: diag([0.03, 0.02, 0.025]) }
            joint base: free(ground -> pelvis);
            body thigh_l { mass: 1.1, com: [0.0, 0.01, -0.12], inertia: diag([0.012, 0.011, 0.002]) }
            body shin_l { mass: 0.6, com: [0.0, 0.0, -0.15], inertia: diag([0.008, 0.008, 0.001]) }
            joint hip_l: revolute(pelvis -> thigh_l) { axis: y, at: [0.0, 0.09, -0.05] }
            joint knee_l: revolute(thigh_l -> shin_l) { axis: y, at: [0.0, 0.0, -0.3] }
            body thigh_r { mass: 1.1, com: [0.0, -0.01, -0.12], inertia: diag([0.012, 0.011, 0.002]) }
            body shin_r { mass: 0.6, com: [0.0, 0.0, -0.15], inertia: diag([0.008, 0.008, 0.001]) }
            joint hip_r: revolute(pelvis -> thigh_r) { axis: y, at: [0.0, -0.09, -0.05] }
            joint knee_r: revolute(thigh_r -> shin_r) { axis: y, at: [0.0, 0.0, -0.3] }
            body waist { mass: 0.4, com: [0.0, 0.0, 0.03], inertia: diag([0.001, 0.001, 0.0008]) }
            body chest { mass: 2.2, com: [0.01, 0.0, 0.15], inertia: diag([0.04, 0.03, 0.02]) }
            joint waist_yaw: revolute(pelvis -> waist) { axis: z, at: [0.0, 0.0, 0.1] }
            joint waist_pitch: revolute(waist -> chest) { axis: y, at: [0.0, 0.0, 0.05] }
            body arm_l { mass: 0.5, com: [0.0, 0.02, -0.1], inertia: diag([0.003, 0.003, 0.0005]) }
            body forearm_l { mass: 0.3, com: [0.0, 0.0, -0.1], inertia: diag([0.002, 0.002, 0.0003]) }
            joint shoulder_l: revolute(chest -> arm_l) { axis: x, at: [0.0, 0.15, 0.3] }
            joint elbow_l: revolute(arm_l -> forearm_l) { axis: y, at: [0.0, 0.0, -0.22] }
            body arm_r { mass: 0.5, com: [0.0, -0.02, -0.1], inertia: diag([0.003, 0.003, 0.0005]) }
            body forearm_r { mass: 0.3, com: [0.0, 0.0, -0.1], inertia: diag([0.002, 0.002, 0.0003]) }
            joint shoulder_r: revolute(chest -> arm_r) { axis: x, at: [0.0, -0.15, 0.3] }
            joint elbow_r: revolute(arm_r -> forearm_r) { axis: y, at: [0.0, 0.0, -0.22] }
        }
    }

    /// Two expansions of one matrix, `scalar` and `packed` (flattened by rows, `model.nv`
    /// columns), take the same values at [`state`] (within `tolerance` of the scalar
    /// value), and the values are not mostly zero.
    pub(crate) fn assert_same_values(
        g: &crate::sym::Graph,
        model: &crate::model::Model,
        (scalar, packed): (&[crate::sym::Node], &[crate::sym::Node]),
        what: &str,
        tolerance: impl Fn(f64) -> f64,
    ) {
        let value = state(model);
        let (want, got) = (g.eval(&value, scalar), g.eval(&value, packed));
        for (k, (w, x)) in want.iter().zip(&got).enumerate() {
            let (row, col) = (k / model.nv, k % model.nv);
            assert!(
                (w - x).abs() < tolerance(*w),
                "{what}[{row}][{col}]: {x} packed, {w} not"
            );
        }
        assert!(want.iter().filter(|w| w.abs() > 1e-6).count() > 2 * model.nv);
    }

    /// A state of `model` (a free root's quaternion normalized): q, and q̇ and q̈ of a few
    /// radians a second (squared).
    pub(crate) fn state(model: &crate::model::Model) -> impl Fn(crate::sym::InputRef) -> f64 {
        let mut q: Vec<f64> = (0..model.nq)
            .map(|k| (0.61 * k as f64 + 0.2).sin())
            .collect();
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let rates: Vec<f64> = (0..model.nv)
            .map(|k| (1.3 * k as f64).cos() * 2.0)
            .collect();
        let accelerations: Vec<f64> = (0..model.nv)
            .map(|k| (0.7 * k as f64 + 0.3).sin() * 3.0)
            .collect();
        move |r| match r.array {
            crate::sym::Array::Q => q[r.index as usize],
            crate::sym::Array::A => accelerations[r.index as usize],
            _ => rates[r.index as usize],
        }
    }
}
