//! Statics and mechanism force analysis: the textbook's free-body method, and the rules that
//! decide at compile time whether it is well posed.
//!
//! Every moving body i balances, in its own frame about its origin P_i,
//!
//!   Σ_c W_c,i(x) = W_i,   W_i = [m a_P + U h;  h × a_P + I_P α + ω × I_P ω] − applied loads,
//!
//! the textbook's shifted-inertia equations (h = m c, c = PG, I_P = I_G − m ĉ², gravity as an
//! acceleration of the base). The unknowns x are the components each connection can
//! transmit (a pin: two forces and no couple in the plane; a roller: one normal force; a
//! planar prismatic joint: a normal force and a couple; a weld: everything) and the efforts
//! of the driven joints. Each unknown acts on the connection's second body and, opposite,
//! on its first (action and reaction). Stacking the bodies gives A(q) x = b(q, q̇, q̈) with
//! 3 equations per body in planar motion (F_x, F_y, M_z) and 6 in space.
//!
//! Rules: the unknowns must match the equations (more: statically indeterminate; fewer: the
//! mechanism moves with no input), and they must match body by body (a maximum matching of
//! equations to the unknowns that can appear in them covers both): a structure that passes
//! the count but not the matching has redundant constraints in one place and a free motion
//! in another.

use super::linear;
use super::resolved::Resolved;
use super::value::{self, Value, Vec3};
use super::{Body, Diagnostics, JointKind};
use crate::syntax::{self, SpanRange};

pub use crate::syntax::{AnalysisPlane as Plane, ConstraintKind};

/// A connection between two bodies: a joint of the tree or a declared constraint.
#[derive(Clone, Debug)]
pub struct Connection {
    /// The joint's or the constraint's name.
    pub name: String,
    /// The first end's tree body (`None`: the ground); the unknowns' directions are fixed in
    /// its frame.
    pub first: Option<usize>,
    /// The second end's tree body; the unknowns act on it as written.
    pub second: Option<usize>,
    /// The connection point on the first body, in its tree-body frame.
    pub point_in_first: Vec3,
    /// The connection point on the second body, in its tree-body frame.
    pub point_in_second: Vec3,
    /// Whether it is a declared constraint (a support or a loop closure), whose components
    /// are also loop-closure equations φ(q) = 0.
    pub closes_loop: bool,
}

/// Whether an unknown is a force or a couple.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Component {
    /// A force through the connection point.
    Force,
    /// A couple.
    Couple,
}

/// One unknown of A(q) x = b: a reaction component or a driving effort.
#[derive(Clone, Debug)]
pub struct Unknown {
    /// `connection.component`, e.g. `A.x`, `B.normal`, `crank.torque`.
    pub name: String,
    /// Index into [`Statics::connections`].
    pub connection: usize,
    /// Force or couple.
    pub component: Component,
    /// Unit direction in the first end's tree-body frame.
    pub direction_in_first: [f64; 3],
    /// Whether this is a driven joint's effort rather than a reaction.
    pub effort: bool,
}

/// The force analysis of a mechanism.
#[derive(Clone, Debug)]
pub struct Statics {
    /// Planar (3 equations per body) or spatial (6).
    pub plane: Plane,
    /// Tree joints (in body order), then declared constraints (in declaration order).
    pub connections: Vec<Connection>,
    /// The unknowns x, connection by connection.
    pub unknowns: Vec<Unknown>,
}

impl Statics {
    /// The balance equations of one body: (force or moment, axis) in the body frame.
    pub fn rows_per_body(&self) -> &'static [(Component, usize)] {
        match self.plane {
            Plane::Planar => &[
                (Component::Force, 0),
                (Component::Force, 1),
                (Component::Couple, 2),
            ],
            Plane::Spatial => &[
                (Component::Force, 0),
                (Component::Force, 1),
                (Component::Force, 2),
                (Component::Couple, 0),
                (Component::Couple, 1),
                (Component::Couple, 2),
            ],
        }
    }

    /// The loop-closure equations: one per reaction component of a declared constraint.
    pub fn closure_components(&self) -> impl Iterator<Item = &Unknown> + '_ {
        self.unknowns
            .iter()
            .filter(|u| !u.effort && self.connections[u.connection].closes_loop)
    }

    /// Number of loop-closure equations.
    pub fn closure_count(&self) -> usize {
        self.closure_components().count()
    }
}

