//! Resolution: numbers to affine values of the declared parameters, inertia forms and shapes
//! to I_G, rotations to matrices, output and `allow` names to flags.
//!
//! Resolution reports what it cannot resolve (undeclared parameters, parameters where only a
//! constant makes sense, missing fields) and carries every span on, for the rules.

use super::dh;
use super::linear;
use super::resolved::{Resolved, ResolvedBody, ResolvedFrame, ResolvedJoint, ResolvedLimits};
use super::value::{self, rotate_matrix, Mat3, Value, Vec3};
use super::{rules, Diagnostics, Outputs, Parameter};
use crate::syntax::{self, Axis, InertiaForm, Number, NumberValue, Rotation, ShapeKind, SpanRange};

struct Resolver<'d> {
    names: Vec<String>,
    /// The parameters' nominal values (0 for one whose nominal value is reported).
    nominal: Vec<f64>,
    used: Vec<bool>,
    /// Rotation entries within it of 0 or ±1 are made exact (`rotation_tolerance:`).
    rotation_tolerance: f64,
    diagnostics: &'d mut Diagnostics,
}

impl Resolver<'_> {
    /// A number as an affine value; undeclared parameters are reported.
    fn value(&mut self, number: &Number) -> Value {
        match &number.value {
            NumberValue::Constant(c) => {
                rules::number_is_finite(*c, number.span, self.diagnostics);
                Value::constant(*c)
            }
            NumberValue::Parameter { name, coefficient } => {
                match self.names.iter().position(|n| n == name) {
                    Some(k) => {
                        self.used[k] = true;
                        // Finite as a coefficient (`m / 0.0` is not) and at the nominal value
                        // (`1e308 * m` with m = 1e308 is not), where `Mechanism::model()`
                        // evaluates it: the runtime's `ModelBuilder` would reject it there.
                        let value = if coefficient.is_finite() {
                            coefficient * self.nominal[k]
                        } else {
                            *coefficient
                        };
                        rules::number_is_finite(value, number.span, self.diagnostics);
                        Value::parameter(k, *coefficient)
                    }
                    None => {
                        rules::report_undeclared_parameter(name, number.span, self.diagnostics);
                        Value::constant(0.0)
                    }
                }
            }
        }
    }

    /// A number that must be a constant (axes, rotations, shape dimensions).
    fn constant(&mut self, number: &Number, what: &str) -> f64 {
        match &number.value {
            NumberValue::Constant(c) => {
                rules::number_is_finite(*c, number.span, self.diagnostics);
                *c
            }
            NumberValue::Parameter { name, .. } => {
                rules::report_parameter_not_allowed(name, what, number.span, self.diagnostics);
                if let Some(k) = self.names.iter().position(|n| n == name) {
                    self.used[k] = true;
                }
                0.0
            }
        }
    }

    /// A number that must be a constant, where another stage reports a parameter: checked
    /// finite, a parameter counted as used (so it is not also reported as unused).
    fn constant_checked_elsewhere(&mut self, number: &Number) {
        match &number.value {
            NumberValue::Constant(c) => rules::number_is_finite(*c, number.span, self.diagnostics),
            NumberValue::Parameter { name, .. } => {
                if let Some(k) = self.names.iter().position(|n| n == name) {
                    self.used[k] = true;
                }
            }
        }
    }

    fn vector(&mut self, v: &syntax::Vector) -> Vec3 {
        std::array::from_fn(|i| self.value(&v.components[i]))
    }

    fn constant_vector(&mut self, v: &syntax::Vector, what: &str) -> [f64; 3] {
        std::array::from_fn(|i| self.constant(&v.components[i], what))
    }

    fn axis(&mut self, axis: &Axis) -> [f64; 3] {
        self.constant_vector(&axis.direction, "an axis")
    }

    /// A rotation matrix (rows) from any rotation form.
    fn rotation(&mut self, rotation: &Rotation) -> [[f64; 3]; 3] {
        match rotation {
            Rotation::Rpy(angles, _) => {
                let [r, p, y] = std::array::from_fn(|i| {
                    let angle = self.constant(&angles[i], "a rotation");
                    value::snapped_angle(angle, self.rotation_tolerance)
                });
                rows(&linear::rotation_from_rpy(r, p, y))
            }
            Rotation::AxisAngle(axis, angle, _) => {
                let a = self.constant_vector(axis, "a rotation");
                let angle = value::snapped_angle(
                    self.constant(angle, "a rotation"),
                    self.rotation_tolerance,
                );
                let length = linear::norm(&a);
                if length == 0.0 || !length.is_finite() {
                    rules::report_zero_rotation_axis(rotation.span(), self.diagnostics);
                    return IDENTITY;
                }
                rows(&linear::rotation_from_axis_angle(
                    &linear::normalize(&a),
                    angle,
                ))
            }
            // Entry by entry: the declaration's tolerance (1e-15 by default).
            Rotation::Matrix(m) => {
                let entries = std::array::from_fn(|i| {
                    std::array::from_fn(|j| self.constant(&m.rows[i][j], "a rotation"))
                });
                value::snapped_within(&entries, self.rotation_tolerance)
            }
        }
    }

    /// A joint's DH row: `at`, `rotation` and `axis` given with it reported, angles
    /// constants, lengths affine. Returns the placement and the span of the row.
    fn dh_placement(
        &mut self,
        joint: &syntax::Joint,
        placement: &syntax::DhPlacement,
    ) -> (dh::Placed, SpanRange) {
        let given = [
            ("axis", joint.axis.as_ref().map(|a| a.span)),
            ("at", joint.at.as_ref().map(|v| v.span)),
            ("rotation", joint.rotation.as_ref().map(Rotation::span)),
        ];
        for (field, span) in given {
            if let Some(span) = span {
                rules::report_field_with_dh(field, placement, span, self.diagnostics);
            }
        }
        // Their numbers count as used (one mistake, one error: not also an unused
        // parameter).
        let mut numbers: Vec<&Number> = Vec::new();
        numbers.extend(joint.axis.iter().flat_map(|a| &a.direction.components));
        numbers.extend(joint.at.iter().flat_map(|v| &v.components));
        match &joint.rotation {
            Some(Rotation::Rpy(angles, _)) => numbers.extend(angles),
            Some(Rotation::AxisAngle(axis, angle, _)) => {
                numbers.extend(&axis.components);
                numbers.push(angle);
            }
            Some(Rotation::Matrix(m)) => numbers.extend(m.rows.iter().flatten()),
            None => {}
        }
        for number in numbers {
            self.constant_checked_elsewhere(number);
        }
        let what = "a DH angle (`alpha` or `theta`)";
        let mut length = |n: &Option<Number>| match n {
            Some(n) => self.value(n),
            None => Value::constant(0.0),
        };
        let (a, d) = (length(&placement.a), length(&placement.d));
        let tolerance = self.rotation_tolerance;
        let mut angle = |n: &Option<Number>| {
            let angle = n.as_ref().map_or(0.0, |n| self.constant(n, what));
            value::snapped_angle(angle, tolerance)
        };
        let (alpha, theta) = (angle(&placement.alpha), angle(&placement.theta));
        let row = dh::Row { a, alpha, d, theta };
        (dh::place(placement.convention, row, rows), placement.span)
    }

    /// I_G from an inertia form; shapes scale with the (affine) mass.
    fn inertia(&mut self, form: &InertiaForm, mass: &Value) -> Mat3 {
        match form {
            InertiaForm::Matrix(m) => {
                std::array::from_fn(|i| std::array::from_fn(|j| self.value(&m.rows[i][j])))
            }
            InertiaForm::Principal {
                moments, rotation, ..
            } => {
                let d = self.vector(moments);
                let diagonal: Mat3 = std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        if i == j {
                            d[i].clone()
                        } else {
                            Value::constant(0.0)
                        }
                    })
                });
                match rotation {
                    Some(r) => {
                        let r = self.rotation(r);
                        rotate_matrix(&r, &diagonal)
                    }
                    None => diagonal,
                }
            }
            InertiaForm::Shape(shape) => {
                let factors = self.shape_factors(&shape.kind);
                std::array::from_fn(|i| {
                    std::array::from_fn(|j| {
                        if i == j {
                            mass * factors[i]
                        } else {
                            Value::constant(0.0)
                        }
                    })
                })
            }
        }
    }

    /// Principal moments of a unit-mass standard solid (I_G = m · factors).
    fn shape_factors(&mut self, shape: &ShapeKind) -> [f64; 3] {
        let mut dimension = |n: &Number| {
            let v = self.constant(n, "a shape dimension");
            rules::shape_dimension_is_not_negative(v, n.span, self.diagnostics);
            v
        };
        match shape {
            ShapeKind::Point => [0.0; 3],
            ShapeKind::Sphere { radius } => [0.4 * dimension(radius).powi(2); 3],
            ShapeKind::Box { size } => {
                let [x, y, z] = std::array::from_fn(|i| dimension(&size.components[i]).powi(2));
                [(y + z) / 12.0, (x + z) / 12.0, (x + y) / 12.0]
            }
            ShapeKind::Rod { length, axis } => {
                let across = dimension(length).powi(2) / 12.0;
                let along = self.axis(axis);
                self.about_axis(along, 0.0, across, axis.span)
            }
            ShapeKind::Cylinder {
                radius,
                length,
                axis,
            } => {
                let (r2, l2) = (dimension(radius).powi(2), dimension(length).powi(2));
                let along = self.axis(axis);
                self.about_axis(along, r2 / 2.0, (3.0 * r2 + l2) / 12.0, axis.span)
            }
        }
    }

    /// Factors of an axisymmetric solid whose axis is a coordinate axis.
    fn about_axis(&mut self, axis: [f64; 3], along: f64, across: f64, span: SpanRange) -> [f64; 3] {
        let nonzero: Vec<usize> = (0..3).filter(|&i| axis[i] != 0.0).collect();
        match nonzero.as_slice() {
            [k] => std::array::from_fn(|i| if i == *k { along } else { across }),
            _ => {
                self.diagnostics.error(
                    span,
                    "a shape's axis must be a body axis: x, y or z (use `inertia: principal(..)` \
                     for other orientations)",
                );
                [across; 3]
            }
        }
    }
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// Rows of a rotation, with entries within 1e-15 of 0 or ±1 made exact: `rpy(pi / 2, 0, 0)`
/// means a quarter turn, whose cosine is 0, not 6e-17, and the exact zeros let the
/// expansion fold the terms they multiply. The same holds for matrices given by their
/// entries, which are often printed by a tool that computed them from angles (Pinocchio
/// gives the Panda's quarter turns as 2.2e-16 and 1): a rotation by 1e-15 rad is no
/// rotation, and keeping the residue costs the Panda's mass matrix 80 % more operations.
/// A URDF that writes π/2 as 1.57079632679 leaves 4.9e-12: `rotation_tolerance: 1e-10;`
/// takes that as exact too, for `rpy`, axis-angle and DH rows by taking the angle as the
/// quarter turn ([`value::snapped_angle`], so that the rotation stays orthonormal), for a
/// matrix entry by entry.
fn rows(m: &linear::Matrix3) -> [[f64; 3]; 3] {
    value::snapped(m)
}

