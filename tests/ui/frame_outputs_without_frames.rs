// A frame output asked for where no frame is declared or welded.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    outputs: [inverse_dynamics, frame_jacobians];
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
