//! The `<name>_into` twins (asked for as `mass_matrix_into` in `outputs:`): each writes
//! into the caller's `out` exactly what its function returns, bit for bit, and every entry
//! of `out` (filled with NaN before the call), on `f64` and on `F64x4` lanes, for
//! functions in one piece (the entries written as they are computed), cut into pieces
//! (each output written by the piece that computes it) and finished by a solve loop (∂q̈,
//! its right-hand sides written into `out` and solved there), in one piece or several.
//! (A triple of matrices with loads, a stack of poses and a one-piece solve loop are in
//! `generated_derivatives.rs`, on its loaded arm and free tree.)
//!
//! The `<name>_sparse_into` twins write only the entries that can be nonzero (of M, those
//! on and above the diagonal): on a free-floating tree with two isomorphic legs (its M and
//! C computed over packed lanes) and on the chain cut into pieces.

use dynamics_runtime::{batch, mechanism, F64x4, Mechanism, Scalar};
use dynamics_tests::into_twins::{assert_same, assert_sparse, state, wobble, Bits};

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
              forward_dynamics_derivatives_into, mass_matrix_sparse_into,
              coriolis_sparse_into, mass_matrix_inverse_sparse_into,
              forward_dynamics_derivatives_sparse_into];
}

mechanism! {
    /// A free base, two isomorphic two-link legs and a one-link arm: 11 dof, entries between
    /// branches zero in M and C.
    pub struct Legged;
    outputs: [mass_matrix_sparse_into, coriolis_matrix_sparse_into,
              centroidal_momentum_matrix_sparse_into, inverse_dynamics_derivatives_sparse_into,
              joint_jacobians_sparse_into];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body thigh_l { mass: 1.0, com: [0.0, 0.0, -0.1], shape: rod(length: 0.2, axis: z) }
    body shin_l { mass: 0.5, com: [0.0, 0.01, -0.1], shape: rod(length: 0.2, axis: z) }
    body thigh_r { mass: 1.0, com: [0.0, 0.0, -0.1], shape: rod(length: 0.2, axis: z) }
    body shin_r { mass: 0.5, com: [0.0, 0.01, -0.1], shape: rod(length: 0.2, axis: z) }
    body arm { mass: 0.7, com: [0.1, 0.0, 0.02], shape: box(size: [0.2, 0.05, 0.05]) }
    joint float: free(ground -> base);
    joint hip_l: revolute(base -> thigh_l) { axis: y, at: [0.0, 0.1, -0.05] }
    joint knee_l: revolute(thigh_l -> shin_l) { axis: y, at: [0.0, 0.0, -0.2] }
    joint hip_r: revolute(base -> thigh_r) { axis: y, at: [0.0, -0.1, -0.05] }
    joint knee_r: revolute(thigh_r -> shin_r) { axis: y, at: [0.0, 0.0, -0.2] }
    joint shoulder: revolute(base -> arm) { axis: x, at: [0.1, 0.0, 0.1] }
}

/// A unit quaternion in q[3..7] (x y z w), the rest of `q` as it is.
fn normalized<T: Scalar>(mut q: [T; 12]) -> [T; 12] {
    let norm = (q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]).sqrt();
    for x in &mut q[3..7] {
        *x /= norm;
    }
    q
}

/// The legged tree's sparse twins at one state, on any scalar (`n` is NaN in it), each
/// leaving the entries between the legs and the arm.
fn legged_sparse_twins<T: Scalar + Bits>(
    (q, v): ([T; 12], [T; 11]),
    n: T,
    what: &dyn Fn(&str) -> String,
) {
    const N: usize = 11;
    let left = assert_sparse(
        Legged::mass_matrix(&q),
        [[n; N]; N],
        (N, N, true),
        |o| Legged::mass_matrix_sparse_into(&q, o),
        &what("mass_matrix"),
    );
    // Below the diagonal (55), between branches above it (2 × 2 legs, 2 × 1 leg–arm: 8),
    // and the zeros of the base's 6 × 6 block (m 1 off its diagonal, 0 in the mass
    // block's corner: 3 + 1 at least).
    assert!(
        left >= 55 + 8 + 3,
        "{}: {left} entries left",
        what("mass_matrix")
    );
    let left = assert_sparse(
        Legged::coriolis_matrix(&q, &v),
        [[n; N]; N],
        (N, N, false),
        |o| Legged::coriolis_matrix_sparse_into(&q, &v, o),
        &what("coriolis_matrix"),
    );
    assert!(
        left >= 16,
        "{}: {left} entries left",
        what("coriolis_matrix")
    );
    // A pair of matrices: ∂τ/∂q above ∂τ/∂q̇, 22 × 11 as `Bits` flattens them.
    let a = v.map(|x| x * x);
    let left = assert_sparse(
        Legged::inverse_dynamics_derivatives(&q, &v, &a),
        ([[n; N]; N], [[n; N]; N]),
        (2 * N, N, false),
        |o| Legged::inverse_dynamics_derivatives_sparse_into(&q, &v, &a, o),
        &what("inverse_dynamics_derivatives"),
    );
    assert!(
        left >= 16,
        "{}: {left} entries left",
        what("inverse_dynamics_derivatives")
    );
    // A stack of six 6 × 11 Jacobians, one per body: the columns of joints that do not
    // carry the body are zero.
    let left = assert_sparse(
        Legged::joint_jacobians(&q),
        [[[n; N]; 6]; 6],
        (6 * 6, N, false),
        |o| Legged::joint_jacobians_sparse_into(&q, o),
        &what("joint_jacobians"),
    );
    assert!(
        left >= 6 * (2 + 2 + 3),
        "{}: {left} entries left",
        what("joint_jacobians")
    );
    assert_sparse(
        Legged::centroidal_momentum_matrix(&q),
        [[n; N]; 6],
        (6, N, false),
        |o| Legged::centroidal_momentum_matrix_sparse_into(&q, o),
        &what("centroidal_momentum_matrix"),
    );
}

