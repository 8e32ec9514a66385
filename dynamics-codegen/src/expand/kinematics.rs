//! Kinematics: every body's pose in the world, the centre of mass and its Jacobian.
//!
//! Forward kinematics composes the joint transforms from the root (R: body → world
//! rotation, p: the body origin P in the world; E, r the joint transform of
//! [`super::geometry`]):
//!
//! ```text
//! R_i = R_λ E_i,    p_i = p_λ + R_λ r_i        (R = 1, p = 0 for the ground)
//! ```
//!
//! The centre of mass, with h_i = m_i c_i the first moment of body i about P_i in its frame,
//! is c = Σ (m_i p_i + R_i h_i) / M, M = Σ m_i. Its Jacobian J_c (3 × nv, ċ = J_c q̇)
//! gathers, joint by joint, the motion of the subtree the joint moves: with M_j and
//! S_j = Σ (m_i p_i + R_i h_i) the mass and the first moment about the world origin of the
//! bodies at and below body j,
//!
//! ```text
//! revolute about s (a = R_j s in the world):  J_c[:, j] = a × (S_j − M_j p_j) / M
//! prismatic along s:                            J_c[:, j] = a M_j / M
//! free, v = [v_P; ω] in the body frame:        J_c[:, j + k] = R_j e_k M_j / M,
//!                                               J_c[:, j + 3 + k] = (R_j e_k) × (S_j − M_j p_j) / M
//! ```
//!
//! (a point x moved by joint j at unit rate moves at a × (x − p_j), or a, or R_j e_k).
//! The inertias are the declared ones: the centre of mass is not a function of the
//! Lagrangian alone, so base parameters do not serve.
//!
//! The Jacobian of body i's frame, 6 × nv, rows [linear; angular], with the origin at P_i
//! and the world's axes (Pinocchio's `LOCAL_WORLD_ALIGNED`): [v_P; ω] in world coordinates
//! is J_i q̇. Its column for a joint j on the path from the root to i is
//!
//! ```text
//! revolute:   [a × (p_i − p_j); a]        prismatic: [a; 0]
//! free:       [R_j e_k; 0] (k = 0, 1, 2),  [(R_j e_k) × (p_i − p_j); R_j e_k]
//! ```
//!
//! and zero for any other joint (it does not move body i).
//!
//! The centroidal momentum matrix A_G (6 × nv, rows [linear; angular], h_G = A_G q̇: the
//! linear momentum and the angular momentum about the centre of mass c, world axes). The
//! subtree that joint j carries, with its composite inertia (m, h, I_P) about P_j in body
//! j's frame ([`crba::slot_composite_inertias`]), moving along the joint's motion subspace s at
//! unit rate, has the momentum [F; M_P] = I^c_j s in that frame (F = m v + ω × h,
//! M_P = h × v + I_P ω); A_G's column is that momentum in the world about c:
//!
//! ```text
//! l = R_j F,    k_c = R_j M_P + (p_j − c) × l
//! ```
//!
//! (for a revolute joint s picks a column of the composite inertia: no products).

use super::crba;
use super::geometry::{BodyInertia, JointTransform};
use super::rnea::{self, SweepInputs};
use super::slots::{SlotParent, Slots};
use super::spatial::{add6, inertia_times, motion_cross, motion_subspace, scale6, Six};
use crate::model::{JointKind, Model};
use crate::sym::{Graph, Mat3, Node, Vec3};

/// The pose of a body frame in the world.
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    /// R: rotation from body to world coordinates.
    pub rotation_in_world: Mat3,
    /// p: the body origin P in the world frame.
    pub origin_in_world: Vec3,
}

/// The pose of every body in the world, parents first.
pub fn body_poses(g: &Graph, model: &Model, transforms: &[JointTransform]) -> Vec<Pose> {
    slot_poses(g, &Slots::each_body(model), transforms)
}

