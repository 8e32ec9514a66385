//! Limbs that are mirror images, as ANYmal's are (hips about +x on one side and −x on the
//! other, thighs and shanks about ±y): the compiler gives the frame of each body declared
//! about a negative coordinate axis a half turn, so that every leg turns about +x, +y, +y
//! and the four legs are computed side by side in the lanes of packed values
//! (`dynamics-codegen`'s `model::frame_turns`). The coordinates, their signs and every
//! output are as declared: each is checked here against the runtime reference, whose model
//! is the declaration's with no frame turned:
//! - the default outputs (inverse dynamics, gravity, bias, M, C, forward dynamics, the
//!   energies, the joint reactions in the declared joint frames) at 30 random states, in
//!   f64 and f32 (`generated_support::check_against_reference`);
//! - the joint placements (the declared joint frames in the world) against the reference's
//!   body poses, A_G v against its centroidal momentum, and M⁻¹ M = 1;
//! - ∂τ and ∂q̈ against the reference at dual numbers.

#[macro_use]
mod generated_support;

use dynamics_runtime::{mechanism, Mechanism, Reference};
use dynamics_tests::assert_placements_are_the_poses;
use dynamics_tests::dual_derivatives::{
    assert_derivatives_are_the_reference_dual_numbers, GeneratedDerivatives,
};
use dynamics_tests::random::SplitMix;
use generated_support::{arr, check_against_reference, Inputs, UnderTest};

