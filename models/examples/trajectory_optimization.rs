//! Trajectory optimisation with the generated derivatives: iLQR (iterative LQR, Li and
//! Todorov 2004, with Tassa, Erez and Todorov's 2012 regularisation) swinging a cart-pole up
//! from hanging to upright with the cart's force alone, and moving the UR5's tool flange to
//! a point 0.3 m away in one second.
//!
//! The plant is the generated forward dynamics q̈ = FD(q, q̇, τ), stepped by semi-implicit
//! Euler with step h, and its Jacobians come from the generated derivatives, exactly (no
//! finite differences): with τ = S u (S picks the actuated coordinates),
//!
//! ```text
//! v⁺ = v + h q̈(q, v, S u)              ∂v⁺/∂q = h ∂q̈/∂q     ∂v⁺/∂v = 1 + h ∂q̈/∂v     ∂v⁺/∂u = h M⁻¹ S
//! q⁺ = q + h v⁺                        ∂q⁺/∂x = [1  0] + h ∂v⁺/∂x,    ∂q⁺/∂u = h ∂v⁺/∂u
//! ```
//!
//! (∂q̈/∂q, ∂q̈/∂q̇) = `forward_dynamics_derivatives`, M⁻¹ = ∂q̈/∂τ = `mass_matrix_inverse`.
//! The costs are sums of squares, Σ ½ ‖r(x, u)‖²_W: their gradients are Jᵣᵀ W r and their
//! Hessians taken as Jᵣᵀ W Jᵣ (Gauss–Newton); the UR5's residual is the flange's position
//! error, whose Jacobian is the linear rows of the generated `frame_jacobians`.
//!
//! iLQR: roll the controls out; backward, the quadratic model of the cost-to-go, with
//! Q_uu = ℓ_uu + Bᵀ (V_xx + μ 1) B regularised by μ; forward, u = ū + α k + K (x − x̄) with
//! the step α halved until the cost decreases; μ shrinks after a success and grows after a
//! failure. Stops when an iteration improves the cost by less than 1e-7 of itself.
//!
//! Printed per problem: iterations, the time per iteration and the share of it spent in
//! the generated functions, the initial and final cost, and the final state. The run fails
//! (a panic) if the pole does not end upright and still (within 0.05 rad, 0.05 m and 0.05
//! per second) or the flange ends more than 5 mm from its target. Run with
//! `cargo run --release -p models --example trajectory_optimization`.

use dynamics_runtime::mechanism;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

mechanism! {
    /// A cart on a rail along x, with a pole hinged on it about y; the force on the cart is
    /// the only input. At θ = 0 the pole stands up; at θ = π it hangs.
    pub struct CartPole;
    gravity: [0.0, 0.0, -9.81];
    outputs: [forward_dynamics, forward_dynamics_derivatives, mass_matrix_inverse];
    body cart { mass: 1.0, shape: box(size: [0.3, 0.2, 0.1]) }
    body pole { mass: 0.2, com: [0.0, 0.0, 0.25], shape: rod(length: 0.5, axis: z) }
    joint rail: prismatic(ground -> cart) { axis: x }
    joint hinge: revolute(cart -> pole) { axis: y }
}

mechanism! {
    /// The UR5 (`urdf/ur5.urdf`) with its tool flange, `tool0`, as on the real robot.
    pub struct Ur5Reach;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, forward_dynamics_derivatives, mass_matrix_inverse,
              frame_placements, frame_jacobians];
    /// The tool flange (ROS-Industrial's `tool0`).
    frame tool0: on wrist_3_link at [0.0, 0.0823, 0.0] rotation rpy(-pi / 2.0, 0.0, 0.0);
}

/// What iLQR needs of a problem: the discrete dynamics and their Jacobians, and the costs
/// with their gradients and (Gauss–Newton) Hessians.
trait Problem {
    /// The state's size.
    fn state_size(&self) -> usize;
    /// x⁺ = f(x, u).
    fn step(&self, x: &DVector<f64>, u: &DVector<f64>) -> DVector<f64>;
    /// (A, B) = (∂f/∂x, ∂f/∂u) at (x, u).
    fn linearize(&self, x: &DVector<f64>, u: &DVector<f64>) -> (DMatrix<f64>, DMatrix<f64>);
    /// The running cost ℓ(x, u) and its model.
    fn running(&self, x: &DVector<f64>, u: &DVector<f64>) -> Model;
    /// The final cost ℓ_f(x) and its model (`u` parts empty).
    fn terminal(&self, x: &DVector<f64>) -> Model;
}

