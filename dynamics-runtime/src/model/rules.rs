//! The validation rules of a declared mechanism, one function per rule.
//!
//! Each rule pushes its findings onto a list, so a model reports all of its errors at once.
//! Tolerances are relative to the magnitude of the numbers involved, so rounding in data
//! typed by hand or converted from URDF passes while real mistakes do not.
//!
//! # Agreement with the compiler
//!
//! `dynamics-codegen` checks the same inertia and rotation rules at compile time, with its
//! own closed-form eigenvalue routine (the runtime cannot depend on the compiler, and the
//! compiler does not link nalgebra). The two solvers' principal moments differ by a few ulps
//! of ‖I‖, so near a tolerance edge one could accept what the other rejects, and the
//! generated `Mechanism::model()` would then panic on a mechanism that compiled. The
//! compiler is the strict judge; the runtime's inertia and rotation rules reject only beyond
//! the same tolerances *plus* [`SOLVER_SLACK`] · ε · ‖I‖ (‖R‖ = 1 for rotations), a margin
//! well above the two solvers' disagreement and far below the tolerances themselves, so that
//! whatever the compiler accepts the runtime accepts too. `tests/rule_agreement.rs` checks
//! this with matrices bisected onto the edges.

use super::builder::JointType;
use super::builder::{BodySpec, FrameSpec, JointSpec};
use super::error::ModelError;
use super::{matrix_from_rows, Placement, GROUND};
use nalgebra::{Matrix3, SymmetricEigen};

/// Relative tolerance of the inertia rules (symmetry, semi-definiteness, triangle).
const INERTIA_TOLERANCE: f64 = 1e-9;
/// Absolute tolerance of |RᵀR − 1| for placement rotations.
const ROTATION_TOLERANCE: f64 = 1e-6;
/// The margin, in units of ε · ‖I‖, by which the inertia and rotation rules widen their
/// tolerances on the rejecting side only (see the module documentation): above the
/// disagreement of the compiler's and nalgebra's eigenvalue solvers (a few ε · ‖I‖), below
/// anything that matters against the 1e-9 relative tolerance.
const SOLVER_SLACK: f64 = 64.0;

/// The rejecting side's extra margin for a matrix whose largest entry is `scale`.
fn slack(scale: f64) -> f64 {
    SOLVER_SLACK * f64::EPSILON * scale
}

/// Rule: every number of a body (mass, mass centre, inertia) is finite.
pub(crate) fn body_numbers_are_finite(body: &BodySpec, errors: &mut Vec<ModelError>) {
    let item = || format!("body `{}`", body.name);
    let i = &body.inertia;
    if !i.mass.is_finite() {
        errors.push(ModelError::NonFinite {
            item: item(),
            field: "mass",
            value: i.mass,
        });
    }
    if let Some(v) = i.com_in_body.iter().find(|v| !v.is_finite()) {
        errors.push(ModelError::NonFinite {
            item: item(),
            field: "mass centre",
            value: *v,
        });
    }
    if let Some(v) = i.inertia_com_in_body.iter().find(|v| !v.is_finite()) {
        errors.push(ModelError::NonFinite {
            item: item(),
            field: "inertia",
            value: *v,
        });
    }
}

/// Rule: a body's mass is not negative (zero is allowed: a frame, or a massless link that
/// carries other bodies).
pub(crate) fn mass_is_not_negative(body: &BodySpec, errors: &mut Vec<ModelError>) {
    if body.inertia.mass < 0.0 {
        errors.push(ModelError::NegativeMass {
            body: body.name.clone(),
            mass: body.inertia.mass,
        });
    }
}

/// Rule: I_G is symmetric, I[i][j] = I[j][i] to a relative tolerance.
pub(crate) fn inertia_is_symmetric(body: &BodySpec, errors: &mut Vec<ModelError>) {
    let m = &body.inertia.inertia_com_in_body;
    let scale = m.amax().max(f64::MIN_POSITIVE);
    for (row, col) in [(0, 1), (0, 2), (1, 2)] {
        let (upper, lower) = (m[(row, col)], m[(col, row)]);
        if (upper - lower).abs() > INERTIA_TOLERANCE * scale + slack(scale) {
            errors.push(ModelError::InertiaNotSymmetric {
                body: body.name.clone(),
                row,
                col,
                upper,
                lower,
            });
            return;
        }
    }
}

