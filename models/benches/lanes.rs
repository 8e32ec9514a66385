//! Throughput of the generated code on many states: one `f64` state per call against four
//! per call (`F64x4`) and eight (`F32x8`), through `dynamics_runtime::batch`, for the UR5
//! and the 18-dof quadruped: inverse dynamics, mass matrix, forward dynamics.
//!
//! ```sh
//! cargo bench -p models --bench lanes                 # everything (~2 min after the build)
//! cargo bench -p models --bench lanes -- 'Ur5/'       # one model
//! ```
//!
//! Ids are `lanes/<Model>/<function>/<variant>`, `mass_matrix_into` the mass matrix
//! written into the result's place (`Robot::mass_matrix_into`, in the `f64` variants and
//! `F64x4_prepacked`, and through `batch::map1_into` as `F64x4`); one measured iteration
//! evaluates the function on all 64 states of a fixed seeded set (angles in ±π, rates in
//! ±2, torques and accelerations in ±5, the quadruped's foot forces in [−20, 40] N, unit
//! quaternions) and keeps every result in memory. Variants:
//!
//! - `f64`: one call per state, on the AVX2 + FMA copy where the CPU has both
//!   (`isa::choose(true)`; the default choice, `dynamics_runtime::isa`);
//! - `f64_baseline`: the same, pinned to the baseline (SSE2) copy, the code `F32x8` runs
//!   (and `F64x4` in a build with AVX);
//! - `F64x4`: `batch::mapN` over the 64 states, 16 calls on four lanes, packing included,
//!   in the copy `f64` runs by default (a build without AVX; `dynamics_runtime::lanes`);
//! - `F64x4_prepacked`: the 16 calls alone, on states already in lanes;
//! - `F32x8`: `batch::mapN` over the same states in `f32`, 8 calls on eight lanes.
//!
//! After criterion's own report, a table gives each variant in ns per state: the median
//! of criterion's 30 samples (flat sampling, so each sample is the same number of
//! iterations) divided by 64. (With `--sample-size` on the command line the table still
//! takes the last 30 timed calls of each benchmark.)

use criterion::{Criterion, SamplingMode};
use dynamics_runtime::{batch, isa, F64x4, Mechanism};
use models::anchors::Ur5;
use models::quadruped::Quadruped;
use std::hint::black_box;
use std::time::Duration;

/// States per measured iteration.
const N: usize = 64;

const UR5: usize = <Ur5 as Mechanism>::NV;
const QUAD_NQ: usize = <Quadruped as Mechanism>::NQ;
const QUAD_NV: usize = <Quadruped as Mechanism>::NV;
const QUAD_NL: usize = <Quadruped as Mechanism>::NUM_LOAD_INPUTS;

#[path = "support/states.rs"]
mod states;
#[path = "support/timing.rs"]
mod timing;
use states::States;
use timing::bench;

fn to_f32<const K: usize>(x: &[[f64; K]]) -> Vec<[f32; K]> {
    x.iter().map(|x| x.map(|x| x as f32)).collect()
}

/// The N states of one field in packs of four lanes.
fn prepack<const K: usize>(x: &[[f64; K]]) -> Vec<[F64x4; K]> {
    x.chunks_exact(4)
        .map(|c| std::array::from_fn(|j| F64x4::from_fn(|k| c[k][j])))
        .collect()
}

