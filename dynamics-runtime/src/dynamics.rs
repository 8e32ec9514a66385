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
    /// (∂q̈/∂q, ∂q̈/∂q̇) of [`Dynamics::acceleration`], each `NV × NV` by rows, the q-columns
    /// in the tangent space (a free base's increment in its own frame): the generated
    /// `forward_dynamics_derivatives` when the mechanism asks for that output, `None`
    /// otherwise (the default). The implicit integrators build their Newton Jacobian from
    /// them when they are there.
    fn acceleration_derivatives(
        q: &Self::Configuration,
        v: &Self::Velocity,
        tau: &Self::Velocity,
        parameters: &Self::Parameters,
        loads: &Self::Loads,
    ) -> Option<(Self::Matrix, Self::Matrix)> {
        let _ = (q, v, tau, parameters, loads);
        None
    }
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
    /// (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇) of the generalized momentum p = M(q) q̇ and its rate
    /// ṗ = τ + C(q, q̇)ᵀ q̇ − g(q) + Q − b q̇, each `NV × NV` by rows (∂ṗ/∂τ = 1, so τ is not
    /// an argument): the generated `momentum_derivatives` when the mechanism asks for that
    /// output, `None` otherwise (the default).
    /// [`variational_midpoint`](crate::integrators::variational_midpoint) builds its exact
    /// Newton Jacobian from them when they are there.
    fn momentum_derivatives(
        q: &Self::Configuration,
        v: &Self::Velocity,
        parameters: &Self::Parameters,
        loads: &Self::Loads,
    ) -> Option<(Self::Matrix, Self::Matrix, Self::Matrix)> {
        let _ = (q, v, parameters, loads);
        None
    }
}

/// Why [`try_integrate_configuration`] cannot apply its free-joint table to its arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutError {
    /// `out` does not have the length of `q`.
    OutputLength {
        /// `q.len()`.
        expected: usize,
        /// `out.len()`.
        found: usize,
    },
    /// A free-joint entry (configuration index, velocity index) that does not start a
    /// block of 7 coordinates and 6 velocities where the walk over `q` and `v` reaches it:
    /// out of range, out of increasing order, overlapping the previous free joint, or with a
    /// velocity index that does not match the coordinates before it.
    FreeJoint {
        /// Its configuration index.
        configuration: usize,
        /// Its velocity index.
        velocity: usize,
    },
    /// `q.len()` is not `v.len()` plus one per free joint (each free joint has 7
    /// coordinates and 6 velocities, every other joint one of each).
    CoordinateCount {
        /// `q.len()`.
        configuration: usize,
        /// `v.len()`.
        velocity: usize,
        /// Entries in the free-joint table.
        free_joints: usize,
    },
}

impl core::fmt::Display for LayoutError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            LayoutError::OutputLength { expected, found } => write!(
                f,
                "the output has {found} coordinates, the configuration {expected}"
            ),
            LayoutError::FreeJoint {
                configuration,
                velocity,
            } => write!(
                f,
                "free joint at configuration index {configuration} and velocity index \
                 {velocity} does not fit the arrays (out of range, out of order, overlapping, \
                 or its indices disagree)"
            ),
            LayoutError::CoordinateCount {
                configuration,
                velocity,
                free_joints,
            } => write!(
                f,
                "{configuration} coordinates and {velocity} velocities do not fit \
                 {free_joints} free joints (NQ must be NV + the number of free joints)"
            ),
        }
    }
}

impl core::error::Error for LayoutError {}

/// The configuration reached from `q` by moving with velocity `v` for `dt`, written into
/// `out`: joint coordinates advance by `v dt`; a free joint (its first configuration index
/// and first velocity index in `free_joints`, in increasing order) moves its origin by
/// `R v_lin dt` and turns its quaternion by the body-frame rotation `ω dt` through the
/// Cayley map `q ⊗ (ω dt/2, 1)`, normalized: branch-free, second-order accurate in the
/// angle, and unit-norm to rounding at every step, so the quaternion stays on the manifold
/// however long the run.
///
/// The table and the arrays are checked first, and `out` is left untouched when they
/// disagree ([`LayoutError`]): `out.len() == q.len()`, every free joint a block of 7
/// coordinates and 6 velocities at matching places, `q.len() == v.len() + free_joints.len()`.
pub fn try_integrate_configuration<T: Scalar>(
    q: &[T],
    v: &[T],
    dt: T,
    free_joints: &[(usize, usize)],
    out: &mut [T],
) -> Result<(), LayoutError> {
    check_layout(q.len(), v.len(), free_joints, out.len())?;
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
    Ok(())
}

