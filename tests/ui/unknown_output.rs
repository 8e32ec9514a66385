// An output the generator does not know (a typo).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    outputs: [inverse_dynamics, mass_matirx];
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