/// Principal moments of a symmetric inertia, ascending.
pub(crate) fn principal_moments(inertia: &Matrix3<f64>) -> [f64; 3] {
    let symmetric = (inertia + inertia.transpose()) * 0.5;
    let mut p: [f64; 3] = SymmetricEigen::new(symmetric).eigenvalues.into();
    p.sort_by(f64::total_cmp);
    p
}

/// Rule: I_G is positive semi-definite: every principal moment is ≥ 0. (Zero moments are
/// allowed: a thin rod about its own axis, a point mass.) `body` and `welded` name the
/// body judged and the bodies merged into it.
fn inertia_is_positive(
    body: &str,
    welded: &[String],
    m: &Matrix3<f64>,
    errors: &mut Vec<ModelError>,
) {
    if !m.iter().all(|v| v.is_finite()) {
        return;
    }
    let p = principal_moments(m);
    let margin = slack(m.amax());
    if p[0] < -INERTIA_TOLERANCE * p[2].abs().max(f64::MIN_POSITIVE) - margin {
        errors.push(ModelError::InertiaNotPositive {
            body: body.to_owned(),
            welded: welded.to_vec(),
            principal_moments: p,
        });
    }
}

/// Rule: the principal moments satisfy the triangle inequality I1 + I2 ≥ I3, which every
/// real mass distribution does (I1 + I2 − I3 = 2∫ z² dm ≥ 0 in principal axes).
fn inertia_satisfies_triangle(
    body: &str,
    welded: &[String],
    m: &Matrix3<f64>,
    errors: &mut Vec<ModelError>,
) {
    if !m.iter().all(|v| v.is_finite()) {
        return;
    }
    let p = principal_moments(m);
    let margin = slack(m.amax());
    // Checked only where the positivity rule clearly passes (the compiler checks the
    // triangle wherever positivity passes, so it has judged every such inertia too).
    let positive = p[0] >= -INERTIA_TOLERANCE * p[2].abs().max(f64::MIN_POSITIVE) + margin;
    if positive && p[0] + p[1] < p[2] - INERTIA_TOLERANCE * (p[0] + p[1] + p[2]) - margin {
        errors.push(ModelError::TriangleInequality {
            body: body.to_owned(),
            welded: welded.to_vec(),
            principal_moments: p,
        });
    }
}

/// A body of a group welded together: its index and its pose in the group's frame (the
/// root body's, or the world's for the bodies welded to the ground).
type Member = (usize, Placement);

/// Whether a body's numbers are fit for the merged-inertia rules: finite, its mass not
/// negative, its inertia symmetric (otherwise other rules report it, and the merged body
/// is not judged).
fn judgeable(body: &BodySpec) -> bool {
    let mut errors = Vec::new();
    body_numbers_are_finite(body, &mut errors);
    mass_is_not_negative(body, &mut errors);
    inertia_is_symmetric(body, &mut errors);
    errors.is_empty()
}