#[test]
fn the_sparse_twins_write_the_entries_that_can_be_nonzero() {
    for seed in 0..5 {
        let what = |f: &str| format!("legged {f}, state {seed}");
        let state = (normalized(state(seed + 700)), state(seed + 800));
        legged_sparse_twins(state, f64::NAN, &what);
        let lanes = |k: usize| -> [F64x4; 12] {
            std::array::from_fn(|i| F64x4::from_fn(|l| wobble(seed * 89 + k * 43 + i * 4 + l)))
        };
        let v = lanes(1);
        let what = |f: &str| format!("legged {f} on F64x4, state {seed}");
        legged_sparse_twins(
            (normalized(lanes(0)), std::array::from_fn(|i| v[i])),
            F64x4::splat(f64::NAN),
            &what,
        );
    }
}

/// `batch::map1_into` over a sparse twin: its packed buffer starts at zero and the twin
/// leaves the zeros, so each state's result is whole, M's lower triangle zero, on nine
/// states (a padded last pack of lanes).
#[test]
fn the_batch_helpers_take_the_sparse_twins() {
    const N: usize = 11;
    let q: Vec<[f64; 12]> = (0..9).map(|k| normalized(state(950 + k))).collect();
    let mut m = vec![[[f64::NAN; N]; N]; q.len()];
    batch::map1_into(&q, &mut m, Legged::mass_matrix_sparse_into).expect("equal lengths");
    for (k, (q, m)) in q.iter().zip(&m).enumerate() {
        let full = Legged::mass_matrix(q);
        for i in 0..N {
            for j in 0..N {
                let want = if j < i { 0.0 } else { full[i][j] };
                assert_eq!(m[i][j].to_bits(), want.to_bits(), "state {k}, ({i}, {j})");
            }
        }
    }
}

#[test]
fn a_sparse_twin_starting_from_zeros_holds_the_result() {
    const N: usize = 11;
    let (q, v): ([f64; 12], [f64; 11]) = (normalized(state(900)), state(901));
    let mut m = [[0.0_f64; N]; N];
    let mut c = [[0.0_f64; N]; N];
    for seed in 0..3 {
        let q = q.map(|x| x + 0.1 * seed as f64);
        let q = normalized(q);
        Legged::mass_matrix_sparse_into(&q, &mut m);
        Legged::coriolis_matrix_sparse_into(&q, &v, &mut c);
        let (full_m, full_c) = (Legged::mass_matrix(&q), Legged::coriolis_matrix(&q, &v));
        for i in 0..N {
            for j in 0..N {
                let want = if j < i { 0.0 } else { full_m[i][j] };
                assert_eq!(
                    m[i][j].to_bits(),
                    want.to_bits(),
                    "M ({i}, {j}), state {seed}"
                );
                assert_eq!(
                    c[i][j].to_bits(),
                    full_c[i][j].to_bits(),
                    "C ({i}, {j}), state {seed}"
                );
            }
        }
    }
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
        // Cut into pieces: the chain's M and M⁻¹ (no zeros: their upper triangles) and C
        // (no zeros: every entry); ∂q̈, finished by a solve loop, every entry.
        let n_upper = N * (N - 1) / 2;
        let left = assert_sparse(
            ChainInto::mass_matrix(&q),
            [[n; N]; N],
            (N, N, true),
            |o| ChainInto::mass_matrix_sparse_into(&q, o),
            &what("mass_matrix, sparse"),
        );
        assert_eq!(left, n_upper, "{}", what("mass_matrix, sparse"));
        assert_sparse(
            ChainInto::coriolis_matrix(&q, &v),
            [[n; N]; N],
            (N, N, false),
            |o| ChainInto::coriolis_matrix_sparse_into(&q, &v, o),
            &what("coriolis_matrix, sparse"),
        );
        let left = assert_sparse(
            ChainInto::mass_matrix_inverse(&q),
            [[n; N]; N],
            (N, N, true),
            |o| ChainInto::mass_matrix_inverse_sparse_into(&q, o),
            &what("M⁻¹, sparse"),
        );
        assert_eq!(left, n_upper, "{}", what("M⁻¹, sparse"));
        assert_same(
            ChainInto::forward_dynamics_derivatives(&q, &v, &a),
            ([[n; N]; N], [[n; N]; N]),
            |o| ChainInto::forward_dynamics_derivatives_sparse_into(&q, &v, &a, o),
            &what("∂q̈, sparse twin of a solve loop: every entry"),
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
