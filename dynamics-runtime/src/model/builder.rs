//! Building a validated [`Model`] from declared bodies, joints, operational frames and
//! applied loads.
//!
//! `build` checks every rule of [`super::rules`] (the inertia rules on the bodies as merged
//! through fixed joints), resolves names, orders the bodies so that `parent[i] < i` (depth
//! first, each subtree contiguous, children in declaration order: Pinocchio's order when
//! the joints are declared as the URDF import declares them, sorted by name), merges bodies
//! joined by fixed joints into composite bodies (parallel-axis theorem), numbers the
//! coordinates, and places every frame (each declared body's, then each declared
//! [`FrameSpec`]) on the tree body it moves with, and every [`LoadSpec`] likewise.

use super::error::{ModelError, ModelErrors};
use super::{
    rules, Body, Frame, Inertia, Joint, JointKind, Load, LoadFrame, LoadType, Model, Placement,
    GROUND,
};
use nalgebra::Vector3;
use std::collections::{HashMap, HashSet};

/// The kind of a declared joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointType {
    /// Rotation about the axis.
    Revolute,
    /// Translation along the axis.
    Prismatic,
    /// No relative motion: the child is merged into the parent.
    Fixed,
    /// Six degrees of freedom relative to the ground (see [`JointKind::FreeFlyer`]).
    FreeFlyer,
}

/// A declared body: a name and its inertial data in its own frame.
#[derive(Clone, Debug, PartialEq)]
pub struct BodySpec {
    /// Unique name.
    pub name: String,
    /// Mass, mass centre and I_G in the body frame.
    pub inertia: Inertia,
}

impl BodySpec {
    /// A body with the given inertial data.
    pub fn new(name: impl Into<String>, inertia: Inertia) -> Self {
        BodySpec {
            name: name.into(),
            inertia,
        }
    }
}

/// A declared joint between a parent body (or `ground`) and a child body.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpec {
    /// Unique name.
    pub name: String,
    /// Kind of motion.
    pub kind: JointType,
    /// Parent body name, or [`GROUND`].
    pub parent: String,
    /// Child body name.
    pub child: String,
    /// Axis in the joint frame (any nonzero length; normalized by `build`). Ignored for
    /// fixed and free-floating joints.
    pub axis: [f64; 3],
    /// Origin of the joint frame in the parent frame.
    pub translation: [f64; 3],
    /// Rotation of the joint frame in the parent frame, by rows.
    pub rotation_rows: [[f64; 3]; 3],
    /// Origin of the child body's frame in the joint frame after the motion (zero unless
    /// [`Self::with_child_frame`]).
    pub child_translation: [f64; 3],
    /// Rotation of the child body's frame in the joint frame after the motion, by rows
    /// (the identity unless [`Self::with_child_frame`]).
    pub child_rotation_rows: [[f64; 3]; 3],
    /// Rotor inertia reflected to each coordinate of the joint.
    pub armature: f64,
    /// Viscous friction coefficient of each coordinate of the joint.
    pub damping: f64,
}

const IDENTITY_ROWS: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

impl JointSpec {
    /// The child's frame in the joint frame after the motion, `None` when it is that frame
    /// (so that a joint without one is assembled as before, bit for bit).
    pub(crate) fn child_frame(&self) -> Option<Placement> {
        (self.child_translation != [0.0; 3] || self.child_rotation_rows != IDENTITY_ROWS)
            .then(|| Placement::new(self.child_translation, self.child_rotation_rows))
    }

    fn new(name: &str, kind: JointType, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        JointSpec {
            name: name.to_owned(),
            kind,
            parent: parent.to_owned(),
            child: child.to_owned(),
            axis,
            translation: [0.0; 3],
            rotation_rows: IDENTITY_ROWS,
            child_translation: [0.0; 3],
            child_rotation_rows: IDENTITY_ROWS,
            armature: 0.0,
            damping: 0.0,
        }
    }

