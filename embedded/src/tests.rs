//! Host-side checks of the `no_std` arm (run with std, which the test harness needs): the
//! `f32` results against the same generated functions in `f64` and in double-double, the
//! gravity torques against the formula derived by hand, the forward dynamics against the
//! inverse, and the computed-torque loop closed through the runtime's RK4.

use super::{control_tick, simulate_step, Arm3, Gains, Target, NV};
use dynamics_runtime::{DoubleDouble, Scalar};
use std::vec::Vec;

/// A reproducible stream of uniform numbers in [−1, 1) (xorshift64).
fn uniform(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// One state: q in [−π, π), q̇ in [−2, 2) rad/s, q̈ in [−5, 5) rad/s², exact in `f32`.
fn states(count: usize) -> Vec<[[f32; NV]; 3]> {
    let mut next = uniform(0x9e37_79b9_7f4a_7c15);
    let mut draw = |scale: f64| -> [f32; NV] { core::array::from_fn(|_| (next() * scale) as f32) };
    (0..count)
        .map(|_| [draw(core::f64::consts::PI), draw(2.0), draw(5.0)])
        .collect()
}

/// The outputs the crate uses, flattened, at (q, q̇, q̈) in any scalar: τ, M, g, and the
/// forward dynamics under τ_f = τ evaluated in f64 and rounded to f32 (so that every type
/// gets the same torques and the forward dynamics' error is its own).
fn outputs<T: Scalar>(q: [f32; NV], v: [f32; NV], a: [f32; NV], to: fn(f32) -> T) -> [Vec<T>; 4] {
    let tau_f64 = Arm3::inverse_dynamics(&q.map(f64::from), &v.map(f64::from), &a.map(f64::from));
    let tau = tau_f64.map(|t| to(t as f32));
    let (q, v, a) = (q.map(to), v.map(to), a.map(to));
    [
        Arm3::inverse_dynamics(&q, &v, &a).to_vec(),
        Arm3::mass_matrix(&q).concat(),
        Arm3::gravity(&q).to_vec(),
        Arm3::forward_dynamics(&q, &v, &tau).to_vec(),
    ]
}

const NAMES: [&str; 4] = [
    "inverse_dynamics",
    "mass_matrix",
    "gravity",
    "forward_dynamics",
];

/// max |x − truth| / max |truth| (normwise relative error), truth at least 1e-30.
fn relative(x: &[f64], truth: &[f64]) -> f64 {
    let scale = truth.iter().fold(1e-30_f64, |m, t| m.max(t.abs()));
    x.iter()
        .zip(truth)
        .fold(0.0_f64, |m, (x, t)| m.max((x - t).abs()))
        / scale
}

/// The f32 outputs agree with the f64 ones to 1e-4 (normwise relative), on 500 states.
#[test]
fn f32_matches_f64() {
    for [q, v, a] in states(500) {
        let single = outputs(q, v, a, |x| x);
        let double = outputs(q, v, a, f64::from);
        for (k, name) in NAMES.iter().enumerate() {
            let single: Vec<f64> = single[k].iter().map(|&x| f64::from(x)).collect();
            let error = relative(&single, &double[k]);
            assert!(
                error < 1e-4,
                "{name} at q = {q:?}, v = {v:?}, a = {a:?}: f32 {single:?} against f64 {:?} ({error:e})",
                double[k]
            );
        }
    }
}

/// g(q) = ∂V/∂q written out: the turret's yaw does not move any height; the shoulder
/// lifts the upper arm's centre (0.15 m), the elbow (0.3 m), the forearm's centre (0.125 m
/// beyond) and the payload (0.25 m beyond); a positive pitch about y lowers the arm.
#[test]
fn gravity_matches_the_hand_formula() {
    let g = 9.81;
    let hand = |q: [f64; NV]| {
        let (c1, c12) = (q[1].cos(), (q[1] + q[2]).cos());
        let shoulder =
            -g * (1.5 * 0.15 * c1 + 0.8 * (0.3 * c1 + 0.125 * c12) + 0.3 * (0.3 * c1 + 0.25 * c12));
        let elbow = -g * (0.8 * 0.125 + 0.3 * 0.25) * c12;
        [0.0, shoulder, elbow]
    };
    for [q, _, _] in states(200) {
        let q64 = q.map(f64::from);
        let truth = hand(q64);
        let double = Arm3::gravity(&q64);
        assert!(
            relative(&double, &truth) < 1e-12,
            "f64 {double:?} against {truth:?}"
        );
        let single = Arm3::gravity(&q).map(f64::from);
        assert!(
            relative(&single, &truth) < 1e-5,
            "f32 {single:?} against {truth:?}"
        );
    }
}

/// The control tick's forward dynamics gives back the commanded acceleration (f32, 1e-4
/// relative to the larger of the two), its torques and mass matrix are the f64 ones to 1e-5.
#[test]
fn control_tick_is_consistent() {
    let gains = Gains {
        kp: [100.0; NV],
        kd: [20.0; NV],
    };
    for [q, v, a] in states(200) {
        let target = Target {
            q: a.map(|x| x * 0.2),
            v: v.map(|x| -x),
            a,
        };
        let tick = control_tick(&q, &v, &target, &gains);
        let commanded: Vec<f64> = tick.commanded.iter().map(|&x| f64::from(x)).collect();
        let back: Vec<f64> = tick.acceleration.iter().map(|&x| f64::from(x)).collect();
        assert!(
            relative(&back, &commanded) < 1e-4,
            "q̈ {back:?} against the command {commanded:?}"
        );
        let (q64, v64) = (q.map(f64::from), v.map(f64::from));
        let tau64 = Arm3::inverse_dynamics(&q64, &v64, &tick.commanded.map(f64::from));
        let tau: Vec<f64> = tick.tau.iter().map(|&x| f64::from(x)).collect();
        assert!(relative(&tau, &tau64) < 1e-5, "τ {tau:?} against {tau64:?}");
        let m: Vec<f64> = tick
            .mass_matrix
            .concat()
            .iter()
            .map(|&x| f64::from(x))
            .collect();
        assert!(relative(&m, &Arm3::mass_matrix(&q64).concat()) < 1e-5);
    }
}

/// The error of each f32 output against the same function evaluated in double-double
/// (~32 digits) at the same f32 inputs: the generated code's own f32 rounding, per output.
/// Printed (`cargo test -p dynamics-embedded-example -- --nocapture`); the bounds asserted
/// are about ten times the worst measured; f64's beside them for comparison.
#[test]
fn f32_accuracy_against_double_double() {
    let to_dd = |x: f32| DoubleDouble::new(f64::from(x));
    let mut worst = [[0.0_f64; 2]; 4];
    for [q, v, a] in states(1000) {
        let dd = outputs(q, v, a, to_dd);
        let single = outputs(q, v, a, |x| x);
        let double = outputs(q, v, a, f64::from);
        for k in 0..4 {
            let truth: Vec<f64> = dd[k].iter().map(|x| x.to_f64()).collect();
            let single: Vec<f64> = single[k].iter().map(|&x| f64::from(x)).collect();
            worst[k][0] = worst[k][0].max(relative(&single, &truth));
            worst[k][1] = worst[k][1].max(relative(&double[k], &truth));
        }
    }
    std::println!("Arm3, 1000 states: worst normwise relative error against double-double");
    std::println!("{:<18} {:>10} {:>10}", "output", "f32", "f64");
    for (k, name) in NAMES.iter().enumerate() {
        std::println!("{name:<18} {:>10.2e} {:>10.2e}", worst[k][0], worst[k][1]);
    }
    // Measured without std (baseline copies, libm): f32 3.6e-7, 2.4e-7, 4.6e-7 and 1.3e-5
    // (M⁻¹ amplifies), f64 9.0e-16, 3.6e-16, 5.9e-16 and 6.3e-14; with std on an AVX2 + FMA
    // host (fused copies): f32 5.9e-7, 1.9e-7, 2.9e-7, 7.2e-6, f64 up to 1.2e-14.
    let bounds = [[5e-6, 1e-14], [5e-6, 1e-14], [5e-6, 1e-14], [1.5e-4, 1e-12]];
    for (k, name) in NAMES.iter().enumerate() {
        assert!(worst[k][0] < bounds[k][0], "{name}: f32 {:e}", worst[k][0]);
        assert!(worst[k][1] < bounds[k][1], "{name}: f64 {:e}", worst[k][1]);
    }
}

/// The computed-torque loop, closed through RK4 at 1 kHz in f32, brings the arm from rest
/// to a fixed target within 1e-4 rad in 2 s (K_p = 100, K_d = 20: critically damped at
/// 10 rad/s) and to rest within 1e-3 rad/s.
#[test]
fn computed_torque_reaches_the_target() {
    let gains = Gains {
        kp: [100.0; NV],
        kd: [20.0; NV],
    };
    let target = Target {
        q: [0.8, -0.6, 1.2],
        v: [0.0; NV],
        a: [0.0; NV],
    };
    let (mut q, mut v) = ([0.0_f32; NV], [0.0_f32; NV]);
    for _ in 0..2000 {
        let tick = control_tick(&q, &v, &target, &gains);
        let next = simulate_step(&q, &v, &tick.tau, 1e-3);
        (q, v) = (next.q, next.v);
    }
    for i in 0..NV {
        assert!((q[i] - target.q[i]).abs() < 1e-4, "q = {q:?}");
        assert!(v[i].abs() < 1e-3, "v = {v:?}");
    }
}
