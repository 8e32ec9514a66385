//! States per second through the batch API on one and on two threads: 4,096 seeded states
//! of the UR5 and of the 18-dof quadruped, inverse dynamics, mass matrix (returned, and
//! written into the result's place by its `_into` twin) and forward dynamics.
//!
//! ```sh
//! cargo bench -p models --bench batch          # ~1 min after the build
//! ```
//!
//! Ids are `batch/<Model>/<function>/<variant>/<threads>`; one measured iteration evaluates
//! the function on all 4,096 states and keeps every result in memory. Variants:
//!
//! - `f64`: one call per state (the AVX2 + FMA copy where the CPU has both), the states
//!   split into blocks of 64 over rayon's threads;
//! - `F64x4`: `batch::map4`/`map1`/`map1_into` on one thread, `batch::par_map4`/`par_map1`/
//!   `par_map1_into` on two (the runtime's feature `rayon`), four states per call, packing
//!   included.
//!
//! Each runs in a rayon pool of 1 and of 2 threads. After criterion's own report, a table
//! gives millions of states per second: 4,096 over the median of criterion's 20 flat
//! samples.

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, SamplingMode};
use dynamics_runtime::{batch, Mechanism};
use models::anchors::Ur5;
use models::quadruped::Quadruped;
use rayon::prelude::*;
use std::hint::black_box;
use std::time::Duration;

/// States per measured iteration.
const N: usize = 4096;
/// States per rayon task for the one-state-per-call variant.
const BLOCK: usize = 64;

const UR5: usize = <Ur5 as Mechanism>::NV;
const QUAD_NQ: usize = <Quadruped as Mechanism>::NQ;
const QUAD_NV: usize = <Quadruped as Mechanism>::NV;
const QUAD_NL: usize = <Quadruped as Mechanism>::NUM_LOAD_INPUTS;

#[path = "support/states.rs"]
mod states;
#[path = "support/timing.rs"]
#[allow(dead_code)] // `ids`, which lanes.rs's table walks
mod timing;
use states::States;

/// `out[i] = f(i)` for every state, one call each, in blocks of [`BLOCK`] states over the
/// current rayon pool's threads.
fn each_state<O: Send>(out: &mut [O], f: impl Fn(usize) -> O + Sync) {
    each_state_into(out, |i, o| *o = f(i));
}

/// `f(i, &mut out[i])` for every state, one call each, as [`each_state`].
fn each_state_into<O: Send>(out: &mut [O], f: impl Fn(usize, &mut O) + Sync) {
    out.par_chunks_mut(BLOCK).enumerate().for_each(|(b, out)| {
        for (k, o) in out.iter_mut().enumerate() {
            f(b * BLOCK + k, o);
        }
    });
}

/// Times `f` (one iteration: all N states, run inside `pool`) as `<group>/<id>`.
fn bench(
    g: &mut BenchmarkGroup<'_, WallTime>,
    group: &str,
    id: &str,
    pool: &rayon::ThreadPool,
    mut f: impl FnMut() + Send,
) {
    timing::bench(g, group, id, || pool.install(&mut f));
}

