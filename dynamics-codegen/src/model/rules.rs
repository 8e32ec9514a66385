//! The rules a declared mechanism must satisfy, one function per rule.
//!
//! Each function states its rule in its doc comment, checks it, and records every violation
//! at the span of the offending tokens with the numbers involved and a hint. Physical rules
//! use the parameters' nominal values. Tolerances are relative, as in the runtime's own
//! validation, so that numbers rounded by hand or by a URDF exporter pass.
//!
//! Numbers the user wrote are printed as written (Rust's shortest round-trip form, in
//! scientific notation below 1e-4 and from 1e6: [`written`]); numbers a rule computed
//! (principal moments, determinants, sums) with six significant digits, by [`computed`], so
//! that rounding noise such as `0.30000000000000004` does not show.
//!
//! The compiler is the strict judge of the inertia and rotation rules: the runtime's
//! `ModelBuilder` checks them again with nalgebra's eigenvalue solver, which differs from
//! [`linear::symmetric_eigenvalues`] by a few ulps, and so rejects only beyond these
//! tolerances plus a margin above that disagreement (see `dynamics-runtime`'s
//! `model::rules`), so the generated `model()` never rejects what compiled here.
//! `tests/rule_agreement.rs` checks it on matrices bisected onto the edges.

use super::linear::{self, Matrix3};
use super::resolved::{Resolved, ResolvedBody, ResolvedJoint};
use super::value::{nominal33, Mat3, Value};
use super::{Diagnostics, Outputs};
use crate::syntax::{self, closest, JointKind, Name, SpanRange};
use proc_macro2::Span;
use std::collections::{HashMap, HashSet};

/// Relative tolerance of the inertia rules.
const INERTIA_TOLERANCE: f64 = 1e-9;
/// Absolute tolerance of |RᵀR − 1|.
const ROTATION_TOLERANCE: f64 = 1e-6;
/// The widest `rotation_tolerance` accepted.
pub(crate) const MAX_ROTATION_TOLERANCE: f64 = 1e-4;
/// The name of the fixed world frame.
pub(crate) const GROUND: &str = "ground";

/// Runs every rule that needs only the resolved declaration.
pub(crate) fn check_all(mechanism: &syntax::Mechanism, resolved: &Resolved, d: &mut Diagnostics) {
    let p = resolved.nominal_parameters();
    parameters_are_used(mechanism, resolved, d);
    type_name_is_usable(&mechanism.name, d);
    names_are_unique(mechanism, d);
    constraint_names_are_unique(mechanism, d);
    // Mass and symmetry are each declared body's; positivity and the triangle inequality
    // are judged on the bodies as merged through fixed joints: a body alone when its
    // inertia is symmetric, bodies merged when each is symmetric and none has a negative
    // mass (each reported on its own). No error that only follows from another on the same
    // body: a shape's I_G scales with the mass, so a negative mass makes it negative too
    // (the mass is the one mistake); an I_G given on its own is judged even when the mass
    // is wrong: its mistakes are the user's too.
    let (symmetric, mass): (Vec<bool>, Vec<bool>) = resolved
        .bodies
        .iter()
        .map(|body| {
            let inertia = nominal33(&body.inertia, &p);
            let mass = mass_is_not_negative(body, &p, d);
            (inertia_is_symmetric(body, &inertia, d), mass)
        })
        .unzip();
    for group in welded_groups(mechanism, resolved, &p) {
        let alone = group.members.len() == 1;
        if group.members.iter().all(|m| {
            let shape = resolved.bodies[m.body].inertia_from_mass;
            symmetric[m.body] && (mass[m.body] || (alone && !shape))
        }) {
            merged_inertia_is_physical(&group, resolved, &p, d);
        }
    }
    for joint in &resolved.joints {
        axis_is_nonzero(joint, d);
        rotation_is_proper(joint, d);
        joint_coefficients_are_not_negative(joint, &p, d);
        limits_and_friction_fit_the_joint(joint, d);
    }
    joints_name_declared_bodies(mechanism, d);
    body_has_one_parent(mechanism, d);
    bodies_reach_the_ground(mechanism, d);
    free_joint_is_on_the_ground(mechanism, d);
    loads_act_on_declared_bodies(mechanism, d);
    frames_are_well_placed(mechanism, resolved, d);
    dynamics_need_a_degree_of_freedom(mechanism, resolved, d);
}

