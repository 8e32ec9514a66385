// Frames: on an unknown body (a typo), named after a body, declared twice, with a reflection,
// and a selection naming no frame, and one frame twice.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    frames: [tool, camera, tool];
    body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: rod(length: 0.4, axis: x) }
    body fore { mass: 0.5, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    joint shoulder: revolute(ground -> upper) { axis: z }
    joint elbow: revolute(upper -> fore) { axis: z, at: [0.4, 0.0, 0.0] }
    frame tool: on froe at [0.3, 0.0, 0.0];
    frame upper: on fore;
    frame tool: on fore at [0.3, 0.0, 0.0] rotation [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
}

fn main() {}
