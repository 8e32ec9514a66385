// A free joint whose parent is a body rather than the ground.
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Drone;
    body cart { mass: 1.0, shape: box(size: [0.2, 0.1, 0.1]) }
    body drone { mass: 0.5, shape: sphere(radius: 0.1) }
    joint rail: prismatic(ground -> cart) { axis: x }
    joint flight: free(cart -> drone);
}

fn main() {}