/// A cost's value, gradient and Hessian (ℓ_ux is zero in both problems here).
struct Model {
    value: f64,
    x: DVector<f64>,
    u: DVector<f64>,
    xx: DMatrix<f64>,
    uu: DMatrix<f64>,
}

/// A mechanism with one coordinate per velocity (no free base), seen through its generated
/// forward dynamics, their derivatives and M⁻¹.
trait Plant {
    /// Velocity coordinates.
    const NV: usize;
    /// The coordinates the controls drive, one per control.
    const ACTUATED: &'static [usize];
    /// q̈(q, v, τ).
    fn forward_dynamics(q: &[f64], v: &[f64], tau: &[f64]) -> Vec<f64>;
    /// (∂q̈/∂q, ∂q̈/∂v, M⁻¹) at (q, v, τ).
    fn derivatives(q: &[f64], v: &[f64], tau: &[f64]) -> [DMatrix<f64>; 3];
}

/// An nv × nv matrix from the generated row arrays.
fn matrix<const N: usize>(rows: &[[f64; N]; N]) -> DMatrix<f64> {
    DMatrix::from_fn(N, N, |i, j| rows[i][j])
}

/// Implements [`Plant`] for a generated mechanism of `$n` coordinates.
macro_rules! plant {
    ($t:ty, $n:literal, $actuated:expr) => {
        impl Plant for $t {
            const NV: usize = $n;
            const ACTUATED: &'static [usize] = $actuated;
            fn forward_dynamics(q: &[f64], v: &[f64], tau: &[f64]) -> Vec<f64> {
                let array = |x: &[f64]| -> [f64; $n] { std::array::from_fn(|i| x[i]) };
                <$t>::forward_dynamics(&array(q), &array(v), &array(tau)).to_vec()
            }
            fn derivatives(q: &[f64], v: &[f64], tau: &[f64]) -> [DMatrix<f64>; 3] {
                let array = |x: &[f64]| -> [f64; $n] { std::array::from_fn(|i| x[i]) };
                let (by_q, by_v) =
                    <$t>::forward_dynamics_derivatives(&array(q), &array(v), &array(tau));
                let m_inverse = <$t>::mass_matrix_inverse(&array(q));
                [matrix(&by_q), matrix(&by_v), matrix(&m_inverse)]
            }
        }
    };
}

plant!(CartPole, 2, &[0]);
plant!(Ur5Reach, 6, &[0, 1, 2, 3, 4, 5]);

/// Time spent in the generated functions (for the printout).
static GENERATED: std::sync::Mutex<Duration> = std::sync::Mutex::new(Duration::ZERO);

fn timed<R>(f: impl FnOnce() -> R) -> R {
    let start = Instant::now();
    let result = f();
    if let Ok(mut total) = GENERATED.lock() {
        *total += start.elapsed();
    }
    result
}

/// τ = S u: the controls on the actuated coordinates, zero on the others.
fn torques<P: Plant>(u: &DVector<f64>) -> Vec<f64> {
    let mut tau = vec![0.0; P::NV];
    for (k, &coordinate) in P::ACTUATED.iter().enumerate() {
        tau[coordinate] = u[k];
    }
    tau
}

/// Semi-implicit Euler over a [`Plant`], x = [q; v], τ = S u.
fn euler_step<P: Plant>(h: f64, x: &DVector<f64>, u: &DVector<f64>) -> DVector<f64> {
    let n = P::NV;
    let (q, v) = (x.rows(0, n), x.rows(n, n));
    let tau = torques::<P>(u);
    let qdd = timed(|| P::forward_dynamics(q.as_slice(), v.as_slice(), &tau));
    let v_next = DVector::from_fn(n, |i, _| v[i] + h * qdd[i]);
    let q_next = DVector::from_fn(n, |i, _| q[i] + h * v_next[i]);
    let mut next = DVector::zeros(2 * n);
    next.rows_mut(0, n).copy_from(&q_next);
    next.rows_mut(n, n).copy_from(&v_next);
    next
}

