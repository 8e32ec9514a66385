//! Random trees with frames through the macro: `tests/build.rs` writes four random
//! mechanisms (3 to 22 moving joints, two with a free root; revolute and prismatic joints
//! about random axes; a body welded through a fixed joint on every third body; frames on
//! moving bodies, on welded bodies and on the ground), each generating every kinematics
//! output, and each output equals the runtime reference (written independently) at 20
//! random states, within 1e-12 · (1 + max |value|):
//! - frame placements, Jacobians (world-aligned and local), velocities and J̇ v against the
//!   reference's frame of the same name (`frame_pose`, `frame_jacobian`,
//!   `frame_jacobian_local`, `frame_velocity`, `frame_classical_acceleration` at q̈ = 0);
//! - body placements, Jacobians, velocities and J̇ v against the reference's body frames;
//! - the centre of mass, J_c q̇ against the linear momentum over the mass, A_G q̇ against the
//!   centroidal momentum h_G, and Ȧ_G q̇ against ḣ_G at q̈ = 0.

use dynamics_runtime::{Mechanism, Reference};
use dynamics_tests::random::{random_state, SplitMix};
use nalgebra::Matrix6xX;

mod trees {
    //! The random frame trees of `tests/build.rs`.
    #![allow(dead_code)]
    include!(concat!(env!("OUT_DIR"), "/random_frame_trees.rs"));
}

/// States per tree.
const STATES: usize = 20;

/// Asserts `|got − expected| ≤ 1e-12 · scale`, naming the quantity.
fn close(got: f64, expected: f64, scale: f64, what: &dyn Fn() -> String) {
    assert!(
        (got - expected).abs() <= 1e-12 * scale,
        "{}: generated {got}, reference {expected}",
        what()
    );
}

