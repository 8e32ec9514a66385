// Issue 21: a slider on a prismatic joint along y, and a roller whose normal is x. The counts
// and the body-by-body matching pass, but the joint already holds x (the roller's closure
// equation changes with no coordinate) and nothing holds y: the force analysis was singular
// at every configuration and returned infinities.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct SliderOnRoller;
    gravity: [0.0, -9.81, 0.0];
    outputs: [force_analysis];
    body slider { mass: 2.0, com: [0.0, 0.0, 0.0], shape: point }
    joint guide: prismatic(ground -> slider) { axis: y }
    constraint roller: roller(ground at [0.0, 0.0, 0.0], slider at [0.0, 0.0, 0.0]) { normal: x };
}

fn main() {}