    /// A revolute joint about `axis` (in the joint frame).
    pub fn revolute(name: &str, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        Self::new(name, JointType::Revolute, parent, child, axis)
    }

    /// A prismatic joint along `axis` (in the joint frame).
    pub fn prismatic(name: &str, parent: &str, child: &str, axis: [f64; 3]) -> Self {
        Self::new(name, JointType::Prismatic, parent, child, axis)
    }

    /// A fixed joint: `child` is rigidly attached to `parent`.
    pub fn fixed(name: &str, parent: &str, child: &str) -> Self {
        Self::new(name, JointType::Fixed, parent, child, [0.0; 3])
    }

    /// A free-floating joint between the ground and `child`.
    pub fn free_flyer(name: &str, child: &str) -> Self {
        Self::new(name, JointType::FreeFlyer, GROUND, child, [0.0; 3])
    }

    /// Places the joint frame in the parent frame: translation and rotation rows.
    pub fn placed(mut self, translation: [f64; 3], rotation_rows: [[f64; 3]; 3]) -> Self {
        self.translation = translation;
        self.rotation_rows = rotation_rows;
        self
    }

    /// Places the child body's frame in the joint frame after the motion:
    /// `x_joint = R x_child + translation`, R given by rows. Without it the child's frame is
    /// the joint frame after the motion. The child's inertial data, the frames and loads
    /// declared on it and the placements of its children's joints are in the child's
    /// frame; the body of the tree (its pose, the frame its joint moves) is the joint frame.
    /// A standard Denavit–Hartenberg row gives Tx(a) Rx(α) here (the language's
    /// `placement: dh(..)`).
    pub fn with_child_frame(mut self, translation: [f64; 3], rotation_rows: [[f64; 3]; 3]) -> Self {
        self.child_translation = translation;
        self.child_rotation_rows = rotation_rows;
        self
    }

    /// Places the joint frame at `translation` with no rotation.
    pub fn at(mut self, translation: [f64; 3]) -> Self {
        self.translation = translation;
        self
    }

    /// Sets the rotor inertia (armature) of each coordinate.
    pub fn with_armature(mut self, armature: f64) -> Self {
        self.armature = armature;
        self
    }

    /// Sets the viscous friction coefficient of each coordinate.
    pub fn with_damping(mut self, damping: f64) -> Self {
        self.damping = damping;
        self
    }
}

/// A declared operational frame: a named frame rigidly attached to a declared body (merged
/// through fixed joints or not) or to the ground, such as a tool centre point or a sensor.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameSpec {
    /// Unique name among the frames, including those of the declared bodies.
    pub name: String,
    /// The declared body it is attached to, or [`GROUND`].
    pub body: String,
    /// Origin of the frame in that body's frame.
    pub translation: [f64; 3],
    /// Rotation frame → body, by rows: `x_in_body = R x_in_frame + translation`.
    pub rotation_rows: [[f64; 3]; 3],
}

impl FrameSpec {
    /// A frame named `name` at the origin of declared body `body` (or [`GROUND`]), with the
    /// body's axes.
    pub fn new(name: &str, body: &str) -> Self {
        FrameSpec {
            name: name.to_owned(),
            body: body.to_owned(),
            translation: [0.0; 3],
            rotation_rows: IDENTITY_ROWS,
        }
    }

    /// Places the frame in the declared body's frame: `x_in_body = R x_in_frame +
    /// translation`, R given by rows.
    pub fn placed(mut self, translation: [f64; 3], rotation_rows: [[f64; 3]; 3]) -> Self {
        self.translation = translation;
        self.rotation_rows = rotation_rows;
        self
    }

    /// Places the frame's origin at `translation` in the declared body's frame, with the
    /// body's axes.
    pub fn at(mut self, translation: [f64; 3]) -> Self {
        self.translation = translation;
        self
    }
}

