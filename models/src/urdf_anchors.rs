//! The anchor models again, imported at compile time from the URDF twins in `models/urdf/`
//! (same numbers as [`crate::anchors`]), so the two front ends can be checked against each
//! other and against Pinocchio.

use dynamics_runtime::mechanism;

mechanism! {
    /// [`crate::anchors::Pendulum`], from `urdf/pendulum.urdf`.
    pub struct PendulumUrdf;
    urdf: "urdf/pendulum.urdf";
    gravity: [0.0, -9.81, 0.0];
}

mechanism! {
    /// [`crate::anchors::DoublePendulum`], from `urdf/double_pendulum.urdf`.
    pub struct DoublePendulumUrdf;
    urdf: "urdf/double_pendulum.urdf";
    gravity: [0.0, -9.81, 0.0];
}

mechanism! {
    /// [`crate::anchors::Planar3`], from `urdf/planar3.urdf`.
    pub struct Planar3Urdf;
    urdf: "urdf/planar3.urdf";
    gravity: [0.0, -9.81, 0.0];
    allow: [triangle_inequality];
}

mechanism! {
    /// [`crate::anchors::Ur5`], from `urdf/ur5.urdf`.
    pub struct Ur5Urdf;
    urdf: "urdf/ur5.urdf";
    gravity: [0.0, 0.0, -9.81];
}

mechanism! {
    /// [`crate::anchors::Panda`], from `urdf/panda.urdf`.
    pub struct PandaUrdf;
    urdf: "urdf/panda.urdf";
    gravity: [0.0, 0.0, -9.81];
}
