// Issue 21: a roller placed on the pin it should brace. Three unknowns, three equations, but
// the roller's reaction acts along the pin's x through the pivot: no unknown takes a moment
// about it. `force_analysis` returned [inf, 19.62, inf].
use dynamics_runtime::mechanism;

mechanism! {
    pub struct PropOnPivot;
    gravity: [0.0, -9.81, 0.0];
    outputs: [force_analysis];
    body beam { mass: 2.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
    joint A: revolute(ground -> beam) { axis: z }
    constraint B: roller(ground at [0.0, 0.0, 0.0], beam at [0.0, 0.0, 0.0]) { normal: x };
}

fn main() {}
