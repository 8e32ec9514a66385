// A body without an inertia (or shape).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0] }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
