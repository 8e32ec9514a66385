//! Tests of the frame kinematics and the centroidal quantities: a planar two-link arm
//! against hand formulas, every quantity against central finite differences of the one
//! below it (the configuration moved on its manifold by `integrate_configuration`), frames
//! on merged bodies, the ground, the errors, and Pinocchio's values for the same tree
//! (`pinocchio_frames.rs`).

use super::{FrameError, Reference};
use crate::model::{
    BodySpec, FrameSpec, Inertia, JointKind, JointSpec, Model, ModelBuilder, Placement, SizeError,
    GROUND,
};
use crate::{integrate_configuration, DoubleDouble};
use nalgebra::{Matrix3, Matrix6xX, Vector3, Vector6};

/// Rows of the rotation by `angle` about z.
fn rz_rows(angle: f64) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

// ---------------------------------------------------------------------------------------
// A planar two-link arm, by hand.

const L1: f64 = 0.6;
const L2: f64 = 0.5;
const M1: f64 = 2.0;
const M2: f64 = 1.5;
/// Mass centres along each link's x axis, and the links' I_zz about them.
const D1: f64 = 0.3;
const D2: f64 = 0.2;
const IZZ1: f64 = 0.06;
const IZZ2: f64 = 0.035;
/// The tool frame at the end of link 2, turned by PHI about z.
const PHI: f64 = 0.3;

fn planar_arm() -> Model {
    ModelBuilder::new()
        .body(BodySpec::new(
            "link1",
            Inertia::new(
                M1,
                [D1, 0.0, 0.0],
                [[0.01, 0.0, 0.0], [0.0, 0.05, 0.0], [0.0, 0.0, IZZ1]],
            ),
        ))
        .body(BodySpec::new(
            "link2",
            Inertia::new(
                M2,
                [D2, 0.0, 0.0],
                [[0.005, 0.0, 0.0], [0.0, 0.03, 0.0], [0.0, 0.0, IZZ2]],
            ),
        ))
        .joint(JointSpec::revolute(
            "shoulder",
            GROUND,
            "link1",
            [0.0, 0.0, 1.0],
        ))
        .joint(JointSpec::revolute("elbow", "link1", "link2", [0.0, 0.0, 1.0]).at([L1, 0.0, 0.0]))
        .frame(FrameSpec::new("tool", "link2").placed([L2, 0.0, 0.0], rz_rows(PHI)))
        .build()
        .expect("valid arm")
}

/// The z component of a planar cross product.
fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn assert_close(what: &str, got: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(got.len(), expected.len(), "{what}");
    for (k, (g, e)) in got.iter().zip(expected).enumerate() {
        assert!(
            (g - e).abs() <= tolerance * (1.0 + e.abs()),
            "{what}[{k}]: got {g}, expected {e} (difference {:e})",
            g - e
        );
    }
}

