//! Denavit–Hartenberg placements (`placement: dh(..)` and `placement: mdh(..)`), on two
//! published arms, each declared several ways through the macro:
//!
//! - the PUMA 560 of Corke's Robotics Toolbox for MATLAB (`models/mdl_puma560.m`: the
//!   standard DH table of Paul, the inertial parameters of Corke and Armstrong-Hélouvry, "A
//!   search for consensus among model parameters reported for the PUMA 560 robot", ICRA
//!   1994, in the standard DH link frames; the armature Jm G² from its motor inertias and
//!   gear ratios), declared with `dh(..)` as published, with `mdh(..)` (the table and the
//!   inertial data rewritten in Craig's convention, below) and with plain `at`/`rotation`;
//! - the Stanford arm of the same toolbox (`models/mdl_stanford.m`: kinematics from Stanford
//!   AIM-177, inertial data from Paul 1981, Tables 6.5 and 6.6), whose third joint is
//!   prismatic with θ = −π/2, declared with `dh(..)` and `mdh(..)`, with an operational
//!   frame on the fifth link.
//!
//! Checked:
//! - at random states, the mass matrix, inverse dynamics, gravity, forward dynamics and body
//!   poses agree across the declarations to 1e-12, and agree with the runtime reference of
//!   the `dh` declaration's `Mechanism::model()` (whose joints carry the child frames
//!   C = Tx(a) Rx(α));
//! - the `dh` declaration's body poses are Craig's frames i (on joint i's axis), and its
//!   bodies named in `frames: [..]` are the standard DH link frames: the product
//!   A_1 ⋯ A_i of A_j = Rz(θ_j + q_j) Tz(d_j) Tx(a_j) Rx(α_j), multiplied out here, which is
//!   the toolbox's `fkine`;
//! - through the compiler library, the generated functions are the same code: the `mdh` and
//!   the `at`/`rotation` declarations give the same tokens, whole; the `dh` declaration gives
//!   the same functions as the `mdh` one, token for token, with the same operation counts
//!   (all but the PUMA's `frame_placements`, which give the DH link frames for `dh` and
//!   Craig's frames for the others).
//!
//! # The PUMA 560 in Craig's convention
//!
//! Standard row i is (a_i, α_i, d_i, θ_i); Craig's row i is (a_{i−1}, α_{i−1}, d_i, θ_i),
//! with a_0 = α_0 = 0:
//!
//! | i | a_i | α_i | d_i | Craig: a_{i−1} | α_{i−1} | d_i |
//! | --- | --- | --- | --- | --- | --- | --- |
//! | 1 | 0 | π/2 | 0 | 0 | 0 | 0 |
//! | 2 | 0.4318 | 0 | 0 | 0 | π/2 | 0 |
//! | 3 | 0.0203 | −π/2 | 0.15005 | 0.4318 | 0 | 0.15005 |
//! | 4 | 0 | π/2 | 0.4318 | 0.0203 | −π/2 | 0.4318 |
//! | 5 | 0 | −π/2 | 0 | 0 | π/2 | 0 |
//! | 6 | 0 | 0 | 0 | 0 | −π/2 | 0 |
//!
//! (all θ_i = 0). Craig's frame i is the standard link frame i without its
//! C_i = Tx(a_i) Rx(α_i), so a mass centre moves to c' = Rx(α_i) c + (a_i, 0, 0) and an
//! inertia to Rx(α_i) I Rx(α_i)ᵀ. With α = ±π/2 these permute axes exactly: Rx(π/2) takes
//! (x, y, z) to (x, −z, y), Rx(−π/2) to (x, z, −y), and swaps the y and z moments. The
//! sums a_i + c_x are written as sums, so that they round as the compiler's do.

use dynamics_runtime::{mechanism, Mechanism, Reference};
use dynamics_tests::random::SplitMix;
use dynamics_tests::{assert_close, condition_number};
use nalgebra::{DMatrix, Matrix3, Matrix4, Vector3};
use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