/// Each slot's pose in the world, parents first: its parent's (packed the same way, or one
/// body's, broadcast to the lanes) composed with the slot's own transform
/// (`slot_transforms`, one a slot).
fn slot_poses(g: &Graph, slots: &Slots, slot_transforms: &[JointTransform]) -> Vec<Pose> {
    let mut poses: Vec<Pose> = Vec::with_capacity(slots.slots.len());
    for (s, t) in slot_transforms.iter().enumerate() {
        poses.push(match slots.parent_slot(s).map(|p| poses[p]) {
            None => Pose {
                rotation_in_world: t.rotation_to_parent,
                origin_in_world: t.origin_in_parent,
            },
            Some(parent) => Pose {
                rotation_in_world: parent.rotation_in_world.mul(g, t.rotation_to_parent),
                origin_in_world: parent
                    .origin_in_world
                    .add(g, parent.rotation_in_world.mul_vec(g, t.origin_in_parent)),
            },
        });
    }
    poses
}

/// Every body's joint frame (after the motion, as declared: Pinocchio's `oMi`) in the
/// world: the body's pose, turned back where the tree turned the body's frame about its
/// joint axis (R_joint = R_body · `joint_frame_in_body`; the origin is the same).
pub fn joint_frame_poses(g: &Graph, model: &Model, transforms: &[JointTransform]) -> Vec<Pose> {
    body_poses(g, model, transforms)
        .into_iter()
        .zip(&model.bodies)
        .map(|(pose, body)| match body.joint.joint_frame_in_body {
            Some(turn) => Pose {
                rotation_in_world: pose.rotation_in_world.mul(g, Mat3::constant(g, turn)),
                origin_in_world: pose.origin_in_world,
            },
            None => pose,
        })
        .collect()
}

/// m p + R h: a body's first moment about the world origin, in world coordinates.
fn first_moment_in_world(g: &Graph, pose: &Pose, inertia: &BodyInertia) -> Vec3 {
    pose.origin_in_world
        .scale(g, inertia.mass)
        .add(g, pose.rotation_in_world.mul_vec(g, inertia.first_moment))
}

/// Each body's value replaced by the sum over its subtree, from the leaves to the root.
fn add_to_parents<V: Copy>(model: &Model, values: &mut [V], add: impl Fn(V, V) -> V) {
    for i in (0..values.len()).rev() {
        if let Some(p) = model.bodies[i].parent {
            values[p] = add(values[p], values[i]);
        }
    }
}

/// M_j and S_j of every subtree: its mass and its first moment about the world origin.
fn subtree_masses_and_moments(
    g: &Graph,
    model: &Model,
    poses: &[Pose],
    inertias: &[BodyInertia],
) -> (Vec<Node>, Vec<Vec3>) {
    let mut mass: Vec<Node> = inertias.iter().map(|b| b.mass).collect();
    let mut moment: Vec<Vec3> = poses
        .iter()
        .zip(inertias)
        .map(|(pose, inertia)| first_moment_in_world(g, pose, inertia))
        .collect();
    add_to_parents(model, &mut mass, |a, b| g.add(a, b));
    add_to_parents(model, &mut moment, |a, b| a.add(g, b));
    (mass, moment)
}

/// A joint axis given in the joint (= body) frame, in world coordinates.
fn axis_in_world(g: &Graph, pose: &Pose, axis_in_body: [f64; 3]) -> Vec3 {
    pose.rotation_in_world
        .mul_vec(g, Vec3::constant(g, axis_in_body))
}

/// 1 / M, the reciprocal of the total mass (a number when the masses are).
fn reciprocal_total_mass(g: &Graph, inertias: &[BodyInertia]) -> Node {
    let masses: Vec<Node> = inertias.iter().map(|b| b.mass).collect();
    g.div(g.one(), g.sum(&masses))
}

