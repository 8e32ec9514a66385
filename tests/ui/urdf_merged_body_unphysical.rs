// The inertia rules judge a URDF link welded through a fixed joint merged with the body it is
// welded to: the placeholder `base` is accepted, but the merged body still violates the
// triangle inequality (fixture urdf/unphysical_merged.urdf).
use dynamics_runtime::mechanism;

mechanism! {
    pub struct Unphysical;
    urdf: "urdf/unphysical_merged.urdf";
    floating_base: true;
}

fn main() {}
