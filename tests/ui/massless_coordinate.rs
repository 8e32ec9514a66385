// A joint that moves only a body with zero mass and zero inertia: M(q) is singular.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body frame { mass: 0.0, shape: point }
    joint pivot: revolute(ground -> frame) { axis: z }
}

fn main() {}
