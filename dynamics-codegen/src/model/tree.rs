//! The tree: bodies ordered depth first from the ground (parents first, each subtree
//! contiguous, children in declaration order: the URDF import declares a file's joints
//! sorted by name, which makes this Pinocchio's order), fixed joints merged into composite
//! bodies, coordinates numbered, and the rule that every coordinate has inertia.
//!
//! A body joined to its parent by a fixed joint becomes a [`Part`] of the parent's tree
//! body, expressed in that body's frame: c' = R c + p, I_G' = R I_G Rᵀ. Joints and loads on
//! a merged body are re-based the same way.
//!
//! A moving body's tree frame is its joint frame after the motion, turned about the joint's
//! axis where [`super::frame_turns`] finds that the turn makes the placements and the
//! inertia sparser, then by a half turn where the axis points the negative way along a
//! coordinate axis (`frame_turns::axis_half_turn`: the axis is then +x, +y or +z, so that
//! mirror-image limbs have the same joints); everything on the body is re-based by that turn
//! as by a weld.

use super::frame_turns;
use super::linear::{self, Matrix3, Vector3};
use super::resolved::{Resolved, ResolvedJoint};
use super::rules::{self, GROUND};
use super::value::{self, nominal3, Value, Vec3};
use super::{
    Body, DeclaredBody, DeclaredFrame, DeclaredJoint, Diagnostics, Frame, Joint, JointKind,
    JointLimits, Load, Model, Part,
};
use crate::syntax::{self, JointKind as Declared};
use std::collections::HashMap;

