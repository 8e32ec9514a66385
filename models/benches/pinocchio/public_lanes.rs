//! Many states per call on one example-robot-data robot, for `public.sh --lanes`: the robot's
//! generated inverse dynamics, mass matrix (in place) and forward dynamics on 64 states, one
//! `f64` call per state against four states per call (`F64x4`, through
//! `dynamics_runtime::batch`, packing included, and on states already in lanes) and eight
//! (`F32x8`, through `batch`). The declaration says `lanes: true;`, as the bundled UR5 and
//! quadruped do.
//!
//! Before timing, every `F64x4` and `F32x8` result is checked against the `f64` call on the
//! same state: within 1e-12 (`F64x4`) and 1e-3 (`F32x8`) of the largest entry of that
//! output, or the example exits nonzero. Timing: 21 rounds, each timing every variant once
//! over enough repetitions of the 64 states to take about 5 ms, the order of the variants
//! turning from round to round; the figures are each variant's median ns per state and the
//! median of its per-round ratios `f64 / variant` (the throughput gain). Prints one
//! Markdown row per output. The states are those of `public_isa.rs` (20 seeded random ones,
//! repeated to 64), not Pinocchio's.

use dynamics_runtime::{batch, isa, F64x4, Mechanism};
use public_robot::Robot;
use std::hint::black_box;
use std::time::Instant;

#[path = "../../examples/support/paired.rs"]
mod paired;

const NQ: usize = <Robot as Mechanism>::NQ;
const NV: usize = <Robot as Mechanism>::NV;
/// States per measured batch.
const N: usize = 64;
const ROUNDS: usize = 21;

/// The variants' median ns per state, and the median per-round ratio of variant 0's time to
/// each variant's.
fn timed(variants: &mut [&mut dyn FnMut()]) -> Vec<(f64, f64)> {
    // Repetitions for about 5 ms of the slowest variant.
    let reps = variants
        .iter_mut()
        .map(|f| {
            let begin = Instant::now();
            f();
            begin.elapsed().as_secs_f64()
        })
        .fold(0.0_f64, f64::max);
    let reps = ((5e-3 / reps.max(1e-9)) as usize).clamp(1, 100_000);
    let count = variants.len();
    let mut ns = vec![Vec::new(); count];
    let mut ratio = vec![Vec::new(); count];
    for round in 0..ROUNDS {
        let mut this = vec![0.0; count];
        for k in 0..count {
            let v = (k + round) % count;
            let begin = Instant::now();
            for _ in 0..reps {
                variants[v]();
            }
            this[v] = begin.elapsed().as_nanos() as f64 / (reps * N) as f64;
        }
        for v in 0..count {
            ns[v].push(this[v]);
            ratio[v].push(this[0] / this[v]);
        }
    }
    ns.into_iter()
        .zip(ratio)
        .map(|(n, r)| (paired::median(n), paired::median(r)))
        .collect()
}

/// Exits nonzero when an entry of `other` differs from `reference`'s by more than
/// `tolerance` times the largest |entry| of `reference` (at least 1).
fn check(name: &str, what: &str, reference: &[Vec<f64>], other: &[Vec<f64>], tolerance: f64) {
    let scale = reference
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
        .max(1.0);
    let worst = reference
        .iter()
        .zip(other)
        .flat_map(|(r, o)| r.iter().zip(o).map(|(a, b)| (a - b).abs()))
        .fold(0.0_f64, f64::max);
    if !(worst <= tolerance * scale) {
        eprintln!(
            "public_lanes: {name} in {what} differs from f64 by {worst:e} (largest entry {scale:e})"
        );
        std::process::exit(1);
    }
}

fn row(robot: &str, name: &str, t: &[(f64, f64)]) {
    println!(
        "| {robot} | {name} | {:.1} | {:.1} ({:.2}×) | {:.1} ({:.2}×) | {:.1} ({:.2}×) |",
        t[0].0, t[1].0, t[1].1, t[2].0, t[2].1, t[3].0, t[3].1
    );
}

/// Each state's result as one list of `f64`.
fn flat<T: Copy + Into<f64>, const K: usize>(x: &[[T; K]]) -> Vec<Vec<f64>> {
    x.iter()
        .map(|r| r.iter().map(|&v| v.into()).collect())
        .collect()
}

/// Each state's matrix as one list of `f64`, row after row.
fn flat_matrix<T: Copy + Into<f64>, const K: usize>(x: &[[[T; K]; K]]) -> Vec<Vec<f64>> {
    x.iter()
        .map(|m| m.iter().flatten().map(|&v| v.into()).collect())
        .collect()
}

fn prepack<const K: usize>(x: &[[f64; K]]) -> Vec<[F64x4; K]> {
    x.chunks(4)
        .map(|c| std::array::from_fn(|k| F64x4::from_fn(|l| c[l][k])))
        .collect()
}

fn to_f32<const K: usize>(x: &[[f64; K]]) -> Vec<[f32; K]> {
    x.iter().map(|r| r.map(|v| v as f32)).collect()
}

