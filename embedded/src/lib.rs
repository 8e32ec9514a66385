//! A `#![no_std]` crate that uses the toolkit as a microcontroller's firmware would: it
//! declares a three-joint arm with `mechanism!` and runs the generated inverse dynamics,
//! mass matrix and forward dynamics in `f32`, with the runtime built without std
//! (`default-features = false`).
//!
//! Contract: nothing here allocates, and nothing links std: CI builds this crate for
//! `thumbv7em-none-eabihf` (a Cortex-M4F, which has no std at all). [`control_tick`] is one
//! tick of a computed-torque controller: the joint torques that give the commanded
//! acceleration, the mass matrix at the state, and the acceleration the forward dynamics
//! predicts under those torques (the commanded one, to rounding). [`simulate_step`]
//! advances the arm by one RK4 step of the runtime's integrators, which need no std either.
//!
//! The host-side tests (below, with std) check the `f32` results against the same
//! functions in `f64` and the gravity torques against the hand-derived formula, measure the
//! `f32` error of every output against double-double evaluation, and close the loop.

#![no_std]

use dynamics_runtime::integrators::{self, Inputs, State};
use dynamics_runtime::mechanism;

mechanism! {
    /// A three-joint arm: a turret turning about the vertical, a shoulder and an elbow
    /// pitching about their y axes, and a 0.3 kg payload welded at the forearm's tip.
    /// q = [yaw, shoulder, elbow]; at q = 0 the arm points along the world's x axis.
    pub struct Arm3;
    gravity: [0.0, 0.0, -9.81];
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics];

    body turret { mass: 2.0, com: [0.0, 0.0, 0.05], shape: cylinder(radius: 0.08, length: 0.1, axis: z) }
    body upper { mass: 1.5, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    body fore { mass: 0.8, com: [0.125, 0.0, 0.0], shape: rod(length: 0.25, axis: x) }
    body payload { mass: 0.3, shape: point }

    joint yaw: revolute(ground -> turret) { axis: z, armature: 0.002 }
    joint shoulder: revolute(turret -> upper) { axis: y, at: [0.0, 0.0, 0.1], armature: 0.002 }
    joint elbow: revolute(upper -> fore) { axis: y, at: [0.3, 0.0, 0.0], armature: 0.001 }
    joint tip: fixed(fore -> payload) { at: [0.25, 0.0, 0.0] }
}

/// The arm's degrees of freedom.
pub const NV: usize = 3;

/// Proportional and derivative gains of [`control_tick`], per joint (1/s², 1/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gains {
    /// K_p.
    pub kp: [f32; NV],
    /// K_d.
    pub kd: [f32; NV],
}

/// Where the arm should be: position, velocity and acceleration of each joint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// q_d (rad).
    pub q: [f32; NV],
    /// q̇_d (rad/s).
    pub v: [f32; NV],
    /// q̈_d (rad/s²).
    pub a: [f32; NV],
}

/// What one control tick computes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tick {
    /// The commanded acceleration q̈_d + K_p (q_d − q) + K_d (q̇_d − q̇).
    pub commanded: [f32; NV],
    /// The torques τ = M(q) q̈_cmd + h(q, q̇): the generated inverse dynamics.
    pub tau: [f32; NV],
    /// M(q), armature included: the generated mass matrix.
    pub mass_matrix: [[f32; NV]; NV],
    /// M(q)⁻¹ (τ − h(q, q̇)): the generated forward dynamics under `tau`, which gives back
    /// `commanded` to rounding.
    pub acceleration: [f32; NV],
}

/// One tick of a computed-torque controller at state (q, q̇), in `f32`: no allocation, no
/// branch on data, a fixed amount of work.
#[must_use]
pub fn control_tick(q: &[f32; NV], v: &[f32; NV], target: &Target, gains: &Gains) -> Tick {
    let commanded: [f32; NV] = core::array::from_fn(|i| {
        target.a[i] + gains.kp[i] * (target.q[i] - q[i]) + gains.kd[i] * (target.v[i] - v[i])
    });
    let tau = Arm3::inverse_dynamics(q, v, &commanded);
    Tick {
        commanded,
        tau,
        mass_matrix: Arm3::mass_matrix(q),
        acceleration: Arm3::forward_dynamics(q, v, &tau),
    }
}

/// The state after `dt` seconds under constant torques `tau`: one step of the runtime's
/// RK4 ([`integrators::rk4`]) on the generated forward dynamics, in `f32`.
#[must_use]
pub fn simulate_step(q: &[f32; NV], v: &[f32; NV], tau: &[f32; NV], dt: f32) -> State<f32, Arm3> {
    let state = State::<f32, Arm3> { q: *q, v: *v };
    let inputs = Inputs::<f32, Arm3> {
        tau,
        parameters: &[],
        loads: &[],
    };
    integrators::rk4(&state, &inputs, dt)
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
mod tests;
