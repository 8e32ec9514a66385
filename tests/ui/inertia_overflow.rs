// A huge mass far from the axis: its moment of inertia, m |c|², overflows f64 (it was
// reported as a moment of inertia of 0).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Heavy;
    body arm { mass: 1e300, com: [1e5, 0.0, 0.0], shape: point }
    joint spin: revolute(ground -> arm) { axis: z }
}

fn main() {}