/// `mechanism! { tokens }`, and the tokens as text in `const $source` for the compiler
/// library.
macro_rules! declared {
    ($source:ident = { $($tokens:tt)* }) => {
        mechanism! { $($tokens)* }
        /// The declaration as written, for `dynamics_codegen::compile`.
        const $source: &str = stringify!($($tokens)*);
    };
}

declared!(PUMA_DH = {
    /// The PUMA 560, standard DH (Corke's `mdl_puma560`), inertial data in the DH link
    /// frames.
    pub struct Puma560Dh;
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics, joint_placements, frame_placements];
    frames: [link1, link2, link3, link4, link5, link6];
    // Link 1's published inertia is its moment about joint 1's axis alone (y of the DH
    // frame 1): it violates the triangle inequality, with a mass of 0.
    allow: [triangle_inequality];
    body link1 { mass: 0.0, com: [0.0, 0.0, 0.0], inertia: diag([0.0, 0.35, 0.0]) }
    body link2 { mass: 17.4, com: [-0.3638, 0.006, 0.2275], inertia: diag([0.13, 0.524, 0.539]) }
    body link3 { mass: 4.8, com: [-0.0203, -0.0141, 0.070], inertia: diag([0.066, 0.086, 0.0125]) }
    body link4 { mass: 0.82, com: [0.0, 0.019, 0.0], inertia: diag([1.8e-3, 1.3e-3, 1.8e-3]) }
    body link5 { mass: 0.34, com: [0.0, 0.0, 0.0], inertia: diag([0.3e-3, 0.4e-3, 0.3e-3]) }
    body link6 { mass: 0.09, com: [0.0, 0.0, 0.032], inertia: diag([0.15e-3, 0.15e-3, 0.04e-3]) }
    joint j1: revolute(ground -> link1) { placement: dh(a: 0.0, alpha: pi / 2, d: 0.0, theta: 0.0), armature: 200e-6 * 62.6111 * 62.6111 }
    joint j2: revolute(link1 -> link2) { placement: dh(a: 0.4318, alpha: 0.0, d: 0.0, theta: 0.0), armature: 200e-6 * 107.815 * 107.815 }
    joint j3: revolute(link2 -> link3) { placement: dh(a: 0.0203, alpha: -pi / 2, d: 0.15005, theta: 0.0), armature: 200e-6 * 53.7063 * 53.7063 }
    joint j4: revolute(link3 -> link4) { placement: dh(a: 0.0, alpha: pi / 2, d: 0.4318, theta: 0.0), armature: 33e-6 * 76.0364 * 76.0364 }
    joint j5: revolute(link4 -> link5) { placement: dh(a: 0.0, alpha: -pi / 2, d: 0.0, theta: 0.0), armature: 33e-6 * 71.923 * 71.923 }
    joint j6: revolute(link5 -> link6) { placement: dh(a: 0.0, alpha: 0.0, d: 0.0, theta: 0.0), armature: 33e-6 * 76.686 * 76.686 }
});

