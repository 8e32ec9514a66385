//! The syntax tree of a mechanism declaration. Every node keeps its span.

use proc_macro2::{Punct, Spacing, Span, TokenStream, TokenTree};
use quote::ToTokens;

/// The tokens a node came from, as the spans of its first and last token.
///
/// On stable Rust `Span::join` returns `None`, so a single `Span` of `-2.0` or `1.0 / 0.0`
/// would shrink to its first token. Keeping both ends lets an error cover the whole
/// expression: [`SpanRange::error`] builds it as `syn::Error::new_spanned` does, and the
/// compiler underlines everything from `first` to `last`.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// The span of the first token.
    pub first: Span,
    /// The span of the last token (the same as `first` for a single token).
    pub last: Span,
}

impl SpanRange {
    /// From the first to the last token.
    pub fn new(first: Span, last: Span) -> Self {
        SpanRange { first, last }
    }

    /// The first and last tokens of a syntax node.
    pub fn of(tokens: &impl ToTokens) -> Self {
        let mut iter = tokens.to_token_stream().into_iter();
        let first = iter.next().map_or_else(Span::call_site, |t| t.span());
        let last = iter.last().map_or(first, |t| t.span());
        SpanRange { first, last }
    }

    /// An error covering the whole range.
    pub fn error(self, message: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(self, message)
    }
}

impl From<Span> for SpanRange {
    fn from(span: Span) -> Self {
        SpanRange {
            first: span,
            last: span,
        }
    }
}

impl ToTokens for SpanRange {
    /// Two placeholder tokens carrying the two spans, for `syn::Error::new_spanned`.
    fn to_tokens(&self, tokens: &mut TokenStream) {
        for span in [self.first, self.last] {
            let mut punct = Punct::new('.', Spacing::Alone);
            punct.set_span(span);
            tokens.extend([TokenTree::Punct(punct)]);
        }
    }
}

/// A number as written: a compile-time constant, or a parameter times a constant.
#[derive(Clone, Debug)]
pub struct Number {
    /// What the number is.
    pub value: NumberValue,
    /// The tokens it came from.
    pub span: SpanRange,
}

/// The value of a [`Number`].
#[derive(Clone, Debug, PartialEq)]
pub enum NumberValue {
    /// A constant folded at compile time.
    Constant(f64),
    /// `coefficient · name`, where `name` must be a declared parameter.
    Parameter {
        /// The parameter's name.
        name: String,
        /// The constant it is scaled by.
        coefficient: f64,
    },
}

impl Number {
    /// A constant at a span.
    pub fn constant(value: f64, span: impl Into<SpanRange>) -> Self {
        Number {
            value: NumberValue::Constant(value),
            span: span.into(),
        }
    }
}

/// An identifier with its span.
#[derive(Clone, Debug)]
pub struct Name {
    /// The text.
    pub text: String,
    /// Where it was written.
    pub span: Span,
}

/// Three numbers `[x, y, z]`.
#[derive(Clone, Debug)]
pub struct Vector {
    /// The components.
    pub components: [Number; 3],
    /// The bracketed tokens.
    pub span: SpanRange,
}

/// A 3×3 matrix `[[..], [..], [..]]`, by rows.
#[derive(Clone, Debug)]
pub struct Matrix {
    /// The rows.
    pub rows: [[Number; 3]; 3],
    /// The bracketed tokens.
    pub span: SpanRange,
}

/// Gravity when a mechanism declares none: (0, 0, −9.81) m/s², the default of Pinocchio,
/// MuJoCo and Drake. The macro and the command-line compiler share it.
pub const DEFAULT_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// The value of `gravity:`.
#[derive(Clone, Debug)]
pub enum Gravity {
    /// `gravity: [x, y, z];`
    Vector(Vector),
    /// `gravity: none;` (zero gravity), at the word `none`.
    None(SpanRange),
}

impl Gravity {
    /// The tokens of the value.
    pub fn span(&self) -> SpanRange {
        match self {
            Gravity::Vector(v) => v.span,
            Gravity::None(span) => *span,
        }
    }
}