/// A declared applied load: a run-time force, couple or both acting on a declared body,
/// the force through a point fixed on the body, given in the body's frame. Its run-time
/// components ([`LoadType::input_count`] of them) are given in the body's axes, or in the
/// world's with [`LoadSpec::in_world`] (the language's `in world`).
#[derive(Clone, Debug, PartialEq)]
pub struct LoadSpec {
    /// Unique name among the loads.
    pub name: String,
    /// The declared body it acts on (merged through fixed joints or not).
    pub body: String,
    /// Force, couple or both.
    pub kind: LoadType,
    /// The point of application in the declared body's frame (the force's line of action
    /// passes through it; a couple ignores it).
    pub point: [f64; 3],
    /// The axes its components are given in.
    pub frame: LoadFrame,
}

impl LoadSpec {
    fn new(name: &str, body: &str, kind: LoadType) -> Self {
        LoadSpec {
            name: name.to_owned(),
            body: body.to_owned(),
            kind,
            point: [0.0; 3],
            frame: LoadFrame::Body,
        }
    }

    /// A force (3 inputs) on declared body `body`, through its origin until [`Self::at`],
    /// in its axes until [`Self::in_world`].
    pub fn force(name: &str, body: &str) -> Self {
        Self::new(name, body, LoadType::Force)
    }

    /// A couple (3 inputs) on declared body `body`, in its axes until [`Self::in_world`].
    pub fn couple(name: &str, body: &str) -> Self {
        Self::new(name, body, LoadType::Couple)
    }

    /// A force and a couple (6 inputs, the force first) on declared body `body`.
    pub fn wrench(name: &str, body: &str) -> Self {
        Self::new(name, body, LoadType::Wrench)
    }

    /// The point of application, in the declared body's frame.
    pub fn at(mut self, point: [f64; 3]) -> Self {
        self.point = point;
        self
    }

    /// The components are given in the world's fixed axes (the point stays fixed on the
    /// body).
    pub fn in_world(self) -> Self {
        self.in_frame(LoadFrame::World)
    }

    /// The components are given in the axes `frame` names.
    pub fn in_frame(mut self, frame: LoadFrame) -> Self {
        self.frame = frame;
        self
    }
}

/// Collects bodies, joints, frames, loads and gravity, then validates them into a [`Model`].
#[derive(Clone, Debug, Default)]
pub struct ModelBuilder {
    bodies: Vec<BodySpec>,
    joints: Vec<JointSpec>,
    frames: Vec<FrameSpec>,
    loads: Vec<LoadSpec>,
    gravity_in_world: [f64; 3],
    skip_triangle_inequality: bool,
    allow_coordinates_without_inertia: bool,
}

impl ModelBuilder {
    /// An empty mechanism with zero gravity.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets gravity in the world frame (m/s²).
    pub fn gravity(mut self, gravity_in_world: [f64; 3]) -> Self {
        self.gravity_in_world = gravity_in_world;
        self
    }

    /// Adds a body.
    pub fn body(mut self, body: BodySpec) -> Self {
        self.bodies.push(body);
        self
    }

    /// Adds a joint.
    pub fn joint(mut self, joint: JointSpec) -> Self {
        self.joints.push(joint);
        self
    }

    /// Adds an operational frame. [`Model::frames`] lists it after the frames of the
    /// declared bodies, in the order the frames were added.
    pub fn frame(mut self, frame: FrameSpec) -> Self {
        self.frames.push(frame);
        self
    }

    /// Adds an applied load. [`Model::loads`] lists the loads in the order they were added,
    /// and their components are consecutive entries of the loads input in that order.
    pub fn load(mut self, load: LoadSpec) -> Self {
        self.loads.push(load);
        self
    }

    /// Accepts inertias whose principal moments violate I1 + I2 ≥ I3. No real body has them,
    /// but some published models do (for example planar links given as laminae with products
    /// of inertia); the dynamics stay well defined as long as I_G is positive semi-definite.
    pub fn skip_triangle_inequality(mut self) -> Self {
        self.skip_triangle_inequality = true;
        self
    }

