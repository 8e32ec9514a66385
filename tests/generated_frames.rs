//! The generated frame outputs and the centroidal bias:
//! - against Pinocchio's `updateFramePlacements` (oMf), `getFrameJacobian(LOCAL_WORLD_ALIGNED)`,
//!   `getFrameClassicalAcceleration` at a = 0 (J̇ v) and `dccrba` (Ȧ_G v), at Pinocchio's 20
//!   sampled states (`tests/data/pinocchio_ext/<name>_frames.json`), to 1e-12: the UR5's
//!   `ee_link` and `tool0` imported from URDF links welded through fixed joints
//!   (`tests/data/urdf/ur5_tool.urdf`), the Panda's flange, hand, fingers and tool centre
//!   point declared with `frame` in the language;
//! - the local Jacobian is the world-aligned one turned into the frame's axes, the frame
//!   velocity is J v;
//! - on a free-floating branched tree with a prismatic joint: frame Jacobians against central
//!   differences of the frame placements along q ⊕ δ, J̇ v against central differences of
//!   J v along the motion, and Ȧ_G v against central differences of A_G v;
//! - every frame output and Ȧ_G v against the runtime reference, to 1e-12, on the free tree,
//!   the UR5 and the Panda.

use dynamics_runtime::{mechanism, Mechanism, Reference};
use dynamics_tests::free_tree;
use nalgebra::Matrix6xX;
use serde::Deserialize;
use std::collections::HashMap;

mechanism! {
    /// The UR5 with its URDF tool frames.
    pub struct Ur5Frames;
    urdf: "data/urdf/ur5_tool.urdf";
    outputs: [frame_placements, frame_jacobians, frame_jacobians_local, frame_velocities, frame_acceleration_biases, centroidal_bias];
}

mechanism! {
    /// The Panda with the frames of its description, declared in the language.
    pub struct PandaFrames;
    urdf: "../models/urdf/panda.urdf";
    outputs: [frame_placements, frame_jacobians, frame_jacobians_local, frame_velocities, frame_acceleration_biases, centroidal_bias];
    /// The flange.
    frame panda_link8: on panda_link7 at [0.0, 0.0, 0.107];
    frame panda_hand: on panda_link7 at [0.0, 0.0, 0.107] rotation rpy(0.0, 0.0, -pi / 4.0);
    frame panda_leftfinger: on panda_link7 at [0.0, 0.0, 0.1654] rotation rpy(0.0, 0.0, -pi / 4.0);
    frame panda_rightfinger: on panda_link7 at [0.0, 0.0, 0.1654] rotation rpy(0.0, 0.0, -pi / 4.0);
    /// The tool centre point, between the fingertips.
    frame panda_hand_tcp: on panda_link7 at [0.0, 0.0, 0.2104] rotation rpy(0.0, 0.0, -pi / 4.0);
}

mechanism! {
    pub struct PendulumFrames;
    urdf: "../models/urdf/pendulum.urdf";
    outputs: [centroidal_bias];
}

mechanism! {
    pub struct DoublePendulumFrames;
    urdf: "../models/urdf/double_pendulum.urdf";
    outputs: [centroidal_bias];
}

mechanism! {
    pub struct Planar3Frames;
    urdf: "../models/urdf/planar3.urdf";
    outputs: [centroidal_bias];
    allow: [triangle_inequality];
}

mechanism! {
    /// A free-floating base with two branches, one ending in a slider; frames on the base, on
    /// a leaf, on a body welded to a leaf, and on the ground.
    pub struct FreeTreeFrames;
    outputs: [frame_placements, frame_jacobians, frame_jacobians_local, frame_velocities, frame_acceleration_biases, centroidal_bias, centroidal_momentum_matrix];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    body tip { mass: 0.1, shape: point }
    joint float: free(ground -> base);
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3) }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0] }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
    joint weld: fixed(right -> tip) { at: [0.0, 0.1, 0.05], rotation: rpy(0.4, 0.0, -0.2) }
    frame imu: on base at [0.05, -0.02, 0.1] rotation rpy(0.0, 0.3, 0.0);
    frame probe: on slider at [0.03, 0.01, 0.0];
    frame on_tip: on tip at [0.02, 0.0, 0.0] rotation axis_angle([1.0, 1.0, 0.0], 0.5);
    frame marker: on ground at [1.0, 2.0, 0.0];
}

