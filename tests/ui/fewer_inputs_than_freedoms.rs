// A four-bar with no driven joint: its one degree of freedom moves with no input.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Undriven;
    gravity: none;
    body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    joint O2: revolute(ground -> crank) { axis: z }
    joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
    joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z }
    constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
}

fn main() {}
