// A point mass on its own revolute axis: turning it moves nothing, M(q) is singular.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Bead;
    body bead { mass: 1.0, com: [0.0, 0.0, 0.5], shape: point }
    joint spin: revolute(ground -> bead) { axis: z }
}

fn main() {}
