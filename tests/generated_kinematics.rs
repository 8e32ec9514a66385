//! The generated kinematics: body placements, Jacobians, velocities and J̇ v, the centre of
//! mass and its Jacobian, the centroidal momentum matrix:
//! - against Pinocchio's `forwardKinematics` (oMi), `getJointJacobian(LOCAL_WORLD_ALIGNED)`,
//!   its joint velocities and `getJointJacobianTimeVariation` times v, `centerOfMass`,
//!   `jacobianCenterOfMass` and `ccrba` for the five anchor robots, imported from the
//!   same URDF files, at Pinocchio's 20 sampled configurations each
//!   (`tests/data/pinocchio_ext/<name>_kinematics.json`), to 1e-12;
//! - on a free-floating branched tree with a prismatic joint: placements and centre of mass
//!   against the runtime reference (body poses and mass centres, written independently),
//!   and both Jacobians against central finite differences of the generated placements and
//!   centre of mass along q ⊕ δ (the free base moved on its manifold by
//!   `integrate_configuration`), J̇ v against central differences of J v along the motion,
//!   and A_G q̇ against the bodies' momentum summed from the placements and Jacobians;
//! - the compact WORLD Jacobians `joint_jacobians_world` (Pinocchio's `data.J`) and
//!   `joint_jacobians_world_time_variation` (`data.J`, `data.dJ`): every column that moves
//!   body i is Pinocchio's J_i column taken to the world origin, [v + p_i × ω; ω], and
//!   Σ_c J̇[:, c] v_c of body i, taken back to its origin as a classical acceleration
//!   (a_P = a_O + α × p_i + ω × v_P), is Pinocchio's J̇_i v; on the free tree J̇ against
//!   central differences of J along q ⊕ t v;
//! - `forward_kinematics(q, v, a)` on all six: its placements and velocities are those of
//!   `joint_placements` and `joint_velocities`, its accelerations J a + J̇ v from
//!   `joint_jacobians` and `joint_acceleration_biases` (the three checked above).

use dynamics_runtime::{mechanism, Mechanism, Reference};
use dynamics_tests::{assert_placements_are_the_poses, free_tree};
use serde::Deserialize;

mechanism! {
    pub struct PendulumKinematics;
    urdf: "../models/urdf/pendulum.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
}

mechanism! {
    pub struct DoublePendulumKinematics;
    urdf: "../models/urdf/double_pendulum.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
}

mechanism! {
    pub struct Planar3Kinematics;
    urdf: "../models/urdf/planar3.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
    allow: [triangle_inequality];
}

mechanism! {
    pub struct Ur5Kinematics;
    urdf: "../models/urdf/ur5.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
}

mechanism! {
    pub struct PandaKinematics;
    urdf: "../models/urdf/panda.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
}

mechanism! {
    /// A free-floating base with two branches, one ending in a slider; offset mass centres
    /// and a rotated placement, so that no term vanishes by symmetry.
    pub struct FreeTreeKinematics;
    outputs: [center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, centroidal_momentum_matrix, joint_velocities, joint_acceleration_biases, forward_kinematics, joint_jacobians_world, joint_jacobians_world_time_variation];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    joint float: free(ground -> base);
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3) }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0] }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
}

#[derive(Deserialize)]
struct Placement {
    rotation: [[f64; 3]; 3],
    translation: [f64; 3],
}

#[derive(Deserialize)]
struct Sample {
    q: Vec<f64>,
    center_of_mass: [f64; 3],
    com_jacobian: Vec<Vec<f64>>,
    joint_placements: Vec<Placement>,
    joint_jacobians_world: Vec<Vec<Vec<f64>>>,
    centroidal_momentum_matrix: Vec<Vec<f64>>,
    v: Vec<f64>,
    joint_jacobian_time_derivative_times_v_world: Vec<[f64; 6]>,
    joint_velocities_local: Vec<[f64; 6]>,
}

fn samples(name: &str) -> Vec<Sample> {
    dynamics_tests::pinocchio_ext_samples(name, "kinematics")
}

/// `|a − b| ≤ 1e-12` entry by entry, with a message naming what differs.
fn assert_close(a: f64, b: f64, what: &dyn Fn() -> String) {
    assert!((a - b).abs() <= 1e-12, "{}: {a} against {b}", what());
}

type Placements<const NB: usize> = [([[f64; 3]; 3], [f64; 3]); NB];