/// A whole `mechanism!` invocation.
#[derive(Clone, Debug)]
pub struct Mechanism {
    /// Doc comments on the mechanism (each line's text).
    pub docs: Vec<String>,
    /// Visibility of the generated type, as written.
    pub visibility: syn::Visibility,
    /// The generated type's name.
    pub name: syn::Ident,
    /// Gravity in the world frame, as declared; `None` when absent, which means the
    /// default (0, 0, −9.81) (`DEFAULT_GRAVITY`).
    pub gravity: Option<Gravity>,
    /// Requested outputs (all when absent).
    pub outputs: Option<Vec<Name>>,
    /// Declared symbolic parameters and their nominal values.
    pub parameters: Vec<Parameter>,
    /// Checks the user waived, with `allow: [...]`.
    pub allow: Vec<Name>,
    /// A URDF file the bodies and joints come from.
    pub urdf: Option<UrdfSource>,
    /// Bodies, in declaration order.
    pub bodies: Vec<Body>,
    /// Joints, in declaration order.
    pub joints: Vec<Joint>,
    /// Applied loads, in declaration order.
    pub loads: Vec<Load>,
    /// Supports and loop-closing connections, in declaration order.
    pub constraints: Vec<Constraint>,
    /// Operational frames, in declaration order.
    pub frames: Vec<Frame>,
    /// `frames: [..]`: the frames the frame outputs cover (every frame when absent).
    pub frame_selection: Option<Vec<Name>>,
    /// `force_analysis: planar;` or `spatial;` (planar when absent).
    pub analysis: Option<(AnalysisPlane, Span)>,
    /// `isa: dispatch;` or `baseline;` (dispatch when absent).
    pub isa: Option<Isa>,
    /// `lanes: true;`: each function expanded with packed values also gets the body the
    /// SIMD lane types run, with none (false when absent).
    pub lanes: bool,
    /// `rotation_tolerance: 1e-10;`: rotation entries within it of 0 or ±1 are taken as
    /// exactly that (1e-15 when absent).
    pub rotation_tolerance: Option<Number>,
}

/// Which copies of each generated function to emit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// Two: one for the crate's target and one for AVX2 + FMA, chosen at run time (the
    /// default).
    Dispatch,
    /// The crate's target only: half the machine code, SSE2 speed on baseline x86-64.
    Baseline,
}

/// How many balance equations each body contributes to the force analysis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AnalysisPlane {
    /// Motion in the world xy plane: ΣF_x = m a_Gx, ΣF_y = m a_Gy, ΣM_z = I α (3 per body).
    Planar,
    /// Three-dimensional: six balance equations per body.
    Spatial,
}

/// The kinds of support or loop-closing connection between two bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstraintKind {
    /// A pin: the two points coincide. Planar: two force components, no couple; spatial: a
    /// hinge about `axis`, three forces and the two couples normal to the axis.
    Pin,
    /// A ball joint (spatial): the points coincide, three force components, no couple.
    Ball,
    /// A roller or a slider on a line: the second point stays on the line through the first
    /// point normal to `normal`: one force along the normal.
    Roller,
    /// A prismatic connection sliding along `axis`: the forces normal to the axis and every
    /// couple (planar: one normal force and the couple about z).
    Prismatic,
    /// A weld: no relative motion, every force and couple component.
    Weld,
}

/// One end of a constraint: a body (or `ground`) and the point on it, in its frame.
#[derive(Clone, Debug)]
pub struct ConstraintEnd {
    /// The body, or `ground`.
    pub body: Name,
    /// The point in the body's frame (the origin when absent).
    pub at: Option<Vector>,
}

/// `constraint name: kind(a at [..], b at [..]) { normal: .. | axis: .. };`: a support or a
/// connection closing a kinematic loop. Directions are given in the first body's frame.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The constraint's name.
    pub name: Name,
    /// What it transmits.
    pub kind: ConstraintKind,
    /// Where the kind was written.
    pub kind_span: Span,
    /// The first body, whose frame the directions and the reaction components are given in.
    pub first: ConstraintEnd,
    /// The second body; the reaction acts on it, its opposite on the first.
    pub second: ConstraintEnd,
    /// The roller's normal, the prismatic's sliding axis, or the spatial pin's hinge axis.
    pub direction: Option<Axis>,
}

/// `urdf: "path";` with `floating_base: bool;`, `urdf_damping: bool;` and
/// `urdf_mimic: bool;`.
#[derive(Clone, Debug)]
pub struct UrdfSource {
    /// The path as written, relative to the crate's manifest directory.
    pub path: syn::LitStr,
    /// Whether the root link gets a free-floating joint.
    pub floating_base: bool,
    /// Whether the joints' `<dynamics damping>` is imported (`urdf_damping: false;` drops
    /// it, as Pinocchio's algorithms ignore it).
    pub damping: bool,
    /// Whether the joints' `<mimic>` is honoured, which the import refuses (the default);
    /// `urdf_mimic: false;` ignores it, each mimic joint an independent coordinate, as
    /// Pinocchio's `buildModel` makes it by default.
    pub mimic: bool,
}

/// `name = nominal` in `parameters: [...]`.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The parameter's name (an input of the generated code).
    pub name: Name,
    /// The value used by `model()` and by the compile-time checks.
    pub nominal: Number,
}

