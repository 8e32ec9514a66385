// A joint's parent is neither a declared body nor `ground` (a typo).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body lower { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> upper) { axis: z }
    joint elbow: revolute(uper -> lower) { axis: z, at: [0.0, -0.4, 0.0] }
}

fn main() {}