declared!(PUMA_MDH = {
    /// The PUMA 560, the same table in Craig's convention, inertial data in Craig's frames.
    pub struct Puma560Mdh;
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics, joint_placements, frame_placements];
    frames: [link1, link2, link3, link4, link5, link6];
    allow: [triangle_inequality];
    body link1 { mass: 0.0, com: [0.0, 0.0, 0.0], inertia: diag([0.0, 0.0, 0.35]) }
    body link2 { mass: 17.4, com: [0.4318 - 0.3638, 0.006, 0.2275], inertia: diag([0.13, 0.524, 0.539]) }
    body link3 { mass: 4.8, com: [0.0203 - 0.0203, 0.070, 0.0141], inertia: diag([0.066, 0.0125, 0.086]) }
    body link4 { mass: 0.82, com: [0.0, 0.0, 0.019], inertia: diag([1.8e-3, 1.8e-3, 1.3e-3]) }
    body link5 { mass: 0.34, com: [0.0, 0.0, 0.0], inertia: diag([0.3e-3, 0.3e-3, 0.4e-3]) }
    body link6 { mass: 0.09, com: [0.0, 0.0, 0.032], inertia: diag([0.15e-3, 0.15e-3, 0.04e-3]) }
    joint j1: revolute(ground -> link1) { placement: mdh(a: 0.0, alpha: 0.0, d: 0.0, theta: 0.0), armature: 200e-6 * 62.6111 * 62.6111 }
    joint j2: revolute(link1 -> link2) { placement: mdh(a: 0.0, alpha: pi / 2, d: 0.0, theta: 0.0), armature: 200e-6 * 107.815 * 107.815 }
    joint j3: revolute(link2 -> link3) { placement: mdh(a: 0.4318, alpha: 0.0, d: 0.15005, theta: 0.0), armature: 200e-6 * 53.7063 * 53.7063 }
    joint j4: revolute(link3 -> link4) { placement: mdh(a: 0.0203, alpha: -pi / 2, d: 0.4318, theta: 0.0), armature: 33e-6 * 76.0364 * 76.0364 }
    joint j5: revolute(link4 -> link5) { placement: mdh(a: 0.0, alpha: pi / 2, d: 0.0, theta: 0.0), armature: 33e-6 * 71.923 * 71.923 }
    joint j6: revolute(link5 -> link6) { placement: mdh(a: 0.0, alpha: -pi / 2, d: 0.0, theta: 0.0), armature: 33e-6 * 76.686 * 76.686 }
});

declared!(PUMA_PLACED = {
    /// The PUMA 560 placed by hand: Craig's row as `at: [a, −d sin α, d cos α]` and
    /// `rotation: Rx(α)` (every θ is 0).
    pub struct Puma560Placed;
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics, joint_placements, frame_placements];
    frames: [link1, link2, link3, link4, link5, link6];
    allow: [triangle_inequality];
    body link1 { mass: 0.0, com: [0.0, 0.0, 0.0], inertia: diag([0.0, 0.0, 0.35]) }
    body link2 { mass: 17.4, com: [0.4318 - 0.3638, 0.006, 0.2275], inertia: diag([0.13, 0.524, 0.539]) }
    body link3 { mass: 4.8, com: [0.0203 - 0.0203, 0.070, 0.0141], inertia: diag([0.066, 0.0125, 0.086]) }
    body link4 { mass: 0.82, com: [0.0, 0.0, 0.019], inertia: diag([1.8e-3, 1.8e-3, 1.3e-3]) }
    body link5 { mass: 0.34, com: [0.0, 0.0, 0.0], inertia: diag([0.3e-3, 0.3e-3, 0.4e-3]) }
    body link6 { mass: 0.09, com: [0.0, 0.0, 0.032], inertia: diag([0.15e-3, 0.15e-3, 0.04e-3]) }
    joint j1: revolute(ground -> link1) { axis: z, armature: 200e-6 * 62.6111 * 62.6111 }
    joint j2: revolute(link1 -> link2) { axis: z, rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], armature: 200e-6 * 107.815 * 107.815 }
    joint j3: revolute(link2 -> link3) { axis: z, at: [0.4318, 0.0, 0.15005], armature: 200e-6 * 53.7063 * 53.7063 }
    joint j4: revolute(link3 -> link4) { axis: z, at: [0.0203, 0.4318, 0.0], rotation: [[1, 0, 0], [0, 0, 1], [0, -1, 0]], armature: 33e-6 * 76.0364 * 76.0364 }
    joint j5: revolute(link4 -> link5) { axis: z, rotation: [[1, 0, 0], [0, 0, -1], [0, 1, 0]], armature: 33e-6 * 71.923 * 71.923 }
    joint j6: revolute(link5 -> link6) { axis: z, rotation: [[1, 0, 0], [0, 0, 1], [0, -1, 0]], armature: 33e-6 * 76.686 * 76.686 }
});

