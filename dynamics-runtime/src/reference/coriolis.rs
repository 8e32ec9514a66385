//! A Christoffel-consistent Coriolis matrix C(q, v), after Echeandia & Wensing (2021),
//! "Numerical methods to compute the Coriolis matrix and Christoffel symbols for rigid-body
//! systems", with linear-first six-vectors.
//!
//! Every quantity is in world coordinates about the world origin. `J_i` is body i's
//! Jacobian (column k = the world-frame motion subspace column `S_k` of a joint supporting
//! i, else 0), `J̇_i` has columns `v_j × S_k` (v_j the velocity of the body that joint k
//! moves), `I_i` is the textbook's spatial inertia moved to the world origin, and
//!
//! ```text
//!   B_i = ½ [ (v_i ×*) I_i + (I_i v_i) ×̄ − I_i (v_i ×) ],   (f ×̄) v = v ×* f,
//!   C   = Σ_i J_iᵀ (B_i J_i + I_i J̇_i).
//! ```
//!
//! Then `C v = Σ J_iᵀ (v_i ×* I_i v_i + I_i J̇_i v)` is the velocity-product part of the
//! Newton–Euler torques (`nle − g`), and `Ṁ − 2C = Σ [J̇ᵀ I J − Jᵀ I J̇ − Jᵀ (I v)×̄ J]` is
//! skew-symmetric because `İ_i = (v ×*) I − I (v ×)` and `f ×̄` is skew.

use super::spatial::{
    force_bar_matrix, force_cross_matrix, join, motion_cross, motion_cross_matrix, motion_to_world,
    spatial_inertia,
};
use super::Reference;
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::DMatrix;

impl<T: Scalar> Reference<'_, T> {
    /// The Coriolis matrix C(q, v) for which `Ṁ − 2C` is skew-symmetric and
    /// `C v = nle(q, v) − g(q)`. No damping: that is a separate term.
    pub fn coriolis_matrix(
        &mut self,
        q: &[T],
        v: &[T],
        c_out: &mut DMatrix<T>,
    ) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_v("v", v)?;
        self.check_square("coriolis matrix rows", "coriolis matrix columns", c_out)?;
        self.update_placements(q);
        self.update_velocities(v);
        // World-frame Jacobian columns S_k and their rates v_j × S_k, per velocity index.
        for (i, body) in self.bodies.iter().enumerate() {
            let pose = &self.poses[i];
            let s = &self.scratch[i];
            let velocity_in_world =
                motion_to_world(pose, &join(&s.velocity_origin_in_body, &s.omega_in_body));
            for k in 0..body.nv {
                let column =
                    motion_to_world(pose, &body.motion_subspace_in_body.column(k).into_owned());
                self.jacobian_column_in_world[body.idx_v + k] = column;
                self.jacobian_rate_column_in_world[body.idx_v + k] =
                    motion_cross(&velocity_in_world, &column);
            }
        }
        c_out.fill(T::zero());
        let half = T::from_f64(0.5);
        for i in 0..self.bodies.len() {
            // The velocity indices of the joints from the root to body i.
            self.support.clear();
            let mut walk = Some(i);
            while let Some(j) = walk {
                let joint = &self.bodies[j];
                self.support.extend(joint.idx_v..joint.idx_v + joint.nv);
                walk = joint.parent;
            }
            let body = &self.bodies[i];
            let pose = &self.poses[i];
            let s = &self.scratch[i];
            let rotation = &pose.rotation_in_world;
            let inertia_in_world = spatial_inertia(
                body.mass,
                &(pose.origin_in_world + rotation * body.com_in_body),
                &(rotation * body.inertia_com_in_body * rotation.transpose()),
            );
            let velocity_in_world =
                motion_to_world(pose, &join(&s.velocity_origin_in_body, &s.omega_in_body));
            let b = (force_cross_matrix(&velocity_in_world) * inertia_in_world
                + force_bar_matrix(&(inertia_in_world * velocity_in_world))
                - inertia_in_world * motion_cross_matrix(&velocity_in_world))
                * half;
            for (slot, &k) in self.support.iter().enumerate() {
                self.coriolis_work[slot] = b * self.jacobian_column_in_world[k]
                    + inertia_in_world * self.jacobian_rate_column_in_world[k];
            }
            for &row in &self.support {
                let j_row = &self.jacobian_column_in_world[row];
                for (slot, &col) in self.support.iter().enumerate() {
                    c_out[(row, col)] += j_row.dot(&self.coriolis_work[slot]);
                }
            }
        }
        Ok(())
    }
}
