//! Anchor models: the mechanisms of the Pinocchio test vectors, declared in the language.
//!
//! Written by `models/tools/anchor_models.py` from `tests/data/pinocchio/*.json`; the
//! URDF twins in `models/urdf/` carry the same numbers.

use dynamics_runtime::mechanism;

mechanism! {
    /// The textbook's uniform rod (m = 2 kg, L = 0.6 m) pivoted at one end, gravity −y.
    ///
    /// Declared from the numbers of `tests/data/pinocchio/pendulum.json`.
    pub struct Pendulum;
    gravity: [0.0, -9.81, 0.0];

    body rod {
        mass: 2.0,
        com: [0.0, -0.3, 0.0],
        inertia: [[0.06, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.06]],
    }

    joint joint1: revolute(ground -> rod) {
        axis: z,
    }
}

mechanism! {
    /// Two uniform rods, 1.5 kg / 0.5 m and 1.0 kg / 0.4 m, gravity −y.
    ///
    /// Declared from the numbers of `tests/data/pinocchio/double_pendulum.json`.
    pub struct DoublePendulum;
    gravity: [0.0, -9.81, 0.0];

    body upper_rod {
        mass: 1.5,
        com: [0.0, -0.25, 0.0],
        inertia: [[0.03125, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.03125]],
    }

    body lower_rod {
        mass: 1.0,
        com: [0.0, -0.2, 0.0],
        inertia: [[0.013333333333333336, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.013333333333333336]],
    }

    joint joint1: revolute(ground -> upper_rod) {
        axis: z,
    }

    joint joint2: revolute(upper_rod -> lower_rod) {
        axis: z,
        at: [0.0, -0.5, 0.0],
    }
}

mechanism! {
    /// A planar three-link chain with offset mass centres and non-diagonal inertias.
    ///
    /// Declared from the numbers of `tests/data/pinocchio/planar3.json`.
    pub struct Planar3;
    gravity: [0.0, -9.81, 0.0];
    // The published inertias of this model violate I1 + I2 ≥ I3 (laminae with products of inertia).
    allow: [triangle_inequality];

    body link1 {
        mass: 3.0,
        com: [0.35, 0.02, 0.0],
        inertia: [[0.029999999999999985, 0.002, 0.0], [0.002, 0.12249999999999998, 0.001], [0.0, 0.001, 0.15249999999999997]],
    }

    body link2 {
        mass: 2.0,
        com: [0.25, 0.04, 0.0],
        inertia: [[0.020000000000000004, 0.002, 0.0], [0.002, 0.041666666666666664, 0.001], [0.0, 0.001, 0.06166666666666666]],
    }

    body link3 {
        mass: 1.0,
        com: [0.15, 0.06, 0.0],
        inertia: [[0.010000000000000002, 0.002, 0.0], [0.002, 0.0075, 0.001], [0.0, 0.001, 0.0175]],
    }

    joint joint1: revolute(ground -> link1) {
        axis: z,
    }

    joint joint2: revolute(link1 -> link2) {
        axis: z,
        at: [0.7, 0.0, 0.0],
    }

    joint joint3: revolute(link2 -> link3) {
        axis: z,
        at: [0.5, 0.0, 0.0],
    }
}

mechanism! {
    /// Universal Robots UR5 (parameters of example-robot-data's ur5_robot.urdf).
    ///
    /// Declared from the numbers of `tests/data/pinocchio/ur5.json`.
    pub struct Ur5;
    gravity: [0.0, 0.0, -9.81];
    // The default outputs, the mass matrix with its `_into` twin (the lanes benchmark's).
    outputs: [inverse_dynamics, gravity, bias, mass_matrix_into, coriolis_matrix, forward_dynamics,
              energy, joint_reactions];
    // The lanes benchmark's and tests' robot: its lanes run the unpacked bodies.
    lanes: true;

    body shoulder_link {
        mass: 3.7,
        com: [0.0, 0.0, 0.0],
        inertia: [[0.010267495893, 0.0, 0.0], [0.0, 0.010267495893, 0.0], [0.0, 0.0, 0.00666]],
    }

    body upper_arm_link {
        mass: 8.393,
        com: [0.0, 0.0, 0.28],
        inertia: [[0.22689067591, 0.0, 0.0], [0.0, 0.22689067591, 0.0], [0.0, 0.0, 0.0151074]],
    }

    body forearm_link {
        mass: 2.275,
        com: [0.0, 0.0, 0.24999999999999994],
        inertia: [[0.049443313556, 0.0, 0.0], [0.0, 0.049443313556, 0.0], [0.0, 0.0, 0.004095]],
    }

    body wrist_1_link {
        mass: 1.219,
        com: [0.0, 0.0, 0.0],
        inertia: [[0.111172755531, 0.0, 0.0], [0.0, 0.111172755531, 0.0], [0.0, 0.0, 0.21942]],
    }

    body wrist_2_link {
        mass: 1.219,
        com: [0.0, 0.0, 0.0],
        inertia: [[0.111172755531, 0.0, 0.0], [0.0, 0.111172755531, 0.0], [0.0, 0.0, 0.21942]],
    }

    body wrist_3_link {
        mass: 0.1879,
        com: [0.0, 0.0, 0.0],
        inertia: [[0.0171364731454, 0.0, 0.0], [0.0, 0.0171364731454, 0.0], [0.0, 0.0, 0.033822]],
    }

    joint shoulder_pan_joint: revolute(ground -> shoulder_link) {
        axis: z,
        at: [0.0, 0.0, 0.089159],
    }

    joint shoulder_lift_joint: revolute(shoulder_link -> upper_arm_link) {
        axis: y,
        at: [0.0, 0.13585, 0.0],
        rotation: [[4.896638650109253e-12, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 4.896638650109253e-12]],
    }

    joint elbow_joint: revolute(upper_arm_link -> forearm_link) {
        axis: y,
        at: [0.0, -0.1197, 0.425],
    }

    joint wrist_1_joint: revolute(forearm_link -> wrist_1_link) {
        axis: y,
        at: [0.0, 0.0, 0.39225],
        rotation: [[4.896638650109253e-12, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 4.896638650109253e-12]],
    }

    joint wrist_2_joint: revolute(wrist_1_link -> wrist_2_link) {
        axis: z,
        at: [0.0, 0.093, 0.0],
    }

    joint wrist_3_joint: revolute(wrist_2_link -> wrist_3_link) {
        axis: y,
        at: [0.0, 0.0, 0.09465],
    }
}

