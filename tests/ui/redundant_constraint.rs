// The counts balance (6 unknowns, 6 equations) but not body by body: `a` is pinned to the
// ground twice (one reaction too many) while `b` hangs from `a` on a pin with no input.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Redundant;
    gravity: none;
    body a { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    body b { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    joint ground_pin: revolute(ground -> a) { axis: z }
    joint hinge: revolute(a -> b) { at: [1.0, 0.0, 0.0], axis: z }
    constraint second_pin: pin(ground at [1.0, 0.0, 0.0], a at [1.0, 0.0, 0.0]);
}

fn main() {}
