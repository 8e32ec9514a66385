//! Time integration of M(q) q̈ + C(q, q̇) q̇ + g(q) = τ + Q, generic over every generated
//! mechanism ([`Dynamics`]) and scalar, without allocation.
//!
//! With a(q, v) the generated forward dynamics and q ⊕ v dt the configuration update of
//! [`Dynamics::integrate`] (free-joint quaternions stay on the unit sphere):
//!
//! ```text
//! explicit Euler       q' = q ⊕ v dt,          v' = v + a(q, v) dt
//! semi-implicit Euler  v' = v + a(q, v) dt,    q' = q ⊕ v' dt          (symplectic)
//! RK4                  the classical four stages on (q, v), stages combined in v
//! implicit midpoint    v' = v + a(q ⊕ v̄ dt/2, v̄) dt, q' = q ⊕ v̄ dt,  v̄ = (v + v')/2
//! ```
//!
//! The implicit midpoint rule is symmetric and, for joint coordinates, symplectic and
//! A-stable; its nonlinear equation is solved by Newton's method, at most `max_iterations`
//! times, and a step that does not converge (or meets a non-finite value) is an error, not
//! a silent result.

use crate::dynamics::Dynamics;
use crate::scalar::Scalar;
use std::fmt;

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
}

impl fmt::Display for StepError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StepError::NotConverged { iterations, last_change } => write!(
                f,
                "implicit step did not converge in {iterations} iterations (last change {last_change:e}); reduce the step"
            ),
            StepError::NonFinite => write!(f, "implicit step produced a non-finite value"),
        }
    }
}

impl std::error::Error for StepError {}

/// One implicit midpoint step: the end velocity w solves
/// F(w) = w − v − dt · a(q ⊕ v̄ dt/2, v̄) = 0 with v̄ = (v + w)/2, by Newton's method with a
/// finite-difference Jacobian J = 1 − dt ∂a/∂w (one extra dynamics evaluation per
/// coordinate) and Gaussian elimination with partial pivoting, until the Newton update is
/// below `tolerance` (max norm), at most `max_iterations` times. Newton converges on stiff
/// problems, where a fixed-point iteration would diverge.
pub fn implicit_midpoint<M: Dynamics<f64>>(
    s: &State<f64, M>,
    inputs: &Inputs<f64, M>,
    dt: f64,
    tolerance: f64,
    max_iterations: usize,
) -> Result<State<f64, M>, StepError> {
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
    let residual = |w: &M::Velocity| {
        let v_mid = midpoint(w);
        let q_mid = M::integrate(&s.q, &v_mid, 0.5 * dt);
        let a = acceleration(&q_mid, &v_mid, inputs);
        let mut f = *w;
        for (k, fk) in f.as_mut().iter_mut().enumerate() {
            *fk = w.as_ref()[k] - s.v.as_ref()[k] - dt * a.as_ref()[k];
        }
        f
    };
    // Start from the explicit Euler guess.
    let mut w = axpy(&s.v, dt, &acceleration(&s.q, &s.v, inputs));
    let mut last_change = f64::INFINITY;
    for _ in 0..max_iterations {
        let f = residual(&w);
        let n = f.as_ref().len();
        let mut jacobian = M::zero_matrix();
        for k in 0..n {
            let h = 1e-7 * (1.0 + w.as_ref()[k].abs());
            let mut shifted = w;
            shifted.as_mut()[k] += h;
            let f_shifted = residual(&shifted);
            for i in 0..n {
                jacobian.as_mut()[i].as_mut()[k] = (f_shifted.as_ref()[i] - f.as_ref()[i]) / h;
            }
        }
        let mut step = f;
        solve_in_place(jacobian.as_mut(), step.as_mut()).ok_or(StepError::NonFinite)?;
        last_change = step.as_ref().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
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

/// Solves A x = b in place (x overwrites b) by Gaussian elimination with partial pivoting;
/// `None` if A is singular or not finite.
fn solve_in_place<R: AsMut<[f64]> + AsRef<[f64]>>(a: &mut [R], b: &mut [f64]) -> Option<()> {
    let n = b.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| {
            a[i].as_ref()[col]
                .abs()
                .total_cmp(&a[j].as_ref()[col].abs())
        })?;
        let magnitude = a[pivot].as_ref()[col].abs();
        if magnitude == 0.0 || magnitude.is_nan() {
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
            b[row] -= factor * b[col];
        }
    }
    for row in (0..n).rev() {
        let sum = (row + 1..n).fold(b[row], |acc, k| acc - a[row].as_ref()[k] * b[k]);
        b[row] = sum / a[row].as_ref()[row];
    }
    b.iter().all(|x| x.is_finite()).then_some(())
}
