//! ∂τ/∂q of inverse dynamics by the analytical recursion (the configuration half of
//! Singh, Russell and Wensing's derivatives of Newton–Euler, 2022), written over the
//! Coriolis matrix's composite terms ([`super::coriolis::CompositeTerms`]).
//!
//! Turning joint j by δq_j moves its subtree rigidly by the screw s_j δq_j. A rigid
//! motion changes no inner product of a motion with a force, so what changes τ is what
//! the subtree does not carry along: every twist below j gains Ψ̇_j δq_j and every
//! acceleration Ψ̈_j δq_j + Ψ̇_j × v_k δq_j, with
//!
//! ```text
//! Ψ̇_j = ṡ_j = v_j × s_j,        Ψ̈_j = a_j × s_j + v_j × Ψ̇_j
//! ```
//!
//! (a_j the spatial acceleration, gravity included as the base's −g). Body k's wrench
//! f_k = I_k a_k + v_k ×* I_k v_k then gains I_k Ψ̈_j + 2 B_k Ψ̇_j beside its rigid motion
//! (B_k the Coriolis matrix's B(I_k, v_k)), so with the subtree sums I^C, B^C and the
//! composite wrench F_j that joint j transmits:
//!
//! ```text
//! ∂τ_i/∂q_j = (I^C_i s_i)·Ψ̈_j + 2 (B^C_iᵀ s_i)·Ψ̇_j     j = i or an ancestor of i
//! ∂τ_i/∂q_j = s_i · (s_j ×* F_j + I^C_j Ψ̈_j + 2 B^C_j Ψ̇_j)   i a strict ancestor of j
//! ```
//!
//! and zero where neither joint is below the other. The forces I^C_i s_i and B^C_iᵀ s_i
//! are the ones the Coriolis matrix carries up the tree, so beside ∂τ/∂q̇ = 2 C + diag(b)
//! the first line costs two inner products an entry; the second carries one wrench per
//! column to the root. Inner products do not depend on the frame, so everything stays in
//! body frames (motion [v_P; ω], force [F; M_P]).
//!
//! For joints of one coordinate. A free joint's own columns come from M
//! ([`super::free_joint_derivatives`]; its twist columns are not derivatives of
//! coordinates). Applied loads are not rigid with their body when given in world axes, so a
//! mechanism with loads keeps forward mode.

use super::coriolis::CompositeTerms;
use super::geometry::{self, BodyInertia, JointTransform};
use super::rnea::{self, SweepInputs};
use super::spatial::{add6, dot6, force_cross, inertia_times, motion_cross, scale6, Six};
use crate::model::{JointKind, Model};
use crate::sym::{Graph, Node};

/// Whether the recursion applies: no loads, and a free joint only on the ground.
pub fn applies(model: &Model) -> bool {
    model.loads.is_empty()
        && model
            .bodies
            .iter()
            .all(|b| b.joint.kind != JointKind::Free || b.parent.is_none())
}

/// ∂τ/∂q (rows τ_i, columns q_j in the tangent space) at (q, `velocity`, `acceleration`)
/// for the columns of one-coordinate joints; a free joint's columns are left zero for the
/// caller. `terms` are the composite terms over the same `inertias` at `velocity`.
pub fn configuration_jacobian(
    g: &Graph,
    model: &Model,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    terms: &CompositeTerms,
    (velocity, acceleration): (&[Node], &[Node]),
) -> Vec<Vec<Node>> {
    let sweep = rnea::sweep(
        g,
        model,
        transforms,
        inertias,
        &SweepInputs {
            velocity,
            acceleration,
            gravity: true,
            loads: false,
        },
    );
    let two = g.constant(2.0);
    // (Ψ̇_j, Ψ̈_j) of each one-coordinate joint.
    let psi: Vec<Option<(Six, Six)>> = model
        .bodies
        .iter()
        .enumerate()
        .map(|(j, body)| {
            (body.joint.kind != JointKind::Free).then(|| {
                let s_j = terms.subspaces[j][0];
                let psi_dot = terms.axis_rates[j][0];
                let twist = terms.twists[j];
                let motion = &sweep.motions[j];
                // The spatial acceleration [a_P − ω × v_P; α].
                let spatial = (motion.accel.sub(g, twist.1.cross(g, twist.0)), motion.alpha);
                let psi_ddot = add6(
                    g,
                    motion_cross(g, spatial, s_j),
                    motion_cross(g, twist, psi_dot),
                );
                (psi_dot, psi_ddot)
            })
        })
        .collect();
    let mut jacobian = vec![vec![g.zero(); model.nv]; model.nv];
    let carry = |i: usize, f: Six| geometry::wrench_to_parent(g, &transforms[i], f.0, f.1);
    // Rows i a strict ancestor of the column's joint j: s_i · G_j, G_j carried up.
    for (j, body) in model.bodies.iter().enumerate() {
        let Some((psi_dot, psi_ddot)) = psi[j] else {
            continue;
        };
        let column = body.joint.idx_v;
        let (b_psi, _) = terms.b_times(g, j, psi_dot);
        let mut g_j = add6(
            g,
            force_cross(g, terms.subspaces[j][0], sweep.wrenches()[j]),
            add6(
                g,
                inertia_times(g, &terms.inertia_composite[j], psi_ddot),
                scale6(g, b_psi, two),
            ),
        );
        let mut i = j;
        while let Some(parent) = model.bodies[i].parent {
            g_j = carry(i, g_j);
            i = parent;
            let ancestor = &model.bodies[i].joint;
            for (r, &s_i) in terms.subspaces[i].iter().enumerate() {
                jacobian[ancestor.idx_v + r][column] = dot6(g, s_i, g_j);
            }
        }
    }
    // Rows i, columns j = i or an ancestor: I^C_i s_i and B^C_iᵀ s_i carried up to j.
    for (i, body) in model.bodies.iter().enumerate() {
        if body.joint.kind == JointKind::Free {
            continue;
        }
        let row = body.joint.idx_v;
        let s_i = terms.subspaces[i][0];
        let mut inertia_s = inertia_times(g, &terms.inertia_composite[i], s_i);
        let mut bt_s = scale6(g, terms.b_times(g, i, s_i).1, two);
        let mut j = i;
        loop {
            if let Some((psi_dot, psi_ddot)) = psi[j] {
                jacobian[row][model.bodies[j].joint.idx_v] =
                    g.add(dot6(g, inertia_s, psi_ddot), dot6(g, bt_s, psi_dot));
            }
            let Some(parent) = model.bodies[j].parent else {
                break;
            };
            inertia_s = carry(j, inertia_s);
            bt_s = carry(j, bt_s);
            j = parent;
        }
    }
    jacobian
}
