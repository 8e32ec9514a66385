//! Mechanisms declared with the toolkit: the textbook's examples and the Pinocchio anchor
//! models (pendulums, a planar chain, UR5, Panda), and the kinematics of the robots of the
//! Pinocchio comparison.

pub mod anchors;
pub mod chains;
pub mod kinematics;
pub mod linkages;
pub mod puma560;
pub mod quadruped;
pub mod scenes;
pub mod seed;
pub mod urdf_anchors;