/// Where a declared body ended up: its tree body (`None`: the ground) and its pose there.
#[derive(Clone)]
struct Attachment {
    body: Option<usize>,
    rotation: [[f64; 3]; 3],
    translation: Vec3,
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn zero3() -> Vec3 {
    std::array::from_fn(|_| Value::constant(0.0))
}

/// Builds the tree of a declaration that passed every rule of [`rules::check_all`].
pub(crate) fn build(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    d: &mut Diagnostics,
) -> Option<Model> {
    let body_index: HashMap<&str, usize> = resolved
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| (b.name.text.as_str(), i))
        .collect();
    let children_of = child_joints(resolved);
    let order = depth_first_order(resolved, &body_index, &children_of);
    let nominal = resolved.nominal_parameters();
    // The force analysis fixes its unknowns' directions in the tree bodies' frames, as
    // declared: its bodies keep them.
    let turns_allowed = !(resolved.outputs.force_analysis
        || resolved.outputs.constraints
        || !mechanism.constraints.is_empty());
    let mut attached: Vec<Option<Attachment>> = vec![None; resolved.bodies.len()];
    let mut bodies: Vec<Body> = Vec::new();
    let (mut nq, mut nv) = (0, 0);
    // Bodies welded through fixed joints, in depth-first order: the default frames.
    let mut welded: Vec<usize> = Vec::new();
    let mut ground_parts: Vec<Part> = Vec::new();
    for j in order {
        let joint = &resolved.joints[j];
        let parent = match joint.parent.text.as_str() {
            GROUND => Attachment {
                body: None,
                rotation: IDENTITY,
                translation: zero3(),
            },
            name => attached[*body_index.get(name)?].clone()?,
        };
        // Pose of the joint frame in the parent's tree body.
        let rotation = value::rotation_product(&parent.rotation, &joint.rotation);
        let translation = value::add(
            &value::rotate(&parent.rotation, &joint.translation),
            &parent.translation,
        );
        let child = *body_index.get(joint.child.text.as_str())?;
        let declared = &resolved.bodies[child];
        let kind = match (joint.kind, joint.axis) {
            (Declared::Fixed, _) => {
                let part = Part {
                    name: declared.name.text.clone(),
                    docs: declared.docs.clone(),
                    weld: Some((joint.name.text.clone(), joint.docs.clone())),
                    mass: declared.mass.clone(),
                    com_in_body: value::add(&value::rotate(&rotation, &declared.com), &translation),
                    inertia_com_in_body: value::rotate_matrix(&rotation, &declared.inertia),
                };
                match parent.body {
                    Some(b) => bodies[b].parts.push(part),
                    None => ground_parts.push(part),
                }
                attached[child] = Some(Attachment {
                    body: parent.body,
                    rotation,
                    translation,
                });
                welded.push(child);
                continue;
            }
            (Declared::Revolute, Some((axis, _))) => JointKind::Revolute {
                axis_in_body: unit(axis),
            },
            (Declared::Prismatic, Some((axis, _))) => JointKind::Prismatic {
                axis_in_body: unit(axis),
            },
            (Declared::Free, _) => JointKind::Free,
            (Declared::Revolute | Declared::Prismatic, None) => return None,
        };
        // The child's declared frame in the joint frame after the motion: the same frame,
        // or a standard DH row's C = Tx(a) Rx(α) (see `super::dh`).
        let (frame_rotation, frame_translation) = match &joint.child_frame {
            Some(c) => (c.rotation, c.translation.clone()),
            None => (IDENTITY, zero3()),
        };
        // The tree body's frame: the joint frame, turned about the axis where that makes the
        // placements sparser (see `super::frame_turns`). A turn Rot(s, φ) joins the joint's
        // placement, and everything on the body is re-expressed by Rot(s, φ)ᵀ.
        let turn = match &kind {
            JointKind::Revolute { axis_in_body } | JointKind::Prismatic { axis_in_body }
                if turns_allowed =>
            {
                let (below, mass) = turn_inputs(
                    resolved,
                    &children_of,
                    &body_index,
                    &joint.child.text,
                    (frame_rotation, nominal3(&frame_translation, &nominal)),
                    &nominal,
                );
                frame_turns::best_turn(*axis_in_body, &rotation, &below, &mass)
            }
            _ => None,
        };
        // An axis along a coordinate axis the negative way is made positive by a half turn
        // of the frame (`frame_turns::axis_half_turn`), after the turn about it.
        let (kind, half_turn) = match kind {
            JointKind::Revolute { axis_in_body } | JointKind::Prismatic { axis_in_body }
                if turns_allowed =>
            {
                match frame_turns::axis_half_turn(axis_in_body) {
                    Some(h) => (
                        kind.with_axis(linear::mul_vector(&h, &axis_in_body)),
                        Some(h),
                    ),
                    None => (kind, None),
                }
            }
            _ => (kind, None),
        };
        let turn = match (turn, half_turn) {
            (Some(t), Some(h)) => Some(linear::mul(&t, &h)),
            (t, h) => t.or(h),
        };
        let joint_frame_in_body = turn.map(|t| linear::transpose(&t));
        let (rotation, frame_rotation, frame_translation) = match &joint_frame_in_body {
            Some(back) => (
                value::rotation_product(&rotation, &linear::transpose(back)),
                value::rotation_product(back, &frame_rotation),
                value::snapped_vector(&value::rotate(back, &frame_translation)),
            ),
            None => (rotation, frame_rotation, frame_translation),
        };
        let tree_joint = Joint {
            name: joint.name.text.clone(),
            docs: joint.docs.clone(),
            rotation_in_parent: rotation,
            translation_in_parent: translation,
            joint_frame_in_body,
            armature: joint.armature.0.clone(),
            damping: joint.damping.0.clone(),
            friction: joint.friction.0,
            limits: JointLimits {
                lower: joint.limits.lower.0,
                upper: joint.limits.upper.0,
                velocity: joint.limits.velocity.0,
                effort: joint.limits.effort.0,
            },
            idx_q: nq,
            idx_v: nv,
            kind,
        };
        let (dq, dv) = if tree_joint.kind == JointKind::Free {
            (7, 6)
        } else {
            (1, 1)
        };
        nq += dq;
        nv += dv;
        // Everything declared in the child's frame reaches the tree through its placement
        // in the tree body's frame, as a welded body's does; its own mass centre and inertia
        // are carried here.
        let (com_in_body, inertia_com_in_body) = if joint.child_frame.is_none()
            && tree_joint.joint_frame_in_body.is_none()
        {
            (declared.com.clone(), declared.inertia.clone())
        } else {
            (
                value::snapped_vector(&value::add(
                    &value::rotate(&frame_rotation, &declared.com),
                    &frame_translation,
                )),
                value::snapped_matrix(&value::rotate_matrix(&frame_rotation, &declared.inertia)),
            )
        };
        attached[child] = Some(Attachment {
            body: Some(bodies.len()),
            rotation: frame_rotation,
            translation: frame_translation,
        });
        bodies.push(Body {
            name: declared.name.text.clone(),
            docs: declared.docs.clone(),
            parent: parent.body,
            joint: tree_joint,
            parts: vec![Part {
                name: declared.name.text.clone(),
                docs: Vec::new(),
                weld: None,
                mass: declared.mass.clone(),
                com_in_body,
                inertia_com_in_body,
            }],
        });
    }
    if resolved.outputs.any_dynamics() {
        check_coordinates_have_inertia(&bodies, resolved, &nominal, d);
    }
    let mut loads = Vec::new();
    let mut offset = 0;
    for (load, point) in mechanism.loads.iter().zip(&resolved.load_points) {
        let declared = *body_index.get(load.body.text.as_str())?;
        let at = attached[declared].clone()?;
        let Some(body) = at.body else {
            d.error(load.body.span, format!("load `{}` acts on `{}`, which is welded to the ground: it does no work and enters no dynamics", load.name.text, load.body.text));
            continue;
        };
        let point = point.clone().unwrap_or_else(zero3);
        loads.push(Load {
            name: load.name.text.clone(),
            docs: load.docs.clone(),
            declared_body: load.body.text.clone(),
            declared_point: point.clone(),
            kind: load.kind,
            frame: load.frame(),
            body,
            rotation_in_body: at.rotation,
            point_in_body: value::add(&value::rotate(&at.rotation, &point), &at.translation),
            input_offset: offset,
        });
        offset += load.kind.input_count();
    }
    let declared_bodies = resolved
        .bodies
        .iter()
        .map(|b| DeclaredBody {
            name: b.name.text.clone(),
            mass: b.mass.clone(),
            com: b.com.clone(),
            inertia: b.inertia.clone(),
        })
        .collect();
    let declared_joints = resolved
        .joints
        .iter()
        .map(|j| DeclaredJoint {
            name: j.name.text.clone(),
            kind: j.kind,
            parent: j.parent.text.clone(),
            child: j.child.text.clone(),
            axis: j.axis.map_or([0.0; 3], |(a, _)| a),
            translation: j.translation.clone(),
            rotation: j.rotation,
            child_frame: j
                .child_frame
                .as_ref()
                .map(|c| (c.translation.clone(), c.rotation)),
            armature: j.armature.0.clone(),
            damping: j.damping.0.clone(),
        })
        .collect();
    let locate = |name: &str| -> Option<(Option<usize>, [[f64; 3]; 3], Vec3)> {
        if name == GROUND {
            return Some((None, IDENTITY, zero3()));
        }
        let at = attached[*body_index.get(name)?].clone()?;
        Some((at.body, at.rotation, at.translation))
    };
    let statics = super::statics::build(mechanism, resolved, &bodies, &locate, d);
    let frames = frames(mechanism, resolved, &welded, &attached, &body_index)?;
    if frames.is_empty() {
        for name in mechanism.outputs.iter().flatten() {
            if name.text.starts_with("frame_") {
                d.error(
                    name.span,
                    format!(
                        "`{}` gives the operational frames, and this mechanism has none: declare \
                         one with `frame name: on body at [x, y, z];` (a body welded to another \
                         through a fixed joint is a frame too)",
                        name.text
                    ),
                );
            }
        }
    }
    Some(Model {
        name: mechanism.name.clone(),
        visibility: mechanism.visibility.clone(),
        docs: mechanism.docs.clone(),
        gravity_in_world: resolved.gravity,
        parameters: resolved.parameters.clone(),
        outputs: resolved.outputs,
        bodies,
        ground_parts,
        loads,
        frames,
        load_inputs: offset,
        nq,
        nv,
        declared_bodies,
        declared_joints,
        declared_frames: resolved
            .frames
            .iter()
            .map(|f| DeclaredFrame {
                name: f.name.text.clone(),
                body: f.body.text.clone(),
                translation: f.translation,
                rotation: f.rotation,
            })
            .collect(),
        skip_triangle_inequality: resolved.skip_triangle_inequality,
        packs: true,
        source_files: Vec::new(),
        statics,
    })
}