/// Resolves every number, form and name list of the declaration.
pub(crate) fn resolve(mechanism: &syntax::Mechanism, diagnostics: &mut Diagnostics) -> Resolved {
    let mut parameters = Vec::new();
    for p in &mechanism.parameters {
        let nominal = match p.nominal.value {
            NumberValue::Constant(c) => {
                rules::number_is_finite(c, p.nominal.span, diagnostics);
                c
            }
            NumberValue::Parameter { .. } => {
                diagnostics.error(
                    p.nominal.span,
                    "a parameter's nominal value must be a constant",
                );
                0.0
            }
        };
        parameters.push(Parameter {
            name: p.name.text.clone(),
            nominal,
        });
    }
    let mut r = Resolver {
        names: parameters.iter().map(|p| p.name.clone()).collect(),
        nominal: parameters
            .iter()
            .map(|p| {
                if p.nominal.is_finite() {
                    p.nominal
                } else {
                    0.0
                }
            })
            .collect(),
        used: vec![false; parameters.len()],
        rotation_tolerance: value::DEFAULT_ROTATION_TOLERANCE,
        diagnostics,
    };
    if let Some(tolerance) = &mechanism.rotation_tolerance {
        let t = r.constant(tolerance, "a rotation tolerance");
        if rules::rotation_tolerance_is_reasonable(t, tolerance.span, r.diagnostics) {
            r.rotation_tolerance = t;
        }
    }
    let gravity = match &mechanism.gravity {
        Some(syntax::Gravity::Vector(g)) => r.constant_vector(g, "gravity"),
        Some(syntax::Gravity::None(_)) => [0.0; 3],
        None => syntax::DEFAULT_GRAVITY,
    };
    let bodies = mechanism
        .bodies
        .iter()
        .map(|b| resolve_body(&mut r, b))
        .collect();
    let joints = mechanism
        .joints
        .iter()
        .map(|j| resolve_joint(&mut r, j))
        .collect();
    // Load points take parameters; constraint points and directions are constants, which the
    // force analysis checks, so here they are checked finite and their parameters counted used.
    let load_points = mechanism
        .loads
        .iter()
        .map(|load| load.at.as_ref().map(|v| r.vector(v)))
        .collect();
    for constraint in &mechanism.constraints {
        let points = [&constraint.first, &constraint.second]
            .into_iter()
            .filter_map(|end| end.at.as_ref());
        for number in points.flat_map(|v| v.components.iter()) {
            r.constant_checked_elsewhere(number);
        }
    }
    let frames = mechanism
        .frames
        .iter()
        .map(|f| resolve_frame(&mut r, f))
        .collect();
    let mut outputs = resolve_outputs(
        &mechanism.outputs,
        !mechanism.constraints.is_empty(),
        r.diagnostics,
    );
    // Declaring how to analyse forces (`force_analysis: planar;`) asks for the analysis.
    if mechanism.outputs.is_none() && mechanism.analysis.is_some() {
        outputs.force_analysis = true;
    }
    let mut skip_triangle_inequality = false;
    for allow in &mechanism.allow {
        match allow.text.as_str() {
            "triangle_inequality" => skip_triangle_inequality = true,
            other => r.diagnostics.error(
                allow.span,
                format!("unknown check `{other}` in `allow`; the only check that can be waived is `triangle_inequality`"),
            ),
        }
    }
    Resolved {
        parameters,
        parameter_used: r.used,
        bodies,
        joints,
        outputs,
        skip_triangle_inequality,
        gravity,
        load_points,
        frames,
    }
}