/// `1 + max |x|` over a 6 × nv matrix.
fn scale_of(matrix: &Matrix6xX<f64>) -> f64 {
    1.0 + matrix.iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

macro_rules! frame_tree_test {
    ($test:ident, $m:ident) => {
        #[test]
        fn $test() {
            use trees::$m;
            const NQ: usize = <$m as Mechanism>::NQ;
            const NV: usize = <$m as Mechanism>::NV;
            let model = <$m as Mechanism>::model();
            let mut reference = Reference::<f64>::new(&model);
            let mut rng = SplitMix(0xf7a3 ^ NV as u64);
            let mut jacobian = Matrix6xX::<f64>::zeros(NV);
            let mut local = Matrix6xX::<f64>::zeros(NV);
            let zero = [0.0; NV];
            let names = <$m as Mechanism>::FRAME_NAMES;
            assert!(!names.is_empty());
            for state in 0..STATES {
                let (q, v, _) = random_state(&model, &mut rng);
                let q: [f64; NQ] = q.try_into().expect("nq");
                let v: [f64; NV] = v.try_into().expect("nv");
                let name = <$m as Mechanism>::NAME;
                // Operational frames and body frames alike: (name, placement, J, local J or
                // none, velocity, J̇ v).
                let frames = $m::frame_placements(&q);
                let frame_jacobians = $m::frame_jacobians(&q);
                let frame_local = $m::frame_jacobians_local(&q);
                let frame_velocities = $m::frame_velocities(&q, &v);
                let frame_biases = $m::frame_acceleration_biases(&q, &v);
                let bodies = $m::joint_placements(&q);
                let body_jacobians = $m::joint_jacobians(&q);
                let body_velocities = $m::joint_velocities(&q, &v);
                let body_biases = $m::joint_acceleration_biases(&q, &v);
                let mut all = Vec::new();
                for (f, frame) in names.iter().enumerate() {
                    all.push((
                        *frame,
                        frames[f],
                        frame_jacobians[f],
                        Some(frame_local[f]),
                        frame_velocities[f],
                        frame_biases[f],
                    ));
                }
                for (b, body) in <$m as Mechanism>::BODY_NAMES.iter().enumerate() {
                    all.push((
                        *body,
                        bodies[b],
                        body_jacobians[b],
                        None,
                        body_velocities[b],
                        body_biases[b],
                    ));
                }
                for (frame, (rotation, origin), world, own, velocity, bias) in all {
                    let what = |item: &str| format!("{name} state {state} frame {frame} {item}");
                    let index = model.frame_index(frame).expect("every frame in the model");
                    let pose = reference.frame_pose(&q, index).expect("sizes match");
                    for r in 0..3 {
                        close(origin[r], pose.origin_in_world[r], 2.0, &|| what("p"));
                        for c in 0..3 {
                            close(rotation[r][c], pose.rotation_in_world[(r, c)], 2.0, &|| {
                                what("R")
                            });
                        }
                    }
                    reference
                        .frame_jacobian(&q, index, &mut jacobian)
                        .expect("sizes match");
                    reference
                        .frame_jacobian_local(&q, index, &mut local)
                        .expect("sizes match");
                    let (s_world, s_local) = (scale_of(&jacobian), scale_of(&local));
                    let expected_velocity = reference
                        .frame_velocity(&q, &v, index)
                        .expect("sizes match");
                    let expected_bias = reference
                        .frame_classical_acceleration(&q, &v, &zero, index)
                        .expect("sizes match");
                    let s_rates = 1.0
                        + expected_velocity
                            .iter()
                            .chain(expected_bias.iter())
                            .fold(0.0_f64, |m, x| m.max(x.abs()));
                    for r in 0..6 {
                        for c in 0..NV {
                            close(world[r][c], jacobian[(r, c)], s_world, &|| what("J"));
                            if let Some(own) = &own {
                                close(own[r][c], local[(r, c)], s_local, &|| what("local J"));
                            }
                        }
                        close(velocity[r], expected_velocity[r], s_rates, &|| {
                            what("velocity")
                        });
                        close(bias[r], expected_bias[r], s_rates, &|| what("J̇v"));
                    }
                }
                // The centre of mass, J_c q̇ = (linear momentum) / M, A_G q̇ = h_G, Ȧ_G q̇ = ḣ_G.
                let com = $m::center_of_mass(&q);
                let expected_com = reference.center_of_mass(&q).expect("sizes match");
                let momentum = reference.centroidal_momentum(&q, &v).expect("sizes match");
                let rate = reference
                    .centroidal_momentum_rate(&q, &v, &zero)
                    .expect("sizes match");
                let total_mass: f64 = model.bodies().iter().map(|b| b.inertia.mass).sum();
                let com_jacobian = $m::center_of_mass_jacobian(&q);
                let a_g = $m::centroidal_momentum_matrix(&q);
                let bias = $m::centroidal_bias(&q, &v);
                let s = 1.0
                    + momentum
                        .iter()
                        .chain(rate.iter())
                        .fold(0.0_f64, |m, x| m.max(x.abs()));
                for r in 0..3 {
                    close(com[r], expected_com[r], 2.0, &|| format!("{name} c[{r}]"));
                    let jc_v: f64 = (0..NV).map(|c| com_jacobian[r][c] * v[c]).sum();
                    close(jc_v * total_mass, momentum[r], s, &|| {
                        format!("{name} J_c v[{r}]")
                    });
                }
                for r in 0..6 {
                    let a_v: f64 = (0..NV).map(|c| a_g[r][c] * v[c]).sum();
                    close(a_v, momentum[r], s, &|| format!("{name} A_G v[{r}]"));
                    close(bias[r], rate[r], s, &|| format!("{name} Ȧ_G v[{r}]"));
                }
            }
        }
    };
}

frame_tree_test!(frame_tree_03, FrameTree03);
frame_tree_test!(frame_tree_08, FrameTree08);
frame_tree_test!(frame_tree_14, FrameTree14);
frame_tree_test!(frame_tree_22, FrameTree22);
