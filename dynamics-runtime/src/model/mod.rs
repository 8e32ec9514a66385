//! The mechanism as plain data: a tree of rigid bodies joined by joints, with gravity.
//!
//! Conventions (SI units, right-handed frames):
//! - body `i` is moved by joint `i`; its parent is `parent[i] < i` (`None` = the ground);
//! - a joint's placement (R, p) is the pose of the joint frame in the parent body's frame at
//!   zero motion: `x_in_parent = R x_in_joint + p`; the body frame is the joint frame after
//!   the joint's motion (rotation about, or translation along, the joint axis);
//! - a body's inertial data are its mass m, mass centre c = PG in the body frame (P is the
//!   body frame's origin, the joint point) and inertia I_G about G in the body frame,
//!   `I_G = ∫ (|r|² 1 − r rᵀ) dm` (products of inertia enter with a minus sign:
//!   `I_xy = −∫ x y dm`, as in URDF and Pinocchio);
//! - gravity is a vector in the world (ground) frame;
//! - six-dimensional quantities are ordered linear first: [F; M_P], [a_P; α].
//!
//! A [`Model`] only exists validated: build it with [`ModelBuilder`], which merges bodies
//! joined by fixed joints into composite bodies and reports every ill-posed item at once.
//!
//! Its frames ([`Model::frames`]) are every declared body's frame (merged or not), then
//! every operational frame declared with [`FrameSpec`], each placed in the tree body it
//! moves with; its loads ([`Model::loads`], declared with [`LoadSpec`]) are placed the same
//! way.

mod builder;
mod error;
mod rules;
#[cfg(test)]
mod tests;

pub use builder::{BodySpec, FrameSpec, JointSpec, JointType, LoadSpec, ModelBuilder};
pub use error::{ModelError, ModelErrors, SizeError};

use nalgebra::{Matrix3, Vector3};

/// Name used for the fixed world frame when naming a joint's parent.
pub const GROUND: &str = "ground";

/// Inertial data of a rigid body, in that body's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Inertia {
    /// Mass m (kg).
    pub mass: f64,
    /// Mass centre c = PG in the body frame (m).
    pub com_in_body: Vector3<f64>,
    /// Inertia I_G about the mass centre, in the body frame (kg·m²).
    pub inertia_com_in_body: Matrix3<f64>,
}

impl Inertia {
    /// Inertia of a body from its mass, its mass centre and I_G, given as plain arrays.
    pub fn new(mass: f64, com_in_body: [f64; 3], inertia_com_in_body: [[f64; 3]; 3]) -> Self {
        Inertia {
            mass,
            com_in_body: Vector3::from(com_in_body),
            inertia_com_in_body: matrix_from_rows(inertia_com_in_body),
        }
    }

    /// A massless, inertialess body (a frame).
    pub fn zero() -> Self {
        Inertia::new(0.0, [0.0; 3], [[0.0; 3]; 3])
    }

    /// The inertia I_P about the body frame's origin P: I_P = I_G − m ĉ².
    pub fn inertia_about_origin(&self) -> Matrix3<f64> {
        let c_hat = self.com_in_body.cross_matrix();
        self.inertia_com_in_body - c_hat * c_hat * self.mass
    }

    /// The same inertia seen from a frame in which this body's frame has pose `pose`.
    pub fn transformed(&self, pose: &Placement) -> Inertia {
        Inertia {
            mass: self.mass,
            com_in_body: pose.rotation * self.com_in_body + pose.translation,
            inertia_com_in_body: pose.rotation
                * self.inertia_com_in_body
                * pose.rotation.transpose(),
        }
    }

    /// The inertia of two bodies rigidly joined, both expressed in the same frame
    /// (parallel-axis theorem about the composite mass centre).
    pub fn combined(&self, other: &Inertia) -> Inertia {
        let mass = self.mass + other.mass;
        let com = if mass > 0.0 {
            (self.com_in_body * self.mass + other.com_in_body * other.mass) / mass
        } else {
            Vector3::zeros()
        };
        let shifted = |part: &Inertia| {
            let d = (part.com_in_body - com).cross_matrix();
            part.inertia_com_in_body - d * d * part.mass
        };
        Inertia {
            mass,
            com_in_body: com,
            inertia_com_in_body: shifted(self) + shifted(other),
        }
    }
}