/// A number computed by a rule, for a message: six significant digits, positional notation
/// from 1e-4 to 1e6 and scientific notation outside (`0.30000000000000004` → `0.3`,
/// `-2.9999999999999996e-17` → `-3e-17`, `-0.0` → `0`).
pub(crate) fn computed(x: f64) -> String {
    if !x.is_finite() {
        return x.to_string();
    }
    let rounded: f64 = format!("{x:.5e}").parse().unwrap_or(x);
    if rounded == 0.0 {
        "0".to_owned()
    } else if (1e-4..1e6).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

/// A number the user wrote, for a message: its shortest round-trip digits (`0.1`, `-2`,
/// never rounded), in positional notation from 1e-4 to 1e6 as [`computed`], in scientific
/// notation outside, so that `1e-300` prints as `1e-300` rather than as 300 digits.
pub(crate) fn written(x: f64) -> String {
    if !x.is_finite() || x == 0.0 || (1e-4..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The nominal value of a number for a message: as written when it is a constant
/// ([`written`]), else (a parameter times a coefficient, at the parameter's nominal value)
/// as [`computed`].
fn nominal_text(value: &Value, p: &[f64]) -> String {
    if value.is_constant() {
        written(value.constant)
    } else {
        computed(value.nominal(p))
    }
}

/// Rule: every number is finite (no NaN, no infinity, e.g. from `1.0 / 0.0`).
pub(crate) fn number_is_finite(value: f64, span: SpanRange, d: &mut Diagnostics) {
    if !value.is_finite() {
        d.error(
            span,
            format!("this number evaluates to {value}; every number must be finite"),
        );
    }
}

/// Rule: a number names only declared parameters.
pub(crate) fn report_undeclared_parameter(name: &str, span: SpanRange, d: &mut Diagnostics) {
    d.error(
        span,
        format!(
            "`{name}` is not a declared parameter; declare it with `parameters: [{name} = <nominal value>];` \
             or write a number"
        ),
    );
}

/// Rule: axes, rotations, gravity and shape dimensions are constants (they select the
/// structure of the generated code), and so are joint limits and friction (they are
/// printed as constants); parameters may appear in masses, mass centres, inertias, joint
/// offsets, armature and damping.
pub(crate) fn report_parameter_not_allowed(
    name: &str,
    what: &str,
    span: SpanRange,
    d: &mut Diagnostics,
) {
    d.error(
        span,
        format!("parameter `{name}` cannot be used in {what}: axes, rotations, gravity, shape dimensions, joint limits and friction must be constants"),
    );
}

/// Rule: a `rotation_tolerance` lies between 1e-15 (the default) and 1e-4 (an angle
/// written to four decimals, 1.5708 for π/2, is 3.7e-6 off). Wider, it would take angles
/// that are meant as such for quarter turns.
pub(crate) fn rotation_tolerance_is_reasonable(
    tolerance: f64,
    span: SpanRange,
    d: &mut Diagnostics,
) -> bool {
    let reasonable = (1e-15..=MAX_ROTATION_TOLERANCE).contains(&tolerance);
    if !reasonable {
        d.error(
            span,
            format!(
                "`rotation_tolerance` is {tolerance:e}; it must lie between 1e-15 (the default) \
                 and 1e-4: angles within it of a quarter turn, and a matrix's entries within \
                 it of 0 or ±1, are taken as exactly that (1e-10 takes a quarter turn written \
                 1.57079632679 as exact, 1e-5 one written 1.5708)"
            ),
        );
    }
    reasonable
}

/// Rule: an axis-angle rotation has a nonzero, finite axis.
pub(crate) fn report_zero_rotation_axis(span: SpanRange, d: &mut Diagnostics) {
    d.error(
        span,
        "the rotation axis has zero length; give a nonzero direction",
    );
}

/// Rule: shape dimensions (lengths, radii) are not negative.
pub(crate) fn shape_dimension_is_not_negative(value: f64, span: SpanRange, d: &mut Diagnostics) {
    if value < 0.0 {
        d.error(
            span,
            format!(
                "a shape dimension is {} m, which is negative",
                written(value)
            ),
        );
    }
}

/// Rule: required fields are present (a body's mass and inertia, a moving joint's axis).
/// `what` is `body` or `joint`; `example` is the hint, with its own backticks.
pub(crate) fn report_missing_field(
    what: &str,
    item: &Name,
    field: &str,
    example: &str,
    span: Span,
    d: &mut Diagnostics,
) {
    d.error(
        span,
        format!(
            "{what} `{}` has no `{field}`; add for example {example}",
            item.text
        ),
    );
}

/// Rule: a DH placement places a revolute or prismatic joint's axis; fixed and free joints
/// have none.
pub(crate) fn report_dh_on_joint_without_axis(
    kind: JointKind,
    placement: &syntax::DhPlacement,
    d: &mut Diagnostics,
) {
    let kind = match kind {
        JointKind::Fixed => "fixed",
        _ => "free",
    };
    d.error(
        placement.span,
        format!(
            "a {kind} joint cannot be placed by `{}(..)`: a Denavit–Hartenberg row places the \
             axis of a revolute or prismatic joint; place a {kind} joint with `at` and \
             `rotation`",
            placement.convention.word()
        ),
    );
}

/// Rule: a DH placement fixes the joint frame and its axis (z), so `at`, `rotation` and
/// `axis` are not given with it.
pub(crate) fn report_field_with_dh(
    field: &str,
    placement: &syntax::DhPlacement,
    span: SpanRange,
    d: &mut Diagnostics,
) {
    let form = placement.convention.word();
    let why = match field {
        "axis" => {
            format!("`{form}(..)` fixes the axis: the joint moves about or along z of its DH frame")
        }
        _ => format!("`{form}(..)` places the joint frame"),
    };
    d.error(
        span,
        format!("`{field}` cannot be given with `placement: {form}(..)`: {why}; remove `{field}`"),
    );
}

/// Rule: fixed and free joints take no axis.
pub(crate) fn report_axis_not_allowed(kind: JointKind, span: SpanRange, d: &mut Diagnostics) {
    let kind = match kind {
        JointKind::Fixed => "fixed",
        _ => "free",
    };
    d.error(span, format!("a {kind} joint has no axis; remove `axis`"));
}

/// Rule: every requested output is one the generator knows.
pub(crate) fn output_is_known(outputs: &mut Outputs, name: &Name, d: &mut Diagnostics) {
    if !outputs.enable(&name.text) {
        let aliases = Outputs::ALIASES.iter().map(|(alias, _)| *alias);
        let known: Vec<&str> = Outputs::NAMES.iter().copied().chain(aliases).collect();
        let suggestion = closest(&name.text, &known)
            .map_or_else(|| ".".to_owned(), |c| format!("; did you mean `{c}`?"));
        d.error(
            name.span,
            format!(
                "unknown output `{}`{suggestion} The outputs are {} (or the short forms {}), \
                 each also with `_into` (`mass_matrix_into`) for a twin that writes into the \
                 caller's `out`, or with `_sparse_into` for one that writes only the entries \
                 that can be nonzero.",
                name.text,
                Outputs::NAMES.join(", "),
                Outputs::ALIASES
                    .iter()
                    .map(|(alias, _)| *alias)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        );
    }
}

/// Rule: every declared parameter is used somewhere (an unused one is almost always a typo).
/// A second parameter of the same name is never used (the name means the first); it is
/// reported once, by [`names_are_unique`].
fn parameters_are_used(mechanism: &syntax::Mechanism, resolved: &Resolved, d: &mut Diagnostics) {
    let mut earlier: HashSet<&str> = HashSet::new();
    for (p, used) in mechanism.parameters.iter().zip(&resolved.parameter_used) {
        let repeated = !earlier.insert(p.name.text.as_str());
        if !used && !repeated {
            d.error(
                p.name.span,
                format!("parameter `{}` is declared but never used", p.name.text),
            );
        }
    }
}

/// Rule: bodies, joints, loads and parameters have unique names, and no body is named
/// `ground`. A repeated name is reported at the repetition, then at the first declaration.
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
            } else if let Some(first) = seen.get(name.text.as_str()) {
                d.error(
                    name.span,
                    format!("a {kind} named `{}` is already declared", name.text),
                );
                d.error(
                    first.span,
                    format!("{kind} `{}` is first declared here", name.text),
                );
            } else {
                seen.insert(&name.text, name);
            }
        }
    }
}

