// A URDF mimic joint, a coupled coordinate, which is not supported (fixture urdf/mimic_joint.urdf).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Gripper;
    urdf: "urdf/mimic_joint.urdf";
}

fn main() {}
