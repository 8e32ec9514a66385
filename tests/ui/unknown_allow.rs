// A check in `allow` that does not exist or cannot be waived.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    allow: [triangle_inequallity];
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
