//! Forward dynamics by the articulated-body algorithm (Featherstone RBDA §7.3, Table 7.1),
//! in spatial form with linear-first six-vectors: motion `[v_P; ω]`, force `[F; M_P]`.
//!
//! Gravity is the ground's fictitious spatial acceleration `a_0 = [−g; 0]`. With `X_i` the
//! motion transform parent → body, `S_i` the motion subspace and `I_i` the textbook's coupled
//! spatial inertia about P:
//!
//! ```text
//!   pass 1 (root → leaves):  v_i = X_i v_λ + S_i q̇_i,   c_i = v_i × S_i q̇_i,
//!                            I^A_i = I_i,   p^A_i = v_i ×* I_i v_i − f_ext,i
//!   pass 2 (leaves → root):  U_i = I^A_i S_i,   D_i = S_iᵀ U_i + armature_i,
//!                            u_i = τ_i − b_i q̇_i − S_iᵀ p^A_i,
//!                            I^a = I^A_i − U_i D_i⁻¹ U_iᵀ,   p^a = p^A_i + I^a c_i + U_i D_i⁻¹ u_i,
//!                            I^A_λ += X_iᵀ I^a X_i,   p^A_λ += X_iᵀ p^a
//!   pass 3 (root → leaves):  a'_i = X_i a_λ + c_i,   q̈_i = D_i⁻¹ (u_i − U_iᵀ a'_i),
//!                            a_i = a'_i + S_i q̈_i
//! ```
//!
//! A free flyer (S = 1, parent = ground) needs no pass-2 update of a parent; its q̈ solves the
//! 6×6 system `(I^A + armature 1) q̈ = u − I^A a'` by LDLᵀ. The velocity of body i is the
//! kinematic one, `[v_P; ω]` in the body frame; `a` are spatial accelerations, so a free
//! flyer's `q̈ = dv/dt` of its body-frame velocity, as in the model's convention.

use super::spatial::{force_cross, join, motion_cross, solve_spd6};
use super::{Motion, Reference, Wrench};
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::{Matrix6, Vector3, Vector6};

impl<T: Scalar> Reference<'_, T> {
    /// Forward dynamics: `q̈ = M⁻¹ (τ − C v − g − diag(b) v + Σ_i J_iᵀ f_ext,i)`, M including
    /// the armature, by the articulated-body algorithm.
    pub fn forward_dynamics(
        &mut self,
        q: &[T],
        v: &[T],
        tau: &[T],
        f_ext: Option<&[Wrench<T>]>,
        qdd_out: &mut [T],
    ) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("tau", tau)?;
        self.check_wrenches("external wrenches", f_ext)?;
        self.check_v("qdd_out", qdd_out)?;
        self.update_placements(q);
        self.update_motion_transforms();
        self.update_velocities(v);
        let n = self.bodies.len();
        // Pass 1: velocity-product accelerations and the bodies' own bias forces.
        for i in 0..n {
            let body = &self.bodies[i];
            let s = &mut self.scratch[i];
            let velocity = join(&s.velocity_origin_in_body, &s.omega_in_body);
            let mut joint_velocity = Vector6::zeros();
            for k in 0..body.nv {
                joint_velocity += body.motion_subspace_in_body.column(k) * v[body.idx_v + k];
            }
            s.bias_accel_in_body = motion_cross(&velocity, &joint_velocity);
            s.inertia_6_in_body = body.spatial_inertia_in_body;
            s.bias_force_in_body =
                force_cross(&velocity, &(body.spatial_inertia_in_body * velocity));
            if let Some(f_ext) = f_ext {
                s.bias_force_in_body -= f_ext[i].to_vector6();
            }
        }
        // Pass 2: articulated inertias and bias forces, leaves first.
        for i in (0..n).rev() {
            let body = &self.bodies[i];
            if let Motion::FreeFlyer = body.motion {
                continue; // a root: nothing to pass on.
            }
            let s = &mut self.scratch[i];
            let axis = body.motion_subspace_in_body.column(0);
            let j = body.idx_v;
            s.aba_u_vector = s.inertia_6_in_body * axis;
            s.aba_d = axis.dot(&s.aba_u_vector) + body.armature;
            s.aba_u = tau[j] - body.damping * v[j] - axis.dot(&s.bias_force_in_body);
            if let Some(l) = body.parent {
                let s = &self.scratch[i];
                let u_over_d = s.aba_u_vector / s.aba_d;
                let inertia_a = s.inertia_6_in_body - u_over_d * s.aba_u_vector.transpose();
                let bias_a =
                    s.bias_force_in_body + inertia_a * s.bias_accel_in_body + u_over_d * s.aba_u;
                let x = s.x_from_parent;
                let (inertia_to_parent, bias_to_parent) =
                    (x.transpose() * inertia_a * x, x.transpose() * bias_a);
                self.scratch[l].inertia_6_in_body += inertia_to_parent;
                self.scratch[l].bias_force_in_body += bias_to_parent;
            }
        }
        // Pass 3: accelerations, root first.
        let accel_ground = join(&(-self.gravity_in_world), &Vector3::zeros());
        for i in 0..n {
            let body = &self.bodies[i];
            let accel_parent = match body.parent {
                None => accel_ground,
                Some(l) => self.scratch[l].spatial_accel_in_body,
            };
            let s = &mut self.scratch[i];
            let accel_before_joint = s.x_from_parent * accel_parent + s.bias_accel_in_body;
            let j = body.idx_v;
            match body.motion {
                Motion::FreeFlyer => {
                    let d = s.inertia_6_in_body + Matrix6::identity() * body.armature;
                    let mut u = -s.bias_force_in_body - s.inertia_6_in_body * accel_before_joint;
                    for k in 0..6 {
                        u[k] += tau[j + k] - body.damping * v[j + k];
                    }
                    let qdd = solve_spd6(&d, &u);
                    qdd_out[j..j + 6].copy_from_slice(qdd.as_slice());
                    s.spatial_accel_in_body = accel_before_joint + qdd;
                }
                _ => {
                    let qdd = (s.aba_u - s.aba_u_vector.dot(&accel_before_joint)) / s.aba_d;
                    qdd_out[j] = qdd;
                    s.spatial_accel_in_body =
                        accel_before_joint + body.motion_subspace_in_body.column(0) * qdd;
                }
            }
        }
        Ok(())
    }
}
