//! Criterion benchmark: one implicit midpoint step of the UR5 with the Newton Jacobian
//! exact (the mechanism generates `forward_dynamics_derivatives`) and by forward
//! differences (it does not), from the same states.
//!
//! ```sh
//! cargo bench -p models --bench integrators
//! ```
//!
//! Ids `Ur5/implicit_midpoint/exact` and `Ur5/implicit_midpoint/differenced`; one measured
//! call is one step (dt = 5 ms, tolerance 1e-12) from one of 20 seeded states, taken in
//! turn. Before timing, the Newton iterations per step of both are printed (the fewest
//! `max_iterations` with which each step converges, summed over the states).

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_runtime::integrators::{self, Inputs, State};
use dynamics_runtime::{mechanism, Dynamics};
use std::hint::black_box;
use std::time::Duration;

mechanism! {
    /// The UR5 with the derivatives of its dynamics.
    pub struct Ur5Exact;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, forward_dynamics_derivatives];
}

mechanism! {
    /// The UR5 without them.
    pub struct Ur5Differenced;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics];
}

const DT: f64 = 5e-3;
const TOLERANCE: f64 = 1e-12;

/// 20 states: q, v and τ from a fixed sequence.
fn states() -> Vec<([f64; 6], [f64; 6], [f64; 6])> {
    (0..20)
        .map(|k| {
            let x = |i: usize, scale: f64| scale * ((k * 6 + i) as f64 * 0.731 + 0.3).sin();
            (
                std::array::from_fn(|i| x(i, 2.0)),
                std::array::from_fn(|i| x(i + 3, 1.5)),
                std::array::from_fn(|i| x(i + 7, 10.0)),
            )
        })
        .collect()
}

/// One step of `M` from a state, and the fewest Newton iterations it converges in.
fn step<M: Dynamics<f64, Configuration = [f64; 6], Velocity = [f64; 6]>>(
    (q, v, tau): &([f64; 6], [f64; 6], [f64; 6]),
    max_iterations: usize,
) -> Option<State<f64, M>> {
    let (p, loads) = (M::nominal_parameters(), M::zero_loads());
    let inputs = Inputs::<f64, M> {
        tau,
        parameters: &p,
        loads: &loads,
    };
    let s = State::<f64, M> { q: *q, v: *v };
    integrators::implicit_midpoint(&s, &inputs, DT, TOLERANCE, max_iterations).ok()
}

fn iterations<M: Dynamics<f64, Configuration = [f64; 6], Velocity = [f64; 6]>>() -> usize {
    states()
        .iter()
        .map(|s| {
            (1..=30)
                .find(|&k| step::<M>(s, k).is_some())
                .unwrap_or(usize::MAX)
        })
        .sum()
}

fn implicit_midpoint(c: &mut Criterion) {
    println!(
        "Newton iterations over 20 steps: exact {}, differenced {}",
        iterations::<Ur5Exact>(),
        iterations::<Ur5Differenced>()
    );
    let states = states();
    let mut group = c.benchmark_group("Ur5/implicit_midpoint");
    let mut k = 0;
    group.bench_function("exact", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            black_box(step::<Ur5Exact>(black_box(&states[k]), 30))
        });
    });
    group.bench_function("differenced", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            black_box(step::<Ur5Differenced>(black_box(&states[k]), 30))
        });
    });
    group.finish();
}

/// The group (criterion's macro makes it a public function).
#[allow(missing_docs)]
mod group {
    use super::*;
    criterion_group! {
        name = benches;
        config = Criterion::default()
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(3));
        targets = implicit_midpoint
    }
}
criterion_main!(group::benches);