declared!(STANFORD_DH = {
    /// The Stanford arm, standard DH (Corke's `mdl_stanford`), joint 3 prismatic with
    /// θ = −π/2; the armature is the toolbox's Jm (gear ratios 1).
    pub struct StanfordDh;
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics, joint_placements, frame_placements];
    // Link 5's published inertia has a zero moment.
    allow: [triangle_inequality];
    body link1 { mass: 9.29, com: [0.0, 0.0175, -0.1105], inertia: diag([0.276, 0.255, 0.071]) }
    body link2 { mass: 5.01, com: [0.0, -1.054, 0.0], inertia: diag([0.108, 0.018, 0.100]) }
    body link3 { mass: 4.25, com: [0.0, 0.0, -6.447], inertia: diag([2.51, 2.51, 0.006]) }
    body link4 { mass: 1.08, com: [0.0, 0.092, -0.054], inertia: diag([0.002, 0.001, 0.001]) }
    body link5 { mass: 0.630, com: [0.0, 0.566, 0.003], inertia: diag([0.003, 0.0004, 0.0]) }
    body link6 { mass: 0.51, com: [0.0, 0.0, 1.554], inertia: diag([0.013, 0.013, 0.0003]) }
    joint j1: revolute(ground -> link1) { placement: dh(d: 0.412, alpha: -pi / 2), armature: 0.953 }
    joint j2: revolute(link1 -> link2) { placement: dh(d: 0.154, alpha: pi / 2), armature: 2.193 }
    joint j3: prismatic(link2 -> link3) { placement: dh(theta: -pi / 2), armature: 0.782 }
    joint j4: revolute(link3 -> link4) { placement: dh(alpha: -pi / 2), armature: 0.106 }
    joint j5: revolute(link4 -> link5) { placement: dh(alpha: pi / 2), armature: 0.097 }
    joint j6: revolute(link5 -> link6) { placement: dh(d: 0.263), armature: 0.020 }
    /// A point 0.1 m along z of the DH link frame 5 (the sixth joint's axis), with its axes.
    frame wrist: on link5 at [0.0, 0.0, 0.1];
});

declared!(STANFORD_MDH = {
    /// The Stanford arm in Craig's convention. Every a_i is 0, so the data move by Rx(α_i)
    /// alone: α_1 = −π/2, α_2 = π/2, α_3 = 0, α_4 = −π/2, α_5 = π/2, α_6 = 0.
    pub struct StanfordMdh;
    outputs: [inverse_dynamics, mass_matrix, gravity, forward_dynamics, joint_placements, frame_placements];
    allow: [triangle_inequality];
    body link1 { mass: 9.29, com: [0.0, -0.1105, -0.0175], inertia: diag([0.276, 0.071, 0.255]) }
    body link2 { mass: 5.01, com: [0.0, 0.0, -1.054], inertia: diag([0.108, 0.100, 0.018]) }
    body link3 { mass: 4.25, com: [0.0, 0.0, -6.447], inertia: diag([2.51, 2.51, 0.006]) }
    body link4 { mass: 1.08, com: [0.0, -0.054, -0.092], inertia: diag([0.002, 0.001, 0.001]) }
    body link5 { mass: 0.630, com: [0.0, -0.003, 0.566], inertia: diag([0.003, 0.0, 0.0004]) }
    body link6 { mass: 0.51, com: [0.0, 0.0, 1.554], inertia: diag([0.013, 0.013, 0.0003]) }
    joint j1: revolute(ground -> link1) { placement: mdh(d: 0.412), armature: 0.953 }
    joint j2: revolute(link1 -> link2) { placement: mdh(alpha: -pi / 2, d: 0.154), armature: 2.193 }
    joint j3: prismatic(link2 -> link3) { placement: mdh(alpha: pi / 2, theta: -pi / 2), armature: 0.782 }
    joint j4: revolute(link3 -> link4) { placement: mdh(), armature: 0.106 }
    joint j5: revolute(link4 -> link5) { placement: mdh(alpha: -pi / 2), armature: 0.097 }
    joint j6: revolute(link5 -> link6) { placement: mdh(alpha: pi / 2, d: 0.263), armature: 0.020 }
    /// The same point in Craig's frame 5: Rx(π/2) (0, 0, 0.1) = (0, −0.1, 0), and the DH
    /// link frame's axes, Rx(π/2) = rpy(π/2, 0, 0).
    frame wrist: on link5 at [0.0, -0.1, 0.0] rotation rpy(pi / 2, 0, 0);
});

