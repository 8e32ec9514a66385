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
use super::matrix_from_rows;
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
/// allowed: a thin rod about its own axis, a point mass.)
pub(crate) fn inertia_is_positive(body: &BodySpec, errors: &mut Vec<ModelError>) {
    let m = &body.inertia.inertia_com_in_body;
    if !m.iter().all(|v| v.is_finite()) {
        return;
    }
    let p = principal_moments(m);
    let margin = slack(m.amax());
    if p[0] < -INERTIA_TOLERANCE * p[2].abs().max(f64::MIN_POSITIVE) - margin {
        errors.push(ModelError::InertiaNotPositive {
            body: body.name.clone(),
            principal_moments: p,
        });
    }
}

/// Rule: the principal moments satisfy the triangle inequality I1 + I2 ≥ I3, which every
/// real mass distribution does (I1 + I2 − I3 = 2∫ z² dm ≥ 0 in principal axes).
pub(crate) fn inertia_satisfies_triangle(body: &BodySpec, errors: &mut Vec<ModelError>) {
    let m = &body.inertia.inertia_com_in_body;
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
            body: body.name.clone(),
            principal_moments: p,
        });
    }
}

/// Rule: every number of a joint (axis, placement, armature, damping) is finite.
pub(crate) fn joint_numbers_are_finite(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    let item = || format!("joint `{}`", joint.name);
    let checks: [(&'static str, &[f64]); 5] = [
        ("axis", &joint.axis),
        ("translation", &joint.translation),
        ("rotation", joint.rotation_rows.as_flattened()),
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

/// Rule: a placement rotation is a proper rotation: RᵀR = 1 and det R = +1.
pub(crate) fn rotation_is_proper(joint: &JointSpec, errors: &mut Vec<ModelError>) {
    match rotation_defect(joint.rotation_rows) {
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