/// Rule: the inertia of each body of the dynamics, the declared bodies welded together
/// through fixed joints merged into one (a group welded to the ground is one too), is
/// positive semi-definite and, unless `triangle` is false, satisfies the triangle
/// inequality: a link's placeholder inertia welded to a real body is accepted, a merged body
/// that is not physical is not. A body welded to nothing is judged as declared.
///
/// Each body walks up through the fixed joint naming it as child (the first such joint) to
/// a body moved otherwise, or to the ground, composing the placements; a walk that meets an
/// unknown parent or loops (rules of their own report both) stops there. The groups are
/// judged in the order of their first declared member; a group of several with a member
/// that is not [`judgeable`] is not judged.
pub(crate) fn merged_inertias_are_physical(
    bodies: &[BodySpec],
    joints: &[JointSpec],
    triangle: bool,
    errors: &mut Vec<ModelError>,
) {
    let index = |name: &str| bodies.iter().position(|b| b.name == name);
    let parent_joint = |name: &str| {
        joints
            .iter()
            .find(|j| j.child == name && j.parent != j.child)
    };
    let mut groups: Vec<(Option<usize>, Vec<Member>)> = Vec::new();
    for b in 0..bodies.len() {
        let (mut at, mut pose, mut root) = (b, Placement::identity(), Some(b));
        for _ in 0..=bodies.len() {
            let Some(joint) = parent_joint(&bodies[at].name).filter(|j| j.kind == JointType::Fixed)
            else {
                root = Some(at);
                break;
            };
            let mut placement = Placement::new(joint.translation, joint.rotation_rows);
            if let Some(frame) = joint.child_frame() {
                placement = placement.compose(&frame);
            }
            pose = placement.compose(&pose);
            if joint.parent == GROUND {
                root = None;
                break;
            }
            match index(&joint.parent) {
                Some(parent) => at = parent,
                None => {
                    root = Some(at);
                    break;
                }
            }
        }
        if root == Some(b) {
            pose = Placement::identity();
        }
        match groups.iter_mut().find(|(r, _)| *r == root) {
            Some((_, members)) => members.push((b, pose)),
            None => groups.push((root, vec![(b, pose)])),
        }
    }
    for (root, mut members) in groups {
        if let Some(k) = members.iter().position(|(b, _)| Some(*b) == root) {
            let first = members.remove(k);
            members.insert(0, first);
        }
        // A body alone is judged as before merging was considered; merged ones only when
        // each is judgeable.
        if members.len() > 1 && !members.iter().all(|(b, _)| judgeable(&bodies[*b])) {
            continue;
        }
        let inertia = match members.as_slice() {
            [(only, _)] => bodies[*only].inertia.inertia_com_in_body,
            _ => {
                let merged = members
                    .iter()
                    .map(|(b, pose)| bodies[*b].inertia.transformed(pose))
                    .reduce(|sum, part| sum.combined(&part));
                match merged {
                    Some(merged) => merged.inertia_com_in_body,
                    None => continue,
                }
            }
        };
        let Some(((first, _), rest)) = members.split_first() else {
            continue;
        };
        let name = &bodies[*first].name;
        let welded: Vec<String> = rest.iter().map(|(b, _)| bodies[*b].name.clone()).collect();
        inertia_is_positive(name, &welded, &inertia, errors);
        if triangle {
            inertia_satisfies_triangle(name, &welded, &inertia, errors);
        }
    }
}

/// Rule: every number of a joint (axis, placement, armature, damping) is finite.
pub(crate) fn joint_numbers_are_finite(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    let item = || format!("joint `{}`", joint.name);
    let checks: [(&'static str, &[f64]); 7] = [
        ("axis", &joint.axis),
        ("translation", &joint.translation),
        ("rotation", joint.rotation_rows.as_flattened()),
        ("child translation", &joint.child_translation),
        ("child rotation", joint.child_rotation_rows.as_flattened()),
        ("armature", std::slice::from_ref(&joint.armature)),
        ("damping", std::slice::from_ref(&joint.damping)),
    ];
    for (field, values) in checks {
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            errors.push(ModelError::NonFinite {
                item: item(),
                field,
                value: *v,
            });
        }
    }
}

/// The factor that brings an axis's largest |component| m to 1 when a square of m would
/// overflow or underflow (m above 1e150 or below 1e-150), else 1 (ordinary axes are
/// computed as before, bit for bit).
fn axis_rescale(axis: [f64; 3]) -> f64 {
    let m = axis.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
    if m.is_finite() && m > 0.0 && !(1e-150..=1e150).contains(&m) {
        m
    } else {
        1.0
    }
}

/// The length of an axis, as m·|a/m| with m from [`axis_rescale`], so that components above
/// 1e154 (whose squares overflow) keep a finite length.
fn axis_length(axis: [f64; 3]) -> f64 {
    let m = axis_rescale(axis);
    m * axis.iter().map(|a| (a / m) * (a / m)).sum::<f64>().sqrt()
}

/// An axis divided by its length, rescaled first (see [`axis_rescale`]).
pub(crate) fn unit_axis(axis: [f64; 3]) -> nalgebra::Vector3<f64> {
    let m = axis_rescale(axis);
    nalgebra::Vector3::from(axis.map(|a| a / m)).normalize()
}

