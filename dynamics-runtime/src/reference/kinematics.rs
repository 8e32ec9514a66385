//! Forward kinematics: body placements and velocities, each in the frame its name says.
//!
//! Placement of body i in its parent λ (joint placement (R_J, p_J), joint coordinate q):
//! - revolute about the unit axis s: `R = R_J Rot(s, q)`, `p = p_J`, with Rodrigues'
//!   formula `Rot(s, q) = cos q 1 + sin q ŝ + (1 − cos q) s sᵀ`;
//! - prismatic along s: `R = R_J`, `p = p_J + R_J s q`;
//! - free flyer, `q = [x, y, z, qx, qy, qz, qw]`: `R = R_J R(quat)`, `p = p_J + R_J [x, y, z]`
//!   (the quaternion must be unit, as in Pinocchio; it is not normalized here).
//!
//! Pose in the world: `R_0i = R_0λ R`, `p_0i = p_0λ + R_0λ p`.
//!
//! Velocities in the body frame (the textbook's rigid-body velocity field, v_Q = v_P + ω × PQ):
//! `ω_i = Rᵀ ω_λ + s q̇` (revolute), `v_P,i = Rᵀ (v_P,λ + ω_λ × p) + s q̇` (prismatic); a free
//! flyer's v = [v_P; ω] is already in the body frame and its parent is the ground.
//!
//! Accelerations in the body frame (the rigid-body acceleration field of the parent at P_i,
//! a_Q = a_P + α × PQ + ω × (ω × PQ), plus the joint's relative motion), with the ground
//! accelerating at a_0 (−g for the Newton–Euler equations, 0 for kinematics):
//!
//! ```text
//!   α_i  = Rᵀ α_λ (+ ω_i × s q̇ + s q̈, revolute)
//!   a_Pi = Rᵀ (a_Pλ + α_λ × p + ω_λ × (ω_λ × p)) (+ 2 ω_i × s q̇ + s q̈, prismatic)
//!   free flyer (parent = ground): α = ω̇_v, a_P = Rᵀ a_0 + v̇_lin + ω × v_lin
//! ```

use super::{BodyConstants, Motion, Pose, Reference};
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::{Matrix3, Vector3};

/// Rotation by `angle` about the unit `axis` (Rodrigues).
fn axis_angle<T: Scalar>(axis: &Vector3<T>, angle: T) -> Matrix3<T> {
    let (sin, cos) = angle.sin_cos();
    Matrix3::identity() * cos
        + super::spatial::skew(axis) * sin
        + axis * axis.transpose() * (T::one() - cos)
}

/// Rotation body → parent of a unit quaternion (x, y, z, w), scalar last.
pub(crate) fn quaternion_rotation<T: Scalar>(x: T, y: T, z: T, w: T) -> Matrix3<T> {
    let rows = crate::dynamics::quaternion_rotation_rows(x, y, z, w);
    Matrix3::from_fn(|r, c| rows[r][c])
}

/// Pose (rotation body → parent, origin in parent) of a body at configuration q.
pub(crate) fn pose_in_parent<T: Scalar>(
    body: &BodyConstants<T>,
    q: &[T],
) -> (Matrix3<T>, Vector3<T>) {
    let r_joint = &body.rotation_joint_in_parent;
    let p_joint = &body.origin_joint_in_parent;
    let qi = &q[body.idx_q..body.idx_q + body.motion_nq()];
    match &body.motion {
        Motion::Revolute { axis } => (r_joint * axis_angle(axis, qi[0]), *p_joint),
        Motion::Prismatic { axis } => (*r_joint, p_joint + r_joint * axis * qi[0]),
        Motion::FreeFlyer => (
            r_joint * quaternion_rotation(qi[3], qi[4], qi[5], qi[6]),
            p_joint + r_joint * Vector3::new(qi[0], qi[1], qi[2]),
        ),
    }
}

impl<T: Scalar> BodyConstants<T> {
    /// Number of configuration coordinates of the joint.
    pub(crate) fn motion_nq(&self) -> usize {
        match self.motion {
            Motion::FreeFlyer => 7,
            _ => 1,
        }
    }
}

/// Component `k` of an optional per-coordinate vector (`None` = zero).
pub(super) fn coordinate<T: Scalar>(x: Option<&[T]>, k: usize) -> T {
    x.map_or(T::zero(), |x| x[k])
}

