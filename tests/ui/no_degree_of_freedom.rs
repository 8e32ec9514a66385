// Every joint is fixed, yet dynamics are asked for.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Statue;
    body plinth { mass: 10.0, shape: box(size: [0.5, 0.5, 0.2]) }
    joint weld: fixed(ground -> plinth);
}

fn main() {}