/// The centre of mass c in the world frame.
pub fn center_of_mass(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec3 {
    let poses = body_poses(g, model, transforms);
    let moments: Vec<Vec3> = poses
        .iter()
        .zip(inertias)
        .map(|(pose, inertia)| first_moment_in_world(g, pose, inertia))
        .collect();
    let total = (0..3).map(|k| g.sum(&moments.iter().map(|m| m.get(k)).collect::<Vec<_>>()));
    let total: Vec<Node> = total.collect();
    Vec3::new(total[0], total[1], total[2]).scale(g, reciprocal_total_mass(g, inertias))
}

/// J_c, 3 rows of nv entries: ċ = J_c q̇ in the world frame.
pub fn center_of_mass_jacobian(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    let poses = body_poses(g, model, transforms);
    let (mass, moment) = subtree_masses_and_moments(g, model, &poses, inertias);
    let inverse_total = reciprocal_total_mass(g, inertias);
    let mut columns: Vec<Vec3> = vec![Vec3::zero(g); model.nv];
    for (j, body) in model.bodies.iter().enumerate() {
        let pose = &poses[j];
        // S_j − M_j p_j: the subtree's first moment about the joint's origin.
        let about_joint = moment[j].sub(g, pose.origin_in_world.scale(g, mass[j]));
        let k = body.joint.idx_v;
        match body.joint.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                columns[k] = axis.cross(g, about_joint);
            }
            JointKind::Prismatic { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                columns[k] = axis.scale(g, mass[j]);
            }
            JointKind::Free => {
                for e in 0..3 {
                    let axis = pose.rotation_in_world.col(e);
                    columns[k + e] = axis.scale(g, mass[j]);
                    columns[k + 3 + e] = axis.cross(g, about_joint);
                }
            }
        }
    }
    (0..3)
        .map(|row| {
            columns
                .iter()
                .map(|c| g.mul(c.get(row), inverse_total))
                .collect()
        })
        .collect()
}

/// The columns of the Jacobian of a point moving with `body` (`None`: the ground), at
/// `point` in the world, world-aligned: column k is [linear; angular] for velocity
/// coordinate k, `None` for a joint that does not move the body (a zero column).
pub fn point_jacobian_columns(
    g: &Graph,
    model: &Model,
    poses: &[Pose],
    body: Option<usize>,
    point: Vec3,
) -> Vec<Option<(Vec3, Vec3)>> {
    let mut columns = vec![None; model.nv];
    let mut on_path = body;
    while let Some(j) = on_path {
        let joint = &model.bodies[j].joint;
        let pose = &poses[j];
        let lever = point.sub(g, pose.origin_in_world);
        let k = joint.idx_v;
        match joint.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                columns[k] = Some((axis.cross(g, lever), axis));
            }
            JointKind::Prismatic { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                columns[k] = Some((axis, Vec3::zero(g)));
            }
            JointKind::Free => {
                for e in 0..3 {
                    let axis = pose.rotation_in_world.col(e);
                    columns[k + e] = Some((axis, Vec3::zero(g)));
                    columns[k + 3 + e] = Some((axis.cross(g, lever), axis));
                }
            }
        }
        on_path = model.bodies[j].parent;
    }
    columns
}

/// Jacobian columns as 6 rows [linear; angular] of nv entries (zero where `None`).
pub fn jacobian_rows(g: &Graph, columns: &[Option<(Vec3, Vec3)>]) -> Vec<Vec<Node>> {
    (0..6)
        .map(|row| {
            columns
                .iter()
                .map(|column| match column {
                    Some((linear, _)) if row < 3 => linear.get(row),
                    Some((_, angular)) => angular.get(row - 3),
                    None => g.zero(),
                })
                .collect()
        })
        .collect()
}

/// The Jacobian of every body's frame in the world-aligned frame at its origin: for body
/// i, 6 rows [linear; angular] of nv entries.
pub fn body_jacobians(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
) -> Vec<Vec<Vec<Node>>> {
    let poses = body_poses(g, model, transforms);
    (0..model.bodies.len())
        .map(|i| {
            let columns =
                point_jacobian_columns(g, model, &poses, Some(i), poses[i].origin_in_world);
            jacobian_rows(g, &columns)
        })
        .collect()
}

