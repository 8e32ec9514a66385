//! The kinematics of the three robots of the Pinocchio comparison (UR5, Panda, the
//! 18-degree-of-freedom quadruped), declared apart from their dynamics so that asking for
//! the kinematics outputs leaves the code generated for [`crate::anchors::Ur5`],
//! [`crate::anchors::Panda`] and [`crate::quadruped::Quadruped`] unchanged.
//!
//! Each mechanism is the same robot as its dynamics twin: the arms are imported from the
//! URDF twins of `models/urdf/` (the numbers of [`crate::anchors`], and of
//! [`crate::urdf_anchors`]), the quadruped is [`crate::quadruped::Quadruped`]'s declaration
//! again without its foot loads (the kinematics take none). The tests below check that each
//! builds the same runtime model as its twin. Gravity is declared as there, although no
//! kinematics output reads it.
//!
//! `benches/dynamics.rs` times every output of these (`<Name>/<output>/generated`), and
//! `benches/pinocchio/compare.sh` sets them beside Pinocchio's `forwardKinematics`,
//! `computeJointJacobians`, `computeJointJacobiansTimeVariation`, `centerOfMass`,
//! `jacobianCenterOfMass` and `ccrba`.
//!
//! They also generate the derivatives of the dynamics and M⁻¹, timed against Pinocchio's
//! computeRNEADerivatives, computeABADerivatives and computeMinverse; the quadruped's
//! derivatives are taken without its foot loads, as Pinocchio gets none.
//!
//! The frames are those Pinocchio's timing program gets from `benches/pinocchio/frames.json`:
//! the URDF links hung on fixed joints (the UR5's `ee_link` and `tool0` and its root links,
//! the Panda's flange, hand and fingers), and the quadruped's four feet.

use dynamics_runtime::mechanism;

