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
//!
//! [`configuration_jacobian`] runs one body at a time, all values scalar;
//! [`configuration_jacobian_packed`] runs over [`Slots`] (isomorphic limbs side by side in
//! the lanes of packed values) and carries each column's three wrenches I^C_j s_j,
//! B^C_jᵀ s_j and G_j up packed four to a value where partly filled ones meet, as the
//! packed Coriolis matrix does: the first two are the Coriolis matrix's own carried
//! wrenches, shared with ∂τ/∂q̇ = 2 C + diag(b) built in the same graph.

use super::coriolis::{self, CompositeTerms};
use super::geometry::{self, BodyInertia, JointTransform};
use super::rnea::{self, BodyMotion, SweepInputs};
use super::slot_columns::{carry_columns_up, CarriedColumns};
use super::slots::{padded, Slots};
use super::spatial::{add6, dot6, force_cross, inertia_times, motion_cross, scale6, Six};
use crate::model::{JointKind, Model};
use crate::sym::{Graph, Node, Vec3};

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

/// [`configuration_jacobian`] over [`Slots`], the composite terms and the Newton–Euler
/// sweep packed lane by lane, the columns' wrenches [I^C_j s_j, B^C_jᵀ s_j, G_j] carried
/// up as the packed Coriolis matrix carries its own (module doc). A free joint's columns
/// are left zero for the caller.
pub fn configuration_jacobian_packed(
    g: &Graph,
    model: &Model,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    (velocity, acceleration): (&[Node], &[Node]),
) -> Vec<Vec<Node>> {
    let slots = Slots::of(model);
    let transforms = slots.transforms(g, transforms);
    let inertias = slots.inertias(g, inertias);
    let terms = coriolis::slot_composite_terms(g, model, &slots, &transforms, &inertias, velocity);
    let sweep = slot_sweep(
        g,
        model,
        &slots,
        (&transforms, &inertias),
        (velocity, acceleration),
    );
    let two = g.constant(2.0);
    let mut jacobian = vec![vec![g.zero(); model.nv]; model.nv];
    carry_columns_up(g, &slots, &transforms, model.packs, |s, carried| {
        let slot = &slots.slots[s];
        let row_of = |k: usize, row_in_joint: usize| {
            model.bodies[*padded(&slot.lanes, k)].joint.idx_v + row_in_joint
        };
        // (Ψ̇, Ψ̈) of the slot's joints, Ψ̈ = a × s + v × Ψ̇, a = [a_P − ω × v_P; α] the
        // spatial acceleration (gravity included).
        let psi = (model.bodies[slot.lanes[0]].joint.kind != JointKind::Free).then(|| {
            let (motion, twist) = (&sweep[s].0, terms.twists[s]);
            let spatial = (motion.accel.sub(g, twist.1.cross(g, twist.0)), motion.alpha);
            let psi_dot = terms.axis_rates[s][0];
            let psi_ddot = add6(
                g,
                motion_cross(g, spatial, terms.subspaces[s][0]),
                motion_cross(g, terms.twists[s], psi_dot),
            );
            (psi_dot, psi_ddot)
        });
        // The columns of the joints below: ∂τ_i/∂q_j = s_i · G_j in this slot's rows i,
        // ∂τ_j/∂q_i = (I^C_j s_j)·Ψ̈_i + 2 (B^C_jᵀ s_j)·Ψ̇_i in their rows j.
        for column in carried.iter() {
            let [inertia_s, bt_s, g_j] = [0, 1, 2].map(|w| column.wrenches[w]);
            for (r, &s_i) in terms.subspaces[s].iter().enumerate() {
                let entry = dot6(g, s_i, g_j);
                for (k, &col) in column.columns.iter().enumerate() {
                    jacobian[row_of(k, r)][col] = g.lane(entry, k);
                }
            }
            if let Some((psi_dot, psi_ddot)) = psi {
                let entry = rows_entry(g, (inertia_s, bt_s), (psi_dot, psi_ddot));
                for (k, &row) in column.columns.iter().enumerate() {
                    jacobian[row][row_of(k, 0)] = g.lane(entry, k);
                }
            }
        }
        // The slot's own columns: their diagonal entries, and their wrenches to carry.
        if let Some((psi_dot, psi_ddot)) = psi {
            let s_j = terms.subspaces[s][0];
            let composite = &terms.inertia_composite[s];
            let inertia_s = inertia_times(g, composite, s_j);
            let bt_s = terms.b_times(g, s, s_j).1;
            let diagonal = rows_entry(g, (inertia_s, bt_s), (psi_dot, psi_ddot));
            let g_j = add6(
                g,
                force_cross(g, s_j, sweep[s].1),
                add6(
                    g,
                    inertia_times(g, composite, psi_ddot),
                    scale6(g, terms.b_times(g, s, psi_dot).0, two),
                ),
            );
            let columns: Vec<usize> = (0..slot.lanes.len()).map(|k| row_of(k, 0)).collect();
            for (k, &j) in columns.iter().enumerate() {
                jacobian[j][j] = g.lane(diagonal, k);
            }
            carried.push(CarriedColumns {
                wrenches: vec![inertia_s, bt_s, g_j],
                columns,
            });
        }
    });
    jacobian
}

