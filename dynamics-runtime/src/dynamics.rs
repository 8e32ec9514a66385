//! The generated dynamics behind traits, so that integrators, controllers and checks can be
//! written once for every mechanism and every scalar, without allocation.
//!
//! `mechanism!` implements [`Dynamics`] for every scalar when it generates forward
//! dynamics, [`Energy`] when it generates the energies, and [`Lagrangian`] when it generates
//! M(q), C(q, q̇) and g(q) too, the terms of M(q) q̈ + C(q, q̇) q̇ + g(q) = τ + Q − b q̇. The
//! associated types are the fixed-size arrays the generated functions take (`[T; NQ]`,
//! `[T; NV]`, ...).

use crate::mechanism::Mechanism;
use crate::scalar::Scalar;

/// Forward dynamics and configuration update of a generated mechanism.
pub trait Dynamics<T: Scalar>: Mechanism {
    /// The configuration q, `[T; NQ]`.
    type Configuration: Copy + AsRef<[T]> + AsMut<[T]>;
    /// A velocity, acceleration or generalized force, `[T; NV]`.
    type Velocity: Copy + AsRef<[T]> + AsMut<[T]>;
    /// The symbolic parameters p, `[T; NUM_PARAMETERS]`.
    type Parameters: Copy + AsRef<[T]>;
    /// The applied loads, `[T; NUM_LOAD_INPUTS]`.
    type Loads: Copy + AsRef<[T]> + AsMut<[T]>;
    /// An `NV × NV` matrix by rows, `[[T; NV]; NV]` (for implicit integrators' Jacobians).
    type Matrix: Copy + AsRef<[Self::Velocity]> + AsMut<[Self::Velocity]>;

    /// The zero velocity (also the zero force).
    fn zero_velocity() -> Self::Velocity;
    /// No applied loads.
    fn zero_loads() -> Self::Loads;
    /// The zero `NV × NV` matrix.
    fn zero_matrix() -> Self::Matrix;
    /// The parameters at their declared nominal values.
    fn nominal_parameters() -> Self::Parameters;
    /// The neutral configuration: zero joint coordinates, identity base orientation.
    fn neutral_configuration() -> Self::Configuration;
    /// q̈ = M(q)⁻¹ (τ + Q − C(q, q̇) q̇ − g(q) − b q̇): the generated forward dynamics.
    fn acceleration(
        q: &Self::Configuration,
        v: &Self::Velocity,
        tau: &Self::Velocity,
        parameters: &Self::Parameters,
        loads: &Self::Loads,
    ) -> Self::Velocity;
    /// Where a step `dt` along velocity `v` leads from `q` (see [`integrate_configuration`]).
    fn integrate(q: &Self::Configuration, v: &Self::Velocity, dt: T) -> Self::Configuration;
}

/// Kinetic plus potential energy of a generated mechanism.
pub trait Energy<T: Scalar>: Dynamics<T> {
    /// T(q, q̇) + V(q).
    fn total_energy(
        q: &Self::Configuration,
        v: &Self::Velocity,
        parameters: &Self::Parameters,
    ) -> T;
}

/// The terms of the Lagrangian L(q, q̇) = ½ q̇ᵀ M(q) q̇ − V(q) of a generated mechanism and
/// of its equations of motion M(q) q̈ + C(q, q̇) q̇ + g(q) = τ + Q − b q̇, for variational
/// integrators.
///
/// C is the Christoffel-consistent Coriolis matrix (Ṁ − 2C skew-symmetric) and g = ∂V/∂q,
/// so ∂L/∂q̇ = M(q) q̇ and ∂L/∂q = C(q, q̇)ᵀ q̇ − g(q) (see
/// [`integrators::variational_midpoint`](crate::integrators::variational_midpoint)). For a
/// free joint the velocity is the body-frame twist, not the derivative of the quaternion
/// coordinates, and the second identity does not hold for those coordinates.
pub trait Lagrangian<T: Scalar>: Dynamics<T> {
    /// M(q), symmetric positive definite, armature on the diagonal.
    fn mass_matrix(q: &Self::Configuration, parameters: &Self::Parameters) -> Self::Matrix;
    /// C(q, q̇) with Ṁ − 2C skew-symmetric: C(q, q̇) q̇ is the Coriolis and centrifugal force.
    fn coriolis_matrix(
        q: &Self::Configuration,
        v: &Self::Velocity,
        parameters: &Self::Parameters,
    ) -> Self::Matrix;
    /// g(q) = ∂V/∂q, the joint forces that hold the mechanism still at q.
    fn gravity(q: &Self::Configuration, parameters: &Self::Parameters) -> Self::Velocity;
}