/// [`try_integrate_configuration`] for arrays and a free-joint table that agree, as the
/// generated `Dynamics::integrate` passes them (`[T; NQ]`, `[T; NV]`, its own free joints):
/// the form generated code calls.
///
/// # Panics
///
/// If the table and the arrays disagree (the [`LayoutError`] cases), which generated code
/// cannot cause; call [`try_integrate_configuration`] with tables built at run time.
pub fn integrate_configuration<T: Scalar>(
    q: &[T],
    v: &[T],
    dt: T,
    free_joints: &[(usize, usize)],
    out: &mut [T],
) {
    if let Err(e) = try_integrate_configuration(q, v, dt, free_joints, out) {
        panic!("integrate_configuration: {e}");
    }
}

/// The checks of [`try_integrate_configuration`], on lengths and the table alone.
fn check_layout(
    nq: usize,
    nv: usize,
    free_joints: &[(usize, usize)],
    out: usize,
) -> Result<(), LayoutError> {
    if out != nq {
        return Err(LayoutError::OutputLength {
            expected: nq,
            found: out,
        });
    }
    let (mut k_q, mut k_v) = (0, 0);
    let mut joints = free_joints.iter().peekable();
    while k_q < nq && k_v < nv {
        if let Some(&(fq, fv)) = joints.next_if(|&&(fq, _)| fq == k_q) {
            if fv != k_v || fq + 7 > nq || fv + 6 > nv {
                return Err(LayoutError::FreeJoint {
                    configuration: fq,
                    velocity: fv,
                });
            }
            k_q += 7;
            k_v += 6;
        } else {
            k_q += 1;
            k_v += 1;
        }
    }
    if let Some(&&(configuration, velocity)) = joints.peek() {
        return Err(LayoutError::FreeJoint {
            configuration,
            velocity,
        });
    }
    if k_q != nq || k_v != nv {
        return Err(LayoutError::CoordinateCount {
            configuration: nq,
            velocity: nv,
            free_joints: free_joints.len(),
        });
    }
    Ok(())
}

/// The rotation body → parent of a unit quaternion (x, y, z, w), scalar last, as rows. The
/// one formula of the runtime: the reference's `quaternion_rotation` is this matrix.
pub(crate) fn quaternion_rotation_rows<T: Scalar>(x: T, y: T, z: T, w: T) -> [[T; 3]; 3] {
    let one = T::one();
    let two = one + one;
    [
        [
            one - two * (y * y + z * z),
            two * (x * y - z * w),
            two * (x * z + y * w),
        ],
        [
            two * (x * y + z * w),
            one - two * (x * x + z * z),
            two * (y * z - x * w),
        ],
        [
            two * (x * z - y * w),
            two * (y * z + x * w),
            one - two * (x * x + y * y),
        ],
    ]
}

/// R(x, y, z, w) v dt: each row's sum in the order of nalgebra's matrix-vector product
/// (column 0 first), then scaled by `dt`, with or without std; for `f64` bit for bit the
/// nalgebra product this runtime computed before it had a no_std build (`matches_nalgebra`).
fn rotate_and_scale<T: Scalar>(x: T, y: T, z: T, w: T, v: [T; 3], dt: T) -> [T; 3] {
    let r = quaternion_rotation_rows(x, y, z, w);
    core::array::from_fn(|i| (r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2]) * dt)
}