/// Compares one robot's generated kinematics with Pinocchio's values.
fn check_kinematics<const NQ: usize, const NV: usize, const NB: usize>(
    name: &str,
    placements: fn(&[f64; NQ]) -> Placements<NB>,
    jacobians: fn(&[f64; NQ]) -> [[[f64; NV]; 6]; NB],
) {
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        assert_eq!(
            sample.joint_placements.len(),
            NB,
            "{name}: one body per joint"
        );
        let (poses, jacobian) = (placements(&q), jacobians(&q));
        for (b, expected) in sample.joint_placements.iter().enumerate() {
            for r in 0..3 {
                assert_close(poses[b].1[r], expected.translation[r], &|| {
                    format!("{name} sample {k} body {b} p[{r}]")
                });
                for c in 0..3 {
                    assert_close(poses[b].0[r][c], expected.rotation[r][c], &|| {
                        format!("{name} sample {k} body {b} R[{r}][{c}]")
                    });
                }
            }
            for r in 0..6 {
                for c in 0..NV {
                    assert_close(
                        jacobian[b][r][c],
                        sample.joint_jacobians_world[b][r][c],
                        &|| format!("{name} sample {k} body {b} J[{r}][{c}]"),
                    );
                }
            }
        }
    }
}

type Twists<const NB: usize> = [[f64; 6]; NB];

/// Compares one robot's generated body velocities and J̇ v with Pinocchio's (its velocities
/// are in the body frame: turned into world axes with its own placements).
fn check_rates<const NQ: usize, const NV: usize, const NB: usize>(
    name: &str,
    velocities: fn(&[f64; NQ], &[f64; NV]) -> Twists<NB>,
    biases: fn(&[f64; NQ], &[f64; NV]) -> Twists<NB>,
) {
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = sample.v.clone().try_into().expect("nv matches");
        let (twists, jdot_v) = (velocities(&q, &v), biases(&q, &v));
        for b in 0..NB {
            let rotation = &sample.joint_placements[b].rotation;
            let local = &sample.joint_velocities_local[b];
            for r in 0..6 {
                let block = 3 * (r / 3);
                let world: f64 = (0..3).map(|c| rotation[r % 3][c] * local[block + c]).sum();
                assert_close(twists[b][r], world, &|| {
                    format!("{name} sample {k} body {b} velocity[{r}]")
                });
                let expected = sample.joint_jacobian_time_derivative_times_v_world[b][r];
                assert_close(jdot_v[b][r], expected, &|| {
                    format!("{name} sample {k} body {b} J̇v[{r}]")
                });
            }
        }
    }
}

/// Compares one robot's generated centroidal momentum matrix with Pinocchio's.
fn check_centroidal<const NQ: usize, const NV: usize>(
    name: &str,
    matrix: fn(&[f64; NQ]) -> [[f64; NV]; 6],
) {
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let a = matrix(&q);
        for r in 0..6 {
            for c in 0..NV {
                assert_close(a[r][c], sample.centroidal_momentum_matrix[r][c], &|| {
                    format!("{name} sample {k} A_G[{r}][{c}]")
                });
            }
        }
    }
}

/// Compares one robot's generated centre of mass and its Jacobian with Pinocchio's values.
fn check_against_pinocchio<const NQ: usize, const NV: usize>(
    name: &str,
    com: fn(&[f64; NQ]) -> [f64; 3],
    jacobian: fn(&[f64; NQ]) -> [[f64; NV]; 3],
) {
    for (k, sample) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let c = com(&q);
        for row in 0..3 {
            let error = (c[row] - sample.center_of_mass[row]).abs();
            assert!(
                error <= 1e-12,
                "{name} sample {k}: c = {c:?}, Pinocchio {:?}",
                sample.center_of_mass
            );
        }
        let j = jacobian(&q);
        for row in 0..3 {
            for col in 0..NV {
                let error = (j[row][col] - sample.com_jacobian[row][col]).abs();
                assert!(
                    error <= 1e-12,
                    "{name} sample {k}: J_c[{row}][{col}] = {}, Pinocchio {}",
                    j[row][col],
                    sample.com_jacobian[row][col]
                );
            }
        }
    }
}

