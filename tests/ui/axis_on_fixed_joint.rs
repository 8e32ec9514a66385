// An axis on a fixed joint, which has no motion.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
    body lamp { mass: 0.1, shape: point }
    joint pivot: revolute(ground -> bob) { axis: z }
    joint mount: fixed(bob -> lamp) { axis: z, at: [0.0, -0.5, 0.0] }
}

fn main() {}
