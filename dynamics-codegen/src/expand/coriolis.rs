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

use super::crba::composite_inertias;
use super::geometry::{self, BodyInertia, JointTransform};
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

/// Spatial velocities of every body, in its own frame.
fn velocities(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<Six> {
    let mut out: Vec<Six> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let (v_p, w_p) = body
            .parent
            .map_or((Vec3::zero(g), Vec3::zero(g)), |p| out[p]);
        let t = &transforms[i];
        let mut w = geometry::to_body(g, t, w_p);
        let mut v = geometry::to_body(g, t, v_p.add(g, w_p.cross(g, t.origin_in_parent)));
        let k = body.joint.idx_v;
        for (col, (sv, sw)) in motion_subspace(g, &body.joint.kind).into_iter().enumerate() {
            v = v.add(g, sv.scale(g, velocity[k + col]));
            w = w.add(g, sw.scale(g, velocity[k + col]));
        }
        out.push((v, w));
    }
    out
}

/// What C is built from, per body in its own frame: the twist v_i, the composite terms
/// ½ İ^C_i (an inertia of mass 0), ½ h^C_i and I^C_i, and each joint's motion axes s and
/// their rates ṡ = v_i × s. The analytical inverse-dynamics derivatives
/// ([`super::rnea_derivatives`]) are built from the same terms.
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

/// The composite terms of C over `inertias` at the joint velocities `velocity`.
pub(crate) fn composite_terms(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> CompositeTerms {
    let n = model.bodies.len();
    let twists = velocities(g, model, transforms, velocity);
    let (rates, mut momenta): (Vec<BodyInertia>, Vec<Six>) = (0..n)
        .map(|i| halved_b_terms(g, &inertias[i], twists[i]))
        .unzip();
    // ½ İ^C and ½ h^C: the subtree sums, each in its body's frame.
    let rate_composite = composite_inertias(g, model, transforms, &rates);
    for i in (0..n).rev() {
        if let Some(p) = model.bodies[i].parent {
            let (f, m) = momenta[i];
            let moved = geometry::wrench_to_parent(g, &transforms[i], f, m);
            momenta[p] = add6(g, momenta[p], moved);
        }
    }
    let i_composite = composite_inertias(g, model, transforms, inertias);
    let subspaces: Vec<Vec<Six>> = model
        .bodies
        .iter()
        .map(|b| motion_subspace(g, &b.joint.kind))
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

/// C(q, q̇), an `nv × nv` matrix of nodes.
pub fn coriolis_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Vec<Vec<Node>> {
    let terms = composite_terms(g, model, transforms, inertias, velocity);
    let CompositeTerms {
        inertia_composite: i_composite,
        subspaces,
        axis_rates,
        ..
    } = &terms;
    let mut c = vec![vec![g.zero(); model.nv]; model.nv];
    for (j, body) in model.bodies.iter().enumerate() {
        for (col, &s_j) in subspaces[j].iter().enumerate() {
            let column = body.joint.idx_v + col;
            let (b_s, bt_s) = terms.b_times(g, j, s_j);
            let mut f1 = add6(
                g,
                inertia_times(g, &i_composite[j], axis_rates[j][col]),
                b_s,
            );
            let mut f2 = inertia_times(g, &i_composite[j], s_j);
            let mut f3 = bt_s;
            for (row_in_joint, &s_row) in subspaces[j].iter().enumerate() {
                c[body.joint.idx_v + row_in_joint][column] = dot6(g, s_row, f1);
            }
            let mut i = j;
            while let Some(p) = model.bodies[i].parent {
                let t = &transforms[i];
                f1 = geometry::wrench_to_parent(g, t, f1.0, f1.1);
                f2 = geometry::wrench_to_parent(g, t, f2.0, f2.1);
                f3 = geometry::wrench_to_parent(g, t, f3.0, f3.1);
                i = p;
                let ancestor = &model.bodies[i].joint;
                for (row_in_joint, &s_i) in subspaces[i].iter().enumerate() {
                    let row = ancestor.idx_v + row_in_joint;
                    c[row][column] = dot6(g, s_i, f1);
                    c[column][row] =
                        g.add(dot6(g, f2, axis_rates[i][row_in_joint]), dot6(g, f3, s_i));
                }
            }
        }
    }
    c
}
