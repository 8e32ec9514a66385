// A misspelt item keyword (`jiont` for `joint`): named, with the keyword meant.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
    jiont pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
