// A declared parameter that no number uses (almost always a typo).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    parameters: [payload = 0.5];
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
