//! The generated centre of mass and its Jacobian:
//! - against Pinocchio's `centerOfMass` and `jacobianCenterOfMass` (world frame) for the
//!   five anchor robots, imported from the same URDF files, at Pinocchio's 20 sampled
//!   configurations each (`tests/data/pinocchio_ext/<name>_com.json`), to 1e-12;
//! - against the runtime reference's centre of mass (body poses and mass centres, written
//!   independently) on a free-floating branched tree with a prismatic joint, and its
//!   Jacobian against central finite differences of the generated centre of mass along
//!   q ⊕ δ (the free base moved on its manifold by `integrate_configuration`).

use dynamics_runtime::{integrate_configuration, mechanism, Mechanism, Reference};
use serde::Deserialize;

mechanism! {
    pub struct PendulumCom;
    urdf: "../models/urdf/pendulum.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian];
}

mechanism! {
    pub struct DoublePendulumCom;
    urdf: "../models/urdf/double_pendulum.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian];
}

mechanism! {
    pub struct Planar3Com;
    urdf: "../models/urdf/planar3.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian];
    allow: [triangle_inequality];
}

mechanism! {
    pub struct Ur5Com;
    urdf: "../models/urdf/ur5.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian];
}

mechanism! {
    pub struct PandaCom;
    urdf: "../models/urdf/panda.urdf";
    outputs: [center_of_mass, center_of_mass_jacobian];
}

mechanism! {
    /// A free-floating base with two branches, one ending in a slider; offset mass centres
    /// and a rotated placement, so that no term vanishes by symmetry.
    pub struct FreeTreeCom;
    outputs: [center_of_mass, center_of_mass_jacobian];
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
struct Sample {
    q: Vec<f64>,
    center_of_mass: [f64; 3],
    com_jacobian: Vec<Vec<f64>>,
}

#[derive(Deserialize)]
struct Samples {
    samples: Vec<Sample>,
}

fn samples(name: &str) -> Vec<Sample> {
    let path = format!(
        "{}/data/pinocchio_ext/{name}_com.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let file: Samples = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
    assert_eq!(file.samples.len(), 20, "{path}");
    file.samples
}

/// Compares one robot's generated functions with Pinocchio's values.
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
        PendulumCom::center_of_mass::<f64>,
        PendulumCom::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "double_pendulum",
        DoublePendulumCom::center_of_mass::<f64>,
        DoublePendulumCom::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "planar3",
        Planar3Com::center_of_mass::<f64>,
        Planar3Com::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "ur5",
        Ur5Com::center_of_mass::<f64>,
        Ur5Com::center_of_mass_jacobian::<f64>,
    );
    check_against_pinocchio(
        "panda",
        PandaCom::center_of_mass::<f64>,
        PandaCom::center_of_mass_jacobian::<f64>,
    );
}

/// A configuration of the free tree: position, a unit quaternion, three joint values.
fn free_tree_configuration(k: usize) -> [f64; 10] {
    let s = k as f64;
    let quaternion = [0.1 + 0.05 * s, -0.2, 0.3, 0.9 - 0.1 * s];
    let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
    [
        0.3 - 0.1 * s,
        0.2 * s,
        1.0,
        quaternion[0] / norm,
        quaternion[1] / norm,
        quaternion[2] / norm,
        quaternion[3] / norm,
        (0.7 + s).sin(),
        (0.3 * s).cos(),
        0.05 * s,
    ]
}

#[test]
fn centre_of_mass_of_a_free_tree_matches_the_reference() {
    let model = <FreeTreeCom as Mechanism>::model();
    let mut reference = Reference::<f64>::new(&model);
    for k in 0..6 {
        let q = free_tree_configuration(k);
        let generated = FreeTreeCom::center_of_mass(&q);
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
fn centre_of_mass_jacobian_of_a_free_tree_is_the_derivative() {
    let free_joints = [(0_usize, 0_usize)];
    for k in 0..6 {
        let q = free_tree_configuration(k);
        let jacobian = FreeTreeCom::center_of_mass_jacobian(&q);
        for col in 0..9 {
            // q ⊕ (±h e_col): the free base moves on its manifold.
            let h = 1e-6;
            let moved = |sign: f64| {
                let mut v = [0.0; 9];
                v[col] = sign;
                let mut out = [0.0; 10];
                integrate_configuration(&q, &v, h, &free_joints, &mut out);
                FreeTreeCom::center_of_mass(&out)
            };
            let (plus, minus) = (moved(1.0), moved(-1.0));
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