/// Names the generated code gives a meaning of its own: the generic scalar parameter `T`,
/// the generated functions' argument names, and Rust's primitive types.
const RESERVED_TYPE_NAMES: [(&str, &str); 24] = [
    ("T", "the generated code's generic scalar type"),
    ("q", "an argument of the generated functions"),
    ("v", "an argument of the generated functions"),
    ("a", "an argument of the generated functions"),
    ("tau", "an argument of the generated functions"),
    ("p", "an argument of the generated functions"),
    ("loads", "an argument of the generated functions"),
    ("bool", "a Rust primitive type"),
    ("char", "a Rust primitive type"),
    ("str", "a Rust primitive type"),
    ("f32", "a Rust primitive type"),
    ("f64", "a Rust primitive type"),
    ("i8", "a Rust primitive type"),
    ("i16", "a Rust primitive type"),
    ("i32", "a Rust primitive type"),
    ("i64", "a Rust primitive type"),
    ("i128", "a Rust primitive type"),
    ("isize", "a Rust primitive type"),
    ("u8", "a Rust primitive type"),
    ("u16", "a Rust primitive type"),
    ("u32", "a Rust primitive type"),
    ("u64", "a Rust primitive type"),
    ("u128", "a Rust primitive type"),
    ("usize", "a Rust primitive type"),
];

/// Rule: the mechanism's type name is none of [`RESERVED_TYPE_NAMES`]: a type
/// named so shadows what the generated code means by it (a generic parameter, an argument
/// binding, a primitive type) and breaks it with errors far from the cause.
fn type_name_is_usable(name: &proc_macro2::Ident, d: &mut Diagnostics) {
    let text = name.to_string();
    let reserved = RESERVED_TYPE_NAMES
        .iter()
        .find(|(reserved, _)| *reserved == text);
    if let Some((_, meaning)) = reserved {
        d.error(
            SpanRange::from(name.span()),
            format!(
                "the mechanism's type cannot be named `{text}`: in the generated code `{text}` is \
                 {meaning}; choose another name, in UpperCamelCase such as `Pendulum`"
            ),
        );
    }
}

/// Rule: a constraint's name differs from every joint's and every other constraint's: the
/// force analysis names its unknowns after them (`pin.x`), so two alike would name two
/// different reactions the same.
fn constraint_names_are_unique(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let mut seen: HashMap<&str, (&str, &Name)> = mechanism
        .joints
        .iter()
        .map(|j| (j.name.text.as_str(), ("joint", &j.name)))
        .collect();
    for constraint in &mechanism.constraints {
        let name = &constraint.name;
        if let Some((kind, first)) = seen.get(name.text.as_str()) {
            d.error(
                name.span,
                format!(
                    "a {kind} named `{}` is already declared; a constraint needs a name of its own \
                     (its reactions are named after it, like a joint's)",
                    name.text
                ),
            );
            d.error(
                first.span,
                format!("{kind} `{}` is first declared here", name.text),
            );
        } else {
            seen.insert(&name.text, ("constraint", name));
        }
    }
}

/// Rule: a body's mass is not negative. Returns whether it is not.
fn mass_is_not_negative(body: &ResolvedBody, p: &[f64], d: &mut Diagnostics) -> bool {
    let negative = body.mass.nominal(p) < 0.0;
    if negative {
        d.error(
            body.mass_span,
            format!(
                "body `{}` has mass {} kg; a mass must be ≥ 0",
                body.name.text,
                nominal_text(&body.mass, p)
            ),
        );
    }
    !negative
}

/// Rule: I_G is symmetric (I_xy = I_yx, ...). Returns whether it is.
fn inertia_is_symmetric(body: &ResolvedBody, inertia: &Matrix3, d: &mut Diagnostics) -> bool {
    let scale = linear::max_abs_entry(inertia).max(f64::MIN_POSITIVE);
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (inertia[i][j] - inertia[j][i]).abs() > INERTIA_TOLERANCE * scale {
            d.error(
                body.inertia_span,
                format!(
                    "the inertia of body `{}` is not symmetric: I[{i}][{j}] = {} but I[{j}][{i}] = {}; \
                     give the same product of inertia on both sides",
                    body.name.text,
                    inertia[i][j],
                    inertia[j][i]
                ),
            );
            return false;
        }
    }
    true
}

/// Principal moments of a symmetric matrix, ascending.
pub(crate) fn principal_moments(inertia: &Matrix3) -> [f64; 3] {
    linear::symmetric_eigenvalues(inertia)
}

/// What is unphysical about an inertia I_G, if anything: a negative principal moment
/// (beyond the relative tolerance), or, where it is positive, moments that violate the
/// triangle inequality (when `triangle` asks for that rule).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum InertiaDefect {
    /// Not positive semi-definite; the principal moments, ascending.
    NotPositive([f64; 3]),
    /// I1 + I2 < I3; the principal moments, ascending.
    Triangle([f64; 3]),
}

impl InertiaDefect {
    /// What is wrong, for a message: `is not positive semi-definite` or `violates the
    /// triangle inequality I1 + I2 ≥ I3`, with the principal moments.
    pub(crate) fn describe(&self) -> String {
        let (what, p) = match self {
            InertiaDefect::NotPositive(p) => ("is not positive semi-definite", p),
            InertiaDefect::Triangle(p) => ("violates the triangle inequality I1 + I2 ≥ I3", p),
        };
        format!(
            "{what} (principal moments {}, {}, {} kg·m²)",
            computed(p[0]),
            computed(p[1]),
            computed(p[2])
        )
    }
}

