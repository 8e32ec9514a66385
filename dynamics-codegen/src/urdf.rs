//! URDF import: a URDF file's links and joints land in the same syntax tree as a hand-written
//! declaration, with spans pointing at the path literal, so every rule of the model stage
//! applies to them and reports at the path, naming the element.
//!
//! Links become bodies (mass, c = the inertial origin, I_G rotated from the inertial frame
//! into the link frame: I_G = R I Rᵀ); `revolute` and `continuous` joints become revolute
//! joints, `prismatic` prismatic, `fixed` fixed (merged later into composite bodies); the
//! joint origin gives the placement (translation and roll-pitch-yaw), `<dynamics damping>`
//! the viscous friction (dropped with `urdf_damping: false`, as Pinocchio's algorithms
//! ignore it), `<dynamics friction>` the Coulomb friction and `<limit>` the limits (both
//! carried to the generated constants, in no generated function; a `continuous` joint's
//! position is unbounded, a fixed joint's limits and friction are not read). The root link
//! is welded to the ground, or given a free joint with `floating_base: true`. Mimic, planar,
//! floating and spherical joints are refused: the tree expansion has no closed form for
//! them.
//!
//! Joints are declared sorted by name (byte order, stable), so that the tree, which takes
//! a body's children in declaration order, orders siblings as Pinocchio does: its URDF
//! parser walks the tree depth first and takes a link's child joints from urdfdom, which
//! keeps them in a map sorted by name, whatever their order in the file. The coordinates
//! of a branched URDF are thus Pinocchio's, each subtree contiguous.
//!
//! The XML is parsed by roxmltree; `read` maps its elements to URDF's meaning, as urdfdom
//! and urdf-rs do: the `<link>` and `<joint>` children of the root element, matched by local
//! name (so namespaces, comments and other elements such as `<material>`, `<gazebo>` and
//! `<transmission>` pass unread); a number parsed as Rust parses `f64` after trimming, a
//! vector as its space-separated words, each of which must be a number, exactly as many as
//! the attribute takes, all finite (a word such as `O.2` or `nan` is an error naming the
//! attribute, its element and the word, as urdfdom rejects it); a link without `<inertial>` has
//! zero mass and inertia, a missing `<origin>` or attribute of it is zero (the identity),
//! a missing `<axis>` is x; a `<limit>`'s `lower` and `upper` are 0 when absent and its
//! `velocity` and `effort` required (as URDF defines it), a joint without `<limit>` is
//! unbounded (urdfdom requires one on revolute and prismatic joints; the dynamics need
//! none); `quat_xyzw` replaces `rpy` from URDF 1.1 on; `<visual>`, `<collision>`,
//! `<calibration>` and `<safety_controller>` are not read. A
//! file that is not well-formed XML, or lacks an element or attribute URDF requires, is
//! reported at its line and column; so is a root element other than `<robot>`.
//!
//! A `continuous` joint has **one** coordinate here, its angle, unbounded (the same
//! coordinate as `revolute`). Pinocchio gives a continuous joint
//! two configuration coordinates, (cos θ, sin θ), and one velocity: configurations exchanged
//! with Pinocchio must convert θ = atan2(sin, cos) for each continuous joint, and its NQ
//! counts one per continuous joint more than this mechanism's.
//!
//! The import adds one joint of its own, attaching the root link to the ground:
//! `ground_weld` (or `root_joint`, free, with `floating_base: true`), or `ground_weld_2`,
//! `ground_weld_3`, ... when the file already uses that name.

use crate::model::linear;
use crate::syntax::{
    self, Axis, Body, InertiaForm, Joint, JointKind, Limits, Matrix, Name, Number, Rotation,
    SpanRange, Vector,
};
use roxmltree::{Document, Node, TextPos};
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

