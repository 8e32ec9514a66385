// A parameter in a rotation, which must be a constant.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    parameters: [tilt = 0.1];
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z, rotation: rpy(0.0, 0.0, tilt) }
}

fn main() {}