/// The standard DH tables (a, α, d, θ) the declarations are made from.
const PUMA_TABLE: [(f64, f64, f64, f64); 6] = [
    (0.0, FRAC_PI_2, 0.0, 0.0),
    (0.4318, 0.0, 0.0, 0.0),
    (0.0203, -FRAC_PI_2, 0.15005, 0.0),
    (0.0, FRAC_PI_2, 0.4318, 0.0),
    (0.0, -FRAC_PI_2, 0.0, 0.0),
    (0.0, 0.0, 0.0, 0.0),
];

const STATES: usize = 25;

/// q, v, a or τ of a six-joint arm.
type Joints = [f64; 6];
/// A pose (R by rows, p).
type Pose = ([[f64; 3]; 3], [f64; 3]);

/// The functions of one declaration, at `f64`.
struct Arm {
    name: &'static str,
    model: fn() -> dynamics_runtime::Model,
    mass_matrix: fn(&Joints) -> [Joints; 6],
    inverse_dynamics: fn(&Joints, &Joints, &Joints) -> Joints,
    gravity: fn(&Joints) -> Joints,
    forward_dynamics: fn(&Joints, &Joints, &Joints) -> Joints,
    joint_placements: fn(&Joints) -> Vec<Pose>,
}

macro_rules! arm {
    ($name:ident) => {
        Arm {
            name: stringify!($name),
            model: <$name as Mechanism>::model,
            mass_matrix: |q| $name::mass_matrix(q),
            inverse_dynamics: |q, v, a| $name::inverse_dynamics(q, v, a),
            gravity: |q| $name::gravity(q),
            forward_dynamics: |q, v, tau| $name::forward_dynamics(q, v, tau),
            joint_placements: |q| $name::joint_placements(q).to_vec(),
        }
    };
}

fn flat(pose: &Pose) -> Vec<f64> {
    pose.0.iter().flatten().chain(&pose.1).copied().collect()
}

fn random_state(rng: &mut SplitMix) -> (Joints, Joints, Joints, Joints) {
    let q = std::array::from_fn(|_| rng.uniform(-3.1, 3.1));
    let v = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
    let a = std::array::from_fn(|_| rng.uniform(-3.0, 3.0));
    let tau = std::array::from_fn(|_| rng.uniform(-20.0, 20.0));
    (q, v, a, tau)
}

