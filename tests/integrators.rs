//! Integrators where methods fail: long conservative runs, a fast-spinning asymmetric body,
//! a stiff joint. Each test asserts that the robust method holds and shows the one that
//! fails, with the failure as a number (growth, NaN or an error), never a crash.

use dynamics_runtime::integrators::{self, Inputs, State, StepError};
use dynamics_runtime::{mechanism, Energy};
use models::anchors::DoublePendulum;
use models::seed::GyroscopicBody;

mechanism! {
    /// The seed's rod with a very stiff viscous damper at the pivot: the velocity decays at
    /// b / I_O = 1000 / 0.24 ≈ 4167 1/s, so explicit schemes need dt < 2 I_O / b = 0.48 ms.
    pub struct StiffPendulum;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics, energy];
    body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }
    joint pivot: revolute(ground -> rod) { axis: z, damping: 1000.0 }
}

type Step<M> = fn(&State<f64, M>, &Inputs<f64, M>, f64) -> State<f64, M>;

/// Runs `steps` steps and returns the largest |E − E0| seen (every 100 steps).
fn energy_drift<M: Energy<f64>>(start: State<f64, M>, step: Step<M>, dt: f64, steps: usize) -> f64 {
    let tau = M::zero_velocity();
    let (p, loads) = (M::nominal_parameters(), M::zero_loads());
    let inputs = Inputs::<f64, M> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let e0 = M::total_energy(&start.q, &start.v, &p);
    let mut s = start;
    let mut worst = 0.0_f64;
    for k in 0..steps {
        s = step(&s, &inputs, dt);
        if k % 100 == 0 {
            worst = worst.max((M::total_energy(&s.q, &s.v, &p) - e0).abs());
        }
    }
    worst
}

#[test]
fn double_pendulum_a_million_steps_midpoint_bounded_explicit_grows() {
    // Released from (1.0, 0.5) rad at rest: chaotic motion, total energy ≈ −6.2 J, kinetic
    // energy up to ≈ 10 J. dt = 1 ms; 10⁶ steps are 1000 s of motion.
    let start = State::<f64, DoublePendulum> {
        q: [1.0, 0.5],
        v: [0.0, 0.0],
    };
    let dt = 1e-3;
    let (tau, p, loads) = ([0.0; 2], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, DoublePendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let e0 = DoublePendulum::total_energy(&start.q, &start.v, &p);
    let mut s = start;
    let mut midpoint = 0.0_f64;
    for _ in 0..1_000_000 {
        s = integrators::implicit_midpoint(&s, &inputs, dt, 1e-13, 20).expect("converges");
        midpoint = midpoint.max((DoublePendulum::total_energy(&s.q, &s.v, &p) - e0).abs());
    }
    let semi_implicit = energy_drift(start, integrators::semi_implicit_euler, dt, 1_000_000);
    let explicit = energy_drift(start, integrators::explicit_euler, dt, 100_000);
    let rk4 = energy_drift(start, integrators::rk4, dt, 100_000);
    println!(
        "|ΔE| max: implicit midpoint {midpoint:.2e} J, semi-implicit Euler {semi_implicit:.2e} J (10⁶ steps); \
         explicit Euler {explicit:.2e} J, RK4 {rk4:.2e} J (10⁵ steps)"
    );
    // The symmetric implicit midpoint rule holds the energy over the whole run.
    assert!(midpoint < 1e-3, "implicit midpoint drifted {midpoint} J");
    // Explicit Euler gains energy steadily (22 J in a tenth of the steps): it fails.
    assert!(explicit > 10.0, "explicit Euler drift {explicit} J");
    // Semi-implicit Euler in (q, q̇) is not symplectic when M depends on q: its error grows,
    // but far slower than explicit Euler's.
    assert!(
        semi_implicit < explicit / 5.0,
        "semi-implicit Euler {semi_implicit} J vs explicit {explicit} J"
    );
    assert!(rk4 < 1e-6, "RK4 drift {rk4} J");
}

/// World-frame angular momentum of the free body (mass centre at its origin):
/// H = R(quaternion) I_G ω.
fn angular_momentum(q: &[f64; 7], v: &[f64; 6]) -> [f64; 3] {
    let (x, y, z, w) = (q[3], q[4], q[5], q[6]);
    let h_body = [0.2 * v[3], 0.3 * v[4], 0.4 * v[5]];
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - z * w),
            2.0 * (x * z + y * w),
        ],
        [
            2.0 * (x * y + z * w),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - x * w),
        ],
        [
            2.0 * (x * z - y * w),
            2.0 * (y * z + x * w),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    std::array::from_fn(|i| r[i][0] * h_body[0] + r[i][1] * h_body[1] + r[i][2] * h_body[2])
}