#[test]
fn centre_of_mass_and_its_jacobian_match_pinocchio() {
    check_against_pinocchio(
        "pendulum",
        PendulumKinematics::center_of_mass::<f64>,
        PendulumKinematics::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "double_pendulum",
        DoublePendulumKinematics::center_of_mass::<f64>,
        DoublePendulumKinematics::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "planar3",
        Planar3Kinematics::center_of_mass::<f64>,
        Planar3Kinematics::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "ur5",
        Ur5Kinematics::center_of_mass::<f64>,
        Ur5Kinematics::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "panda",
        PandaKinematics::center_of_mass::<f64>,
        PandaKinematics::center_of_mass_jacobian::<f64>,
    );
}

#[test]
fn placements_and_joint_jacobians_match_pinocchio() {
    check_kinematics(
        "pendulum",
        PendulumKinematics::joint_placements::<f64>,
        PendulumKinematics::joint_jacobians::<f64>,
    );
    check_kinematics(
        "double_pendulum",
        DoublePendulumKinematics::joint_placements::<f64>,
        DoublePendulumKinematics::joint_jacobians::<f64>,
    );
    check_kinematics(
        "planar3",
        Planar3Kinematics::joint_placements::<f64>,
        Planar3Kinematics::joint_jacobians::<f64>,
    );
    check_kinematics(
        "ur5",
        Ur5Kinematics::joint_placements::<f64>,
        Ur5Kinematics::joint_jacobians::<f64>,
    );
    check_kinematics(
        "panda",
        PandaKinematics::joint_placements::<f64>,
        PandaKinematics::joint_jacobians::<f64>,
    );
}

#[test]
fn body_velocities_and_acceleration_biases_match_pinocchio() {
    check_rates(
        "pendulum",
        PendulumKinematics::joint_velocities::<f64>,
        PendulumKinematics::joint_acceleration_biases::<f64>,
    );
    check_rates(
        "double_pendulum",
        DoublePendulumKinematics::joint_velocities::<f64>,
        DoublePendulumKinematics::joint_acceleration_biases::<f64>,
    );
    check_rates(
        "planar3",
        Planar3Kinematics::joint_velocities::<f64>,
        Planar3Kinematics::joint_acceleration_biases::<f64>,
    );
    check_rates(
        "ur5",
        Ur5Kinematics::joint_velocities::<f64>,
        Ur5Kinematics::joint_acceleration_biases::<f64>,
    );
    check_rates(
        "panda",
        PandaKinematics::joint_velocities::<f64>,
        PandaKinematics::joint_acceleration_biases::<f64>,
    );
}

#[test]
fn centroidal_momentum_matrix_matches_pinocchio() {
    check_centroidal(
        "pendulum",
        PendulumKinematics::centroidal_momentum_matrix::<f64>,
    );
    check_centroidal(
        "double_pendulum",
        DoublePendulumKinematics::centroidal_momentum_matrix::<f64>,
    );
    check_centroidal(
        "planar3",
        Planar3Kinematics::centroidal_momentum_matrix::<f64>,
    );
    check_centroidal("ur5", Ur5Kinematics::centroidal_momentum_matrix::<f64>);
    check_centroidal("panda", PandaKinematics::centroidal_momentum_matrix::<f64>);
}

#[test]
fn centre_of_mass_of_a_free_tree_matches_the_reference() {
    let model = <FreeTreeKinematics as Mechanism>::model();
    let mut reference = Reference::<f64>::new(&model);
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let generated = FreeTreeKinematics::center_of_mass(&q);
        let expected = reference.center_of_mass(&q).expect("sizes match");
        for row in 0..3 {
            assert!(
                (generated[row] - expected[row]).abs() <= 1e-13,
                "q = {q:?}: generated {generated:?}, reference {expected:?}"
            );
        }
    }
}

#[test]
fn placements_of_a_free_tree_match_the_reference() {
    let model = <FreeTreeKinematics as Mechanism>::model();
    let mut reference = Reference::<f64>::new(&model);
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let expected = reference.body_poses(&q).expect("sizes match");
        assert_placements_are_the_poses(&FreeTreeKinematics::joint_placements(&q), expected);
    }
}