/// ∂τ_j/∂q_i = (I^C_j s_j)·Ψ̈_i + 2 (B^C_jᵀ s_j)·Ψ̇_i, j = i or below i.
fn rows_entry(g: &Graph, (inertia_s, bt_s): (Six, Six), (psi_dot, psi_ddot): (Six, Six)) -> Node {
    let half = dot6(g, bt_s, psi_dot);
    g.add(dot6(g, inertia_s, psi_ddot), g.add(half, half))
}

/// The Newton–Euler sweeps over `slots` (lane k of each value is the slot's lane-k body):
/// each slot's motion (gravity as the base's −g) and the wrench f its joints transmit,
/// [F; M_P] in the body frames.
fn slot_sweep(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    (velocity, acceleration): (&[Node], &[Node]),
) -> Vec<(BodyMotion, Six)> {
    let gravity = Vec3::constant(g, model.gravity_in_world).neg(g);
    let base = BodyMotion::new(g, Vec3::zero(g), Vec3::zero(g), gravity);
    let mut motions: Vec<BodyMotion> = Vec::with_capacity(slots.slots.len());
    for (s, slot) in slots.slots.iter().enumerate() {
        let joint = &model.bodies[slot.lanes[0]].joint;
        // The inputs with lane 0's joint's entries the slot's lanes' zipped.
        let zipped = |values: &[Node]| {
            let mut out = values.to_vec();
            for d in 0..joint.kind.dofs() {
                out[joint.idx_v + d] =
                    slots.zip_lanes(g, s, |b| values[model.bodies[b].joint.idx_v + d]);
            }
            out
        };
        let (velocity, acceleration) = (zipped(velocity), zipped(acceleration));
        let inputs = SweepInputs {
            velocity: &velocity,
            acceleration: &acceleration,
            gravity: true,
            loads: false,
        };
        let parent = slots.parent_slot(s).map_or(base, |p| motions[p]);
        motions.push(rnea::forward(g, joint, &transforms[s], parent, &inputs));
    }
    let mut wrenches: Vec<Six> = motions
        .iter()
        .zip(inertias)
        .map(|(motion, inertia)| rnea::body_wrench(g, motion, inertia))
        .collect();
    super::slots::sum_wrenches_up(g, slots, transforms, &mut wrenches);
    motions.into_iter().zip(wrenches).collect()
}

#[cfg(test)]
mod tests {
    use super::{configuration_jacobian, configuration_jacobian_packed};
    use crate::expand::coriolis::composite_terms;
    use crate::expand::tests::{assert_same_values, humanoid};
    use crate::expand::{fresh_graph, inputs};
    use crate::sym::Array;

    /// The packed recursion (legs and arms in pairs of lanes, the waist's columns packed
    /// again where they meet) is the body-by-body one entry for entry, in fewer operations.
    #[test]
    fn the_packed_recursion_is_the_scalar_one() {
        let model = humanoid();
        let (g, t, i) = fresh_graph(&model);
        let (v, a) = (
            inputs(&g, Array::V, model.nv),
            inputs(&g, Array::A, model.nv),
        );
        let terms = composite_terms(&g, &model, &t, &i, &v);
        let scalar = configuration_jacobian(&g, &model, (&t, &i), &terms, (&v, &a)).concat();
        let packed = configuration_jacobian_packed(&g, &model, (&t, &i), (&v, &a)).concat();
        let count = g.op_count(&packed);
        assert!(2 * count.packed > count.total(), "{count}");
        assert!(count.total() < g.op_count(&scalar).total(), "{count}");
        // Every joint column (the free root's six are the caller's) has entries.
        let relative = |w: f64| 1e-12 * (1.0 + w.abs());
        assert_same_values(&g, &model, (&scalar, &packed), "∂τ/∂q", relative);
    }
}
