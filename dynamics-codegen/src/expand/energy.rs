//! Kinetic and potential energy.
//!
//! Velocity sweep (body frame): ω_i = Eᵀω_λ + s q̇ (revolute), v_i = Eᵀ(v_λ + ω_λ × r)
//! (+ s q̇ for a prismatic joint); for a free joint ω = v_ang, v = v_lin. Then, about P with
//! h = m c and I_P = I_G − m ĉ²:
//!
//! ```text
//! T = ½ Σ_i (m v·v + 2 v·(ω × h) + ω·I_P ω) + ½ Σ_k armature_k q̇_k²
//! V = −Σ_i g·(m p_i + R_i h) = −Σ_i (m (g·p_i) + g_i·h)
//! ```
//!
//! with g_i = R_iᵀ g the gravity in body i's frame (g_i = Eᵀ g_λ) and g·p_i = g·p_λ + g_λ·r
//! (zero potential at the world origin, as Pinocchio).

use super::geometry::{self, BodyInertia, JointTransform};
use crate::model::{JointKind, Model};
use crate::sym::{Graph, Node, Vec3};

/// T(q, q̇).
pub fn kinetic(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Node {
    let mut twists: Vec<(Vec3, Vec3)> = Vec::with_capacity(model.bodies.len());
    let mut twice = g.zero();
    for (i, body) in model.bodies.iter().enumerate() {
        let (omega_parent, v_parent) = body
            .parent
            .map_or((Vec3::zero(g), Vec3::zero(g)), |p| twists[p]);
        let t = &transforms[i];
        let k = body.joint.idx_v;
        let omega_in = geometry::to_body(g, t, omega_parent);
        let v_in = geometry::to_body(
            g,
            t,
            v_parent.add(g, omega_parent.cross(g, t.origin_in_parent)),
        );
        let (omega, v) = match body.joint.kind {
            JointKind::Revolute { axis_in_body } => (
                omega_in.add(g, Vec3::constant(g, axis_in_body).scale(g, velocity[k])),
                v_in,
            ),
            JointKind::Prismatic { axis_in_body } => (
                omega_in,
                v_in.add(g, Vec3::constant(g, axis_in_body).scale(g, velocity[k])),
            ),
            JointKind::Free => (
                omega_in.add(
                    g,
                    Vec3::new(velocity[k + 3], velocity[k + 4], velocity[k + 5]),
                ),
                v_in.add(g, Vec3::new(velocity[k], velocity[k + 1], velocity[k + 2])),
            ),
        };
        twists.push((omega, v));
        let inertia = &inertias[i];
        let linear = g.mul(inertia.mass, v.dot(g, v));
        let coupling = g.mul(
            g.constant(2.0),
            v.dot(g, omega.cross(g, inertia.first_moment)),
        );
        let angular = omega.dot(g, inertia.inertia_about_origin.mul_vec(g, omega));
        twice = g.add(twice, g.add(linear, g.add(coupling, angular)));
        let armature = geometry::value(g, &body.joint.armature);
        for j in k..k + body.joint.kind.dofs() {
            twice = g.add(twice, g.mul(armature, g.mul(velocity[j], velocity[j])));
        }
    }
    g.mul(g.constant(0.5), twice)
}

/// V(q).
pub fn potential(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Node {
    let gravity = Vec3::constant(g, model.gravity_in_world);
    // Per body: gravity in its frame, and g·p (p = its origin in the world).
    let mut frames: Vec<(Vec3, Node)> = Vec::with_capacity(model.bodies.len());
    let mut total = g.zero();
    for (i, body) in model.bodies.iter().enumerate() {
        let (g_parent, height_parent) = body.parent.map_or((gravity, g.zero()), |p| frames[p]);
        let t = &transforms[i];
        let g_body = geometry::to_body(g, t, g_parent);
        let height = g.add(height_parent, g_parent.dot(g, t.origin_in_parent));
        frames.push((g_body, height));
        let inertia = &inertias[i];
        let work = g.add(
            g.mul(inertia.mass, height),
            g_body.dot(g, inertia.first_moment),
        );
        total = g.sub(total, work);
    }
    total
}
