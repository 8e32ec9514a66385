// A URDF file that does not exist (an absolute path: the message repeats it).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Robot;
    urdf: "/nonexistent/dynamics-tests/robot.urdf";
}

fn main() {}
