//! The batch helpers allocate nothing: a counting global allocator (this test binary's own,
//! so it holds a single test) sees no allocation, reallocation or deallocation while
//! `batch::map1`..`map3` run the UR5's inverse dynamics, mass matrix, forward dynamics and
//! bias, and `batch::map1_into` its mass matrix written in place, on 13 states (a padded last pack), on `F64x4` and on `F32x8`.

use dynamics_runtime::batch;
use models::anchors::Ur5;
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};
use std::alloc::System;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

const N: usize = 13;

/// The four functions through the batch helpers, on states and outputs allocated before;
/// what the allocator saw meanwhile, and whether every call returned `Ok`.
macro_rules! run {
    ($t:ty) => {{
        let q: [[$t; 6]; N] =
            std::array::from_fn(|i| std::array::from_fn(|k| (0.1 * (i + k) as f64) as $t));
        let v: [[$t; 6]; N] = std::array::from_fn(|i| {
            std::array::from_fn(|k| (0.2 * k as f64 - 0.03 * i as f64) as $t)
        });
        let a = black_box(v);
        let zero: $t = 0.0;
        let (mut tau, mut qdd, mut h) = ([[zero; 6]; N], [[zero; 6]; N], [[zero; 6]; N]);
        let mut m = [[[zero; 6]; 6]; N];
        let region = Region::new(GLOBAL);
        let ok = [
            batch::map3(&q, &v, &a, &mut tau, Ur5::inverse_dynamics).is_ok(),
            batch::map1(&q, &mut m, Ur5::mass_matrix).is_ok(),
            batch::map3(&q, &v, &tau, &mut qdd, Ur5::forward_dynamics).is_ok(),
            batch::map2(&q, &v, &mut h, Ur5::bias).is_ok(),
            batch::map1_into(&q, &mut m, Ur5::mass_matrix_into).is_ok(),
        ];
        let change = region.change();
        black_box((&tau, &m, &qdd, &h));
        (
            ok,
            (
                change.allocations,
                change.reallocations,
                change.deallocations,
            ),
        )
    }};
}

#[test]
fn batch_helpers_allocate_nothing() {
    // The allocator is global: the test harness's own threads can allocate meanwhile (as
    // in generated_no_alloc.rs); code that allocates does so on every run, so three runs
    // with one of them clean is the test.
    let mut changes = Vec::new();
    for _ in 0..3 {
        let (ok64, change64) = run!(f64);
        let (ok32, change32) = run!(f32);
        assert!(ok64.iter().chain(&ok32).all(|ok| *ok));
        changes.push((change64, change32));
        if (change64, change32) == ((0, 0, 0), (0, 0, 0)) {
            break;
        }
    }
    assert_eq!(
        changes.last(),
        Some(&((0, 0, 0), (0, 0, 0))),
        "the batch helpers allocated (allocations, reallocations, deallocations; F64x4, F32x8) in every run: {changes:?}"
    );
}