/// Rule: I_G is positive semi-definite: every principal moment ≥ 0 (a thin rod has a zero
/// moment about its axis, a point mass all zero); and the principal moments satisfy
/// I1 + I2 ≥ I3, as every real mass distribution does (I1 + I2 − I3 = 2∫z² dm in principal
/// axes), unless `triangle` is false (`allow: [triangle_inequality]`). The triangle is
/// checked wherever the positivity rule passes (a tiny negative moment within its tolerance
/// included), so that the runtime, which skips it near that edge, never judges alone.
pub(crate) fn inertia_defect(inertia: &Matrix3, triangle: bool) -> Option<InertiaDefect> {
    let p = principal_moments(inertia);
    if p[0] < -INERTIA_TOLERANCE * p[2].abs().max(f64::MIN_POSITIVE) {
        return Some(InertiaDefect::NotPositive(p));
    }
    if triangle && p[0] + p[1] < p[2] - INERTIA_TOLERANCE * (p[0] + p[1] + p[2]) {
        return Some(InertiaDefect::Triangle(p));
    }
    None
}

/// Declared bodies welded together through fixed joints: one body of the dynamics, which
/// the inertia rules judge as a whole.
pub(crate) struct WeldedGroup {
    /// The body the others are welded to (the one a moving joint moves), or `None` for the
    /// bodies welded to the ground.
    pub root: Option<usize>,
    /// The declared bodies: the root first, then in declaration order.
    pub members: Vec<Member>,
}

/// A declared body of a [`WeldedGroup`], placed in the group's frame (the root's, or the
/// world's): x_group = rotation x_body + translation, at the nominal parameters.
pub(crate) struct Member {
    /// Index among the declared bodies.
    pub body: usize,
    /// Rotation of its frame in the group's frame.
    pub rotation: Matrix3,
    /// Its origin in the group's frame.
    pub translation: [f64; 3],
}

/// The declared bodies grouped by what they are welded to, each group in the order of its
/// first member's declaration, its root first. Each body walks up through the fixed joints
/// that make it its parent's (the first joint naming it as child), composing their
/// placements, to a body moved by another kind of joint, or to the ground. A walk that
/// meets an undeclared parent, or loops (rules of their own report both), stops: the body
/// is the root of its group.
///
/// Linear in the number of bodies: a walk stops at the first body whose walk is known and
/// takes its result (the pose of that body in the group's frame, composed with the
/// placements walked so far), so that a chain of n welded links costs n steps, not n²/2.
/// The placements compose from the group's root down (x_root = R x + t with R = R_up R_j,
/// t = R_up t_j + t_up), as the tree merges the bodies (`tree::build`).
pub(crate) fn welded_groups(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    p: &[f64],
) -> Vec<WeldedGroup> {
    let index: HashMap<&str, usize> = resolved
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| (b.name.text.as_str(), i))
        .collect();
    let mut parent_joint: HashMap<&str, &ResolvedJoint> = HashMap::new();
    for (joint, declared) in resolved.joints.iter().zip(&mechanism.joints) {
        if !is_self_joint(declared) {
            parent_joint
                .entry(joint.child.text.as_str())
                .or_insert(joint);
        }
    }
    /// What a walk through a body finds: the root of its group and the body's pose in the
    /// root's frame, or a loop (its walk never ends).
    #[derive(Clone, Copy)]
    enum Walk {
        Unknown,
        OnPath,
        Loop,
        Found(Option<usize>, Matrix3, [f64; 3]),
    }
    let n = resolved.bodies.len();
    let mut walks = vec![Walk::Unknown; n];
    // One step up from body `at`: where its walk ends now, or the parent it continues at
    // and the placement of its fixed joint.
    enum Step<'a> {
        End(Walk),
        Up(usize, &'a ResolvedJoint),
    }
    let step = |at: usize| -> Step {
        let name = resolved.bodies[at].name.text.as_str();
        let Some(joint) = parent_joint
            .get(name)
            .filter(|j| j.kind == JointKind::Fixed)
        else {
            return Step::End(Walk::Found(Some(at), linear::IDENTITY, [0.0; 3]));
        };
        let placement = (
            joint.rotation,
            super::value::nominal3(&joint.translation, p),
        );
        if joint.parent.text == GROUND {
            return Step::End(Walk::Found(None, placement.0, placement.1));
        }
        match index.get(joint.parent.text.as_str()) {
            Some(&parent) => Step::Up(parent, joint),
            // An undeclared parent: the walk stops here, this body the root, its joint's
            // placement composed (as the walks through it always did).
            None => Step::End(Walk::Found(Some(at), placement.0, placement.1)),
        }
    };
    let mut path: Vec<(usize, &ResolvedJoint)> = Vec::new();
    for b in 0..n {
        if !matches!(walks[b], Walk::Unknown) {
            continue;
        }
        // Up to a body whose walk is known, a body without a fixed joint to a declared
        // parent, or a body already on this path (a loop).
        let mut at = b;
        let mut end = loop {
            match walks[at] {
                Walk::Unknown => {}
                Walk::OnPath => break Walk::Loop,
                known => break known,
            }
            match step(at) {
                Step::End(found) => {
                    walks[at] = found;
                    break found;
                }
                Step::Up(parent, joint) => {
                    walks[at] = Walk::OnPath;
                    path.push((at, joint));
                    at = parent;
                }
            }
        };
        // Back down the path, composing each fixed joint's placement under its parent's
        // pose.
        while let Some((body, joint)) = path.pop() {
            end = match end {
                Walk::Found(root, r_up, t_up) => Walk::Found(
                    root,
                    linear::mul(&r_up, &joint.rotation),
                    linear::add_vectors(
                        &linear::mul_vector(&r_up, &super::value::nominal3(&joint.translation, p)),
                        &t_up,
                    ),
                ),
                other => other,
            };
            walks[body] = end;
        }
    }
    let mut groups: Vec<WeldedGroup> = Vec::new();
    let mut group_of: HashMap<Option<usize>, usize> = HashMap::new();
    for (b, body) in resolved.bodies.iter().enumerate() {
        let (root, rotation, translation) = match walks[b] {
            // Its own root (or a walk stopped by a loop, reported elsewhere).
            Walk::Found(root, ..) if root == Some(b) || body.name.text == GROUND => {
                (Some(b), linear::IDENTITY, [0.0; 3])
            }
            Walk::Found(root, rotation, translation) => (root, rotation, translation),
            Walk::Loop | Walk::OnPath | Walk::Unknown => (Some(b), linear::IDENTITY, [0.0; 3]),
        };
        let member = Member {
            body: b,
            rotation,
            translation,
        };
        match group_of.get(&root) {
            Some(&k) => groups[k].members.push(member),
            None => {
                group_of.insert(root, groups.len());
                groups.push(WeldedGroup {
                    root,
                    members: vec![member],
                });
            }
        }
    }
    root_first(&mut groups);
    groups
}

