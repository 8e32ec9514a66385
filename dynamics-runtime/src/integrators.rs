//! Time integration of M(q) q̈ + C(q, q̇) q̇ + g(q) = τ + Q, generic over every generated
//! mechanism ([`Dynamics`]) and scalar, without allocation.
//!
//! With a(q, v) the generated forward dynamics and q ⊕ v dt the configuration update of
//! [`Dynamics::integrate`] (free-joint quaternions stay on the unit sphere):
//!
//! ```text
//! explicit Euler        q' = q ⊕ v dt,          v' = v + a(q, v) dt
//! semi-implicit Euler   v' = v + a(q, v) dt,    q' = q ⊕ v' dt
//! RK4                   the classical four stages on (q, v), stages combined in v
//! implicit midpoint     v' = v + a(q ⊕ v̄ dt/2, v̄) dt, q' = q ⊕ v̄ dt,  v̄ = (v + v')/2
//! variational midpoint  p  = M(q̄) v̄ − h/2 (C(q̄, v̄)ᵀ v̄ − g(q̄) + F(q̄, v̄)),
//!                       p' = M(q̄) v̄ + h/2 (C(q̄, v̄)ᵀ v̄ − g(q̄) + F(q̄, v̄)),
//!                       q̄ = (q + q')/2, v̄ = (q' − q)/h, p = M(q) v, F = τ + Q − b v̄
//! ```
//!
//! The implicit midpoint rule is symmetric and A-stable, but symplectic only where M is
//! constant; so is semi-implicit Euler in (q, q̇). The variational midpoint rule is the
//! discrete Euler–Lagrange equation of L_d(q, q') = h L(q̄, v̄): its map (q, p) → (q', p')
//! is symplectic for any configuration-dependent M(q), so the energy error stays bounded
//! over arbitrarily long conservative runs and momenta of symmetries are conserved.
//! The implicit schemes solve their nonlinear equation by Newton's method, at most
//! `max_iterations` times, and a step that does not converge (or meets a non-finite value)
//! is an error, not a silent result.

use crate::dynamics::{Dynamics, Lagrangian};
pub use crate::scalar::Real;
use crate::scalar::{abs, Scalar};
use core::fmt;

/// A mechanism's state: configuration and velocity.
pub struct State<T: Scalar, M: Dynamics<T>> {
    /// q.
    pub q: M::Configuration,
    /// q̇.
    pub v: M::Velocity,
}

impl<T: Scalar, M: Dynamics<T>> Clone for State<T, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T: Scalar, M: Dynamics<T>> Copy for State<T, M> {}

/// What drives a step: joint forces, parameters and applied loads, constant over the step.
pub struct Inputs<'a, T: Scalar, M: Dynamics<T>> {
    /// τ.
    pub tau: &'a M::Velocity,
    /// p.
    pub parameters: &'a M::Parameters,
    /// Q's inputs.
    pub loads: &'a M::Loads,
}

fn axpy<T: Scalar, V: AsRef<[T]> + AsMut<[T]> + Copy>(x: &V, a: T, y: &V) -> V {
    let mut out = *x;
    for ((o, &xi), &yi) in out.as_mut().iter_mut().zip(x.as_ref()).zip(y.as_ref()) {
        *o = xi + a * yi;
    }
    out
}

fn acceleration<T: Scalar, M: Dynamics<T>>(
    q: &M::Configuration,
    v: &M::Velocity,
    inputs: &Inputs<T, M>,
) -> M::Velocity {
    M::acceleration(q, v, inputs.tau, inputs.parameters, inputs.loads)
}

/// One explicit (forward) Euler step.
pub fn explicit_euler<T: Scalar, M: Dynamics<T>>(
    s: &State<T, M>,
    inputs: &Inputs<T, M>,
    dt: T,
) -> State<T, M> {
    let a = acceleration(&s.q, &s.v, inputs);
    State {
        q: M::integrate(&s.q, &s.v, dt),
        v: axpy(&s.v, dt, &a),
    }
}

/// One semi-implicit (symplectic) Euler step: velocity first, then position with the new
/// velocity.
pub fn semi_implicit_euler<T: Scalar, M: Dynamics<T>>(
    s: &State<T, M>,
    inputs: &Inputs<T, M>,
    dt: T,
) -> State<T, M> {
    let v = axpy(&s.v, dt, &acceleration(&s.q, &s.v, inputs));
    State {
        q: M::integrate(&s.q, &v, dt),
        v,
    }
}

