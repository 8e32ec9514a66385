//! The centroidal momentum h_G and its rate ḣ_G (Orin, Goswami and Lee 2013; Pinocchio's
//! `hg` and `dhg`), six-vectors linear first, in world axes.
//!
//! Each body i has mass m, mass centre c = PG and I_G in its own frame, pose (R, p) in the
//! world, and ω, α, the velocity v_P and the classical acceleration a_P of its origin P in
//! its own frame. Its mass centre is G_i = p + R c in the world, and the mechanism's is
//! G = Σ m_i G_i / Σ m_i. From the textbook's rigid-body fields,
//!
//! ```text
//!   v_G = v_P + ω × c,   a_G = a_P + α × c + ω × (ω × c)        (in body axes)
//! ```
//!
//! The momentum, with the angular part about the mechanism's mass centre G:
//!
//! ```text
//!   h_G = [ Σ m R v_G ;  Σ (G_i − G) × m R v_G + R I_G ω ]
//! ```
//!
//! Its rate along the motion is the resultant of the forces the bodies need, F = m a_G and
//! M_G = I_G α + ω × I_G ω (the textbook's Newton–Euler equations at each mass centre, with
//! a_P and α from the reference's forward sweep, without gravity):
//!
//! ```text
//!   ḣ_G = [ Σ R F ;  Σ (G_i − G) × R F + R M_G ]
//! ```
//!
//! The angular part is taken about the moving G: d/dt Σ (G_i − G) × m v_Gi =
//! Σ (G_i − G) × m a_Gi + Σ (v_Gi − Ġ) × m v_Gi, and the last sum is −Ġ × (Σ m v_Gi) =
//! −Ġ × (M Ġ) = 0. So ḣ_G = A_G a + Ȧ_G v, and at a = 0 it is Ȧ_G v. Both are the time
//! derivative of h_G along (q(t), v(t)) with q̇ = v and v̇ = a.
//!
//! A mechanism without mass (every body massless but with rotational inertia, or moved only
//! through armature) has no mass centre: G is taken at the world origin, which changes
//! nothing since every m_i is zero.

use super::Reference;
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::{Vector3, Vector6};

impl<T: Scalar> Reference<'_, T> {
    /// G = Σ m_i G_i / Σ m_i in the world from the current poses (the world origin if the
    /// mechanism has no mass).
    fn com_in_world(&self) -> Vector3<T> {
        let (total, first_moment) = self.mass_and_first_moment();
        if total == T::zero() {
            Vector3::zeros()
        } else {
            first_moment / total
        }
    }

    /// The centroidal momentum at (q, v): `h_G = [Σ m v_G; Σ (G_i − G) × m v_G + I_G ω]`,
    /// the linear momentum and the angular momentum about the mechanism's mass centre G, in
    /// world axes (Pinocchio's `computeCentroidalMomentum`, `hg`; = A_G v).
    pub fn centroidal_momentum(&mut self, q: &[T], v: &[T]) -> Result<Vector6<T>, SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.update_placements(q);
        self.update_velocities(v);
        let com = self.com_in_world();
        let mut linear_in_world = Vector3::zeros();
        let mut angular_in_world = Vector3::zeros();
        for ((body, pose), s) in self.bodies.iter().zip(&self.poses).zip(&self.scratch) {
            let rotation = &pose.rotation_in_world;
            let c = &body.com_in_body;
            let omega = &s.omega_in_body;
            let momentum_in_world =
                rotation * (s.velocity_origin_in_body + omega.cross(c)) * body.mass;
            let com_offset_in_world = pose.origin_in_world + rotation * c - com;
            linear_in_world += momentum_in_world;
            angular_in_world += com_offset_in_world.cross(&momentum_in_world)
                + rotation * (body.inertia_com_in_body * omega);
        }
        Ok(super::spatial::join(&linear_in_world, &angular_in_world))
    }

    /// The rate of the centroidal momentum at (q, v, a), without gravity: `ḣ_G = [Σ F;
    /// Σ (G_i − G) × F + M_G]` with each body's F = m a_G and M_G = I_G α + ω × I_G ω, in
    /// world axes, the angular part about the moving mass centre G (= A_G a + Ȧ_G v; at
    /// a = 0, Ȧ_G v. Pinocchio's `computeCentroidalMomentumTimeVariation`, `dhg`).
    pub fn centroidal_momentum_rate(
        &mut self,
        q: &[T],
        v: &[T],
        a: &[T],
    ) -> Result<Vector6<T>, SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_v("a", a)?;
        self.update_placements(q);
        self.update_accelerations(Some(v), Some(a), Vector3::zeros());
        let com = self.com_in_world();
        let mut force_in_world = Vector3::zeros();
        let mut moment_in_world = Vector3::zeros();
        for ((body, pose), s) in self.bodies.iter().zip(&self.poses).zip(&self.scratch) {
            let rotation = &pose.rotation_in_world;
            let c = &body.com_in_body;
            let i_g = &body.inertia_com_in_body;
            let (omega, alpha) = (&s.omega_in_body, &s.alpha_in_body);
            let accel_com_in_body =
                s.accel_origin_in_body + alpha.cross(c) + omega.cross(&omega.cross(c));
            let force = rotation * accel_com_in_body * body.mass;
            let moment_com_in_body = i_g * alpha + omega.cross(&(i_g * omega));
            let com_offset_in_world = pose.origin_in_world + rotation * c - com;
            force_in_world += force;
            moment_in_world += com_offset_in_world.cross(&force) + rotation * moment_com_in_body;
        }
        Ok(super::spatial::join(&force_in_world, &moment_in_world))
    }
}
