//! An 18-degree-of-freedom quadruped: a free-floating torso and four three-joint legs
//! (hip abduction about x, hip flexion and knee about y), with a contact force on each foot.
//!
//! Parameters of a Mini-Cheetah-class robot as tabulated in `dog_control/config/model.lua`
//! of github.com/sqrt81/src_dog (torso 3.575 kg, hip 0.650 kg, thigh 0.863 kg, shin
//! 0.119 kg, 0.2 m thigh and shin); the legs are mirror images of the front-left one, by the
//! signs of their hip positions.

use dynamics_runtime::mechanism;

mechanism! {
    /// A Mini-Cheetah-class quadruped on a free-floating torso, gravity −z. The loads are
    /// the ground contact forces on the feet, in each shin's frame.
    pub struct Quadruped;
    gravity: [0.0, 0.0, -9.81];
    // The default outputs, the mass matrix with its `_into` twin (the lanes benchmark's).
    outputs: [inverse_dynamics, gravity, bias, mass_matrix_into, coriolis_matrix, forward_dynamics,
              energy, joint_reactions];
    // The lanes benchmark's and tests' robot: its lanes run the unpacked bodies.
    lanes: true;

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
    /// Ground contact force on the foot.
    load foot_fl: force on shin_fl at [0.0, 0.0, -0.2];

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
    /// Ground contact force on the foot.
    load foot_fr: force on shin_fr at [0.0, 0.0, -0.2];

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
    /// Ground contact force on the foot.
    load foot_hl: force on shin_hl at [0.0, 0.0, -0.2];

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
    /// Ground contact force on the foot.
    load foot_hr: force on shin_hr at [0.0, 0.0, -0.2];
}