/// One classical Runge–Kutta step (fourth order for joint coordinates; the configuration
/// update of free joints follows the stages' velocities).
pub fn rk4<T: Scalar, M: Dynamics<T>>(
    s: &State<T, M>,
    inputs: &Inputs<T, M>,
    dt: T,
) -> State<T, M> {
    let half = dt * T::from_f64(0.5);
    let (q1, v1) = (s.q, s.v);
    let a1 = acceleration(&q1, &v1, inputs);
    let q2 = M::integrate(&s.q, &v1, half);
    let v2 = axpy(&s.v, half, &a1);
    let a2 = acceleration(&q2, &v2, inputs);
    let q3 = M::integrate(&s.q, &v2, half);
    let v3 = axpy(&s.v, half, &a2);
    let a3 = acceleration(&q3, &v3, inputs);
    let q4 = M::integrate(&s.q, &v3, dt);
    let v4 = axpy(&s.v, dt, &a3);
    let a4 = acceleration(&q4, &v4, inputs);
    let sixth = T::from_f64(1.0 / 6.0);
    let two = T::from_f64(2.0);
    let mut v_mean = v1;
    let mut a_mean = a1;
    for k in 0..v_mean.as_ref().len() {
        v_mean.as_mut()[k] =
            (v1.as_ref()[k] + two * (v2.as_ref()[k] + v3.as_ref()[k]) + v4.as_ref()[k]) * sixth;
        a_mean.as_mut()[k] =
            (a1.as_ref()[k] + two * (a2.as_ref()[k] + a3.as_ref()[k]) + a4.as_ref()[k]) * sixth;
    }
    State {
        q: M::integrate(&s.q, &v_mean, dt),
        v: axpy(&s.v, dt, &a_mean),
    }
}

/// Why an implicit step failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepError {
    /// The fixed-point iteration did not reach the tolerance within the iteration bound.
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// The last change of the velocity (max norm).
        last_change: f64,
    },
    /// A non-finite value appeared (the dynamics blew up or were singular).
    NonFinite,
    /// The variational midpoint rule was given a mechanism with a free joint (NQ ≠ NV): its
    /// quaternion coordinates are not a vector space and its velocity is not their time
    /// derivative, so the midpoint (q + q')/2 and the difference quotient (q' − q)/h mean
    /// nothing there. Use [`implicit_midpoint`] or [`rk4`] for free-floating mechanisms.
    FreeJoint,
    /// An argument outside its domain (checked before any work): the step `dt` and the
    /// `tolerance` must be finite and positive, `max_iterations` at least 1. `what` names
    /// the argument and its domain.
    InvalidArgument {
        /// The argument and what it must be, e.g. "dt must be finite and positive".
        what: &'static str,
    },
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::NotConverged { iterations, last_change } => write!(
                f,
                "implicit step did not converge in {iterations} iterations (last change {last_change:e}); reduce the step"
            ),
            StepError::NonFinite => write!(f, "implicit step produced a non-finite value"),
            StepError::FreeJoint => write!(
                f,
                "the variational midpoint rule works in joint coordinates; a free joint's quaternion is not one (use implicit_midpoint or rk4)"
            ),
            StepError::InvalidArgument { what } => write!(f, "invalid argument: {what}"),
        }
    }
}

impl core::error::Error for StepError {}