/// The configuration reached from `q` by moving with velocity `v` for `dt`, written into
/// `out`: joint coordinates advance by `v dt`; a free joint (its first configuration index
/// and first velocity index in `free_joints`) moves its origin by `R v_lin dt` and turns its
/// quaternion by the body-frame rotation `ω dt` through the Cayley map
/// `q ⊗ (ω dt/2, 1)`, normalized: branch-free, second-order accurate in the angle, and
/// unit-norm to rounding at every step, so the quaternion stays on the manifold however
/// long the run.
pub fn integrate_configuration<T: Scalar>(
    q: &[T],
    v: &[T],
    dt: T,
    free_joints: &[(usize, usize)],
    out: &mut [T],
) {
    out.copy_from_slice(q);
    // Joint coordinates: q_k += v_k dt, for every coordinate outside a free joint.
    let mut k_q = 0;
    let mut k_v = 0;
    let mut joints = free_joints.iter().peekable();
    while k_q < q.len() && k_v < v.len() {
        if let Some(&(fq, fv)) = joints.next_if(|&&(fq, _)| fq == k_q) {
            free_joint_step(&q[fq..fq + 7], &v[fv..fv + 6], dt, &mut out[fq..fq + 7]);
            k_q += 7;
            k_v += 6;
            continue;
        }
        out[k_q] = q[k_q] + v[k_v] * dt;
        k_q += 1;
        k_v += 1;
    }
}

/// One free joint: position += R(quat) v_lin dt; quat ← quat ⊗ Cayley(ω dt).
fn free_joint_step<T: Scalar>(q: &[T], v: &[T], dt: T, out: &mut [T]) {
    let (x, y, z, w) = (q[3], q[4], q[5], q[6]);
    let two = T::from_f64(2.0);
    let one = T::one();
    let r = crate::reference::quaternion_rotation(x, y, z, w);
    let moved = r * nalgebra::Vector3::new(v[0], v[1], v[2]) * dt;
    for i in 0..3 {
        out[i] = q[i] + moved[i];
    }
    // quat ⊗ (ω dt / 2, 1), then normalized: the Cayley map, with the rounding of each step
    // projected away so the norm cannot drift over long runs.
    let half = dt / two;
    let (a, b, c) = (v[3] * half, v[4] * half, v[5] * half);
    let product = [
        w * a + x + y * c - z * b,
        w * b - x * c + y + z * a,
        w * c + x * b - y * a + z,
        w - x * a - y * b - z * c,
    ];
    let inv = one / product.iter().fold(T::zero(), |acc, &p| acc + p * p).sqrt();
    for (o, p) in out[3..7].iter_mut().zip(product) {
        *o = p * inv;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joint_coordinates_advance_linearly() {
        let mut out = [0.0; 3];
        integrate_configuration(&[1.0, 2.0, 3.0], &[0.5, -1.0, 2.0], 0.1, &[], &mut out);
        assert_eq!(out, [1.05, 1.9, 3.2]);
    }

    #[test]
    fn free_joint_turns_on_the_manifold() {
        // Spin about z at 1 rad/s for 1000 steps of 1 ms: the quaternion stays unit and the
        // angle reached is 1 rad to second order per step.
        let mut q: [f64; 8] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.3];
        let v: [f64; 7] = [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0];
        let mut out = q;
        for _ in 0..1000 {
            integrate_configuration(&q, &v, 1e-3, &[(0, 0)], &mut out);
            q = out;
        }
        let norm = (q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]).sqrt();
        assert!((norm - 1.0).abs() < 1e-15, "{norm}");
        let angle = 2.0 * q[5].atan2(q[6]);
        assert!((angle - 1.0).abs() < 1e-6, "{angle}");
        // Moving along body x while turning: the origin traces the unit circle's arc.
        assert!(
            (q[0] - 1.0_f64.sin()).abs() < 1e-3 && (q[1] - (1.0 - 1.0_f64.cos())).abs() < 1e-3,
            "{q:?}"
        );
        // The coordinate after the free joint advanced by v dt.
        assert!((q[7] - 0.3).abs() < 1e-15);
    }
}
