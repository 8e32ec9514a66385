//! The rules a declared mechanism must satisfy, one function per rule.
//!
//! Each function states its rule in its doc comment, checks it, and records every violation
//! at the span of the offending tokens with the numbers involved and a hint. Physical rules
//! use the parameters' nominal values. Tolerances are relative, as in the runtime's own
//! validation, so that numbers rounded by hand or by a URDF exporter pass.

use super::resolve::{Resolved, ResolvedBody, ResolvedJoint};
use super::value::{nominal33, Mat3};
use super::{Diagnostics, Outputs};
use crate::syntax::{self, JointKind, Name};
use nalgebra::{Matrix3, SymmetricEigen};
use proc_macro2::Span;
use std::collections::HashMap;

/// Relative tolerance of the inertia rules.
const INERTIA_TOLERANCE: f64 = 1e-9;
/// Absolute tolerance of |RᵀR − 1|.
const ROTATION_TOLERANCE: f64 = 1e-6;
/// The name of the fixed world frame.
pub(crate) const GROUND: &str = "ground";

/// Runs every rule that needs only the resolved declaration.
pub(crate) fn check_all(mechanism: &syntax::Mechanism, resolved: &Resolved, d: &mut Diagnostics) {
    let p = resolved.nominal_parameters();
    parameters_are_used(mechanism, resolved, d);
    names_are_unique(mechanism, d);
    for body in &resolved.bodies {
        let inertia = matrix(&nominal33(&body.inertia, &p));
        mass_is_not_negative(body, body.mass.nominal(&p), d);
        if inertia_is_symmetric(body, &inertia, d) {
            inertia_is_positive(body, &inertia, d);
            if !resolved.skip_triangle_inequality {
                inertia_satisfies_triangle(body, &inertia, d);
            }
        }
    }
    for joint in &resolved.joints {
        axis_is_nonzero(joint, d);
        rotation_is_proper(joint, d);
        joint_coefficients_are_not_negative(joint, &p, d);
    }
    joints_name_declared_bodies(mechanism, d);
    body_has_one_parent(mechanism, d);
    bodies_reach_the_ground(mechanism, d);
    free_joint_is_on_the_ground(mechanism, d);
    loads_act_on_declared_bodies(mechanism, d);
    dynamics_need_a_degree_of_freedom(mechanism, resolved, d);
}

