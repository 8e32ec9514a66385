//! The `<name>_into` twins (asked for as `mass_matrix_into` in `outputs:`): each writes
//! into the caller's `out` exactly what its function returns, bit for bit, and every entry
//! of `out` (filled with NaN before the call), on `f64` and on `F64x4` lanes, for
//! functions in one piece (the entries written as they are computed), cut into pieces
//! (each output written by the piece that computes it) and finished by a solve loop (∂q̈,
//! its right-hand sides written into `out` and solved there), in one piece or several.

use dynamics_runtime::{mechanism, F64x4, Mechanism, Scalar};

mechanism! {
    pub struct PandaInto;
    urdf: "../models/urdf/panda.urdf";
    outputs: [inverse_dynamics, mass_matrix_into, coriolis_matrix_into, kinetic_energy_into,
              joint_reactions_into, inverse_dynamics_derivatives_into,
              forward_dynamics_derivatives_into, mass_matrix_inverse_into];
}

mechanism! {
    /// A three-joint arm with loads: its derivatives are a triple of matrices.
    pub struct LoadedArmInto;
    outputs: [mass_matrix_into, inverse_dynamics_derivatives_into, joint_placements_into,
              forward_dynamics_derivatives_into];
    body upper { mass: 2.0, com: [0.0, 0.0, 0.2], shape: cylinder(radius: 0.04, length: 0.4, axis: z) }
    body fore { mass: 1.2, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    body tip { mass: 0.3, com: [0.05, 0.0, 0.01], shape: box(size: [0.1, 0.04, 0.03]) }
    joint shoulder: revolute(ground -> upper) { axis: z }
    joint elbow: revolute(upper -> fore) { axis: y, at: [0.0, 0.0, 0.4], damping: 0.1 }
    joint wrist: prismatic(fore -> tip) { axis: x, at: [0.3, 0.0, 0.0] }
    load push: force on tip at [0.1, 0.01, 0.0] in world;
    load spin: couple on upper;
}

mechanism! {
    /// A ten-link spatial chain: its Coriolis matrix and ∂τ are cut into two pieces each.
    pub struct ChainInto;
    outputs: [coriolis_matrix_into, inverse_dynamics_derivatives_into, mass_matrix_inverse_into,
              forward_dynamics_derivatives_into];
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

mechanism! {
    /// The same chain with the baseline copies only: its pieces are plain functions.
    pub struct ChainIntoBaseline;
    isa: baseline;
    outputs: [coriolis_matrix_into, forward_dynamics_derivatives_into];
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

mechanism! {
    /// A free-floating base with two branches: its ∂q̈ is one piece ending in a solve loop.
        pub struct FreeTreeInto;
    outputs: [forward_dynamics_derivatives_into];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    joint float: free(ground -> base) { damping: 0.15, armature: 0.02 }
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3), damping: 0.2 }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0], armature: 0.05 }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
}

/// The bits of every number in a value (arrays, tuples, nested), in order.
trait Bits {
    fn bits(&self, out: &mut Vec<u64>);
}
impl Bits for f64 {
    fn bits(&self, out: &mut Vec<u64>) {
        out.push(self.to_bits());
    }
}
impl Bits for F64x4 {
    fn bits(&self, out: &mut Vec<u64>) {
        out.extend(self.to_array().map(f64::to_bits));
    }
}
impl<B: Bits, const N: usize> Bits for [B; N] {
    fn bits(&self, out: &mut Vec<u64>) {
        self.iter().for_each(|b| b.bits(out));
    }
}
impl<A: Bits, B: Bits> Bits for (A, B) {
    fn bits(&self, out: &mut Vec<u64>) {
        self.0.bits(out);
        self.1.bits(out);
    }
}
impl<A: Bits, B: Bits, C: Bits> Bits for (A, B, C) {
    fn bits(&self, out: &mut Vec<u64>) {
        self.0.bits(out);
        self.1.bits(out);
        self.2.bits(out);
    }
}

/// `into` wrote exactly `expected` into an `out` that held NaN everywhere.
fn assert_same<O: Bits>(expected: O, mut out: O, into: impl FnOnce(&mut O), what: &str) {
    let mut before = Vec::new();
    out.bits(&mut before);
    assert!(
        before.iter().all(|&b| f64::from_bits(b).is_nan()),
        "{what}: `out` starts as NaN"
    );
    into(&mut out);
    let (mut got, mut want) = (Vec::new(), Vec::new());
    out.bits(&mut got);
    expected.bits(&mut want);
    assert_eq!(got, want, "{what}: `_into` against the returned value");
}

/// A number in [-2, 2) from a counter (no randomness needed: any state will do).
fn wobble(k: usize) -> f64 {
    ((k as f64) * 0.618_033_988_75).fract() * 4.0 - 2.0
}

fn state<const N: usize>(seed: usize) -> [f64; N] {
    std::array::from_fn(|i| wobble(seed * 31 + i))
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
fn a_triple_of_matrices_and_a_stack_of_poses_are_written_whole() {
    const N: usize = <LoadedArmInto as Mechanism>::NV;
    const L: usize = <LoadedArmInto as Mechanism>::NUM_LOAD_INPUTS;
    let n = f64::NAN;
    for seed in 0..10 {
        let (q, v, a, loads): ([f64; N], [f64; N], [f64; N], [f64; L]) = (
            state(seed),
            state(seed + 7),
            state(seed + 11),
            state(seed + 13),
        );
        let what = |f: &str| format!("loaded arm {f}, state {seed}");
        assert_same(
            LoadedArmInto::mass_matrix(&q),
            [[n; N]; N],
            |o| LoadedArmInto::mass_matrix_into(&q, o),
            &what("mass_matrix"),
        );
        assert_same(
            LoadedArmInto::inverse_dynamics_derivatives(&q, &v, &a, &loads),
            ([[n; N]; N], [[n; N]; N], [[n; L]; N]),
            |o| LoadedArmInto::inverse_dynamics_derivatives_into(&q, &v, &a, &loads, o),
            &what("∂τ"),
        );
        let poses = LoadedArmInto::joint_placements(&q);
        let nan_poses = poses.map(|(r, t)| (r.map(|row| row.map(|_| n)), t.map(|_| n)));
        assert_same(
            poses,
            nan_poses,
            |o| LoadedArmInto::joint_placements_into(&q, o),
            &what("joint_placements"),
        );
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

#[test]
fn a_solve_loop_solves_in_place_in_out() {
    const NQ: usize = <FreeTreeInto as Mechanism>::NQ;
    const N: usize = <FreeTreeInto as Mechanism>::NV;
    let n = f64::NAN;
    for seed in 0..5 {
        let (mut q, v, tau): ([f64; NQ], [f64; N], [f64; N]) =
            (state(seed + 600), state(seed + 700), state(seed + 800));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        assert_same(
            FreeTreeInto::forward_dynamics_derivatives(&q, &v, &tau),
            ([[n; N]; N], [[n; N]; N]),
            |o| FreeTreeInto::forward_dynamics_derivatives_into(&q, &v, &tau, o),
            &format!("free tree ∂q̈, state {seed}"),
        );
    }
}