/// Reads the mechanism's URDF file (if it names one) and appends its bodies and joints.
/// Returns the absolute path read, so that the caller can make Cargo rebuild on change.
pub fn import(
    mechanism: &mut syntax::Mechanism,
    manifest_dir: &Path,
) -> syn::Result<Option<PathBuf>> {
    let Some(source) = mechanism.urdf.clone() else {
        return Ok(None);
    };
    let span = source.path.span();
    let written = source.path.value();
    let path = manifest_dir.join(&written);
    let text = std::fs::read_to_string(&path).map_err(|e| {
        syn::Error::new(
            span,
            format!(
                "cannot read URDF file `{written}` (looked for {}): {e}",
                path.display()
            ),
        )
    })?;
    let robot = read(&text).map_err(|e| syn::Error::new(span, e.describe(&written)))?;
    let mut errors: Option<syn::Error> = None;
    let mut refuse = |message: String| {
        let e = syn::Error::new(span, format!("URDF file `{written}`: {message}"));
        match &mut errors {
            Some(all) => all.combine(e),
            None => errors = Some(e),
        }
    };
    let number = |x: f64| Number::constant(x, span);
    let range = SpanRange::from(span);
    let vector = |v: [f64; 3]| Vector {
        components: v.map(number),
        span: range,
    };
    let name = |text: &str| Name {
        text: text.to_owned(),
        span,
    };
    // The inertial frames' rotations are cleaned as the joints' are when the declaration
    // sets `rotation_tolerance` (resolution reports a tolerance that is not a constant, or
    // out of range, and the compilation stops there).
    let tolerance = match mechanism.rotation_tolerance.as_ref().map(|n| &n.value) {
        Some(syntax::NumberValue::Constant(t)) => Some(*t),
        _ => None,
    };
    for link in &robot.links {
        let [ixx, ixy, ixz, iyy, iyz, izz] = link.inertial.inertia;
        let inertia_in_inertial = [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]];
        let [roll, pitch, yaw] =
            link.inertial.origin.rpy.map(|angle| {
                tolerance.map_or(angle, |t| crate::model::value::snapped_angle(angle, t))
            });
        let r = linear::rotation_from_rpy(roll, pitch, yaw);
        let inertia = linear::rotate(&r, &inertia_in_inertial);
        mechanism.bodies.push(Body {
            docs: vec![format!(" Link `{}` of `{written}`.", link.name)],
            name: name(&link.name),
            mass: Some(number(link.inertial.mass)),
            com: Some(vector(link.inertial.origin.xyz)),
            inertia: Some(InertiaForm::Matrix(Matrix {
                rows: inertia.map(|row| row.map(number)),
                span: range,
            })),
            span: range,
        });
    }
    // Sorted by name (stable): the tree takes a body's children in declaration order, and
    // Pinocchio takes a link's child joints in name order (see the module's docs).
    let mut joints: Vec<&UrdfJoint> = robot.joints.iter().collect();
    joints.sort_by(|a, b| a.name.cmp(&b.name));
    for joint in joints {
        let kind = match joint.kind {
            JointType::Revolute | JointType::Continuous => JointKind::Revolute,
            JointType::Prismatic => JointKind::Prismatic,
            JointType::Fixed => JointKind::Fixed,
            JointType::Floating => {
                refuse(format!(
                    "joint `{}` is a `floating` joint, which is not supported inside the tree; \
                     for a floating root link, leave its joint out of the file and declare \
                     `floating_base: true;` (the root link then gets a free joint `root_joint`)",
                    joint.name
                ));
                continue;
            }
            JointType::Planar | JointType::Spherical => {
                refuse(format!(
                    "joint `{}` is a `{}` joint, which is not supported (use revolute, \
                     continuous, prismatic or fixed joints)",
                    joint.name,
                    joint.kind.written()
                ));
                continue;
            }
        };
        if let (Some(mimicked), true) = (&joint.mimic, source.mimic) {
            refuse(format!(
                "joint `{}` mimics joint `{mimicked}`; mimic joints are not supported \
                 (`urdf_mimic: false;` makes each an independent coordinate, as Pinocchio's \
                 buildModel does by default; or make it fixed)",
                joint.name
            ));
            continue;
        }
        let moving = matches!(kind, JointKind::Revolute | JointKind::Prismatic);
        let mut docs = vec![format!(" Joint `{}` of `{written}`.", joint.name)];
        if let Some(mimicked) = &joint.mimic {
            docs.push(format!(
                " Its URDF `<mimic joint=\"{mimicked}\">` is ignored (`urdf_mimic: false;`): an \
                 independent coordinate, as in Pinocchio's `buildModel`."
            ));
        }
        if joint.kind == JointType::Continuous {
            docs.push(
                " A URDF `continuous` joint: one coordinate here, the angle θ (Pinocchio has \
                 two, cos θ and sin θ)."
                    .to_owned(),
            );
        }
        if moving && joint.damping != 0.0 {
            docs.push(if source.damping {
                format!(
                    " Its URDF damping b = {} enters the dynamics: b q̇ is in `inverse_dynamics` \
                     and `bias`, and opposes the motion in `forward_dynamics` (Pinocchio's \
                     `rnea`, `nle` and `aba` leave it out; `urdf_damping: false;` drops it).",
                    joint.damping
                )
            } else {
                format!(
                    " Its URDF damping {} is dropped (`urdf_damping: false;`).",
                    joint.damping
                )
            });
        }
        // A continuous joint has no position limits (urdfdom reads them, Pinocchio and the
        // URDF specification ignore them); a fixed joint has no limits at all.
        let bounded = matches!(joint.kind, JointType::Revolute | JointType::Prismatic);
        let limits = joint.limit.as_ref().filter(|_| moving).map(|l| Limits {
            lower: bounded.then(|| number(l.lower)),
            upper: bounded.then(|| number(l.upper)),
            velocity: Some(number(l.velocity)),
            effort: Some(number(l.effort)),
            span: range,
        });
        let coefficient = |x: f64| (moving && x != 0.0).then(|| number(x));
        mechanism.joints.push(Joint {
            docs,
            name: name(&joint.name),
            kind,
            kind_span: span,
            parent: name(&joint.parent),
            child: name(&joint.child),
            axis: moving.then(|| Axis {
                direction: vector(joint.axis),
                span: range,
            }),
            at: Some(vector(joint.origin.xyz)),
            rotation: Some(Rotation::Rpy(joint.origin.rpy.map(number), range)),
            placement: None,
            armature: None,
            damping: if source.damping {
                coefficient(joint.damping)
            } else {
                None
            },
            friction: coefficient(joint.friction),
            limits,
            driven: None,
        });
    }
    let children: HashSet<&str> = robot.joints.iter().map(|j| j.child.as_str()).collect();
    let roots: Vec<&str> = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .filter(|l| !children.contains(l))
        .collect();
    match roots.as_slice() {
        [root] => mechanism.joints.push(Joint {
            docs: vec![format!(" Attaches the root link `{root}` to the ground.")],
            name: name(&fresh_joint_name(
                if source.floating_base {
                    "root_joint"
                } else {
                    "ground_weld"
                },
                &robot,
            )),
            kind: if source.floating_base {
                JointKind::Free
            } else {
                JointKind::Fixed
            },
            kind_span: span,
            parent: name("ground"),
            child: name(root),
            axis: None,
            at: None,
            rotation: None,
            placement: None,
            armature: None,
            damping: None,
            friction: None,
            limits: None,
            driven: None,
        }),
        [] => refuse(no_root(&robot)),
        _ => refuse(format!(
            "expected exactly one root link (a link that is no joint's child), found {}: {}",
            roots.len(),
            roots.join(", ")
        )),
    }
    match errors {
        Some(e) => Err(e),
        None => Ok(Some(path)),
    }
}

/// The name of the joint the import adds to attach the root link: `base` (`root_joint` or
/// `ground_weld`) unless the file already names a joint or link so, else the first of
/// `base_2`, `base_3`, ... that it does not use, so that the import never collides with a
/// name of the file.
fn fresh_joint_name(base: &str, robot: &Robot) -> String {
    let used = |candidate: &str| {
        robot.joints.iter().any(|j| j.name == candidate)
            || robot.links.iter().any(|l| l.name == candidate)
    };
    if !used(base) {
        return base.to_owned();
    }
    (2..)
        .map(|k| format!("{base}_{k}"))
        .find(|candidate| !used(candidate))
        .unwrap_or_else(|| base.to_owned())
}

/// Why a file has no root link (every link is some joint's child): no links at all, the
/// joints forming a cycle (named, found by walking up from the first link through the
/// parents), or a parent that is not a declared link.
fn no_root(robot: &Robot) -> String {
    let Some(first) = robot.links.first() else {
        return "the file declares no `<link>`, so there is no root link".to_owned();
    };
    // Each link's first joint naming it as child.
    let mut parent_joints: HashMap<&str, &UrdfJoint> = HashMap::new();
    for joint in &robot.joints {
        parent_joints.entry(joint.child.as_str()).or_insert(joint);
    }
    let parent_joint = |link: &str| parent_joints.get(link).copied();
    // The joints met walking up from `first`, each to the parent of the one before, and
    // where each link was first met (the child of that path entry).
    let mut path: Vec<&UrdfJoint> = Vec::new();
    let mut met: HashMap<&str, usize> = HashMap::new();
    let mut link = first.name.as_str();
    loop {
        if let Some(&start) = met.get(link) {
            let steps: Vec<String> = path[start..]
                .iter()
                .rev()
                .map(|j| format!("`{}` → `{}` (joint `{}`)", j.parent, j.child, j.name))
                .collect();
            return format!(
                "there is no root link (every link is some joint's child) because the joints \
                 form a cycle: {}",
                steps.join(", ")
            );
        }
        let Some(joint) = parent_joint(link) else {
            return format!(
                "there is no root link (every link is some joint's child): the parents of \
                 link `{}` lead to `{link}`, which is not a `<link>` of the file",
                first.name
            );
        };
        met.entry(joint.child.as_str()).or_insert(path.len());
        path.push(joint);
        link = &joint.parent;
    }
}

/// The manifest directory of the crate being compiled (where URDF paths are relative to).
pub fn manifest_dir() -> PathBuf {
    std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default()
}

/// What the import reads of a URDF file: its links and joints, in file order.
struct Robot {
    links: Vec<Link>,
    joints: Vec<UrdfJoint>,
}

/// A `<link>`.
struct Link {
    name: String,
    inertial: Inertial,
}

/// A link's `<inertial>`; a link without one has zero mass and inertia.
#[derive(Default)]
struct Inertial {
    /// The inertial frame in the link frame: the mass centre and the inertia's axes.
    origin: Pose,
    mass: f64,
    /// `ixx, ixy, ixz, iyy, iyz, izz` in the inertial frame.
    inertia: [f64; 6],
}

