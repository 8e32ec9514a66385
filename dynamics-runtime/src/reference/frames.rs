//! Operational frames: poses, Jacobians, velocities and classical accelerations, with
//! Pinocchio's conventions (six-vectors linear first).
//!
//! A frame F (an entry of [`crate::Model::frames`]) is rigidly attached to body b of the
//! tree: its origin is at r = PF and its rotation frame → body is R_bF, both in b's frame
//! (P is b's origin). With b's pose (R_b, p_b) in the world, the frame's pose is
//!
//! ```text
//!   R_F = R_b R_bF,   p_F = p_b + R_b r                     (Pinocchio's oMf)
//! ```
//!
//! Velocity of the frame's origin, from the textbook's rigid-body velocity field
//! v_Q = v_P + ω × PQ, first in b's axes, then in the world's:
//!
//! ```text
//!   v_F,in_body = v_P + ω × r
//!   LOCAL_WORLD_ALIGNED:  [v_F; ω]_in_world = [R_b v_F,in_body; R_b ω_in_body] = J v
//!   LOCAL:                [v_F; ω]_in_frame = [R_Fᵀ v_F,in_world; R_Fᵀ ω_in_world]
//! ```
//!
//! The Jacobian J (6 × nv) is the map v ↦ [v_F; ω]: the sweep of body velocities is linear
//! in v, so column k is the frame's velocity for the unit joint rate v = e_k.
//!
//! Classical acceleration of the frame's origin, from the textbook's rigid-body acceleration
//! field a_Q = a_P + α × PQ + ω × (ω × PQ), with a_P and α from the forward sweep of the
//! Newton–Euler equations, without gravity:
//!
//! ```text
//!   a_F,in_body = a_P + α × r + ω × (ω × r)
//!   [p̈_F; ω̇]_in_world = [R_b a_F,in_body; R_b α_in_body]
//! ```
//!
//! (d/dt (R_b ω_in_body) = R_b α_in_body, since Ṙ_b ω_in_body = R_b (ω × ω) = 0.) This is
//! the time derivative of J v along the motion, J̇ v + J a; at a = 0 it is J̇ v (Pinocchio's
//! `getFrameClassicalAcceleration` and `getFrameJacobianTimeVariation` · v, both
//! LOCAL_WORLD_ALIGNED).
//!
//! A frame on the ground has the pose (R_bF, r) and zero velocity, Jacobian and acceleration.
//!
//! # Frame indices
//! Every method takes `frame`, an index into [`crate::Model::frames`] (find one by name with
//! [`crate::Model::frame_index`]). An index out of range is [`FrameError::NoSuchFrame`]; a
//! slice of the wrong length is [`FrameError::Size`]. Lengths are checked first (q, v, a),
//! then the index, then the output.

use super::spatial::join;
use super::{FrameConstants, Pose, Reference};
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::{Matrix3, Matrix6xX, Vector3, Vector6};
use std::fmt;

/// Why a frame method of [`Reference`] could not run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// A slice or output matrix has the wrong size for the model.
    Size(SizeError),
    /// The frame index is not an index into [`crate::Model::frames`].
    NoSuchFrame {
        /// The index given.
        index: usize,
        /// How many frames the model has.
        frames: usize,
    },
}

impl From<SizeError> for FrameError {
    fn from(e: SizeError) -> Self {
        FrameError::Size(e)
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrameError::Size(e) => e.fmt(f),
            FrameError::NoSuchFrame { index, frames } => write!(
                f,
                "frame {index} does not exist: the model has {frames} frames (indices \
                 0..{frames} into Model::frames())"
            ),
        }
    }
}

impl std::error::Error for FrameError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            FrameError::Size(e) => Some(e),
            FrameError::NoSuchFrame { .. } => None,
        }
    }
}

/// Rotates both halves of a six-vector: `[R lin; R ang]`.
fn rotate_both<T: Scalar>(rotation: &Matrix3<T>, m: &Vector6<T>) -> Vector6<T> {
    let (lin, ang) = super::spatial::split(m);
    join(&(rotation * lin), &(rotation * ang))
}

