// `urdf_damping` (as `floating_base`) applies to a URDF file; this mechanism imports none.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    urdf_damping: false;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
    joint pivot: revolute(ground -> bob) { axis: z, damping: 0.1 }
}

fn main() {}