#[test]
fn planar_arm_against_hand_formulas() {
    let model = planar_arm();
    let tool = model.frame_index("tool").expect("declared");
    assert_eq!(tool, 2);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a): ([f64; 2], [f64; 2], [f64; 2]) = ([0.4, -0.9], [1.3, -0.7], [0.5, 2.0]);
    let (s1, c1) = q[0].sin_cos();
    let (s12, c12) = (q[0] + q[1]).sin_cos();
    let (w1, w12) = (v[0], v[0] + v[1]);
    let (a1, a12) = (a[0], a[0] + a[1]);

    // Placement: the arm's tip, turned by θ1 + θ2 + φ.
    let pose = r.frame_pose(&q, tool).expect("sizes match");
    let tip = [L1 * c1 + L2 * c12, L1 * s1 + L2 * s12, 0.0];
    assert_close("origin", pose.origin_in_world.as_slice(), &tip, 1e-15);
    let turned = Placement::new([0.0; 3], rz_rows(q[0] + q[1] + PHI)).rotation;
    assert_close(
        "rotation",
        pose.rotation_in_world.as_slice(),
        turned.as_slice(),
        1e-15,
    );

    // Jacobian, LOCAL_WORLD_ALIGNED: ∂tip/∂q, and ω = (θ̇1 + θ̇2) z.
    let mut jacobian = Matrix6xX::zeros(2);
    r.frame_jacobian(&q, tool, &mut jacobian)
        .expect("sizes match");
    let expected = [
        [-L1 * s1 - L2 * s12, L1 * c1 + L2 * c12, 0.0, 0.0, 0.0, 1.0],
        [-L2 * s12, L2 * c12, 0.0, 0.0, 0.0, 1.0],
    ];
    for k in 0..2 {
        let column: Vector6<f64> = jacobian.column(k).into_owned();
        assert_close("jacobian", column.as_slice(), &expected[k], 1e-15);
    }
    // LOCAL: the same columns in the tool's axes.
    let mut local = Matrix6xX::zeros(2);
    r.frame_jacobian_local(&q, tool, &mut local)
        .expect("sizes match");
    for k in 0..2 {
        let linear = turned.transpose() * Vector3::new(expected[k][0], expected[k][1], 0.0);
        let column: Vector6<f64> = local.column(k).into_owned();
        assert_close(
            "local jacobian",
            column.as_slice(),
            &[linear.x, linear.y, linear.z, 0.0, 0.0, 1.0],
            1e-15,
        );
    }

    // Velocity: J v.
    let velocity = r.frame_velocity(&q, &v, tool).expect("sizes match");
    let tip_velocity = [
        -L1 * s1 * w1 - L2 * s12 * w12,
        L1 * c1 * w1 + L2 * c12 * w12,
        0.0,
        0.0,
        0.0,
        w12,
    ];
    assert_close("velocity", velocity.as_slice(), &tip_velocity, 1e-15);

    // Classical acceleration: the tip's second derivative; at a = 0, J̇ v.
    let tip_accel = |a1: f64, a12: f64| {
        [
            -L1 * (c1 * w1 * w1 + s1 * a1) - L2 * (c12 * w12 * w12 + s12 * a12),
            L1 * (-s1 * w1 * w1 + c1 * a1) + L2 * (-s12 * w12 * w12 + c12 * a12),
            0.0,
            0.0,
            0.0,
            a12,
        ]
    };
    let accel = r
        .frame_classical_acceleration(&q, &v, &a, tool)
        .expect("sizes match");
    assert_close("acceleration", accel.as_slice(), &tip_accel(a1, a12), 1e-14);
    let jdot_v = r
        .frame_classical_acceleration(&q, &v, &[0.0; 2], tool)
        .expect("sizes match");
    assert_close("J̇ v", jdot_v.as_slice(), &tip_accel(0.0, 0.0), 1e-14);

    // Centroidal momentum: the mass centres, their velocities and accelerations by hand.
    let g1 = [D1 * c1, D1 * s1];
    let g2 = [L1 * c1 + D2 * c12, L1 * s1 + D2 * s12];
    let g = [
        (M1 * g1[0] + M2 * g2[0]) / (M1 + M2),
        (M1 * g1[1] + M2 * g2[1]) / (M1 + M2),
    ];
    let v1 = [-D1 * s1 * w1, D1 * c1 * w1];
    let v2 = [
        -L1 * s1 * w1 - D2 * s12 * w12,
        L1 * c1 * w1 + D2 * c12 * w12,
    ];
    let acc1 = [
        -D1 * (c1 * w1 * w1 + s1 * a1),
        D1 * (-s1 * w1 * w1 + c1 * a1),
    ];
    let acc2 = [
        -L1 * (c1 * w1 * w1 + s1 * a1) - D2 * (c12 * w12 * w12 + s12 * a12),
        L1 * (-s1 * w1 * w1 + c1 * a1) + D2 * (-s12 * w12 * w12 + c12 * a12),
    ];
    let rel = |p: [f64; 2]| [p[0] - g[0], p[1] - g[1]];
    let scaled = |m: f64, x: [f64; 2]| [m * x[0], m * x[1]];
    let h = r.centroidal_momentum(&q, &v).expect("sizes match");
    let h_by_hand = [
        M1 * v1[0] + M2 * v2[0],
        M1 * v1[1] + M2 * v2[1],
        0.0,
        0.0,
        0.0,
        cross2(rel(g1), scaled(M1, v1)) + cross2(rel(g2), scaled(M2, v2)) + IZZ1 * w1 + IZZ2 * w12,
    ];
    assert_close("h_G", h.as_slice(), &h_by_hand, 1e-14);
    let h_dot = r.centroidal_momentum_rate(&q, &v, &a).expect("sizes match");
    let h_dot_by_hand = [
        M1 * acc1[0] + M2 * acc2[0],
        M1 * acc1[1] + M2 * acc2[1],
        0.0,
        0.0,
        0.0,
        cross2(rel(g1), scaled(M1, acc1))
            + cross2(rel(g2), scaled(M2, acc2))
            + IZZ1 * a1
            + IZZ2 * a12,
    ];
    assert_close("ḣ_G", h_dot.as_slice(), &h_dot_by_hand, 1e-14);
}