/// Rule: a revolute or prismatic axis has nonzero length (it is normalized afterwards).
pub(crate) fn axis_is_nonzero(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    let moving = matches!(joint.kind, JointType::Revolute | JointType::Prismatic);
    let norm = axis_length(joint.axis);
    if moving && norm.is_finite() && norm < 1e-12 {
        errors.push(ModelError::ZeroAxis {
            joint: joint.name.clone(),
            axis: joint.axis,
        });
    }
}

/// What is wrong with a placement rotation, if anything.
enum RotationDefect {
    /// max |RᵀR − 1| beyond the tolerance.
    NotOrthonormal(f64),
    /// Orthonormal, but det R < 0: a reflection.
    Improper(f64),
}

/// Checks that R (given by rows, finite) is a proper rotation: RᵀR = 1 and det R = +1.
/// `None` for a non-finite matrix, which the finiteness rules report.
fn rotation_defect(rows: [[f64; 3]; 3]) -> Option<RotationDefect> {
    let r = matrix_from_rows(rows);
    if !r.iter().all(|v| v.is_finite()) {
        return None;
    }
    let deviation = (r.transpose() * r - Matrix3::identity()).amax();
    if deviation > ROTATION_TOLERANCE + slack(1.0) {
        Some(RotationDefect::NotOrthonormal(deviation))
    } else if r.determinant() < 0.0 {
        Some(RotationDefect::Improper(r.determinant()))
    } else {
        None
    }
}

/// Rule: a placement rotation is a proper rotation: RᵀR = 1 and det R = +1 (the joint
/// frame's, and the child's frame's when [`JointSpec::with_child_frame`] gave one).
pub(crate) fn rotation_is_proper(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    rotation_rows_are_proper(joint, joint.rotation_rows, errors);
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    if joint.child_rotation_rows != identity {
        rotation_rows_are_proper(joint, joint.child_rotation_rows, errors);
    }
}

/// [`rotation_is_proper`] for one of a joint's rotations.
fn rotation_rows_are_proper(joint: &JointSpec, rows: [[f64; 3]; 3], errors: &mut Vec<ModelError>) {
    match rotation_defect(rows) {
        Some(RotationDefect::NotOrthonormal(deviation)) => {
            errors.push(ModelError::RotationNotOrthonormal {
                joint: joint.name.clone(),
                deviation,
            })
        }
        Some(RotationDefect::Improper(determinant)) => errors.push(ModelError::RotationImproper {
            joint: joint.name.clone(),
            determinant,
        }),
        None => {}
    }
}

/// Rule: every number of a declared frame's placement is finite.
pub(crate) fn frame_numbers_are_finite(frame: &FrameSpec, errors: &mut Vec<ModelError>) {
    let checks: [(&'static str, &[f64]); 2] = [
        ("translation", &frame.translation),
        ("rotation", frame.rotation_rows.as_flattened()),
    ];
    for (field, values) in checks {
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            errors.push(ModelError::NonFinite {
                item: format!("frame `{}`", frame.name),
                field,
                value: *v,
            });
        }
    }
}

/// Rule: a declared frame's rotation is a proper rotation, with a joint's tolerance and slack
/// (so that the runtime accepts whatever frame rotation the compiler accepts, as for joints).
pub(crate) fn frame_rotation_is_proper(frame: &FrameSpec, errors: &mut Vec<ModelError>) {
    match rotation_defect(frame.rotation_rows) {
        Some(RotationDefect::NotOrthonormal(deviation)) => {
            errors.push(ModelError::FrameRotationNotOrthonormal {
                frame: frame.name.clone(),
                deviation,
            })
        }
        Some(RotationDefect::Improper(determinant)) => {
            errors.push(ModelError::FrameRotationImproper {
                frame: frame.name.clone(),
                determinant,
            })
        }
        None => {}
    }
}

/// Rule: armature (rotor inertia) and viscous damping are not negative.
pub(crate) fn joint_coefficients_are_not_negative(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    for (field, value) in [("armature", joint.armature), ("damping", joint.damping)] {
        if value < 0.0 {
            errors.push(ModelError::NegativeJointCoefficient {
                joint: joint.name.clone(),
                field,
                value,
            });
        }
    }
}