/// The frames the frame outputs cover: the welded bodies, then the declared frames, or
/// the frames `frames: [..]` lists (any of those, or a tree body), in its order. `None` if
/// a name does not resolve (the rules have reported it).
fn frames(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    welded: &[usize],
    attached: &[Option<Attachment>],
    body_index: &HashMap<&str, usize>,
) -> Option<Vec<Frame>> {
    let body_frame = |declared: usize| -> Option<Frame> {
        let at = attached[declared].clone()?;
        let body = &resolved.bodies[declared];
        Some(Frame {
            name: body.name.text.clone(),
            docs: body.docs.clone(),
            body: at.body,
            rotation_in_body: at.rotation,
            origin_in_body: at.translation,
        })
    };
    let declared_frame = |f: &super::resolved::ResolvedFrame| -> Option<Frame> {
        let at = if f.body.text == GROUND {
            Attachment {
                body: None,
                rotation: IDENTITY,
                translation: zero3(),
            }
        } else {
            attached[*body_index.get(f.body.text.as_str())?].clone()?
        };
        let translation = std::array::from_fn(|k| Value::constant(f.translation[k]));
        Some(Frame {
            name: f.name.text.clone(),
            docs: f.docs.clone(),
            body: at.body,
            rotation_in_body: value::rotation_product(&at.rotation, &f.rotation),
            origin_in_body: value::add(&value::rotate(&at.rotation, &translation), &at.translation),
        })
    };
    match &mechanism.frame_selection {
        None => welded
            .iter()
            .map(|&b| body_frame(b))
            .chain(resolved.frames.iter().map(declared_frame))
            .collect(),
        Some(names) => names
            .iter()
            .map(
                |name| match resolved.frames.iter().find(|f| f.name.text == name.text) {
                    Some(f) => declared_frame(f),
                    None => body_frame(*body_index.get(name.text.as_str())?),
                },
            )
            .collect(),
    }
}