/// Every declaration of an arm against the first, to 1e-12, and the first against the
/// runtime reference of its `Mechanism::model()`, to 1e-12 (forward dynamics to
/// 1e-12 · cond(M)), at random states.
fn declarations_agree(arms: &[Arm], seed: u64) {
    let first = &arms[0];
    let model = (first.model)();
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(seed);
    for state in 0..STATES {
        let (q, v, a, tau) = random_state(&mut rng);
        let m = (first.mass_matrix)(&q);
        let m_flat: Vec<f64> = m.iter().flatten().copied().collect();
        let mut m_ref = DMatrix::zeros(6, 6);
        reference.mass_matrix(&q, &mut m_ref).expect("sizes match");
        let m_ref_flat: Vec<f64> = m_ref.transpose().iter().copied().collect();
        let what = |arm: &str, item: &str| format!("{arm}, state {state}: {item}");
        assert_close(
            &what(first.name, "mass matrix vs reference"),
            &m_flat,
            &m_ref_flat,
            1e-12,
        );
        let cond = condition_number(&m_ref);
        let mut tau_ref = [0.0; 6];
        reference
            .inverse_dynamics(&q, &v, &a, None, &mut tau_ref)
            .expect("sizes match");
        let id = (first.inverse_dynamics)(&q, &v, &a);
        assert_close(
            &what(first.name, "inverse dynamics vs reference"),
            &id,
            &tau_ref,
            1e-12,
        );
        let mut g_ref = [0.0; 6];
        reference.gravity(&q, &mut g_ref).expect("sizes match");
        let g = (first.gravity)(&q);
        assert_close(&what(first.name, "gravity vs reference"), &g, &g_ref, 1e-12);
        let mut qdd_ref = [0.0; 6];
        reference
            .forward_dynamics(&q, &v, &tau, None, &mut qdd_ref)
            .expect("sizes match");
        let fd = (first.forward_dynamics)(&q, &v, &tau);
        assert_close(
            &what(first.name, "forward dynamics vs reference"),
            &fd,
            &qdd_ref,
            1e-12 * cond,
        );
        let poses = (first.joint_placements)(&q);
        let poses_ref = reference.body_poses(&q).expect("sizes match").to_vec();
        for (k, (pose, expected)) in poses.iter().zip(&poses_ref).enumerate() {
            let expected: Vec<f64> = expected
                .rotation_in_world
                .transpose()
                .iter()
                .chain(expected.origin_in_world.iter())
                .copied()
                .collect();
            assert_close(
                &what(first.name, &format!("body {k} pose vs reference")),
                &flat(pose),
                &expected,
                1e-12,
            );
        }
        for arm in &arms[1..] {
            let other: Vec<f64> = (arm.mass_matrix)(&q).iter().flatten().copied().collect();
            assert_close(&what(arm.name, "mass matrix"), &other, &m_flat, 1e-12);
            assert_close(
                &what(arm.name, "inverse dynamics"),
                &(arm.inverse_dynamics)(&q, &v, &a),
                &id,
                1e-12,
            );
            assert_close(&what(arm.name, "gravity"), &(arm.gravity)(&q), &g, 1e-12);
            assert_close(
                &what(arm.name, "forward dynamics"),
                &(arm.forward_dynamics)(&q, &v, &tau),
                &fd,
                1e-12,
            );
            for (k, (pose, expected)) in (arm.joint_placements)(&q).iter().zip(&poses).enumerate() {
                assert_close(
                    &what(arm.name, &format!("body {k} pose")),
                    &flat(pose),
                    &flat(expected),
                    1e-12,
                );
            }
        }
    }
}

#[test]
fn the_puma_560_declared_three_ways_agrees() {
    declarations_agree(
        &[arm!(Puma560Dh), arm!(Puma560Mdh), arm!(Puma560Placed)],
        560,
    );
}

/// The Stanford arm's standard DH table (a, α, d, θ), joint 3 prismatic.
const STANFORD_TABLE: [(f64, f64, f64, f64); 6] = [
    (0.0, -FRAC_PI_2, 0.412, 0.0),
    (0.0, FRAC_PI_2, 0.154, 0.0),
    (0.0, 0.0, 0.0, -FRAC_PI_2),
    (0.0, -FRAC_PI_2, 0.0, 0.0),
    (0.0, FRAC_PI_2, 0.0, 0.0),
    (0.0, 0.0, 0.263, 0.0),
];

#[test]
fn the_stanford_arm_declared_two_ways_agrees() {
    declarations_agree(&[arm!(StanfordDh), arm!(StanfordMdh)], 1969);
    // The frame on link 5, declared in the DH link frame and in Craig's frame, is
    // A_1 ⋯ A_5 Tz(0.1), the prismatic A_3 = Rz(θ_3) Tz(d_3 + q_3) Tx(a_3) Rx(α_3).
    let mut rng = SplitMix(5);
    for state in 0..STATES {
        let (q, ..) = random_state(&mut rng);
        let dh = StanfordDh::frame_placements(&q)[StanfordDh::FRAME_WRIST];
        let mdh = StanfordMdh::frame_placements(&q)[StanfordMdh::FRAME_WRIST];
        assert_close(
            &format!("state {state}: wrist frame"),
            &flat(&dh),
            &flat(&mdh),
            1e-12,
        );
        let mut product = Matrix4::<f64>::identity();
        for (i, &(a, alpha, d, theta)) in STANFORD_TABLE[..5].iter().enumerate() {
            let (theta, d) = if i == 2 {
                (theta, d + q[i])
            } else {
                (theta + q[i], d)
            };
            product = product
                * rz(theta)
                * translation(0.0, 0.0, d)
                * translation(a, 0.0, 0.0)
                * rx(alpha);
        }
        let wrist = product * translation(0.0, 0.0, 0.1);
        assert_close(
            &format!("state {state}: wrist frame, by hand"),
            &matrix_entries(&pose_matrix(&dh)),
            &matrix_entries(&wrist),
            1e-12,
        );
    }
}