mechanism! {
    /// Franka Emika Panda arm, fingers fixed (parameters of example-robot-data's panda.urdf).
    ///
    /// Declared from the numbers of `tests/data/pinocchio/panda.json`.
    pub struct Panda;
    gravity: [0.0, 0.0, -9.81];

    body panda_link1 {
        mass: 4.970684,
        com: [0.003875, 0.002081, -0.04762],
        inertia: [[0.70337, -0.000139, 0.006772], [-0.000139, 0.70661, 0.019169], [0.006772, 0.019169, 0.009117]],
    }

    body panda_link2 {
        mass: 0.646926,
        com: [-0.003141, -0.02872, 0.003495],
        inertia: [[0.007962, -0.003925, 0.010254], [-0.003925, 0.02811, 0.000704], [0.010254, 0.000704, 0.025995]],
    }

    body panda_link3 {
        mass: 3.228604,
        com: [0.027518, 0.039252, -0.066502],
        inertia: [[0.037242, -0.004761, -0.011396], [-0.004761, 0.036155, -0.012805], [-0.011396, -0.012805, 0.01083]],
    }

    body panda_link4 {
        mass: 3.587895,
        com: [-0.05316999999999999, 0.10441899999999997, 0.027453999999999992],
        inertia: [[0.025853, 0.007796, -0.001332], [0.007796, 0.019552, 0.008641], [-0.001332, 0.008641, 0.028323]],
    }

    body panda_link5 {
        mass: 1.225946,
        com: [-0.011953, 0.041065, -0.038437],
        inertia: [[0.035549, -0.002117, -0.004037], [-0.002117, 0.029474, 0.000229], [-0.004037, 0.000229, 0.008627]],
    }

    body panda_link6 {
        mass: 1.666555,
        com: [0.060149, -0.014117, -0.010517],
        inertia: [[0.0019640000000000005, 0.000109, -0.001158], [0.000109, 0.004354, 0.000341], [-0.001158, 0.000341, 0.005433]],
    }

    body panda_link7 {
        mass: 1.4955219999999998,
        com: [0.0017208742976286572, 0.0013603544171612294, 0.10048528114865576],
        inertia: [[0.016529853712634626, 0.0003948922971191777, -0.0007066957106145017], [0.0003948922971191777, 0.014107248642161839, -0.001051105327046708], [-0.0007066957106145017, -0.001051105327046708, 0.006676955556640956]],
    }

    joint panda_joint1: revolute(ground -> panda_link1) {
        axis: z,
        at: [0.0, 0.0, 0.333],
    }

    joint panda_joint2: revolute(panda_link1 -> panda_link2) {
        axis: z,
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, 1.0], [0.0, -1.0, 2.220446049250313e-16]],
    }

    joint panda_joint3: revolute(panda_link2 -> panda_link3) {
        axis: z,
        at: [0.0, -0.316, 0.0],
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, -1.0], [0.0, 1.0, 2.220446049250313e-16]],
    }

    joint panda_joint4: revolute(panda_link3 -> panda_link4) {
        axis: z,
        at: [0.0825, 0.0, 0.0],
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, -1.0], [0.0, 1.0, 2.220446049250313e-16]],
    }

    joint panda_joint5: revolute(panda_link4 -> panda_link5) {
        axis: z,
        at: [-0.0825, 0.384, 0.0],
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, 1.0], [0.0, -1.0, 2.220446049250313e-16]],
    }

    joint panda_joint6: revolute(panda_link5 -> panda_link6) {
        axis: z,
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, -1.0], [0.0, 1.0, 2.220446049250313e-16]],
    }

    joint panda_joint7: revolute(panda_link6 -> panda_link7) {
        axis: z,
        at: [0.088, 0.0, 0.0],
        rotation: [[1.0, 0.0, 0.0], [0.0, 2.220446049250313e-16, -1.0], [0.0, 1.0, 2.220446049250313e-16]],
    }
}