/// One implicit midpoint step: the end velocity w solves
/// F(w) = w − v − dt · a(q ⊕ v̄ dt/2, v̄) = 0 with v̄ = (v + w)/2, by Newton's method and
/// Gaussian elimination with partial pivoting, until the Newton update is below `tolerance`
/// (max norm), at most `max_iterations` times. Newton converges on stiff problems, where a
/// fixed-point iteration would diverge.
///
/// The Jacobian J = ∂F/∂w = 1 − dt (¼ dt ∂a/∂q + ½ ∂a/∂q̇), at the midpoint, is exact when
/// the mechanism generates `forward_dynamics_derivatives`
/// ([`Dynamics::acceleration_derivatives`]; for a free base it takes the tangent of q ⊕ δ
/// as δ, an error of order dt |ω| that Newton's method absorbs), and by forward differences
/// otherwise (one extra dynamics evaluation per coordinate).
///
/// Errors: [`StepError::InvalidArgument`] unless `dt` and `tolerance` are finite and
/// positive and `max_iterations` ≥ 1; [`StepError::NonFinite`] when a NaN or infinite value
/// appears; [`StepError::NotConverged`] after `max_iterations` updates above `tolerance`.
pub fn implicit_midpoint<M: Dynamics<f64>>(
    s: &State<f64, M>,
    inputs: &Inputs<f64, M>,
    dt: f64,
    tolerance: f64,
    max_iterations: usize,
) -> Result<State<f64, M>, StepError> {
    check_arguments(dt, tolerance, max_iterations)?;
    let midpoint = |w: &M::Velocity| {
        let mut v_mid = s.v;
        for (m, (&a, &b)) in v_mid
            .as_mut()
            .iter_mut()
            .zip(s.v.as_ref().iter().zip(w.as_ref()))
        {
            *m = 0.5 * (a + b);
        }
        v_mid
    };
    // F(w), and the midpoint state (q ⊕ v̄ dt/2, v̄) it was evaluated at.
    let residual = |w: &M::Velocity| {
        let v_mid = midpoint(w);
        let q_mid = M::integrate(&s.q, &v_mid, 0.5 * dt);
        let a = acceleration(&q_mid, &v_mid, inputs);
        let mut f = *w;
        for (k, fk) in f.as_mut().iter_mut().enumerate() {
            *fk = w.as_ref()[k] - s.v.as_ref()[k] - dt * a.as_ref()[k];
        }
        (f, q_mid, v_mid)
    };
    // Start from the explicit Euler guess.
    let mut w = axpy(&s.v, dt, &acceleration(&s.q, &s.v, inputs));
    let mut last_change = f64::INFINITY;
    for _ in 0..max_iterations {
        let (f, q_mid, v_mid) = residual(&w);
        let n = f.as_ref().len();
        let exact = M::acceleration_derivatives(
            &q_mid,
            &v_mid,
            inputs.tau,
            inputs.parameters,
            inputs.loads,
        );
        let mut jacobian = M::zero_matrix();
        if let Some((by_q, by_v)) = exact {
            for i in 0..n {
                for k in 0..n {
                    let da_dw = 0.25 * dt * by_q.as_ref()[i].as_ref()[k]
                        + 0.5 * by_v.as_ref()[i].as_ref()[k];
                    let identity = if i == k { 1.0 } else { 0.0 };
                    jacobian.as_mut()[i].as_mut()[k] = identity - dt * da_dw;
                }
            }
        } else {
            for k in 0..n {
                let h = 1e-7 * (1.0 + w.as_ref()[k].abs());
                let mut shifted = w;
                shifted.as_mut()[k] += h;
                let (f_shifted, _, _) = residual(&shifted);
                for i in 0..n {
                    jacobian.as_mut()[i].as_mut()[k] = (f_shifted.as_ref()[i] - f.as_ref()[i]) / h;
                }
            }
        }
        let mut step = f;
        solve_in_place(jacobian.as_mut(), step.as_mut()).ok_or(StepError::NonFinite)?;
        last_change = max_norm(step.as_ref());
        for (wk, dk) in w.as_mut().iter_mut().zip(step.as_ref()) {
            *wk -= dk;
        }
        if !last_change.is_finite() {
            return Err(StepError::NonFinite);
        }
        if last_change <= tolerance {
            let v_mid = midpoint(&w);
            return Ok(State {
                q: M::integrate(&s.q, &v_mid, dt),
                v: w,
            });
        }
    }
    Err(StepError::NotConverged {
        iterations: max_iterations,
        last_change,
    })
}

/// max_k |x_k|, NaN if an entry is NaN (a plain `>` or `f64::max` would pass NaN over and
/// let a convergence test succeed on it).
fn max_norm<T: Real>(x: &[T]) -> T {
    let mut m = T::zero();
    for &xi in x {
        let a = abs(xi);
        if a.partial_cmp(&a).is_none() {
            return a;
        }
        if a > m {
            m = a;
        }
    }
    m
}

/// The common preconditions of the implicit steps: `dt` and `tolerance` finite and positive,
/// at least one iteration.
fn check_arguments<T: Real>(dt: T, tolerance: T, max_iterations: usize) -> Result<(), StepError> {
    let positive = |x: T| x.to_f64().is_finite() && x > T::zero();
    if !positive(dt) {
        Err(StepError::InvalidArgument {
            what: "the step dt must be finite and positive",
        })
    } else if !positive(tolerance) {
        Err(StepError::InvalidArgument {
            what: "the tolerance must be finite and positive",
        })
    } else if max_iterations == 0 {
        Err(StepError::InvalidArgument {
            what: "max_iterations must be at least 1",
        })
    } else {
        Ok(())
    }
}

