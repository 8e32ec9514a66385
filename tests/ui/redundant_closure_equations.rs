// Two constraints close the four-bar's loop at one point: the pin holds x and y, the roller x
// again. The counts and the matching pass (no joint is driven), but the closure equations
// `B.x` and `C.normal` are one equation twice: Φ_q has rank 2 for 3 rows everywhere.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct TwiceClosed;
    gravity: [0.0, -9.81, 0.0];
    body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    joint O2: revolute(ground -> crank) { axis: z }
    joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
    joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z }
    constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
    constraint C: roller(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]) { normal: x };
}

fn main() {}