/// An `<origin>`: a translation and roll-pitch-yaw angles; missing, the identity.
#[derive(Clone, Copy, Default)]
struct Pose {
    xyz: [f64; 3],
    rpy: [f64; 3],
}

/// A `<joint>`.
struct UrdfJoint {
    name: String,
    kind: JointType,
    /// The joint frame in the parent link's frame.
    origin: Pose,
    parent: String,
    child: String,
    /// In the joint frame; [1, 0, 0] when the joint has no `<axis>`.
    axis: [f64; 3],
    /// `<dynamics damping>`, 0 when absent.
    damping: f64,
    /// `<dynamics friction>`, 0 when absent.
    friction: f64,
    /// `<limit>`, when present.
    limit: Option<UrdfLimit>,
    /// The joint named by `<mimic joint>`.
    mimic: Option<String>,
}

/// A `<limit>`: `lower` and `upper` 0 when absent, `velocity` and `effort` required, as
/// URDF defines it.
struct UrdfLimit {
    lower: f64,
    upper: f64,
    velocity: f64,
    effort: f64,
}

/// URDF's joint types.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
    Spherical,
}

impl JointType {
    const ALL: [JointType; 7] = [
        JointType::Revolute,
        JointType::Continuous,
        JointType::Prismatic,
        JointType::Fixed,
        JointType::Floating,
        JointType::Planar,
        JointType::Spherical,
    ];

    /// The name of the type in a URDF file.
    fn written(self) -> &'static str {
        match self {
            JointType::Revolute => "revolute",
            JointType::Continuous => "continuous",
            JointType::Prismatic => "prismatic",
            JointType::Fixed => "fixed",
            JointType::Floating => "floating",
            JointType::Planar => "planar",
            JointType::Spherical => "spherical",
        }
    }
}

/// Why a file cannot be read as URDF, and where, when that is known.
#[derive(Debug)]
struct Malformed {
    at: Option<TextPos>,
    message: String,
}

impl Malformed {
    /// The message of the compile error.
    fn describe(&self, written: &str) -> String {
        match self.at {
            Some(at) => format!(
                "URDF file `{written}` is malformed at line {}, column {}: {}",
                at.row, at.col, self.message
            ),
            None => format!("URDF file `{written}` is malformed: {}", self.message),
        }
    }

    /// A file that is not well-formed XML: roxmltree's message, with its position (which
    /// roxmltree writes into its message as ` at row:col`) taken out.
    fn xml(e: &roxmltree::Error) -> Self {
        let position = e.pos();
        let at = format!(" at {position}");
        let described = e.to_string();
        let message = match e {
            roxmltree::Error::UnexpectedCloseTag(expected, actual, _) => format!(
                "found `</{actual}>` where `</{expected}>` was expected (is a `<{expected}>` \
                 element left open?)"
            ),
            _ => described.replacen(&at, "", 1),
        };
        Malformed {
            at: described.contains(&at).then_some(position),
            message,
        }
    }
}

/// Reads the links and joints of a URDF document.
fn read(text: &str) -> Result<Robot, Malformed> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..roxmltree::ParsingOptions::default()
    };
    let document = Document::parse_with_options(text, options).map_err(|e| Malformed::xml(&e))?;
    let robot = document.root_element();
    if robot.tag_name().name() != "robot" {
        return Err(Malformed {
            at: Some(document.text_pos_at(robot.range().start)),
            message: format!(
                "the root element is `<{}>`; a URDF file's root element is `<robot>`",
                robot.tag_name().name()
            ),
        });
    }
    let reader = Reader {
        document: &document,
        quaternions: version(robot) >= (1, 1),
    };
    let mut links = Vec::new();
    let mut joints = Vec::new();
    for element in robot.children().filter(Node::is_element) {
        match element.tag_name().name() {
            "link" => links.push(reader.link(element)?),
            "joint" => joints.push(reader.joint(element)?),
            _ => {}
        }
    }
    Ok(Robot { links, joints })
}

/// The URDF version of `<robot version="major.minor">`; 1.0 when absent or unreadable, as
/// in urdfdom.
fn version(robot: Node) -> (u32, u32) {
    robot
        .attribute("version")
        .and_then(|v| {
            let (major, minor) = v.trim().split_once('.')?;
            Some((major.parse().ok()?, minor.parse().ok()?))
        })
        .unwrap_or((1, 0))
}

/// Roll, pitch and yaw of the rotation of a quaternion (x, y, z, w), as urdfdom's
/// `Rotation::getRPY`: normalized first (zero is the identity), with pitch at ±π/2 (gimbal
/// lock) given as roll 0 and all of the turn about z.
fn quaternion_to_rpy([x, y, z, w]: [f64; 4]) -> [f64; 3] {
    let norm = (x * x + y * y + z * z + w * w).sqrt();
    let [x, y, z, w] = if norm > 0.0 {
        [x / norm, y / norm, z / norm, w / norm]
    } else {
        [0.0, 0.0, 0.0, 1.0]
    };
    let sin_pitch = -2.0 * (x * z - w * y);
    if sin_pitch <= -0.99999 {
        [0.0, -std::f64::consts::FRAC_PI_2, 2.0 * x.atan2(-y)]
    } else if sin_pitch >= 0.99999 {
        [0.0, std::f64::consts::FRAC_PI_2, 2.0 * (-x).atan2(y)]
    } else {
        let (xx, yy, zz, ww) = (x * x, y * y, z * z, w * w);
        [
            (2.0 * (y * z + w * x)).atan2(ww - xx - yy + zz),
            sin_pitch.asin(),
            (2.0 * (x * y + w * z)).atan2(ww + xx - yy - zz),
        ]
    }
}

/// Reads elements of one document, reporting at their line and column.
struct Reader<'a, 'input> {
    document: &'a Document<'input>,
    /// Whether `<origin quat_xyzw>` is read (URDF 1.1 and later).
    quaternions: bool,
}

impl<'a, 'input> Reader<'a, 'input> {
    /// An error at byte `at` of the text.
    fn error(&self, at: usize, message: String) -> Malformed {
        Malformed {
            at: Some(self.document.text_pos_at(at)),
            message,
        }
    }

    /// An error at an element.
    fn at(&self, element: Node, message: String) -> Malformed {
        self.error(element.range().start, message)
    }

    /// The child element `<name>` of `element`, which may appear at most once. `what` names
    /// `element` for messages.
    fn child(
        &self,
        element: Node<'a, 'input>,
        name: &str,
        what: &str,
    ) -> Result<Option<Node<'a, 'input>>, Malformed> {
        let mut found = element
            .children()
            .filter(|c| c.is_element() && c.tag_name().name() == name);
        let first = found.next();
        match found.next() {
            Some(second) => Err(self.at(second, format!("{what} has a second `<{name}>`"))),
            None => Ok(first),
        }
    }

    /// The child element `<name>` of `element`, which must appear once.
    fn required_child(
        &self,
        element: Node<'a, 'input>,
        name: &str,
        what: &str,
    ) -> Result<Node<'a, 'input>, Malformed> {
        self.child(element, name, what)?
            .ok_or_else(|| self.at(element, format!("{what} has no `<{name}>`")))
    }

