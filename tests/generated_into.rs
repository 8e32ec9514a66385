//! The `<name>_into` twins (asked for as `mass_matrix_into` in `outputs:`): each writes
//! into the caller's `out` exactly what its function returns, bit for bit, and every entry
//! of `out` (filled with NaN before the call), on `f64` and on `F64x4` lanes, for
//! functions in one piece (the entries written as they are computed), cut into pieces
//! (each output written by the piece that computes it) and finished by a solve loop (∂q̈,
//! its right-hand sides written into `out` and solved there), in one piece or several.
//! (A triple of matrices with loads, a stack of poses and a one-piece solve loop are in
//! `generated_derivatives.rs`, on its loaded arm and free tree.)

use dynamics_runtime::{mechanism, F64x4, Mechanism, Scalar};
use dynamics_tests::into_twins::{assert_same, state, wobble, Bits};

mechanism! {
    pub struct PandaInto;
    urdf: "../models/urdf/panda.urdf";
    outputs: [inverse_dynamics, mass_matrix_into, coriolis_matrix_into, kinetic_energy_into,
              joint_reactions_into, inverse_dynamics_derivatives_into,
              forward_dynamics_derivatives_into, mass_matrix_inverse_into];
}

/// A ten-link spatial chain (axes z, y, x in turn) named `$name`, with the settings given:
/// its Coriolis matrix and ∂τ are cut into two pieces each, its ∂q̈ into three.
macro_rules! chain {
    ($name:ident; $($setting:tt)*) => {
        mechanism! {
            pub struct $name;
            $($setting)*
            body l0 { mass: 1.0, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l1 { mass: 1.1, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l2 { mass: 1.2, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l3 { mass: 1.3, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l4 { mass: 1.4, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l5 { mass: 1.5, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l6 { mass: 1.6, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l7 { mass: 1.7, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l8 { mass: 1.8, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            body l9 { mass: 1.9, com: [0.1, 0.01, 0.02], inertia: [[0.01, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.015]] }
            joint j0: revolute(ground -> l0) { axis: z, at: [0.2, 0.0, 0.05] }
            joint j1: revolute(l0 -> l1) { axis: y, at: [0.2, 0.0, 0.05] }
            joint j2: revolute(l1 -> l2) { axis: x, at: [0.2, 0.0, 0.05] }
            joint j3: revolute(l2 -> l3) { axis: z, at: [0.2, 0.0, 0.05] }
            joint j4: revolute(l3 -> l4) { axis: y, at: [0.2, 0.0, 0.05] }
            joint j5: revolute(l4 -> l5) { axis: x, at: [0.2, 0.0, 0.05] }
            joint j6: revolute(l5 -> l6) { axis: z, at: [0.2, 0.0, 0.05] }
            joint j7: revolute(l6 -> l7) { axis: y, at: [0.2, 0.0, 0.05] }
            joint j8: revolute(l7 -> l8) { axis: x, at: [0.2, 0.0, 0.05] }
            joint j9: revolute(l8 -> l9) { axis: z, at: [0.2, 0.0, 0.05] }
        }
    };
}

chain! {
    ChainInto;
    outputs: [coriolis_matrix_into, inverse_dynamics_derivatives_into, mass_matrix_inverse_into,
              forward_dynamics_derivatives_into];
}

// The same chain with the baseline copies only: its pieces are plain functions.
chain! {
    ChainIntoBaseline;
    isa: baseline;
    outputs: [coriolis_matrix_into, forward_dynamics_derivatives_into];
}

const PANDA: usize = <PandaInto as Mechanism>::NV;

/// The Panda's twins at one state, on any scalar (`n` is NaN in it): the mass matrix and
/// the Coriolis matrix (written as computed), ∂τ (a pair, as computed) and ∂q̈ (a pair,
/// finished by a solve loop, written after it).
fn panda_twins<T: Scalar + Bits>(
    (q, v, a): ([T; PANDA], [T; PANDA], [T; PANDA]),
    n: T,
    what: &dyn Fn(&str) -> String,
) {
    const N: usize = PANDA;
    assert_same(
        PandaInto::mass_matrix(&q),
        [[n; N]; N],
        |o| PandaInto::mass_matrix_into(&q, o),
        &what("mass_matrix"),
    );
    assert_same(
        PandaInto::coriolis_matrix(&q, &v),
        [[n; N]; N],
        |o| PandaInto::coriolis_matrix_into(&q, &v, o),
        &what("coriolis_matrix"),
    );
    assert_same(
        PandaInto::inverse_dynamics_derivatives(&q, &v, &a),
        ([[n; N]; N], [[n; N]; N]),
        |o| PandaInto::inverse_dynamics_derivatives_into(&q, &v, &a, o),
        &what("∂τ"),
    );
    assert_same(
        PandaInto::forward_dynamics_derivatives(&q, &v, &a),
        ([[n; N]; N], [[n; N]; N]),
        |o| PandaInto::forward_dynamics_derivatives_into(&q, &v, &a, o),
        &what("∂q̈"),
    );
}

#[test]
fn the_into_twins_write_what_their_functions_return_on_f64() {
    const N: usize = PANDA;
    let n = f64::NAN;
    for seed in 0..10 {
        let (q, v, a): ([f64; N], [f64; N], [f64; N]) =
            (state(seed), state(seed + 100), state(seed + 200));
        let what = |f: &str| format!("Panda {f}, state {seed}");
        panda_twins((q, v, a), n, &what);
        assert_same(
            PandaInto::kinetic_energy(&q, &v),
            n,
            |o| PandaInto::kinetic_energy_into(&q, &v, o),
            &what("kinetic_energy"),
        );
        let reactions = PandaInto::joint_reactions(&q, &v, &a);
        assert_same(
            reactions,
            reactions.map(|w| w.map(|_| n)),
            |o| PandaInto::joint_reactions_into(&q, &v, &a, o),
            &what("joint_reactions"),
        );
        assert_same(
            PandaInto::mass_matrix_inverse(&q),
            [[n; N]; N],
            |o| PandaInto::mass_matrix_inverse_into(&q, o),
            &what("M⁻¹"),
        );
    }
}

#[test]
fn the_into_twins_write_what_their_functions_return_on_lanes() {
    let lanes = |seed: usize| -> [F64x4; PANDA] {
        std::array::from_fn(|i| F64x4::from_fn(|k| wobble(seed * 131 + i * 4 + k)))
    };
    for seed in 0..5 {
        let state = (lanes(seed), lanes(seed + 50), lanes(seed + 90));
        let what = |f: &str| format!("Panda on F64x4, {f}, state {seed}");
        panda_twins(state, F64x4::splat(f64::NAN), &what);
    }
}

#[test]
fn functions_cut_into_pieces_write_each_output_in_the_piece_that_computes_it() {
    const N: usize = <ChainInto as Mechanism>::NV;
    let n = f64::NAN;
    for seed in 0..5 {
        let (q, v, a): ([f64; N], [f64; N], [f64; N]) =
            (state(seed + 300), state(seed + 400), state(seed + 500));
        let what = |f: &str| format!("chain {f}, state {seed}");
        assert_same(
            ChainInto::coriolis_matrix(&q, &v),
            [[n; N]; N],
            |o| ChainInto::coriolis_matrix_into(&q, &v, o),
            &what("coriolis_matrix"),
        );
        assert_same(
            ChainInto::inverse_dynamics_derivatives(&q, &v, &a),
            ([[n; N]; N], [[n; N]; N]),
            |o| ChainInto::inverse_dynamics_derivatives_into(&q, &v, &a, o),
            &what("∂τ"),
        );
        assert_same(
            ChainInto::mass_matrix_inverse(&q),
            [[n; N]; N],
            |o| ChainInto::mass_matrix_inverse_into(&q, o),
            &what("M⁻¹"),
        );
        assert_same(
            ChainInto::forward_dynamics_derivatives(&q, &v, &a),
            ([[n; N]; N], [[n; N]; N]),
            |o| ChainInto::forward_dynamics_derivatives_into(&q, &v, &a, o),
            &what("∂q̈ (three pieces, then the solve)"),
        );
        assert_same(
            ChainIntoBaseline::coriolis_matrix(&q, &v),
            [[n; N]; N],
            |o| ChainIntoBaseline::coriolis_matrix_into(&q, &v, o),
            &what("coriolis_matrix, baseline copies only"),
        );
        assert_same(
            ChainIntoBaseline::forward_dynamics_derivatives(&q, &v, &a),
            ([[n; N]; N], [[n; N]; N]),
            |o| ChainIntoBaseline::forward_dynamics_derivatives_into(&q, &v, &a, o),
            &what("∂q̈, baseline copies only"),
        );
        let lanes = |k: usize| -> [F64x4; N] {
            std::array::from_fn(|i| F64x4::from_fn(|l| wobble(seed * 97 + k * 41 + i * 4 + l)))
        };
        let (q, v, a) = (lanes(0), lanes(1), lanes(2));
        let n = F64x4::splat(f64::NAN);
        assert_same(
            ChainInto::coriolis_matrix(&q, &v),
            [[n; N]; N],
            |o| ChainInto::coriolis_matrix_into(&q, &v, o),
            &what("coriolis_matrix on F64x4"),
        );
        assert_same(
            ChainInto::forward_dynamics_derivatives(&q, &v, &a),
            ([[n; N]; N], [[n; N]; N]),
            |o| ChainInto::forward_dynamics_derivatives_into(&q, &v, &a, o),
            &what("∂q̈ on F64x4"),
        );
    }
}