mechanism! {
    /// [`crate::anchors::Ur5`]'s kinematics, from `urdf/ur5.urdf`.
    pub struct Ur5Kinematics;
    urdf: "urdf/ur5.urdf";
    gravity: [0.0, 0.0, -9.81];
    outputs: [joint_placements, joint_jacobians, joint_velocities, joint_acceleration_biases,
              joint_jacobians_world, joint_jacobians_world_time_variation, forward_kinematics,
              center_of_mass, center_of_mass_jacobian, centroidal_momentum_matrix,
              frame_placements, frame_jacobians, frame_acceleration_biases, centroidal_bias,
              inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
    frame world: on ground;
    frame base_link: on ground;
    frame ee_link: on wrist_3_link at [0.0, 0.0823, 0.0] rotation rpy(0.0, 0.0, pi / 2.0);
    frame tool0: on wrist_3_link at [0.0, 0.0823, 0.0] rotation rpy(-pi / 2.0, 0.0, 0.0);
}

mechanism! {
    /// [`crate::anchors::Panda`]'s kinematics, from `urdf/panda.urdf`.
    pub struct PandaKinematics;
    urdf: "urdf/panda.urdf";
    gravity: [0.0, 0.0, -9.81];
    outputs: [joint_placements, joint_jacobians, joint_velocities, joint_acceleration_biases,
              joint_jacobians_world, joint_jacobians_world_time_variation, forward_kinematics,
              center_of_mass, center_of_mass_jacobian, centroidal_momentum_matrix,
              frame_placements, frame_jacobians, frame_acceleration_biases, centroidal_bias,
              inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
    frame panda_link8: on panda_link7 at [0.0, 0.0, 0.107];
    frame panda_hand: on panda_link7 at [0.0, 0.0, 0.107] rotation rpy(0.0, 0.0, -pi / 4.0);
    frame panda_leftfinger: on panda_link7 at [0.0, 0.0, 0.1654] rotation rpy(0.0, 0.0, -pi / 4.0);
    frame panda_rightfinger: on panda_link7 at [0.0, 0.0, 0.1654] rotation rpy(0.0, 0.0, -pi / 4.0);
}

mechanism! {
    /// [`crate::quadruped::Quadruped`]'s kinematics: its declaration again, without the
    /// foot loads.
    pub struct QuadrupedKinematics;
    gravity: [0.0, 0.0, -9.81];
    outputs: [joint_placements, joint_jacobians, joint_velocities, joint_acceleration_biases,
              joint_jacobians_world, joint_jacobians_world_time_variation, forward_kinematics,
              center_of_mass, center_of_mass_jacobian, centroidal_momentum_matrix,
              frame_placements, frame_jacobians, frame_acceleration_biases, centroidal_bias,
              inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];

    /// The torso, its frame at the mass centre along its principal axes.
    body torso { mass: 3.575, inertia: diag([0.017528444, 0.129944698, 0.143418825]) }
    /// Floating base: position and orientation of the torso in the world.
    joint base: free(ground -> torso);

    body hip_fl { mass: 0.65, com: [0.05016, -0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_fl {
        mass: 0.863,
        com: [0.0, 0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, -0.000261229], [0.0, -0.000261229, 617.145e-6]],
    }
    body shin_fl { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_fl: revolute(torso -> hip_fl) { axis: x, at: [0.23, 0.0805, 0.0] }
    joint hip_fl: revolute(hip_fl -> thigh_fl) { axis: y, at: [0.053, 0.0575, 0.0] }
    joint knee_fl: revolute(thigh_fl -> shin_fl) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_fr { mass: 0.65, com: [0.05016, 0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_fr {
        mass: 0.863,
        com: [0.0, -0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, 0.000261229], [0.0, 0.000261229, 617.145e-6]],
    }
    body shin_fr { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_fr: revolute(torso -> hip_fr) { axis: x, at: [0.23, -0.0805, 0.0] }
    joint hip_fr: revolute(hip_fr -> thigh_fr) { axis: y, at: [0.053, -0.0575, 0.0] }
    joint knee_fr: revolute(thigh_fr -> shin_fr) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_hl { mass: 0.65, com: [-0.05016, -0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_hl {
        mass: 0.863,
        com: [0.0, 0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, -0.000261229], [0.0, -0.000261229, 617.145e-6]],
    }
    body shin_hl { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_hl: revolute(torso -> hip_hl) { axis: x, at: [-0.23, 0.0805, 0.0] }
    joint hip_hl: revolute(hip_hl -> thigh_hl) { axis: y, at: [-0.053, 0.0575, 0.0] }
    joint knee_hl: revolute(thigh_hl -> shin_hl) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_hr { mass: 0.65, com: [-0.05016, 0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_hr {
        mass: 0.863,
        com: [0.0, -0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, 0.000261229], [0.0, 0.000261229, 617.145e-6]],
    }
    body shin_hr { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_hr: revolute(torso -> hip_hr) { axis: x, at: [-0.23, -0.0805, 0.0] }
    joint hip_hr: revolute(hip_hr -> thigh_hr) { axis: y, at: [-0.053, -0.0575, 0.0] }
    joint knee_hr: revolute(thigh_hr -> shin_hr) { axis: y, at: [0.0, 0.0, -0.2] }

    /// The feet, where the foot loads of the dynamics twin act.
    frame foot_fl: on shin_fl at [0.0, 0.0, -0.2];
    frame foot_fr: on shin_fr at [0.0, 0.0, -0.2];
    frame foot_hl: on shin_hl at [0.0, 0.0, -0.2];
    frame foot_hr: on shin_hr at [0.0, 0.0, -0.2];
}

#[cfg(test)]
mod tests {
    use super::{PandaKinematics, QuadrupedKinematics, Ur5Kinematics};
    use crate::anchors::{Panda, Ur5};
    use crate::quadruped::Quadruped;
    use dynamics_runtime::{Mechanism, Model};

    /// The two models have the same tree, joints, placements and inertias, to `tolerance`
    /// (the URDF twins write rotations as rpy angles, the declarations as matrices).
    fn assert_same_robot(a: &Model, b: &Model, tolerance: f64) {
        let close = |x: f64, y: f64, what: &str| {
            assert!((x - y).abs() <= tolerance, "{what}: {x} against {y}");
        };
        assert_eq!(a.nq(), b.nq());
        assert_eq!(a.nv(), b.nv());
        assert_eq!(a.bodies().len(), b.bodies().len());
        for (x, y) in a.gravity_in_world().iter().zip(b.gravity_in_world().iter()) {
            close(*x, *y, "gravity");
        }
        for (p, q) in a.bodies().iter().zip(b.bodies()) {
            let name = &p.name;
            assert_eq!(p.name, q.name);
            assert_eq!(p.parent, q.parent, "{name}");
            assert_eq!(p.joint.name, q.joint.name, "{name}");
            assert_eq!(p.joint.kind, q.joint.kind, "{name}");
            assert_eq!(
                (p.joint.idx_q, p.joint.idx_v),
                (q.joint.idx_q, q.joint.idx_v)
            );
            let (s, t) = (&p.joint.placement_in_parent, &q.joint.placement_in_parent);
            for (x, y) in s.translation.iter().zip(t.translation.iter()) {
                close(*x, *y, &format!("{name} joint translation"));
            }
            for (x, y) in s.rotation.iter().zip(t.rotation.iter()) {
                close(*x, *y, &format!("{name} joint rotation"));
            }
            let (s, t) = (&p.inertia, &q.inertia);
            close(s.mass, t.mass, &format!("{name} mass"));
            for (x, y) in s.com_in_body.iter().zip(t.com_in_body.iter()) {
                close(*x, *y, &format!("{name} mass centre"));
            }
            for (x, y) in s
                .inertia_com_in_body
                .iter()
                .zip(t.inertia_com_in_body.iter())
            {
                close(*x, *y, &format!("{name} inertia"));
            }
        }
    }

    #[test]
    fn the_kinematics_mechanisms_are_the_dynamics_robots() {
        assert_same_robot(&Ur5Kinematics::model(), &Ur5::model(), 1e-12);
        assert_same_robot(&PandaKinematics::model(), &Panda::model(), 1e-12);
        assert_same_robot(&QuadrupedKinematics::model(), &Quadruped::model(), 0.0);
    }
}
