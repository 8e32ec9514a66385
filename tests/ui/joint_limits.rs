// Limits belong to revolute and prismatic joints, lower ≤ upper, velocity and effort ≥ 0.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: point }
    body tool { mass: 0.2, shape: point }
    joint shoulder: revolute(ground -> upper) {
        axis: z,
        limits: { lower: 1.5, upper: -1.5, effort: -10.0 },
    }
    joint weld: fixed(upper -> tool) { at: [0.4, 0.0, 0.0], limits: { velocity: 1.0 } }
}

fn main() {}
