//! A Coriolis matrix C(q, q̇) with Ṁ − 2C skew-symmetric (the Christoffel-consistent one),
//! organized like the composite-rigid-body mass matrix.
//!
//! With world-frame Jacobians, C = Σ_i J_iᵀ (I_i J̇_i + B_i J_i), where
//! B(I, v) = ½ [(v×*) I + (I v)×̄ − I (v×)] and (f×̄) v = v ×* f (Echeandia & Wensing,
//! 2021); since B + Bᵀ = İ, C + Cᵀ = Ṁ. Joint k's column of J_i is its motion axis s_k,
//! with ṡ_k = v_k × s_k. Only bodies below both joints contribute, so with composite sums
//! over subtrees, I^C_j = Σ I_i and B^C_j = Σ B_i (each carried to body j's frame as
//! Xᵀ · X):
//!
//! ```text
//! C_ij = s_iᵀ (I^C_j ṡ_j + B^C_j s_j)              i = j or an ancestor of j
//! C_ji = (I^C_j s_j)ᵀ ṡ_i + (B^C_jᵀ s_j)ᵀ s_i      i a strict ancestor of j
//! ```
//!
//! B is never formed as a 6×6 matrix. Its symmetric part is ½ İ, the rate of the inertia
//! in a fixed frame, (v×*) I − I (v×): an inertia of mass 0 with first moment
//! ḣ = m v_P + ω × h and rotational part
//! İ_P = ω̂ I_P − I_P ω̂ − (h v_Pᵀ + v_P hᵀ) + 2 (v_P·h) 1.
//! Its skew part is ½ (I v)×̄ (f×̄ is skew), and Xᵀ (f×̄) X = (Xᵀ f)×̄. So
//!
//! ```text
//! B^C_j = ½ İ^C_j + ½ (h^C_j)×̄,    h^C_j = Σ I_i v_i (the subtree's momentum)
//! B^C_j s = ½ (İ^C_j s + s ×* h^C_j),    B^C_jᵀ s = ½ (İ^C_j s − s ×* h^C_j)
//! ```
//!
//! with İ^C carried up the tree like the composite inertias and h^C like a wrench, which
//! costs a fraction of carrying dense 6×6 matrices. The halves are taken on the constant
//! inertias (½ I_i), where they fold away. Spatial inner products do not depend on the
//! frame, so each column's forces are carried up the tree like the mass matrix's.
//! Six-dimensional quantities are linear first: motion [v_P; ω], force [F; M_P].
//!
//! Both runs sweep [`Slots`]: [`coriolis_matrix`] one body a slot, all values scalar (the
//! derivatives' body-by-body candidate is built on it); [`coriolis_matrix_packed`] (the
//! generated `coriolis_matrix`, and the derivatives' packed candidate) isomorphic limbs side by side in the lanes of packed values, and
//! columns carried four to a value ([`super::slot_columns`]). The humanoid g1's C (35 dof):
//! 15,768 multiplications and additions column by column, 7,809 so, 7,024 of them on four
//! lanes.

use super::crba::slot_composite_inertias;
use super::geometry::{self, BodyInertia, JointTransform};
use super::slot_columns::{carry_columns_up, CarriedColumns};
use super::slots::{padded, Slots};
use super::spatial::{add6, dot6, force_cross, inertia_times, motion_cross, sub6, Six};
use super::spatial::{motion_subspace, symmetric};
use crate::model::Model;
use crate::sym::{Graph, Node, Vec3};

/// Half of body i's B terms, in its frame: ½ İ_i as an inertia of mass 0 and the momentum
/// ½ I_i v_i (whose linear part is also ½ ḣ_i).
fn halved_b_terms(g: &Graph, inertia: &BodyInertia, twist: Six) -> (BodyInertia, Six) {
    let half = g.constant(0.5);
    let halved = BodyInertia {
        mass: g.mul(inertia.mass, half),
        first_moment: inertia.first_moment.scale(g, half),
        inertia_about_origin: inertia.inertia_about_origin.scale(g, half),
        mass_centre: None,
    };
    let momentum = inertia_times(g, &halved, twist);
    let (v, w) = twist;
    let h = halved.first_moment;
    let rotating = w.cross_matrix(g).mul(g, halved.inertia_about_origin);
    let v_dot_h = v.dot(g, h);
    let rotational_rate = symmetric(|r, c| {
        let commutator = g.add(rotating.get(r, c), rotating.get(c, r));
        let shift = g.add(g.mul(h.get(r), v.get(c)), g.mul(v.get(r), h.get(c)));
        let entry = g.sub(commutator, shift);
        if r == c {
            g.add(entry, g.add(v_dot_h, v_dot_h))
        } else {
            entry
        }
    });
    let rate = BodyInertia {
        mass: g.zero(),
        first_moment: momentum.0,
        inertia_about_origin: rotational_rate,
        mass_centre: None,
    };
    (rate, momentum)
}

