//! The generated functions allocate nothing: a counting global allocator (this test
//! binary's own, so it holds a single test) sees no allocation, reallocation or
//! deallocation while every generated function, and its nalgebra wrapper `*_na`, runs once
//! in double and once in single precision, for the UR5 and the Panda (every output), the
//! textbook's free-flying gyroscopic body (the outputs it asks for) and a random tree of
//! `tests/build.rs` with loads, a symbolic mass, armature and damping, and forward dynamics
//! by both methods.

use dynamics_runtime::nalgebra::SVector;
use dynamics_runtime::Scalar;
use models::anchors::{Panda, Ur5};
use models::seed::GyroscopicBody;
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};
use std::alloc::System;
use std::hint::black_box;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

mod trees {
    //! One random tree of `tests/build.rs`: six joints, armature, damping, three loads, a
    //! symbolic mass, forward dynamics by both methods.
    #![allow(dead_code)]
    include!(concat!(env!("OUT_DIR"), "/random_tree_06.rs"));
}
use trees::RandomTree06;

/// An input of length N with varied entries (a unit quaternion is not needed: nothing
/// here checks values).
fn input<T: Scalar, const N: usize>(offset: f64) -> [T; N] {
    std::array::from_fn(|k| T::from_f64(0.3 + offset + 0.17 * k as f64))
}

/// Calls every generated function of a mechanism with every output, and its `_na` twin,
/// with the parameters and loads (if any) after the state; sums one entry of each result
/// so that nothing is optimized away.
macro_rules! every_function {
    ($t:ty, $m:ty, nq: $nq:expr, nv: $nv:expr $(, p: $np:expr)? $(, loads: $nl:expr)?
) => {{
        let q: [$t; $nq] = black_box(input(0.0));
        let v: [$t; $nv] = black_box(input(0.1));
        let a: [$t; $nv] = black_box(input(0.2));
        let tau: [$t; $nv] = black_box(input(0.3));
        $(let p: [$t; $np] = black_box(input(0.5));)?
        $(let loads: [$t; $nl] = black_box(input(0.4));)?
        let (qn, vn, an, taun) = (
            SVector::from(q), SVector::from(v), SVector::from(a), SVector::from(tau),
        );
        $(let pn: SVector<$t, $np> = SVector::from(p);)?
        $(let loadsn: SVector<$t, $nl> = SVector::from(loads);)?
        let mut sum: $t = 0.0;
        sum += <$m>::inverse_dynamics(&q, &v, &a, $(&p as &[$t; $np],)? $(&loads as &[$t; $nl],)?)[0];
        sum += <$m>::inverse_dynamics_na(&qn, &vn, &an, $(&pn as &SVector<$t, $np>,)? $(&loadsn as &SVector<$t, $nl>,)?)[0];
        sum += <$m>::gravity(&q, $(&p as &[$t; $np],)?)[0];
        sum += <$m>::gravity_na(&qn, $(&pn as &SVector<$t, $np>,)?)[0];
        sum += <$m>::bias(&q, &v, $(&p as &[$t; $np],)?)[0];
        sum += <$m>::bias_na(&qn, &vn, $(&pn as &SVector<$t, $np>,)?)[0];
        sum += <$m>::mass_matrix(&q, $(&p as &[$t; $np],)?)[0][0];
        sum += <$m>::mass_matrix_na(&qn, $(&pn as &SVector<$t, $np>,)?)[(0, 0)];
        sum += <$m>::coriolis_matrix(&q, &v, $(&p as &[$t; $np],)?)[0][0];
        sum += <$m>::coriolis_matrix_na(&qn, &vn, $(&pn as &SVector<$t, $np>,)?)[(0, 0)];
        sum += <$m>::forward_dynamics(&q, &v, &tau, $(&p as &[$t; $np],)? $(&loads as &[$t; $nl],)?)[0];
        sum += <$m>::forward_dynamics_na(&qn, &vn, &taun, $(&pn as &SVector<$t, $np>,)? $(&loadsn as &SVector<$t, $nl>,)?)[0];
        sum += <$m>::kinetic_energy(&q, &v, $(&p as &[$t; $np],)?);
        sum += <$m>::kinetic_energy_na(&qn, &vn, $(&pn as &SVector<$t, $np>,)?);
        sum += <$m>::potential_energy(&q, $(&p as &[$t; $np],)?);
        sum += <$m>::potential_energy_na(&qn, $(&pn as &SVector<$t, $np>,)?);
        sum += <$m>::joint_reactions(&q, &v, &a, $(&p as &[$t; $np],)? $(&loads as &[$t; $nl],)?)[0][0];
        sum += <$m>::joint_reactions_na(&qn, &vn, &an, $(&pn as &SVector<$t, $np>,)? $(&loadsn as &SVector<$t, $nl>,)?)[(0, 0)];
        black_box(sum)
    }};
}