#[test]
fn body_frames_are_the_body_poses() {
    let model = planar_arm();
    let mut r = Reference::<f64>::new(&model);
    let q = [0.4, -0.9];
    let poses = r.body_poses(&q).expect("sizes match").to_vec();
    for (name, body) in [("link1", 0), ("link2", 1)] {
        let index = model.frame_index(name).expect("every body is a frame");
        assert_eq!(r.frame_pose(&q, index).expect("sizes match"), poses[body]);
    }
}

// ---------------------------------------------------------------------------------------
// A free-floating tree with frames everywhere, against finite differences.

/// A free-floating base carrying a turned revolute arm, a slider on the arm and a hand
/// welded to the arm; frames on the base, the slider, the (merged) hand and the ground.
fn floating_tree(gravity: [f64; 3]) -> Model {
    let body = |name: &str, mass: f64, com: [f64; 3]| {
        BodySpec::new(
            name,
            Inertia::new(
                mass,
                com,
                [[0.03, 0.002, 0.0], [0.002, 0.02, 0.001], [0.0, 0.001, 0.04]],
            ),
        )
    };
    let turned = *nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.5).matrix();
    let rows = |m: Matrix3<f64>| {
        [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ]
    };
    let tilted = *nalgebra::Rotation3::from_euler_angles(-0.4, 0.7, 0.1).matrix();
    ModelBuilder::new()
        .gravity(gravity)
        .body(body("base", 3.0, [0.02, -0.01, 0.05]))
        .body(body("arm", 1.2, [0.1, 0.05, -0.02]))
        .body(body("slider", 0.5, [0.03, 0.0, 0.01]))
        .body(body("hand", 0.4, [0.0, 0.02, 0.04]))
        .joint(JointSpec::free_flyer("float", "base"))
        .joint(
            JointSpec::revolute("hinge", "base", "arm", [0.2, 1.0, -0.3])
                .placed([0.2, 0.0, 0.1], rows(turned)),
        )
        .joint(JointSpec::prismatic("slide", "arm", "slider", [1.0, 0.3, 0.0]).at([0.3, 0.0, 0.0]))
        .joint(JointSpec::fixed("wrist", "arm", "hand").placed([0.0, 0.35, 0.05], rows(tilted)))
        .frame(FrameSpec::new("imu", "base").placed([0.05, 0.02, -0.03], rz_rows(0.7)))
        .frame(FrameSpec::new("tip", "slider").at([0.1, -0.02, 0.03]))
        .frame(FrameSpec::new("tool", "hand").placed([0.02, 0.15, -0.01], rows(turned)))
        .frame(FrameSpec::new("marker", GROUND).placed([1.0, -2.0, 0.5], rz_rows(-1.1)))
        .build()
        .expect("valid tree")
}

fn tree_state() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let q = vec![
        0.1,
        -0.2,
        0.3,
        0.2,
        -0.1,
        0.3,
        0.9273618495495703,
        0.7,
        -0.2,
    ];
    let v = vec![0.5, -1.0, 0.2, 1.5, -0.3, 0.8, 2.0, -1.0];
    let a = vec![1.0, 0.3, -0.5, 0.2, 0.9, -1.1, 0.4, 2.0];
    (q, v, a)
}

/// `q ⊕ t v`: the configuration reached by moving with velocity v for time t.
fn moved(model: &Model, q: &[f64], v: &[f64], t: f64) -> Vec<f64> {
    let free_joints: Vec<(usize, usize)> = model
        .bodies()
        .iter()
        .filter(|b| b.joint.kind == JointKind::FreeFlyer)
        .map(|b| (b.joint.idx_q, b.joint.idx_v))
        .collect();
    let mut out = vec![0.0; q.len()];
    integrate_configuration(q, v, t, &free_joints, &mut out);
    out
}