/// (A, B) of [`euler_step`] from the generated derivatives (module documentation).
fn euler_jacobians<P: Plant>(
    h: f64,
    x: &DVector<f64>,
    u: &DVector<f64>,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (n, m) = (P::NV, P::ACTUATED.len());
    let (q, v) = (x.rows(0, n), x.rows(n, n));
    let tau = torques::<P>(u);
    let [by_q, by_v, m_inverse] = timed(|| P::derivatives(q.as_slice(), v.as_slice(), &tau));
    let selection = DMatrix::from_fn(n, m, |i, k| f64::from(u8::from(P::ACTUATED[k] == i)));
    // Rows of v⁺, then q⁺ = q + h v⁺.
    let dv_dx = {
        let mut d = DMatrix::zeros(n, 2 * n);
        d.columns_mut(0, n).copy_from(&(&by_q * h));
        d.columns_mut(n, n)
            .copy_from(&(DMatrix::identity(n, n) + &by_v * h));
        d
    };
    let dv_du = &m_inverse * &selection * h;
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    a.view_mut((0, 0), (n, n)).fill_with_identity();
    let dq_from_dv = &dv_dx * h;
    let top = a.rows(0, n) + dq_from_dv;
    a.rows_mut(0, n).copy_from(&top);
    a.rows_mut(n, n).copy_from(&dv_dx);
    let mut b = DMatrix::zeros(2 * n, m);
    b.rows_mut(0, n).copy_from(&(&dv_du * h));
    b.rows_mut(n, n).copy_from(&dv_du);
    (a, b)
}

/// The cart-pole swing-up: from hanging still at the origin to upright still at the origin
/// in `steps` steps of `h`; quadratic costs on the state error and the force.
struct SwingUp {
    h: f64,
}

impl SwingUp {
    const GOAL: [f64; 4] = [0.0, 0.0, 0.0, 0.0];
    /// Running weights on the state error, and on the force (N⁻²).
    const RUNNING: [f64; 4] = [0.1, 0.1, 0.01, 0.01];
    const FORCE: f64 = 0.01;
    /// Final weights on the state error.
    const FINAL: [f64; 4] = [1000.0, 1000.0, 100.0, 100.0];
}

impl Problem for SwingUp {
    fn state_size(&self) -> usize {
        4
    }
    fn step(&self, x: &DVector<f64>, u: &DVector<f64>) -> DVector<f64> {
        euler_step::<CartPole>(self.h, x, u)
    }
    fn linearize(&self, x: &DVector<f64>, u: &DVector<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
        euler_jacobians::<CartPole>(self.h, x, u)
    }
    fn running(&self, x: &DVector<f64>, u: &DVector<f64>) -> Model {
        let mut model = weighted_state_error(x, &Self::GOAL, &Self::RUNNING, self.h);
        model.value += 0.5 * self.h * Self::FORCE * u[0] * u[0];
        model.u = DVector::from_element(1, self.h * Self::FORCE * u[0]);
        model.uu = DMatrix::from_element(1, 1, self.h * Self::FORCE);
        model
    }
    fn terminal(&self, x: &DVector<f64>) -> Model {
        weighted_state_error(x, &Self::GOAL, &Self::FINAL, 1.0)
    }
}

/// ½ s Σ w_i (x_i − g_i)², its gradient and Hessian; no control part.
fn weighted_state_error(x: &DVector<f64>, goal: &[f64], weights: &[f64], s: f64) -> Model {
    let error = DVector::from_fn(x.len(), |i, _| x[i] - goal[i]);
    let w = DVector::from_fn(x.len(), |i, _| s * weights[i]);
    Model {
        value: 0.5 * error.component_mul(&error).dot(&w),
        x: error.component_mul(&w),
        u: DVector::zeros(0),
        xx: DMatrix::from_diagonal(&w),
        uu: DMatrix::zeros(0, 0),
    }
}

/// The UR5 reach: the flange's origin to `target` (world, m) at the end, the arm still;
/// small running costs on the torques and the joint rates.
struct Reach {
    h: f64,
    target: [f64; 3],
}

impl Reach {
    /// Running weights: on the torques ((N·m)⁻²) and the joint rates.
    const TORQUE: f64 = 1e-4;
    const RATE: f64 = 1e-2;
    /// Final weights: on the position error (m⁻²) and the joint rates.
    const POSITION: f64 = 1e4;
    const STILL: f64 = 10.0;
}