/// The random tree also asks for forward dynamics by both methods.
macro_rules! forward_dynamics_twins {
    ($t:ty) => {{
        let q: [$t; 6] = black_box(input(0.0));
        let v: [$t; 6] = black_box(input(0.1));
        let tau: [$t; 6] = black_box(input(0.3));
        let p: [$t; 1] = black_box(input(0.5));
        let loads: [$t; 12] = black_box(input(0.4));
        let (qn, vn, taun) = (SVector::from(q), SVector::from(v), SVector::from(tau));
        let (pn, loadsn) = (SVector::from(p), SVector::from(loads));
        let mut sum: $t = 0.0;
        sum += RandomTree06::forward_dynamics_aba(&q, &v, &tau, &p, &loads)[0];
        sum += RandomTree06::forward_dynamics_aba_na(&qn, &vn, &taun, &pn, &loadsn)[0];
        sum += RandomTree06::forward_dynamics_ldlt(&q, &v, &tau, &p, &loads)[0];
        sum += RandomTree06::forward_dynamics_ldlt_na(&qn, &vn, &taun, &pn, &loadsn)[0];
        black_box(sum)
    }};
}

/// The free body generates inverse dynamics, mass matrix, forward dynamics and energies
/// only.
macro_rules! gyroscopic_body {
    ($t:ty) => {{
        let q: [$t; 7] = black_box(input(0.0));
        let v: [$t; 6] = black_box(input(0.1));
        let a: [$t; 6] = black_box(input(0.2));
        let (qn, vn, an) = (SVector::from(q), SVector::from(v), SVector::from(a));
        let mut sum: $t = 0.0;
        sum += GyroscopicBody::inverse_dynamics(&q, &v, &a)[0];
        sum += GyroscopicBody::inverse_dynamics_na(&qn, &vn, &an)[0];
        sum += GyroscopicBody::mass_matrix(&q)[0][0] + GyroscopicBody::mass_matrix_na(&qn)[(0, 0)];
        sum += GyroscopicBody::forward_dynamics(&q, &v, &a)[0];
        sum += GyroscopicBody::forward_dynamics_na(&qn, &vn, &an)[0];
        sum += GyroscopicBody::kinetic_energy(&q, &v) + GyroscopicBody::kinetic_energy_na(&qn, &vn);
        sum += GyroscopicBody::potential_energy(&q) + GyroscopicBody::potential_energy_na(&qn);
        black_box(sum)
    }};
}

#[test]
fn generated_functions_allocate_nothing() {
    // The allocator is global: the test harness's own threads can allocate while the
    // functions run (seen once, on a loaded machine). Code that allocates does so on every
    // run, so three runs with one of them clean is the test.
    let mut changes = Vec::new();
    for _ in 0..3 {
        let (sums, change) = run_every_function();
        // Something was computed (the values themselves are checked elsewhere).
        assert!(sums.iter().all(|s| s.is_finite()), "{sums:?}");
        let counts = (
            change.allocations,
            change.reallocations,
            change.deallocations,
        );
        changes.push(counts);
        if counts == (0, 0, 0) {
            break;
        }
    }
    assert_eq!(
        changes.last(),
        Some(&(0, 0, 0)),
        "the generated code allocated (allocations, reallocations, deallocations) in every run: {changes:?}"
    );
    use dynamics_runtime::Mechanism;
    assert_eq!(
        (
            RandomTree06::PARAMETER_NAMES.len(),
            RandomTree06::NUM_LOAD_INPUTS
        ),
        (1, 12)
    );
}

/// Every function once, and what the allocator saw meanwhile.
fn run_every_function() -> ([f64; 10], stats_alloc::Stats) {
    let region = Region::new(GLOBAL);
    let sums = [
        every_function!(f64, Ur5, nq: 6, nv: 6),
        f64::from(every_function!(f32, Ur5, nq: 6, nv: 6)),
        every_function!(f64, Panda, nq: 7, nv: 7),
        f64::from(every_function!(f32, Panda, nq: 7, nv: 7)),
        every_function!(f64, RandomTree06, nq: 6, nv: 6, p: 1, loads: 12),
        f64::from(every_function!(f32, RandomTree06, nq: 6, nv: 6, p: 1, loads: 12)),
        forward_dynamics_twins!(f64),
        f64::from(forward_dynamics_twins!(f32)),
        gyroscopic_body!(f64),
        f64::from(gyroscopic_body!(f32)),
    ];
    (sums, region.change())
}