/// The joint Jacobians in Pinocchio's WORLD convention, all in one 6 × nv matrix (its
/// `data.J` after `computeJointJacobians`): column k is the spatial motion that velocity
/// coordinate k gives its joint's body at unit rate, [v_O; ω] with v_O the velocity of the
/// body point passing through the world origin O, world axes (joint j's body at (R_j, p_j)):
///
/// ```text
/// revolute about a = R_j s:  [p_j × a; a]        prismatic along a:  [a; 0]
/// free (v in the body frame): [R_j e_k; 0],  [p_j × R_j e_k; R_j e_k]
/// ```
///
/// Body i's WORLD Jacobian is these columns over the joints from the root to i (zero
/// elsewhere); its LOCAL_WORLD_ALIGNED one shifts each to P_i: v_P = v_O + ω × p_i.
pub fn world_jacobian_columns(g: &Graph, model: &Model, poses: &[Pose]) -> Vec<Six> {
    let mut columns: Vec<Six> = vec![(Vec3::zero(g), Vec3::zero(g)); model.nv];
    for (j, body) in model.bodies.iter().enumerate() {
        let pose = &poses[j];
        let about_origin = |axis: Vec3| (pose.origin_in_world.cross(g, axis), axis);
        let k = body.joint.idx_v;
        match body.joint.kind {
            JointKind::Revolute { axis_in_body } => {
                columns[k] = about_origin(axis_in_world(g, pose, axis_in_body));
            }
            JointKind::Prismatic { axis_in_body } => {
                columns[k] = (axis_in_world(g, pose, axis_in_body), Vec3::zero(g));
            }
            JointKind::Free => {
                for e in 0..3 {
                    let axis = pose.rotation_in_world.col(e);
                    columns[k + e] = (axis, Vec3::zero(g));
                    columns[k + 3 + e] = about_origin(axis);
                }
            }
        }
    }
    columns
}

/// J̇ of [`world_jacobian_columns`] (Pinocchio's `data.dJ` after
/// `computeJointJacobiansTimeVariation`). A column is body j's frame carrying a constant
/// motion s, X_j s, so its rate is V_j × X_j s with V_j = Σ (columns of the joints from the
/// root to j) q̇ the body's spatial velocity in the world at O (motion cross product
/// [v; ω] × [u; a] = [ω × u + v × a; ω × a]). For a one-coordinate joint V_j may be taken
/// as the parent's, since s × s = 0.
pub fn world_jacobian_rates(
    g: &Graph,
    model: &Model,
    columns: &[Six],
    velocity: &[Node],
) -> Vec<Six> {
    let zero: Six = (Vec3::zero(g), Vec3::zero(g));
    let mut body_velocities: Vec<Six> = Vec::with_capacity(model.bodies.len());
    let mut rates: Vec<Six> = vec![zero; model.nv];
    for body in &model.bodies {
        let parent = body.parent.map_or(zero, |p| body_velocities[p]);
        let dofs = body.joint.idx_v..body.joint.idx_v + body.joint.kind.dofs();
        let own = dofs.clone().fold(parent, |sum, k| {
            add6(g, sum, scale6(g, columns[k], velocity[k]))
        });
        let carrier = if dofs.len() == 1 { parent } else { own };
        for k in dofs {
            rates[k] = motion_cross(g, carrier, columns[k]);
        }
        body_velocities.push(own);
    }
    rates
}