/// One free joint: position += R(quat) v_lin dt; quat ← quat ⊗ Cayley(ω dt).
fn free_joint_step<T: Scalar>(q: &[T], v: &[T], dt: T, out: &mut [T]) {
    let (x, y, z, w) = (q[3], q[4], q[5], q[6]);
    let two = T::from_f64(2.0);
    let one = T::one();
    let moved = rotate_and_scale(x, y, z, w, [v[0], v[1], v[2]], dt);
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

    /// The rotation of a free joint's displacement against the same matrix times an nalgebra
    /// vector (how the runtime computed it before its no_std build), bit for bit in f64 on
    /// 10 000 random unit quaternions, velocities and steps.
    #[cfg(feature = "std")]
    #[test]
    fn matches_nalgebra() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..10_000 {
            let quat = [next(), next(), next(), next()];
            let norm = quat.iter().map(|c| c * c).sum::<f64>().sqrt();
            let [x, y, z, w] = quat.map(|c| c / norm);
            let v = [next() * 3.0, next(), next() * 0.1];
            let dt = next().abs() * 0.01;
            let by_hand = rotate_and_scale(x, y, z, w, v, dt);
            let rows = quaternion_rotation_rows(x, y, z, w);
            let r = nalgebra::Matrix3::from_fn(|i, j| rows[i][j]);
            let with_nalgebra: [f64; 3] =
                (r * nalgebra::Vector3::new(v[0], v[1], v[2]) * dt).into();
            assert_eq!(
                by_hand.map(f64::to_bits),
                with_nalgebra.map(f64::to_bits),
                "q = {:?}, v = {v:?}, dt = {dt}",
                [x, y, z, w]
            );
        }
    }

    #[test]
    fn joint_coordinates_advance_linearly() {
        let mut out = [0.0; 3];
        integrate_configuration(&[1.0, 2.0, 3.0], &[0.5, -1.0, 2.0], 0.1, &[], &mut out);
        assert_eq!(out, [1.05, 1.9, 3.2]);
    }

    use nalgebra::{Quaternion, UnitQuaternion, Vector3};

    /// The quaternion of a configuration, `[x, y, z, w]` from index `at`.
    fn quaternion(q: &[f64], at: usize) -> UnitQuaternion<f64> {
        UnitQuaternion::new_unchecked(Quaternion::new(q[at + 3], q[at], q[at + 1], q[at + 2]))
    }

    /// exp(ω t / 2) = (sin(|ω| t / 2) ω/|ω|, cos(|ω| t / 2)): a turn by |ω| t about ω.
    fn exp_half(omega: Vector3<f64>, t: f64) -> UnitQuaternion<f64> {
        let half = omega.norm() * t / 2.0;
        let u = omega.normalize() * half.sin();
        UnitQuaternion::new_unchecked(Quaternion::new(half.cos(), u.x, u.y, u.z))
    }

    /// ∫₀ᵀ exp([ω]× t) dt = T·1 + (1 − cos θ)/|ω|² [ω]× + (θ − sin θ)/|ω|³ [ω]×², θ = |ω| T:
    /// the displacement, in the initial body frame, of a body moving with constant body
    /// velocity v and angular velocity ω for a time T is this times v.
    fn turning_displacement(omega: Vector3<f64>, v: Vector3<f64>, t: f64) -> Vector3<f64> {
        let w = omega.norm();
        let theta = w * t;
        let k = omega.cross_matrix();
        (nalgebra::Matrix3::identity() * t
            + k * ((1.0 - theta.cos()) / (w * w))
            + k * k * ((theta - theta.sin()) / (w * w * w)))
            * v
    }

    #[test]
    fn free_joint_moves_as_the_closed_form_of_a_constant_twist() {
        // A free joint turned away from the identity, then a joint coordinate; constant
        // body twist (v, ω) and joint rate 0.5 for 1000 steps of 1 ms (T = 1 s).
        let start = UnitQuaternion::from_scaled_axis(Vector3::new(0.4, -0.9, 0.3));
        let p0 = Vector3::new(0.2, -0.1, 1.5);
        let mut q = [0.0_f64; 8];
        q[..3].copy_from_slice(p0.as_slice());
        q[3..7].copy_from_slice(start.coords.as_slice());
        q[7] = 0.3;
        let v_lin = Vector3::new(1.0, -0.5, 0.25);
        let omega = Vector3::new(0.6, -1.2, 0.9);
        let rate = 0.5;
        let mut v = [0.0_f64; 7];
        v[..3].copy_from_slice(v_lin.as_slice());
        v[3..6].copy_from_slice(omega.as_slice());
        v[6] = rate;
        let (dt, steps) = (1e-3, 1000);
        let t = dt * steps as f64;

        // One step: the documented Cayley map turns by 2 atan(|ω| dt / 2) about ω, which is
        // exp(ω dt / 2) to within (|ω| dt)³ / 12 in angle; the origin moves by R(q) v dt.
        let mut out = q;
        integrate_configuration(&q, &v, dt, &[(0, 0)], &mut out);
        let one_step = quaternion(&out, 3).angle_to(&(start * exp_half(omega, dt)));
        let cayley_bound = (omega.norm() * dt).powi(3) / 12.0;
        assert!(
            one_step <= cayley_bound * 1.01 + 1e-15,
            "{one_step:e} > {cayley_bound:e}"
        );
        let moved = Vector3::new(out[0], out[1], out[2]) - p0;
        let expected = start * v_lin * dt;
        assert!((moved - expected).amax() <= 1e-15, "{moved} vs {expected}");
        assert!((out[7] - (0.3 + rate * dt)).abs() <= 1e-15, "{}", out[7]);

        for _ in 0..steps {
            integrate_configuration(&q, &v, dt, &[(0, 0)], &mut out);
            q = out;
        }
        // Orientation: q0 ⊗ exp(ω T / 2); the per-step Cayley errors add up along the one
        // axis, to steps · (|ω| dt)³ / 12 = 3.1e-7 rad, against a turn of 1.6 rad.
        let turned = quaternion(&q, 3);
        let norm = turned.coords.norm();
        assert!((norm - 1.0).abs() < 1e-15, "unit norm drifted to {norm}");
        let angle_error = turned.angle_to(&(start * exp_half(omega, t)));
        let bound = steps as f64 * cayley_bound;
        assert!(angle_error <= bound * 1.01, "{angle_error:e} > {bound:e}");
        // Position: p0 + R0 ∫ exp([ω]× t) dt v; the step is first order (the origin moves
        // along R at the start of each step), its error at most |ω| |v| T dt / 2.
        let position = Vector3::new(q[0], q[1], q[2]);
        let exact = p0 + start * turning_displacement(omega, v_lin, t);
        let position_bound = omega.norm() * v_lin.norm() * t * dt / 2.0;
        let position_error = (position - exact).norm();
        assert!(
            position_error <= position_bound,
            "{position} vs {exact}: {position_error:e} > {position_bound:e}"
        );
        // The joint coordinate after the free joint: 0.3 + 0.5 T.
        assert!((q[7] - (0.3 + rate * t)).abs() < 1e-12, "{}", q[7]);
    }

    #[test]
    fn an_inconsistent_layout_is_an_error_and_leaves_out_untouched() {
        let q = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.3];
        let v = [0.0; 7];
        let try_with = |free: &[(usize, usize)], out_len: usize| {
            let mut out = [f64::NAN; 9];
            let r = try_integrate_configuration(&q, &v, 1e-3, free, &mut out[..out_len]);
            if r.is_err() {
                assert!(out.iter().all(|x| x.is_nan()), "out written on error");
            }
            r
        };
        assert_eq!(try_with(&[(0, 0)], 8), Ok(()));
        // Used to panic: "range end index 9 out of range" past the end of q.
        assert_eq!(
            try_with(&[(2, 2)], 8),
            Err(LayoutError::FreeJoint {
                configuration: 2,
                velocity: 2
            })
        );
        // A short output buffer used to panic in copy_from_slice.
        assert_eq!(
            try_with(&[(0, 0)], 7),
            Err(LayoutError::OutputLength {
                expected: 8,
                found: 7
            })
        );
        // A velocity index that disagrees with the coordinates before it.
        assert_eq!(
            try_with(&[(0, 1)], 8),
            Err(LayoutError::FreeJoint {
                configuration: 0,
                velocity: 1
            })
        );
        // A free joint the walk never reaches used to be silently treated as joint
        // coordinates.
        assert_eq!(
            try_with(&[(0, 0), (20, 20)], 8),
            Err(LayoutError::FreeJoint {
                configuration: 20,
                velocity: 20
            })
        );
        // No free joint: 8 coordinates and 7 velocities do not match.
        assert_eq!(
            try_with(&[], 8),
            Err(LayoutError::CoordinateCount {
                configuration: 8,
                velocity: 7,
                free_joints: 0
            })
        );
    }

    #[test]
    #[should_panic(expected = "integrate_configuration: free joint at configuration index 2")]
    fn the_infallible_form_panics_with_the_reason() {
        let mut out = [0.0; 8];
        integrate_configuration(&[0.0; 8], &[0.0; 7], 1e-3, &[(2, 2)], &mut out);
    }
}
