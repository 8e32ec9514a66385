// Two bodies share a name.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body link { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body link { mass: 0.5, com: [0.0, -0.15, 0.0], shape: rod(length: 0.3, axis: y) }
    joint shoulder: revolute(ground -> link) { axis: z }
}

fn main() {}
