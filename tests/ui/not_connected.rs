// A body that no joint attaches to anything.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body payload { mass: 0.5, shape: sphere(radius: 0.05) }
    joint shoulder: revolute(ground -> upper) { axis: z }
}

fn main() {}
