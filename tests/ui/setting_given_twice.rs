// A mechanism setting given twice (here `gravity`): the second is an error that points at the first.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    gravity: [0.0, -9.81, 0.0];
    outputs: [inverse_dynamics];
    gravity: none;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
