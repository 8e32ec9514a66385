// A load on a body welded to the ground: it does no work.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body stand { mass: 5.0, shape: box(size: [0.2, 0.2, 1.0]) }
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    joint weld: fixed(ground -> stand);
    joint pivot: revolute(stand -> bob) { axis: z, at: [0.0, 0.0, 0.5] }
    load push: force on stand at [0.0, 0.0, 0.5];
}

fn main() {}
