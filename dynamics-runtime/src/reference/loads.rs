//! Applied loads as generalized forces, by virtual power (textbook, "generalized forces";
//! Featherstone RBDA §2.4): a force F through a point P fixed on body b and a couple M on
//! b contribute, per unit joint rate, the power they would deliver,
//!
//! ```text
//!   Q = Σ_loads  J_Pᵀ F_in_world + J_ωᵀ M_in_world
//! ```
//!
//! where J_P (3 × nv) maps v to the velocity of P and J_ω (3 × nv) maps v to b's angular
//! velocity, both in world axes. Column k of both is the motion for the unit joint rate
//! v = e_k, from the rigid-body velocity field v_P = v_O + ω × OP in b's axes, turned into
//! the world's by R_b (as [`super::frames`] builds frame Jacobians).
//!
//! The components of a load ([`crate::Model::loads`]) are given in the declared body's axes
//! or in the world's ([`crate::LoadFrame`]): in world axes they are
//!
//! ```text
//!   in body:   F_in_world = R_b R_db F,     R_db the declared body's axes in tree body b
//!   in world:  F_in_world = F
//! ```
//!
//! Nothing here shares the Newton–Euler sweep's treatment of external wrenches, so the two
//! check each other: `inverse_dynamics(q, v, a, None) − Q` is τ under the loads and
//! `forward_dynamics(q, v, τ + Q, None)` the motion they cause.

use super::Reference;
use crate::model::{LoadFrame, LoadType, SizeError};
use crate::scalar::Scalar;
use nalgebra::{Matrix3, Vector3};

/// One load of [`crate::Model::loads`], with its constants converted to `T` once.
#[derive(Clone, Copy, Debug)]
pub(super) struct LoadConstants<T: Scalar> {
    /// The tree body it acts on, `None` for one welded to the ground.
    pub body: Option<usize>,
    pub kind: LoadType,
    pub frame: LoadFrame,
    /// R_db: the declared body's axes in the tree body's frame.
    pub rotation_declared_in_body: Matrix3<T>,
    /// The point of application r = OP in the tree body's frame.
    pub point_in_body: Vector3<T>,
    pub input_offset: usize,
}

impl<T: Scalar> LoadConstants<T> {
    /// The three components at `offset` of the load's inputs, in world axes for a body whose
    /// rotation into the world is `rotation_in_world`.
    fn in_world(&self, loads: &[T], offset: usize, rotation_in_world: &Matrix3<T>) -> Vector3<T> {
        let k = self.input_offset + offset;
        let given = Vector3::new(loads[k], loads[k + 1], loads[k + 2]);
        match self.frame {
            LoadFrame::World => given,
            LoadFrame::Body => rotation_in_world * (self.rotation_declared_in_body * given),
        }
    }

    /// The force and the couple of the load, in world axes.
    fn force_and_couple_in_world(
        &self,
        loads: &[T],
        rotation_in_world: &Matrix3<T>,
    ) -> (Vector3<T>, Vector3<T>) {
        match self.kind {
            LoadType::Force => (self.in_world(loads, 0, rotation_in_world), Vector3::zeros()),
            LoadType::Couple => (Vector3::zeros(), self.in_world(loads, 0, rotation_in_world)),
            LoadType::Wrench => (
                self.in_world(loads, 0, rotation_in_world),
                self.in_world(loads, 3, rotation_in_world),
            ),
        }
    }
}

impl<T: Scalar> Reference<'_, T> {
    /// The generalized force Q (length nv) of the model's applied loads at configuration
    /// q, for the load inputs `loads` (length [`crate::Model::num_load_inputs`], each load's
    /// components in its declared axes): Q = Σ J_Pᵀ F + J_ωᵀ M, by virtual power. It is what
    /// the generated functions' `loads` argument adds to the joint forces: τ under the loads
    /// is [`Reference::inverse_dynamics`] without them less Q, and the motion they cause is
    /// [`Reference::forward_dynamics`] at τ + Q.
    pub fn generalized_load_forces(
        &mut self,
        q: &[T],
        loads: &[T],
        out: &mut [T],
    ) -> Result<(), SizeError> {
        self.check_q(q)?;
        SizeError::check("loads", self.model.num_load_inputs(), loads.len())?;
        self.check_v("out", out)?;
        self.update_placements(q);
        let mut unit_rates = std::mem::take(&mut self.unit_rates);
        for (k, q_k) in out.iter_mut().enumerate() {
            unit_rates.fill(T::zero());
            unit_rates[k] = T::one();
            self.update_velocities(&unit_rates);
            *q_k = T::zero();
            for load in &self.loads {
                let Some(b) = load.body else {
                    continue; // welded to the ground: it never moves, so does no work
                };
                let rotation_in_world = &self.poses[b].rotation_in_world;
                let s = &self.scratch[b];
                // Column k of J_P and J_ω: the point's velocity and the body's angular
                // velocity for v = e_k, in world axes.
                let point_velocity = rotation_in_world
                    * (s.velocity_origin_in_body + s.omega_in_body.cross(&load.point_in_body));
                let omega = rotation_in_world * s.omega_in_body;
                let (force, couple) = load.force_and_couple_in_world(loads, rotation_in_world);
                *q_k += point_velocity.dot(&force) + omega.dot(&couple);
            }
        }
        self.unit_rates = unit_rates;
        Ok(())
    }
}
