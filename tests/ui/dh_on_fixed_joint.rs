// A Denavit–Hartenberg placement on a fixed joint, which has no axis to place.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [-0.2, 0.0, 0.0], shape: point }
    body tool { mass: 0.1, shape: point }
    joint shoulder: revolute(ground -> upper) { placement: dh(a: 0.4, alpha: pi / 2) }
    joint mount: fixed(upper -> tool) { placement: mdh(a: 0.1, alpha: -pi / 2) }
}

fn main() {}