fn resolve_frame(r: &mut Resolver, frame: &syntax::Frame) -> ResolvedFrame {
    let translation = match &frame.at {
        Some(at) => r.constant_vector(at, "a frame's placement"),
        None => [0.0; 3],
    };
    let (rotation, rotation_span) = match &frame.rotation {
        Some(rot) => (r.rotation(rot), rot.span()),
        None => (linear::IDENTITY, SpanRange::from(frame.name.span)),
    };
    ResolvedFrame {
        docs: frame.docs.clone(),
        name: frame.name.clone(),
        body: frame.body.clone(),
        translation,
        rotation,
        rotation_span,
    }
}

fn resolve_body(r: &mut Resolver, body: &syntax::Body) -> ResolvedBody {
    let name_span = SpanRange::from(body.name.span);
    let (mass, mass_span) = match &body.mass {
        Some(m) => (r.value(m), m.span),
        None => {
            rules::report_missing_field(
                "body",
                &body.name,
                "mass",
                "`mass: 1.0`",
                body.name.span,
                r.diagnostics,
            );
            (Value::constant(0.0), name_span)
        }
    };
    let com = match &body.com {
        Some(c) => r.vector(c),
        None => std::array::from_fn(|_| Value::constant(0.0)),
    };
    let (inertia, inertia_span) = match &body.inertia {
        Some(form) => {
            let span = match form {
                InertiaForm::Matrix(m) => m.span,
                InertiaForm::Principal { span, .. } => *span,
                InertiaForm::Shape(s) => s.span,
            };
            (r.inertia(form, &mass), span)
        }
        None => {
            rules::report_missing_field(
                "body",
                &body.name,
                "inertia",
                "`inertia: [[..], [..], [..]]`, or `shape: point` for a point mass",
                body.name.span,
                r.diagnostics,
            );
            (
                std::array::from_fn(|_| std::array::from_fn(|_| Value::constant(0.0))),
                name_span,
            )
        }
    };
    ResolvedBody {
        docs: body.docs.clone(),
        name: body.name.clone(),
        mass,
        mass_span,
        com,
        inertia,
        inertia_span,
        inertia_from_mass: matches!(body.inertia, Some(InertiaForm::Shape(_))),
    }
}