#[derive(Deserialize)]
struct Placement {
    rotation: [[f64; 3]; 3],
    translation: [f64; 3],
}

#[derive(Deserialize)]
struct FrameSample {
    placement: Placement,
    jacobian_world: Vec<Vec<f64>>,
    jdot_v_world: [f64; 6],
}

#[derive(Deserialize)]
struct Sample {
    q: Vec<f64>,
    v: Vec<f64>,
    centroidal_bias: [f64; 6],
    frames: HashMap<String, FrameSample>,
}

fn samples(name: &str) -> Vec<Sample> {
    dynamics_tests::pinocchio_ext_samples(name, "frames")
}

/// `|a − b| ≤ 1e-12`, with a message naming what differs.
fn assert_close(a: f64, b: f64, what: &dyn Fn() -> String) {
    assert!((a - b).abs() <= 1e-12, "{}: {a} against {b}", what());
}

type Placements<const NF: usize> = [([[f64; 3]; 3], [f64; 3]); NF];
type Jacobians<const NV: usize, const NF: usize> = [[[f64; NV]; 6]; NF];

/// The frame outputs of one robot, as functions.
struct FrameOutputs<const NQ: usize, const NV: usize, const NF: usize> {
    names: &'static [&'static str],
    placements: fn(&[f64; NQ]) -> Placements<NF>,
    jacobians: fn(&[f64; NQ]) -> Jacobians<NV, NF>,
    local: fn(&[f64; NQ]) -> Jacobians<NV, NF>,
    velocities: fn(&[f64; NQ], &[f64; NV]) -> [[f64; 6]; NF],
    biases: fn(&[f64; NQ], &[f64; NV]) -> [[f64; 6]; NF],
}

/// The frame outputs of a generated mechanism, in f64.
macro_rules! frame_outputs {
    ($m:ty) => {
        FrameOutputs {
            names: <$m as Mechanism>::FRAME_NAMES,
            placements: <$m>::frame_placements::<f64>,
            jacobians: <$m>::frame_jacobians::<f64>,
            local: <$m>::frame_jacobians_local::<f64>,
            velocities: <$m>::frame_velocities::<f64>,
            biases: <$m>::frame_acceleration_biases::<f64>,
        }
    };
}

/// Compares every frame Pinocchio has and the robot generates; returns how many frames were
/// compared.
fn check_frames<const NQ: usize, const NV: usize, const NF: usize>(
    name: &str,
    outputs: &FrameOutputs<NQ, NV, NF>,
) -> usize {
    let mut compared = 0;
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = sample.v.clone().try_into().expect("nv matches");
        let placements = (outputs.placements)(&q);
        let jacobians = (outputs.jacobians)(&q);
        let local = (outputs.local)(&q);
        let velocities = (outputs.velocities)(&q, &v);
        let biases = (outputs.biases)(&q, &v);
        compared = 0;
        for (f, frame) in outputs.names.iter().enumerate() {
            // The root link `base` is placed differently in Pinocchio's descriptions.
            let Some(expected) = sample.frames.get(*frame).filter(|_| *frame != "base") else {
                continue;
            };
            compared += 1;
            let what = |item: &str| format!("{name} sample {k} frame {frame} {item}");
            let (rotation, origin) = &placements[f];
            for r in 0..3 {
                assert_close(origin[r], expected.placement.translation[r], &|| {
                    what(&format!("p[{r}]"))
                });
                for c in 0..3 {
                    assert_close(rotation[r][c], expected.placement.rotation[r][c], &|| {
                        what(&format!("R[{r}][{c}]"))
                    });
                }
            }
            for r in 0..6 {
                for c in 0..NV {
                    assert_close(jacobians[f][r][c], expected.jacobian_world[r][c], &|| {
                        what(&format!("J[{r}][{c}]"))
                    });
                }
                assert_close(biases[f][r], expected.jdot_v_world[r], &|| {
                    what(&format!("J̇v[{r}]"))
                });
            }
            check_local_and_velocity(&placements[f], &jacobians[f], &local[f], &velocities[f], &v);
        }
    }
    compared
}