/// v + t a.
fn advanced(v: &[f64], a: &[f64], t: f64) -> Vec<f64> {
    v.iter().zip(a).map(|(v, a)| v + t * a).collect()
}

/// Central-difference step, and the tolerance it allows (truncation ~ h², rounding ~ ε/h).
const H: f64 = 1e-5;
const FD_TOLERANCE: f64 = 1e-8;

#[test]
fn jacobians_are_derivatives_of_the_poses() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, _) = tree_state();
    let nv = model.nv();
    let mut jacobian = Matrix6xX::zeros(nv);
    let mut local = Matrix6xX::zeros(nv);
    for frame in 0..model.frames().len() {
        r.frame_jacobian(&q, frame, &mut jacobian)
            .expect("sizes match");
        r.frame_jacobian_local(&q, frame, &mut local)
            .expect("sizes match");
        let pose = r.frame_pose(&q, frame).expect("sizes match");
        for k in 0..nv {
            let mut unit = vec![0.0; nv];
            unit[k] = 1.0;
            let plus = r
                .frame_pose(&moved(&model, &q, &unit, H), frame)
                .expect("sizes match");
            let minus = r
                .frame_pose(&moved(&model, &q, &unit, -H), frame)
                .expect("sizes match");
            let linear = (plus.origin_in_world - minus.origin_in_world) / (2.0 * H);
            // Ṙ Rᵀ = ω̂.
            let omega_hat = (plus.rotation_in_world - minus.rotation_in_world)
                * pose.rotation_in_world.transpose()
                / (2.0 * H);
            let omega = Vector3::new(omega_hat[(2, 1)], omega_hat[(0, 2)], omega_hat[(1, 0)]);
            let by_differences = [linear.x, linear.y, linear.z, omega.x, omega.y, omega.z];
            let column: Vector6<f64> = jacobian.column(k).into_owned();
            assert_close(
                &format!("frame {frame} column {k}"),
                column.as_slice(),
                &by_differences,
                FD_TOLERANCE,
            );
            // LOCAL: the same in the frame's axes.
            let to_frame = pose.rotation_in_world.transpose();
            let local_linear = to_frame * Vector3::new(column[0], column[1], column[2]);
            let local_angular = to_frame * Vector3::new(column[3], column[4], column[5]);
            let local_column: Vector6<f64> = local.column(k).into_owned();
            assert_close(
                &format!("frame {frame} local column {k}"),
                local_column.as_slice(),
                &[
                    local_linear.x,
                    local_linear.y,
                    local_linear.z,
                    local_angular.x,
                    local_angular.y,
                    local_angular.z,
                ],
                1e-14,
            );
        }
        // And the velocity is J v.
        let velocity = r.frame_velocity(&q, &v, frame).expect("sizes match");
        let j_v = &jacobian * nalgebra::DVector::from_column_slice(&v);
        assert_close(
            &format!("frame {frame} velocity"),
            velocity.as_slice(),
            j_v.as_slice(),
            1e-14,
        );
    }
}

#[test]
fn classical_accelerations_are_derivatives_of_the_velocities() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let zero = vec![0.0; model.nv()];
    for frame in 0..model.frames().len() {
        // J̇ v: d/dt (J v) along q(t) = q ⊕ t v with v held.
        let plus = r
            .frame_velocity(&moved(&model, &q, &v, H), &v, frame)
            .expect("sizes match");
        let minus = r
            .frame_velocity(&moved(&model, &q, &v, -H), &v, frame)
            .expect("sizes match");
        let jdot_v = r
            .frame_classical_acceleration(&q, &v, &zero, frame)
            .expect("sizes match");
        assert_close(
            &format!("frame {frame} J̇ v"),
            jdot_v.as_slice(),
            ((plus - minus) / (2.0 * H)).as_slice(),
            FD_TOLERANCE,
        );
        // J̇ v + J a: along (q ⊕ t v, v + t a). Gravity has no part in it.
        let plus = r
            .frame_velocity(&moved(&model, &q, &v, H), &advanced(&v, &a, H), frame)
            .expect("sizes match");
        let minus = r
            .frame_velocity(&moved(&model, &q, &v, -H), &advanced(&v, &a, -H), frame)
            .expect("sizes match");
        let accel = r
            .frame_classical_acceleration(&q, &v, &a, frame)
            .expect("sizes match");
        assert_close(
            &format!("frame {frame} acceleration"),
            accel.as_slice(),
            ((plus - minus) / (2.0 * H)).as_slice(),
            FD_TOLERANCE,
        );
    }
}

