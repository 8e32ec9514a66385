// A misspelt item keyword (`bodi` for `body`): named, with the keyword meant.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    bodi bob { mass: 1.0, com: [0.0, -0.5, 0.0], shape: point }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
