// A shape with a negative length.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: -0.6, axis: y) }
    joint pivot: revolute(ground -> rod) { axis: z }
}

fn main() {}