    /// The attribute `name` of `element`, which must be present.
    fn required(
        &self,
        element: Node<'a, 'input>,
        name: &str,
        what: &str,
    ) -> Result<&'a str, Malformed> {
        element
            .attribute(name)
            .ok_or_else(|| self.at(element, format!("{what} has no `{name}`")))
    }

    /// An error at the value of attribute `name`.
    fn at_value(&self, element: Node, name: &str, message: String) -> Malformed {
        let at = element
            .attribute_node(name)
            .map_or(element.range().start, |a| a.range_value().start);
        self.error(at, message)
    }

    /// The number in attribute `name`, if present: one finite number (surrounding spaces
    /// allowed), as urdfdom requires.
    fn number(&self, element: Node, name: &str, what: &str) -> Result<Option<f64>, Malformed> {
        let Some(text) = element.attribute(name) else {
            return Ok(None);
        };
        match text.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Some(x)),
            Ok(_) => Err(self.at_value(
                element,
                name,
                format!("`{name}` of {what} is `{text}`, which is not a finite number"),
            )),
            Err(_) => Err(self.at_value(
                element,
                name,
                format!("`{name}` of {what} is `{text}`, which is not a number"),
            )),
        }
    }

    /// The number in attribute `name`, which must be present.
    fn required_number(
        &self,
        element: Node<'a, 'input>,
        name: &str,
        what: &str,
    ) -> Result<f64, Malformed> {
        self.required(element, name, what)?;
        Ok(self.number(element, name, what)?.unwrap_or_default())
    }

    /// The `N` space-separated numbers of attribute `name`, if present. Every word must be a
    /// finite number and there must be exactly `N` of them, as in urdfdom: a word that is not
    /// a number (`O.2` for `0.2`) is an error naming it, never passed over.
    fn numbers<const N: usize>(
        &self,
        element: Node,
        name: &str,
        what: &str,
    ) -> Result<Option<[f64; N]>, Malformed> {
        let Some(text) = element.attribute(name) else {
            return Ok(None);
        };
        let mut numbers = Vec::with_capacity(N);
        for word in text.split_whitespace() {
            match word.parse::<f64>() {
                Ok(x) if x.is_finite() => numbers.push(x),
                Ok(_) => {
                    return Err(self.at_value(
                        element,
                        name,
                        format!(
                            "`{name}` of {what} is `{text}`, in which `{word}` is not a finite \
                             number"
                        ),
                    ))
                }
                Err(_) => {
                    return Err(self.at_value(
                        element,
                        name,
                        format!(
                            "`{name}` of {what} is `{text}`, in which `{word}` is not a number"
                        ),
                    ))
                }
            }
        }
        numbers.try_into().map(Some).map_err(|numbers: Vec<f64>| {
            self.at_value(
                element,
                name,
                format!(
                    "`{name}` of {what} is `{text}`, which has {} numbers; it needs {N}",
                    numbers.len()
                ),
            )
        })
    }

    /// The `<origin>` child of `element` (`owner` names it), the identity when absent.
    fn origin(&self, element: Node<'a, 'input>, owner: &str) -> Result<Pose, Malformed> {
        let Some(origin) = self.child(element, "origin", owner)? else {
            return Ok(Pose::default());
        };
        let what = format!("the `<origin>` of {owner}");
        let xyz = self.numbers(origin, "xyz", &what)?.unwrap_or_default();
        let mut rpy = self.numbers(origin, "rpy", &what)?.unwrap_or_default();
        if self.quaternions && origin.attribute("quat_xyzw").is_some() {
            if origin.attribute("rpy").is_some() {
                return Err(self.at(
                    origin,
                    format!("{what} has both `rpy` and `quat_xyzw`; give one or the other"),
                ));
            }
            if let Some(q) = self.numbers::<4>(origin, "quat_xyzw", &what)? {
                rpy = quaternion_to_rpy(q);
            }
        }
        Ok(Pose { xyz, rpy })
    }

    /// A `<link>`.
    fn link(&self, element: Node<'a, 'input>) -> Result<Link, Malformed> {
        let name = self.required(element, "name", "a `<link>`")?;
        let owner = format!("link `{name}`");
        let inertial = match self.child(element, "inertial", &owner)? {
            None => Inertial::default(),
            Some(inertial) => {
                let what = format!("the `<inertial>` of {owner}");
                let origin = self.origin(inertial, &what)?;
                let mass = self.required_child(inertial, "mass", &what)?;
                let mass =
                    self.required_number(mass, "value", &format!("the `<mass>` of {owner}"))?;
                let element = self.required_child(inertial, "inertia", &what)?;
                let what = format!("the `<inertia>` of {owner}");
                let mut inertia = [0.0; 6];
                for (i, name) in ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
                    .iter()
                    .enumerate()
                {
                    inertia[i] = self.required_number(element, name, &what)?;
                }
                Inertial {
                    origin,
                    mass,
                    inertia,
                }
            }
        };
        Ok(Link {
            name: name.to_owned(),
            inertial,
        })
    }

    /// A `<joint>`.
    fn joint(&self, element: Node<'a, 'input>) -> Result<UrdfJoint, Malformed> {
        let name = self.required(element, "name", "a `<joint>`")?;
        let owner = format!("joint `{name}`");
        let written = self.required(element, "type", &owner)?;
        let kind = JointType::ALL
            .into_iter()
            .find(|t| t.written() == written)
            .ok_or_else(|| {
                self.at_value(
                    element,
                    "type",
                    format!(
                        "{owner} has type `{written}`, which is not a URDF joint type (revolute, \
                         continuous, prismatic, fixed, floating, planar or spherical)"
                    ),
                )
            })?;
        let link = |tag: &str| -> Result<String, Malformed> {
            let node = self.required_child(element, tag, &owner)?;
            let link = self.required(node, "link", &format!("the `<{tag}>` of {owner}"))?;
            Ok(link.to_owned())
        };
        let (parent, child) = (link("parent")?, link("child")?);
        let axis = match self.child(element, "axis", &owner)? {
            Some(axis) => {
                let what = format!("the `<axis>` of {owner}");
                self.required(axis, "xyz", &what)?;
                self.numbers(axis, "xyz", &what)?.unwrap_or_default()
            }
            None => [1.0, 0.0, 0.0],
        };
        let (damping, friction) = match self.child(element, "dynamics", &owner)? {
            Some(dynamics) => {
                let what = format!("the `<dynamics>` of {owner}");
                (
                    self.number(dynamics, "damping", &what)?.unwrap_or(0.0),
                    self.number(dynamics, "friction", &what)?.unwrap_or(0.0),
                )
            }
            None => (0.0, 0.0),
        };
        let limit = match self.child(element, "limit", &owner)? {
            Some(limit) => {
                let what = format!("the `<limit>` of {owner}");
                Some(UrdfLimit {
                    lower: self.number(limit, "lower", &what)?.unwrap_or(0.0),
                    upper: self.number(limit, "upper", &what)?.unwrap_or(0.0),
                    velocity: self.required_number(limit, "velocity", &what)?,
                    effort: self.required_number(limit, "effort", &what)?,
                })
            }
            None => None,
        };
        let mimic = match self.child(element, "mimic", &owner)? {
            Some(mimic) => Some(
                self.required(mimic, "joint", &format!("the `<mimic>` of {owner}"))?
                    .to_owned(),
            ),
            None => None,
        };
        Ok(UrdfJoint {
            name: name.to_owned(),
            kind,
            origin: self.origin(element, &owner)?,
            parent,
            child,
            axis,
            damping,
            friction,
            limit,
            mimic,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    fn import_tokens(tokens: proc_macro2::TokenStream) -> syn::Result<syntax::Mechanism> {
        let mut m: syntax::Mechanism = syn::parse2(tokens)?;
        import(&mut m, &manifest_dir().join("..").join("models"))?;
        Ok(m)
    }

    #[test]
    fn imports_the_ur5_twin() {
        let m = import_tokens(quote! { struct Ur5; urdf: "urdf/ur5.urdf"; }).expect("imports");
        assert_eq!(m.bodies.len(), 7);
        assert_eq!(m.joints.len(), 7);
        let model = crate::model::lower(&m).expect("valid");
        assert_eq!((model.nq, model.nv), (6, 6));
        assert_eq!(model.bodies[0].name, "shoulder_link");
    }

    #[test]
    fn floating_base_adds_a_free_joint() {
        let m = import_tokens(quote! { struct Ur5; urdf: "urdf/ur5.urdf"; floating_base: true; })
            .expect("imports");
        let model = crate::model::lower(&m).expect("valid");
        assert_eq!((model.nq, model.nv), (13, 12));
    }

    /// Imports `text` as a URDF file written into a fresh temporary directory.
    fn import_text(test: &str, text: &str) -> syn::Result<syntax::Mechanism> {
        import_text_with(test, text, quote!())
    }

    /// [`import_text`] with `settings` after the `urdf:` setting.
    fn import_text_with(
        test: &str,
        text: &str,
        settings: proc_macro2::TokenStream,
    ) -> syn::Result<syntax::Mechanism> {
        let dir = std::env::temp_dir().join(format!(
            "dynamics-codegen-urdf-{test}-{}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).expect("temporary directory");
        std::fs::write(dir.join("robot.urdf"), text).expect("write URDF");
        let mut m: syntax::Mechanism =
            syn::parse2(quote! { struct R; urdf: "robot.urdf"; #settings })?;
        let result = import(&mut m, &dir);
        std::fs::remove_dir_all(&dir).expect("remove temporary directory");
        result.map(|_| m)
    }

    #[test]
    fn malformed_file_reports_a_line_and_column() {
        let e = import_text(
            "malformed",
            "<robot name=\"r\">\n  <link name=\"base\"/>\n  <link name=\"arm\">\n</robot>\n",
        )
        .expect_err("malformed");
        assert_eq!(
            e.to_string(),
            "URDF file `robot.urdf` is malformed at line 4, column 1: found `</robot>` where \
             `</link>` was expected (is a `<link>` element left open?)"
        );
    }

    #[test]
    fn unsupported_joints_are_named_as_in_urdf() {
        let e = import_text(
            "planar",
            r#"<robot name="r">
                 <link name="base"/>
                 <link name="arm">
                   <inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
                 </link>
                 <joint name="slide" type="planar">
                   <parent link="base"/><child link="arm"/>
                 </joint>
               </robot>"#,
        )
        .expect_err("planar");
        assert!(
            e.to_string().contains("joint `slide` is a `planar` joint"),
            "{e}"
        );
    }

    /// The constant of a number the import wrote.
    fn constant(n: &Number) -> f64 {
        match n.value {
            syntax::NumberValue::Constant(x) => x,
            _ => panic!("not a constant: {n:?}"),
        }
    }

    fn vector3(v: &Vector) -> [f64; 3] {
        v.components.each_ref().map(constant)
    }

    fn inertia(body: &Body) -> [[f64; 3]; 3] {
        match &body.inertia {
            Some(InertiaForm::Matrix(m)) => {
                m.rows.each_ref().map(|row| row.each_ref().map(constant))
            }
            other => panic!("not a matrix: {other:?}"),
        }
    }

    fn rpy(joint: &Joint) -> [f64; 3] {
        match &joint.rotation {
            Some(Rotation::Rpy(angles, _)) => angles.each_ref().map(constant),
            other => panic!("not rpy: {other:?}"),
        }
    }

    /// A link `name` with a unit mass and inertia diag(1, 2, 3).
    fn link(name: &str) -> String {
        format!(
            r#"<link name="{name}"><inertial><mass value="1"/>
                 <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial></link>"#
        )
    }

    #[test]
    fn a_link_without_inertial_has_zero_mass_and_inertia() {
        let m = import_text(
            "no-inertial",
            &format!(
                r#"<robot name="r"><link name="base"/>{}
                   <joint name="j" type="revolute"><parent link="base"/><child link="arm"/></joint>
                   </robot>"#,
                link("arm")
            ),
        )
        .expect("imports");
        let base = &m.bodies[0];
        assert_eq!(base.name.text, "base");
        assert_eq!(base.mass.as_ref().map(constant), Some(0.0));
        assert_eq!(base.com.as_ref().map(vector3), Some([0.0; 3]));
        assert_eq!(inertia(base), [[0.0; 3]; 3]);
        // The arm's inertial frame is the link frame: no origin, no rotation.
        assert_eq!(
            inertia(&m.bodies[1]),
            [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 3.0]]
        );
    }

    #[test]
    fn missing_origins_are_the_identity_and_missing_attributes_zero() {
        let m = import_text(
            "no-origin",
            &format!(
                r#"<robot name="r"><link name="base"/>{}{}
                   <joint name="a" type="revolute"><parent link="base"/><child link="arm"/></joint>
                   <joint name="b" type="revolute"><origin xyz="0 0 0.5"/>
                     <parent link="arm"/><child link="hand"/></joint>
                   </robot>"#,
                link("arm"),
                link("hand")
            ),
        )
        .expect("imports");
        let [a, b] = [&m.joints[0], &m.joints[1]];
        assert_eq!(a.at.as_ref().map(vector3), Some([0.0; 3]));
        assert_eq!(rpy(a), [0.0; 3]);
        assert_eq!(b.at.as_ref().map(vector3), Some([0.0, 0.0, 0.5]));
        assert_eq!(rpy(b), [0.0; 3]);
    }

    #[test]
    fn the_default_axis_is_x_and_continuous_joints_are_revolute() {
        let m = import_text(
            "axis",
            &format!(
                r#"<robot name="r"><link name="base"/>{}{}{}
                   <joint name="spin" type="continuous"><parent link="base"/><child link="a"/></joint>
                   <joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
                     <axis xyz=" 0  1 0 "/><limit effort="1" velocity="2"/></joint>
                   <joint name="weld" type="fixed"><parent link="b"/><child link="c"/>
                     <axis xyz="0 0 1"/></joint>
                   </robot>"#,
                link("a"),
                link("b"),
                link("c")
            ),
        )
        .expect("imports");
        // Declared in name order, not the file's.
        let [slide, spin, weld] = [&m.joints[0], &m.joints[1], &m.joints[2]];
        assert_eq!(
            [&spin.name.text, &slide.name.text, &weld.name.text],
            ["spin", "slide", "weld"]
        );
        assert_eq!(spin.kind, JointKind::Revolute);
        assert!(
            spin.docs.iter().any(|d| d.contains("Pinocchio")),
            "{:?}",
            spin.docs
        );
        assert_eq!(
            spin.axis.as_ref().map(|a| vector3(&a.direction)),
            Some([1.0, 0.0, 0.0])
        );
        assert_eq!(slide.kind, JointKind::Prismatic);
        assert_eq!(
            slide.axis.as_ref().map(|a| vector3(&a.direction)),
            Some([0.0, 1.0, 0.0])
        );
        // A fixed joint takes no axis, even when the file gives one.
        assert_eq!(weld.kind, JointKind::Fixed);
        assert!(weld.axis.is_none());
        // The root is welded to the ground.
        assert_eq!(m.joints[3].name.text, "ground_weld");
        assert_eq!(m.joints[3].child.text, "base");
    }

    #[test]
    fn the_inertia_is_rotated_into_the_link_frame_and_damping_is_read() {
        // A quarter turn about z takes the inertial x axis to the link's y axis.
        let m = import_text(
            "rotated",
            r#"<robot name="r"><link name="base"/>
                 <link name="arm"><inertial>
                   <origin xyz="0.1 0.2 0.3" rpy="0 0 1.5707963267948966"/>
                   <mass value=" 2.5 "/>
                   <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/>
                 </inertial></link>
                 <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
                   <origin rpy="0.5 -0.25 1" xyz="1 2 3"/><dynamics damping="0.7" friction="1"/>
                 </joint>
                 <joint name="k" type="revolute"><parent link="arm"/><child link="tip"/>
                   <dynamics damping="0"/></joint>
                 <link name="tip"/>
               </robot>"#,
        )
        .expect("imports");
        let arm = &m.bodies[1];
        assert_eq!(arm.mass.as_ref().map(constant), Some(2.5));
        assert_eq!(arm.com.as_ref().map(vector3), Some([0.1, 0.2, 0.3]));
        let i = inertia(arm);
        let expected = [[2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]];
        for (row, expected_row) in i.iter().zip(expected) {
            for (x, e) in row.iter().zip(expected_row) {
                assert!((x - e).abs() < 1e-15, "{i:?}");
            }
        }
        let [j, k] = [&m.joints[0], &m.joints[1]];
        assert_eq!(rpy(j), [0.5, -0.25, 1.0]);
        assert_eq!(j.at.as_ref().map(vector3), Some([1.0, 2.0, 3.0]));
        assert_eq!(j.damping.as_ref().map(constant), Some(0.7));
        assert!(k.damping.is_none(), "zero damping is no damping");
        assert!(j.armature.is_none());
    }

    #[test]
    fn comments_namespaces_and_other_elements_are_passed_over() {
        let m = import_text(
            "namespaces",
            &format!(
                r#"<?xml version="1.0" encoding="utf-8"?>
                   <!-- exported by hand -->
                   <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
                     <xacro:property name="length" value="1"/>
                     <material name="grey"><color rgba="0.5 0.5 0.5 1"/></material>
                     <link name="base"><visual><geometry><box size="1 1 1"/></geometry></visual>
                       <!-- <inertial> left out on purpose --></link>
                     <gazebo reference="base"><link name="not_a_link"/></gazebo>
                     {}
                     <joint name="j" type="revolute"><!-- a comment -->
                       <parent link="base"/><child link="arm"/>
                       <calibration rising="0"/><safety_controller k_velocity="1"/></joint>
                     <transmission name="t"><joint name="j"/></transmission>
                   </robot>"#,
                link("arm")
            ),
        )
        .expect("imports");
        let names: Vec<&str> = m.bodies.iter().map(|b| b.name.text.as_str()).collect();
        assert_eq!(names, ["base", "arm"]);
        let names: Vec<&str> = m.joints.iter().map(|j| j.name.text.as_str()).collect();
        assert_eq!(names, ["j", "ground_weld"]);
        // Elements in a default namespace, or prefixed, are read by their local names.
        for robot in [
            r#"<robot xmlns="http://example.com/urdf" name="r"><link name="base"/></robot>"#,
            r#"<u:robot xmlns:u="http://example.com/urdf" name="r"><u:link name="base"/></u:robot>"#,
        ] {
            let m = import_text("default-namespace", robot).expect("imports");
            assert_eq!(m.bodies.len(), 1);
        }
    }

    #[test]
    fn quaternions_replace_rpy_from_urdf_1_1() {
        // A quarter turn about z: (x, y, z, w) = (0, 0, sin π/4, cos π/4).
        let file = |version: &str| {
            format!(
                r#"<robot name="r" {version}><link name="base"/>{}
                   <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
                   <origin quat_xyzw="0 0 0.7071067811865476 0.7071067811865476"/></joint>
                   </robot>"#,
                link("arm")
            )
        };
        let m = import_text("quaternion", &file(r#"version="1.1""#)).expect("imports");
        let [roll, pitch, yaw] = rpy(&m.joints[0]);
        assert_eq!((roll, pitch), (0.0, 0.0));
        assert!((yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-15, "{yaw}");
        // Before 1.1, quat_xyzw is not URDF and is passed over.
        let m = import_text("quaternion-1-0", &file("")).expect("imports");
        assert_eq!(rpy(&m.joints[0]), [0.0; 3]);
        // At gimbal lock (pitch ±π/2) the turn about z takes all of roll − yaw.
        assert_eq!(
            quaternion_to_rpy([
                0.0,
                std::f64::consts::FRAC_1_SQRT_2,
                0.0,
                std::f64::consts::FRAC_1_SQRT_2
            ]),
            [0.0, std::f64::consts::FRAC_PI_2, 0.0]
        );
        assert_eq!(quaternion_to_rpy([0.0; 4]), [0.0; 3]);
    }

    #[test]
    fn malformed_urdf_is_reported_at_the_element() {
        let cases = [
            (
                r#"<robot name="r">
  <link name="arm"><inertial><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
</robot>"#,
                "at line 2, column 20: the `<inertial>` of link `arm` has no `<mass>`",
            ),
            (
                r#"<robot name="r">
  <link name="arm"><inertial><mass value="one"/></inertial></link>
</robot>"#,
                "at line 2, column 43: `value` of the `<mass>` of link `arm` is `one`, which is \
                 not a number",
            ),
            (
                r#"<robot name="r"><link name="a"/><link name="b"/>
  <joint name="j" type="revolute"><origin xyz="0 0"/><parent link="a"/><child link="b"/></joint>
</robot>"#,
                "at line 2, column 48: `xyz` of the `<origin>` of joint `j` is `0 0`, which has 2 \
                 numbers; it needs 3",
            ),
            (
                r#"<robot name="r"><link name="a"/><link name="b"/>
  <joint name="j" type="hinge"><parent link="a"/><child link="b"/></joint>
</robot>"#,
                "at line 2, column 25: joint `j` has type `hinge`, which is not a URDF joint type \
                 (revolute, continuous, prismatic, fixed, floating, planar or spherical)",
            ),
            (
                r#"<robot name="r"><link name="a"/><link name="b"/>
  <joint name="j" type="fixed"><parent link="a"/><child link="b"/><parent link="b"/></joint>
</robot>"#,
                "at line 2, column 67: joint `j` has a second `<parent>`",
            ),
            (
                r#"<robot name="r"><link/></robot>"#,
                "at line 1, column 17: a `<link>` has no `name`",
            ),
        ];
        for (i, (text, expected)) in cases.into_iter().enumerate() {
            let e = import_text(&format!("malformed-urdf-{i}"), text).expect_err(expected);
            assert_eq!(
                e.to_string(),
                format!("URDF file `robot.urdf` is malformed {expected}")
            );
        }
    }

    /// The numbers of a joint's limits: lower, upper, velocity, effort (`None` when absent).
    fn limits(joint: &Joint) -> Option<[Option<f64>; 4]> {
        joint
            .limits
            .as_ref()
            .map(|l| [&l.lower, &l.upper, &l.velocity, &l.effort].map(|n| n.as_ref().map(constant)))
    }

    #[test]
    fn limits_and_friction_are_read() {
        let m = import_text(
            "limits",
            &format!(
                r#"<robot name="r"><link name="base"/>{}{}{}{}
                   <joint name="a" type="revolute"><parent link="base"/><child link="w"/>
                     <limit lower="-1.5" upper="2" velocity="3" effort="40"/>
                     <dynamics friction="0.25"/></joint>
                   <joint name="b" type="continuous"><parent link="w"/><child link="x"/>
                     <limit lower="-1" upper="1" velocity="5" effort="6"/></joint>
                   <joint name="c" type="prismatic"><parent link="x"/><child link="y"/>
                     <limit velocity="0.5" effort="100"/></joint>
                   <joint name="d" type="fixed"><parent link="y"/><child link="z"/>
                     <limit lower="-1" upper="1" velocity="5" effort="6"/>
                     <dynamics damping="1" friction="2"/></joint>
                   </robot>"#,
                link("w"),
                link("x"),
                link("y"),
                link("z")
            ),
        )
        .expect("imports");
        let [a, b, c, d] = [&m.joints[0], &m.joints[1], &m.joints[2], &m.joints[3]];
        assert_eq!(
            limits(a),
            Some([Some(-1.5), Some(2.0), Some(3.0), Some(40.0)])
        );
        assert_eq!(a.friction.as_ref().map(constant), Some(0.25));
        // A continuous joint's position is unbounded, whatever the file says.
        assert_eq!(limits(b), Some([None, None, Some(5.0), Some(6.0)]));
        assert!(b.friction.is_none());
        // `lower` and `upper` are 0 when absent, as URDF defines them.
        assert_eq!(
            limits(c),
            Some([Some(0.0), Some(0.0), Some(0.5), Some(100.0)])
        );
        // A fixed joint's limits, damping and friction are not read.
        assert_eq!(limits(d), None);
        assert!(d.friction.is_none() && d.damping.is_none());
        let model = crate::model::lower(&m).expect("valid");
        let tree: Vec<_> = model.bodies.iter().map(|b| &b.joint).collect();
        assert_eq!(tree[1].limits.lower, f64::NEG_INFINITY);
        assert_eq!(tree[1].limits.velocity, 5.0);
        assert_eq!(tree[0].friction, 0.25);
    }

    #[test]
    fn a_limit_needs_velocity_and_effort_and_must_be_ordered() {
        let file = |limit: &str| {
            format!(
                r#"<robot name="r"><link name="base"/>{}
                   <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
                   {limit}</joint></robot>"#,
                link("arm")
            )
        };
        let e = import_text(
            "limit-velocity",
            &file(r#"<limit lower="0" upper="1" effort="1"/>"#),
        )
        .expect_err("no velocity");
        assert!(
            e.to_string()
                .ends_with("the `<limit>` of joint `j` has no `velocity`"),
            "{e}"
        );
        // Imported, then rejected by the rules, which name the joint.
        let m = import_text(
            "limit-order",
            &file(r#"<limit lower="1" upper="-1" velocity="1" effort="-2"/>"#),
        )
        .expect("imports");
        let e = crate::model::lower(&m).expect_err("unordered");
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(
            messages,
            [
                "joint `j` has lower limit 1 above its upper limit -1; the lower limit must be ≤ \
                 the upper",
                "joint `j` has effort limit -2; it must be ≥ 0",
            ]
        );
    }

    #[test]
    fn urdf_damping_false_drops_the_damping_only() {
        let text = format!(
            r#"<robot name="r"><link name="base"/>{}
               <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
               <dynamics damping="0.7" friction="0.1"/></joint></robot>"#,
            link("arm")
        );
        let m = import_text("damped", &text).expect("imports");
        assert_eq!(m.joints[0].damping.as_ref().map(constant), Some(0.7));
        assert!(
            m.joints[0]
                .docs
                .iter()
                .any(|d| d.contains("Pinocchio's `rnea`")),
            "{:?}",
            m.joints[0].docs
        );
        let dir = std::env::temp_dir().join(format!(
            "dynamics-codegen-urdf-undamped-{}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).expect("temporary directory");
        std::fs::write(dir.join("robot.urdf"), &text).expect("write URDF");
        let mut m: syntax::Mechanism =
            syn::parse2(quote! { struct R; urdf: "robot.urdf"; urdf_damping: false; })
                .expect("parses");
        let result = import(&mut m, &dir);
        std::fs::remove_dir_all(&dir).expect("remove temporary directory");
        result.expect("imports");
        assert!(m.joints[0].damping.is_none());
        assert_eq!(m.joints[0].friction.as_ref().map(constant), Some(0.1));
    }

    #[test]
    fn mimic_floating_and_spherical_joints_are_refused_together() {
        let e = import_text(
            "refused",
            &format!(
                r#"<robot name="r"><link name="base"/>{}{}{}
                   <joint name="a" type="prismatic"><parent link="base"/><child link="x"/></joint>
                   <joint name="b" type="prismatic"><parent link="base"/><child link="y"/>
                     <mimic joint="a" multiplier="-1"/></joint>
                   <joint name="c" type="floating"><parent link="base"/><child link="z"/></joint>
                   </robot>"#,
                link("x"),
                link("y"),
                link("z")
            ),
        )
        .expect_err("refused");
        let messages: Vec<String> = e.into_iter().map(|e| e.to_string()).collect();
        assert_eq!(
            messages,
            [
                "URDF file `robot.urdf`: joint `b` mimics joint `a`; mimic joints are not \
                 supported (`urdf_mimic: false;` makes each an independent coordinate, as \
                 Pinocchio's buildModel does by default; or make it fixed)",
                "URDF file `robot.urdf`: joint `c` is a `floating` joint, which is not supported \
                 inside the tree; for a floating root link, leave its joint out of the file and \
                 declare `floating_base: true;` (the root link then gets a free joint `root_joint`)",
            ]
        );
    }

    /// `urdf_mimic: false;` imports a mimic joint as an independent coordinate (Pinocchio's
    /// `buildModel` without its `mimic` flag), saying so in the joint's docs.
    #[test]
    fn urdf_mimic_false_makes_a_mimic_joint_independent() {
        let text = format!(
            r#"<robot name="r"><link name="base"/>{}{}
               <joint name="a" type="prismatic"><parent link="base"/><child link="x"/>
                 <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.2"/></joint>
               <joint name="b" type="prismatic"><parent link="base"/><child link="y"/>
                 <axis xyz="0 -1 0"/><limit lower="0" upper="0.04" effort="20" velocity="0.2"/>
                 <mimic joint="a" multiplier="1"/></joint>
               </robot>"#,
            link("x"),
            link("y")
        );
        assert!(import_text("mimic-refused", &text).is_err());
        let m = import_text_with("mimic-independent", &text, quote!(urdf_mimic: false;))
            .expect("imports");
        let b = m
            .joints
            .iter()
            .find(|j| j.name.text == "b")
            .expect("joint b");
        assert_eq!(b.kind, syntax::JointKind::Prismatic);
        assert!(
            b.docs
                .iter()
                .any(|d| d.contains("`<mimic joint=\"a\">` is ignored")),
            "{:?}",
            b.docs
        );
        let model = crate::model::lower(&m).expect("valid");
        assert_eq!((model.nq, model.nv), (2, 2));
    }

    /// Two links `base` and `arm` joined by a revolute joint `j` with `origin` as its
    /// `<origin>` element and `axis` as its `<axis>` element.
    fn one_joint(version: &str, origin: &str, axis: &str) -> String {
        format!(
            r#"<robot name="r" {version}><link name="base"/>{}
               <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
               {origin}{axis}</joint></robot>"#,
            link("arm")
        )
    }

    #[test]
    fn words_that_are_not_finite_numbers_are_errors_not_dropped() {
        // Each used to import: the bad word was passed over and the rest read as the vector.
        let cases = [
            (
                one_joint("", r#"<origin xyz="0.1 O.2 0.3 0.4"/>"#, ""),
                "`xyz` of the `<origin>` of joint `j` is `0.1 O.2 0.3 0.4`, in which `O.2` is \
                 not a number",
            ),
            (
                one_joint("", "", r#"<axis xyz="0 zero 0 1"/>"#),
                "`xyz` of the `<axis>` of joint `j` is `0 zero 0 1`, in which `zero` is not a \
                 number",
            ),
            (
                one_joint(r#"version="1.1""#, r#"<origin quat_xyzw="nan 0 0 1"/>"#, ""),
                "`quat_xyzw` of the `<origin>` of joint `j` is `nan 0 0 1`, in which `nan` is \
                 not a finite number",
            ),
            (
                one_joint(r#"version="1.1""#, r#"<origin quat_xyzw="0 0 1"/>"#, ""),
                "`quat_xyzw` of the `<origin>` of joint `j` is `0 0 1`, which has 3 numbers; it \
                 needs 4",
            ),
            (
                one_joint("", r#"<origin xyz="0 0 0 1"/>"#, ""),
                "`xyz` of the `<origin>` of joint `j` is `0 0 0 1`, which has 4 numbers; it \
                 needs 3",
            ),
            (
                one_joint("", r#"<origin rpy="inf 0 0"/>"#, ""),
                "`rpy` of the `<origin>` of joint `j` is `inf 0 0`, in which `inf` is not a \
                 finite number",
            ),
            (
                r#"<robot name="r"><link name="arm"><inertial><mass value="NaN"/>
                   <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
                   </robot>"#
                    .to_owned(),
                "`value` of the `<mass>` of link `arm` is `NaN`, which is not a finite number",
            ),
        ];
        for (i, (text, expected)) in cases.iter().enumerate() {
            let e = import_text(&format!("bad-word-{i}"), text).expect_err(expected);
            let message = e.to_string();
            assert!(
                message.starts_with("URDF file `robot.urdf` is malformed at line ")
                    && message.ends_with(expected),
                "{message}"
            );
        }
    }

    #[test]
    fn the_root_element_must_be_robot() {
        let e = import_text(
            "not-robot",
            r#"<model name="r"><link name="base"/></model>"#,
        )
        .expect_err("not a robot");
        assert_eq!(
            e.to_string(),
            "URDF file `robot.urdf` is malformed at line 1, column 1: the root element is \
             `<model>`; a URDF file's root element is `<robot>`"
        );
    }

    #[test]
    fn a_cycle_without_a_root_link_is_named() {
        let e = import_text(
            "cycle",
            &format!(
                r#"<robot name="r">{}{}{}
                   <joint name="ab" type="revolute"><parent link="a"/><child link="b"/></joint>
                   <joint name="bc" type="revolute"><parent link="b"/><child link="c"/></joint>
                   <joint name="ca" type="revolute"><parent link="c"/><child link="a"/></joint>
                   </robot>"#,
                link("a"),
                link("b"),
                link("c")
            ),
        )
        .expect_err("cycle");
        assert_eq!(
            e.to_string(),
            "URDF file `robot.urdf`: there is no root link (every link is some joint's child) \
             because the joints form a cycle: `a` → `b` (joint `ab`), `b` → `c` (joint `bc`), \
             `c` → `a` (joint `ca`)"
        );
        let e = import_text("no-links", r#"<robot name="r"/>"#).expect_err("no links");
        assert!(e.to_string().contains("declares no `<link>`"), "{e}");
    }

    #[test]
    fn the_added_root_joint_does_not_collide_with_the_file_names() {
        for (floating, name) in [(false, "ground_weld"), (true, "root_joint")] {
            let text = format!(
                r#"<robot name="r"><link name="base"/>{}{}
                   <joint name="{name}" type="revolute"><parent link="base"/><child link="a"/>
                   </joint>
                   <joint name="{name}_2" type="revolute"><parent link="a"/><child link="b"/>
                   </joint></robot>"#,
                link("a"),
                link("b")
            );
            let dir = std::env::temp_dir().join(format!(
                "dynamics-codegen-urdf-collision-{floating}-{}",
                std::process::id()
            ));
            std::fs::create_dir_all(&dir).expect("temporary directory");
            std::fs::write(dir.join("robot.urdf"), text).expect("write URDF");
            let mut m: syntax::Mechanism = syn::parse2(if floating {
                quote! { struct R; urdf: "robot.urdf"; floating_base: true; }
            } else {
                quote! { struct R; urdf: "robot.urdf"; }
            })
            .expect("parses");
            let result = import(&mut m, &dir);
            std::fs::remove_dir_all(&dir).expect("remove temporary directory");
            result.expect("imports");
            let names: Vec<&str> = m.joints.iter().map(|j| j.name.text.as_str()).collect();
            let added = format!("{name}_3");
            assert_eq!(names, [name, &format!("{name}_2"), &added]);
            crate::model::lower(&m).expect("no duplicate joint name");
        }
    }

    /// The coordinates come depth first, each link's child joints in name order, as
    /// Pinocchio's URDF parser orders them, whatever the file's order (here breadth first,
    /// and the hips not in name order, nor their links).
    #[test]
    fn joints_come_depth_first_in_name_order() {
        let m = import_text(
            "order",
            &format!(
                r#"<robot name="r"><link name="base"/>{}{}{}{}
                   <joint name="fr_hip" type="revolute"><parent link="base"/><child link="a"/></joint>
                   <joint name="fl_hip" type="revolute"><parent link="base"/><child link="b"/></joint>
                   <joint name="fr_knee" type="revolute"><parent link="a"/><child link="c"/></joint>
                   <joint name="fl_knee" type="revolute"><parent link="b"/><child link="d"/></joint>
                   </robot>"#,
                link("a"),
                link("b"),
                link("c"),
                link("d")
            ),
        )
        .expect("imports");
        let model = crate::model::lower(&m).expect("valid");
        let joints: Vec<&str> = model.bodies.iter().map(|b| b.joint.name.as_str()).collect();
        assert_eq!(joints, ["fl_hip", "fl_knee", "fr_hip", "fr_knee"]);
        let parents: Vec<Option<usize>> = model.bodies.iter().map(|b| b.parent).collect();
        assert_eq!(parents, [None, Some(0), None, Some(2)]);
    }

    #[test]
    fn missing_file_is_an_error_at_the_path() {
        let e = import_tokens(quote! { struct R; urdf: "urdf/nope.urdf"; }).expect_err("missing");
        assert!(
            e.to_string()
                .contains("cannot read URDF file `urdf/nope.urdf`"),
            "{e}"
        );
    }
}
