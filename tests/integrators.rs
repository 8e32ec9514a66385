//! Integrators where methods fail: long conservative runs, a fast-spinning asymmetric body,
//! a stiff joint. Each test asserts that the robust method holds and shows the one that
//! fails, with the failure as a number (growth, NaN or an error), never a crash.

use dynamics_runtime::integrators::{self, Inputs, State, StepError};
use dynamics_runtime::Lagrangian;
use dynamics_runtime::{mechanism, DoubleDouble, Energy};
use dynamics_tests::random::SplitMix;
use models::anchors::DoublePendulum;
use models::seed::GyroscopicBody;

mechanism! {
    /// The textbook's rod with a very stiff viscous damper at the pivot: the velocity decays at
    /// b / I_O = 1000 / 0.24 ≈ 4167 1/s, so explicit schemes need dt < 2 I_O / b = 0.48 ms.
    pub struct StiffPendulum;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics, mass_matrix, coriolis, gravity, energy];
    body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }
    joint pivot: revolute(ground -> rod) { axis: z, damping: 1000.0 }
}

type Step<M> = fn(&State<f64, M>, &Inputs<f64, M>, f64) -> State<f64, M>;

/// Runs `steps` unforced steps from `start` and hands `observe` each step's index and
/// |E − E₀| (the total energy against the start's).
fn unforced_energy_errors<M: Energy<f64>>(
    start: State<f64, M>,
    step: Step<M>,
    dt: f64,
    steps: usize,
    mut observe: impl FnMut(usize, f64),
) {
    let tau = M::zero_velocity();
    let (p, loads) = (M::nominal_parameters(), M::zero_loads());
    let inputs = Inputs::<f64, M> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let e0 = M::total_energy(&start.q, &start.v, &p);
    let mut s = start;
    for k in 0..steps {
        s = step(&s, &inputs, dt);
        observe(k, (M::total_energy(&s.q, &s.v, &p) - e0).abs());
    }
}

