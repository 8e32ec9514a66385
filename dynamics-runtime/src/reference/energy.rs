//! Kinetic and potential energy (textbook, "An energy check on the pendulum equation" and
//! "Generalized-coordinate equations", `T = ½ q̇ᵀ M q̇`).
//!
//! Kinetic energy, per body in its own frame, from the mass-centre velocity
//! `v_G = v_P + ω × c` and König's theorem, plus the rotors behind the joints:
//!
//! ```text
//!   T = Σ_i ½ (m_i v_G,i · v_G,i + ω_i · I_G,i ω_i) + Σ_k ½ armature_k v_k²
//! ```
//!
//! Potential energy of gravity, zero at the world origin (as Pinocchio's):
//! `V = −Σ_i m_i g · c_i,world`, with `c_i,world = p_0i + R_0i c_i` the mass centre in the world.
//! For the textbook's pendulum this is `V = m g l (1 − cos θ) − m g l`.

use super::Reference;
use crate::model::SizeError;
use crate::scalar::Scalar;

impl<T: Scalar> Reference<'_, T> {
    /// The kinetic energy `½ vᵀ M(q) v`, armature included.
    pub fn kinetic_energy(&mut self, q: &[T], v: &[T]) -> Result<T, SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.update_placements(q);
        self.update_velocities(v);
        let half = T::from_f64(0.5);
        let mut energy = T::zero();
        for (body, s) in self.bodies.iter().zip(&self.scratch) {
            let omega = &s.omega_in_body;
            let velocity_com = s.velocity_origin_in_body + omega.cross(&body.com_in_body);
            energy += (velocity_com.dot(&velocity_com) * body.mass
                + omega.dot(&(body.inertia_com_in_body * omega)))
                * half;
            for k in body.idx_v..body.idx_v + body.nv {
                energy += body.armature * v[k] * v[k] * half;
            }
        }
        Ok(energy)
    }

    /// The potential energy of gravity `−Σ_i m_i g · c_i,world` (zero at the world origin).
    pub fn potential_energy(&mut self, q: &[T]) -> Result<T, SizeError> {
        self.check_q(q)?;
        self.update_placements(q);
        let mut energy = T::zero();
        for (body, pose) in self.bodies.iter().zip(&self.poses) {
            let com_in_world = pose.origin_in_world + pose.rotation_in_world * body.com_in_body;
            energy -= self.gravity_in_world.dot(&com_in_world) * body.mass;
        }
        Ok(energy)
    }
}