/// What a turn of a tree body's frame changes: the moving joints below the declared body
/// (directly or through bodies welded to it) and the inertia of the body and the bodies
/// welded to it, in the frame where `placement` places the declared body's own frame. (A
/// walk with its own stack: a URDF may weld thousands of links in a chain.)
fn turn_inputs(
    resolved: &Resolved,
    children_of: &HashMap<&str, Vec<usize>>,
    body_index: &HashMap<&str, usize>,
    body: &str,
    placement: ([[f64; 3]; 3], [f64; 3]),
    nominal: &[f64],
) -> (
    Vec<frame_turns::ChildPlacement>,
    frame_turns::MassProperties,
) {
    let mut below = Vec::new();
    let mut mass = frame_turns::MassProperties {
        first_moment: [0.0; 3],
        inertia_about_origin: linear::ZERO,
    };
    let mut stack = vec![(body, placement)];
    while let Some((body, (rotation, translation))) = stack.pop() {
        if let Some(declared) = body_index.get(body).map(|&b| &resolved.bodies[b]) {
            // h += m c, I_P += I_G + m (|c|² 1 − c cᵀ), c and I_G in the body's frame.
            let m = declared.mass.nominal(nominal);
            let c = linear::add_vectors(
                &linear::mul_vector(&rotation, &nominal3(&declared.com, nominal)),
                &translation,
            );
            let i_g = linear::rotate(&rotation, &value::nominal33(&declared.inertia, nominal));
            mass.first_moment =
                linear::add_vectors(&mass.first_moment, &linear::scale_vector(&c, m));
            mass.inertia_about_origin = linear::add(
                &mass.inertia_about_origin,
                &linear::add(&i_g, &linear::scale(&linear::parallel_axis(&c), m)),
            );
        }
        for &k in children_of.get(body).into_iter().flatten() {
            let joint = &resolved.joints[k];
            let joint_rotation = value::rotation_product(&rotation, &joint.rotation);
            let origin = linear::add_vectors(
                &linear::mul_vector(&rotation, &nominal3(&joint.translation, nominal)),
                &translation,
            );
            match (joint.kind, joint.axis) {
                (Declared::Fixed, _) => {
                    stack.push((joint.child.text.as_str(), (joint_rotation, origin)))
                }
                (kind, axis) => below.push(frame_turns::ChildPlacement {
                    rotation_in_body: joint_rotation,
                    origin_in_body: origin,
                    axis: match kind {
                        Declared::Revolute | Declared::Prismatic => axis.map(|(a, _)| unit(a)),
                        _ => None,
                    },
                }),
            }
        }
    }
    (below, mass)
}