fn main() {
    let robot = std::env::var("PUBLIC_ROBOT").unwrap_or_else(|_| "robot".to_owned());
    // f64 calls and the lanes in the copy f64 runs by default (AVX2 + FMA where the CPU has it).
    isa::choose(true);
    let quaternion = (NQ == NV + 1).then_some(3);
    let s = paired::states::<NQ, NV>(quaternion);
    let q: Vec<[f64; NQ]> = (0..N).map(|i| s[i % s.len()].0).collect();
    let v: Vec<[f64; NV]> = (0..N).map(|i| s[i % s.len()].1).collect();
    let a: Vec<[f64; NV]> = (0..N).map(|i| s[i % s.len()].2).collect();
    let (q32, v32, a32) = (to_f32(&q), to_f32(&v), to_f32(&a));
    let (pq, pv, pa) = (prepack(&q), prepack(&v), prepack(&a));
    let r = robot.as_str();

    // Inverse dynamics (a as accelerations) and forward dynamics (a as torques), each a
    // generated function handed on as it is, so that every variant calls the same code a
    // user's loop would.
    macro_rules! three_inputs {
        ($name:literal, $f:path) => {{
            let mut out = vec![[0.0; NV]; N];
            let mut out4 = vec![[0.0; NV]; N];
            let mut out32 = vec![[0.0_f32; NV]; N];
            let mut packed = vec![[F64x4::splat(0.0); NV]; N / 4];
            for i in 0..N {
                out[i] = $f(&q[i], &v[i], &a[i]);
            }
            let lanes_ok = batch::map3(&q, &v, &a, &mut out4, $f).is_ok()
                && batch::map3(&q32, &v32, &a32, &mut out32, $f).is_ok();
            if !lanes_ok {
                eprintln!("public_lanes: a batch's inputs differ in length");
                std::process::exit(1);
            }
            check($name, "F64x4", &flat(&out), &flat(&out4), 1e-12);
            check($name, "F32x8", &flat(&out), &flat(&out32), 1e-3);
            let t = timed(&mut [
                &mut || {
                    for i in 0..N {
                        out[i] = $f(&q[i], &v[i], &a[i]);
                    }
                    black_box(&mut out);
                },
                &mut || {
                    black_box(batch::map3(&q, &v, &a, &mut out4, $f).is_ok());
                    black_box(&mut out4);
                },
                &mut || {
                    for i in 0..N / 4 {
                        packed[i] = $f(&pq[i], &pv[i], &pa[i]);
                    }
                    black_box(&mut packed);
                },
                &mut || {
                    black_box(batch::map3(&q32, &v32, &a32, &mut out32, $f).is_ok());
                    black_box(&mut out32);
                },
            ]);
            row(r, $name, &t);
        }};
    }
    three_inputs!("inverse_dynamics", Robot::inverse_dynamics);
    three_inputs!("forward_dynamics", Robot::forward_dynamics);

    // The mass matrix in place, as a controller that keeps M's storage calls it.
    let mut m = vec![[[0.0; NV]; NV]; N];
    let mut m4 = vec![[[0.0; NV]; NV]; N];
    let mut m32 = vec![[[0.0_f32; NV]; NV]; N];
    let mut packed = vec![[[F64x4::splat(0.0); NV]; NV]; N / 4];
    for i in 0..N {
        Robot::mass_matrix_into(&q[i], &mut m[i]);
    }
    let lanes_ok = batch::map1_into(&q, &mut m4, |q, out| Robot::mass_matrix_into(q, out)).is_ok()
        && batch::map1_into(&q32, &mut m32, |q, out| Robot::mass_matrix_into(q, out)).is_ok();
    if !lanes_ok {
        eprintln!("public_lanes: a batch's inputs differ in length");
        std::process::exit(1);
    }
    check(
        "mass_matrix_into",
        "F64x4",
        &flat_matrix(&m),
        &flat_matrix(&m4),
        1e-12,
    );
    check(
        "mass_matrix_into",
        "F32x8",
        &flat_matrix(&m),
        &flat_matrix(&m32),
        1e-3,
    );
    let t = timed(&mut [
        &mut || {
            for i in 0..N {
                Robot::mass_matrix_into(&q[i], &mut m[i]);
            }
            black_box(&mut m);
        },
        &mut || {
            black_box(
                batch::map1_into(&q, &mut m4, |q, out| Robot::mass_matrix_into(q, out)).is_ok(),
            );
            black_box(&mut m4);
        },
        &mut || {
            for i in 0..N / 4 {
                Robot::mass_matrix_into(&pq[i], &mut packed[i]);
            }
            black_box(&mut packed);
        },
        &mut || {
            black_box(
                batch::map1_into(&q32, &mut m32, |q, out| Robot::mass_matrix_into(q, out)).is_ok(),
            );
            black_box(&mut m32);
        },
    ]);
    row(r, "mass_matrix_into", &t);
}