/// Each group's root first, then the bodies welded to it in declaration order.
fn root_first(groups: &mut [WeldedGroup]) {
    for group in groups {
        if let Some(k) = group
            .members
            .iter()
            .position(|m| Some(m.body) == group.root)
        {
            let root = group.members.remove(k);
            group.members.insert(0, root);
        }
    }
}

/// The mass, mass centre and I_G of parts (mass, mass centre, I_G, each in one common
/// frame) taken as one body: I_G = Σ I_G,k + m_k (|d_k|² 1 − d_k d_kᵀ), d_k = c_k − c.
pub(crate) fn merged_inertia(parts: &[(f64, [f64; 3], Matrix3)]) -> Matrix3 {
    let mass: f64 = parts.iter().map(|(m, _, _)| m).sum();
    let com = if mass > 0.0 {
        let weighted = parts.iter().fold([0.0; 3], |sum, (m, c, _)| {
            linear::add_vectors(&sum, &linear::scale_vector(c, *m))
        });
        linear::scale_vector(&weighted, 1.0 / mass)
    } else {
        [0.0; 3]
    };
    parts.iter().fold(linear::ZERO, |sum, (m, c, i)| {
        let d = linear::sub_vectors(c, &com);
        let shift = linear::parallel_axis(&d);
        linear::add(&sum, &linear::add(i, &linear::scale(&shift, *m)))
    })
}

