// A massless body on a free joint carrying one body on a revolute joint: each of the 7
// coordinates moves the arm, but the arm alone has 6 inertial degrees of freedom (turning the
// base and the hinge oppositely moves nothing), so M(q) is singular at every configuration.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct FloatingArm;
    body base { mass: 0.0, shape: point }
    body arm { mass: 1.0, com: [0.5, 0.0, 0.0], shape: box(size: [1.0, 0.1, 0.1]) }
    joint float: free(ground -> base);
    joint hinge: revolute(base -> arm) { axis: z, at: [0.1, 0.2, 0.0] }
}

fn main() {}
