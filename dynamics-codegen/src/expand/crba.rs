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
//!
//! Both runs sweep [`Slots`]: [`mass_matrix`] one body to a slot, all values scalar;
//! [`mass_matrix_packed`] (the generated `mass_matrix`) isomorphic limbs (a humanoid's
//! legs, its arms, a quadruped's four legs) side by side in the lanes of packed values, so
//! that one operation moves the composite inertias, or carries the columns, of two to four
//! limbs; above the limbs the columns f travel packed four to a value wherever partly
//! filled ones meet ([`super::slot_columns::pack_columns`]), one transform applied to the
//! four. Lane by lane it is the same arithmetic; only the order in which a parent adds up
//! its children's composite inertias follows the slots. The humanoid g1's M (35 dof):
//! 4,266 multiplications and additions column by column, 2,091 so, nearly all on four
//! lanes.

use super::geometry::{self, BodyInertia, JointTransform};
use super::slot_columns::{pack_columns, CarriedColumns};
use super::slots::{padded, SlotParent, Slots};
use super::spatial::{congruence, dot6, inertia_times, motion_subspace, symmetric};
use crate::model::Model;
use crate::sym::{Graph, Mat3, Node, Vec3};

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

/// M(q), full and symmetric, with armature on the diagonal, column by column: each
/// column's wrench carried up on its own, all values scalar.
pub fn mass_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    by_slots(
        g,
        model,
        &Slots::each_body(model),
        transforms,
        inertias,
        false,
    )
}

/// [`mass_matrix`] packed: isomorphic limbs computed side by side ([`Slots`]), their
/// composite inertias and columns in the lanes of packed values; above them the columns
/// travel packed four to a value wherever partly filled ones meet, each ancestor step's
/// transform applied to the four at once. For the mass matrix returned on its own: inside
/// forward dynamics (M then LDLᵀ) the packed M made go2's 14 % slower (283 → 323 ns, per
/// state, 20 states), where go2's M alone takes 0.70 of its time.
pub fn mass_matrix_packed(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    // Columns packed again where they meet, if the model packs at all ([`Model::packs`]).
    by_slots(
        g,
        model,
        &Slots::of(model),
        transforms,
        inertias,
        model.packs,
    )
}

/// M(q) over `slots`, partly filled packs of columns packed again where they meet when
/// `repack`.
fn by_slots(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    repack: bool,
) -> Vec<Vec<Node>> {
    let transforms = slots.transforms(g, transforms);
    let composite = slot_composite_inertias(g, slots, &transforms, &slots.inertias(g, inertias));
    let mut m = vec![vec![g.zero(); model.nv]; model.nv];
    let mut arriving: Vec<Vec<CarriedColumns>> = slots.slots.iter().map(|_| Vec::new()).collect();
    for s in (0..slots.slots.len()).rev() {
        let slot = &slots.slots[s];
        let joint = &model.bodies[slot.lanes[0]].joint;
        let subspace = motion_subspace(g, &joint.kind);
        let mut carried = std::mem::take(&mut arriving[s]);
        for (col, s_col) in subspace.iter().enumerate() {
            let columns = slot
                .lanes
                .iter()
                .map(|&b| model.bodies[b].joint.idx_v + col)
                .collect();
            carried.push(CarriedColumns {
                wrenches: vec![inertia_times(g, &composite[s], *s_col)],
                columns,
            });
        }
        if repack && slot.lanes.len() == 1 && slot.parent != SlotParent::Ground {
            carried = pack_columns(g, carried);
        }
        for c in &carried {
            for (row_in_joint, &s_row) in subspace.iter().enumerate() {
                // M_ij = s_iᵀ f.
                let entry = dot6(g, s_row, c.wrenches[0]);
                for (k, &column) in c.columns.iter().enumerate() {
                    // In a packed slot lane k is both the row's body and the column's.
                    let row_joint = &model.bodies[*padded(&slot.lanes, k)].joint;
                    let row = row_joint.idx_v + row_in_joint;
                    let value = g.lane(entry, k);
                    m[row][column] = value;
                    if !(row_joint.idx_v..row_joint.idx_v + joint.kind.dofs()).contains(&column) {
                        m[column][row] = value;
                    }
                }
            }
        }
        if let Some(p) = slots.parent_slot(s) {
            for c in carried {
                arriving[p].push(c.moved_to_parent(g, &transforms[s]));
            }
        }
        for &b in &slot.lanes {
            let joint = &model.bodies[b].joint;
            let armature = geometry::value(g, &joint.armature);
            for k in joint.idx_v..joint.idx_v + joint.kind.dofs() {
                m[k][k] = g.add(m[k][k], armature);
            }
        }
    }
    m
}

/// Composite inertias by slots (the children's before their parents'): each slot's lanes'
/// composite inertias, packed as the slot is; a scalar parent takes each lane's in turn.
pub(crate) fn slot_composite_inertias(
    g: &Graph,
    slots: &Slots,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<BodyInertia> {
    let mut composite = inertias.to_vec();
    for s in (0..slots.slots.len()).rev() {
        let Some(p) = slots.parent_slot(s) else {
            continue;
        };
        let moved = to_parent(g, &transforms[s], &composite[s]);
        for k in slots.lanes_into_parent(s) {
            let lane = |x: Node| k.map_or(x, |k| g.lane(x, k));
            let acc = &mut composite[p];
            acc.mass = g.add(acc.mass, lane(moved.mass));
            acc.first_moment = acc
                .first_moment
                .add(g, Vec3(moved.first_moment.0.map(lane)));
            let rotational = Mat3(moved.inertia_about_origin.0.map(|row| row.map(lane)));
            acc.inertia_about_origin = acc.inertia_about_origin.add(g, rotational);
        }
    }
    composite
}