fn matrix(m: &[[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| m[i][j])
}

/// Rule: every number is finite (no NaN, no infinity, e.g. from `1.0 / 0.0`).
pub(crate) fn number_is_finite(value: f64, span: Span, d: &mut Diagnostics) {
    if !value.is_finite() {
        d.error(
            span,
            format!("this number evaluates to {value}; every number must be finite"),
        );
    }
}

/// Rule: a number names only declared parameters.
pub(crate) fn report_undeclared_parameter(name: &str, span: Span, d: &mut Diagnostics) {
    d.error(
        span,
        format!(
            "`{name}` is not a declared parameter; declare it with `parameters: [{name} = <nominal value>];` \
             or write a number"
        ),
    );
}

/// Rule: axes, rotations, gravity and shape dimensions are constants (they select the
/// structure of the generated code); parameters may appear in masses, mass centres,
/// inertias, joint offsets, armature and damping.
pub(crate) fn report_parameter_not_allowed(
    name: &str,
    what: &str,
    span: Span,
    d: &mut Diagnostics,
) {
    d.error(
        span,
        format!("parameter `{name}` cannot be used in {what}: axes, rotations, gravity and shape dimensions must be constants"),
    );
}

/// Rule: an axis-angle rotation has a nonzero, finite axis.
pub(crate) fn report_zero_rotation_axis(span: Span, d: &mut Diagnostics) {
    d.error(
        span,
        "the rotation axis has zero length; give a nonzero direction",
    );
}

/// Rule: shape dimensions (lengths, radii) are not negative.
pub(crate) fn shape_dimension_is_not_negative(value: f64, span: Span, d: &mut Diagnostics) {
    if value < 0.0 {
        d.error(
            span,
            format!("a shape dimension is {value} m, which is negative"),
        );
    }
}

/// Rule: required fields are present (a body's mass and inertia, a moving joint's axis).
pub(crate) fn report_missing_field(
    item: &Name,
    field: &str,
    example: &str,
    span: Span,
    d: &mut Diagnostics,
) {
    d.error(
        span,
        format!(
            "`{}` has no `{field}`; add for example `{example}`",
            item.text
        ),
    );
    let _ = item.span;
}

/// Rule: fixed and free joints take no axis.
pub(crate) fn report_axis_not_allowed(kind: JointKind, span: Span, d: &mut Diagnostics) {
    let kind = match kind {
        JointKind::Fixed => "fixed",
        _ => "free",
    };
    d.error(span, format!("a {kind} joint has no axis; remove `axis`"));
}

/// Rule: every requested output is one the generator knows.
pub(crate) fn output_is_known(outputs: &mut Outputs, name: &Name, d: &mut Diagnostics) {
    if !outputs.enable(&name.text) {
        d.error(
            name.span,
            format!(
                "unknown output `{}`; expected one of {}",
                name.text,
                Outputs::NAMES.join(", ")
            ),
        );
    }
}

/// Rule: every declared parameter is used somewhere (an unused one is almost always a typo).
fn parameters_are_used(mechanism: &syntax::Mechanism, resolved: &Resolved, d: &mut Diagnostics) {
    for (p, used) in mechanism.parameters.iter().zip(&resolved.parameter_used) {
        if !used {
            d.error(
                p.name.span,
                format!("parameter `{}` is declared but never used", p.name.text),
            );
        }
    }
}

/// Rule: bodies, joints, loads and parameters have unique names, and no body is named
/// `ground`.
fn names_are_unique(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let groups: [(&str, Vec<&Name>); 4] = [
        ("body", mechanism.bodies.iter().map(|b| &b.name).collect()),
        ("joint", mechanism.joints.iter().map(|j| &j.name).collect()),
        ("load", mechanism.loads.iter().map(|l| &l.name).collect()),
        (
            "parameter",
            mechanism.parameters.iter().map(|p| &p.name).collect(),
        ),
    ];
    for (kind, names) in groups {
        let mut seen: HashMap<&str, &Name> = HashMap::new();
        for name in names {
            if kind == "body" && name.text == GROUND {
                d.error(
                    name.span,
                    "`ground` is the fixed world frame; a body cannot be named `ground`",
                );
            } else if seen.insert(&name.text, name).is_some() {
                d.error(
                    name.span,
                    format!("a {kind} named `{}` is already declared", name.text),
                );
            }
        }
    }
}

/// Rule: a body's mass is not negative.
fn mass_is_not_negative(body: &ResolvedBody, mass: f64, d: &mut Diagnostics) {
    if mass < 0.0 {
        d.error(
            body.mass_span,
            format!(
                "body `{}` has mass {mass} kg; a mass must be ≥ 0",
                body.name.text
            ),
        );
    }
}

/// Rule: I_G is symmetric (I_xy = I_yx, ...). Returns whether it is.
fn inertia_is_symmetric(body: &ResolvedBody, inertia: &Matrix3<f64>, d: &mut Diagnostics) -> bool {
    let scale = inertia.amax().max(f64::MIN_POSITIVE);
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (inertia[(i, j)] - inertia[(j, i)]).abs() > INERTIA_TOLERANCE * scale {
            d.error(
                body.inertia_span,
                format!(
                    "the inertia of body `{}` is not symmetric: I[{i}][{j}] = {} but I[{j}][{i}] = {}; \
                     give the same product of inertia on both sides",
                    body.name.text,
                    inertia[(i, j)],
                    inertia[(j, i)]
                ),
            );
            return false;
        }
    }
    true
}

/// Principal moments of a symmetric matrix, ascending.
pub(crate) fn principal_moments(inertia: &Matrix3<f64>) -> [f64; 3] {
    let mut p: [f64; 3] = SymmetricEigen::new(*inertia).eigenvalues.into();
    p.sort_by(f64::total_cmp);
    p
}

/// Rule: I_G is positive semi-definite: every principal moment ≥ 0 (a thin rod has a zero
/// moment about its axis, a point mass all zero).
fn inertia_is_positive(body: &ResolvedBody, inertia: &Matrix3<f64>, d: &mut Diagnostics) {
    let p = principal_moments(inertia);
    if p[0] < -INERTIA_TOLERANCE * p[2].abs().max(f64::MIN_POSITIVE) {
        d.error(
            body.inertia_span,
            format!(
                "the inertia of body `{}` is not positive semi-definite: its principal moments are \
                 {}, {}, {} kg·m²; check the signs of the products of inertia",
                body.name.text, p[0], p[1], p[2]
            ),
        );
    }
}

