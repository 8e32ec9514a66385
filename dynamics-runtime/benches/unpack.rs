//! What the batch helpers pay to hand back a large result: `batch::map1_into` over 64
//! states of an 18 × 18 matrix (the quadruped's mass matrix, 2.6 kB a state) with a
//! function that computes nothing, so that only packing q and unpacking the packed result
//! (the 4 × 4 transposes) is timed, beside a plain copy of the same 64 matrices.
//!
//! ```sh
//! cargo bench -p dynamics-runtime --bench unpack
//! ```
//!
//! `unpack/map1_into_18x18`: the helper, in the copy the kernels run (AVX2 + FMA where the
//! CPU has them); `unpack/copy_18x18`: `out[i] = src[i]` for the 64 matrices. ns per
//! iteration of 64 states; divide by 64 for a state.

use criterion::{criterion_main, Criterion};
use dynamics_runtime::{batch, isa, F64x4};
use std::hint::black_box;

const N: usize = 64;

fn benches() {
    let mut c = Criterion::default().configure_from_args();
    isa::choose(true);
    let q = vec![[0.5_f64; 19]; N];
    let mut m = vec![[[0.0_f64; 18]; 18]; N];
    c.bench_function("unpack/map1_into_18x18", |b| {
        b.iter(|| {
            let done = batch::map1_into(
                &q,
                &mut m,
                |q: &[F64x4; 19], out: &mut [[F64x4; 18]; 18]| {
                    black_box(q);
                    black_box(out);
                },
            );
            black_box(done.is_ok());
            black_box(&mut m);
        })
    });
    let src = vec![[[0.25_f64; 18]; 18]; N];
    c.bench_function("unpack/copy_18x18", |b| {
        b.iter(|| {
            for (o, s) in m.iter_mut().zip(black_box(&src)) {
                *o = *s;
            }
            black_box(&mut m);
        })
    });
}

criterion_main!(benches);