    /// Accepts joints that move no mass, no inertia and have no armature (with everything
    /// their bodies carry), which make M(q) singular: for a mechanism used for its
    /// kinematics (poses, Jacobians, velocities), energies or reactions only, whose links
    /// may be massless (a URDF without `<inertial>`). The model's forward dynamics is then
    /// undefined. The generated `Mechanism::model()` of a mechanism that asks for no
    /// output needing M(q) builds its model so, as the compiler checks such a mechanism's
    /// coordinates only when it asks for one.
    pub fn allow_coordinates_without_inertia(mut self) -> Self {
        self.allow_coordinates_without_inertia = true;
        self
    }

    /// Validates the declaration and builds the model, or returns every error found.
    pub fn build(self) -> Result<Model, ModelErrors> {
        let mut errors = Vec::new();
        self.check_numbers(&mut errors);
        let tree = self.resolve_tree(&mut errors);
        self.resolve_frames(&mut errors);
        self.resolve_loads(&mut errors);
        match tree {
            Some(order) if errors.is_empty() => {
                let model = self.assemble(&order);
                if !self.allow_coordinates_without_inertia {
                    check_massless_subtrees(&model, &mut errors);
                }
                if errors.is_empty() {
                    Ok(model)
                } else {
                    Err(ModelErrors(errors))
                }
            }
            _ => Err(ModelErrors(errors)),
        }
    }

    fn check_numbers(&self, errors: &mut Vec<ModelError>) {
        for (i, g) in self.gravity_in_world.iter().enumerate() {
            if !g.is_finite() {
                errors.push(ModelError::NonFinite {
                    item: "gravity".into(),
                    field: ["x", "y", "z"][i],
                    value: *g,
                });
            }
        }
        for body in &self.bodies {
            rules::body_numbers_are_finite(body, errors);
            rules::mass_is_not_negative(body, errors);
            rules::inertia_is_symmetric(body, errors);
        }
        rules::merged_inertias_are_physical(
            &self.bodies,
            &self.joints,
            !self.skip_triangle_inequality,
            errors,
        );
        for joint in &self.joints {
            rules::joint_numbers_are_finite(joint, errors);
            rules::axis_is_nonzero(joint, errors);
            rules::rotation_is_proper(joint, errors);
            rules::joint_coefficients_are_not_negative(joint, errors);
        }
        for frame in &self.frames {
            rules::frame_numbers_are_finite(frame, errors);
            rules::frame_rotation_is_proper(frame, errors);
        }
        for load in &self.loads {
            if let Some(v) = load.point.iter().find(|v| !v.is_finite()) {
                errors.push(ModelError::NonFinite {
                    item: format!("load `{}`", load.name),
                    field: "point",
                    value: *v,
                });
            }
        }
    }

    /// Checks that every load acts on a declared body and has a name no other load has.
    fn resolve_loads(&self, errors: &mut Vec<ModelError>) {
        let body_names: HashSet<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
        let mut load_names: HashSet<&str> = HashSet::new();
        for load in &self.loads {
            if !body_names.contains(load.body.as_str()) {
                errors.push(ModelError::UnknownLoadBody {
                    load: load.name.clone(),
                    body: load.body.clone(),
                });
            }
            if !load_names.insert(&load.name) {
                errors.push(ModelError::DuplicateName {
                    kind: "load",
                    name: load.name.clone(),
                });
            }
        }
    }

