// `urdf_damping` takes `true` or `false` (here a word that is neither); the declaration is
// refused before the file is read.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Arm;
    urdf: "urdf/robot.urdf";
    urdf_damping: maybe;
}

fn main() {}