/// A rigid transform: the pose of a child frame in a parent frame,
/// `x_in_parent = rotation · x_in_child + translation`.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// Rotation from child-frame to parent-frame coordinates.
    pub rotation: Matrix3<f64>,
    /// Origin of the child frame, in the parent frame.
    pub translation: Vector3<f64>,
}

impl Placement {
    /// The identity placement.
    pub fn identity() -> Self {
        Placement {
            rotation: Matrix3::identity(),
            translation: Vector3::zeros(),
        }
    }

    /// A placement from a translation and a rotation matrix given by rows.
    pub fn new(translation: [f64; 3], rotation_rows: [[f64; 3]; 3]) -> Self {
        Placement {
            rotation: matrix_from_rows(rotation_rows),
            translation: Vector3::from(translation),
        }
    }

    /// A pure translation.
    pub fn translation(translation: [f64; 3]) -> Self {
        Placement {
            rotation: Matrix3::identity(),
            translation: Vector3::from(translation),
        }
    }

    /// The placement from roll-pitch-yaw angles (URDF: R = Rz(yaw) Ry(pitch) Rx(roll)).
    pub fn from_rpy(translation: [f64; 3], rpy: [f64; 3]) -> Self {
        let r = nalgebra::Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]);
        Placement {
            rotation: *r.matrix(),
            translation: Vector3::from(translation),
        }
    }

    /// `self ∘ child`: the pose of a grandchild frame given the child's pose in it.
    pub fn compose(&self, child: &Placement) -> Placement {
        Placement {
            rotation: self.rotation * child.rotation,
            translation: self.rotation * child.translation + self.translation,
        }
    }
}

/// What a joint lets its child body do relative to the parent.
#[derive(Clone, Debug, PartialEq)]
pub enum JointKind {
    /// Rotation by q about a unit axis of the joint frame (one coordinate).
    Revolute {
        /// Unit axis in the joint frame.
        axis_in_joint: Vector3<f64>,
    },
    /// Translation by q along a unit axis of the joint frame (one coordinate).
    Prismatic {
        /// Unit axis in the joint frame.
        axis_in_joint: Vector3<f64>,
    },
    /// A free-floating base: q = [x, y, z, qx, qy, qz, qw] (position of the body frame in the
    /// parent, unit quaternion body → parent, scalar last); v = [v_P; ω], the velocity of the
    /// body origin and the angular velocity, both in the body frame; a = dv/dt of that vector.
    FreeFlyer,
}

impl JointKind {
    /// Number of configuration coordinates.
    pub fn nq(&self) -> usize {
        match self {
            JointKind::FreeFlyer => 7,
            _ => 1,
        }
    }

    /// Number of velocity coordinates.
    pub fn nv(&self) -> usize {
        match self {
            JointKind::FreeFlyer => 6,
            _ => 1,
        }
    }
}

/// A joint of the validated tree: it moves exactly one body.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Kind and axis.
    pub kind: JointKind,
    /// Pose of the joint frame in the parent body's frame at zero motion (after merging
    /// fixed joints, in the frame of the composite parent body).
    pub placement_in_parent: Placement,
    /// Rotor inertia reflected to the joint coordinate (kg·m² or kg), added to M's diagonal.
    pub armature: f64,
    /// Viscous friction coefficient b: the joint resists with −b q̇.
    pub damping: f64,
    /// Index of the joint's first coordinate in q.
    pub idx_q: usize,
    /// Index of the joint's first coordinate in v.
    pub idx_v: usize,
}

/// A (composite) rigid body of the validated tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// The body's name (the name of the moving body when fixed bodies were merged into it).
    pub name: String,
    /// Index of the parent body, `None` for the ground. Always smaller than this body's index.
    pub parent: Option<usize>,
    /// The joint that moves this body.
    pub joint: Joint,
    /// Inertial data in this body's frame, including every body merged into it.
    pub inertia: Inertia,
}

