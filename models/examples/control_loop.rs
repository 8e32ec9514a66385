//! A real-time control loop: computed-torque tracking of the Franka Panda, the plant
//! simulated by the generated forward dynamics, and the latency of the controller's
//! per-tick work (inverse dynamics + mass matrix) over 10⁶ ticks, generated against the
//! runtime reference. Real-time users buy the tail, not the median.
//!
//! Controller (1 kHz): a_cmd = q̈_d + K_d (q̇_d − q̇) + K_p (q_d − q), τ = ID(q, q̇, a_cmd),
//! and M(q) (for a task-space layer or logging). Plant: RK4 on the generated
//! forward dynamics, 1 ms step. Run with
//! `cargo run --release -p models --example control_loop`.

use dynamics_runtime::integrators::{self, Inputs, State};
use dynamics_runtime::{Mechanism, Reference};
use models::anchors::Panda;
use nalgebra::DMatrix;
use std::hint::black_box;
use std::time::Instant;

const TICKS: usize = 1_000_000;
const DT: f64 = 1e-3;

/// Desired joint trajectory: q_d = q0 + A sin(ω t), with its derivatives.
fn desired(t: f64) -> ([f64; 7], [f64; 7], [f64; 7]) {
    let q0 = [0.0, -0.3, 0.0, -2.0, 0.0, 1.8, 0.8];
    let mut out = ([0.0; 7], [0.0; 7], [0.0; 7]);
    for k in 0..7 {
        let (amplitude, omega) = (0.3 + 0.05 * k as f64, 1.0 + 0.3 * k as f64);
        let (s, c) = (omega * t).sin_cos();
        out.0[k] = q0[k] + amplitude * s;
        out.1[k] = amplitude * omega * c;
        out.2[k] = -amplitude * omega * omega * s;
    }
    out
}

fn command(q: &[f64; 7], v: &[f64; 7], t: f64) -> [f64; 7] {
    let (kp, kd) = (400.0, 40.0);
    let (qd, vd, ad) = desired(t);
    std::array::from_fn(|k| ad[k] + kd * (vd[k] - v[k]) + kp * (qd[k] - q[k]))
}

/// p50, p99.9 and max of per-tick latencies (ns).
fn percentiles(mut ns: Vec<u32>) -> (u32, u32, u32) {
    ns.sort_unstable();
    let at = |p: f64| ns[((ns.len() - 1) as f64 * p) as usize];
    (at(0.5), at(0.999), *ns.last().unwrap_or(&0))
}

fn main() {
    // The generated code's instruction set (AVX2 + FMA copies or baseline ones) is chosen
    // at its first call, which reads `DYNAMICS_ISA` from the environment (an allocation):
    // make that call here, before the real-time loop, not in its first tick.
    let wide = dynamics_runtime::isa::wide();
    // Tracking with the generated code in the loop.
    let params = [0.0; 0];
    let loads = [0.0; 0];
    let start = desired(0.0);
    let mut state = State::<f64, Panda> {
        q: start.0,
        v: start.1,
    };
    let mut worst_error = 0.0_f64;
    let mut generated_ns = Vec::with_capacity(TICKS);
    for tick in 0..TICKS {
        let t = tick as f64 * DT;
        let a_cmd = command(&state.q, &state.v, t);
        let begin = Instant::now();
        let tau =
            Panda::inverse_dynamics(black_box(&state.q), black_box(&state.v), black_box(&a_cmd));
        let m = Panda::mass_matrix(black_box(&state.q));
        generated_ns.push(begin.elapsed().as_nanos() as u32);
        black_box(m);
        let inputs = Inputs::<f64, Panda> {
            tau: &tau,
            parameters: &params,
            loads: &loads,
        };
        state = integrators::rk4(&state, &inputs, DT);
        if tick > 1000 {
            let (qd, _, _) = desired(t + DT);
            worst_error = worst_error.max(
                (0..7)
                    .map(|k| (qd[k] - state.q[k]).abs())
                    .fold(0.0, f64::max),
            );
        }
    }
    // The same controller work by the runtime reference, on the same states.
    let model = Panda::model();
    let mut reference = Reference::<f64>::new(&model);
    let (mut tau_ref, mut m_ref) = (vec![0.0; 7], DMatrix::zeros(7, 7));
    let mut reference_ns = Vec::with_capacity(TICKS);
    let mut state = State::<f64, Panda> {
        q: start.0,
        v: start.1,
    };
    for tick in 0..TICKS {
        let t = tick as f64 * DT;
        let a_cmd = command(&state.q, &state.v, t);
        let begin = Instant::now();
        let _ = reference.inverse_dynamics(
            black_box(&state.q),
            black_box(&state.v),
            black_box(&a_cmd),
            None,
            &mut tau_ref,
        );
        let _ = reference.mass_matrix(black_box(&state.q), &mut m_ref);
        reference_ns.push(begin.elapsed().as_nanos() as u32);
        let tau: [f64; 7] = std::array::from_fn(|k| tau_ref[k]);
        let inputs = Inputs::<f64, Panda> {
            tau: &tau,
            parameters: &params,
            loads: &loads,
        };
        state = integrators::rk4(&state, &inputs, DT);
    }
    println!(
        "Computed-torque tracking of the {} ({} dof), 1 kHz, {TICKS} ticks ({} s):",
        Panda::NAME,
        Panda::NV,
        TICKS as f64 * DT
    );
    println!("  worst joint tracking error after the first second: {worst_error:.2e} rad");
    println!(
        "  generated code: {} copies (DYNAMICS_ISA=baseline pins the baseline ones)",
        if wide { "AVX2 + FMA" } else { "baseline" }
    );
    println!("  controller work per tick (inverse dynamics + mass matrix), ns:");
    println!("  {:<12} {:>8} {:>8} {:>8}", "", "p50", "p99.9", "max");
    for (name, ns) in [("generated", generated_ns), ("reference", reference_ns)] {
        let (p50, p999, max) = percentiles(ns);
        println!("  {name:<12} {p50:>8} {p999:>8} {max:>8}");
    }
    println!("  (one Instant pair of timer overhead included; the max is set by the OS scheduler");
    println!("  unless the loop runs on an isolated core with real-time priority)");
}