fn resolve_joint(r: &mut Resolver, joint: &syntax::Joint) -> ResolvedJoint {
    use syntax::JointKind::*;
    let placed = match (&joint.placement, joint.kind) {
        (Some(placement), Revolute | Prismatic) => Some(r.dh_placement(joint, placement)),
        (Some(placement), Fixed | Free) => {
            rules::report_dh_on_joint_without_axis(joint.kind, placement, r.diagnostics);
            None
        }
        (None, _) => None,
    };
    if let Some((placed, span)) = placed {
        // The DH row fixed the joint frame and its axis (z); `at`, `rotation` and `axis`
        // were reported if given too.
        return ResolvedJoint {
            axis: Some(([0.0, 0.0, 1.0], span)),
            translation: placed.joint.translation,
            rotation: placed.joint.rotation,
            rotation_span: span,
            child_frame: placed.child,
            ..resolve_joint_coefficients(r, joint)
        };
    }
    let axis = match (&joint.axis, joint.kind) {
        (Some(a), Revolute | Prismatic) => Some((r.axis(a), a.span)),
        (None, Revolute | Prismatic) => {
            rules::report_missing_field(
                "joint",
                &joint.name,
                "axis",
                "`axis: z`",
                joint.kind_span,
                r.diagnostics,
            );
            None
        }
        (Some(a), Fixed | Free) => {
            rules::report_axis_not_allowed(joint.kind, a.span, r.diagnostics);
            None
        }
        (None, Fixed | Free) => None,
    };
    let translation = match &joint.at {
        Some(v) => r.vector(v),
        None => std::array::from_fn(|_| Value::constant(0.0)),
    };
    let (rotation, rotation_span) = match &joint.rotation {
        Some(rot) => (r.rotation(rot), rot.span()),
        None => (IDENTITY, SpanRange::from(joint.name.span)),
    };
    ResolvedJoint {
        axis,
        translation,
        rotation,
        rotation_span,
        ..resolve_joint_coefficients(r, joint)
    }
}

