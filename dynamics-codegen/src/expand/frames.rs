//! Operational frames: poses, Jacobians, velocities and J̇ q̇ of frames rigidly attached to
//! the bodies (a tool centre point, a foot, a body welded through a fixed joint).
//!
//! A frame f on body b sits at r_f with rotation R_f in b's frame. With b's pose (R_b, p_b)
//! from [`kinematics::body_poses`]:
//!
//! ```text
//! R = R_b R_f,    p = p_b + R_b r_f                       (x_world = R x_frame + p)
//! ```
//!
//! Its Jacobian, world-aligned at its origin (Pinocchio's `LOCAL_WORLD_ALIGNED`), is the
//! Jacobian of the point p moving with b ([`kinematics::point_jacobian_columns`]): column j
//! is [a × (p − p_j); a] for a revolute joint j on the path to the root, [a; 0] for a
//! prismatic one, and zero (not computed) for any other joint. In the frame's own axes
//! (`LOCAL`) both blocks are turned by Rᵀ. The velocity is J q̇ = [v_P + ω × ρ; ω] from its
//! body's ([`kinematics::body_velocities`]), and the classical
//! acceleration of the frame's origin at q̈ = 0 follows from its body's (the rigid-body
//! acceleration field, with ρ = R_b r_f the lever in world axes):
//!
//! ```text
//! a_f = a_P + α × ρ + ω × (ω × ρ),    α_f = α          (= J̇ q̇ at q̈ = 0)
//! ```
//!
//! A frame on the ground has the constant pose (R_f, r_f) and zero rates.

use super::geometry::{vector, JointTransform};
use super::kinematics::{self, MotionInWorld, Pose};
use crate::model::{Frame, Model};
use crate::sym::{Graph, Mat3, Node, Vec3};

/// The pose of one frame in the world, from the poses of the bodies.
fn frame_pose(g: &Graph, body_poses: &[Pose], frame: &Frame) -> Pose {
    let rotation = Mat3::constant(g, frame.rotation_in_body);
    let origin = vector(g, &frame.origin_in_body);
    match frame.body {
        None => Pose {
            rotation_in_world: rotation,
            origin_in_world: origin,
        },
        Some(b) => {
            let body = &body_poses[b];
            Pose {
                rotation_in_world: body.rotation_in_world.mul(g, rotation),
                origin_in_world: body
                    .origin_in_world
                    .add(g, body.rotation_in_world.mul_vec(g, origin)),
            }
        }
    }
}

/// ρ = R_b r_f: the frame's origin relative to its body's, in world axes.
fn lever_in_world(g: &Graph, body: &Pose, frame: &Frame) -> Vec3 {
    body.rotation_in_world
        .mul_vec(g, vector(g, &frame.origin_in_body))
}

/// The pose of every frame of the model in the world.
pub fn frame_poses(g: &Graph, model: &Model, transforms: &[JointTransform]) -> Vec<Pose> {
    let poses = kinematics::body_poses(g, model, transforms);
    model
        .frames
        .iter()
        .map(|frame| frame_pose(g, &poses, frame))
        .collect()
}

/// Which axes a frame Jacobian is given in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JacobianAxes {
    /// The world's axes at the frame's origin (Pinocchio's `LOCAL_WORLD_ALIGNED`).
    WorldAligned,
    /// The frame's own axes (Pinocchio's `LOCAL`).
    Local,
}

/// Every frame's Jacobian, 6 rows [linear; angular] of nv entries, in `axes`.
pub fn frame_jacobians(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    axes: JacobianAxes,
) -> Vec<Vec<Vec<Node>>> {
    let poses = kinematics::body_poses(g, model, transforms);
    model
        .frames
        .iter()
        .map(|frame| {
            let pose = frame_pose(g, &poses, frame);
            let mut columns = kinematics::point_jacobian_columns(
                g,
                model,
                &poses,
                frame.body,
                pose.origin_in_world,
            );
            if axes == JacobianAxes::Local {
                let to_frame = pose.rotation_in_world.transpose();
                for (linear, angular) in columns.iter_mut().flatten() {
                    *linear = to_frame.mul_vec(g, *linear);
                    *angular = to_frame.mul_vec(g, *angular);
                }
            }
            kinematics::jacobian_rows(g, &columns)
        })
        .collect()
}

/// Every frame's velocity [v; ω] in world axes at its origin: its body's, carried by the
/// velocity field, v = v_P + ω × ρ (= J q̇ with J of [`frame_jacobians`]).
pub fn frame_velocities(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<(Vec3, Vec3)> {
    let velocities = kinematics::body_velocities(g, model, transforms, velocity);
    let poses = kinematics::body_poses(g, model, transforms);
    model
        .frames
        .iter()
        .map(|frame| match frame.body {
            None => (Vec3::zero(g), Vec3::zero(g)),
            Some(b) => {
                let (linear, angular) = velocities[b];
                let lever = lever_in_world(g, &poses[b], frame);
                (linear.add(g, angular.cross(g, lever)), angular)
            }
        })
        .collect()
}

/// Every frame's classical acceleration [a_f; α] in world axes at q̈ = 0: J̇ q̇.
pub fn frame_acceleration_biases(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<(Vec3, Vec3)> {
    let zero = vec![g.zero(); model.nv];
    let motions = kinematics::motions_in_world(g, model, transforms, velocity, &zero);
    let poses = kinematics::body_poses(g, model, transforms);
    model
        .frames
        .iter()
        .map(|frame| match frame.body {
            None => (Vec3::zero(g), Vec3::zero(g)),
            Some(b) => {
                let MotionInWorld {
                    accel,
                    alpha,
                    omega,
                } = motions[b];
                let lever = lever_in_world(g, &poses[b], frame);
                let accel = accel
                    .add(g, alpha.cross(g, lever))
                    .add(g, omega.cross(g, omega.cross(g, lever)));
                (accel, alpha)
            }
        })
        .collect()
}