/// Spatial velocities of every slot's bodies, in their own frames.
fn velocities(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<Six> {
    let mut out: Vec<Six> = Vec::with_capacity(slots.slots.len());
    for (s, slot) in slots.slots.iter().enumerate() {
        let (v_p, w_p) = slots
            .parent_slot(s)
            .map_or((Vec3::zero(g), Vec3::zero(g)), |p| out[p]);
        let t = &transforms[s];
        let mut w = geometry::to_body(g, t, w_p);
        let mut v = geometry::to_body(g, t, v_p.add(g, w_p.cross(g, t.origin_in_parent)));
        let kind = &model.bodies[slot.lanes[0]].joint.kind;
        for (col, (sv, sw)) in motion_subspace(g, kind).into_iter().enumerate() {
            let rate = slots.zip_lanes(g, s, |b| velocity[model.bodies[b].joint.idx_v + col]);
            v = v.add(g, sv.scale(g, rate));
            w = w.add(g, sw.scale(g, rate));
        }
        out.push((v, w));
    }
    out
}

/// What C is built from, per slot of bodies ([`Slots`]) in their own frames: the twist
/// v_i, the composite terms ½ İ^C_i (an inertia of mass 0), ½ h^C_i and I^C_i, and each
/// joint's motion axes s and their rates ṡ = v_i × s. The analytical inverse-dynamics
/// derivatives ([`super::rnea_derivatives`]) are built from the same terms, one body a slot
/// or over the packed slots.
pub(crate) struct CompositeTerms {
    /// v_i = [v_P; ω].
    pub twists: Vec<Six>,
    /// ½ İ^C_i.
    pub half_rate_composite: Vec<BodyInertia>,
    /// ½ h^C_i.
    pub half_momenta: Vec<Six>,
    /// I^C_i.
    pub inertia_composite: Vec<BodyInertia>,
    /// The joint's motion axes s, one per velocity coordinate.
    pub subspaces: Vec<Vec<Six>>,
    /// ṡ = v_i × s for each axis.
    pub axis_rates: Vec<Vec<Six>>,
}

impl CompositeTerms {
    /// (B^C_i s, B^C_iᵀ s) = ½ (İ^C_i s ± s ×* h^C_i).
    pub fn b_times(&self, g: &Graph, i: usize, s: Six) -> (Six, Six) {
        let symmetric_part = inertia_times(g, &self.half_rate_composite[i], s);
        let skew_part = force_cross(g, s, self.half_momenta[i]);
        (
            add6(g, symmetric_part, skew_part),
            sub6(g, symmetric_part, skew_part),
        )
    }
}

/// The composite terms of C over `inertias` at the joint velocities `velocity`, one body a
/// slot (indexed by body).
pub(crate) fn composite_terms(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> CompositeTerms {
    slot_composite_terms(
        g,
        model,
        &Slots::each_body(model),
        transforms,
        inertias,
        velocity,
    )
}

/// The composite terms of C over `slots`, from the slots' transforms and inertias (indexed
/// by slot).
pub(crate) fn slot_composite_terms(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> CompositeTerms {
    let n = slots.slots.len();
    let twists = velocities(g, model, slots, transforms, velocity);
    let (rates, mut momenta): (Vec<BodyInertia>, Vec<Six>) = (0..n)
        .map(|i| halved_b_terms(g, &inertias[i], twists[i]))
        .unzip();
    // ½ İ^C and ½ h^C: the subtree sums, each in its body's frame.
    let rate_composite = slot_composite_inertias(g, slots, transforms, &rates);
    super::slots::sum_wrenches_up(g, slots, transforms, &mut momenta);
    let i_composite = slot_composite_inertias(g, slots, transforms, inertias);
    let subspaces: Vec<Vec<Six>> = slots
        .slots
        .iter()
        .map(|slot| motion_subspace(g, &model.bodies[slot.lanes[0]].joint.kind))
        .collect();
    let axis_rates: Vec<Vec<Six>> = subspaces
        .iter()
        .zip(&twists)
        .map(|(s, &twist)| s.iter().map(|&col| motion_cross(g, twist, col)).collect())
        .collect();
    CompositeTerms {
        twists,
        half_rate_composite: rate_composite,
        half_momenta: momenta,
        inertia_composite: i_composite,
        subspaces,
        axis_rates,
    }
}

/// C(q, q̇), an `nv × nv` matrix of nodes, one body a slot, all values scalar (for the
/// derivatives built on it).
pub fn coriolis_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Vec<Vec<Node>> {
    let slots = Slots::each_body(model);
    by_slots(g, model, &slots, (transforms, inertias), velocity, false)
}

/// [`coriolis_matrix`] packed: isomorphic limbs side by side ([`Slots`]), their twists,
/// composite terms and columns in the lanes of packed values; above them the columns'
/// three wrenches travel packed four to a value wherever partly filled ones meet, as the
/// packed mass matrix's do ([`super::crba::mass_matrix_packed`]).
pub fn coriolis_matrix_packed(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Vec<Vec<Node>> {
    let slots = Slots::of(model);
    // Columns packed again where they meet, if the model packs at all ([`Model::packs`]).
    by_slots(
        g,
        model,
        &slots,
        (transforms, inertias),
        velocity,
        model.packs,
    )
}

/// C over `slots` from every body's transform and inertia (zipped into the slots'),
/// partly filled packs of columns packed again where they meet when `repack`. Column j
/// carries the wrenches f1 = I^C_j ṡ_j + B^C_j s_j, f2 = I^C_j s_j and f3 = B^C_jᵀ s_j up
/// the tree: C_ij = s_iᵀ f1 and C_ji = f2ᵀ ṡ_i + f3ᵀ s_i at each ancestor i.
fn by_slots(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    velocity: &[Node],
    repack: bool,
) -> Vec<Vec<Node>> {
    let transforms = slots.transforms(g, transforms);
    let inertias = slots.inertias(g, inertias);
    let terms = slot_composite_terms(g, model, slots, &transforms, &inertias, velocity);
    let mut c = vec![vec![g.zero(); model.nv]; model.nv];
    carry_columns_up(g, slots, &transforms, repack, |s, carried| {
        let slot = &slots.slots[s];
        let row_of = |k: usize, row_in_joint: usize| {
            model.bodies[*padded(&slot.lanes, k)].joint.idx_v + row_in_joint
        };
        // The columns of the bodies below: in a packed slot lane k is the row's body too.
        for column in carried.iter() {
            let [f1, f2, f3] = [0, 1, 2].map(|w| column.wrenches[w]);
            for (r, &s_i) in terms.subspaces[s].iter().enumerate() {
                let below = dot6(g, s_i, f1);
                let above = g.add(dot6(g, f2, terms.axis_rates[s][r]), dot6(g, f3, s_i));
                for (k, &col) in column.columns.iter().enumerate() {
                    c[row_of(k, r)][col] = g.lane(below, k);
                    c[col][row_of(k, r)] = g.lane(above, k);
                }
            }
        }
        // The slot's own columns, and their entries in its own rows.
        for (col, &s_j) in terms.subspaces[s].iter().enumerate() {
            let (b_s, bt_s) = terms.b_times(g, s, s_j);
            let composite = &terms.inertia_composite[s];
            let f1 = add6(
                g,
                inertia_times(g, composite, terms.axis_rates[s][col]),
                b_s,
            );
            for (r, &s_row) in terms.subspaces[s].iter().enumerate() {
                let entry = dot6(g, s_row, f1);
                for k in 0..slot.lanes.len() {
                    c[row_of(k, r)][row_of(k, col)] = g.lane(entry, k);
                }
            }
            carried.push(CarriedColumns {
                wrenches: vec![f1, inertia_times(g, composite, s_j), bt_s],
                columns: (0..slot.lanes.len()).map(|k| row_of(k, col)).collect(),
            });
        }
    });
    c
}

#[cfg(test)]
mod tests {
    use super::{coriolis_matrix, coriolis_matrix_packed};
    use crate::expand::{
        fresh_graph, inputs,
        slots::Slots,
        tests::{assert_same_values, humanoid},
    };
    use crate::sym::Array;

    /// The packed C (limbs in pairs of lanes, the waist's single columns and the arms'
    /// pairs packed again where they meet) is the column-by-column C entry for entry, and
    /// most of its operations are on four lanes.
    #[test]
    fn the_packed_coriolis_matrix_is_the_scalar_one() {
        let model = humanoid();
        let lanes: Vec<usize> = Slots::of(&model)
            .slots
            .iter()
            .map(|s| s.lanes.len())
            .collect();
        assert_eq!(
            lanes,
            [1, 2, 2, 1, 1, 2, 2],
            "pelvis, legs, waist, chest, arms"
        );
        let (g, t, i) = fresh_graph(&model);
        let v = inputs(&g, Array::V, model.nv);
        let scalar = coriolis_matrix(&g, &model, &t, &i, &v).concat();
        let packed = coriolis_matrix_packed(&g, &model, &t, &i, &v).concat();
        let count = g.op_count(&packed);
        assert!(2 * count.packed > count.total(), "{count}");
        assert!(count.total() < g.op_count(&scalar).total(), "{count}");
        assert_same_values(&g, &model, (&scalar, &packed), "C", |_| 1e-12);
    }
}