const E: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
const AXES: [&str; 3] = ["x", "y", "z"];

/// Two unit vectors normal to a unit axis: the other two coordinate axes (cyclic order) when
/// the axis is one, so that the couples of a hinge about z are the x and y components.
fn normals(axis: [f64; 3]) -> [[f64; 3]; 2] {
    for k in 0..3 {
        if (axis[k].abs() - 1.0).abs() < 1e-12 {
            return [E[(k + 1) % 3], E[(k + 2) % 3]];
        }
    }
    let least = (0..3)
        .min_by(|&i, &j| axis[i].abs().total_cmp(&axis[j].abs()))
        .unwrap_or(0);
    let first = linear::normalize(&cross(&axis, &E[least]));
    [first, cross(&axis, &first)]
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    linear::normalize(&v)
}

fn rotate(r: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    linear::mul_vector(r, &v)
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Where a declared body ended up: its tree body (`None`: ground), and the rotation and
/// translation of its declared frame in that tree body's frame.
pub(crate) type Locate<'a> = dyn Fn(&str) -> Option<(Option<usize>, [[f64; 3]; 3], Vec3)> + 'a;

/// Collects the unknowns of one connection.
struct Builder {
    plane: Plane,
    connections: Vec<Connection>,
    unknowns: Vec<Unknown>,
}

impl Builder {
    fn push(&mut self, suffix: &str, component: Component, direction: [f64; 3], effort: bool) {
        let connection = self.connections.len() - 1;
        self.unknowns.push(Unknown {
            name: format!("{}.{suffix}", self.connections[connection].name),
            connection,
            component,
            direction_in_first: direction,
            effort,
        });
    }

    /// Forces along the first frame's axes: x, y in the plane, x, y, z in space.
    fn forces(&mut self, rotation: &[[f64; 3]; 3]) {
        let n = if self.plane == Plane::Planar { 2 } else { 3 };
        for k in 0..n {
            self.push(AXES[k], Component::Force, rotate(rotation, E[k]), false);
        }
    }

    /// Couples along the first frame's axes: z in the plane, x, y, z in space.
    fn couples(&mut self, rotation: &[[f64; 3]; 3]) {
        match self.plane {
            Plane::Planar => self.push("couple", Component::Couple, rotate(rotation, E[2]), false),
            Plane::Spatial => {
                for k in 0..3 {
                    let name = format!("couple_{}", AXES[k]);
                    self.push(&name, Component::Couple, rotate(rotation, E[k]), false);
                }
            }
        }
    }

    /// A hinge about `axis`: forces, and (in space) the two couples normal to the axis.
    fn hinge(&mut self, rotation: &[[f64; 3]; 3], axis: [f64; 3]) {
        self.forces(rotation);
        if self.plane == Plane::Spatial {
            for (k, n) in normals(axis).into_iter().enumerate() {
                self.push(&format!("couple{}", k + 1), Component::Couple, n, false);
            }
        }
    }

    /// A slide along `axis`: the forces normal to it and every couple.
    fn slide(&mut self, rotation: &[[f64; 3]; 3], axis: [f64; 3]) {
        match self.plane {
            Plane::Planar => {
                let normal = cross(&E[2], &axis);
                self.push("normal", Component::Force, normal, false);
            }
            Plane::Spatial => {
                for (k, n) in normals(axis).into_iter().enumerate() {
                    self.push(&format!("normal{}", k + 1), Component::Force, n, false);
                }
            }
        }
        self.couples(rotation);
    }
}

/// Builds the force analysis, checking every rule; `None` when it is not asked for or an
/// error was reported.
pub(crate) fn build(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    bodies: &[Body],
    locate: &Locate,
    d: &mut Diagnostics,
) -> Option<Statics> {
    let outputs = resolved.outputs;
    let wanted = outputs.force_analysis || outputs.constraints;
    if !wanted && mechanism.constraints.is_empty() {
        return None;
    }
    let plane = mechanism.analysis.map_or(Plane::Planar, |(p, _)| p);
    let errors_before = d.has_errors();
    if plane == Plane::Planar {
        gravity_is_in_the_plane(mechanism, resolved, d);
    }
    let mut b = Builder {
        plane,
        connections: Vec::new(),
        unknowns: Vec::new(),
    };
    // Joints of the tree: the reactions their motion leaves, in the parent's frame, and the
    // effort along the motion when driven (every joint of a mechanism without constraints).
    let driven_by_default = mechanism.constraints.is_empty();
    for (i, body) in bodies.iter().enumerate() {
        let joint = &body.joint;
        let declared = mechanism.joints.iter().find(|j| j.name.text == joint.name);
        let driven = declared
            .and_then(|j| j.driven)
            .map_or(driven_by_default, |(flag, _)| flag);
        let span = declared.map_or_else(|| mechanism.name.span(), |j| j.kind_span);
        let r = joint.rotation_in_parent;
        b.connections.push(Connection {
            name: joint.name.clone(),
            first: body.parent,
            second: Some(i),
            point_in_first: joint.translation_in_parent.clone(),
            point_in_second: std::array::from_fn(|_| Value::constant(0.0)),
            closes_loop: false,
        });
        match joint.kind {
            JointKind::Revolute { axis_in_body } => {
                let axis = rotate(&r, axis_in_body);
                if plane == Plane::Planar {
                    planar_rotation(&joint.name, "revolute", &r, span, d);
                }
                b.hinge(&E, axis);
                if driven {
                    b.push("torque", Component::Couple, axis, true);
                }
            }
            JointKind::Prismatic { axis_in_body } => {
                let axis = rotate(&r, axis_in_body);
                if plane == Plane::Planar {
                    planar_rotation(&joint.name, "prismatic", &r, span, d);
                    direction_in_plane(&joint.name, "axis", axis, span, d);
                }
                b.slide(&E, axis);
                if driven {
                    b.push("force", Component::Force, axis, true);
                }
            }
            JointKind::Free => {
                if plane == Plane::Planar {
                    d.error(span, format!("joint `{}` is free, but the force analysis is planar; declare `force_analysis: spatial;` or use planar joints", joint.name));
                }
                if declared
                    .and_then(|j| j.driven)
                    .is_some_and(|(flag, _)| flag)
                {
                    d.error(span, format!("the free joint `{}` cannot be driven: it has no actuator; apply its loads with `load`", joint.name));
                }
            }
        }
    }
    for constraint in &mechanism.constraints {
        declare_constraint(&mut b, constraint, locate, d);
    }
    if let (Some(constraint), Some(free)) = (
        mechanism.constraints.first(),
        bodies.iter().find(|b| b.joint.kind == JointKind::Free),
    ) {
        d.error(constraint.name.span, format!("constraints cannot close loops through the free joint `{}` (its quaternion coordinates have no loop-closure Jacobian here); declare the floating body with planar or revolute/prismatic joints", free.joint.name));
    }
    if d.has_errors() && !errors_before {
        return None;
    }
    let statics = Statics {
        plane,
        connections: b.connections,
        unknowns: b.unknowns,
    };
    if !d.has_errors() {
        unknowns_match_equations(mechanism, &statics, bodies, d);
    }
    Some(statics)
}

/// The connection and unknowns of one declared constraint.
fn declare_constraint(
    b: &mut Builder,
    constraint: &syntax::Constraint,
    locate: &Locate,
    d: &mut Diagnostics,
) {
    let name = &constraint.name.text;
    let end = |end: &syntax::ConstraintEnd| -> Option<(Option<usize>, [[f64; 3]; 3], Vec3)> {
        let (body, rotation, translation) = locate(&end.body.text)?;
        let point = match &end.at {
            Some(v) => v.components.clone().map(|c| match c.value {
                syntax::NumberValue::Constant(x) => Value::constant(x),
                syntax::NumberValue::Parameter { .. } => Value::constant(f64::NAN),
            }),
            None => std::array::from_fn(|_| Value::constant(0.0)),
        };
        Some((
            body,
            rotation,
            value::add(&value::rotate(&rotation, &point), &translation),
        ))
    };
    let (Some(first), Some(second)) = (end(&constraint.first), end(&constraint.second)) else {
        for e in [&constraint.first, &constraint.second] {
            if locate(&e.body.text).is_none() {
                d.error(e.body.span, format!("constraint `{name}` names `{}`, which is not a declared body (or `ground`)", e.body.text));
            }
        }
        return;
    };
    for e in [&constraint.first, &constraint.second] {
        if let Some(v) = &e.at {
            for c in &v.components {
                if matches!(c.value, syntax::NumberValue::Parameter { .. }) {
                    d.error(c.span, "a constraint's point must be a constant here");
                }
            }
        }
    }
    if first.0 == second.0 {
        let what = if first.0.is_none() {
            "the ground"
        } else {
            "the same body"
        };
        d.error(constraint.name.span, format!("constraint `{name}` connects {what} to itself (`{}` and `{}`): it transmits nothing", constraint.first.body.text, constraint.second.body.text));
        return;
    }
    let rotation = first.1;
    let direction = constraint.direction.as_ref().map(|axis| {
        let raw: [f64; 3] = std::array::from_fn(|i| match axis.direction.components[i].value {
            syntax::NumberValue::Constant(x) => x,
            syntax::NumberValue::Parameter { .. } => f64::NAN,
        });
        (raw, axis.span)
    });
    let mut direction_in_first = |what: &str, default: Option<[f64; 3]>| -> Option<[f64; 3]> {
        let raw = match (direction, default) {
            (Some((raw, span)), _) => {
                let n = linear::norm(&raw);
                if n == 0.0 || !n.is_finite() {
                    d.error(span, format!("the {what} of constraint `{name}` must be a nonzero constant direction"));
                    return None;
                }
                raw
            }
            (None, Some(default)) => default,
            (None, None) => {
                d.error(constraint.kind_span, format!("constraint `{name}` needs its {what}: `{{ {what}: y }}`, in the frame of `{}`", constraint.first.body.text));
                return None;
            }
        };
        let v = unit(rotate(&rotation, unit(raw)));
        if b.plane == Plane::Planar {
            let span = direction.map_or(SpanRange::from(constraint.kind_span), |(_, s)| s);
            direction_in_plane(name, what, v, span, d);
        }
        Some(v)
    };
    let kind = constraint.kind;
    let axis = match kind {
        ConstraintKind::Roller => direction_in_first("normal", None),
        ConstraintKind::Prismatic => direction_in_first("axis", None),
        ConstraintKind::Pin if b.plane == Plane::Spatial => {
            direction_in_first("axis", Some([0.0, 0.0, 1.0]))
        }
        _ => {
            if let Some((_, span)) = direction {
                d.error(
                    span,
                    format!(
                        "a {} constraint has no direction; remove it",
                        kind_name(kind)
                    ),
                );
            }
            Some([0.0, 0.0, 1.0])
        }
    };
    if kind == ConstraintKind::Ball && b.plane == Plane::Planar {
        d.error(constraint.kind_span, format!("constraint `{name}` is a ball joint, which needs `force_analysis: spatial;` (in the plane it is a pin)"));
        return;
    }
    let Some(axis) = axis else { return };
    b.connections.push(Connection {
        name: name.clone(),
        first: first.0,
        second: second.0,
        point_in_first: first.2,
        point_in_second: second.2,
        closes_loop: true,
    });
    match kind {
        ConstraintKind::Pin => b.hinge(&rotation, axis),
        ConstraintKind::Ball => b.forces(&rotation),
        ConstraintKind::Roller => b.push("normal", Component::Force, axis, false),
        ConstraintKind::Prismatic => b.slide(&rotation, axis),
        ConstraintKind::Weld => {
            b.forces(&rotation);
            b.couples(&rotation);
        }
    }
}

fn kind_name(kind: ConstraintKind) -> &'static str {
    match kind {
        ConstraintKind::Pin => "pin",
        ConstraintKind::Ball => "ball",
        ConstraintKind::Roller => "roller",
        ConstraintKind::Prismatic => "prismatic",
        ConstraintKind::Weld => "weld",
    }
}