/// A x, for an `NV × NV` matrix stored by rows.
fn mat_vec<T: Scalar, M: Dynamics<T>>(a: &M::Matrix, x: &M::Velocity) -> M::Velocity {
    let mut out = *x;
    for (o, row) in out.as_mut().iter_mut().zip(a.as_ref()) {
        *o = row
            .as_ref()
            .iter()
            .zip(x.as_ref())
            .fold(T::zero(), |acc, (&r, &xi)| acc + r * xi);
    }
    out
}

/// Aᵀ x, for an `NV × NV` matrix stored by rows.
fn mat_t_vec<T: Scalar, M: Dynamics<T>>(a: &M::Matrix, x: &M::Velocity) -> M::Velocity {
    let mut out = M::zero_velocity();
    for (row, &xi) in a.as_ref().iter().zip(x.as_ref()) {
        for (o, &r) in out.as_mut().iter_mut().zip(row.as_ref()) {
            *o += r * xi;
        }
    }
    out
}

/// The discrete momenta at both ends of the step from `q` to `q + h w` (w = v̄, the mean
/// velocity), with the forces of the discrete Lagrange–d'Alembert principle:
/// `(−D₁L_d − f⁻, D₂L_d + f⁺) = M(q̄) w ∓ h/2 (C(q̄, w)ᵀ w − g(q̄) + F(q̄, w))`, q̄ = q + w h/2.
///
/// The non-conservative force F = τ + Q − b w is read off the generated forward dynamics as
/// F = M(q̄) q̈ + C(q̄, w) w + g(q̄), q̈ = a(q̄, w): exact, and every force the mechanism
/// declares (joint forces, damping, applied loads) enters without code of its own.
fn discrete_momenta<T: Scalar, M: Lagrangian<T>>(
    q: &M::Configuration,
    w: &M::Velocity,
    inputs: &Inputs<T, M>,
    h: T,
) -> (M::Velocity, M::Velocity) {
    let half_h = h * T::from_f64(0.5);
    let q_mid = M::integrate(q, w, half_h);
    let mass = M::mass_matrix(&q_mid, inputs.parameters);
    let coriolis = M::coriolis_matrix(&q_mid, w, inputs.parameters);
    let gravity = M::gravity(&q_mid, inputs.parameters);
    let qdd = acceleration(&q_mid, w, inputs);
    let (momentum, m_qdd) = (mat_vec::<T, M>(&mass, w), mat_vec::<T, M>(&mass, &qdd));
    let (c_w, ct_w) = (
        mat_vec::<T, M>(&coriolis, w),
        mat_t_vec::<T, M>(&coriolis, w),
    );
    let (mut before, mut after) = (momentum, momentum);
    for k in 0..momentum.as_ref().len() {
        let dl_dq = ct_w.as_ref()[k] - gravity.as_ref()[k];
        let force = m_qdd.as_ref()[k] + c_w.as_ref()[k] + gravity.as_ref()[k];
        let impulse = half_h * (dl_dq + force);
        before.as_mut()[k] -= impulse;
        after.as_mut()[k] += impulse;
    }
    (before, after)
}