#[test]
fn joint_jacobians_of_a_free_tree_are_the_derivatives_of_the_placements() {
    let h = 1e-6;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let jacobians = FreeTreeKinematics::joint_jacobians(&q);
        let here = FreeTreeKinematics::joint_placements(&q);
        for col in 0..9 {
            let plus = FreeTreeKinematics::joint_placements(&free_tree::moved(
                &q,
                &free_tree::unit(col),
                h,
            ));
            let minus = FreeTreeKinematics::joint_placements(&free_tree::moved(
                &q,
                &free_tree::unit(col),
                -h,
            ));
            for b in 0..4 {
                // Linear rows: dp/dt. Angular rows: ω with Ṙ Rᵀ = ω̂.
                let rate = |r: usize, c: usize| (plus[b].0[r][c] - minus[b].0[r][c]) / (2.0 * h);
                let spin =
                    |r: usize, c: usize| (0..3).map(|m| rate(r, m) * here[b].0[c][m]).sum::<f64>();
                let omega = [spin(2, 1), spin(0, 2), spin(1, 0)];
                for r in 0..3 {
                    let velocity = (plus[b].1[r] - minus[b].1[r]) / (2.0 * h);
                    let (lin, ang) = (jacobians[b][r][col], jacobians[b][3 + r][col]);
                    assert!(
                        (lin - velocity).abs() <= 1e-8,
                        "q {q:?} body {b} J[{r}][{col}] {lin}, {velocity}"
                    );
                    assert!(
                        (ang - omega[r]).abs() <= 1e-8,
                        "q {q:?} body {b} J[{}][{col}] {ang}, {}",
                        3 + r,
                        omega[r]
                    );
                }
            }
        }
    }
}

#[test]
fn centre_of_mass_jacobian_of_a_free_tree_is_the_derivative() {
    let h = 1e-6;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let jacobian = FreeTreeKinematics::center_of_mass_jacobian(&q);
        for col in 0..9 {
            let plus =
                FreeTreeKinematics::center_of_mass(&free_tree::moved(&q, &free_tree::unit(col), h));
            let minus = FreeTreeKinematics::center_of_mass(&free_tree::moved(
                &q,
                &free_tree::unit(col),
                -h,
            ));
            for row in 0..3 {
                let difference = (plus[row] - minus[row]) / (2.0 * h);
                assert!(
                    (jacobian[row][col] - difference).abs() <= 1e-8,
                    "q = {q:?}: J_c[{row}][{col}] = {}, central difference {difference}",
                    jacobian[row][col]
                );
            }
        }
    }
}

/// A_G q̇ of the free tree is the momentum of its bodies, summed in the test from the
/// generated placements and Jacobians and the runtime model's inertias:
/// l = Σ m v_G, k = Σ (x_G − c) × m v_G + R I_G Rᵀ ω.
#[test]
fn centroidal_momentum_of_a_free_tree_is_the_bodies_momentum() {
    let model = <FreeTreeKinematics as Mechanism>::model();
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let v: [f64; 9] = std::array::from_fn(|i| (0.4 * i as f64 + 0.3 * k as f64).sin());
        let a = FreeTreeKinematics::centroidal_momentum_matrix(&q);
        let generated: Vec<f64> = (0..6)
            .map(|r| (0..9).map(|c| a[r][c] * v[c]).sum())
            .collect();
        let placements = FreeTreeKinematics::joint_placements(&q);
        let jacobians = FreeTreeKinematics::joint_jacobians(&q);
        let centre = FreeTreeKinematics::center_of_mass(&q);
        let (mut linear, mut angular) = ([0.0; 3], [0.0; 3]);
        for (b, body) in model.bodies().iter().enumerate() {
            let rotation = nalgebra::Matrix3::from_fn(|r, c| placements[b].0[r][c]);
            let origin = nalgebra::Vector3::from(placements[b].1);
            let twist: Vec<f64> = (0..6)
                .map(|r| (0..9).map(|c| jacobians[b][r][c] * v[c]).sum())
                .collect();
            let (v_origin, omega) = (
                nalgebra::Vector3::new(twist[0], twist[1], twist[2]),
                nalgebra::Vector3::new(twist[3], twist[4], twist[5]),
            );
            let inertia = &body.inertia;
            let offset = rotation * inertia.com_in_body;
            let v_centre = v_origin + omega.cross(&offset);
            let momentum = v_centre * inertia.mass;
            let lever = origin + offset - nalgebra::Vector3::from(centre);
            let spin = rotation * inertia.inertia_com_in_body * rotation.transpose() * omega;
            let k_body = lever.cross(&momentum) + spin;
            for r in 0..3 {
                linear[r] += momentum[r];
                angular[r] += k_body[r];
            }
        }
        for r in 0..3 {
            assert!(
                (generated[r] - linear[r]).abs() <= 1e-12,
                "l[{r}]: {} against {}",
                generated[r],
                linear[r]
            );
            assert!(
                (generated[3 + r] - angular[r]).abs() <= 1e-12,
                "k[{r}]: {} against {}",
                generated[3 + r],
                angular[r]
            );
        }
    }
}