#[test]
fn centroidal_momentum_rate_is_the_derivative_of_the_momentum() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let zero = vec![0.0; model.nv()];
    for (accel, what) in [(&zero, "Ȧ_G v"), (&a, "ḣ_G")] {
        let plus = r
            .centroidal_momentum(&moved(&model, &q, &v, H), &advanced(&v, accel, H))
            .expect("sizes match");
        let minus = r
            .centroidal_momentum(&moved(&model, &q, &v, -H), &advanced(&v, accel, -H))
            .expect("sizes match");
        let rate = r
            .centroidal_momentum_rate(&q, &v, accel)
            .expect("sizes match");
        assert_close(
            what,
            rate.as_slice(),
            ((plus - minus) / (2.0 * H)).as_slice(),
            FD_TOLERANCE,
        );
    }
    // The linear momentum is the total mass times the velocity of the mass centre.
    let h = r.centroidal_momentum(&q, &v).expect("sizes match");
    let com_velocity = (r
        .center_of_mass(&moved(&model, &q, &v, H))
        .expect("sizes match")
        - r.center_of_mass(&moved(&model, &q, &v, -H))
            .expect("sizes match"))
        / (2.0 * H);
    let mass: f64 = model.bodies().iter().map(|b| b.inertia.mass).sum();
    assert_close(
        "linear momentum",
        &h.as_slice()[..3],
        (com_velocity * mass).as_slice(),
        FD_TOLERANCE,
    );
}

