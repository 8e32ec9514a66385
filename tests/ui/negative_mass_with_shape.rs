// A negative mass with a shape: the shape's inertia scales with the mass and so is
// negative too, but only the mass, the cause, is reported.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Pendulum;
    body bob { mass: -1.0, com: [0.0, -0.5, 0.0], shape: rod(length: 1.0, axis: y) }
    joint pivot: revolute(ground -> bob) { axis: z }
}

fn main() {}
