//! Criterion benchmark: one implicit midpoint step of the UR5 and one variational midpoint
//! step of the UR5 and of the Panda with the Newton Jacobian exact (the mechanism generates `forward_dynamics_derivatives`,
//! or `momentum_derivatives` for the variational step) and by forward differences (it does
//! not), from the same states.
//!
//! ```sh
//! cargo bench -p models --bench integrators
//! ```
//!
//! Ids `Ur5/implicit_midpoint/{exact,differenced}` and
//! `{Ur5,Panda}/variational_midpoint/{exact,differenced}`; one measured call is one step (dt = 5 ms,
//! tolerance 1e-12) from one of 20 seeded states, taken in turn. Before timing, the Newton
//! iterations per step of each are printed (the fewest `max_iterations` with which each
//! step converges, summed over the states).

use criterion::{criterion_group, criterion_main, Criterion};
use dynamics_runtime::integrators::{self, Inputs, State};
use dynamics_runtime::{mechanism, Lagrangian};
use std::hint::black_box;
use std::time::Duration;

mechanism! {
    /// The UR5 with the derivatives of its dynamics.
    pub struct Ur5Exact;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity,
              forward_dynamics_derivatives];
}

mechanism! {
    /// The UR5 without them.
    pub struct Ur5Differenced;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity];
}

mechanism! {
    /// The UR5 with its Lagrangian's terms and the momentum derivatives.
    pub struct Ur5MomentumExact;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity, momentum_derivatives];
}

mechanism! {
    /// The UR5 with its Lagrangian's terms only.
    pub struct Ur5MomentumDifferenced;
    urdf: "urdf/ur5.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity];
}

mechanism! {
    /// The Panda with its Lagrangian's terms and the momentum derivatives.
    pub struct PandaMomentumExact;
    urdf: "urdf/panda.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity, momentum_derivatives];
}

mechanism! {
    /// The Panda with its Lagrangian's terms only.
    pub struct PandaMomentumDifferenced;
    urdf: "urdf/panda.urdf";
    outputs: [forward_dynamics, mass_matrix, coriolis_matrix, gravity];
}

const DT: f64 = 5e-3;
const TOLERANCE: f64 = 1e-12;

/// 20 states: q, v and τ from a fixed sequence.
fn states<const N: usize>() -> Vec<([f64; N], [f64; N], [f64; N])> {
    (0..20)
        .map(|k| {
            let x = |i: usize, scale: f64| scale * ((k * N + i) as f64 * 0.731 + 0.3).sin();
            (
                std::array::from_fn(|i| x(i, 2.0)),
                std::array::from_fn(|i| x(i + 3, 1.5)),
                std::array::from_fn(|i| x(i + 7, 10.0)),
            )
        })
        .collect()
}

/// Which implicit step.
#[derive(Clone, Copy)]
enum Method {
    Midpoint,
    Variational,
}

/// One step of `M` by `method` from a state; `None` if it does not converge in
/// `max_iterations`.
fn step<const N: usize, M: Lagrangian<f64, Configuration = [f64; N], Velocity = [f64; N]>>(
    method: Method,
    (q, v, tau): &([f64; N], [f64; N], [f64; N]),
    max_iterations: usize,
) -> Option<State<f64, M>> {
    let (p, loads) = (M::nominal_parameters(), M::zero_loads());
    let inputs = Inputs::<f64, M> {
        tau,
        parameters: &p,
        loads: &loads,
    };
    let s = State::<f64, M> { q: *q, v: *v };
    match method {
        Method::Midpoint => {
            integrators::implicit_midpoint(&s, &inputs, DT, TOLERANCE, max_iterations).ok()
        }
        Method::Variational => {
            integrators::variational_midpoint(&s, &inputs, DT, TOLERANCE, max_iterations).ok()
        }
    }
}

/// The fewest Newton iterations of each step, summed over the states.
fn iterations<const N: usize, M: Lagrangian<f64, Configuration = [f64; N], Velocity = [f64; N]>>(
    method: Method,
) -> usize {
    states::<N>()
        .iter()
        .map(|s| {
            (1..=30)
                .find(|&k| step::<N, M>(method, s, k).is_some())
                .unwrap_or(usize::MAX)
        })
        .sum()
}

/// Times one step of `Exact` and of `Differenced` by `method`, after printing their
/// iteration counts.
fn compare<const N: usize, Exact, Differenced>(c: &mut Criterion, method: Method, name: &str)
where
    Exact: Lagrangian<f64, Configuration = [f64; N], Velocity = [f64; N]>,
    Differenced: Lagrangian<f64, Configuration = [f64; N], Velocity = [f64; N]>,
{
    println!(
        "{name}: Newton iterations over 20 steps: exact {}, differenced {}",
        iterations::<N, Exact>(method),
        iterations::<N, Differenced>(method)
    );
    let states = states::<N>();
    let mut group = c.benchmark_group(name);
    let mut k = 0;
    group.bench_function("exact", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            black_box(step::<N, Exact>(method, black_box(&states[k]), 30))
        });
    });
    group.bench_function("differenced", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            black_box(step::<N, Differenced>(method, black_box(&states[k]), 30))
        });
    });
    group.finish();
}

fn implicit_steps(c: &mut Criterion) {
    compare::<6, Ur5Exact, Ur5Differenced>(c, Method::Midpoint, "Ur5/implicit_midpoint");
    compare::<6, Ur5MomentumExact, Ur5MomentumDifferenced>(
        c,
        Method::Variational,
        "Ur5/variational_midpoint",
    );
    compare::<7, PandaMomentumExact, PandaMomentumDifferenced>(
        c,
        Method::Variational,
        "Panda/variational_midpoint",
    );
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
        targets = implicit_steps
    }
}
criterion_main!(group::benches);