/// A named frame rigidly attached to a body of the tree: every declared body has one
/// (including those merged away through fixed joints), and so has every operational frame
/// declared with [`FrameSpec`].
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The declared body's name, or the declared frame's.
    pub name: String,
    /// The body of the tree it moves with, `None` for the ground.
    pub body: Option<usize>,
    /// Pose of the frame in that body's frame.
    pub placement_in_body: Placement,
}

/// What an applied load is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadType {
    /// A force through the load's point (3 inputs).
    Force,
    /// A couple (3 inputs).
    Couple,
    /// A force through the load's point and a couple (6 inputs, the force first).
    Wrench,
}

impl LoadType {
    /// Number of run-time inputs: 3 for a force or a couple, 6 for a wrench.
    pub fn input_count(self) -> usize {
        match self {
            LoadType::Wrench => 6,
            LoadType::Force | LoadType::Couple => 3,
        }
    }
}

/// The axes an applied load's run-time components are given in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LoadFrame {
    /// The axes of the declared body it acts on, turning with it (the default).
    #[default]
    Body,
    /// The world's fixed axes (the language's `in world`).
    World,
}

/// An applied load on a body of the tree, declared with [`LoadSpec`]: its components are
/// entries `input_offset..input_offset + kind.input_count()` of the loads input.
#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    /// The load's name.
    pub name: String,
    /// Force, couple or both.
    pub kind: LoadType,
    /// The axes its components are given in.
    pub frame: LoadFrame,
    /// The body of the tree it acts on, `None` for a body welded to the ground (where it
    /// does no work).
    pub body: Option<usize>,
    /// The declared body's axes (rotation) and the point of application (translation), in
    /// that tree body's frame.
    pub placement_in_body: Placement,
    /// Index of its first component in the loads input.
    pub input_offset: usize,
}

/// A validated mechanism: a tree of bodies ordered parents first.
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    pub(crate) bodies: Vec<Body>,
    pub(crate) frames: Vec<Frame>,
    pub(crate) loads: Vec<Load>,
    pub(crate) num_load_inputs: usize,
    pub(crate) gravity_in_world: Vector3<f64>,
    pub(crate) nq: usize,
    pub(crate) nv: usize,
}

impl Model {
    /// The bodies, parents before children; body `i` is moved by joint `i`.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Every declared body as a frame on the tree (merged ones included), in declaration
    /// order, then every operational frame ([`FrameSpec`]) in the order it was added. The
    /// reference's frame methods take an index into this list.
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }

    /// The applied loads, in the order they were added ([`ModelBuilder::load`]).
    pub fn loads(&self) -> &[Load] {
        &self.loads
    }

    /// Length of the loads input: 3 per force or couple, 6 per wrench.
    pub fn num_load_inputs(&self) -> usize {
        self.num_load_inputs
    }

    /// Gravity in the world frame (m/s²).
    pub fn gravity_in_world(&self) -> Vector3<f64> {
        self.gravity_in_world
    }

    /// Length of the configuration vector q.
    pub fn nq(&self) -> usize {
        self.nq
    }

    /// Length of the velocity vector v (degrees of freedom).
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// Index of the body with this name (merged bodies are found through [`Model::frame`]).
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The frame of a declared body (merged or not) or an operational frame, by name.
    pub fn frame(&self, name: &str) -> Option<&Frame> {
        self.frames.iter().find(|f| f.name == name)
    }

    /// The index in [`Model::frames`] of the frame with this name (a declared body's or an
    /// operational frame's).
    pub fn frame_index(&self, name: &str) -> Option<usize> {
        self.frames.iter().position(|f| f.name == name)
    }

    /// The neutral configuration: zero joint coordinates, identity base orientation.
    pub fn neutral_configuration(&self) -> Vec<f64> {
        let mut q = vec![0.0; self.nq];
        for body in &self.bodies {
            if body.joint.kind == JointKind::FreeFlyer {
                q[body.joint.idx_q + 6] = 1.0;
            }
        }
        q
    }
}

pub(crate) fn matrix_from_rows(rows: [[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::new(
        rows[0][0], rows[0][1], rows[0][2], rows[1][0], rows[1][1], rows[1][2], rows[2][0],
        rows[2][1], rows[2][2],
    )
}
