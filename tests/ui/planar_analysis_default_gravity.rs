// A planar force analysis with no `gravity:`: the default (0, 0, -9.81) leaves the plane.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct SupportedBeam;
    body beam { mass: 4.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    joint A: revolute(ground -> beam) { axis: z }
    constraint B: roller(ground at [1.0, 0.0, 0.0], beam at [1.0, 0.0, 0.0]) { normal: y };
}

fn main() {}