fn unit(axis: [f64; 3]) -> [f64; 3] {
    linear::normalize(&axis)
}

/// Each body's (or the ground's) joints to its children, by the body's name, in
/// declaration order.
fn child_joints(resolved: &Resolved) -> HashMap<&str, Vec<usize>> {
    let mut children: HashMap<&str, Vec<usize>> = HashMap::new();
    for (j, joint) in resolved.joints.iter().enumerate() {
        children
            .entry(joint.parent.text.as_str())
            .or_default()
            .push(j);
    }
    children
}

/// Joint indices in depth-first order from the ground, children in declaration order.
fn depth_first_order(
    resolved: &Resolved,
    body_index: &HashMap<&str, usize>,
    children: &HashMap<&str, Vec<usize>>,
) -> Vec<usize> {
    let mut order = Vec::new();
    let mut stack: Vec<usize> = children
        .get(GROUND)
        .map(|c| c.iter().rev().copied().collect())
        .unwrap_or_default();
    let mut visited = vec![false; resolved.joints.len()];
    while let Some(j) = stack.pop() {
        if std::mem::replace(&mut visited[j], true) {
            continue;
        }
        order.push(j);
        let child = resolved.joints[j].child.text.as_str();
        if body_index.contains_key(child) {
            if let Some(c) = children.get(child) {
                stack.extend(c.iter().rev().copied());
            }
        }
    }
    order
}

/// World poses (rotation, origin) of every tree body at configuration `angles` (one value
/// per revolute or prismatic joint, free joints at identity).
fn poses(bodies: &[Body], p: &[f64], angles: impl Fn(usize) -> f64) -> Vec<(Matrix3, Vector3)> {
    let mut out: Vec<(Matrix3, Vector3)> = Vec::with_capacity(bodies.len());
    for (i, body) in bodies.iter().enumerate() {
        let (r_parent, o_parent) = body.parent.map_or((linear::IDENTITY, [0.0; 3]), |k| out[k]);
        let j = &body.joint;
        let r_joint = linear::mul(&r_parent, &j.rotation_in_parent);
        let o_joint = linear::add_vectors(
            &o_parent,
            &linear::mul_vector(&r_parent, &nominal3(&j.translation_in_parent, p)),
        );
        out.push(match j.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = linear::normalize(&axis_in_body);
                (
                    linear::mul(
                        &r_joint,
                        &linear::rotation_from_axis_angle(&axis, angles(i)),
                    ),
                    o_joint,
                )
            }
            JointKind::Prismatic { axis_in_body } => (
                r_joint,
                linear::add_vectors(
                    &o_joint,
                    &linear::scale_vector(&linear::mul_vector(&r_joint, &axis_in_body), angles(i)),
                ),
            ),
            JointKind::Free => (r_joint, o_joint),
        });
    }
    out
}