/// J_local = blockdiag(Rᵀ, Rᵀ) J_world, and the velocity is J_world v.
fn check_local_and_velocity<const NV: usize>(
    placement: &([[f64; 3]; 3], [f64; 3]),
    world: &[[f64; NV]; 6],
    local: &[[f64; NV]; 6],
    velocity: &[f64; 6],
    v: &[f64; NV],
) {
    let rotation = &placement.0;
    for c in 0..NV {
        for block in [0, 3] {
            for r in 0..3 {
                let turned: f64 = (0..3).map(|m| rotation[m][r] * world[block + m][c]).sum();
                let got = local[block + r][c];
                assert!(
                    (got - turned).abs() <= 1e-12,
                    "local J[{}][{c}] {got}, Rᵀ J {turned}",
                    block + r
                );
            }
        }
    }
    for r in 0..6 {
        let jv: f64 = (0..NV).map(|c| world[r][c] * v[c]).sum();
        assert!(
            (velocity[r] - jv).abs() <= 1e-12,
            "velocity[{r}] {}, J v {jv}",
            velocity[r]
        );
    }
}

#[test]
fn urdf_frames_of_the_ur5_match_pinocchio() {
    assert_eq!(
        <Ur5Frames as Mechanism>::FRAME_NAMES,
        ["base", "ee_link", "tool0"]
    );
    assert_eq!(Ur5Frames::FRAME_TOOL0, 2);
    let outputs = frame_outputs!(Ur5Frames);
    assert_eq!(check_frames("ur5", &outputs), 2);
}

#[test]
fn declared_frames_of_the_panda_match_pinocchio() {
    // The root link comes first, then the declared frames.
    assert_eq!(PandaFrames::FRAME_PANDA_HAND_TCP, 5);
    let outputs = frame_outputs!(PandaFrames);
    assert_eq!(check_frames("panda", &outputs), 5);
}

/// Compares one robot's Ȧ_G v with Pinocchio's.
fn check_centroidal_bias<const NQ: usize, const NV: usize>(
    name: &str,
    bias: fn(&[f64; NQ], &[f64; NV]) -> [f64; 6],
) {
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = sample.v.clone().try_into().expect("nv matches");
        let got = bias(&q, &v);
        for r in 0..6 {
            assert_close(got[r], sample.centroidal_bias[r], &|| {
                format!("{name} sample {k} Ȧ_G v[{r}]")
            });
        }
    }
}

#[test]
fn centroidal_bias_matches_pinocchio() {
    check_centroidal_bias("pendulum", PendulumFrames::centroidal_bias::<f64>);
    check_centroidal_bias(
        "double_pendulum",
        DoublePendulumFrames::centroidal_bias::<f64>,
    );
    check_centroidal_bias("planar3", Planar3Frames::centroidal_bias::<f64>);
    check_centroidal_bias("ur5", Ur5Frames::centroidal_bias::<f64>);
    check_centroidal_bias("panda", PandaFrames::centroidal_bias::<f64>);
}

