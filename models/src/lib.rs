//! Mechanisms declared with the toolkit: the textbook's examples and the Pinocchio anchor
//! models (pendulums, a planar chain, UR5, Panda).

pub mod anchors;
pub mod chains;
pub mod linkages;
pub mod puma560;
pub mod quadruped;
pub mod scenes;
pub mod seed;
pub mod urdf_anchors;