impl<T: Scalar> Reference<'_, T> {
    /// Placements of every body in its parent and in the world, at q (length checked by the
    /// caller).
    pub(crate) fn update_placements(&mut self, q: &[T]) {
        for i in 0..self.bodies.len() {
            let (rotation, origin) = pose_in_parent(&self.bodies[i], q);
            let pose = match self.bodies[i].parent {
                None => Pose {
                    rotation_in_world: rotation,
                    origin_in_world: origin,
                },
                Some(p) => {
                    let parent = self.poses[p];
                    Pose {
                        rotation_in_world: parent.rotation_in_world * rotation,
                        origin_in_world: parent.origin_in_world + parent.rotation_in_world * origin,
                    }
                }
            };
            let s = &mut self.scratch[i];
            s.rotation_in_parent = rotation;
            s.origin_in_parent = origin;
            self.poses[i] = pose;
        }
    }

    /// ω and v_P of every body in its own frame, at v; needs [`Self::update_placements`].
    pub(crate) fn update_velocities(&mut self, v: &[T]) {
        for i in 0..self.bodies.len() {
            let body = &self.bodies[i];
            let (rotation, origin) = (
                self.scratch[i].rotation_in_parent,
                self.scratch[i].origin_in_parent,
            );
            let (parent_omega, parent_velocity) = match body.parent {
                None => (Vector3::zeros(), Vector3::zeros()),
                Some(p) => (
                    self.scratch[p].omega_in_body,
                    self.scratch[p].velocity_origin_in_body,
                ),
            };
            let rt = rotation.transpose();
            let mut omega_in_body = rt * parent_omega;
            let mut velocity_origin_in_body = rt * (parent_velocity + parent_omega.cross(&origin));
            let vi = &v[body.idx_v..body.idx_v + body.nv];
            match &body.motion {
                Motion::Revolute { axis } => omega_in_body += axis * vi[0],
                Motion::Prismatic { axis } => velocity_origin_in_body += axis * vi[0],
                Motion::FreeFlyer => {
                    velocity_origin_in_body += Vector3::new(vi[0], vi[1], vi[2]);
                    omega_in_body += Vector3::new(vi[3], vi[4], vi[5]);
                }
            }
            let s = &mut self.scratch[i];
            s.omega_in_body = omega_in_body;
            s.velocity_origin_in_body = velocity_origin_in_body;
        }
    }

    /// ω, α and the classical acceleration a_P of every body in its own frame, for
    /// velocities v and accelerations a (`None` = zero) with the ground accelerating at
    /// `accel_ground_in_world` (−g for the Newton–Euler equations, zero for kinematics);
    /// needs [`Self::update_placements`].
    pub(crate) fn update_accelerations(
        &mut self,
        v: Option<&[T]>,
        a: Option<&[T]>,
        accel_ground_in_world: Vector3<T>,
    ) {
        for i in 0..self.bodies.len() {
            let body = &self.bodies[i];
            let (rotation, p) = (
                self.scratch[i].rotation_in_parent,
                self.scratch[i].origin_in_parent,
            );
            let (omega_parent, alpha_parent, accel_parent) = match body.parent {
                None => (Vector3::zeros(), Vector3::zeros(), accel_ground_in_world),
                Some(l) => {
                    let s = &self.scratch[l];
                    (s.omega_in_body, s.alpha_in_body, s.accel_origin_in_body)
                }
            };
            let rt = rotation.transpose();
            let mut omega = rt * omega_parent;
            let mut alpha = rt * alpha_parent;
            let mut accel_origin = rt
                * (accel_parent
                    + alpha_parent.cross(&p)
                    + omega_parent.cross(&omega_parent.cross(&p)));
            let (vi, ai) = (
                |k| coordinate(v, body.idx_v + k),
                |k| coordinate(a, body.idx_v + k),
            );
            match &body.motion {
                Motion::Revolute { axis } => {
                    omega += axis * vi(0);
                    alpha += omega.cross(&(axis * vi(0))) + axis * ai(0);
                }
                Motion::Prismatic { axis } => {
                    accel_origin += omega.cross(&(axis * vi(0))) * T::from_f64(2.0) + axis * ai(0);
                }
                Motion::FreeFlyer => {
                    let v_lin = Vector3::new(vi(0), vi(1), vi(2));
                    omega += Vector3::new(vi(3), vi(4), vi(5));
                    alpha += Vector3::new(ai(3), ai(4), ai(5));
                    accel_origin += Vector3::new(ai(0), ai(1), ai(2)) + omega.cross(&v_lin);
                }
            }
            let s = &mut self.scratch[i];
            s.omega_in_body = omega;
            s.alpha_in_body = alpha;
            s.accel_origin_in_body = accel_origin;
        }
    }

    /// Forward kinematics: the pose of every body frame in the world at configuration q,
    /// indexed like [`crate::Model::bodies`].
    pub fn body_poses(&mut self, q: &[T]) -> Result<&[Pose<T>], SizeError> {
        self.check_q(q)?;
        self.update_placements(q);
        Ok(&self.poses)
    }

    /// The centre of mass in the world frame at configuration q:
    /// c = Σ m_i (p_i + R_i c_i) / Σ m_i over the bodies' poses (R_i, p_i) and mass centres
    /// c_i (in their frames).
    pub fn center_of_mass(&mut self, q: &[T]) -> Result<Vector3<T>, SizeError> {
        self.check_q(q)?;
        self.update_placements(q);
        let (total, first_moment) = self.mass_and_first_moment();
        Ok(first_moment / total)
    }

    /// Σ m_i and Σ m_i (p_i + R_i c_i) (in the world) at the current placements.
    pub(crate) fn mass_and_first_moment(&self) -> (T, Vector3<T>) {
        let mut first_moment = Vector3::zeros();
        let mut total = T::zero();
        for (body, pose) in self.bodies.iter().zip(&self.poses) {
            let centre = pose.origin_in_world + pose.rotation_in_world * body.com_in_body;
            first_moment += centre * body.mass;
            total += body.mass;
        }
        (total, first_moment)
    }
}