/// One model's three functions in the five variants. `$ids`, `$mm`, `$fds`: the calls
/// on (q, v, a, loads) as `|q, v, a, l| ...` closures written for any scalar.
macro_rules! model {
    ($c:expr, $name:literal, $states:expr, $nv:expr,
     id: |$q:ident, $v:ident, $a:ident, $l:ident| $id:expr,
     mm: |$mq:ident| $mm:expr,
     mm_into: |$iq:ident, $io:ident| $mm_into:expr,
     fd: |$fq:ident, $fv:ident, $ft:ident, $fl:ident| $fd:expr) => {{
        let s = $states;
        let (q32, v32, a32, tau32, l32) = (
            to_f32(&s.q),
            to_f32(&s.v),
            to_f32(&s.a),
            to_f32(&s.tau),
            to_f32(&s.loads),
        );
        let (pq, pv, pa, ptau, pl) = (
            prepack(&s.q),
            prepack(&s.v),
            prepack(&s.a),
            prepack(&s.tau),
            prepack(&s.loads),
        );
        let mut out = vec![[0.0_f64; $nv]; N];
        let mut out32 = vec![[0.0_f32; $nv]; N];
        let mut packed_out = vec![[F64x4::splat(0.0); $nv]; N / 4];
        let mut m = vec![[[0.0_f64; $nv]; $nv]; N];
        let mut m32 = vec![[[0.0_f32; $nv]; $nv]; N];
        let mut packed_m = vec![[[F64x4::splat(0.0); $nv]; $nv]; N / 4];
        for (variant, wide) in [("f64", true), ("f64_baseline", false)] {
            isa::choose(wide);
            bench($c, $name, &format!("inverse_dynamics/{variant}"), || {
                for i in 0..N {
                    let ($q, $v, $a, $l) = (&s.q[i], &s.v[i], &s.a[i], &s.loads[i]);
                    out[i] = $id;
                }
                black_box(&mut out);
            });
            bench($c, $name, &format!("mass_matrix/{variant}"), || {
                for i in 0..N {
                    let $mq = &s.q[i];
                    m[i] = $mm;
                }
                black_box(&mut m);
            });
            bench($c, $name, &format!("mass_matrix_into/{variant}"), || {
                for i in 0..N {
                    let ($iq, $io) = (&s.q[i], &mut m[i]);
                    $mm_into;
                }
                black_box(&mut m);
            });
            bench($c, $name, &format!("forward_dynamics/{variant}"), || {
                for i in 0..N {
                    let ($fq, $fv, $ft, $fl) = (&s.q[i], &s.v[i], &s.tau[i], &s.loads[i]);
                    out[i] = $fd;
                }
                black_box(&mut out);
            });
        }
        // The lanes run the copy f64 runs by default (the AVX2 one where the CPU has it).
        isa::choose(true);
        bench($c, $name, "inverse_dynamics/F64x4", || {
            black_box(
                batch::map4(&s.q, &s.v, &s.a, &s.loads, &mut out, |$q, $v, $a, $l| $id).is_ok(),
            );
            black_box(&mut out);
        });
        bench($c, $name, "mass_matrix/F64x4", || {
            black_box(batch::map1(&s.q, &mut m, |$mq| $mm).is_ok());
            black_box(&mut m);
        });
        bench($c, $name, "mass_matrix_into/F64x4", || {
            black_box(batch::map1_into(&s.q, &mut m, |$iq, $io| $mm_into).is_ok());
            black_box(&mut m);
        });
        bench($c, $name, "forward_dynamics/F64x4", || {
            black_box(
                batch::map4(
                    &s.q,
                    &s.v,
                    &s.tau,
                    &s.loads,
                    &mut out,
                    |$fq, $fv, $ft, $fl| $fd,
                )
                .is_ok(),
            );
            black_box(&mut out);
        });

        bench($c, $name, "inverse_dynamics/F32x8", || {
            black_box(
                batch::map4(&q32, &v32, &a32, &l32, &mut out32, |$q, $v, $a, $l| $id).is_ok(),
            );
            black_box(&mut out32);
        });
        bench($c, $name, "mass_matrix/F32x8", || {
            black_box(batch::map1(&q32, &mut m32, |$mq| $mm).is_ok());
            black_box(&mut m32);
        });
        bench($c, $name, "forward_dynamics/F32x8", || {
            black_box(
                batch::map4(
                    &q32,
                    &v32,
                    &tau32,
                    &l32,
                    &mut out32,
                    |$fq, $fv, $ft, $fl| $fd,
                )
                .is_ok(),
            );
            black_box(&mut out32);
        });

        bench($c, $name, "inverse_dynamics/F64x4_prepacked", || {
            for i in 0..N / 4 {
                let ($q, $v, $a, $l) = (&pq[i], &pv[i], &pa[i], &pl[i]);
                packed_out[i] = $id;
            }
            black_box(&mut packed_out);
        });
        bench($c, $name, "mass_matrix/F64x4_prepacked", || {
            for i in 0..N / 4 {
                let $mq = &pq[i];
                packed_m[i] = $mm;
            }
            black_box(&mut packed_m);
        });
        bench($c, $name, "mass_matrix_into/F64x4_prepacked", || {
            for i in 0..N / 4 {
                let ($iq, $io) = (&pq[i], &mut packed_m[i]);
                $mm_into;
            }
            black_box(&mut packed_m);
        });
        bench($c, $name, "forward_dynamics/F64x4_prepacked", || {
            for i in 0..N / 4 {
                let ($fq, $fv, $ft, $fl) = (&pq[i], &pv[i], &ptau[i], &pl[i]);
                packed_out[i] = $fd;
            }
            black_box(&mut packed_out);
        });
    }};
}

