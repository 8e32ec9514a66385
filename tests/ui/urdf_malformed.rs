// A URDF file that is not well-formed XML (fixture urdf/malformed.urdf, placed by tests/ui.rs).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Robot;
    urdf: "urdf/malformed.urdf";
}

fn main() {}
