// A load's components in axes the language does not know: `in` takes `world` or `body`.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
    load push: force on bob at [0.0, -0.5, 0.0] in wrold;
}

fn main() {}
