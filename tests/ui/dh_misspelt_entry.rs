// A misspelt entry of a Denavit–Hartenberg row names the entry meant.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [-0.2, 0.0, 0.0], shape: point }
    joint shoulder: revolute(ground -> upper) { placement: dh(a: 0.4, alhpa: pi / 2, d: 0.1) }
}

fn main() {}