/// `body name { mass: .., com: .., inertia: .. | shape: .. }`.
#[derive(Clone, Debug)]
pub struct Body {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The body's name.
    pub name: Name,
    /// Mass m (kg).
    pub mass: Option<Number>,
    /// Mass centre c = PG in the body frame (m); the origin when absent.
    pub com: Option<Vector>,
    /// How I_G is given.
    pub inertia: Option<InertiaForm>,
    /// The whole `{ ... }` block.
    pub span: SpanRange,
}

/// The ways to give I_G, the inertia about the mass centre in the body frame.
// With proc-macro2's `span-locations` (the command-line tool's line and column) a span
// carries its position, and this enum's largest variant crosses clippy's size threshold;
// it is built once per declaration, so its size does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum InertiaForm {
    /// `inertia: [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]`.
    Matrix(Matrix),
    /// `inertia: diag([i1, i2, i3])` or `inertia: principal([i1, i2, i3], rpy: [r, p, y])`:
    /// principal moments about principal axes rotated by R in the body frame, I_G = R D Rᵀ.
    Principal {
        /// The principal moments.
        moments: Vector,
        /// Orientation of the principal axes (identity when absent).
        rotation: Option<Rotation>,
        /// The whole form.
        span: SpanRange,
    },
    /// `shape: rod(length: l, axis: y)` and the like: I_G computed from the mass.
    Shape(Shape),
}

/// A standard solid with its dimensions; I_G follows from the body's mass.
#[derive(Clone, Debug)]
pub struct Shape {
    /// Which solid.
    pub kind: ShapeKind,
    /// The whole form.
    pub span: SpanRange,
}

/// The standard solids.
#[derive(Clone, Debug)]
pub enum ShapeKind {
    /// A thin rod of length l along an axis: m l²/12 about the other two axes.
    Rod {
        /// Length (m).
        length: Number,
        /// Along which body axis.
        axis: Axis,
    },
    /// A solid box with side lengths along x, y, z.
    Box {
        /// Side lengths (m).
        size: Vector,
    },
    /// A solid cylinder of radius r and length l along an axis.
    Cylinder {
        /// Radius (m).
        radius: Number,
        /// Length (m).
        length: Number,
        /// Along which body axis.
        axis: Axis,
    },
    /// A solid sphere of radius r.
    Sphere {
        /// Radius (m).
        radius: Number,
    },
    /// A point mass: I_G = 0.
    Point,
}

/// A direction: `x`, `-y`, ... or `[a, b, c]`.
#[derive(Clone, Debug)]
pub struct Axis {
    /// The direction, not normalized.
    pub direction: Vector,
    /// Where it was written.
    pub span: SpanRange,
}

/// The ways to give a rotation.
#[allow(clippy::large_enum_variant)] // as InertiaForm
#[derive(Clone, Debug)]
pub enum Rotation {
    /// `rpy(roll, pitch, yaw)`: R = Rz(yaw) Ry(pitch) Rx(roll), as in URDF.
    Rpy([Number; 3], SpanRange),
    /// `axis_angle([x, y, z], angle)`.
    AxisAngle(Vector, Number, SpanRange),
    /// `[[..], [..], [..]]` by rows.
    Matrix(Matrix),
}

impl Rotation {
    /// The tokens the rotation came from.
    pub fn span(&self) -> SpanRange {
        match self {
            Rotation::Rpy(_, s) | Rotation::AxisAngle(_, _, s) => *s,
            Rotation::Matrix(m) => m.span,
        }
    }
}

/// The kinds of joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Rotation about `axis`.
    Revolute,
    /// Translation along `axis`.
    Prismatic,
    /// No motion: the child merges into the parent.
    Fixed,
    /// A free-floating base (six degrees of freedom relative to the ground).
    Free,
}

/// The two Denavit–Hartenberg conventions of [`DhPlacement`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DhConvention {
    /// `dh(..)`, standard (distal) DH: on joint i the row (a_i, α_i, d_i, θ_i), frame i =
    /// frame i−1 · Rz(θ) Tz(d) Tx(a) Rx(α), the joint's axis the z axis of frame i−1.
    Standard,
    /// `mdh(..)`, modified (proximal) DH, Craig's: on joint i the row (a_{i−1}, α_{i−1},
    /// d_i, θ_i), frame i = frame i−1 · Rx(α) Tx(a) Rz(θ) Tz(d), the joint's axis the z
    /// axis of frame i.
    Modified,
}

impl DhConvention {
    /// The form's word: `dh` or `mdh`.
    pub fn word(self) -> &'static str {
        match self {
            DhConvention::Standard => "dh",
            DhConvention::Modified => "mdh",
        }
    }
}

