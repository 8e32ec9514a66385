//! The loop that generated code runs for solves on large trees (`tree_ldlt`), alone, on the
//! coordinate trees of two public robots: a humanoid with a free base (35 coordinates: the
//! base's six in a chain, two legs of six on it, a waist of three, two arms of seven on the
//! waist; 306 (coordinate, ancestor) pairs, the tree of Unitree's G1) and a quadruped (18: the
//! base's six, four legs of three; 99 pairs, Unitree's Go2).
//!
//! ```sh
//! cargo bench -p dynamics-runtime --bench tree_ldlt
//! ```
//!
//! `tree_ldlt/<robot>/solve_columns`: M X = B for two matrices of nv columns, as the forward
//! dynamics derivatives solve ∂q̈/∂q and ∂q̈/∂v; `tree_ldlt/<robot>/solve_lower_columns`: the
//! last sweep alone on one nv × nv matrix, as M⁻¹ finishes. Each in the copy a generated
//! function runs (`Scalar::run_kernel`: AVX2 + FMA on this machine), on a factor and
//! right-hand sides of seeded numbers, the matrices restored from a copy at every
//! iteration, row by row (the copy is part of the time). ns per call.

use criterion::{criterion_main, Criterion};
use dynamics_runtime::tree_ldlt::{solve_columns, solve_lower_columns, CoordinateTree};
use dynamics_runtime::Scalar;
use std::hint::black_box;

/// The number of (coordinate, ancestor) pairs of a tree given by its parents.
const fn pairs<const N: usize>(parents: [Option<usize>; N]) -> usize {
    let mut depth = [0; N];
    let mut total = 0;
    let mut k = 0;
    while k < N {
        if let Some(i) = parents[k] {
            depth[k] = depth[i] + 1;
        }
        total += depth[k];
        k += 1;
    }
    total
}

/// Coordinate `first..first + len` in a chain below `parent`.
const fn chain<const N: usize>(
    mut parents: [Option<usize>; N],
    parent: Option<usize>,
    first: usize,
    len: usize,
) -> [Option<usize>; N] {
    let mut k = 0;
    while k < len {
        parents[first + k] = if k == 0 { parent } else { Some(first + k - 1) };
        k += 1;
    }
    parents
}

/// The humanoid's 35 coordinates, depth first.
const HUMANOID: [Option<usize>; 35] = {
    let p = chain([None; 35], None, 0, 6);
    let p = chain(p, Some(5), 6, 6);
    let p = chain(p, Some(5), 12, 6);
    let p = chain(p, Some(5), 18, 3);
    let p = chain(p, Some(20), 21, 7);
    chain(p, Some(20), 28, 7)
};

/// The quadruped's 18 coordinates, depth first.
const QUADRUPED: [Option<usize>; 18] = {
    let p = chain([None; 18], None, 0, 6);
    let p = chain(p, Some(5), 6, 3);
    let p = chain(p, Some(5), 9, 3);
    let p = chain(p, Some(5), 12, 3);
    chain(p, Some(5), 15, 3)
};

/// Seeded numbers in [−0.5, 0.5) (a fixed xorshift stream).
fn numbers(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

/// `x = b`, row by row: one copy of the whole matrix is a call of the C library's
/// `memmove`, whose `rep movsb` took this machine (AMD Zen 4, glibc 2.36) about 3 µs for
/// the humanoid's 9.8 kB, more than the solve.
#[inline(always)]
fn restore<const N: usize>(x: &mut [[f64; N]; N], b: &[[f64; N]; N]) {
    for (row, b_row) in x.iter_mut().zip(b) {
        *row = *black_box(b_row);
    }
}

fn bench_tree<const N: usize, const P: usize>(
    c: &mut Criterion,
    robot: &str,
    tree: &CoordinateTree<N, P>,
) {
    let mut next = numbers(0x9e37_79b9_7f4a_7c15);
    let factor: [f64; P] = std::array::from_fn(|_| next());
    let inverse_pivot: [f64; N] = std::array::from_fn(|_| 1.0 + next());
    let b: [[f64; N]; N] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
    let b2: [[f64; N]; N] = std::array::from_fn(|_| std::array::from_fn(|_| next()));
    let mut group = c.benchmark_group(format!("tree_ldlt/{robot}"));
    group.bench_function("solve_columns", |bencher| {
        let mut xy = (b, b2);
        bencher.iter(|| {
            restore(&mut xy.0, &b);
            restore(&mut xy.1, &b2);
            f64::run_kernel_into(
                &mut xy,
                #[inline(always)]
                |isa, (x, y)| solve_columns(isa, tree, &factor, &inverse_pivot, [x, y]),
                #[inline(always)]
                |isa, (x, y)| solve_columns(isa, tree, &factor, &inverse_pivot, [x, y]),
            );
            black_box(&xy);
        });
    });
    group.bench_function("solve_lower_columns", |bencher| {
        let mut x = b;
        bencher.iter(|| {
            restore(&mut x, &b);
            f64::run_kernel_into(
                &mut x,
                #[inline(always)]
                |isa, x| solve_lower_columns(isa, tree, &factor, [x]),
                #[inline(always)]
                |isa, x| solve_lower_columns(isa, tree, &factor, [x]),
            );
            black_box(&x);
        });
    });
    group.finish();
}

fn benches() {
    const H: CoordinateTree<35, { pairs(HUMANOID) }> = CoordinateTree::new(HUMANOID);
    const Q: CoordinateTree<18, { pairs(QUADRUPED) }> = CoordinateTree::new(QUADRUPED);
    let mut c = Criterion::default().configure_from_args();
    bench_tree(&mut c, "humanoid", &H);
    bench_tree(&mut c, "quadruped", &Q);
}

criterion_main!(benches);