mechanism! {
    /// A free torso on four legs that are mirror images left to right and front to back,
    /// each declared about the axes its side would use: hips about ±x, thighs and shanks
    /// about ±y; the hips turned a little about x, mirrored.
    pub struct MirroredQuadruped;
    outputs: [inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics,
              kinetic_energy, potential_energy, joint_reactions, centroidal_momentum_matrix,
              mass_matrix_inverse, joint_placements, inverse_dynamics_derivatives,
              forward_dynamics_derivatives];
    body torso { mass: 20.0, com: [0.01, 0.0, 0.02], inertia: diag([0.3, 0.6, 0.7]) }
    joint base: free(ground -> torso);
    body hip_lf { mass: 1.5, com: [0.05, 0.02, 0.0], inertia: [[0.002, 0.0001, 0.0], [0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
    body thigh_lf { mass: 1.2, com: [0.0, 0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
    body shank_lf { mass: 0.4, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
    joint haa_lf: revolute(torso -> hip_lf) { axis: [1.0, 0.0, 0.0], at: [0.28, 0.1, 0.0], rotation: rpy(0.2, 0.0, 0.0) }
    joint hfe_lf: revolute(hip_lf -> thigh_lf) { axis: [0.0, 1.0, 0.0], at: [0.06, 0.05, 0.0] }
    joint kfe_lf: revolute(thigh_lf -> shank_lf) { axis: [0.0, 1.0, 0.0], at: [0.0, 0.02, -0.28] }
    body hip_rf { mass: 1.5, com: [0.05, -0.02, 0.0], inertia: [[0.002, -0.0001, 0.0], [-0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
    body thigh_rf { mass: 1.2, com: [0.0, -0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
    body shank_rf { mass: 0.4, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
    joint haa_rf: revolute(torso -> hip_rf) { axis: [-1.0, 0.0, 0.0], at: [0.28, -0.1, 0.0], rotation: rpy(-0.2, 0.0, 0.0) }
    joint hfe_rf: revolute(hip_rf -> thigh_rf) { axis: [0.0, -1.0, 0.0], at: [0.06, -0.05, 0.0] }
    joint kfe_rf: revolute(thigh_rf -> shank_rf) { axis: [0.0, -1.0, 0.0], at: [0.0, -0.02, -0.28] }
    body hip_lh { mass: 1.4, com: [-0.05, 0.02, 0.0], inertia: [[0.002, -0.0001, 0.0], [-0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
    body thigh_lh { mass: 1.2, com: [0.0, 0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
    body shank_lh { mass: 0.45, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
    joint haa_lh: revolute(torso -> hip_lh) { axis: [-1.0, 0.0, 0.0], at: [-0.28, 0.1, 0.0], rotation: rpy(0.2, 0.0, 0.0) }
    joint hfe_lh: revolute(hip_lh -> thigh_lh) { axis: [0.0, 1.0, 0.0], at: [-0.06, 0.05, 0.0] }
    joint kfe_lh: revolute(thigh_lh -> shank_lh) { axis: [0.0, 1.0, 0.0], at: [0.0, 0.02, -0.28] }
    body hip_rh { mass: 1.4, com: [-0.05, -0.02, 0.0], inertia: [[0.002, 0.0001, 0.0], [0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
    body thigh_rh { mass: 1.2, com: [0.0, -0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
    body shank_rh { mass: 0.45, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
    joint haa_rh: revolute(torso -> hip_rh) { axis: [1.0, 0.0, 0.0], at: [-0.28, -0.1, 0.0], rotation: rpy(-0.2, 0.0, 0.0) }
    joint hfe_rh: revolute(hip_rh -> thigh_rh) { axis: [0.0, -1.0, 0.0], at: [-0.06, -0.05, 0.0] }
    joint kfe_rh: revolute(thigh_rh -> shank_rh) { axis: [0.0, -1.0, 0.0], at: [0.0, -0.02, -0.28] }
}

const NQ: usize = <MirroredQuadruped as Mechanism>::NQ;
const NV: usize = <MirroredQuadruped as Mechanism>::NV;

#[test]
fn the_default_outputs_of_mirror_image_legs_are_the_reference() {
    let model =
        |p: &[f64]| MirroredQuadruped::model_with_parameters(p).unwrap_or_else(|e| panic!("{e}"));
    let under_test = UnderTest {
        name: <MirroredQuadruped as Mechanism>::NAME,
        model: Box::new(model),
        num_parameters: 0,
        loads: &[],
        num_load_inputs: 0,
        f64: generated_functions!(f64, MirroredQuadruped, p: no, loads: no),
        f32: generated_functions!(f32, MirroredQuadruped, p: no, loads: no),
    };
    assert_eq!(under_test.f64.len(), 9);
    check_against_reference(&under_test, 30, 0x0d1e).print("mirrored quadruped");
}

/// A random configuration, its quaternion normalized, and a velocity.
fn random_state(rng: &mut SplitMix) -> ([f64; NQ], [f64; NV]) {
    let mut q: [f64; NQ] = std::array::from_fn(|_| rng.uniform(-1.5, 1.5));
    let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
    q[3..7].iter_mut().for_each(|x| *x /= norm);
    (q, std::array::from_fn(|_| rng.uniform(-2.0, 2.0)))
}

#[test]
fn placements_centroidal_momentum_and_m_inverse_of_mirror_image_legs_are_the_reference() {
    let model = MirroredQuadruped::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(0x0d1f);
    for _ in 0..10 {
        let (q, v) = random_state(&mut rng);
        let poses = reference.body_poses(&q).expect("sizes");
        assert_placements_are_the_poses(&MirroredQuadruped::joint_placements(&q), poses);
        let a_g = MirroredQuadruped::centroidal_momentum_matrix(&q);
        let h_g = reference.centroidal_momentum(&q, &v).expect("sizes");
        for r in 0..6 {
            let x: f64 = (0..NV).map(|c| a_g[r][c] * v[c]).sum();
            assert!(
                (x - h_g[r]).abs() <= 1e-12 * (1.0 + h_g[r].abs()),
                "h_G[{r}]: {x}, {}",
                h_g[r]
            );
        }
        let (m, m_inverse) = (
            MirroredQuadruped::mass_matrix(&q),
            MirroredQuadruped::mass_matrix_inverse(&q),
        );
        for i in 0..NV {
            for j in 0..NV {
                let x: f64 = (0..NV).map(|k| m_inverse[i][k] * m[k][j]).sum();
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((x - want).abs() <= 1e-10, "(M⁻¹ M)[{i}][{j}] = {x}");
            }
        }
    }
}

#[test]
fn derivatives_of_mirror_image_legs_are_the_reference_dual_numbers() {
    assert_derivatives_are_the_reference_dual_numbers(
        &MirroredQuadruped::model(),
        &GeneratedDerivatives::<NQ, NV> {
            inverse_dynamics: MirroredQuadruped::inverse_dynamics,
            inverse_dynamics_derivatives: MirroredQuadruped::inverse_dynamics_derivatives,
            forward_dynamics_derivatives: MirroredQuadruped::forward_dynamics_derivatives,
        },
    );
}
