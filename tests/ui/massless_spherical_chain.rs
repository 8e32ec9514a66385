// Three revolute joints with intersecting axes on massless links, ending at a point mass off
// their common point: each joint moves the mass, but the mass moves on a sphere (2 degrees of
// freedom for 3 coordinates), so M(q) is singular at every configuration.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct SphericalBob;
    body yaw_link { mass: 0.0, shape: point }
    body pitch_link { mass: 0.0, shape: point }
    body bob { mass: 1.0, com: [0.0, 0.0, -1.0], shape: point }
    joint yaw: revolute(ground -> yaw_link) { axis: z }
    joint pitch: revolute(yaw_link -> pitch_link) { axis: x }
    joint roll: revolute(pitch_link -> bob) { axis: y }
}

fn main() {}