#[test]
fn centroidal_momentum_rate_is_the_wrench_the_base_needs() {
    // Without gravity, the wrench the free joint would transmit to the base (Newton–Euler's
    // backward sweep) is the rate of the whole mechanism's momentum: moved to world axes
    // and about the mass centre G, M_G = R M_P + (P − G) × R F.
    let model = floating_tree([0.0; 3]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let mut reactions = vec![super::Wrench::zero(); model.bodies().len()];
    r.joint_reactions(&q, &v, &a, None, &mut reactions)
        .expect("sizes match");
    let base = r.body_poses(&q).expect("sizes match")[0];
    let com = r.center_of_mass(&q).expect("sizes match");
    let force = base.rotation_in_world * reactions[0].force;
    let moment =
        base.rotation_in_world * reactions[0].moment + (base.origin_in_world - com).cross(&force);
    let rate = r.centroidal_momentum_rate(&q, &v, &a).expect("sizes match");
    assert_close(
        "ḣ_G",
        rate.as_slice(),
        &[force.x, force.y, force.z, moment.x, moment.y, moment.z],
        1e-13,
    );
}

#[test]
fn a_frame_on_a_merged_body_is_the_composition_of_placements() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let tool = model.frame_index("tool").expect("declared");
    let hand = model.frame("hand").expect("a body's frame");
    let arm = model.body_index("arm").expect("a tree body");
    assert_eq!(
        (model.frames()[tool].body, hand.body),
        (Some(arm), Some(arm))
    );
    // The arm's pose, then the hand's placement in the arm, then the tool's in the hand.
    let turned = *nalgebra::Rotation3::from_euler_angles(0.3, -0.2, 0.5).matrix();
    let tool_in_hand = Placement {
        rotation: turned,
        translation: Vector3::new(0.02, 0.15, -0.01),
    };
    let arm_pose = r.body_poses(&q).expect("sizes match")[arm];
    let arm_in_world = Placement {
        rotation: arm_pose.rotation_in_world,
        translation: arm_pose.origin_in_world,
    };
    let composed = arm_in_world
        .compose(&hand.placement_in_body)
        .compose(&tool_in_hand);
    let pose = r.frame_pose(&q, tool).expect("sizes match");
    assert_close(
        "rotation",
        pose.rotation_in_world.as_slice(),
        composed.rotation.as_slice(),
        1e-15,
    );
    assert_close(
        "origin",
        pose.origin_in_world.as_slice(),
        composed.translation.as_slice(),
        1e-15,
    );
    // The same frame declared directly on the arm, at the composed placement, moves alike.
    let hand_and_tool = hand.placement_in_body.compose(&tool_in_hand);
    let rows = |m: &Matrix3<f64>| {
        [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ]
    };
    let direct_model = ModelBuilder::new()
        .gravity([0.0, 0.0, -9.81])
        .body(BodySpec::new("base", model.bodies()[0].inertia.clone()))
        .body(BodySpec::new("arm", model.bodies()[arm].inertia.clone()))
        .body(BodySpec::new("slider", model.bodies()[2].inertia.clone()))
        .joint(JointSpec::free_flyer("float", "base"))
        .joint({
            let joint = &model.bodies()[arm].joint;
            let p = &joint.placement_in_parent;
            let axis = match joint.kind {
                JointKind::Revolute { axis_in_joint } => axis_in_joint,
                ref other => panic!("{other:?}"),
            };
            JointSpec::revolute("hinge", "base", "arm", axis.into())
                .placed(p.translation.into(), rows(&p.rotation))
        })
        .joint({
            let joint = &model.bodies()[2].joint;
            let axis = match joint.kind {
                JointKind::Prismatic { axis_in_joint } => axis_in_joint,
                ref other => panic!("{other:?}"),
            };
            JointSpec::prismatic("slide", "arm", "slider", axis.into())
                .at(joint.placement_in_parent.translation.into())
        })
        .frame(FrameSpec::new("tool", "arm").placed(
            hand_and_tool.translation.into(),
            rows(&hand_and_tool.rotation),
        ))
        .build()
        .expect("valid tree");
    let direct = direct_model.frame_index("tool").expect("declared");
    let mut rd = Reference::<f64>::new(&direct_model);
    // (Equal to rounding only: the builder normalizes the copied unit axes again.)
    let direct_pose = rd.frame_pose(&q, direct).expect("sizes match");
    assert_close(
        "direct rotation",
        direct_pose.rotation_in_world.as_slice(),
        pose.rotation_in_world.as_slice(),
        1e-15,
    );
    assert_close(
        "direct origin",
        direct_pose.origin_in_world.as_slice(),
        pose.origin_in_world.as_slice(),
        1e-15,
    );
    let nv = model.nv();
    let (mut j, mut jd) = (Matrix6xX::zeros(nv), Matrix6xX::zeros(nv));
    r.frame_jacobian(&q, tool, &mut j).expect("sizes match");
    rd.frame_jacobian(&q, direct, &mut jd).expect("sizes match");
    assert_close("direct jacobian", jd.as_slice(), j.as_slice(), 1e-15);
    let accel = r
        .frame_classical_acceleration(&q, &v, &a, tool)
        .expect("sizes match");
    let direct_accel = rd
        .frame_classical_acceleration(&q, &v, &a, direct)
        .expect("sizes match");
    assert_close(
        "direct acceleration",
        direct_accel.as_slice(),
        accel.as_slice(),
        1e-14,
    );
}

#[test]
fn a_frame_on_the_ground_stays_still() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let marker = model.frame_index("marker").expect("declared");
    let pose = r.frame_pose(&q, marker).expect("sizes match");
    assert_eq!(pose.origin_in_world, Vector3::new(1.0, -2.0, 0.5));
    assert_eq!(
        pose.rotation_in_world,
        Placement::new([0.0; 3], rz_rows(-1.1)).rotation
    );
    let mut jacobian = Matrix6xX::from_element(model.nv(), 7.0);
    r.frame_jacobian(&q, marker, &mut jacobian)
        .expect("sizes match");
    assert_eq!(jacobian, Matrix6xX::zeros(model.nv()));
    r.frame_jacobian_local(&q, marker, &mut jacobian)
        .expect("sizes match");
    assert_eq!(jacobian, Matrix6xX::zeros(model.nv()));
    assert_eq!(
        r.frame_velocity(&q, &v, marker).expect("sizes match"),
        Vector6::zeros()
    );
    assert_eq!(
        r.frame_classical_acceleration(&q, &v, &a, marker)
            .expect("sizes match"),
        Vector6::zeros()
    );
}