fn homogeneous(rotation: Matrix3<f64>, translation: Vector3<f64>) -> Matrix4<f64> {
    let mut t = Matrix4::identity();
    t.fixed_view_mut::<3, 3>(0, 0).copy_from(&rotation);
    t.fixed_view_mut::<3, 1>(0, 3).copy_from(&translation);
    t
}

fn rx(angle: f64) -> Matrix4<f64> {
    let (s, c) = angle.sin_cos();
    homogeneous(
        Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        Vector3::zeros(),
    )
}

fn rz(angle: f64) -> Matrix4<f64> {
    let (s, c) = angle.sin_cos();
    homogeneous(
        Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
        Vector3::zeros(),
    )
}

fn translation(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    homogeneous(Matrix3::identity(), Vector3::new(x, y, z))
}

fn pose_matrix(pose: &Pose) -> Matrix4<f64> {
    let r = Matrix3::from_fn(|i, j| pose.0[i][j]);
    homogeneous(r, Vector3::from(pose.1))
}

fn matrix_entries(m: &Matrix4<f64>) -> Vec<f64> {
    m.transpose().iter().copied().collect()
}

/// The `dh` declaration's frames named in `frames: [..]` are the standard DH link frames,
/// A_1 ⋯ A_i (Corke's `fkine` up to link i); its body poses are Craig's frames, the link
/// frames without their C_i = Tx(a_i) Rx(α_i); the `mdh` declaration's frames are its body
/// poses. The runtime model has the same DH link frames.
#[test]
fn the_dh_link_frames_are_the_products_of_the_dh_transforms() {
    let model = Puma560Dh::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(17);
    for state in 0..STATES {
        let (q, ..) = random_state(&mut rng);
        let frames = Puma560Dh::frame_placements(&q);
        let bodies = Puma560Dh::joint_placements(&q);
        let craig = Puma560Mdh::frame_placements(&q);
        let mut product = Matrix4::identity();
        for (i, &(a, alpha, d, theta)) in PUMA_TABLE.iter().enumerate() {
            let c = translation(a, 0.0, 0.0) * rx(alpha);
            product = product * rz(theta + q[i]) * translation(0.0, 0.0, d) * c;
            let what = |item: &str| format!("state {state}, link {}: {item}", i + 1);
            assert_close(
                &what("DH link frame"),
                &matrix_entries(&pose_matrix(&frames[i])),
                &matrix_entries(&product),
                1e-12,
            );
            let body = pose_matrix(&bodies[i]) * c;
            assert_close(
                &what("body pose times C"),
                &matrix_entries(&body),
                &matrix_entries(&product),
                1e-12,
            );
            assert_close(
                &what("Craig frame"),
                &flat(&craig[i]),
                &flat(&bodies[i]),
                1e-12,
            );
            let index = model
                .frame_index(&format!("link{}", i + 1))
                .expect("every body is a frame");
            let pose = reference.frame_pose(&q, index).expect("a frame");
            let runtime = homogeneous(pose.rotation_in_world, pose.origin_in_world);
            assert_close(
                &what("runtime frame"),
                &matrix_entries(&runtime),
                &matrix_entries(&product),
                1e-12,
            );
        }
    }
}