/// Rule: the inertia of each body of the dynamics, the declared bodies welded together
/// through fixed joints merged into one, is physical ([`inertia_defect`]): a URDF link's
/// placeholder inertia welded to a real body is no error, a merged body that is not
/// physical is. A body welded to nothing is judged alone, as declared (its matrix as
/// written, not rotated). Reported at the root's inertia (the first member's, for the
/// bodies welded to the ground).
fn merged_inertia_is_physical(
    group: &WeldedGroup,
    resolved: &Resolved,
    p: &[f64],
    d: &mut Diagnostics,
) {
    let triangle = !resolved.skip_triangle_inequality;
    let body = |k: usize| &resolved.bodies[group.members[k].body];
    let (inertia, what) = if let [only] = group.members.as_slice() {
        let declared = &resolved.bodies[only.body];
        (
            nominal33(&declared.inertia, p),
            format!("body `{}`", declared.name.text),
        )
    } else {
        let parts: Vec<(f64, [f64; 3], Matrix3)> = group
            .members
            .iter()
            .map(|m| {
                let declared = &resolved.bodies[m.body];
                let com = super::value::nominal3(&declared.com, p);
                (
                    declared.mass.nominal(p),
                    linear::add_vectors(&linear::mul_vector(&m.rotation, &com), &m.translation),
                    linear::rotate(&m.rotation, &nominal33(&declared.inertia, p)),
                )
            })
            .collect();
        let names = |skip: usize| -> String {
            (skip..group.members.len())
                .map(|k| format!("`{}`", body(k).name.text))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let what = match group.root {
            Some(_) => format!(
                "body `{}` merged with {} (welded to it through fixed joints)",
                body(0).name.text,
                names(1)
            ),
            None => format!("the bodies welded to the ground, {}, merged", names(0)),
        };
        (merged_inertia(&parts), what)
    };
    let span = match group.root {
        Some(root) => resolved.bodies[root].inertia_span,
        None => body(0).inertia_span,
    };
    match inertia_defect(&inertia, triangle) {
        Some(InertiaDefect::NotPositive(p)) => d.error(
            span,
            format!(
                "the inertia of {what} is not positive semi-definite: its principal moments \
                 are {}, {}, {} kg·m²; check the signs of the products of inertia",
                computed(p[0]),
                computed(p[1]),
                computed(p[2])
            ),
        ),
        Some(InertiaDefect::Triangle(p)) => d.error(
            span,
            format!(
                "the principal moments of {what} ({}, {}, {} kg·m²) violate the triangle \
                 inequality I1 + I2 ≥ I3 ({} < {}): no mass distribution has this inertia \
                 (`allow: [triangle_inequality];` accepts it anyway)",
                computed(p[0]),
                computed(p[1]),
                computed(p[2]),
                computed(p[0] + p[1]),
                computed(p[2])
            ),
        ),
        None => {}
    }
}

/// Rule: a revolute or prismatic axis has nonzero length.
fn axis_is_nonzero(joint: &ResolvedJoint, d: &mut Diagnostics) {
    if let Some((axis, span)) = joint.axis {
        if linear::norm(&axis) < 1e-12 {
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
    rotation_is_proper_at(
        &joint.rotation,
        joint.rotation_span,
        &format!("joint `{}`", joint.name.text),
        d,
    );
}

/// A rotation matrix is orthonormal with determinant +1; `what` names its owner.
fn rotation_is_proper_at(r: &[[f64; 3]; 3], span: SpanRange, what: &str, d: &mut Diagnostics) {
    let deviation = linear::max_abs_entry(&linear::sub(
        &linear::mul(&linear::transpose(r), r),
        &linear::IDENTITY,
    ));
    if deviation > ROTATION_TOLERANCE {
        d.error(
            span,
            format!(
                "the rotation of {what} is not orthonormal: the largest entry of |RᵀR − 1| is {} \
                 (at most {ROTATION_TOLERANCE:e} is accepted); give a rotation matrix whose rows are \
                 orthogonal unit vectors, rpy(r, p, y) or axis_angle([x, y, z], angle)",
                computed(deviation)
            ),
        );
    } else if linear::determinant(r) < 0.0 {
        d.error(
            span,
            format!(
                "the rotation of {what} has determinant {}: it is a reflection, not a rotation",
                computed(linear::determinant(r))
            ),
        );
    }
}

/// Rule: armature and damping are not negative.
fn joint_coefficients_are_not_negative(joint: &ResolvedJoint, p: &[f64], d: &mut Diagnostics) {
    for (field, (value, span)) in [("armature", &joint.armature), ("damping", &joint.damping)] {
        if value.nominal(p) < 0.0 {
            d.error(
                *span,
                format!(
                    "joint `{}` has {field} {}; it must be ≥ 0",
                    joint.name.text,
                    nominal_text(value, p)
                ),
            );
        }
    }
}

/// Rule: limits and friction belong to a revolute or prismatic joint (a fixed joint does
/// not move, a free joint's six coordinates have no one limit), and are consistent: lower ≤
/// upper, and the velocity and effort limits and the friction not negative.
fn limits_and_friction_fit_the_joint(joint: &ResolvedJoint, d: &mut Diagnostics) {
    let name = &joint.name.text;
    if matches!(joint.kind, JointKind::Fixed | JointKind::Free) {
        let kind = if joint.kind == JointKind::Fixed {
            "fixed"
        } else {
            "free"
        };
        if let Some(span) = joint.limits.span {
            d.error(
                span,
                format!("joint `{name}` is a {kind} joint, which has no limits; remove `limits`"),
            );
        }
        if joint.friction.0 != 0.0 {
            d.error(
                joint.friction.1,
                format!(
                    "joint `{name}` is a {kind} joint, which has no friction; remove `friction`"
                ),
            );
        }
        return;
    }
    let l = &joint.limits;
    if l.lower.0 > l.upper.0 {
        d.error(
            l.span.unwrap_or(l.upper.1),
            format!(
                "joint `{name}` has lower limit {} above its upper limit {}; the lower limit \
                 must be ≤ the upper",
                written(l.lower.0),
                written(l.upper.0)
            ),
        );
    }
    for (what, (value, span)) in [
        ("velocity limit", l.velocity),
        ("effort limit", l.effort),
        ("friction", joint.friction),
    ] {
        if value < 0.0 {
            d.error(
                span,
                format!(
                    "joint `{name}` has {what} {}; it must be ≥ 0",
                    written(value)
                ),
            );
        }
    }
}

/// Rule: a joint's parent and child are declared bodies (or `ground` for the parent), and
/// differ.
fn joints_name_declared_bodies(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let names: HashSet<&str> = mechanism
        .bodies
        .iter()
        .map(|b| b.name.text.as_str())
        .collect();
    let declared = |n: &str| names.contains(n);
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
/// which a tree cannot express). A joint from a body to itself is not counted: it is
/// reported once, by [`joints_name_declared_bodies`].
fn body_has_one_parent(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let mut first: HashMap<&str, &syntax::Joint> = HashMap::new();
    for joint in mechanism.joints.iter().filter(|j| !is_self_joint(j)) {
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

/// Whether a joint attaches a body to itself (reported by [`joints_name_declared_bodies`]).
fn is_self_joint(joint: &syntax::Joint) -> bool {
    joint.child.text == joint.parent.text
}

/// Rule: every body is connected to the ground through a chain of joints (no body left
/// floating, no cycle of joints that never reaches the ground). Mistakes other rules report
/// are not reported again here: a body named `ground` ([`names_are_unique`]) and a joint
/// from a body to itself ([`joints_name_declared_bodies`]), which is then not counted as a
/// parent, nor its body as left floating.
fn bodies_reach_the_ground(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
    let parent_of: HashMap<&str, &str> = mechanism
        .joints
        .iter()
        .filter(|j| !is_self_joint(j))
        .map(|j| (j.child.text.as_str(), j.parent.text.as_str()))
        .collect();
    let self_joined: HashSet<&str> = mechanism
        .joints
        .iter()
        .filter(|j| is_self_joint(j))
        .map(|j| j.child.text.as_str())
        .collect();
    let declared: HashSet<&str> = mechanism
        .bodies
        .iter()
        .map(|b| b.name.text.as_str())
        .collect();
    // Bodies some earlier walk went through: what lies above them was seen then (the ground,
    // an undeclared parent, or a cycle, reported by the first walk that met it), so a walk
    // that reaches one stops there. Each body is walked through once.
    let mut walked: HashSet<&str> = HashSet::new();
    let mut reported_cycle: HashSet<&str> = HashSet::new();
    for body in mechanism.bodies.iter().filter(|b| b.name.text != GROUND) {
        let start = body.name.text.as_str();
        let mut walk = start;
        let mut path = vec![walk];
        let mut on_path: HashMap<&str, usize> = HashMap::from([(walk, 0)]);
        loop {
            if walk != start && walked.contains(walk) {
                break;
            }
            match parent_of.get(walk) {
                None => {
                    if walk == start && !self_joined.contains(walk) {
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
                Some(&p) if p == GROUND || !declared.contains(p) => break,
                Some(&p) if on_path.contains_key(p) => {
                    if !reported_cycle.contains(p) {
                        let cycle = &path[on_path[p]..];
                        reported_cycle.extend(cycle.iter().copied());
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
                    on_path.insert(p, path.len());
                    path.push(p);
                    walk = p;
                }
            }
        }
        walked.extend(path);
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
    let declared: HashSet<&str> = mechanism
        .bodies
        .iter()
        .map(|b| b.name.text.as_str())
        .collect();
    for load in &mechanism.loads {
        if !declared.contains(load.body.text.as_str()) {
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

/// Rule: a frame is attached to a declared body or the ground, is named unlike every body
/// (each body is a frame of its own, named after it) and every other frame, and has a
/// proper rotation; `frames: [..]` names frames.
fn frames_are_well_placed(mechanism: &syntax::Mechanism, resolved: &Resolved, d: &mut Diagnostics) {
    let body_names: Vec<&str> = mechanism
        .bodies
        .iter()
        .map(|b| b.name.text.as_str())
        .collect();
    let is_body: HashSet<&str> = body_names.iter().copied().collect();
    let mut seen: HashMap<&str, &Name> = HashMap::new();
    for frame in &resolved.frames {
        let body = frame.body.text.as_str();
        if body != GROUND && !is_body.contains(body) {
            let hint = match crate::syntax::closest(body, &body_names) {
                Some(near) => format!("; did you mean `{near}`?"),
                None => " (the fixed frame is `ground`)".to_owned(),
            };
            d.error(
                frame.body.span,
                format!(
                    "frame `{}` is on unknown body `{body}`{hint}",
                    frame.name.text
                ),
            );
        }
        let name = frame.name.text.as_str();
        if is_body.contains(name) || name == GROUND {
            d.error(
                frame.name.span,
                format!(
                    "a frame cannot be named `{name}`: every body is a frame named after it (and \
                     `ground` is the world); choose another name"
                ),
            );
        } else if let Some(first) = seen.get(name) {
            d.error(
                frame.name.span,
                format!("a frame named `{name}` is already declared"),
            );
            d.error(first.span, format!("frame `{name}` is first declared here"));
        } else {
            seen.insert(name, &frame.name);
        }
        rotation_is_proper_at(
            &frame.rotation,
            frame.rotation_span,
            &format!("frame `{name}`"),
            d,
        );
    }
    let mut selected_before: HashSet<&str> = HashSet::new();
    for selected in mechanism.frame_selection.iter().flatten() {
        let text = selected.text.as_str();
        if !selected_before.insert(text) {
            d.error(selected.span, format!("`frames:` names `{text}` twice"));
        }
        if !seen.contains_key(text) && !is_body.contains(text) {
            let names: Vec<&str> = seen
                .keys()
                .copied()
                .chain(body_names.iter().copied())
                .collect();
            let hint = match crate::syntax::closest(text, &names) {
                Some(near) => format!("; did you mean `{near}`?"),
                None => String::new(),
            };
            d.error(
                selected.span,
                format!(
                    "`frames:` names `{text}`, which is neither a declared `frame` nor a \
                     body{hint}"
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

/// What [`coordinate_has_inertia`] measured for a joint, at the parameters' nominal values:
/// the mass of the bodies the joint moves, and the largest over the configurations tried of
/// the inertia its motion meets.
pub(crate) struct CoordinateInertia {
    /// Total mass of the bodies the joint moves (kg); independent of the configuration.
    pub mass: f64,
    /// Revolute: the moment of inertia of those bodies about the joint axis. Free: the
    /// smallest principal moment of their inertia about their centre of mass (the free
    /// block of M is their spatial inertia, singular when that is). Prismatic: unused
    /// (a translation meets only the mass). In kg·m².
    pub moment: f64,
    /// How many configurations were tried.
    pub configurations: usize,
    /// The joint's armature (rotor inertia), added to the coordinate's diagonal entry of M.
    pub armature: f64,
    /// Whether the mass and every moment measured were finite numbers: with huge masses,
    /// mass centres or placements (`mass: 1e300` a metre from the axis) the sums overflow to
    /// infinity or NaN, which no comparison with zero judges.
    pub finite: bool,
}

/// Rule: every joint coordinate has inertia: a revolute joint's subtree has a nonzero moment
/// of inertia about the joint axis, a prismatic joint's subtree has mass, a free joint's
/// subtree has mass and a nonsingular rotational inertia, in at least one of the
/// configurations sampled, or the joint has armature (which adds to the coordinate's own
/// entries of M, so M = \[armature\] for a massless slider is not singular). Otherwise M(q) is
/// singular for every q. "Nonzero" is relative to `scale`, the size of the mechanism's
/// inertia as a whole (when that is finite; else only 0 is). A mass or moment that is not
/// finite (the numbers overflow `f64`) is an error of its own, whatever the armature: M(q)
/// then holds infinities or NaN.
pub(crate) fn coordinate_has_inertia(
    joint: &Name,
    kind: &super::JointKind,
    measured: &CoordinateInertia,
    scale: f64,
    d: &mut Diagnostics,
) {
    use super::JointKind::{Free, Prismatic, Revolute};
    if !measured.finite {
        let about = match kind {
            Revolute { .. } => "a moment of inertia about its axis",
            Prismatic { .. } => "a mass",
            Free => "an inertia about their centre of mass",
        };
        d.error(
            joint.span,
            format!(
                "the inertia that the coordinate of joint `{}` moves overflows: the bodies it \
                 moves (total mass {} kg) have {about} that is not a finite number (beyond \
                 f64's range, about 1.8e308) in the configurations tried, so the mass matrix \
                 M(q) cannot be computed; use smaller numbers (other units, or a mass centre \
                 and placements nearer the joint)",
                joint.text,
                computed(measured.mass)
            ),
        );
        return;
    }
    let negligible =
        |x: f64| x == 0.0 || (scale.is_finite() && x.abs() <= 1e-12 * scale.max(f64::MIN_POSITIVE));
    let amount = |x: f64| {
        if x == 0.0 {
            "0 kg·m² in every configuration tried".to_owned()
        } else {
            format!(
                "at most {} kg·m² in the {} configurations tried, negligible next to the rest \
                 of the mechanism",
                computed(x),
                measured.configurations
            )
        }
    };
    if !negligible(measured.armature) {
        return;
    }
    let mass = computed(measured.mass);
    let (what, hint) = match kind {
        Revolute { .. } if negligible(measured.moment) => (
            format!(
                "the bodies it moves (total mass {mass} kg) have a moment of inertia about its \
                 axis of {}",
                amount(measured.moment)
            ),
            "put mass away from its axis or give the bodies inertia about it",
        ),
        Prismatic { .. } | Free if negligible(measured.mass) => (
            format!("the bodies it moves have total mass {mass} kg"),
            "add mass to the bodies it moves",
        ),
        Free if negligible(measured.moment) => (
            format!(
                "the bodies it moves (total mass {mass} kg) have a smallest principal moment of \
                 inertia about their centre of mass of {}",
                amount(measured.moment)
            ),
            "give the bodies it moves inertia about every axis",
        ),
        _ => return,
    };
    d.error(
        joint.span,
        format!(
            "the coordinate of joint `{}` has no inertia: {what}, so the mass matrix M(q) is \
             singular; {hint}, or make the joint fixed",
            joint.text
        ),
    );
}

/// Nominal-valued matrix helper for other modules.
pub(crate) fn nominal_matrix(m: &Mat3, p: &[f64]) -> Matrix3 {
    nominal33(m, p)
}

#[cfg(test)]
mod tests {
    //! The linear rules against the quadratic and cubic ones they replaced (issue 21), on
    //! random declarations with every mistake the walks meet: undeclared parents, joints from
    //! a body to itself, second parents, cycles, bodies with no joint, welded chains.
    use super::*;
    use crate::model::resolve;

    // The rules as they were (commit dcded28), verbatim but for their names.

    fn welded_groups_before(
        mechanism: &syntax::Mechanism,
        resolved: &Resolved,
        p: &[f64],
    ) -> Vec<WeldedGroup> {
        let index: HashMap<&str, usize> = resolved
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.name.text.as_str(), i))
            .collect();
        let mut parent_joint: HashMap<&str, &ResolvedJoint> = HashMap::new();
        for (joint, declared) in resolved.joints.iter().zip(&mechanism.joints) {
            if !is_self_joint(declared) {
                parent_joint
                    .entry(joint.child.text.as_str())
                    .or_insert(joint);
            }
        }
        let mut groups: Vec<WeldedGroup> = Vec::new();
        for (b, body) in resolved.bodies.iter().enumerate() {
            let (mut at, mut rotation, mut translation) = (b, linear::IDENTITY, [0.0; 3]);
            let mut root = Some(b);
            for _ in 0..=resolved.bodies.len() {
                let name = resolved.bodies[at].name.text.as_str();
                let Some(joint) = parent_joint
                    .get(name)
                    .filter(|j| j.kind == JointKind::Fixed)
                else {
                    root = Some(at);
                    break;
                };
                // The body's pose in the joint's parent: the placement composed on the left.
                let r = joint.rotation;
                rotation = linear::mul(&r, &rotation);
                translation = linear::add_vectors(
                    &linear::mul_vector(&r, &translation),
                    &crate::model::value::nominal3(&joint.translation, p),
                );
                if joint.parent.text == GROUND {
                    root = None;
                    break;
                }
                match index.get(joint.parent.text.as_str()) {
                    Some(&parent) => at = parent,
                    None => {
                        root = Some(at);
                        break;
                    }
                }
            }
            if root == Some(b) || body.name.text == GROUND {
                // Its own root (or a walk stopped by a cycle, reported elsewhere).
                (rotation, translation) = (linear::IDENTITY, [0.0; 3]);
                root = Some(b);
            }
            let member = Member {
                body: b,
                rotation,
                translation,
            };
            match groups.iter_mut().find(|g| g.root == root) {
                Some(group) => group.members.push(member),
                None => groups.push(WeldedGroup {
                    root,
                    members: vec![member],
                }),
            }
        }
        root_first(&mut groups);
        groups
    }

    fn bodies_reach_the_ground_before(mechanism: &syntax::Mechanism, d: &mut Diagnostics) {
        let parent_of: HashMap<&str, &str> = mechanism
            .joints
            .iter()
            .filter(|j| !is_self_joint(j))
            .map(|j| (j.child.text.as_str(), j.parent.text.as_str()))
            .collect();
        let has_self_joint = |n: &str| {
            mechanism
                .joints
                .iter()
                .any(|j| is_self_joint(j) && j.child.text == n)
        };
        let declared = |n: &str| mechanism.bodies.iter().any(|b| b.name.text == n);
        let mut reported_cycle: Vec<&str> = Vec::new();
        for body in mechanism.bodies.iter().filter(|b| b.name.text != GROUND) {
            let mut walk = body.name.text.as_str();
            let mut path = vec![walk];
            loop {
                match parent_of.get(walk) {
                    None => {
                        if walk == body.name.text && !has_self_joint(walk) {
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

    /// A random declaration of `n` bodies.
    fn declaration(seed: u64, n: usize) -> String {
        let mut state = seed;
        let mut next = move |k: u64| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % k
        };
        let mut text = String::from("pub struct R; gravity: none; outputs: [kinetic_energy];\n");
        for b in 0..n {
            text += &format!("body b{b} {{ mass: 1.0, com: [0.1, 0.0, 0.0], shape: point }}\n");
        }
        for j in 0..n + n / 4 {
            let child = next(n as u64);
            let parent = match next(10) {
                0 | 1 => "ground".to_owned(),
                2 => "nowhere".to_owned(),
                3 => format!("b{child}"),
                _ if j < n && next(3) > 0 => format!("b{}", next(child.max(1))),
                _ => format!("b{}", next(n as u64)),
            };
            let angles: Vec<f64> = (0..3).map(|_| next(628) as f64 / 100.0).collect();
            let at: Vec<f64> = (0..3).map(|_| next(200) as f64 / 100.0 - 1.0).collect();
            let (kind, axis) = if next(4) == 0 {
                ("revolute", ", axis: z")
            } else {
                ("fixed", "")
            };
            text += &format!(
                "joint j{j}: {kind}({parent} -> b{child}) {{ at: [{}, {}, {}], rotation: rpy({}, {}, {}){axis} }}\n",
                at[0], at[1], at[2], angles[0], angles[1], angles[2]
            );
        }
        text
    }

    fn messages(d: &mut Diagnostics) -> Vec<String> {
        match d.take_result() {
            Ok(()) => Vec::new(),
            Err(e) => e.into_iter().map(|e| e.to_string()).collect(),
        }
    }

    #[test]
    fn the_linear_walks_agree_with_the_quadratic_ones() {
        for seed in 0..300 {
            let n = 1 + (seed as usize % 23);
            let text = declaration(seed, n);
            let mechanism: syntax::Mechanism = syn::parse_str(&text).expect("parses");
            let mut d = Diagnostics::default();
            let resolved = resolve::resolve(&mechanism, &mut d);
            let p = resolved.nominal_parameters();
            let (new, old) = (
                welded_groups(&mechanism, &resolved, &p),
                welded_groups_before(&mechanism, &resolved, &p),
            );
            assert_eq!(new.len(), old.len(), "{text}");
            for (a, b) in new.iter().zip(&old) {
                assert_eq!(a.root, b.root, "{text}");
                let bodies = |g: &WeldedGroup| g.members.iter().map(|m| m.body).collect::<Vec<_>>();
                assert_eq!(bodies(a), bodies(b), "{text}");
                for (x, y) in a.members.iter().zip(&b.members) {
                    for i in 0..3 {
                        assert!(
                            (x.translation[i] - y.translation[i]).abs() < 1e-12,
                            "{text}"
                        );
                        for j in 0..3 {
                            assert!(
                                (x.rotation[i][j] - y.rotation[i][j]).abs() < 1e-12,
                                "{text}"
                            );
                        }
                    }
                }
            }
            let (mut new, mut old) = (Diagnostics::default(), Diagnostics::default());
            bodies_reach_the_ground(&mechanism, &mut new);
            bodies_reach_the_ground_before(&mechanism, &mut old);
            assert_eq!(messages(&mut new), messages(&mut old), "{text}");
        }
    }
}
