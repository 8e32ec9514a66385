//! Inverse dynamics by the recursive Newton–Euler algorithm, in the textbook's mass-centre form.
//!
//! Gravity enters as a fictitious upward acceleration of the ground, `a_0 = −g`
//! (Featherstone RBDA §5.3): every body then carries its weight through its acceleration,
//! and the backward sweep yields the loads the joints really transmit.
//!
//! Forward sweep (`Reference::update_accelerations`, shared with the frame kinematics), in the
//! frame of body i, whose pose in its parent λ is (R, p):
//!
//! ```text
//!   ω_i  = Rᵀ ω_λ (+ s q̇, revolute)
//!   α_i  = Rᵀ α_λ (+ ω_i × s q̇ + s q̈, revolute)                 (α = ω̇ in body axes)
//!   a_Pi = Rᵀ (a_Pλ + α_λ × p + ω_λ × (ω_λ × p))                 (textbook ch. 7, point of λ at P_i)
//!          (+ 2 ω_i × s q̇ + s q̈, prismatic: Coriolis and relative acceleration)
//!   free flyer (parent = ground): ω = ω_v, α = ω̇_v, a_P = Rᵀ a_0 + v̇_lin + ω × v_lin
//! ```
//!
//! Body equations (textbook, "Newton–Euler equations at the mass center" and "Moving the
//! reference point to the body"), with c = PG:
//!
//! ```text
//!   a_G = a_P + α × c + ω × (ω × c),   F = m a_G,
//!   M_G = I_G α + ω × (I_G ω),         M_P = M_G + c × F
//! ```
//!
//! Backward sweep (action–reaction between parent and child): the wrench the joint
//! transmits to body i is `f_i = [F; M_P]_i − f_ext,i + Σ_children [R F_c; R M_c + p × R F_c]`,
//! and the joint needs `τ_i = s_iᵀ f_i + armature q̈_i + b q̇_i` (revolute `s · M_P`, prismatic
//! `s · F`, free flyer all six components).

use super::kinematics::coordinate;
use super::{Reference, Wrench};
use crate::model::SizeError;
use crate::scalar::Scalar;

impl<T: Scalar> Reference<'_, T> {
    /// Both sweeps; leaves each joint's wrench f_i in the body's scratch. `None` for v or a
    /// means zero. Lengths are checked by the callers.
    fn newton_euler(
        &mut self,
        q: &[T],
        v: Option<&[T]>,
        a: Option<&[T]>,
        f_ext: Option<&[Wrench<T>]>,
    ) {
        self.update_placements(q);
        self.update_accelerations(v, a, -self.gravity_in_world);
        for i in 0..self.bodies.len() {
            let body = &self.bodies[i];
            let s = &self.scratch[i];
            let (omega, alpha, accel_origin) =
                (s.omega_in_body, s.alpha_in_body, s.accel_origin_in_body);
            // The body's equations about its mass centre G, then moved to P.
            let c = &body.com_in_body;
            let i_g = &body.inertia_com_in_body;
            let accel_com = accel_origin + alpha.cross(c) + omega.cross(&omega.cross(c));
            let force = accel_com * body.mass;
            let moment_com = i_g * alpha + omega.cross(&(i_g * omega));
            let mut moment_origin = moment_com + c.cross(&force);
            let mut force = force;
            if let Some(f_ext) = f_ext {
                force -= f_ext[i].force;
                moment_origin -= f_ext[i].moment;
            }
            self.scratch[i].joint_wrench_in_body = super::spatial::join(&force, &moment_origin);
        }
        for i in (0..self.bodies.len()).rev() {
            if let Some(l) = self.bodies[i].parent {
                let s = &self.scratch[i];
                let (force, moment) = super::spatial::split(&s.joint_wrench_in_body);
                let force_in_parent = s.rotation_in_parent * force;
                let moment_in_parent =
                    s.rotation_in_parent * moment + s.origin_in_parent.cross(&force_in_parent);
                self.scratch[l].joint_wrench_in_body +=
                    super::spatial::join(&force_in_parent, &moment_in_parent);
            }
        }
    }

    /// `τ_i = s_iᵀ f_i`, plus `b q̇` if `damped_v` and `armature q̈` if `armature_a` is given.
    fn project_onto_joints(&self, damped_v: Option<&[T]>, armature_a: Option<&[T]>, tau: &mut [T]) {
        for (body, s) in self.bodies.iter().zip(&self.scratch) {
            for k in 0..body.nv {
                let j = body.idx_v + k;
                tau[j] = body
                    .motion_subspace_in_body
                    .column(k)
                    .dot(&s.joint_wrench_in_body)
                    + body.damping * coordinate(damped_v, j)
                    + body.armature * coordinate(armature_a, j);
            }
        }
    }

    /// Inverse dynamics: `τ = M(q) a + C(q, v) v + g(q) + diag(b) v − Σ_i J_iᵀ f_ext,i`, M
    /// including the armature. `f_ext` (one per body, see [`Wrench`]) may be `None`.
    pub fn inverse_dynamics(
        &mut self,
        q: &[T],
        v: &[T],
        a: &[T],
        f_ext: Option<&[Wrench<T>]>,
        tau: &mut [T],
    ) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("a", a)?;
        self.check_wrenches("external wrenches", f_ext)?;
        self.check_v("tau", tau)?;
        self.newton_euler(q, Some(v), Some(a), f_ext);
        self.project_onto_joints(Some(v), Some(a), tau);
        Ok(())
    }

    /// The generalized gravity g(q): the torques that hold the mechanism still at q.
    pub fn gravity(&mut self, q: &[T], g_out: &mut [T]) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("g_out", g_out)?;
        self.newton_euler(q, None, None, None);
        self.project_onto_joints(None, None, g_out);
        Ok(())
    }

    /// The bias `C(q, v) v + g(q) + diag(b) v`: inverse dynamics at zero acceleration,
    /// without external loads.
    pub fn bias(&mut self, q: &[T], v: &[T], out: &mut [T]) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("out", out)?;
        self.newton_euler(q, Some(v), None, None);
        self.project_onto_joints(Some(v), None, out);
        Ok(())
    }

    /// The nonlinear effects `C(q, v) v + g(q)` (Pinocchio's `nle`: no damping).
    pub fn nonlinear_effects(&mut self, q: &[T], v: &[T], out: &mut [T]) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("out", out)?;
        self.newton_euler(q, Some(v), None, None);
        self.project_onto_joints(None, None, out);
        Ok(())
    }

    /// The wrench each joint transmits from the parent (or the ground) to its body, `[F; M_P]`
    /// in the body frame about the joint point P, for the motion (q, v, a) under the external
    /// wrenches. It includes the actuator's component along the joint axis, `s_iᵀ f_i`, which
    /// is the joint torque less the armature and damping terms (those act on the rotor, not
    /// on the body).
    pub fn joint_reactions(
        &mut self,
        q: &[T],
        v: &[T],
        a: &[T],
        f_ext: Option<&[Wrench<T>]>,
        out: &mut [Wrench<T>],
    ) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("a", a)?;
        self.check_wrenches("external wrenches", f_ext)?;
        self.check_wrenches("out", Some(out))?;
        self.newton_euler(q, Some(v), Some(a), f_ext);
        for (wrench, s) in out.iter_mut().zip(&self.scratch) {
            *wrench = Wrench::from_vector6(&s.joint_wrench_in_body);
        }
        Ok(())
    }
}