/// One step of the midpoint variational integrator, symplectic for a configuration-dependent
/// mass matrix: the discrete Euler–Lagrange equations of
/// `L_d(q₀, q₁) = h L((q₀ + q₁)/2, (q₁ − q₀)/h)` in position–momentum form,
///
/// ```text
/// p₀ = −D₁L_d(q₀, q₁) − f⁻ = M(q̄) v̄ − h/2 (C(q̄, v̄)ᵀ v̄ − g(q̄) + F(q̄, v̄))   (solved for q₁)
/// p₁ =  D₂L_d(q₀, q₁) + f⁺ = M(q̄) v̄ + h/2 (C(q̄, v̄)ᵀ v̄ − g(q̄) + F(q̄, v̄))
/// q̄ = (q₀ + q₁)/2,  v̄ = (q₁ − q₀)/h,  F = τ + Q − b v̄,  f⁻ = f⁺ = h/2 F(q̄, v̄)
/// ```
///
/// with ∂L/∂q̇ = M(q) q̇ and ∂L/∂q = C(q, q̇)ᵀ q̇ − g(q) for L = ½ q̇ᵀ M q̇ − V. Proof of the
/// second, in one line: Ṁ − 2C skew and M symmetric give Ṁ = C + Cᵀ, and the Euler–Lagrange
/// equations d/dt(M q̇) − ∂T/∂q = M q̈ + C q̇ give C q̇ = Ṁ q̇ − ∂T/∂q, so
/// Cᵀ q̇ = Ṁ q̇ − C q̇ = ∂T/∂q, and ∂V/∂q = g. Generalized forces (τ, damping, applied loads)
/// enter by the discrete Lagrange–d'Alembert principle, h/2 of the midpoint force at each
/// end; without them the map (q₀, p₀) → (q₁, p₁) is symplectic and a momentum whose
/// coordinate L does not depend on is conserved exactly (to the Newton tolerance).
///
/// The state carried is (q, q̇), like the other integrators: p₀ = M(q₀) q̇₀ on entry and
/// q̇₁ = M(q₁)⁻¹ p₁ on exit, the continuous Legendre transform, so the step is the
/// symplectic (q, p) map seen through it (one extra mass matrix and solve per step).
///
/// The unknown is the mean velocity v̄ (q₁ = q₀ + h v̄), from the guess q̇₀ + h a(q₀, q̇₀)/2.
/// Newton's method solves with Gaussian elimination and partial pivoting. Its Jacobian is
/// exact when the mechanism generates `momentum_derivatives`
/// ([`Lagrangian::momentum_derivatives`]; see [`exact_momentum_jacobian`]), by forward
/// differences otherwise (step √tolerance · (1 + |v̄ₖ|)); either is formed at the first
/// iteration and again whenever an update shrinks by less than a factor four (forming the
/// exact one at every iteration saved a tenth of the iterations on a stiff pendulum but
/// cost more time than it saved on the UR5). It stops when the update of v̄ is below
/// `tolerance · (1 + |v̄|)` (max norms: relative for fast motion, since the momentum
/// residual carries rounding of the order ε cond(M) |v̄|), after at most `max_iterations`
/// iterations ([`StepError::NotConverged`]), or at a non-finite value
/// ([`StepError::NonFinite`]). `dt` and `tolerance` must be finite and positive and
/// `max_iterations` ≥ 1 ([`StepError::InvalidArgument`] otherwise: a zero tolerance would
/// make the difference step zero).
///
/// Joint coordinates only: a mechanism with a free joint (NQ ≠ NV, quaternion
/// coordinates) is rejected with [`StepError::FreeJoint`].
pub fn variational_midpoint<T: Real, M: Lagrangian<T>>(
    s: &State<T, M>,
    inputs: &Inputs<T, M>,
    dt: T,
    tolerance: T,
    max_iterations: usize,
) -> Result<State<T, M>, StepError> {
    check_arguments(dt, tolerance, max_iterations)?;
    if M::NQ != M::NV {
        return Err(StepError::FreeJoint);
    }
    let p0 = mat_vec::<T, M>(&M::mass_matrix(&s.q, inputs.parameters), &s.v);
    let residual = |w: &M::Velocity| {
        let (mut r, _) = discrete_momenta(&s.q, w, inputs, dt);
        for (rk, &pk) in r.as_mut().iter_mut().zip(p0.as_ref()) {
            *rk -= pk;
        }
        r
    };
    let mut w = axpy(
        &s.v,
        dt * T::from_f64(0.5),
        &acceleration(&s.q, &s.v, inputs),
    );
    let difference_step = tolerance.sqrt();
    let mut jacobian = M::zero_matrix();
    let mut refresh = true;
    let mut last_change: Option<T> = None;
    for _ in 0..max_iterations {
        let r = residual(&w);
        let exact = refresh
            .then(|| exact_momentum_jacobian(&s.q, &w, inputs, dt))
            .flatten();
        if let Some(exact) = exact {
            jacobian = exact;
        } else if refresh {
            for k in 0..r.as_ref().len() {
                let h = difference_step * (T::one() + abs(w.as_ref()[k]));
                let mut shifted = w;
                shifted.as_mut()[k] += h;
                let r_shifted = residual(&shifted);
                for (row, (&a, &b)) in jacobian
                    .as_mut()
                    .iter_mut()
                    .zip(r_shifted.as_ref().iter().zip(r.as_ref()))
                {
                    row.as_mut()[k] = (a - b) / h;
                }
            }
        }
        let (mut factors, mut step) = (jacobian, r);
        solve_in_place(factors.as_mut(), step.as_mut()).ok_or(StepError::NonFinite)?;
        for (wk, &dk) in w.as_mut().iter_mut().zip(step.as_ref()) {
            *wk -= dk;
        }
        let (change, size) = (max_norm(step.as_ref()), max_norm(w.as_ref()));
        if !(change.to_f64().is_finite() && size.to_f64().is_finite()) {
            return Err(StepError::NonFinite);
        }
        if change <= tolerance * (T::one() + size) {
            let (_, p1) = discrete_momenta(&s.q, &w, inputs, dt);
            let q1 = M::integrate(&s.q, &w, dt);
            let mut v1 = p1;
            let mut mass = M::mass_matrix(&q1, inputs.parameters);
            solve_in_place(mass.as_mut(), v1.as_mut()).ok_or(StepError::NonFinite)?;
            return Ok(State { q: q1, v: v1 });
        }
        refresh = last_change.is_some_and(|last| change * T::from_f64(4.0) > last);
        last_change = Some(change);
    }
    Err(StepError::NotConverged {
        iterations: max_iterations,
        last_change: last_change.map_or(f64::INFINITY, T::to_f64),
    })
}