#[test]
fn wrong_sizes_and_frames_are_errors() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let frames = model.frames().len();
    let no_such = FrameError::NoSuchFrame {
        index: frames,
        frames,
    };
    let size = |what, expected, got| {
        FrameError::Size(SizeError {
            what,
            expected,
            got,
        })
    };
    let mut jacobian = Matrix6xX::zeros(8);
    let mut narrow = Matrix6xX::zeros(7);
    assert_eq!(r.frame_pose(&q, frames), Err(no_such));
    assert_eq!(r.frame_pose(&q[1..], 0), Err(size("q", 9, 8)));
    assert_eq!(r.frame_jacobian(&q, frames, &mut jacobian), Err(no_such));
    assert_eq!(
        r.frame_jacobian(&q, 0, &mut narrow),
        Err(size("frame jacobian columns", 8, 7))
    );
    assert_eq!(
        r.frame_jacobian_local(&q, 0, &mut narrow),
        Err(size("frame jacobian columns", 8, 7))
    );
    assert_eq!(
        r.frame_jacobian_local(&q, frames, &mut jacobian),
        Err(no_such)
    );
    assert_eq!(r.frame_velocity(&q, &v[1..], 0), Err(size("v", 8, 7)));
    assert_eq!(r.frame_velocity(&q, &v, frames), Err(no_such));
    assert_eq!(
        r.frame_classical_acceleration(&q, &v, &a[1..], 0),
        Err(size("a", 8, 7))
    );
    assert_eq!(
        r.frame_classical_acceleration(&q, &v, &a, usize::MAX),
        Err(FrameError::NoSuchFrame {
            index: usize::MAX,
            frames
        })
    );
    assert_eq!(
        r.centroidal_momentum(&q, &v[1..]),
        Err(SizeError {
            what: "v",
            expected: 8,
            got: 7
        })
    );
    assert!(r.centroidal_momentum(&q[1..], &v).is_err());
    assert!(r.centroidal_momentum_rate(&q, &v, &a[1..]).is_err());
    assert_eq!(
        no_such.to_string(),
        format!("frame {frames} does not exist: the model has {frames} frames (indices 0..{frames} into Model::frames())")
    );
    assert_eq!(
        size("v", 8, 7).to_string(),
        "`v` has length 7 but the model needs 8"
    );
    // The right sizes work.
    assert!(r.frame_jacobian(&q, frames - 1, &mut jacobian).is_ok());
}

#[test]
fn a_massless_mechanism_has_centroidal_momentum() {
    // A spinning disc of inertia but no mass: no mass centre, h_G = [0; I ω].
    let model = ModelBuilder::new()
        .body(BodySpec::new(
            "disc",
            Inertia::new(
                0.0,
                [0.0; 3],
                [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.2]],
            ),
        ))
        .joint(JointSpec::revolute("spin", GROUND, "disc", [0.0, 0.0, 1.0]).at([1.0, 2.0, 0.0]))
        .build()
        .expect("valid");
    let mut r = Reference::<f64>::new(&model);
    let h = r.centroidal_momentum(&[0.3], &[2.0]).expect("sizes match");
    assert_eq!(h, Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.4));
    let h_dot = r
        .centroidal_momentum_rate(&[0.3], &[2.0], &[-1.0])
        .expect("sizes match");
    assert_eq!(h_dot, Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, -0.2));
}

#[test]
fn other_scalars_follow_double() {
    let model = floating_tree([0.0, 0.0, -9.81]);
    let (q, v, a) = tree_state();
    let tool = model.frame_index("tool").expect("declared");
    let mut r64 = Reference::<f64>::new(&model);
    let mut r32 = Reference::<f32>::new(&model);
    let mut rdd = Reference::<DoubleDouble>::new(&model);
    let to32 = |x: &[f64]| x.iter().map(|&y| y as f32).collect::<Vec<f32>>();
    let todd = |x: &[f64]| x.iter().map(|&y| DoubleDouble::from(y)).collect::<Vec<_>>();
    let expected = r64
        .frame_classical_acceleration(&q, &v, &a, tool)
        .expect("sizes match");
    let single = r32
        .frame_classical_acceleration(&to32(&q), &to32(&v), &to32(&a), tool)
        .expect("sizes match");
    let double_double = rdd
        .frame_classical_acceleration(&todd(&q), &todd(&v), &todd(&a), tool)
        .expect("sizes match");
    for k in 0..6 {
        assert!((f64::from(single[k]) - expected[k]).abs() < 1e-4 * (1.0 + expected[k].abs()));
        assert!(
            (double_double[k].to_f64() - expected[k]).abs() < 1e-14 * (1.0 + expected[k].abs())
        );
    }
    let mut jacobian = Matrix6xX::<f32>::zeros(model.nv());
    r32.frame_jacobian_local(&to32(&q), tool, &mut jacobian)
        .expect("sizes match");
    let h = rdd
        .centroidal_momentum_rate(&todd(&q), &todd(&v), &todd(&a))
        .expect("sizes match");
    let h64 = r64
        .centroidal_momentum_rate(&q, &v, &a)
        .expect("sizes match");
    for k in 0..6 {
        assert!((h[k].to_f64() - h64[k]).abs() < 1e-13 * (1.0 + h64[k].abs()));
    }
}

