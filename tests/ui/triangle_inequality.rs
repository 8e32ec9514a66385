// Principal moments with I1 + I2 < I3: no mass distribution has them.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.1, 0.1, 0.3]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