/// A_G, the centroidal momentum matrix: 6 rows [linear; angular about the centre of mass]
/// of nv entries, world axes. Computed over [`Slots`]: isomorphic limbs side by side in the
/// lanes of packed values (their poses, composite inertias and columns), as the packed mass
/// matrix is ([`crba::mass_matrix_packed`]).
pub fn centroidal_momentum_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    let slots = Slots::of(model);
    let slot_transforms = slots.transforms(g, transforms);
    let composite =
        crba::slot_composite_inertias(g, &slots, &slot_transforms, &slots.inertias(g, inertias));
    let poses = slot_poses(g, &slots, &slot_transforms);
    // c from the roots' composite first moments: m p + R h of each root's subtree.
    let mut moment = Vec3::zero(g);
    for (s, slot) in slots.slots.iter().enumerate() {
        if slot.parent == SlotParent::Ground {
            let root = first_moment_in_world(g, &poses[s], &composite[s]);
            for lane in 0..slot.lanes.len() {
                moment = moment.add(g, root.lane(g, lane));
            }
        }
    }
    let centre = moment.scale(g, reciprocal_total_mass(g, inertias));
    let mut columns: Vec<(Vec3, Vec3)> = vec![(Vec3::zero(g), Vec3::zero(g)); model.nv];
    for (s, slot) in slots.slots.iter().enumerate() {
        let pose = &poses[s];
        let lever = pose.origin_in_world.sub(g, centre);
        let kind = &model.bodies[slot.lanes[0]].joint.kind;
        for (k, sv) in motion_subspace(g, kind).into_iter().enumerate() {
            // The subtree's momentum [F; M_P] in the body's frame at P, turned into the world
            // and taken about c.
            let (force, moment) = inertia_times(g, &composite[s], sv);
            let linear = pose.rotation_in_world.mul_vec(g, force);
            let angular = pose
                .rotation_in_world
                .mul_vec(g, moment)
                .add(g, lever.cross(g, linear));
            for (lane, &b) in slot.lanes.iter().enumerate() {
                columns[model.bodies[b].joint.idx_v + k] =
                    (linear.lane(g, lane), angular.lane(g, lane));
            }
        }
    }
    (0..6)
        .map(|row| {
            columns
                .iter()
                .map(|(l, a)| if row < 3 { l.get(row) } else { a.get(row - 3) })
                .collect()
        })
        .collect()
}

/// Every body's velocity [v_P; ω] in world axes at its origin, by the rigid-body velocity
/// field from the root: ω_i = ω_λ + a q̇ (revolute about a = R_i s), v_i = v_λ + ω_λ × (p_i −
/// p_λ) (+ a q̇ for a prismatic joint); a free base's v = [v_P; ω] is in its own frame,
/// turned by R. (The same as J q̇ with the Jacobians of [`body_jacobians`], in O(n).)
pub fn body_velocities(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<(Vec3, Vec3)> {
    let poses = body_poses(g, model, transforms);
    let mut out: Vec<(Vec3, Vec3)> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let pose = &poses[i];
        let (mut linear, mut angular) = match body.parent {
            None => (Vec3::zero(g), Vec3::zero(g)),
            Some(p) => {
                let (v_parent, omega_parent) = out[p];
                let lever = pose.origin_in_world.sub(g, poses[p].origin_in_world);
                (v_parent.add(g, omega_parent.cross(g, lever)), omega_parent)
            }
        };
        let k = body.joint.idx_v;
        match body.joint.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                angular = angular.add(g, axis.scale(g, velocity[k]));
            }
            JointKind::Prismatic { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                linear = linear.add(g, axis.scale(g, velocity[k]));
            }
            JointKind::Free => {
                let own = |offset: usize| {
                    Vec3::new(
                        velocity[k + offset],
                        velocity[k + offset + 1],
                        velocity[k + offset + 2],
                    )
                };
                linear = linear.add(g, pose.rotation_in_world.mul_vec(g, own(0)));
                angular = angular.add(g, pose.rotation_in_world.mul_vec(g, own(3)));
            }
        }
        out.push((linear, angular));
    }
    out
}

/// A body's motion in world axes: the classical acceleration a_P of its origin, α and ω.
#[derive(Clone, Copy, Debug)]
pub struct MotionInWorld {
    /// a_P, the classical acceleration of the body origin.
    pub accel: Vec3,
    /// α, the angular acceleration.
    pub alpha: Vec3,
    /// ω, the angular velocity.
    pub omega: Vec3,
}

