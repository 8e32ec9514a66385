// A roller props the second link of a driven arm at its hinge. The closure is regular (the
// prop holds the arm's tip), but no unknown takes a moment on `flap`, which turns freely:
// A(q) is singular at every configuration although counts and matching pass.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct PropAtHinge;
    gravity: [0.0, -9.81, 0.0];
    body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    body flap { mass: 0.5, com: [0.25, 0.0, 0.0], shape: rod(length: 0.5, axis: x) }
    joint shoulder: revolute(ground -> arm) { axis: z, driven: true }
    joint hinge: revolute(arm -> flap) { axis: z, at: [1.0, 0.0, 0.0] }
    constraint prop: roller(ground at [1.0, 0.0, 0.0], flap at [0.0, 0.0, 0.0]) { normal: y };
}

fn main() {}
