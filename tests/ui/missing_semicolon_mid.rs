// A frame's `;` is missing before the next item: the error points at the frame's end.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    frame tip: on bob at [0.0, -0.5, 0.0]
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
