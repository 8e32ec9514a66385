// Several different mistakes in one declaration: every one is reported, not only the first.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    outputs: [inverse_dynamics, mass_matirx];
    body upper { mass: -1.0, com: [0.0, -0.2, 0.0], inertia: diag([0.1, 0.1, 0.3]) }
    body lower { mass: payload, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: [0.0, 0.0, 0.0] }
    joint elbow: revolute(uper -> lower) { axis: z, at: [0.0, -0.4, 0.0] }
}

fn main() {}