/// Rule: in a planar analysis, gravity lies in the xy plane.
fn gravity_is_in_the_plane(
    mechanism: &syntax::Mechanism,
    resolved: &Resolved,
    d: &mut Diagnostics,
) {
    if resolved.gravity[2] != 0.0 {
        let span = mechanism
            .gravity
            .as_ref()
            .map_or(SpanRange::from(mechanism.name.span()), |g| g.span());
        let default = if mechanism.gravity.is_none() {
            " (the default when `gravity:` is absent is [0.0, 0.0, -9.81])"
        } else {
            ""
        };
        d.error(span, format!("gravity has a z component ({}){default}, but the force analysis is planar (motion in the xy plane); put gravity in the plane (e.g. `gravity: [0.0, -9.81, 0.0];`), declare `gravity: none;` for none, or declare `force_analysis: spatial;`", super::rules::computed(resolved.gravity[2])));
    }
}

/// Rule: in a planar analysis, a joint's placement keeps the z axis (a rotation about z).
fn planar_rotation(
    name: &str,
    kind: &str,
    r: &[[f64; 3]; 3],
    span: proc_macro2::Span,
    d: &mut Diagnostics,
) {
    let z = rotate(r, E[2]);
    if (z[2].abs() - 1.0).abs() > 1e-12 {
        d.error(span, format!("the {kind} joint `{name}` leaves the xy plane (its placement turns z to [{}, {}, {}]), but the force analysis is planar; declare `force_analysis: spatial;`", super::rules::computed(z[0]), super::rules::computed(z[1]), super::rules::computed(z[2])));
    }
}

