// A literal with a type suffix: `300u8` was read as 300 kg, `1.1f32` as the f64 1.1. A
// mechanism's numbers have no Rust type (the generated code converts each to its scalar).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: 300u8, com: [0.0, -0.5, 0.0], shape: point }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