#[test]
fn intermediate_axis_flip_keeps_energy_momentum_and_a_unit_quaternion() {
    // Spinning at 5 rad/s about the intermediate principal axis (I = 0.3 between 0.2 and
    // 0.4) with a 1e-3 perturbation: the spin axis flips over and over (Dzhanibekov).
    let q0 = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    let v0 = [0.0, 0.0, 0.0, 1e-3, 5.0, 0.0];
    let (tau, p, loads) = ([0.0; 6], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, GyroscopicBody> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let e0 = GyroscopicBody::total_energy(&q0, &v0, &p);
    let h0 = angular_momentum(&q0, &v0);
    let mut s = State::<f64, GyroscopicBody> { q: q0, v: v0 };
    let (mut flips, mut last_sign) = (0, 1.0_f64);
    let (mut e_drift, mut h_drift, mut norm_drift) = (0.0_f64, 0.0_f64, 0.0_f64);
    for _ in 0..20_000 {
        s = integrators::rk4(&s, &inputs, 1e-3);
        if s.v[4].signum() != last_sign {
            flips += 1;
            last_sign = s.v[4].signum();
        }
        e_drift = e_drift.max((GyroscopicBody::total_energy(&s.q, &s.v, &p) - e0).abs() / e0);
        let h = angular_momentum(&s.q, &s.v);
        h_drift = h_drift.max((0..3).map(|i| (h[i] - h0[i]).abs()).fold(0.0, f64::max) / 1.5);
        let norm = s.q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        norm_drift = norm_drift.max((norm - 1.0).abs());
    }
    println!("20 s, RK4 dt = 1 ms: {flips} flips, relative |ΔE| {e_drift:.2e}, relative |ΔH| {h_drift:.2e}, |‖quaternion‖ − 1| {norm_drift:.2e}");
    assert!(
        flips >= 2,
        "the intermediate axis should flip; saw {flips} sign changes"
    );
    assert!(e_drift < 1e-9, "energy drift {e_drift}");
    assert!(h_drift < 1e-4, "angular momentum drift {h_drift}");
    assert!(norm_drift < 1e-14, "quaternion norm drift {norm_drift}");
}

#[test]
fn stiff_damper_explicit_blows_up_implicit_holds() {
    let (tau, p, loads) = ([0.0], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, StiffPendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let start = State::<f64, StiffPendulum> { q: [0.5], v: [2.0] };
    let dt = 1e-3; // twice the explicit stability limit of 0.48 ms
    let mut explicit = start;
    let mut implicit = start;
    let mut failure = None;
    for _ in 0..200 {
        explicit = integrators::semi_implicit_euler(&explicit, &inputs, dt);
        match integrators::implicit_midpoint(&implicit, &inputs, dt, 1e-12, 10) {
            Ok(next) => implicit = next,
            Err(e) => failure = Some(e),
        }
    }
    println!(
        "after 0.2 s: explicit (semi-implicit Euler) v = {:e}, implicit midpoint v = {:e}",
        explicit.v[0], implicit.v[0]
    );
    // The explicit scheme amplifies the velocity by |1 − dt b / I| ≈ 3.2 per step: it blows up.
    assert!(
        explicit.v[0].is_nan() || explicit.v[0].abs() >= 1e6,
        "explicit should blow up, v = {}",
        explicit.v[0]
    );
    // Implicit midpoint (A-stable, Newton): converges every step and damps the motion out.
    assert_eq!(failure, None::<StepError>);
    assert!(
        implicit.v[0].abs() < 0.1,
        "implicit midpoint v = {}",
        implicit.v[0]
    );
}

#[test]
fn implicit_step_reports_failure_instead_of_garbage() {
    let (tau, p, loads) = ([0.0], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, StiffPendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let start = State::<f64, StiffPendulum> {
        q: [0.5],
        v: [f64::NAN],
    };
    assert_eq!(
        integrators::implicit_midpoint(&start, &inputs, 1e-3, 1e-12, 10).err(),
        Some(StepError::NonFinite)
    );
    let start = State::<f64, StiffPendulum> { q: [0.5], v: [2.0] };
    let zero_iterations = integrators::implicit_midpoint(&start, &inputs, 1e-3, 1e-12, 0);
    assert!(matches!(
        zero_iterations,
        Err(StepError::NotConverged { iterations: 0, .. })
    ));
}
