// A URDF `floating` joint: refused inside the tree; the error says how to float the root
// link instead (fixture urdf/floating_joint.urdf).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Drone;
    urdf: "urdf/floating_joint.urdf";
}

fn main() {}