/// The compiled declaration (`source` without its doc comment, its type renamed to `Arm`):
/// the whole generated code, each inherent function by name, and each one's operation
/// counts and longest chain, all as text.
fn generated(
    source: &str,
    name: &str,
) -> (String, BTreeMap<String, String>, BTreeMap<String, String>) {
    let start = source.find("pub struct").expect("a type");
    let source = source[start..].replace(name, "Arm");
    let mechanism: dynamics_codegen::Mechanism = syn::parse_str(&source).expect("parses");
    let compiled = dynamics_codegen::compile(mechanism, Path::new(".")).expect("compiles");
    let costs = compiled
        .functions()
        .into_iter()
        .map(|f| (f.name, format!("{:?} {}", f.ops, f.longest_chain)))
        .collect();
    let tokens = dynamics_codegen::to_tokens(&compiled);
    let file: syn::File = syn::parse2(tokens.clone()).expect("valid Rust");
    let mut functions = BTreeMap::new();
    for item in &file.items {
        if let syn::Item::Impl(block) = item {
            if block.trait_.is_none() {
                for item in &block.items {
                    if let syn::ImplItem::Fn(f) = item {
                        let text = quote_tokens(f);
                        functions.insert(f.sig.ident.to_string(), text);
                    }
                }
            }
        }
    }
    (tokens.to_string(), functions, costs)
}

/// Asserts two generated texts are the same, showing where they first differ.
#[track_caller]
fn assert_same(a: &str, b: &str, what: &str) {
    if let Some(at) = a
        .bytes()
        .zip(b.bytes())
        .position(|(x, y)| x != y)
        .or_else(|| (a.len() != b.len()).then_some(a.len().min(b.len())))
    {
        let context = |s: &str| {
            let bytes = &s.as_bytes()[at.saturating_sub(300)..(at + 300).min(s.len())];
            String::from_utf8_lossy(bytes).into_owned()
        };
        panic!(
            "{what} differ at byte {at}:\n  {}\nvs\n  {}",
            context(a),
            context(b)
        );
    }
}

fn quote_tokens(f: &syn::ImplItemFn) -> String {
    use quote::ToTokens;
    f.to_token_stream().to_string()
}

/// The declarations compile to the same code: `mdh` and `at`/`rotation` to the same tokens,
/// whole; `dh` to the same functions as `mdh`, token for token and operation for operation
/// (but the PUMA's `frame_placements`, which give other frames).
#[test]
fn the_declarations_compile_to_the_same_code() {
    let (dh_tokens, dh, dh_costs) = generated(PUMA_DH, "Puma560Dh");
    let (mdh_tokens, mdh, mdh_costs) = generated(PUMA_MDH, "Puma560Mdh");
    let (placed_tokens, _, _) = generated(PUMA_PLACED, "Puma560Placed");
    assert_same(
        &mdh_tokens,
        &placed_tokens,
        "the code of mdh(..) and at/rotation",
    );
    assert!(
        dh_tokens.contains("with_child_frame") && !mdh_tokens.contains("with_child_frame"),
        "the runtime model of dh(..) has its child frames"
    );
    assert_eq!(
        dh.keys().collect::<Vec<_>>(),
        mdh.keys().collect::<Vec<_>>()
    );
    assert_eq!(dh.len(), 6, "{:?}", dh.keys());
    for (name, code) in &dh {
        if name != "frame_placements" {
            assert_same(code, &mdh[name], &format!("the PUMA's `{name}`"));
            assert_eq!(dh_costs[name], mdh_costs[name], "`{name}` costs differ");
        }
    }
    assert_ne!(dh["frame_placements"], mdh["frame_placements"]);
    let (_, dh, dh_costs) = generated(STANFORD_DH, "StanfordDh");
    let (_, mdh, mdh_costs) = generated(STANFORD_MDH, "StanfordMdh");
    assert_eq!(
        dh.keys().collect::<Vec<_>>(),
        mdh.keys().collect::<Vec<_>>()
    );
    for (name, code) in &dh {
        assert_same(code, &mdh[name], &format!("the Stanford arm's `{name}`"));
    }
    assert_eq!(dh_costs, mdh_costs);
}
