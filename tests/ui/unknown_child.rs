// A joint's child is not a declared body.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z }
    joint elbow: revolute(upper -> forearm) { axis: z, at: [0.0, -0.4, 0.0] }
}

fn main() {}