/// The exact Jacobian of the residual of [`variational_midpoint`] with respect to v̄,
/// when the mechanism generates `momentum_derivatives`. With q̄ = q + v̄ h/2 and
/// R(v̄) = M(q̄) v̄ − h/2 ṗ(q̄, v̄) − p₀ (ṗ = τ + Cᵀ v̄ − g + Q − b v̄, the bracket of the
/// discrete momentum),
///
/// ```text
/// ∂R/∂v̄ = M(q̄) + h/2 ∂p/∂q − h/2 (h/2 ∂ṗ/∂q + ∂ṗ/∂q̇),   all at (q̄, v̄),
/// ```
///
/// p = M(q) q̇; ∂ṗ/∂q holds second derivatives of M, which is why it takes a generated
/// output of its own. `None` when the mechanism does not generate it.
pub fn exact_momentum_jacobian<T: Scalar, M: Lagrangian<T>>(
    q: &M::Configuration,
    w: &M::Velocity,
    inputs: &Inputs<T, M>,
    h: T,
) -> Option<M::Matrix> {
    let half_h = h * T::from_f64(0.5);
    let q_mid = M::integrate(q, w, half_h);
    let (dp_dq, dpdot_dq, dpdot_dv) =
        M::momentum_derivatives(&q_mid, w, inputs.parameters, inputs.loads)?;
    let mut jacobian = M::mass_matrix(&q_mid, inputs.parameters);
    for (i, row) in jacobian.as_mut().iter_mut().enumerate() {
        let rows = (
            dp_dq.as_ref()[i].as_ref(),
            dpdot_dq.as_ref()[i].as_ref(),
            dpdot_dv.as_ref()[i].as_ref(),
        );
        for (k, entry) in row.as_mut().iter_mut().enumerate() {
            let rate = half_h * rows.1[k] + rows.2[k];
            *entry += half_h * (rows.0[k] - rate);
        }
    }
    Some(jacobian)
}

/// Solves A x = b in place (x overwrites b) by Gaussian elimination with partial pivoting;
/// `None` if A is singular or not finite.
fn solve_in_place<T: Real, R: AsMut<[T]> + AsRef<[T]>>(a: &mut [R], b: &mut [T]) -> Option<()> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| {
            let (x, y) = (abs(a[i].as_ref()[col]), abs(a[j].as_ref()[col]));
            x.partial_cmp(&y).unwrap_or(core::cmp::Ordering::Equal)
        })?;
        let magnitude = abs(a[pivot].as_ref()[col]);
        if magnitude == T::zero() || !magnitude.to_f64().is_finite() {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..n {
            let factor = a[row].as_ref()[col] / a[col].as_ref()[col];
            for k in col..n {
                let upper = a[col].as_ref()[k];
                a[row].as_mut()[k] -= factor * upper;
            }
            let pivot_b = b[col];
            b[row] -= factor * pivot_b;
        }
    }
    for row in (0..n).rev() {
        let sum = (row + 1..n).fold(b[row], |acc, k| acc - a[row].as_ref()[k] * b[k]);
        b[row] = sum / a[row].as_ref()[row];
    }
    b.iter().all(|x| x.to_f64().is_finite()).then_some(())
}