    /// Checks that every declared frame is attached to a declared body (or the ground) and
    /// has a name no other frame has: neither a declared body's (every body is a frame), nor
    /// the ground's, nor another declared frame's.
    fn resolve_frames(&self, errors: &mut Vec<ModelError>) {
        let body_names: HashSet<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
        let mut frame_names: HashSet<&str> = HashSet::new();
        for frame in &self.frames {
            if frame.body != GROUND && !body_names.contains(frame.body.as_str()) {
                errors.push(ModelError::UnknownFrameBody {
                    frame: frame.name.clone(),
                    body: frame.body.clone(),
                });
            }
            let taken_by = if frame.name == GROUND {
                Some("the ground")
            } else if body_names.contains(frame.name.as_str()) {
                Some("a body (every declared body is a frame)")
            } else if !frame_names.insert(&frame.name) {
                Some("another frame")
            } else {
                None
            };
            if let Some(taken_by) = taken_by {
                errors.push(ModelError::DuplicateFrameName {
                    frame: frame.name.clone(),
                    taken_by,
                });
            }
        }
    }

    /// Resolves names and returns the joints (indices into `self.joints`) in depth-first
    /// order from the ground, or `None` if the declaration is not a tree rooted at the ground.
    fn resolve_tree(&self, errors: &mut Vec<ModelError>) -> Option<Vec<usize>> {
        let before = errors.len();
        let mut body_index: HashMap<&str, usize> = HashMap::new();
        for (i, body) in self.bodies.iter().enumerate() {
            if body.name == GROUND || body_index.insert(&body.name, i).is_some() {
                errors.push(ModelError::DuplicateName {
                    kind: "body",
                    name: body.name.clone(),
                });
            }
        }
        let mut joint_names: HashMap<&str, usize> = HashMap::new();
        for (i, joint) in self.joints.iter().enumerate() {
            if joint_names.insert(&joint.name, i).is_some() {
                errors.push(ModelError::DuplicateName {
                    kind: "joint",
                    name: joint.name.clone(),
                });
            }
        }
        // parent_joint[b] = the joint whose child is body b.
        let mut parent_joint: Vec<Option<usize>> = vec![None; self.bodies.len()];
        // Parent body of each joint: None = ground.
        let mut joint_parent: Vec<Option<usize>> = vec![None; self.joints.len()];
        for (j, joint) in self.joints.iter().enumerate() {
            if joint.parent != GROUND {
                match body_index.get(joint.parent.as_str()) {
                    Some(&p) => joint_parent[j] = Some(p),
                    None => errors.push(ModelError::UnknownBody {
                        joint: joint.name.clone(),
                        role: "parent",
                        name: joint.parent.clone(),
                    }),
                }
            }
            if joint.child == GROUND {
                errors.push(ModelError::GroundAsChild {
                    joint: joint.name.clone(),
                });
                continue;
            }
            if joint.parent == joint.child {
                errors.push(ModelError::SelfJoint {
                    joint: joint.name.clone(),
                });
                continue;
            }
            if joint.kind == JointType::FreeFlyer && joint.parent != GROUND {
                errors.push(ModelError::FreeFlyerNotOnGround {
                    joint: joint.name.clone(),
                    parent: joint.parent.clone(),
                });
            }
            match body_index.get(joint.child.as_str()) {
                None => errors.push(ModelError::UnknownBody {
                    joint: joint.name.clone(),
                    role: "child",
                    name: joint.child.clone(),
                }),
                Some(&c) => match parent_joint[c] {
                    Some(first) => errors.push(ModelError::TwoParents {
                        body: joint.child.clone(),
                        first_joint: self.joints[first].name.clone(),
                        second_joint: joint.name.clone(),
                    }),
                    None => parent_joint[c] = Some(j),
                },
            }
        }
        if errors.len() > before {
            return None;
        }
        // Depth-first order from the ground, children in declaration order.
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); self.bodies.len() + 1];
        let slot = |p: Option<usize>| p.map_or(0, |p| p + 1);
        for (j, p) in joint_parent.iter().enumerate() {
            children[slot(*p)].push(j);
        }
        let mut order = Vec::with_capacity(self.joints.len());
        let mut reached = vec![false; self.bodies.len()];
        let mut stack: Vec<usize> = children[0].iter().rev().copied().collect();
        while let Some(j) = stack.pop() {
            order.push(j);
            let c = body_index[self.joints[j].child.as_str()];
            reached[c] = true;
            stack.extend(children[c + 1].iter().rev().copied());
        }
        report_unreached(self, &reached, &parent_joint, &joint_parent, errors);
        (errors.len() == before).then_some(order)
    }

    /// Builds the model from joints in depth-first order, merging fixed joints.
    fn assemble(&self, order: &[usize]) -> Model {
        let index_of: HashMap<&str, usize> = self
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.name.as_str(), i))
            .collect();
        // Where each declared body ended up: tree body (None = ground) and its pose there.
        let mut attached: Vec<Option<(Option<usize>, Placement)>> = vec![None; self.bodies.len()];
        let mut bodies: Vec<Body> = Vec::new();
        let (mut nq, mut nv) = (0, 0);
        for &j in order {
            let spec = &self.joints[j];
            let (tree_parent, parent_pose) = match spec.parent.as_str() {
                GROUND => (None, Placement::identity()),
                name => attached[index_of[name]]
                    .clone()
                    .unwrap_or((None, Placement::identity())),
            };
            let joint_pose =
                parent_pose.compose(&Placement::new(spec.translation, spec.rotation_rows));
            let child_frame = spec.child_frame();
            let child = index_of[spec.child.as_str()];
            let inertia = &self.bodies[child].inertia;
            let axis = rules::unit_axis(spec.axis);
            let kind = match spec.kind {
                JointType::Fixed => {
                    let child_pose = match &child_frame {
                        Some(frame) => joint_pose.compose(frame),
                        None => joint_pose,
                    };
                    if let Some(b) = tree_parent {
                        let moved = inertia.transformed(&child_pose);
                        bodies[b].inertia = bodies[b].inertia.combined(&moved);
                    }
                    attached[child] = Some((tree_parent, child_pose));
                    continue;
                }
                JointType::Revolute => JointKind::Revolute {
                    axis_in_joint: axis,
                },
                JointType::Prismatic => JointKind::Prismatic {
                    axis_in_joint: axis,
                },
                JointType::FreeFlyer => JointKind::FreeFlyer,
            };
            let joint = Joint {
                name: spec.name.clone(),
                placement_in_parent: joint_pose,
                armature: spec.armature,
                damping: spec.damping,
                idx_q: nq,
                idx_v: nv,
                kind,
            };
            nq += joint.kind.nq();
            nv += joint.kind.nv();
            // The child's frame in its tree body (the joint frame after the motion).
            let (child_pose, inertia) = match child_frame {
                Some(frame) => (frame.clone(), inertia.transformed(&frame)),
                None => (Placement::identity(), inertia.clone()),
            };
            attached[child] = Some((Some(bodies.len()), child_pose));
            bodies.push(Body {
                name: spec.child.clone(),
                parent: tree_parent,
                joint,
                inertia,
            });
        }
        let mut frames: Vec<Frame> = self
            .bodies
            .iter()
            .zip(&attached)
            .map(|(b, a)| {
                let (body, placement_in_body) = a.clone().unwrap_or((None, Placement::identity()));
                Frame {
                    name: b.name.clone(),
                    body,
                    placement_in_body,
                }
            })
            .collect();
        // Declared frames: the declared body's pose in its tree body, then the frame's pose
        // in the declared body (`resolve_frames` checked the names; an unknown one cannot
        // reach here, and would be placed on the ground rather than panic).
        for spec in &self.frames {
            let own = Placement::new(spec.translation, spec.rotation_rows);
            let declared_body = index_of
                .get(spec.body.as_str())
                .and_then(|&b| attached[b].clone());
            let (body, placement_in_body) = match declared_body {
                Some((body, body_pose)) => (body, body_pose.compose(&own)),
                None => (None, own),
            };
            frames.push(Frame {
                name: spec.name.clone(),
                body,
                placement_in_body,
            });
        }
        // Loads: the declared body's pose in its tree body carries the point and the body's
        // axes (`resolve_loads` checked the names; an unknown one cannot reach here, and
        // would act on the ground, that is on nothing, rather than panic).
        let mut input_offset = 0;
        let loads = self
            .loads
            .iter()
            .map(|spec| {
                let (body, body_pose) = index_of
                    .get(spec.body.as_str())
                    .and_then(|&b| attached[b].clone())
                    .unwrap_or((None, Placement::identity()));
                let load = Load {
                    name: spec.name.clone(),
                    kind: spec.kind,
                    frame: spec.frame,
                    body,
                    placement_in_body: body_pose.compose(&Placement::translation(spec.point)),
                    input_offset,
                };
                input_offset += spec.kind.input_count();
                load
            })
            .collect();
        Model {
            bodies,
            frames,
            loads,
            num_load_inputs: input_offset,
            gravity_in_world: Vector3::from(self.gravity_in_world),
            nq,
            nv,
        }
    }
}

