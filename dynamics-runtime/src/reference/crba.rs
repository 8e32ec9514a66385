//! The joint-space inertia matrix M(q) by the composite-rigid-body algorithm
//! (Featherstone RBDA §6.2, Table 6.2), in spatial form with linear-first six-vectors.
//!
//! Each body's spatial inertia about its origin P is the textbook's coupled matrix
//! `I_i = [[m 1, −m ĉ], [m ĉ, I_P]]`, `I_P = I_G − m ĉ²`. With `X_i` the motion transform from
//! the parent λ(i) to body i and `S_i` the motion subspace in the body frame:
//!
//! ```text
//!   I^c_i = I_i + Σ_{children j} X_jᵀ I^c_j X_j          (composite inertia, leaves first)
//!   F = I^c_i S_i,   M_ii = S_iᵀ F + armature_i 1
//!   j = i; while λ(j) exists: F = X_jᵀ F, j = λ(j), M_ji = S_jᵀ F, M_ij = M_jiᵀ
//! ```

use super::spatial::motion_transform;
use super::Reference;
use crate::model::SizeError;
use crate::scalar::Scalar;
use nalgebra::DMatrix;

impl<T: Scalar> Reference<'_, T> {
    /// Motion transforms X_i (parent → body) at the current placements.
    pub(crate) fn update_motion_transforms(&mut self) {
        for s in self.scratch.iter_mut() {
            s.x_from_parent = motion_transform(&s.rotation_in_parent, &s.origin_in_parent);
        }
    }

    /// The joint-space inertia matrix M(q), full and symmetric, with the armature on its
    /// diagonal (kinetic energy `½ vᵀ M v`).
    pub fn mass_matrix(&mut self, q: &[T], m_out: &mut DMatrix<T>) -> Result<(), SizeError> {
        self.check_q(q)?;
        self.check_square("mass matrix rows", "mass matrix columns", m_out)?;
        self.update_placements(q);
        self.update_motion_transforms();
        let n = self.bodies.len();
        for i in 0..n {
            self.scratch[i].inertia_6_in_body = self.bodies[i].spatial_inertia_in_body;
        }
        for i in (0..n).rev() {
            if let Some(l) = self.bodies[i].parent {
                let s = &self.scratch[i];
                let in_parent = s.x_from_parent.transpose() * s.inertia_6_in_body * s.x_from_parent;
                self.scratch[l].inertia_6_in_body += in_parent;
            }
        }
        m_out.fill(T::zero());
        for i in 0..n {
            let body = &self.bodies[i];
            for col in 0..body.nv {
                let column = body.idx_v + col;
                let mut force =
                    self.scratch[i].inertia_6_in_body * body.motion_subspace_in_body.column(col);
                // The joint's own block, upper triangle mirrored so M is exactly symmetric.
                for row in 0..=col {
                    let value = body.motion_subspace_in_body.column(row).dot(&force);
                    m_out[(body.idx_v + row, column)] = value;
                    m_out[(column, body.idx_v + row)] = value;
                }
                m_out[(column, column)] += body.armature;
                let mut j = i;
                while let Some(l) = self.bodies[j].parent {
                    force = self.scratch[j].x_from_parent.transpose() * force;
                    j = l;
                    let ancestor = &self.bodies[j];
                    for row in 0..ancestor.nv {
                        let value = ancestor.motion_subspace_in_body.column(row).dot(&force);
                        m_out[(ancestor.idx_v + row, column)] = value;
                        m_out[(column, ancestor.idx_v + row)] = value;
                    }
                }
            }
        }
        Ok(())
    }
}