#[test]
fn frame_jacobians_of_a_free_tree_are_the_derivatives_of_the_placements() {
    assert_eq!(
        <FreeTreeFrames as Mechanism>::FRAME_NAMES,
        ["tip", "imu", "probe", "on_tip", "marker"]
    );
    let h = 1e-6;
    let mut moving_columns = 0;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let jacobians = FreeTreeFrames::frame_jacobians(&q);
        let here = FreeTreeFrames::frame_placements(&q);
        for col in 0..9 {
            let plus =
                FreeTreeFrames::frame_placements(&free_tree::moved(&q, &free_tree::unit(col), h));
            let minus =
                FreeTreeFrames::frame_placements(&free_tree::moved(&q, &free_tree::unit(col), -h));
            for f in 0..5 {
                // Linear rows: dp/dt. Angular rows: ω with Ṙ Rᵀ = ω̂.
                let rate = |r: usize, c: usize| (plus[f].0[r][c] - minus[f].0[r][c]) / (2.0 * h);
                let spin =
                    |r: usize, c: usize| (0..3).map(|m| rate(r, m) * here[f].0[c][m]).sum::<f64>();
                let omega = [spin(2, 1), spin(0, 2), spin(1, 0)];
                for r in 0..3 {
                    let velocity = (plus[f].1[r] - minus[f].1[r]) / (2.0 * h);
                    let (lin, ang) = (jacobians[f][r][col], jacobians[f][3 + r][col]);
                    assert!(
                        (lin - velocity).abs() <= 1e-8,
                        "frame {f} col {col} linear[{r}] {lin}, difference {velocity}"
                    );
                    assert!(
                        (ang - omega[r]).abs() <= 1e-8,
                        "frame {f} col {col} angular[{r}] {ang}, difference {}",
                        omega[r]
                    );
                    if lin != 0.0 {
                        moving_columns += 1;
                    }
                }
            }
        }
        // The ground's frame never moves; the slider's probe does not move with hip_right.
        assert!(jacobians[FreeTreeFrames::FRAME_MARKER]
            .iter()
            .all(|row| row.iter().all(|&x| x == 0.0)));
        assert!(jacobians[FreeTreeFrames::FRAME_PROBE]
            .iter()
            .all(|row| row[8] == 0.0));
    }
    assert!(moving_columns > 100);
}

#[test]
fn frame_acceleration_biases_of_a_free_tree_are_the_rate_of_j_v() {
    let h = 1e-6;
    for k in 0..6 {
        let (q, v) = (free_tree::configuration(k), free_tree::velocity(k));
        let biases = FreeTreeFrames::frame_acceleration_biases(&q, &v);
        let plus = FreeTreeFrames::frame_velocities(&free_tree::moved(&q, &v, h), &v);
        let minus = FreeTreeFrames::frame_velocities(&free_tree::moved(&q, &v, -h), &v);
        for f in 0..5 {
            for r in 0..6 {
                let rate = (plus[f][r] - minus[f][r]) / (2.0 * h);
                assert!(
                    (biases[f][r] - rate).abs() <= 1e-7,
                    "sample {k} frame {f} J̇v[{r}] {}, difference {rate}",
                    biases[f][r]
                );
            }
        }
    }
}

#[test]
fn centroidal_bias_of_a_free_tree_is_the_rate_of_a_g_v() {
    let h = 1e-6;
    for k in 0..6 {
        let (q, v) = (free_tree::configuration(k), free_tree::velocity(k));
        let bias = FreeTreeFrames::centroidal_bias(&q, &v);
        let momentum = |q: &[f64; 10]| {
            let a = FreeTreeFrames::centroidal_momentum_matrix(q);
            a.map(|row| (0..9).map(|c| row[c] * v[c]).sum::<f64>())
        };
        let (plus, minus) = (
            momentum(&free_tree::moved(&q, &v, h)),
            momentum(&free_tree::moved(&q, &v, -h)),
        );
        for r in 0..6 {
            let rate = (plus[r] - minus[r]) / (2.0 * h);
            assert!(
                (bias[r] - rate).abs() <= 1e-7,
                "sample {k} Ȧ_G v[{r}] {}, difference {rate}",
                bias[r]
            );
        }
    }
}

