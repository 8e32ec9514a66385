// Joints that attach two bodies to each other and never reach the ground.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Loop;
    body a { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    body b { mass: 1.0, com: [0.0, -0.2, 0.0], shape: rod(length: 0.4, axis: y) }
    joint ab: revolute(a -> b) { axis: z, at: [0.0, -0.4, 0.0] }
    joint ba: revolute(b -> a) { axis: z, at: [0.0, -0.4, 0.0] }
}

fn main() {}