/// One model's three functions, both variants, on 1 and 2 threads. The closures take
/// (q, v, a, loads) for inverse dynamics, q for the mass matrix, (q, v, τ, loads) for
/// forward dynamics, written for any scalar.
macro_rules! model {
    ($c:expr, $group:expr, $states:expr, $nv:expr,
     id: |$q:ident, $v:ident, $a:ident, $l:ident| $id:expr,
     mm: |$mq:ident| $mm:expr,
     mm_into: |$iq:ident, $io:ident| $mm_into:expr,
     fd: |$fq:ident, $fv:ident, $ft:ident, $fl:ident| $fd:expr) => {{
        let s = $states;
        let mut out = vec![[0.0_f64; $nv]; N];
        let mut m = vec![[[0.0_f64; $nv]; $nv]; N];
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a rayon pool");
            bench(
                $c,
                $group,
                &format!("inverse_dynamics/f64/{threads}"),
                &pool,
                || {
                    each_state(&mut out, |i| {
                        let ($q, $v, $a, $l) = (&s.q[i], &s.v[i], &s.a[i], &s.loads[i]);
                        $id
                    });
                    black_box(&mut out);
                },
            );
            bench(
                $c,
                $group,
                &format!("inverse_dynamics/F64x4/{threads}"),
                &pool,
                || {
                    let r = if threads == 1 {
                        batch::map4(&s.q, &s.v, &s.a, &s.loads, &mut out, |$q, $v, $a, $l| $id)
                    } else {
                        batch::par_map4(&s.q, &s.v, &s.a, &s.loads, &mut out, |$q, $v, $a, $l| $id)
                    };
                    black_box((r.is_ok(), &mut out));
                },
            );
            bench(
                $c,
                $group,
                &format!("mass_matrix/f64/{threads}"),
                &pool,
                || {
                    each_state(&mut m, |i| {
                        let $mq = &s.q[i];
                        $mm
                    });
                    black_box(&mut m);
                },
            );
            bench(
                $c,
                $group,
                &format!("mass_matrix/F64x4/{threads}"),
                &pool,
                || {
                    let r = if threads == 1 {
                        batch::map1(&s.q, &mut m, |$mq| $mm)
                    } else {
                        batch::par_map1(&s.q, &mut m, |$mq| $mm)
                    };
                    black_box((r.is_ok(), &mut m));
                },
            );
            bench(
                $c,
                $group,
                &format!("mass_matrix_into/f64/{threads}"),
                &pool,
                || {
                    each_state_into(&mut m, |i, $io| {
                        let $iq = &s.q[i];
                        $mm_into
                    });
                    black_box(&mut m);
                },
            );
            bench(
                $c,
                $group,
                &format!("mass_matrix_into/F64x4/{threads}"),
                &pool,
                || {
                    let r = if threads == 1 {
                        batch::map1_into(&s.q, &mut m, |$iq, $io| $mm_into)
                    } else {
                        batch::par_map1_into(&s.q, &mut m, |$iq, $io| $mm_into)
                    };
                    black_box((r.is_ok(), &mut m));
                },
            );
            bench(
                $c,
                $group,
                &format!("forward_dynamics/f64/{threads}"),
                &pool,
                || {
                    each_state(&mut out, |i| {
                        let ($fq, $fv, $ft, $fl) = (&s.q[i], &s.v[i], &s.tau[i], &s.loads[i]);
                        $fd
                    });
                    black_box(&mut out);
                },
            );
            bench(
                $c,
                $group,
                &format!("forward_dynamics/F64x4/{threads}"),
                &pool,
                || {
                    let r = if threads == 1 {
                        batch::map4(
                            &s.q,
                            &s.v,
                            &s.tau,
                            &s.loads,
                            &mut out,
                            |$fq, $fv, $ft, $fl| $fd,
                        )
                    } else {
                        batch::par_map4(
                            &s.q,
                            &s.v,
                            &s.tau,
                            &s.loads,
                            &mut out,
                            |$fq, $fv, $ft, $fl| $fd,
                        )
                    };
                    black_box((r.is_ok(), &mut out));
                },
            );
        }
    }};
}

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("batch/Ur5");
    g.sampling_mode(SamplingMode::Flat);
    model!(&mut g, "batch/Ur5", States::<UR5, UR5, 0>::new(1, N), UR5,
        id: |q, v, a, l| { let _ = l; Ur5::inverse_dynamics(q, v, a) },
        mm: |q| Ur5::mass_matrix(q),
        mm_into: |q, out| Ur5::mass_matrix_into(q, out),
        fd: |q, v, t, l| { let _ = l; Ur5::forward_dynamics(q, v, t) });
    g.finish();
    let mut g = c.benchmark_group("batch/Quadruped");
    g.sampling_mode(SamplingMode::Flat);
    model!(&mut g, "batch/Quadruped", States::<QUAD_NQ, QUAD_NV, QUAD_NL>::new(2, N), QUAD_NV,
        id: |q, v, a, l| Quadruped::inverse_dynamics(q, v, a, l),
        mm: |q| Quadruped::mass_matrix(q),
        mm_into: |q, out| Quadruped::mass_matrix_into(q, out),
        fd: |q, v, t, l| Quadruped::forward_dynamics(q, v, t, l));
    g.finish();
}

/// The table: millions of states per second, medians over the last 20 samples.
fn table() {
    let rate = |id: &str| timing::median_of_last(id, 20).map(|s| N as f64 / s / 1e6);
    println!("\nmillions of states per second (median of 20 samples, {N} states each)\n");
    println!("| model | function | f64, 1 thread | f64, 2 threads | F64x4, 1 thread | F64x4, 2 threads |");
    println!("| --- | --- | ---: | ---: | ---: | ---: |");
    for (model, name) in [("Ur5", "UR5"), ("Quadruped", "quadruped")] {
        for function in [
            "inverse_dynamics",
            "mass_matrix",
            "mass_matrix_into",
            "forward_dynamics",
        ] {
            let cell = |variant: &str, threads: usize| {
                rate(&format!("batch/{model}/{function}/{variant}/{threads}"))
                    .map_or_else(|| "–".to_owned(), |r| format!("{r:.2}"))
            };
            println!(
                "| {name} | {} | {} | {} | {} | {} |",
                match function.strip_suffix("_into") {
                    Some(base) => format!("{}, `_into`", base.replace('_', " ")),
                    None => function.replace('_', " "),
                },
                cell("f64", 1),
                cell("f64", 2),
                cell("F64x4", 1),
                cell("F64x4", 2)
            );
        }
    }
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    benches(&mut c);
    c.final_summary();
    table();
}