/// Reports bodies the depth-first walk did not reach: each cycle once, the rest as not
/// connected to the ground.
fn report_unreached(
    builder: &ModelBuilder,
    reached: &[bool],
    parent_joint: &[Option<usize>],
    joint_parent: &[Option<usize>],
    errors: &mut Vec<ModelError>,
) {
    let parent_of = |b: usize| parent_joint[b].and_then(|j| joint_parent[j]);
    let mut on_reported_cycle = vec![false; reached.len()];
    for b in 0..reached.len() {
        if reached[b] || on_reported_cycle[b] {
            continue;
        }
        if parent_joint[b].is_none() {
            errors.push(ModelError::NotConnected {
                body: builder.bodies[b].name.clone(),
            });
            continue;
        }
        // Follow parents: either a body with no parent joint (not connected) or a cycle.
        let mut seen = vec![false; reached.len()];
        let mut walk = b;
        let mut cycle_start = None;
        while let Some(p) = parent_of(walk) {
            if seen[p] {
                cycle_start = Some(p);
                break;
            }
            seen[walk] = true;
            walk = p;
        }
        match cycle_start {
            Some(start) if !on_reported_cycle[start] => {
                let mut cycle = vec![start];
                let mut w = parent_of(start);
                while let Some(p) = w.filter(|&p| p != start) {
                    cycle.push(p);
                    w = parent_of(p);
                }
                for &c in &cycle {
                    on_reported_cycle[c] = true;
                }
                let mut names: Vec<String> = cycle
                    .iter()
                    .map(|&c| builder.bodies[c].name.clone())
                    .collect();
                names.sort();
                errors.push(ModelError::Cycle { bodies: names });
            }
            Some(_) => {}
            None => errors.push(ModelError::NotConnected {
                body: builder.bodies[b].name.clone(),
            }),
        }
    }
}

/// Rule: every moving body, together with everything it carries, has mass or inertia, or
/// its joint has armature (rotor inertia, added to the coordinate's own entries of M);
/// otherwise its joint coordinate has no inertia and M(q) is singular.
fn check_massless_subtrees(model: &Model, errors: &mut Vec<ModelError>) {
    let n = model.bodies.len();
    let mut carries_inertia = vec![false; n];
    for i in (0..n).rev() {
        let own = &model.bodies[i].inertia;
        carries_inertia[i] |= own.mass > 0.0 || own.inertia_com_in_body.amax() > 0.0;
        if let Some(p) = model.bodies[i].parent {
            carries_inertia[p] |= carries_inertia[i];
        }
    }
    for (body, carries) in model.bodies.iter().zip(carries_inertia) {
        if !carries && body.joint.armature <= 0.0 {
            errors.push(ModelError::MasslessSubtree {
                body: body.name.clone(),
                joint: body.joint.name.clone(),
            });
        }
    }
}