impl Problem for Reach {
    fn state_size(&self) -> usize {
        12
    }
    fn step(&self, x: &DVector<f64>, u: &DVector<f64>) -> DVector<f64> {
        euler_step::<Ur5Reach>(self.h, x, u)
    }
    fn linearize(&self, x: &DVector<f64>, u: &DVector<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
        euler_jacobians::<Ur5Reach>(self.h, x, u)
    }
    fn running(&self, x: &DVector<f64>, u: &DVector<f64>) -> Model {
        let mut weights = [0.0; 12];
        weights[6..].fill(Self::RATE);
        let mut model = weighted_state_error(x, &[0.0; 12], &weights, self.h);
        model.value += 0.5 * self.h * Self::TORQUE * u.norm_squared();
        model.u = u * (self.h * Self::TORQUE);
        model.uu = DMatrix::identity(6, 6) * (self.h * Self::TORQUE);
        model
    }
    fn terminal(&self, x: &DVector<f64>) -> Model {
        let mut weights = [0.0; 12];
        weights[6..].fill(Self::STILL);
        let mut model = weighted_state_error(x, &[0.0; 12], &weights, 1.0);
        // ½ w ‖p(q) − p*‖², with ∂p/∂q the linear rows of the flange's Jacobian.
        let q: [f64; 6] = std::array::from_fn(|i| x[i]);
        let (placement, jacobian) = timed(|| {
            (
                Ur5Reach::frame_placements(&q)[Ur5Reach::FRAME_TOOL0],
                Ur5Reach::frame_jacobians(&q)[Ur5Reach::FRAME_TOOL0],
            )
        });
        let error = DVector::from_fn(3, |i, _| placement.1[i] - self.target[i]);
        let dp_dq = DMatrix::from_fn(3, 6, |i, j| jacobian[i][j]);
        model.value += 0.5 * Self::POSITION * error.norm_squared();
        let gradient = dp_dq.transpose() * &error * Self::POSITION;
        let hessian = dp_dq.transpose() * &dp_dq * Self::POSITION;
        let mut x_part = model.x.rows_mut(0, 6);
        x_part += gradient;
        let mut xx_part = model.xx.view_mut((0, 0), (6, 6));
        xx_part += hessian;
        model
    }
}

/// The result of [`ilqr`].
struct Solution {
    states: Vec<DVector<f64>>,
    cost: f64,
    initial_cost: f64,
    iterations: usize,
    elapsed: Duration,
}

/// The states and the total cost of the controls `controls` from `x0`.
fn rollout<P: Problem>(
    problem: &P,
    x0: &DVector<f64>,
    controls: &[DVector<f64>],
) -> (Vec<DVector<f64>>, f64) {
    let mut states = vec![x0.clone()];
    let mut cost = 0.0;
    for u in controls {
        let x = states.last().unwrap_or(x0);
        cost += problem.running(x, u).value;
        let next = problem.step(x, u);
        states.push(next);
    }
    cost += problem.terminal(states.last().unwrap_or(x0)).value;
    (states, cost)
}

/// iLQR from the controls `controls` (module documentation).
fn ilqr<P: Problem>(problem: &P, x0: &DVector<f64>, mut controls: Vec<DVector<f64>>) -> Solution {
    let start = Instant::now();
    let nx = problem.state_size();
    let steps = controls.len();
    let (mut states, mut cost) = rollout(problem, x0, &controls);
    let initial_cost = cost;
    let mut mu = 1e-6;
    let mut iterations = 0;
    while iterations < 200 {
        iterations += 1;
        let linear: Vec<_> = (0..steps)
            .map(|k| problem.linearize(&states[k], &controls[k]))
            .collect();
        // Backward pass: gains k (feedforward) and K (feedback), or a failure to factor.
        let final_model = problem.terminal(&states[steps]);
        let (mut v_x, mut v_xx) = (final_model.x, final_model.xx);
        let mut gains: Vec<(DVector<f64>, DMatrix<f64>)> = Vec::with_capacity(steps);
        let mut factored = true;
        for k in (0..steps).rev() {
            let (a, b) = &linear[k];
            let l = problem.running(&states[k], &controls[k]);
            let regularised = &v_xx + DMatrix::identity(nx, nx) * mu;
            let q_x = &l.x + a.transpose() * &v_x;
            let q_u = &l.u + b.transpose() * &v_x;
            let q_xx = &l.xx + a.transpose() * &v_xx * a;
            let q_uu = &l.uu + b.transpose() * &regularised * b;
            let q_ux = b.transpose() * &regularised * a;
            let Some(cholesky) = q_uu.clone().cholesky() else {
                factored = false;
                break;
            };
            let feedforward = -cholesky.solve(&q_u);
            let feedback = -cholesky.solve(&q_ux);
            v_x = &q_x
                + feedback.transpose() * &q_uu * &feedforward
                + feedback.transpose() * &q_u
                + q_ux.transpose() * &feedforward;
            v_xx = &q_xx
                + feedback.transpose() * &q_uu * &feedback
                + feedback.transpose() * &q_ux
                + q_ux.transpose() * &feedback;
            v_xx = (&v_xx + v_xx.transpose()) * 0.5;
            gains.push((feedforward, feedback));
        }
        if !factored {
            mu = (mu * 10.0).max(1e-6);
            continue;
        }
        gains.reverse();
        // Forward pass with a line search on the feedforward step.
        let mut accepted = None;
        let mut alpha = 1.0;
        for _ in 0..12 {
            let mut x = x0.clone();
            let mut new_controls = Vec::with_capacity(steps);
            for k in 0..steps {
                let (feedforward, feedback) = &gains[k];
                let u = &controls[k] + feedforward * alpha + feedback * (&x - &states[k]);
                x = problem.step(&x, &u);
                new_controls.push(u);
            }
            let (new_states, new_cost) = rollout(problem, x0, &new_controls);
            if new_cost < cost {
                accepted = Some((new_states, new_controls, new_cost));
                break;
            }
            alpha *= 0.5;
        }
        match accepted {
            Some((new_states, new_controls, new_cost)) => {
                let improvement = cost - new_cost;
                states = new_states;
                controls = new_controls;
                cost = new_cost;
                mu = (mu / 10.0).max(1e-9);
                if improvement < 1e-7 * cost {
                    break;
                }
            }
            None => {
                mu *= 10.0;
                if mu > 1e8 {
                    break;
                }
            }
        }
    }
    Solution {
        states,
        cost,
        initial_cost,
        iterations,
        elapsed: start.elapsed(),
    }
}

