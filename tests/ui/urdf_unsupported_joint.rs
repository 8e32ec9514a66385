// A URDF planar joint, which the tree expansion does not support (fixture urdf/planar_joint.urdf).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Robot;
    urdf: "urdf/planar_joint.urdf";
    gravity: [0.0, 0.0, -9.81];
}

fn main() {}
