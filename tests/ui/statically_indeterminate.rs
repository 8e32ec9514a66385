// A beam pinned at both ends: four reaction components for three balance equations.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct PinnedPinned;
    gravity: none;
    body beam { mass: 4.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    joint A: revolute(ground -> beam) { axis: z }
    constraint B: pin(ground at [1.0, 0.0, 0.0], beam at [1.0, 0.0, 0.0]);
}

fn main() {}