/// Applies [`rules::coordinate_has_inertia`] to every joint, at three configurations.
fn check_coordinates_have_inertia(
    bodies: &[Body],
    resolved: &Resolved,
    p: &[f64],
    d: &mut Diagnostics,
) {
    let configurations: [fn(usize) -> f64; 3] =
        [|_| 0.0, |i| 0.7 + 0.9 * i as f64, |i| -1.3 + 0.4 * i as f64];
    let mut measured: Vec<rules::CoordinateInertia> = bodies
        .iter()
        .map(|_| rules::CoordinateInertia {
            mass: 0.0,
            moment: 0.0,
            configurations: configurations.len(),
            armature: 0.0,
            finite: true,
        })
        .collect();
    let mut scale = 0.0;
    for body in bodies {
        for part in &body.parts {
            scale += part.mass.nominal(p).abs()
                * (1.0 + linear::norm_squared(&nominal3(&part.com_in_body, p)))
                + linear::trace(&rules::nominal_matrix(&part.inertia_com_in_body, p)).abs();
        }
    }
    for configuration in configurations {
        let world = poses(bodies, p, configuration);
        let subtrees = subtrees_about_origins(bodies, p, &world);
        for (j, &(mass, first_moment, inertia_about_origin)) in subtrees.iter().enumerate() {
            let r_j = world[j].0;
            let moment = match bodies[j].joint.kind {
                JointKind::Revolute { axis_in_body } => {
                    let a = linear::mul_vector(&r_j, &axis_in_body);
                    linear::dot(&linear::vector_mul(&a, &inertia_about_origin), &a)
                }
                JointKind::Prismatic { .. } => 0.0,
                // A free body turns about its centre of mass (a rod spinning about its own
                // axis moves no mass, wherever the joint origin is): the inertia about the
                // subtree's centre of mass c, I_o − M (|c|² 1 − c cᵀ), c = h / M from o.
                JointKind::Free => {
                    let centre = if mass != 0.0 {
                        linear::scale_vector(&first_moment, 1.0 / mass)
                    } else {
                        [0.0; 3]
                    };
                    let about_centre = linear::sub(
                        &inertia_about_origin,
                        &linear::scale(&linear::parallel_axis(&centre), mass),
                    );
                    rules::principal_moments(&about_centre)[0]
                }
            };
            measured[j].mass = mass;
            // (`max` would pass over a NaN: an overflow is recorded on its own.)
            measured[j].moment = measured[j].moment.max(moment);
            measured[j].finite &= mass.is_finite() && moment.is_finite();
        }
    }
    let joints: HashMap<&str, &ResolvedJoint> = resolved
        .joints
        .iter()
        .map(|rj| (rj.name.text.as_str(), rj))
        .collect();
    for (body, measured) in bodies.iter().zip(&mut measured) {
        measured.armature = body.joint.armature.nominal(p);
        if let Some(joint) = joints.get(body.joint.name.as_str()) {
            rules::coordinate_has_inertia(&joint.name, &body.joint.kind, measured, scale, d);
        }
    }
}

/// Each tree body's subtree (the body and every body below it, with their welded parts)
/// at the poses `world`: its mass M, its first moment h = Σ m (c − o_j) and its inertia
/// about the body's joint origin o_j, in world axes,
/// Σ R I_G Rᵀ + m (|c − o_j|² 1 − (c − o_j)(c − o_j)ᵀ). Built from the leaves up, each
/// child's sums shifted from its origin to its parent's: with d = o_child − o_j and
/// h = Σ m (c − o_child), the first moment gains M d and the inertia
/// M (|d|² 1 − d dᵀ) + 2 (h·d) 1 − (h dᵀ + d hᵀ); linear in the number of bodies.
fn subtrees_about_origins(
    bodies: &[Body],
    p: &[f64],
    world: &[(Matrix3, Vector3)],
) -> Vec<(f64, Vector3, Matrix3)> {
    // (mass, first moment about the body's origin, inertia about it), world axes.
    let mut sums: Vec<(f64, Vector3, Matrix3)> = Vec::with_capacity(bodies.len());
    for (k, body) in bodies.iter().enumerate() {
        let r_k = world[k].0;
        let mut sum = (0.0, [0.0; 3], linear::ZERO);
        for part in &body.parts {
            let m = part.mass.nominal(p);
            // The mass centre relative to the body's origin.
            let c = linear::mul_vector(&r_k, &nominal3(&part.com_in_body, p));
            let i_g = linear::rotate(&r_k, &rules::nominal_matrix(&part.inertia_com_in_body, p));
            sum.0 += m;
            sum.1 = linear::add_vectors(&sum.1, &linear::scale_vector(&c, m));
            sum.2 = linear::add(
                &sum.2,
                &linear::add(&i_g, &linear::scale(&linear::parallel_axis(&c), m)),
            );
        }
        sums.push(sum);
    }
    for k in (0..bodies.len()).rev() {
        let Some(parent) = bodies[k].parent else {
            continue;
        };
        let (mass, h, inertia) = sums[k];
        let d = linear::sub_vectors(&world[k].1, &world[parent].1);
        let cross_terms = linear::sub(
            &linear::scale(&linear::IDENTITY, 2.0 * linear::dot(&h, &d)),
            &linear::add(&linear::outer(&h, &d), &linear::outer(&d, &h)),
        );
        let gained = linear::add(
            &inertia,
            &linear::add(
                &linear::scale(&linear::parallel_axis(&d), mass),
                &cross_terms,
            ),
        );
        let into = &mut sums[parent];
        into.0 += mass;
        into.1 = linear::add_vectors(
            &into.1,
            &linear::add_vectors(&h, &linear::scale_vector(&d, mass)),
        );
        into.2 = linear::add(&into.2, &gained);
    }
    sums
}