/// Every body's classical acceleration [a_P; α] and ω in world axes at velocity `velocity`
/// and acceleration `acceleration`, without gravity, by the rigid-body acceleration field
/// from the root, in world axes (a = R_i s the joint axis, r = p_i − p_λ):
///
/// ```text
/// revolute:   ω_i = ω_λ + a q̇,   α_i = α_λ + ω_λ × a q̇ + a q̈,   a_i = a_λ + α_λ × r + ω_λ × (ω_λ × r)
/// prismatic:  ω_i = ω_λ,         α_i = α_λ,   a_i = a_λ + α_λ × r + ω_λ × (ω_λ × r) + 2 ω_λ × a q̇ + a q̈
/// free:       ω = R ω_b,   α = R ω̇_b,   a_P = R (v̇_b + ω_b × v_b)   (v = [v_b; ω_b] in the body frame)
/// ```
///
/// At q̈ = 0, [a_P; α] is J̇ q̇.
pub fn motions_in_world(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
    acceleration: &[Node],
) -> Vec<MotionInWorld> {
    let poses = body_poses(g, model, transforms);
    let mut out: Vec<MotionInWorld> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let pose = &poses[i];
        let zero = Vec3::zero(g);
        let parent = body.parent.map(|p| (out[p], poses[p].origin_in_world));
        // The motion of the parent's point that coincides with P_i.
        let (mut accel, mut alpha, mut omega) = match parent {
            None => (zero, zero, zero),
            Some((m, origin)) => {
                let r = pose.origin_in_world.sub(g, origin);
                let accel = m
                    .accel
                    .add(g, m.alpha.cross(g, r))
                    .add(g, m.omega.cross(g, m.omega.cross(g, r)));
                (accel, m.alpha, m.omega)
            }
        };
        let k = body.joint.idx_v;
        match body.joint.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                let spin = axis.scale(g, velocity[k]);
                alpha = alpha
                    .add(g, omega.cross(g, spin))
                    .add(g, axis.scale(g, acceleration[k]));
                omega = omega.add(g, spin);
            }
            JointKind::Prismatic { axis_in_body } => {
                let axis = axis_in_world(g, pose, axis_in_body);
                let slide = axis.scale(g, velocity[k]);
                let coriolis = omega.cross(g, slide);
                accel = accel
                    .add(g, coriolis.add(g, coriolis))
                    .add(g, axis.scale(g, acceleration[k]));
            }
            JointKind::Free => {
                let own = |x: &[Node], offset: usize| {
                    Vec3::new(x[k + offset], x[k + offset + 1], x[k + offset + 2])
                };
                let (v_body, omega_body) = (own(velocity, 0), own(velocity, 3));
                let linear = own(acceleration, 0).add(g, omega_body.cross(g, v_body));
                accel = accel.add(g, pose.rotation_in_world.mul_vec(g, linear));
                alpha = alpha.add(g, pose.rotation_in_world.mul_vec(g, own(acceleration, 3)));
                omega = omega.add(g, pose.rotation_in_world.mul_vec(g, omega_body));
            }
        }
        out.push(MotionInWorld {
            accel,
            alpha,
            omega,
        });
    }
    out
}

/// Ȧ_G q̇, the rate of the centroidal momentum h_G = A_G q̇ at q̈ = 0 (world axes, angular
/// part about the moving centre of mass c). Each body's rate of momentum about its origin P
/// is the textbook's F = m a_P + U h, M_P = h × a_P + I_P α + ω × I_P ω
/// ([`rnea::body_wrench`]) at q̈ = 0 without gravity; summed in the world about its origin,
/// ḣ_O = Σ [R F; R M_P + p × R F], and shifted to c: ḣ_G = [ḣ_lin; ḣ_O,ang − c × ḣ_lin]
/// (the term ċ × M ċ of moving the reference point vanishes).
pub fn centroidal_bias(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Vec<Node> {
    let zero = vec![g.zero(); model.nv];
    let inputs = SweepInputs {
        velocity,
        acceleration: &zero,
        gravity: false,
        loads: false,
    };
    let motions = rnea::motions(g, model, transforms, &inputs);
    let poses = body_poses(g, model, transforms);
    let mut linear = Vec3::zero(g);
    let mut angular = Vec3::zero(g);
    for ((motion, pose), inertia) in motions.iter().zip(&poses).zip(inertias) {
        let (force, moment) = rnea::body_wrench(g, motion, inertia);
        let force_in_world = pose.rotation_in_world.mul_vec(g, force);
        linear = linear.add(g, force_in_world);
        angular = angular.add(
            g,
            pose.rotation_in_world
                .mul_vec(g, moment)
                .add(g, pose.origin_in_world.cross(g, force_in_world)),
        );
    }
    let centre = center_of_mass(g, model, transforms, inertias);
    let angular = angular.sub(g, centre.cross(g, linear));
    linear.0.iter().chain(&angular.0).copied().collect()
}