/// A joint's names and coefficients, its placement the identity with no axis (for
/// [`resolve_joint`] to fill in).
fn resolve_joint_coefficients(r: &mut Resolver, joint: &syntax::Joint) -> ResolvedJoint {
    let mut coefficient = |n: &Option<Number>| match n {
        Some(n) => (r.value(n), n.span),
        None => (Value::constant(0.0), SpanRange::from(joint.name.span)),
    };
    let armature = coefficient(&joint.armature);
    let damping = coefficient(&joint.damping);
    let name_span = SpanRange::from(joint.name.span);
    let mut constant = |n: Option<&Number>, what: &str, absent: f64| match n {
        Some(n) => (r.constant(n, what), n.span),
        None => (absent, name_span),
    };
    let friction = constant(joint.friction.as_ref(), "a joint's friction", 0.0);
    let limits = match &joint.limits {
        Some(l) => ResolvedLimits {
            lower: constant(l.lower.as_ref(), "joint limits", f64::NEG_INFINITY),
            upper: constant(l.upper.as_ref(), "joint limits", f64::INFINITY),
            velocity: constant(l.velocity.as_ref(), "joint limits", f64::INFINITY),
            effort: constant(l.effort.as_ref(), "joint limits", f64::INFINITY),
            span: Some(l.span),
        },
        None => ResolvedLimits {
            lower: (f64::NEG_INFINITY, name_span),
            upper: (f64::INFINITY, name_span),
            velocity: (f64::INFINITY, name_span),
            effort: (f64::INFINITY, name_span),
            span: None,
        },
    };
    ResolvedJoint {
        docs: joint.docs.clone(),
        name: joint.name.clone(),
        kind: joint.kind,
        parent: joint.parent.clone(),
        child: joint.child.clone(),
        axis: None,
        translation: std::array::from_fn(|_| Value::constant(0.0)),
        rotation: IDENTITY,
        rotation_span: name_span,
        child_frame: None,
        armature,
        damping,
        friction,
        limits,
    }
}

fn resolve_outputs(
    names: &Option<Vec<syntax::Name>>,
    constrained: bool,
    diagnostics: &mut Diagnostics,
) -> Outputs {
    let Some(names) = names else {
        return if constrained {
            Outputs::constrained()
        } else {
            Outputs::all()
        };
    };
    let mut outputs = Outputs::default();
    for name in names {
        rules::output_is_known(&mut outputs, name, diagnostics);
    }
    outputs
}
