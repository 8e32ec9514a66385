//! The columns of ∂τ/∂q̇ and ∂τ/∂q that belong to a free joint F, from the mass matrix and
//! the Coriolis matrix instead of forward-mode differentiation of Newton–Euler.
//!
//! **Velocity.** F's six velocities are its twist ν_F = [v; ω] in its own frame, not
//! derivatives of coordinates, so the Christoffel argument behind ∂(C q̇)/∂q̇ = 2C fails
//! there. With world-frame Jacobians, C(q, x) y = Σ_i J_iᵀ (I_i J̇_i(x) y + B(I_i, J_i x) J_i y)
//! ([`super::coriolis`]) is bilinear, Γ(x, y), and ∂(C q̇)/∂q̇ e_k = Γ(q̇, e_k) + Γ(e_k, q̇).
//! For F's twist axis s_k (e_k in F's frame) the axes of F's subtree turn with it, so
//! J̇_i(e_k) q̇ = s_k × (v_i − v_λ) for a body i below F (λ: F's parent), and
//! J̇_i(q̇) e_k = v_F × s_k; with B(I, s) v − B(I, v) s = −I (s × v) the two orders differ by
//! Σ_i J_iᵀ I_i (s_k × (v_F − v_λ)), which is M(q) times the twist s_k × ν_F in F's
//! columns. So
//!
//! ```text
//! ∂τ/∂q̇ e_k = 2 C(q, q̇) e_k + M_F (e_k × ν_F) + b_k e_k
//! ```
//!
//! M_F: M's six columns of F without armature (armature multiplies q̈, not the
//! velocity-product accelerations), × the spatial cross product of motions, b_k F's damping.
//!
//! **Configuration.** Turning a free joint on the ground by q ⊕ δ, δ = [δv; δω] in its own
//! frame, at fixed ν_F and joint rates, moves nothing the sweeps see but the direction of
//! gravity in its frame, g_F = Eᵀ g: δg_F = −δω × g_F. Gravity enters as the base
//! acceleration [−g_F; 0] (τ is linear in it through M), so, without loads given in world
//! axes (which turn in F's frame with it),
//!
//! ```text
//! ∂τ/∂q along δv = 0,    along δω = e_m:  M_F,lin (e_m × g_F)
//! ```
//!
//! M_F,lin: M's three columns of F's linear velocity, without armature. Both formulas are
//! checked against forward mode in the unit tests and against dual numbers and Pinocchio in
//! the generated-code tests.

use super::geometry::{self, JointTransform};
use super::spatial::{motion_cross, Six};
use crate::model::{Joint, Model};
use crate::sym::{Graph, Node, Vec3};

/// e_k, the k-th unit twist [v; ω].
fn unit_twist(g: &Graph, k: usize) -> Six {
    let mut e = [0.0; 6];
    e[k] = 1.0;
    (
        Vec3::constant(g, [e[0], e[1], e[2]]),
        Vec3::constant(g, [e[3], e[4], e[5]]),
    )
}

/// M_F u for a twist u in F's columns (rigid-body part: `mass_matrix`'s armature taken
/// back off F's diagonal), one entry per row of M.
fn times_free_columns(
    g: &Graph,
    joint: &Joint,
    mass_matrix: &[Vec<Node>],
    u: [Node; 6],
) -> Vec<Node> {
    let k = joint.idx_v;
    let armature = geometry::value(g, &joint.armature);
    mass_matrix
        .iter()
        .enumerate()
        .map(|(row, entries)| {
            let free_columns: Vec<Node> = (k..k + 6)
                .map(|col| {
                    if row == col {
                        g.sub(entries[col], armature)
                    } else {
                        entries[col]
                    }
                })
                .collect();
            // Rows read from the lanes of one pack share its packed sum.
            g.lanewise(&free_columns, |m| {
                m.iter()
                    .zip(u)
                    .fold(g.zero(), |sum, (&entry, ub)| g.add(sum, g.mul(entry, ub)))
            })
        })
        .collect()
}

/// [v; ω] as six nodes.
fn components((l, a): Six) -> [Node; 6] {
    [l.get(0), l.get(1), l.get(2), a.get(0), a.get(1), a.get(2)]
}

/// Column `joint.idx_v + k` (k < 6) of ∂τ/∂q̇ for the free joint `joint`:
/// 2 C e_k + M_F (e_k × ν_F) + b e_k. `coriolis` is C(q, q̇) by rows, `velocity` q̇.
pub fn velocity_column(
    g: &Graph,
    joint: &Joint,
    (mass_matrix, coriolis): (&[Vec<Node>], &[Vec<Node>]),
    velocity: &[Node],
    k: usize,
) -> Vec<Node> {
    let col = joint.idx_v + k;
    let v = |j: usize| velocity[joint.idx_v + j];
    let twist = (Vec3::new(v(0), v(1), v(2)), Vec3::new(v(3), v(4), v(5)));
    let u = components(motion_cross(g, unit_twist(g, k), twist));
    let correction = times_free_columns(g, joint, mass_matrix, u);
    let two = g.constant(2.0);
    let damping = geometry::value(g, &joint.damping);
    coriolis
        .iter()
        .zip(correction)
        .enumerate()
        .map(|(row, (c, m))| {
            let entry = g.lanewise(&[c[col], m], |x| g.add(g.mul(two, x[0]), x[1]));
            if row == col {
                g.add(entry, damping)
            } else {
                entry
            }
        })
        .collect()
}

/// Column `joint.idx_v + k` (k < 6) of ∂τ/∂q (tangent space) for the free joint `joint`
/// on the ground (`transform`: its E and r), in a mechanism without loads in world axes: zero
/// along the translation, M_F,lin (e_m × g_F) along the rotation e_m, m = k − 3.
pub fn configuration_column(
    g: &Graph,
    model: &Model,
    (joint, transform): (&Joint, &JointTransform),
    mass_matrix: &[Vec<Node>],
    k: usize,
) -> Vec<Node> {
    if k < 3 {
        return vec![g.zero(); model.nv];
    }
    let gravity_in_joint =
        geometry::to_body(g, transform, Vec3::constant(g, model.gravity_in_world));
    let (_, axis) = unit_twist(g, k);
    let linear = axis.cross(g, gravity_in_joint);
    let zero = g.zero();
    let u = [
        linear.get(0),
        linear.get(1),
        linear.get(2),
        zero,
        zero,
        zero,
    ];
    times_free_columns(g, joint, mass_matrix, u)
}