fn report(name: &str, solution: &Solution) {
    let generated = GENERATED.lock().map(|d| *d).unwrap_or_default();
    let per_iteration = solution.elapsed.as_secs_f64() * 1e3 / solution.iterations as f64;
    println!(
        "{name}: {} iterations, {per_iteration:.2} ms per iteration ({:.0} % in the generated \
         functions), cost {:.4} -> {:.4}",
        solution.iterations,
        100.0 * generated.as_secs_f64() / solution.elapsed.as_secs_f64(),
        solution.initial_cost,
        solution.cost
    );
    if let Ok(mut total) = GENERATED.lock() {
        *total = Duration::ZERO;
    }
}

fn main() {
    // The cart-pole: 2.5 s in steps of 20 ms, from hanging (θ = π) to upright.
    let swing_up = SwingUp { h: 0.02 };
    let hanging = DVector::from_vec(vec![0.0, PI, 0.0, 0.0]);
    let solution = ilqr(&swing_up, &hanging, vec![DVector::zeros(1); 125]);
    report("cart-pole swing-up", &solution);
    let last = solution.states.last().cloned().unwrap_or(hanging);
    println!(
        "  final cart {:+.4} m, pole {:+.4} rad, rates {:+.4} m/s {:+.4} rad/s",
        last[0], last[1], last[2], last[3]
    );
    assert!(
        last[0].abs() < 0.05
            && last[1].abs() < 0.05
            && last[2].abs() < 0.05
            && last[3].abs() < 0.05,
        "the pole does not end upright and still: {last}"
    );

    // The UR5: 1 s in steps of 10 ms, the flange 0.3 m from where it starts.
    let q0 = [0.0, -1.2, 1.5, -1.9, -1.57, 0.0];
    let start = Ur5Reach::frame_placements(&q0)[Ur5Reach::FRAME_TOOL0].1;
    let target = [start[0] - 0.2, start[1] + 0.15, start[2] + 0.15];
    let reach = Reach { h: 0.01, target };
    let x0 = DVector::from_fn(12, |i, _| if i < 6 { q0[i] } else { 0.0 });
    let solution = ilqr(&reach, &x0, vec![DVector::zeros(6); 100]);
    report("UR5 reach", &solution);
    let last = solution.states.last().cloned().unwrap_or(x0);
    let q: [f64; 6] = std::array::from_fn(|i| last[i]);
    let end = Ur5Reach::frame_placements(&q)[Ur5Reach::FRAME_TOOL0].1;
    let miss = (0..3)
        .map(|i| (end[i] - target[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    println!(
        "  flange {:.1} mm from its target, joint rates up to {:.3} rad/s at the end",
        miss * 1e3,
        last.rows(6, 6).amax()
    );
    assert!(miss < 5e-3, "the flange ends {miss} m from its target");
}
