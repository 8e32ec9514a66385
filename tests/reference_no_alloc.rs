//! The reference allocates nothing once its workspace exists: a counting global allocator
//! (this test binary's own, so it holds a single test) sees no allocation, reallocation or
//! deallocation during any method of [`Reference`] after [`Reference::new`], from the first
//! call on, for a fixed-base arm (the UR5 anchor) and for a tree with a free-flyer root,
//! revolute and prismatic joints, armature, damping and loads in body and world axes. It
//! first lets the harness's main thread block ([`dynamics_tests::let_the_harness_settle`]),
//! whose first wait allocates once.

use dynamics_runtime::{
    BodySpec, Inertia, JointSpec, LoadSpec, Model, ModelBuilder, Reference, Wrench,
};
use dynamics_tests::anchors;
use nalgebra::{DMatrix, Vector3};
use stats_alloc::{Region, StatsAlloc, INSTRUMENTED_SYSTEM};
use std::alloc::System;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

fn floating_tree() -> Model {
    let body = |name: &str, mass: f64| {
        BodySpec::new(
            name,
            Inertia::new(
                mass,
                [0.05, -0.02, 0.1],
                [
                    [0.02, 0.001, 0.0],
                    [0.001, 0.03, 0.002],
                    [0.0, 0.002, 0.025],
                ],
            ),
        )
    };
    ModelBuilder::new()
        .gravity([0.0, 0.0, -9.81])
        .body(body("base", 5.0))
        .body(body("arm", 1.0))
        .body(body("slider", 0.5))
        .body(body("leg", 0.8))
        .joint(JointSpec::free_flyer("float", "base").with_armature(0.01))
        .joint(
            JointSpec::revolute("shoulder", "base", "arm", [0.0, 1.0, 0.0])
                .at([0.1, 0.0, 0.2])
                .with_armature(0.05)
                .with_damping(0.2),
        )
        .joint(
            JointSpec::prismatic("slide", "arm", "slider", [1.0, 0.0, 0.0])
                .at([0.3, 0.0, 0.0])
                .with_damping(1.0),
        )
        .joint(JointSpec::revolute("hip", "base", "leg", [1.0, 0.0, 0.0]).at([0.0, 0.1, -0.2]))
        .load(LoadSpec::force("push", "slider").at([0.05, 0.0, 0.1]))
        .load(
            LoadSpec::wrench("wind", "leg")
                .at([0.0, 0.2, 0.0])
                .in_world(),
        )
        .build()
        .expect("valid model")
}

/// Every public method of the reference once, on preallocated inputs and outputs.
fn exercise(reference: &mut Reference<f64>, q: &[f64], v: &[f64], a: &[f64]) -> f64 {
    let nv = v.len();
    let n = reference.model().bodies().len();
    let wrenches = vec![Wrench::new(Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.1, 0.2, -0.3)); n];
    let mut out = vec![0.0; nv];
    let mut qdd = vec![0.0; nv];
    let mut matrix = DMatrix::zeros(nv, nv);
    let mut reactions = vec![Wrench::zero(); n];
    let loads: Vec<f64> = (0..reference.model().num_load_inputs())
        .map(|k| 0.5 * k as f64 - 1.0)
        .collect();
    let mut load_forces = vec![0.0; nv];

    let region = Region::new(GLOBAL);
    reference
        .inverse_dynamics(q, v, a, Some(&wrenches), &mut out)
        .expect("sizes match");
    reference
        .inverse_dynamics(q, v, a, None, &mut out)
        .expect("sizes match");
    reference.gravity(q, &mut out).expect("sizes match");
    reference.bias(q, v, &mut out).expect("sizes match");
    reference
        .nonlinear_effects(q, v, &mut out)
        .expect("sizes match");
    reference
        .coriolis_matrix(q, v, &mut matrix)
        .expect("sizes match");
    reference.mass_matrix(q, &mut matrix).expect("sizes match");
    reference
        .forward_dynamics(q, v, &out, Some(&wrenches), &mut qdd)
        .expect("sizes match");
    reference
        .forward_dynamics(q, v, &out, None, &mut qdd)
        .expect("sizes match");
    let energy = reference.kinetic_energy(q, v).expect("sizes match")
        + reference.potential_energy(q).expect("sizes match");
    reference
        .joint_reactions(q, v, a, Some(&wrenches), &mut reactions)
        .expect("sizes match");
    reference
        .generalized_load_forces(q, &loads, &mut load_forces)
        .expect("sizes match");
    let x = reference.body_poses(q).expect("sizes match")[n - 1]
        .origin_in_world
        .x;
    // The error path allocates nothing either.
    let wrong = reference.gravity(&q[1..], &mut out);
    let change = region.change();

    assert!(wrong.is_err());
    assert_eq!(
        (
            change.allocations,
            change.reallocations,
            change.deallocations
        ),
        (0, 0, 0),
        "the reference allocated: {change:?}"
    );
    energy + x + qdd[0] + matrix[(0, 0)] + reactions[0].force.x + load_forces[0]
}

#[test]
fn reference_methods_allocate_nothing_after_new() {
    dynamics_tests::let_the_harness_settle();
    let ur5 = anchors::load("ur5").unwrap_or_else(|e| panic!("{e}"));
    let model = ur5.model.builder().build().expect("ur5 builds");
    let sample = &ur5.samples[0];
    let mut reference = Reference::<f64>::new(&model);
    let checksum = exercise(&mut reference, &sample.q, &sample.v, &sample.a);
    assert!(checksum.is_finite());

    let model = floating_tree();
    let mut q = model.neutral_configuration();
    q[0] = 0.3;
    q[3..7].copy_from_slice(&[0.1, -0.2, 0.3, (1.0f64 - 0.14).sqrt()]);
    q[7] = 0.4;
    q[8] = 0.1;
    q[9] = -0.7;
    let v: Vec<f64> = (0..model.nv()).map(|k| 0.3 * k as f64 - 1.0).collect();
    let a: Vec<f64> = (0..model.nv()).map(|k| 1.0 - 0.2 * k as f64).collect();
    let mut reference = Reference::<f64>::new(&model);
    let checksum = exercise(&mut reference, &q, &v, &a);
    assert!(checksum.is_finite());
}
