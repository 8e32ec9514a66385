// Products of inertia so large that a principal moment is negative.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob {
        mass: 1.0,
        com: [0.0, -0.5, 0.0],
        inertia: [[0.1, 0.2, 0.0], [0.2, 0.1, 0.0], [0.0, 0.0, 0.1]],
    }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