/// On the free tree, J̇ q̇ is the derivative of J q̇ along the motion: J(q ⊕ h q̇) q̇ against
/// J(q ⊖ h q̇) q̇ by central differences.
#[test]
fn acceleration_biases_of_a_free_tree_are_the_rate_of_the_jacobians() {
    let h = 1e-6;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let v: [f64; 9] = std::array::from_fn(|i| (0.4 * i as f64 + 0.3 * k as f64).cos());
        let along =
            |step: f64| FreeTreeKinematics::joint_velocities(&free_tree::moved(&q, &v, step), &v);
        let (plus, minus) = (along(h), along(-h));
        let bias = FreeTreeKinematics::joint_acceleration_biases(&q, &v);
        for b in 0..4 {
            for r in 0..6 {
                let rate = (plus[b][r] - minus[b][r]) / (2.0 * h);
                assert!(
                    (bias[b][r] - rate).abs() <= 1e-7,
                    "q {q:?} body {b} J̇v[{r}] {} against {rate}",
                    bias[b][r]
                );
            }
        }
    }
}

/// `forward_kinematics`: placements, velocities and accelerations at (q, v, a).
type ForwardKinematics<const NQ: usize, const NV: usize, const NB: usize> =
    fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> (Placements<NB>, Twists<NB>, Twists<NB>);

/// `joint_placements`, `joint_velocities`, `joint_jacobians`, `joint_acceleration_biases`.
type SingleOutputs<const NQ: usize, const NV: usize, const NB: usize> = (
    fn(&[f64; NQ]) -> Placements<NB>,
    fn(&[f64; NQ], &[f64; NV]) -> Twists<NB>,
    fn(&[f64; NQ]) -> [[[f64; NV]; 6]; NB],
    fn(&[f64; NQ], &[f64; NV]) -> Twists<NB>,
);

/// `forward_kinematics(q, v, a)` of one mechanism against the single outputs at a state.
fn check_forward_kinematics<const NQ: usize, const NV: usize, const NB: usize>(
    name: &str,
    (q, v, a): (&[f64; NQ], &[f64; NV], &[f64; NV]),
    forward: ForwardKinematics<NQ, NV, NB>,
    singles: SingleOutputs<NQ, NV, NB>,
) {
    let (poses, twists, accelerations) = forward(q, v, a);
    let (placements, velocities, jacobians, biases) = singles;
    let (poses_alone, twists_alone) = (placements(q), velocities(q, v));
    let (jacobian, bias) = (jacobians(q), biases(q, v));
    for b in 0..NB {
        for r in 0..3 {
            assert_close(poses[b].1[r], poses_alone[b].1[r], &|| {
                format!("{name} p[{b}][{r}]")
            });
            for c in 0..3 {
                let what = || format!("{name} R[{b}][{r}][{c}]");
                assert_close(poses[b].0[r][c], poses_alone[b].0[r][c], &what);
            }
        }
        for r in 0..6 {
            assert_close(twists[b][r], twists_alone[b][r], &|| {
                format!("{name} velocity[{b}][{r}]")
            });
            let expected = bias[b][r] + (0..NV).map(|c| jacobian[b][r][c] * a[c]).sum::<f64>();
            assert_close(accelerations[b][r], expected, &|| {
                format!("{name} acceleration[{b}][{r}]")
            });
        }
    }
}

macro_rules! forward_kinematics_of {
    ($m:ident, $name:expr, $q:expr, $v:expr, $a:expr) => {
        check_forward_kinematics(
            $name,
            ($q, $v, $a),
            $m::forward_kinematics,
            (
                $m::joint_placements,
                $m::joint_velocities,
                $m::joint_jacobians,
                $m::joint_acceleration_biases,
            ),
        )
    };
}

