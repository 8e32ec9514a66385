// A body is the child of two joints: a closed loop, which a tree cannot express.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct FourBar;
    body crank { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    body coupler { mass: 1.0, com: [0.2, 0.0, 0.0], shape: rod(length: 0.4, axis: x) }
    joint a: revolute(ground -> crank) { axis: z }
    joint b: revolute(ground -> rocker) { axis: z, at: [0.5, 0.0, 0.0] }
    joint c: revolute(crank -> coupler) { axis: z, at: [0.2, 0.0, 0.0] }
    joint d: revolute(rocker -> coupler) { axis: z, at: [0.3, 0.0, 0.0] }
}

fn main() {}