/// Runs `steps` steps and returns the largest |E − E0| seen (every 100 steps).
fn energy_drift<M: Energy<f64>>(start: State<f64, M>, step: Step<M>, dt: f64, steps: usize) -> f64 {
    let mut worst = 0.0_f64;
    unforced_energy_errors(start, step, dt, steps, |k, error| {
        if k % 100 == 0 {
            worst = worst.max(error);
        }
    });
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
    let implicit_midpoint: Step<DoublePendulum> = |s, inputs, dt| {
        integrators::implicit_midpoint(s, inputs, dt, 1e-13, 20).expect("converges")
    };
    let mut midpoint = 0.0_f64;
    unforced_energy_errors(start, implicit_midpoint, dt, 1_000_000, |_, error| {
        midpoint = midpoint.max(error);
    });
    let semi_implicit = energy_drift(start, integrators::semi_implicit_euler, dt, 1_000_000);
    let explicit = energy_drift(start, integrators::explicit_euler, dt, 100_000);
    let rk4 = energy_drift(start, integrators::rk4, dt, 100_000);
    println!(
        "|ΔE| max: implicit midpoint {midpoint:.2e} J, semi-implicit Euler {semi_implicit:.2e} J (10⁶ steps); \
         explicit Euler {explicit:.2e} J, RK4 {rk4:.2e} J (10⁵ steps)"
    );
    // The implicit midpoint rule keeps the energy error small over the whole run, but it
    // is not symplectic in (q, q̇) for this configuration-dependent M: its error grew from
    // 3.4e-4 J (first tenth) to 1.08e-3 J (last tenth) in one measurement; the variational
    // scheme is the one without drift (its test below). Each change of rounding changes
    // this chaotic trajectory: the largest error was 4.3e-4 J before the base-parameter
    // regrouping, 1.08e-3 J after it, 8.7e-4 J with the batched sines and cosines. The
    // bound has margin over all three.
    assert!(midpoint < 2e-3, "implicit midpoint drifted {midpoint} J");
    // Explicit Euler gains energy steadily (17 to 22 J in a tenth of the steps, depending on
    // the last bit of the trigonometry, which this chaotic trajectory amplifies): it fails.
    assert!(explicit > 10.0, "explicit Euler drift {explicit} J");
    // Semi-implicit Euler in (q, q̇) is not symplectic when M depends on q: its error grows,
    // but far slower than explicit Euler's: over ten times as many steps it stays below
    // explicit Euler's (measured 8.4 J against 16.8 J; 6.6 J against 22 J with glibc's sin_cos).
    assert!(
        semi_implicit < explicit,
        "semi-implicit Euler {semi_implicit} J (10⁶ steps) vs explicit {explicit} J (10⁵ steps)"
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

mechanism! {
    /// A Furuta pendulum: an arm turning about the vertical z, a rod swinging about the arm's
    /// axis x at its tip. L does not depend on the arm angle q₀, so its momentum
    /// p₀ = (M(q) q̇)₀, the angular momentum about the vertical, is conserved.
    pub struct Furuta;
    gravity: [0.0, 0.0, -9.81];
    outputs: [forward_dynamics, mass_matrix, coriolis, gravity, energy];
    body arm { mass: 1.0, com: [0.15, 0.0, 0.0], inertia: diag([1e-3, 8e-3, 8e-3]) }
    body rod { mass: 0.5, com: [0.0, 0.0, -0.2], inertia: diag([7e-3, 7e-3, 1e-4]) }
    joint turn: revolute(ground -> arm) { axis: z }
    joint swing: revolute(arm -> rod) { axis: x, at: [0.3, 0.0, 0.0] }
}

mechanism! {
    /// A free-flying brick: quaternion coordinates, which the variational midpoint rule
    /// rejects.
    pub struct FreeBrick;
    gravity: [0.0, 0.0, -9.81];
    body brick { mass: 1.0, inertia: diag([0.2, 0.3, 0.4]) }
    joint flight: free(ground -> brick);
}

/// The variational midpoint step at relative tolerance 1e-12, as a [`Step`] (a failed step
/// fails the test).
fn variational<M: Lagrangian<f64>>(
    s: &State<f64, M>,
    inputs: &Inputs<f64, M>,
    dt: f64,
) -> State<f64, M> {
    integrators::variational_midpoint(s, inputs, dt, 1e-12, 20)
        .unwrap_or_else(|e| panic!("variational step failed: {e}"))
}

/// Largest |E − E₀| over the first and the last tenth of a run of `steps` steps (energy
/// read every step).
fn energy_error_first_and_last_tenth<M: Energy<f64>>(
    start: State<f64, M>,
    step: Step<M>,
    dt: f64,
    steps: usize,
) -> (f64, f64) {
    let (mut first, mut last) = (0.0_f64, 0.0_f64);
    unforced_energy_errors(start, step, dt, steps, |k, error| {
        if k < steps / 10 {
            first = first.max(error);
        } else if k >= steps - steps / 10 {
            last = last.max(error);
        }
        assert!(error.is_finite(), "non-finite energy at step {k}");
    });
    (first, last)
}

#[test]
fn double_pendulum_a_million_steps_variational_bounded() {
    // 1000 s at dt = 1 ms from both rods raised, (1.5, 1.0) rad at rest: E ≈ 0.96 J, the
    // lower rod flips over from the first seconds, so every tenth of the run visits the same
    // chaotic set and their energy errors are comparable. (From the lower start above, the
    // first seconds can stay in gentler swings with a smaller error, whatever the method.)
    let start = State::<f64, DoublePendulum> {
        q: [1.5, 1.0],
        v: [0.0, 0.0],
    };
    let (v_first, v_last) = energy_error_first_and_last_tenth(start, variational, 1e-3, 1_000_000);
    let (s_first, s_last) =
        energy_error_first_and_last_tenth(start, integrators::semi_implicit_euler, 1e-3, 1_000_000);
    println!(
        "max |ΔE| over the first / last 10⁵ of 10⁶ steps: variational midpoint {v_first:.2e} / {v_last:.2e} J, \
         semi-implicit Euler {s_first:.2e} / {s_last:.2e} J"
    );
    // Symplectic for the configuration-dependent M: an O(h²) error (1.5e-3 J measured) that
    // does not grow over the run.
    assert!(
        v_first.max(v_last) < 3e-3,
        "variational midpoint |ΔE| {v_first} / {v_last} J"
    );
    assert!(
        v_last < 1.5 * v_first,
        "variational energy error grew: {v_first} -> {v_last} J"
    );
    // Semi-implicit Euler in (q, q̇), first order and not symplectic here: thousands of
    // times larger.
    assert!(
        s_first.min(s_last) > 1e3 * v_first.max(v_last),
        "semi-implicit Euler {s_first} / {s_last} J"
    );
}

/// The final configuration and velocity after `seconds` of the double pendulum from
/// (1.0, 0.5) rad at rest.
fn double_pendulum_after(step: Step<DoublePendulum>, dt: f64, seconds: f64) -> [f64; 4] {
    let (tau, p, loads) = ([0.0; 2], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, DoublePendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let mut s = State::<f64, DoublePendulum> {
        q: [1.0, 0.5],
        v: [0.0, 0.0],
    };
    for _ in 0..(seconds / dt).round() as usize {
        s = step(&s, &inputs, dt);
    }
    [s.q[0], s.q[1], s.v[0], s.v[1]]
}

#[test]
fn variational_midpoint_is_second_order() {
    let truth = double_pendulum_after(integrators::rk4, 1e-4, 1.0);
    let errors: Vec<f64> = [4e-3, 2e-3, 1e-3]
        .iter()
        .map(|&dt| {
            let end = double_pendulum_after(variational, dt, 1.0);
            (0..4)
                .map(|k| (end[k] - truth[k]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let ratios = [errors[0] / errors[1], errors[1] / errors[2]];
    println!(
        "variational midpoint, state error after 1 s at dt = 4, 2, 1 ms: {:.2e} {:.2e} {:.2e}; ratios {ratios:.3?}",
        errors[0], errors[1], errors[2]
    );
    for r in ratios {
        assert!(
            (3.6..4.4).contains(&r),
            "halving dt divided the error by {r}, not 4"
        );
    }
}

#[test]
fn furuta_pendulum_variational_conserves_the_vertical_angular_momentum() {
    // Arm spinning at 2 rad/s, rod released at 1 rad: the rod's swing trades angular
    // momentum between arm and rod, whose total about the vertical stays constant.
    let (tau, p, loads) = ([0.0; 2], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, Furuta> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let momentum = |s: &State<f64, Furuta>| {
        let m = <Furuta as Lagrangian<f64>>::mass_matrix(&s.q, &p);
        m[0][0] * s.v[0] + m[0][1] * s.v[1]
    };
    let start = State::<f64, Furuta> {
        q: [0.0, 1.0],
        v: [2.0, 0.0],
    };
    let (h0, e0) = (
        momentum(&start),
        Furuta::total_energy(&start.q, &start.v, &p),
    );
    let dt = 1e-2;
    let methods: [(&str, Step<Furuta>); 3] = [
        ("variational midpoint", variational),
        ("implicit midpoint", |s, i, dt| {
            integrators::implicit_midpoint(s, i, dt, 1e-13, 20).unwrap_or_else(|e| panic!("{e}"))
        }),
        ("semi-implicit Euler", integrators::semi_implicit_euler),
    ];
    let mut drifts = [0.0_f64; 3];
    for ((name, step), drift) in methods.iter().zip(&mut drifts) {
        let (mut s, mut energy) = (start, 0.0_f64);
        for _ in 0..10_000 {
            s = step(&s, &inputs, dt);
            *drift = drift.max((momentum(&s) - h0).abs() / h0.abs());
            energy = energy.max((Furuta::total_energy(&s.q, &s.v, &p) - e0).abs());
        }
        println!(
            "Furuta, 100 s at dt = 10 ms, {name}: relative |Δp₀| {drift:.2e}, |ΔE| {energy:.2e} J"
        );
    }
    assert!(
        drifts[0] < 1e-11,
        "variational midpoint momentum drift {}",
        drifts[0]
    );
    assert!(
        drifts[1] > 1e3 * drifts[0] && drifts[2] > 1e3 * drifts[0],
        "{drifts:?}"
    );
}

#[test]
fn lagrangian_gradient_is_coriolis_transpose_minus_gravity() {
    // ∂L/∂q = C(q, q̇)ᵀ q̇ − g(q), the identity the variational step rests on, against central
    // differences of L = T − V built from the generated energies.
    let p = [0.0; 0];
    let lagrangian =
        |q: &[f64; 2], v: &[f64; 2]| Furuta::kinetic_energy(q, v) - Furuta::potential_energy(q);
    let mut rng = SplitMix(11);
    let mut worst = 0.0_f64;
    for _ in 0..20 {
        let q: [f64; 2] = std::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let v: [f64; 2] = std::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let c = <Furuta as Lagrangian<f64>>::coriolis_matrix(&q, &v, &p);
        let g = <Furuta as Lagrangian<f64>>::gravity(&q, &p);
        for k in 0..2 {
            let h = 1e-5;
            let (mut plus, mut minus) = (q, q);
            plus[k] += h;
            minus[k] -= h;
            let numeric = (lagrangian(&plus, &v) - lagrangian(&minus, &v)) / (2.0 * h);
            let formula = c[0][k] * v[0] + c[1][k] * v[1] - g[k];
            worst = worst.max((numeric - formula).abs() / (1.0 + numeric.abs()));
        }
    }
    assert!(worst < 1e-8, "∂L/∂q differs from Cᵀq̇ − g by {worst}");
}

#[test]
fn variational_forces_enter_by_lagrange_d_alembert() {
    // A constant torque τ is the force of the potential −τ·q: the scheme is then the
    // conservative one for L + τ·q, so E − τ·q stays bounded over a long run.
    let (tau, p, loads) = ([0.5, 0.2], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, DoublePendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let balance = |s: &State<f64, DoublePendulum>| {
        DoublePendulum::total_energy(&s.q, &s.v, &p) - tau[0] * s.q[0] - tau[1] * s.q[1]
    };
    let mut s = State::<f64, DoublePendulum> {
        q: [0.5, 0.3],
        v: [0.0, 0.0],
    };
    let b0 = balance(&s);
    let mut worst = 0.0_f64;
    for _ in 0..20_000 {
        s = variational(&s, &inputs, 1e-3);
        worst = worst.max((balance(&s) - b0).abs());
    }
    println!(
        "constant torque, 20 s: |Δ(E − τ·q)| ≤ {worst:.2e} J, q = {:?}",
        s.q
    );
    assert!(worst < 1e-5, "E − τ·q drifted {worst} J");

    // Damping: the stiff damper at twice the explicit stability limit, like implicit midpoint.
    let (tau, p, loads) = ([0.0], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, StiffPendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let mut s = State::<f64, StiffPendulum> { q: [0.5], v: [2.0] };
    for _ in 0..200 {
        s = integrators::variational_midpoint(&s, &inputs, 1e-3, 1e-12, 10).expect("converges");
    }
    println!(
        "stiff damper after 0.2 s: variational midpoint v = {:e}",
        s.v[0]
    );
    assert!(
        s.v[0].abs() < 0.1 && (s.q[0] - 0.5).abs() < 0.01,
        "{:?} {:?}",
        s.q,
        s.v
    );
}

#[test]
fn variational_midpoint_runs_in_every_scalar_and_rejects_free_joints() {
    // 1 s of the double pendulum in f32, f64 and double-double: the three agree to the
    // f32 and f64 precision (the differences are rounding, not the scheme).
    fn run<T: integrators::Real>(tolerance: f64) -> [f64; 2] {
        let (tau, p, loads): ([T; 2], [T; 0], [T; 0]) = ([T::zero(); 2], [], []);
        let inputs = Inputs::<T, DoublePendulum> {
            tau: &tau,
            parameters: &p,
            loads: &loads,
        };
        let mut s = State::<T, DoublePendulum> {
            q: [T::from_f64(1.0), T::from_f64(0.5)],
            v: [T::zero(); 2],
        };
        for _ in 0..500 {
            s = integrators::variational_midpoint(
                &s,
                &inputs,
                T::from_f64(2e-3),
                T::from_f64(tolerance),
                20,
            )
            .unwrap_or_else(|e| panic!("{e}"));
        }
        s.q.map(T::to_f64)
    }
    let (single, double, double_double) = (
        run::<f32>(1e-5),
        run::<f64>(1e-12),
        run::<DoubleDouble>(1e-26),
    );
    let gap = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
    println!(
        "after 1 s: |f32 − double-double| {:.1e}, |f64 − double-double| {:.1e}",
        gap(single, double_double),
        gap(double, double_double)
    );
    assert!(gap(single, double_double) < 1e-3);
    assert!(gap(double, double_double) < 1e-11);

    let (tau, p, loads) = ([0.0; 6], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, FreeBrick> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let s = State::<f64, FreeBrick> {
        q: [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        v: [0.0, 0.0, 0.0, 0.1, 0.2, 0.3],
    };
    assert_eq!(
        integrators::variational_midpoint(&s, &inputs, 1e-3, 1e-12, 10).err(),
        Some(StepError::FreeJoint)
    );
}

/// A NaN velocity is reported as non-finite by both midpoint steps, not passed over by their
/// norms or returned as a state.
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
    assert_eq!(
        integrators::variational_midpoint(&start, &inputs, 1e-3, 1e-12, 10).err(),
        Some(StepError::NonFinite)
    );
}

/// A step size or tolerance that is zero, negative or not finite, or no iteration at all, is
/// a bad argument and says so (it used to read as NonFinite, or as NotConverged with a last
/// change of 0).
#[test]
fn implicit_steps_reject_bad_arguments() {
    let (tau, p, loads) = ([0.0], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, StiffPendulum> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let start = State::<f64, StiffPendulum> { q: [0.5], v: [2.0] };
    let bad = [0.0, -1.0, f64::NAN, f64::INFINITY];
    let mut cases: Vec<(f64, f64, usize)> = Vec::new();
    for x in bad {
        cases.push((1e-3, x, 10));
        cases.push((x, 1e-12, 10));
    }
    cases.push((1e-3, 1e-12, 0));
    for (dt, tolerance, iterations) in cases {
        let implicit = integrators::implicit_midpoint(&start, &inputs, dt, tolerance, iterations);
        let variational =
            integrators::variational_midpoint(&start, &inputs, dt, tolerance, iterations);
        for (scheme, result) in [("implicit", implicit), ("variational", variational)] {
            assert!(
                matches!(result, Err(StepError::InvalidArgument { .. })),
                "{scheme} midpoint, dt {dt}, tolerance {tolerance}, {iterations} iterations: {:?}",
                result.err()
            );
        }
    }
}

mechanism! {
    /// A double pendulum with stiff dampers (decay rates of some hundred per second), with
    /// the derivatives of its dynamics: the implicit midpoint step's Newton Jacobian is exact.
    pub struct StiffDoubleExact;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics, forward_dynamics_derivatives];
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body lower { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z, damping: 20.0 }
    joint elbow: revolute(upper -> lower) { axis: z, at: [0.0, -0.4, 0.0], damping: 5.0 }
}

mechanism! {
    /// The same double pendulum without the derivatives: forward differences.
    pub struct StiffDoubleDifferenced;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics];
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body lower { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z, damping: 20.0 }
    joint elbow: revolute(upper -> lower) { axis: z, at: [0.0, -0.4, 0.0], damping: 5.0 }
}

/// An implicit step of a mechanism with two coordinates, no parameters and no loads, with
/// at most the given number of Newton iterations.
type Implicit<M> =
    fn(&State<f64, M>, &Inputs<f64, M>, f64, f64, usize) -> Result<State<f64, M>, StepError>;

/// 100 steps of `step` (dt = 0.01, tolerance 1e-12) from (0.9, −0.4) rad at (1.5, −2.0) rad/s
/// under τ = (0.3, −0.1): the end state and the Newton iterations of all steps (for each,
/// the fewest `max_iterations` with which it converges).
fn hundred_implicit_steps<M>(step: Implicit<M>) -> ([f64; 2], [f64; 2], usize)
where
    M: dynamics_runtime::Dynamics<
        f64,
        Configuration = [f64; 2],
        Velocity = [f64; 2],
        Parameters = [f64; 0],
        Loads = [f64; 0],
    >,
{
    let (tau, p, loads) = ([0.3, -0.1], [0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, M> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let (dt, tolerance) = (0.01, 1e-12);
    let mut s = State::<f64, M> {
        q: [0.9, -0.4],
        v: [1.5, -2.0],
    };
    let mut iterations = 0;
    for _ in 0..100 {
        iterations += (1..=30)
            .find(|&k| step(&s, &inputs, dt, tolerance, k).is_ok())
            .unwrap_or(usize::MAX);
        s = step(&s, &inputs, dt, tolerance, 30).expect("converges");
    }
    (s.q, s.v, iterations)
}

/// The same end state to 1e-9 (both solve their step's equations to the tolerance) and no
/// more Newton iterations for the exact Jacobian than for the differenced one.
fn assert_exact_matches_differenced(
    what: &str,
    (exact_q, exact_v, exact): ([f64; 2], [f64; 2], usize),
    (differenced_q, differenced_v, differenced): ([f64; 2], [f64; 2], usize),
) {
    println!("{what}: Newton iterations in 100 steps: exact {exact}, differenced {differenced}");
    for k in 0..2 {
        assert!(
            (exact_q[k] - differenced_q[k]).abs() < 1e-9
                && (exact_v[k] - differenced_v[k]).abs() < 1e-9,
            "{what}: q {exact_q:?} v {exact_v:?} against q {differenced_q:?} v {differenced_v:?}"
        );
    }
    assert!(exact <= differenced, "{what}: {exact} > {differenced}");
}

/// With the generated derivatives the implicit midpoint step takes the exact Newton Jacobian:
/// the same trajectory as with forward differences (both solve F(w) = 0 to the tolerance),
/// in no more Newton iterations per step.
#[test]
fn implicit_midpoint_takes_the_exact_jacobian_when_the_derivatives_are_generated() {
    use dynamics_runtime::Dynamics;
    let (q, v, tau) = ([0.9, -0.4], [1.5, -2.0], [0.3, -0.1]);
    assert!(
        StiffDoubleExact::acceleration_derivatives(&q, &v, &tau, &[], &[]).is_some()
            && StiffDoubleDifferenced::acceleration_derivatives(&q, &v, &tau, &[], &[]).is_none()
    );
    assert_exact_matches_differenced(
        "implicit midpoint",
        hundred_implicit_steps::<StiffDoubleExact>(integrators::implicit_midpoint),
        hundred_implicit_steps::<StiffDoubleDifferenced>(integrators::implicit_midpoint),
    );
}

mechanism! {
    /// The stiff double pendulum with its Lagrangian's terms and the momentum derivatives:
    /// the variational midpoint step's Newton Jacobian is exact.
    pub struct StiffDoubleMomentum;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity, momentum_derivatives];
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body lower { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z, damping: 20.0 }
    joint elbow: revolute(upper -> lower) { axis: z, at: [0.0, -0.4, 0.0], damping: 5.0 }
}

mechanism! {
    /// The same without the momentum derivatives: the variational step differences.
    pub struct StiffDoubleLagrangian;
    gravity: [0.0, -9.81, 0.0];
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity];
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body lower { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z, damping: 20.0 }
    joint elbow: revolute(upper -> lower) { axis: z, at: [0.0, -0.4, 0.0], damping: 5.0 }
}

/// `exact_momentum_jacobian` is the derivative of the variational step's residual
/// R(v̄) = M(q̄) v̄ − h/2 (C(q̄, v̄)ᵀ v̄ − g(q̄) + F(q̄, v̄)), F = M q̈ + C v̄ + g with q̈ the
/// generated forward dynamics (the force of the damping and τ), q̄ = q + v̄ h/2, taken here
/// by dual numbers through the generated M, C, g and forward dynamics; within 1e-12.
#[test]
fn variational_jacobian_is_the_dual_derivative_of_the_residual() {
    use dynamics_runtime::Dual;
    type D = Dual<f64>;
    type S = StiffDoubleMomentum;
    let (q, w, tau, h) = ([0.9, -0.4], [1.5, -2.0], [0.3, -0.1], 0.01);
    let (p, loads) = ([0.0; 0], [0.0; 0]);
    let inputs = Inputs::<f64, S> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    let jacobian = integrators::exact_momentum_jacobian(&q, &w, &inputs, h).expect("generated");
    let differenced = Inputs::<f64, StiffDoubleLagrangian> {
        tau: &tau,
        parameters: &p,
        loads: &loads,
    };
    assert!(integrators::exact_momentum_jacobian(&q, &w, &differenced, h).is_none());
    for col in 0..2 {
        let wd: [D; 2] = std::array::from_fn(|i| {
            if i == col {
                D::variable(w[i])
            } else {
                D::constant(w[i])
            }
        });
        let half_h = D::constant(h / 2.0);
        let q_mid: [D; 2] = std::array::from_fn(|i| D::constant(q[i]) + half_h * wd[i]);
        let mass = S::mass_matrix(&q_mid);
        let coriolis = S::coriolis_matrix(&q_mid, &wd);
        let gravity = S::gravity(&q_mid);
        let qdd = S::forward_dynamics(&q_mid, &wd, &tau.map(D::constant));
        for row in 0..2 {
            let (mut momentum, mut force, mut dl_dq) =
                (D::constant(0.0), gravity[row], -gravity[row]);
            for j in 0..2 {
                momentum += mass[row][j] * wd[j];
                force += mass[row][j] * qdd[j] + coriolis[row][j] * wd[j];
                dl_dq += coriolis[j][row] * wd[j];
            }
            let residual = momentum - half_h * (dl_dq + force);
            let (got, expected) = (jacobian[row][col], residual.derivative);
            assert!(
                (got - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                "∂R/∂v̄[{row}][{col}]: {got}, dual numbers {expected}"
            );
        }
    }
}

/// With `momentum_derivatives` generated the variational midpoint step takes the exact Newton
/// Jacobian: the same trajectory as with forward differences (both solve the discrete
/// Euler–Lagrange equations to the tolerance), in no more Newton iterations (261 either way
/// in 100 steps, measured; a Jacobian without its ∂p/∂q term took 345 and fails).
#[test]
fn variational_midpoint_takes_the_exact_jacobian_when_the_momentum_derivatives_are_generated() {
    assert_exact_matches_differenced(
        "variational midpoint",
        hundred_implicit_steps::<StiffDoubleMomentum>(integrators::variational_midpoint),
        hundred_implicit_steps::<StiffDoubleLagrangian>(integrators::variational_midpoint),
    );
}