impl<T: Scalar> Reference<'_, T> {
    /// The constants of frame `frame`, or [`FrameError::NoSuchFrame`].
    fn frame_constants(&self, frame: usize) -> Result<FrameConstants<T>, FrameError> {
        self.frames
            .get(frame)
            .copied()
            .ok_or(FrameError::NoSuchFrame {
                index: frame,
                frames: self.frames.len(),
            })
    }

    /// The frame's pose in the world from the current body poses.
    fn frame_pose_in_world(&self, frame: &FrameConstants<T>) -> Pose<T> {
        match frame.body {
            None => Pose {
                rotation_in_world: frame.rotation_frame_in_body,
                origin_in_world: frame.origin_frame_in_body,
            },
            Some(b) => {
                let body = &self.poses[b];
                Pose {
                    rotation_in_world: body.rotation_in_world * frame.rotation_frame_in_body,
                    origin_in_world: body.origin_in_world
                        + body.rotation_in_world * frame.origin_frame_in_body,
                }
            }
        }
    }

    /// `[v_F; ω]` in world axes from the current body poses and velocities.
    fn frame_velocity_in_world(&self, frame: &FrameConstants<T>) -> Vector6<T> {
        match frame.body {
            None => Vector6::zeros(),
            Some(b) => {
                let s = &self.scratch[b];
                let r = &frame.origin_frame_in_body;
                let velocity_in_body = s.velocity_origin_in_body + s.omega_in_body.cross(r);
                let rotation = &self.poses[b].rotation_in_world;
                join(
                    &(rotation * velocity_in_body),
                    &(rotation * s.omega_in_body),
                )
            }
        }
    }

    /// The pose of frame `frame` in the world at configuration q: `x_in_world =
    /// rotation_in_world · x_in_frame + origin_in_world` (Pinocchio's oMf).
    pub fn frame_pose(&mut self, q: &[T], frame: usize) -> Result<Pose<T>, FrameError> {
        self.check_q(q)?;
        let frame = self.frame_constants(frame)?;
        self.update_placements(q);
        Ok(self.frame_pose_in_world(&frame))
    }

    /// The Jacobian of frame `frame` at q, LOCAL_WORLD_ALIGNED: the 6 × nv matrix J with
    /// `J v = [v_F; ω]`, the velocity of the frame's origin and the angular velocity, both in
    /// world axes (Pinocchio's `getFrameJacobian(.., LOCAL_WORLD_ALIGNED)`). Written into
    /// `jacobian`, which must have nv columns ([`FrameError::Size`] otherwise).
    pub fn frame_jacobian(
        &mut self,
        q: &[T],
        frame: usize,
        jacobian: &mut Matrix6xX<T>,
    ) -> Result<(), FrameError> {
        self.check_q(q)?;
        let frame = self.frame_constants(frame)?;
        SizeError::check("frame jacobian columns", self.model.nv(), jacobian.ncols())?;
        self.update_placements(q);
        // Column k: the frame's velocity for the unit joint rate v = e_k.
        let mut unit_rates = std::mem::take(&mut self.unit_rates);
        for k in 0..unit_rates.len() {
            unit_rates.fill(T::zero());
            unit_rates[k] = T::one();
            self.update_velocities(&unit_rates);
            jacobian.set_column(k, &self.frame_velocity_in_world(&frame));
        }
        self.unit_rates = unit_rates;
        Ok(())
    }

    /// The Jacobian of frame `frame` at q, LOCAL: `J v = [v_F; ω]` with both blocks in the
    /// frame's own axes (Pinocchio's `getFrameJacobian(.., LOCAL)`), that is
    /// `[R_Fᵀ 0; 0 R_Fᵀ]` times the LOCAL_WORLD_ALIGNED Jacobian of
    /// [`Reference::frame_jacobian`]. `jacobian` must have nv columns.
    pub fn frame_jacobian_local(
        &mut self,
        q: &[T],
        frame: usize,
        jacobian: &mut Matrix6xX<T>,
    ) -> Result<(), FrameError> {
        self.frame_jacobian(q, frame, jacobian)?;
        let frame = self.frame_constants(frame)?;
        let world_to_frame = self
            .frame_pose_in_world(&frame)
            .rotation_in_world
            .transpose();
        for k in 0..jacobian.ncols() {
            let column: Vector6<T> = jacobian.column(k).into_owned();
            jacobian.set_column(k, &rotate_both(&world_to_frame, &column));
        }
        Ok(())
    }

    /// The velocity of frame `frame` at (q, v), LOCAL_WORLD_ALIGNED: `[v_F; ω]`, the velocity
    /// of its origin and the angular velocity in world axes (= J v; Pinocchio's
    /// `getFrameVelocity(.., LOCAL_WORLD_ALIGNED)`).
    pub fn frame_velocity(
        &mut self,
        q: &[T],
        v: &[T],
        frame: usize,
    ) -> Result<Vector6<T>, FrameError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        let frame = self.frame_constants(frame)?;
        self.update_placements(q);
        self.update_velocities(v);
        Ok(self.frame_velocity_in_world(&frame))
    }

    /// The classical acceleration of frame `frame` at (q, v, a), without gravity:
    /// `[p̈_F; ω̇]`, the acceleration of its origin and the angular acceleration in world
    /// axes (= J̇ v + J a; at a = 0, J̇ v. Pinocchio's
    /// `getFrameClassicalAcceleration(.., LOCAL_WORLD_ALIGNED)`).
    pub fn frame_classical_acceleration(
        &mut self,
        q: &[T],
        v: &[T],
        a: &[T],
        frame: usize,
    ) -> Result<Vector6<T>, FrameError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("a", a)?;
        let frame = self.frame_constants(frame)?;
        let Some(b) = frame.body else {
            return Ok(Vector6::zeros());
        };
        self.update_placements(q);
        self.update_accelerations(Some(v), Some(a), Vector3::zeros());
        let s = &self.scratch[b];
        let (omega, alpha) = (&s.omega_in_body, &s.alpha_in_body);
        let r = &frame.origin_frame_in_body;
        let accel_in_body = s.accel_origin_in_body + alpha.cross(r) + omega.cross(&omega.cross(r));
        let rotation = &self.poses[b].rotation_in_world;
        Ok(join(&(rotation * accel_in_body), &(rotation * alpha)))
    }
}