/// The generated frame outputs and Ȧ_G v against the runtime reference (written
/// independently), frame by frame through the runtime model's frame of the same name.
fn check_against_reference<M: Mechanism, const NQ: usize, const NV: usize, const NF: usize>(
    outputs: &FrameOutputs<NQ, NV, NF>,
    centroidal_bias: fn(&[f64; NQ], &[f64; NV]) -> [f64; 6],
    states: &[([f64; NQ], [f64; NV])],
) {
    let model = M::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut jacobian = Matrix6xX::<f64>::zeros(NV);
    let mut local = Matrix6xX::<f64>::zeros(NV);
    let zero = [0.0; NV];
    for (q, v) in states {
        let placements = (outputs.placements)(q);
        let (world, own) = ((outputs.jacobians)(q), (outputs.local)(q));
        let (velocities, biases) = ((outputs.velocities)(q, v), (outputs.biases)(q, v));
        for (f, name) in outputs.names.iter().enumerate() {
            let index = model
                .frame_index(name)
                .expect("the runtime model has every frame");
            let pose = reference.frame_pose(q, index).expect("sizes match");
            reference
                .frame_jacobian(q, index, &mut jacobian)
                .expect("sizes match");
            reference
                .frame_jacobian_local(q, index, &mut local)
                .expect("sizes match");
            let velocity = reference.frame_velocity(q, v, index).expect("sizes match");
            let bias = reference
                .frame_classical_acceleration(q, v, &zero, index)
                .expect("sizes match");
            let close = |a: f64, b: f64, what: &str| {
                assert!(
                    (a - b).abs() <= 1e-12,
                    "{} frame {name} {what}: generated {a}, reference {b}",
                    M::NAME
                );
            };
            for r in 0..3 {
                close(placements[f].1[r], pose.origin_in_world[r], "p");
                for c in 0..3 {
                    close(placements[f].0[r][c], pose.rotation_in_world[(r, c)], "R");
                }
            }
            for r in 0..6 {
                for c in 0..NV {
                    close(world[f][r][c], jacobian[(r, c)], "J");
                    close(own[f][r][c], local[(r, c)], "local J");
                }
                close(velocities[f][r], velocity[r], "velocity");
                close(biases[f][r], bias[r], "J̇v");
            }
        }
        let rate = reference
            .centroidal_momentum_rate(q, v, &zero)
            .expect("sizes match");
        let generated = centroidal_bias(q, v);
        for r in 0..6 {
            assert!(
                (generated[r] - rate[r]).abs() <= 1e-12,
                "{} Ȧ_G v[{r}]: generated {}, reference {}",
                M::NAME,
                generated[r],
                rate[r]
            );
        }
    }
}

#[test]
fn frames_and_centroidal_bias_match_the_reference() {
    let free_tree: Vec<_> = (0..6)
        .map(|k| (free_tree::configuration(k), free_tree::velocity(k)))
        .collect();
    check_against_reference::<FreeTreeFrames, 10, 9, 5>(
        &frame_outputs!(FreeTreeFrames),
        FreeTreeFrames::centroidal_bias::<f64>,
        &free_tree,
    );
    let states = |name: &str| -> Vec<(Vec<f64>, Vec<f64>)> {
        samples(name).into_iter().map(|s| (s.q, s.v)).collect()
    };
    let ur5: Vec<([f64; 6], [f64; 6])> = states("ur5")
        .into_iter()
        .map(|(q, v)| (q.try_into().expect("nq"), v.try_into().expect("nv")))
        .collect();
    check_against_reference::<Ur5Frames, 6, 6, 3>(
        &frame_outputs!(Ur5Frames),
        Ur5Frames::centroidal_bias::<f64>,
        &ur5,
    );
    let panda: Vec<([f64; 7], [f64; 7])> = states("panda")
        .into_iter()
        .map(|(q, v)| (q.try_into().expect("nq"), v.try_into().expect("nv")))
        .collect();
    check_against_reference::<PandaFrames, 7, 7, 6>(
        &frame_outputs!(PandaFrames),
        PandaFrames::centroidal_bias::<f64>,
        &panda,
    );
}