/// Rule: the principal moments satisfy I1 + I2 ≥ I3, as every real mass distribution does
/// (I1 + I2 − I3 = 2∫z² dm in principal axes). Waived by `allow: [triangle_inequality]`.
fn inertia_satisfies_triangle(body: &ResolvedBody, inertia: &Matrix3<f64>, d: &mut Diagnostics) {
    let p = principal_moments(inertia);
    if p[0] >= 0.0 && p[0] + p[1] < p[2] - INERTIA_TOLERANCE * (p[0] + p[1] + p[2]) {
        d.error(
            body.inertia_span,
            format!(
                "the principal moments of body `{}` ({}, {}, {} kg·m²) violate the triangle inequality \
                 I1 + I2 ≥ I3 ({} < {}): no mass distribution has this inertia \
                 (`allow: [triangle_inequality];` accepts it anyway)",
                body.name.text,
                p[0],
                p[1],
                p[2],
                p[0] + p[1],
                p[2]
            ),
        );
    }
}

/// Rule: a revolute or prismatic axis has nonzero length.
fn axis_is_nonzero(joint: &ResolvedJoint, d: &mut Diagnostics) {
    if let Some((axis, span)) = joint.axis {
        let norm = axis.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm < 1e-12 {
            d.error(
                span,
                format!(
                    "joint `{}` has axis [{}, {}, {}], which has zero length; give a direction such as `z`",
                    joint.name.text, axis[0], axis[1], axis[2]
                ),
            );
        }
    }
}

/// Rule: a placement rotation is a proper rotation: RᵀR = 1 and det R = +1.
fn rotation_is_proper(joint: &ResolvedJoint, d: &mut Diagnostics) {
    let r = matrix(&joint.rotation);
    let deviation = (r.transpose() * r - Matrix3::identity()).amax();
    if deviation > ROTATION_TOLERANCE {
        d.error(
            joint.rotation_span,
            format!(
                "the rotation of joint `{}` is not orthonormal (max |RᵀR − 1| = {deviation:e}); \
                 give a rotation matrix, rpy(r, p, y) or axis_angle([x, y, z], angle)",
                joint.name.text
            ),
        );
    } else if r.determinant() < 0.0 {
        d.error(
            joint.rotation_span,
            format!(
                "the rotation of joint `{}` has determinant {}: it is a reflection, not a rotation",
                joint.name.text,
                r.determinant()
            ),
        );
    }
}

/// Rule: armature and damping are not negative.
fn joint_coefficients_are_not_negative(joint: &ResolvedJoint, p: &[f64], d: &mut Diagnostics) {
    for (field, (value, span)) in [("armature", &joint.armature), ("damping", &joint.damping)] {
        let v = value.nominal(p);
        if v < 0.0 {
            d.error(
                *span,
                format!(
                    "joint `{}` has {field} {v}; it must be ≥ 0",
                    joint.name.text
                ),
            );
        }
    }
}

/// Rule: a joint's parent and child are declared bodies (or `ground` for the parent), and
/// differ.
fn joints_name_declared_bodies(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let declared = |n: &str| mechanism.bodies.iter().any(|b| b.name.text == n);
    for joint in &mechanism.joints {
        if joint.parent.text != GROUND && !declared(&joint.parent.text) {
            d.error(
                joint.parent.span,
                format!(
                    "unknown parent `{}`: no body has this name (the fixed frame is `ground`)",
                    joint.parent.text
                ),
            );
        }
        if joint.child.text == GROUND {
            d.error(
                joint.child.span,
                "the ground cannot be a joint's child; write `ground -> body`",
            );
        } else if !declared(&joint.child.text) {
            d.error(
                joint.child.span,
                format!(
                    "unknown child `{}`: no body has this name",
                    joint.child.text
                ),
            );
        } else if joint.child.text == joint.parent.text {
            d.error(
                joint.child.span,
                format!(
                    "joint `{}` attaches body `{}` to itself",
                    joint.name.text, joint.child.text
                ),
            );
        }
    }
}

/// Rule: every body is the child of at most one joint (a second parent would close a loop,
/// which a tree cannot express).
fn body_has_one_parent(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let mut first: HashMap<&str, &syntax::Joint> = HashMap::new();
    for joint in &mechanism.joints {
        if let Some(earlier) = first.insert(&joint.child.text, joint) {
            d.error(
                joint.child.span,
                format!(
                    "body `{}` already has a parent through joint `{}`: a body has one parent in a tree \
                     (closed loops are not supported here)",
                    joint.child.text, earlier.name.text
                ),
            );
            first.insert(&joint.child.text, earlier);
        }
    }
}

