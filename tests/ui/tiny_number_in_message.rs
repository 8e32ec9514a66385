// A number the user wrote is printed in its short form: `-1e-300`, not 300 digits.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: -1e-300, com: [0.0, -0.5, 0.0], shape: point }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