fn benches(c: &mut Criterion) {
    let mut g = c.benchmark_group("lanes/Ur5");
    g.sampling_mode(SamplingMode::Flat);
    model!(&mut g, "lanes/Ur5", &States::<UR5, UR5, 0>::new(1, N), UR5,
        id: |q, v, a, _l| Ur5::inverse_dynamics(q, v, a),
        mm: |q| Ur5::mass_matrix(q),
        mm_into: |q, out| Ur5::mass_matrix_into(q, out),
        fd: |q, v, tau, _l| Ur5::forward_dynamics(q, v, tau));
    g.finish();
    let mut g = c.benchmark_group("lanes/Quadruped");
    g.sampling_mode(SamplingMode::Flat);
    model!(&mut g, "lanes/Quadruped", &States::<QUAD_NQ, QUAD_NV, QUAD_NL>::new(2, N), QUAD_NV,
        id: |q, v, a, l| Quadruped::inverse_dynamics(q, v, a, l),
        mm: |q| Quadruped::mass_matrix(q),
        mm_into: |q, out| Quadruped::mass_matrix_into(q, out),
        fd: |q, v, tau, l| Quadruped::forward_dynamics(q, v, tau, l));
    g.finish();
}

/// The median of the last `samples` recorded calls of each benchmark (criterion's samples;
/// the calls before them are its warm-up), ns per state, as a table per model and function.
fn table(samples: usize) {
    const VARIANTS: [&str; 5] = ["f64", "f64_baseline", "F64x4", "F64x4_prepacked", "F32x8"];
    let ns_per_state = |id: &str| timing::median_of_last(id, samples).map(|s| s * 1e9 / N as f64);
    let medians: Vec<(String, f64)> = timing::ids()
        .into_iter()
        .filter_map(|id| ns_per_state(&id).map(|ns| (id, ns)))
        .collect();
    if medians.is_empty() {
        return;
    }
    println!("\nns per state (median of {samples} samples of {N} states each):\n");
    println!("| model | function | {} |", VARIANTS.join(" | "));
    println!("| --- | --- |{}", " ---: |".repeat(VARIANTS.len()));
    let mut rows: Vec<String> = Vec::new();
    for (id, _) in &medians {
        if let Some((row, _)) = id.rsplit_once('/') {
            if !rows.iter().any(|r| r == row) {
                rows.push(row.to_string());
            }
        }
    }
    for row in rows {
        let mut parts = row.split('/').skip(1);
        let (model, function) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
        let cells: Vec<String> = VARIANTS
            .iter()
            .map(|v| {
                medians
                    .iter()
                    .find(|(id, _)| *id == format!("{row}/{v}"))
                    .map_or("–".to_string(), |(_, ns)| format!("{ns:.1}"))
            })
            .collect();
        println!("| {model} | {function} | {} |", cells.join(" | "));
    }
}

fn main() {
    const SAMPLES: usize = 30;
    let mut c = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(2000))
        .sample_size(SAMPLES)
        .configure_from_args();
    benches(&mut c);
    c.final_summary();
    table(SAMPLES);
}