/// At Pinocchio's sampled q and v of the anchors, with an acceleration of our own, and at
/// the free tree's states.
#[test]
fn forward_kinematics_is_the_placements_velocities_and_accelerations() {
    fn arrays<const NQ: usize, const NV: usize>(s: &Sample) -> ([f64; NQ], [f64; NV], [f64; NV]) {
        let q: [f64; NQ] = s.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = s.v.clone().try_into().expect("nv matches");
        let a: [f64; NV] = std::array::from_fn(|i| (1.3 * i as f64 + q[0]).sin());
        (q, v, a)
    }
    for s in samples("pendulum") {
        let (q, v, a) = arrays(&s);
        forward_kinematics_of!(PendulumKinematics, "pendulum", &q, &v, &a);
    }
    for s in samples("double_pendulum") {
        let (q, v, a) = arrays(&s);
        forward_kinematics_of!(DoublePendulumKinematics, "double_pendulum", &q, &v, &a);
    }
    for s in samples("planar3") {
        let (q, v, a) = arrays(&s);
        forward_kinematics_of!(Planar3Kinematics, "planar3", &q, &v, &a);
    }
    for s in samples("ur5") {
        let (q, v, a) = arrays(&s);
        forward_kinematics_of!(Ur5Kinematics, "ur5", &q, &v, &a);
    }
    for s in samples("panda") {
        let (q, v, a) = arrays(&s);
        forward_kinematics_of!(PandaKinematics, "panda", &q, &v, &a);
    }
    for k in 0..6 {
        let (q, v, a) = (
            free_tree::configuration(k),
            free_tree::velocity(k),
            free_tree::acceleration(k),
        );
        forward_kinematics_of!(FreeTreeKinematics, "free tree", &q, &v, &a);
    }
}

type Matrix<const NV: usize> = [[f64; NV]; 6];

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn column<const NV: usize>(m: &Matrix<NV>, c: usize) -> ([f64; 3], [f64; 3]) {
    ([m[0][c], m[1][c], m[2][c]], [m[3][c], m[4][c], m[5][c]])
}

#[track_caller]
fn assert_within(got: f64, expected: f64, tolerance: f64, what: &dyn Fn() -> String) {
    assert!(
        (got - expected).abs() <= tolerance,
        "{}: {got} against {expected}",
        what()
    );
}

/// The J of the two outputs agree (to rounding: each function's code is scheduled on its
/// own).
fn assert_same<const NV: usize>(a: &Matrix<NV>, b: &Matrix<NV>, what: &dyn Fn() -> String) {
    for r in 0..6 {
        for c in 0..NV {
            assert_within(a[r][c], b[r][c], 1e-15, &|| {
                format!("{} J[{r}][{c}]", what())
            });
        }
    }
}

/// One anchor robot's J and J̇ against Pinocchio's values (see the file's doc).
fn check_world_jacobians<const NQ: usize, const NV: usize>(
    name: &str,
    world: fn(&[f64; NQ]) -> Matrix<NV>,
    time_variation: fn(&[f64; NQ], &[f64; NV]) -> (Matrix<NV>, Matrix<NV>),
) {
    let samples = samples(name);
    assert!(!samples.is_empty(), "{name}: no samples");
    for (k, sample) in samples.iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = sample.v.clone().try_into().expect("nv matches");
        let j = world(&q);
        let (j_again, j_dot) = time_variation(&q, &v);
        assert_same(&j, &j_again, &|| format!("{name} sample {k}"));
        let mut checked = [false; NV];
        for (b, lwa) in sample.joint_jacobians_world.iter().enumerate() {
            let p = sample.joint_placements[b].translation;
            let moves = |c: usize| (0..6).any(|r| lwa[r][c] != 0.0);
            for c in (0..NV).filter(|&c| moves(c)) {
                checked[c] = true;
                let omega = [lwa[3][c], lwa[4][c], lwa[5][c]];
                let shift = cross(p, omega);
                for r in 0..3 {
                    let what = || format!("{name} sample {k} body {b} J[{r}][{c}]");
                    assert_within(j[r][c], lwa[r][c] + shift[r], 1e-12, &what);
                    let what = || format!("{name} sample {k} body {b} J[{}][{c}]", 3 + r);
                    assert_within(j[3 + r][c], omega[r], 1e-12, &what);
                }
            }
            // Body b's spatial acceleration at the origin (a = 0), then its classical
            // acceleration at p_b: a_P = a_O + α × p + ω × v_P, with [v_P; ω] = J_b v.
            let (mut a_origin, mut alpha) = ([0.0; 3], [0.0; 3]);
            let (mut v_point, mut omega) = ([0.0; 3], [0.0; 3]);
            for c in (0..NV).filter(|&c| moves(c)) {
                let (lin, ang) = column(&j_dot, c);
                for r in 0..3 {
                    a_origin[r] += lin[r] * v[c];
                    alpha[r] += ang[r] * v[c];
                    v_point[r] += lwa[r][c] * v[c];
                    omega[r] += lwa[3 + r][c] * v[c];
                }
            }
            let (turn, carry) = (cross(alpha, p), cross(omega, v_point));
            let expected = &sample.joint_jacobian_time_derivative_times_v_world[b];
            for r in 0..3 {
                let what = || format!("{name} sample {k} body {b} J̇v[{r}]");
                assert_within(a_origin[r] + turn[r] + carry[r], expected[r], 1e-12, &what);
                let what = || format!("{name} sample {k} body {b} J̇v[{}]", 3 + r);
                assert_within(alpha[r], expected[3 + r], 1e-12, &what);
            }
        }
        assert!(checked.iter().all(|&c| c), "{name}: a column moves no body");
    }
}

