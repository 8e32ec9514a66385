// A load's axes given twice.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
    load push: force on bob in world at [0.0, -0.5, 0.0] in world;
}

fn main() {}
