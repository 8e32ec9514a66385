// A Denavit–Hartenberg placement with `at` and `axis` on the same joint: the row places the
// joint frame and fixes the axis (z), so each is an error at its tokens.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [-0.2, 0.0, 0.0], shape: point }
    body lower { mass: 0.5, com: [-0.2, 0.0, 0.0], shape: point }
    joint shoulder: revolute(ground -> upper) { placement: dh(a: 0.4, alpha: pi / 2) }
    joint elbow: revolute(upper -> lower) {
        axis: y,
        at: [0.0, 0.0, 0.1],
        placement: dh(a: 0.4, d: 0.1),
    }
}

fn main() {}