/// `placement: dh(a: .., alpha: .., d: .., theta: ..)` or `placement: mdh(..)`: a revolute
/// or prismatic joint placed by a row of a Denavit–Hartenberg table instead of `at`,
/// `rotation` and `axis` (the axis is z of the DH frame). Each entry is optional, 0 when
/// absent; the joint's coordinate adds to θ (revolute) or d (prismatic), so the entries
/// given are the offsets at q = 0.
#[derive(Clone, Debug)]
pub struct DhPlacement {
    /// Standard or modified.
    pub convention: DhConvention,
    /// Link length a (m).
    pub a: Option<Number>,
    /// Link twist α (rad).
    pub alpha: Option<Number>,
    /// Link offset d (m).
    pub d: Option<Number>,
    /// Joint angle θ (rad).
    pub theta: Option<Number>,
    /// The whole form, `dh(..)` or `mdh(..)`.
    pub span: SpanRange,
}

/// `joint name: kind(parent -> child) { axis: .., at: .., rotation: .., placement: ..,
/// armature: .., damping: .., friction: .., limits: { .. }, driven: .. }`.
#[derive(Clone, Debug)]
pub struct Joint {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The joint's name.
    pub name: Name,
    /// The kind of motion.
    pub kind: JointKind,
    /// Where the kind was written.
    pub kind_span: Span,
    /// The parent body, or `ground`.
    pub parent: Name,
    /// The child body.
    pub child: Name,
    /// The axis in the joint frame (revolute and prismatic).
    pub axis: Option<Axis>,
    /// The joint frame's origin in the parent frame.
    pub at: Option<Vector>,
    /// The joint frame's rotation in the parent frame.
    pub rotation: Option<Rotation>,
    /// A Denavit–Hartenberg row placing the joint (instead of `axis`, `at` and
    /// `rotation`).
    pub placement: Option<DhPlacement>,
    /// Rotor inertia reflected to the coordinate.
    pub armature: Option<Number>,
    /// Viscous friction coefficient.
    pub damping: Option<Number>,
    /// Coulomb (dry) friction, carried to the generated `JOINT_FRICTION`; it enters no
    /// generated function.
    pub friction: Option<Number>,
    /// Position, velocity and effort limits, carried to the generated `JOINT_LIMITS`.
    pub limits: Option<Limits>,
    /// `driven: true`: an actuator drives the coordinate, so the force analysis solves for
    /// its effort (in a mechanism without constraints every joint is driven).
    pub driven: Option<(bool, Span)>,
}

/// `limits: { lower: .., upper: .., velocity: .., effort: .. }` on a revolute or prismatic
/// joint: each entry optional, a missing one unbounded. Constants (not parameters).
#[derive(Clone, Debug)]
pub struct Limits {
    /// Lowest position (rad or m).
    pub lower: Option<Number>,
    /// Highest position (rad or m).
    pub upper: Option<Number>,
    /// Largest |velocity| (rad/s or m/s).
    pub velocity: Option<Number>,
    /// Largest |effort| (N·m or N).
    pub effort: Option<Number>,
    /// The whole `{ .. }` block.
    pub span: SpanRange,
}

/// What an applied load is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadKind {
    /// A force (3 run-time inputs) through a point of the body.
    Force,
    /// A couple (3 run-time inputs).
    Couple,
    /// A force through a point and a couple (6 run-time inputs).
    Wrench,
}

/// The axes a load's run-time components are given in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadFrame {
    /// The loaded body's own axes, turning with it (`in body`, the default).
    Body,
    /// The world's fixed axes (`in world`): the generated code turns the components into
    /// the body's axes, F_in_body = R_bodyᵀ F_in_world.
    World,
}

/// `load name: force on body [at [x, y, z]] [in world | in body];`: a run-time input acting
/// on a body, its components given in the body's axes (or the world's, with `in world`),
/// through a point fixed on the body and given in the body frame.
#[derive(Clone, Debug)]
pub struct Load {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The load's name.
    pub name: Name,
    /// Force, couple or both.
    pub kind: LoadKind,
    /// The body it acts on.
    pub body: Name,
    /// The point of application in the body frame (the origin when absent).
    pub at: Option<Vector>,
    /// `in world` or `in body` as written, with the span of the frame's word (the body's
    /// axes when absent).
    pub frame: Option<(LoadFrame, Span)>,
}

impl Load {
    /// The axes the load's components are given in: the body's unless `in world`.
    pub fn frame(&self) -> LoadFrame {
        self.frame.map_or(LoadFrame::Body, |(frame, _)| frame)
    }
}

/// `frame name: on body [at [x, y, z]] [rotation ..];`: an operational frame (a tool
/// centre point, a foot, a camera) rigidly attached to a body, placed in the body's frame:
/// x_body = R x_frame + p.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Doc comments.
    pub docs: Vec<String>,
    /// The frame's name.
    pub name: Name,
    /// The body it is attached to, or `ground`.
    pub body: Name,
    /// Its origin p in the body frame (the body's origin when absent).
    pub at: Option<Vector>,
    /// Its rotation R in the body frame (the body's axes when absent).
    pub rotation: Option<Rotation>,
}