#[test]
fn world_jacobians_and_their_rates_match_pinocchio() {
    check_world_jacobians(
        "pendulum",
        PendulumKinematics::joint_jacobians_world,
        PendulumKinematics::joint_jacobians_world_time_variation,
    );
    check_world_jacobians(
        "double_pendulum",
        DoublePendulumKinematics::joint_jacobians_world,
        DoublePendulumKinematics::joint_jacobians_world_time_variation,
    );
    check_world_jacobians(
        "planar3",
        Planar3Kinematics::joint_jacobians_world,
        Planar3Kinematics::joint_jacobians_world_time_variation,
    );
    check_world_jacobians(
        "ur5",
        Ur5Kinematics::joint_jacobians_world,
        Ur5Kinematics::joint_jacobians_world_time_variation,
    );
    check_world_jacobians(
        "panda",
        PandaKinematics::joint_jacobians_world,
        PandaKinematics::joint_jacobians_world_time_variation,
    );
}

/// On the free tree J̇ is the derivative of J along the motion: J(q ⊕ h v) against
/// J(q ⊖ h v) by central differences.
#[test]
fn world_jacobian_rates_of_a_free_tree_are_the_derivatives() {
    let h = 1e-6;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let v = free_tree::velocity(k);
        let (j, j_dot) = FreeTreeKinematics::joint_jacobians_world_time_variation(&q, &v);
        assert_same(&j, &FreeTreeKinematics::joint_jacobians_world(&q), &|| {
            format!("q {q:?}")
        });
        let plus = FreeTreeKinematics::joint_jacobians_world(&free_tree::moved(&q, &v, h));
        let minus = FreeTreeKinematics::joint_jacobians_world(&free_tree::moved(&q, &v, -h));
        for r in 0..6 {
            for c in 0..9 {
                let rate = (plus[r][c] - minus[r][c]) / (2.0 * h);
                let what = || format!("q {q:?} J̇[{r}][{c}]");
                assert_within(j_dot[r][c], rate, 1e-7, &what);
            }
        }
    }
}

/// J v of the free tree is the base's velocity at the world origin (columns 0..6: the
/// base's v = [v_P; ω] in its own frame, moved to the origin in world axes: R v_P + p × R ω),
/// checked column by column against the base's placement; and J̇ vanishes at v = 0.
#[test]
fn world_jacobian_of_the_free_base_is_its_twist_at_the_origin() {
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let j = FreeTreeKinematics::joint_jacobians_world(&q);
        let (_, j_dot) = FreeTreeKinematics::joint_jacobians_world_time_variation(&q, &[0.0; 9]);
        assert!(j_dot.iter().flatten().all(|&x| x == 0.0), "J̇ at v = 0");
        let rotation = FreeTreeKinematics::joint_placements(&q)[0].0;
        let p = [q[0], q[1], q[2]];
        for e in 0..3 {
            let axis = [rotation[0][e], rotation[1][e], rotation[2][e]];
            let (lin, ang) = column(&j, e);
            let (lin_spin, ang_spin) = column(&j, 3 + e);
            let moment = cross(p, axis);
            for r in 0..3 {
                let what = || format!("q {q:?} column {e} row {r}");
                assert_within(lin[r], axis[r], 1e-14, &what);
                assert_within(ang[r], 0.0, 0.0, &what);
                assert_within(lin_spin[r], moment[r], 1e-14, &what);
                assert_within(ang_spin[r], axis[r], 1e-14, &what);
            }
        }
    }
}
