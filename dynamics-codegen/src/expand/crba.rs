//! The mass matrix M(q) by composite rigid bodies, exploiting the tree's sparsity.
//!
//! Composite inertia (backward sweep): the inertia of body i and everything it carries,
//! about P_i in body i's frame, as (m, h, I_P). Moving a child's composite inertia into the
//! parent frame, where the child origin is at r and its rotation is E:
//!
//! ```text
//! m' = m,   h' = E h + m r,
//! I' = E I_P Eᵀ − ((E h)^ r̂ + r̂ (E h)^) − m r̂²
//! ```
//!
//! (the textbook's I_P = I_G − m ĉ² applied to the shifted mass centre). Column j: the wrench
//! that the composite body needs to move along joint j's motion subspace s_j,
//! f = I^c_j s_j (F = m v + ω × h, M_P = h × v + I_P ω for s = [v; ω]); then
//! M_ij = s_iᵀ f for j and each ancestor i, carrying f to each parent frame on the way.
//! Entries between bodies on different branches are zero and cost nothing. M depends on the
//! inertias only through the kinetic energy, so the generated function is expanded over
//! base inertial parameters ([`crate::passes::base_parameters`]).

use super::geometry::{self, BodyInertia, JointTransform};
use super::spatial::{congruence, inertia_times, motion_subspace, symmetric};
use crate::model::Model;
use crate::sym::{Graph, Node, Vec3};

/// Composite inertias of every body's subtree, about its origin, in its frame.
pub fn composite_inertias(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<BodyInertia> {
    let mut composite = inertias.to_vec();
    for i in (0..model.bodies.len()).rev() {
        if let Some(p) = model.bodies[i].parent {
            let moved = to_parent(g, &transforms[i], &composite[i]);
            let acc = &mut composite[p];
            acc.mass = g.add(acc.mass, moved.mass);
            acc.first_moment = acc.first_moment.add(g, moved.first_moment);
            acc.inertia_about_origin = acc.inertia_about_origin.add(g, moved.inertia_about_origin);
        }
    }
    composite
}

/// A body's inertia expressed in its parent's frame, about the parent's origin.
fn to_parent(g: &Graph, t: &JointTransform, inertia: &BodyInertia) -> BodyInertia {
    let e = t.rotation_to_parent;
    let r = t.origin_in_parent;
    let h_rotated = e.mul_vec(g, inertia.first_moment);
    let r_hat = r.cross_matrix(g);
    let h_hat = h_rotated.cross_matrix(g);
    let rotated = congruence(g, e, inertia.inertia_about_origin);
    // ĥ r̂ + r̂ ĥ and m r̂² are symmetric: one triangle computed, mirrored.
    let h_r = h_hat.mul(g, r_hat);
    let cross_terms = symmetric(|i, j| g.add(h_r.get(i, j), h_r.get(j, i)));
    let r_r = symmetric(|i, j| r_hat.row(i).dot(g, r_hat.col(j)));
    let shift = r_r.scale(g, inertia.mass);
    BodyInertia {
        mass: inertia.mass,
        first_moment: h_rotated.add(g, r.scale(g, inertia.mass)),
        inertia_about_origin: rotated.sub(g, cross_terms).sub(g, shift),
        mass_centre: None,
    }
}

/// sᵀ f for a motion column s = [v; ω] and a wrench f = [F; M].
fn project(g: &Graph, column: &(Vec3, Vec3), force: Vec3, moment: Vec3) -> Node {
    g.add(column.0.dot(g, force), column.1.dot(g, moment))
}

/// M(q), full and symmetric, with armature on the diagonal.
pub fn mass_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    let composite = composite_inertias(g, model, transforms, inertias);
    let subspaces: Vec<Vec<(Vec3, Vec3)>> = model
        .bodies
        .iter()
        .map(|b| motion_subspace(g, &b.joint.kind))
        .collect();
    let mut m = vec![vec![g.zero(); model.nv]; model.nv];
    for (j, body) in model.bodies.iter().enumerate() {
        let c = &composite[j];
        for (col, s) in subspaces[j].iter().enumerate() {
            let column = body.joint.idx_v + col;
            let (mut force, mut moment) = inertia_times(g, c, *s);
            for (row_in_joint, s_row) in subspaces[j].iter().enumerate() {
                let row = body.joint.idx_v + row_in_joint;
                m[row][column] = project(g, s_row, force, moment);
            }
            let mut i = j;
            while let Some(p) = model.bodies[i].parent {
                (force, moment) = geometry::wrench_to_parent(g, &transforms[i], force, moment);
                i = p;
                for (row_in_joint, s_row) in subspaces[i].iter().enumerate() {
                    let row = model.bodies[i].joint.idx_v + row_in_joint;
                    let entry = project(g, s_row, force, moment);
                    m[row][column] = entry;
                    m[column][row] = entry;
                }
            }
        }
        let armature = geometry::value(g, &body.joint.armature);
        for k in body.joint.idx_v..body.joint.idx_v + body.joint.kind.dofs() {
            m[k][k] = g.add(m[k][k], armature);
        }
    }
    m
}
