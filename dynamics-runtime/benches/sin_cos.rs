//! `sin_cos` of f64 alone: std (glibc's `sincos`, a call) against `fast_trig::sin_cos`
//! (inlined polynomial), its `mul_add` twin, and `fast_trig::sin_cos_array` (six angles in
//! one loop, which LLVM vectorizes two by two).
//!
//! ```sh
//! cargo bench -p dynamics-runtime --bench sin_cos
//! ```
//!
//! `sin_cos/<variant>/throughput`: one measured iteration is the sines and cosines of six
//! independent angles (a six-joint arm's), summed so that none is dead code; the angles are
//! 64 sets of six, uniform in [−π, π], taken in turn. `sin_cos/<variant>/latency`: six calls
//! in a chain, each angle depending on the previous result, so that nothing overlaps.
//! `sin_cos/fast_array/throughput`: the six of a set in one `sin_cos_array` call.
//! ns per iteration; divide by six for one pair.

use criterion::{criterion_main, Criterion};
use dynamics_runtime::__private::fast_trig;
use std::f64::consts::PI;
use std::hint::black_box;

/// 64 sets of six angles, uniform in [−π, π] (a fixed xorshift stream).
fn angles() -> Vec<[f64; 6]> {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * PI - PI
    };
    (0..64).map(|_| std::array::from_fn(|_| next())).collect()
}

/// The two benchmarks of one variant; a macro, so that each variant is inlined as it would
/// be in generated code (a function pointer would make every variant a call).
macro_rules! bench_variant {
    ($group:expr, $sets:expr, $name:expr, $f:path) => {
        $group.bench_function(format!("{}/throughput", $name), |b| {
            let mut i = 0;
            b.iter(|| {
                let q = black_box(&$sets[i % $sets.len()]);
                i += 1;
                let mut sum = 0.0;
                for &x in q {
                    let (s, c) = $f(x);
                    sum += s * c;
                }
                sum
            })
        });
        $group.bench_function(format!("{}/latency", $name), |b| {
            let mut i = 0;
            b.iter(|| {
                let q = black_box(&$sets[i % $sets.len()]);
                i += 1;
                let mut carry = 0.0;
                for &x in q {
                    let (s, c) = $f(x + carry);
                    carry = (s * c) * 1e-300;
                }
                carry
            })
        });
    };
}

fn bench(c: &mut Criterion) {
    let sets = angles();
    let mut group = c.benchmark_group("sin_cos");
    bench_variant!(group, sets, "std", f64::sin_cos);
    bench_variant!(group, sets, "fast", fast_trig::sin_cos);
    bench_variant!(group, sets, "fast_mul_add", fast_trig::sin_cos_mul_add);
    group.bench_function("fast_array/throughput", |b| {
        let mut i = 0;
        b.iter(|| {
            let q = black_box(&sets[i % sets.len()]);
            i += 1;
            let (s, c) = fast_trig::sin_cos_array(q);
            let mut sum = 0.0;
            for k in 0..6 {
                sum += s[k] * c[k];
            }
            sum
        })
    });
    group.finish();
}

/// The group (criterion's macro makes it a public function).
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench);
}

criterion_main!(group::benches);