/// Rule: in a planar analysis, a joint's or a constraint's direction lies in the plane
/// (a revolute axis is the normal z: checked by [`planar_rotation`] and the axis itself).
fn direction_in_plane(
    name: &str,
    what: &str,
    v: [f64; 3],
    span: impl Into<SpanRange>,
    d: &mut Diagnostics,
) {
    if v[2].abs() > 1e-12 {
        d.error(span, format!("the {what} of `{name}` has a z component ({}), but the force analysis is planar: it must lie in the xy plane", super::rules::computed(v[2])));
    }
}

/// Rule: the unknowns match the balance equations, in number and body by body.
///
/// The structure is the bipartite graph of equations (rows: each body's balance
/// components) and unknowns (an unknown of a connection can appear in every row of its two
/// bodies of its kind: a force in the force rows and the moment rows, a couple in the moment
/// rows). A maximum matching that leaves an equation unmatched means A(q) is singular for
/// every q; the equations reachable from it by alternating paths belong to bodies that can
/// move with no input, the unknowns reachable from an unmatched unknown to redundant
/// constraints.
fn unknowns_match_equations(
    mechanism: &syntax::Mechanism,
    statics: &Statics,
    bodies: &[Body],
    d: &mut Diagnostics,
) {
    let rows = statics.rows_per_body();
    let equations = rows.len() * bodies.len();
    let unknowns = statics.unknowns.len();
    let per_body = if statics.plane == Plane::Planar {
        "3 per body in planar motion"
    } else {
        "6 per body"
    };
    let bodies_word = if bodies.len() == 1 { "body" } else { "bodies" };
    let body_list = bodies
        .iter()
        .map(|b| format!("`{}`", b.name))
        .collect::<Vec<_>>()
        .join(", ");
    let unknown_list = if statics.unknowns.is_empty() {
        "none".to_owned()
    } else {
        statics
            .unknowns
            .iter()
            .map(|u| u.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    let last_constraint = mechanism.constraints.last().map(|c| c.name.span);
    if unknowns > equations {
        d.error(
            last_constraint.unwrap_or_else(|| mechanism.name.span()),
            format!(
                "the mechanism is statically indeterminate: {unknowns} unknown reaction components \
                 and efforts ({unknown_list}) against {equations} balance equations ({per_body} × \
                 {} {bodies_word}: {body_list}); {} of them cannot be found from equilibrium: remove a \
                 support, release a component (a pin to a roller) or undrive a joint",
                bodies.len(),
                unknowns - equations
            ),
        );
        return;
    }
    if unknowns < equations {
        d.error(
            mechanism.name.span(),
            format!(
                "the mechanism has fewer inputs than degrees of freedom: {unknowns} unknown \
                 reaction components and efforts ({unknown_list}) against {equations} balance \
                 equations ({per_body} × {} {bodies_word}: {body_list}), so {} degree(s) of freedom \
                 move with no input; mark the driving joints `driven: true` or add supports",
                bodies.len(),
                equations - unknowns
            ),
        );
        return;
    }
    // Which rows each unknown can appear in.
    let touches = |u: &Unknown, row: usize| -> bool {
        let (body, (kind, _)) = (row / rows.len(), rows[row % rows.len()]);
        let c = &statics.connections[u.connection];
        (c.first == Some(body) || c.second == Some(body))
            && (u.component == Component::Force || kind == Component::Couple)
    };
    let adjacency: Vec<Vec<usize>> = (0..equations)
        .map(|row| {
            (0..unknowns)
                .filter(|&k| touches(&statics.unknowns[k], row))
                .collect()
        })
        .collect();
    let (row_match, col_match) = maximum_matching(&adjacency, unknowns);
    if row_match.iter().all(Option::is_some) {
        return;
    }
    // Rows reachable from unmatched rows (bodies that move freely); columns reachable from
    // unmatched columns (redundant constraints).
    let mut free_rows = vec![false; equations];
    let mut stack: Vec<usize> = (0..equations).filter(|&r| row_match[r].is_none()).collect();
    while let Some(r) = stack.pop() {
        if std::mem::replace(&mut free_rows[r], true) {
            continue;
        }
        for &c in &adjacency[r] {
            if let Some(next) = col_match[c] {
                stack.push(next);
            }
        }
    }
    let mut redundant = vec![false; unknowns];
    let mut stack: Vec<usize> = (0..unknowns).filter(|&c| col_match[c].is_none()).collect();
    while let Some(c) = stack.pop() {
        if std::mem::replace(&mut redundant[c], true) {
            continue;
        }
        for r in (0..equations).filter(|&r| adjacency[r].contains(&c)) {
            if let Some(next) = row_match[r] {
                stack.push(next);
            }
        }
    }
    let mut moving: Vec<&str> = Vec::new();
    for (r, _) in free_rows.iter().enumerate().filter(|(_, f)| **f) {
        let name = bodies[r / rows.len()].name.as_str();
        if !moving.contains(&name) {
            moving.push(name);
        }
    }
    let redundant_names: Vec<&str> = statics
        .unknowns
        .iter()
        .zip(&redundant)
        .filter(|(_, r)| **r)
        .map(|(u, _)| u.name.as_str())
        .collect();
    // Point at a declared constraint among the redundant ones if there is one.
    let redundant_connections = || {
        statics
            .unknowns
            .iter()
            .zip(&redundant)
            .filter(|(_, r)| **r)
            .map(|(u, _)| &statics.connections[u.connection])
    };
    let first_redundant = redundant_connections()
        .find(|c| c.closes_loop)
        .or_else(|| redundant_connections().next())
        .map(|c| c.name.as_str());
    let span = first_redundant
        .and_then(|n| {
            mechanism
                .constraints
                .iter()
                .map(|c| &c.name)
                .chain(mechanism.joints.iter().map(|j| &j.name))
                .find(|c| c.text == n)
        })
        .map_or_else(|| mechanism.name.span(), |n| n.span);
    let quote = |names: &[&str]| {
        names
            .iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    d.error(
        span,
        format!(
            "redundant constraint: the {unknowns} unknowns match the {equations} balance equations \
             in number but not body by body: the reactions {} over-constrain their bodies \
             (equilibrium cannot determine them), while {} can move with no input; A(q) is \
             singular in every configuration",
            redundant_names.join(", "),
            quote(&moving)
        ),
    );
}

/// A maximum bipartite matching of rows to columns (augmenting paths): for each row its
/// column, for each column its row.
fn maximum_matching(
    adjacency: &[Vec<usize>],
    columns: usize,
) -> (Vec<Option<usize>>, Vec<Option<usize>>) {
    let mut row_match = vec![None; adjacency.len()];
    let mut col_match: Vec<Option<usize>> = vec![None; columns];
    fn augment(
        r: usize,
        adjacency: &[Vec<usize>],
        seen: &mut [bool],
        row_match: &mut [Option<usize>],
        col_match: &mut [Option<usize>],
    ) -> bool {
        for &c in &adjacency[r] {
            if std::mem::replace(&mut seen[c], true) {
                continue;
            }
            let free = match col_match[c] {
                None => true,
                Some(other) => augment(other, adjacency, seen, row_match, col_match),
            };
            if free {
                row_match[r] = Some(c);
                col_match[c] = Some(r);
                return true;
            }
        }
        false
    }
    for r in 0..adjacency.len() {
        let mut seen = vec![false; columns];
        augment(r, adjacency, &mut seen, &mut row_match, &mut col_match);
    }
    (row_match, col_match)
}