/// Row-major rows of a 6 × nv matrix.
fn rows_of(m: &Matrix6xX<f64>) -> Vec<Vec<f64>> {
    (0..6).map(|r| m.row(r).iter().copied().collect()).collect()
}

#[test]
fn pinocchio_agrees_on_the_floating_tree() {
    use super::pinocchio_frames as pin;
    let model = floating_tree([0.0, 0.0, -9.81]);
    let mut r = Reference::<f64>::new(&model);
    let (q, v, a) = tree_state();
    let zero = vec![0.0; model.nv()];
    let tool = model.frame_index("tool").expect("declared");
    let tip = model.frame_index("tip").expect("declared");
    let pose = r.frame_pose(&q, tool).expect("sizes match");
    let rotation_rows: Vec<f64> = pose.rotation_in_world.transpose().as_slice().to_vec();
    let tolerance = 1e-14;
    assert_close(
        "oMf rotation",
        &rotation_rows,
        pin::TOOL_ROTATION.as_flattened(),
        tolerance,
    );
    assert_close(
        "oMf translation",
        pose.origin_in_world.as_slice(),
        &pin::TOOL_ORIGIN,
        tolerance,
    );
    let mut jacobian = Matrix6xX::zeros(model.nv());
    for (frame, local, expected, what) in [
        (tool, false, &pin::TOOL_JACOBIAN, "tool J"),
        (tool, true, &pin::TOOL_JACOBIAN_LOCAL, "tool J local"),
        (tip, false, &pin::TIP_JACOBIAN, "tip J"),
    ] {
        if local {
            r.frame_jacobian_local(&q, frame, &mut jacobian)
        } else {
            r.frame_jacobian(&q, frame, &mut jacobian)
        }
        .expect("sizes match");
        for (row, expected_row) in rows_of(&jacobian).iter().zip(expected) {
            assert_close(what, row, expected_row, tolerance);
        }
    }
    let velocity = r.frame_velocity(&q, &v, tool).expect("sizes match");
    assert_close(
        "tool v",
        velocity.as_slice(),
        &pin::TOOL_VELOCITY,
        tolerance,
    );
    let accel = r
        .frame_classical_acceleration(&q, &v, &a, tool)
        .expect("sizes match");
    assert_close(
        "tool a",
        accel.as_slice(),
        &pin::TOOL_CLASSICAL_ACCELERATION,
        tolerance,
    );
    for (frame, expected, what) in [
        (tool, &pin::TOOL_JDOT_V, "tool J̇ v"),
        (tip, &pin::TIP_JDOT_V, "tip J̇ v"),
    ] {
        let jdot_v = r
            .frame_classical_acceleration(&q, &v, &zero, frame)
            .expect("sizes match");
        assert_close(what, jdot_v.as_slice(), expected, tolerance);
    }
    let h = r.centroidal_momentum(&q, &v).expect("sizes match");
    assert_close("hg", h.as_slice(), &pin::HG, tolerance);
    let h_dot = r.centroidal_momentum_rate(&q, &v, &a).expect("sizes match");
    assert_close("dhg", h_dot.as_slice(), &pin::DHG, tolerance);
    let dag_v = r
        .centroidal_momentum_rate(&q, &v, &zero)
        .expect("sizes match");
    assert_close("dAg v", dag_v.as_slice(), &pin::DAG_V, tolerance);
}