/// Rule: every body is connected to the ground through a chain of joints (no body left
/// floating, no cycle of joints that never reaches the ground).
fn bodies_reach_the_ground(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let parent_of: HashMap<&str, &str> = mechanism
        .joints
        .iter()
        .map(|j| (j.child.text.as_str(), j.parent.text.as_str()))
        .collect();
    let declared = |n: &str| mechanism.bodies.iter().any(|b| b.name.text == n);
    let mut reported_cycle: Vec<&str> = Vec::new();
    for body in &mechanism.bodies {
        let mut walk = body.name.text.as_str();
        let mut path = vec![walk];
        loop {
            match parent_of.get(walk) {
                None => {
                    if walk == body.name.text {
                        d.error(
                            body.name.span,
                            format!(
                                "body `{}` is not connected to the ground: no joint has it as child; \
                                 add a joint such as `joint j: fixed(ground -> {})`",
                                body.name.text, body.name.text
                            ),
                        );
                    }
                    break;
                }
                Some(&p) if p == GROUND || !declared(p) => break,
                Some(&p) if path.contains(&p) => {
                    if !reported_cycle.contains(&p) {
                        let start = path.iter().position(|b| *b == p).unwrap_or(0);
                        let cycle = &path[start..];
                        reported_cycle.extend_from_slice(cycle);
                        d.error(
                            body.name.span,
                            format!(
                                "joints form a cycle through bodies {} that never reaches the ground",
                                cycle.iter().map(|b| format!("`{b}`")).collect::<Vec<_>>().join(", ")
                            ),
                        );
                    }
                    break;
                }
                Some(&p) => {
                    path.push(p);
                    walk = p;
                }
            }
        }
    }
}

/// Rule: a free joint connects the ground to a body (a floating base), nothing else.
fn free_joint_is_on_the_ground(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    for joint in &mechanism.joints {
        if joint.kind == JointKind::Free && joint.parent.text != GROUND {
            d.error(
                joint.parent.span,
                format!(
                    "a free joint gives a floating base six degrees of freedom relative to the ground; \
                     its parent must be `ground`, not `{}`",
                    joint.parent.text
                ),
            );
        }
    }
}

/// Rule: a load acts on a declared body.
fn loads_act_on_declared_bodies(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    for load in &mechanism.loads {
        if !mechanism
            .bodies
            .iter()
            .any(|b| b.name.text == load.body.text)
        {
            d.error(
                load.body.span,
                format!(
                    "load `{}` acts on unknown body `{}`",
                    load.name.text, load.body.text
                ),
            );
        }
    }
}

/// Rule: dynamics outputs need at least one degree of freedom.
fn dynamics_need_a_degree_of_freedom(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    d: &mut Diagnostics,
) {
    let moving = mechanism.joints.iter().any(|j| j.kind != JointKind::Fixed);
    if !moving && resolved.outputs.any_dynamics() {
        let span = match &mechanism.outputs {
            Some(names) if !names.is_empty() => names[0].span,
            _ => mechanism.name.span(),
        };
        d.error(
            span,
            "the mechanism has no degree of freedom (every joint is fixed), so it has no dynamics \
             to generate; add a moving joint or ask only for `energy`",
        );
    }
}

/// Rule: every joint coordinate has inertia: a revolute joint's subtree has a nonzero moment
/// of inertia about the joint axis, a prismatic joint's subtree has mass, a free joint's
/// subtree has mass and a nonsingular rotational inertia, in at least one of the
/// configurations sampled. Otherwise M(q) is singular for every q.
pub(crate) fn coordinate_has_inertia(
    joint: &Name,
    kind_span: Span,
    inertia_about_axis: f64,
    scale: f64,
    d: &mut Diagnostics,
) {
    if inertia_about_axis.abs() <= 1e-12 * scale.max(f64::MIN_POSITIVE) || inertia_about_axis == 0.0
    {
        let _ = kind_span;
        d.error(
            joint.span,
            format!(
                "the coordinate of joint `{}` has no inertia: nothing it moves has mass or inertia \
                 along its motion, so the mass matrix M(q) is singular; add mass to the bodies it \
                 moves or make the joint fixed",
                joint.text
            ),
        );
    }
}

/// Nominal-valued matrix helper for other modules.
pub(crate) fn nominal_matrix(m: &Mat3, p: &[f64]) -> Matrix3<f64> {
    matrix(&nominal33(m, p))
}
