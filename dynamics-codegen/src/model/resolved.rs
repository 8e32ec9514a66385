//! The declaration with its numbers resolved: what resolution ([`super::resolve`]) gives
//! the rules ([`super::rules`]) and the tree builder ([`super::tree`]). Every value keeps the
//! span of the tokens it came from.

use super::dh::Pose;
use super::value::{Mat3, Value, Vec3};
use super::{Outputs, Parameter};
use crate::syntax::{self, SpanRange};

/// A body with resolved numbers.
pub(crate) struct ResolvedBody {
    pub docs: Vec<String>,
    pub name: syntax::Name,
    pub mass: Value,
    pub mass_span: SpanRange,
    pub com: Vec3,
    pub inertia: Mat3,
    pub inertia_span: SpanRange,
    /// Whether I_G was computed from the mass (a `shape`), so that it shares the mass's
    /// sign.
    pub inertia_from_mass: bool,
}

/// A joint with resolved numbers.
pub(crate) struct ResolvedJoint {
    pub docs: Vec<String>,
    pub name: syntax::Name,
    pub kind: syntax::JointKind,
    pub parent: syntax::Name,
    pub child: syntax::Name,
    /// The axis as given, and its span (revolute and prismatic only).
    pub axis: Option<([f64; 3], SpanRange)>,
    pub translation: Vec3,
    pub rotation: [[f64; 3]; 3],
    pub rotation_span: SpanRange,
    /// The child body's declared frame in its model frame (the joint frame after the
    /// motion): a standard DH row's C = Tx(a) Rx(α); `None` when they are the same frame.
    pub child_frame: Option<Pose>,
    pub armature: (Value, SpanRange),
    pub damping: (Value, SpanRange),
    /// Coulomb friction (0 when absent), at its number (the joint's name when absent).
    pub friction: (f64, SpanRange),
    /// The limits, unbounded where absent.
    pub limits: ResolvedLimits,
}

/// A joint's limits: each a constant with its span (±∞ at the joint's name when absent).
pub(crate) struct ResolvedLimits {
    pub lower: (f64, SpanRange),
    pub upper: (f64, SpanRange),
    pub velocity: (f64, SpanRange),
    pub effort: (f64, SpanRange),
    /// The `limits: { .. }` block, when given.
    pub span: Option<SpanRange>,
}

/// An operational frame with resolved numbers.
pub(crate) struct ResolvedFrame {
    pub docs: Vec<String>,
    pub name: syntax::Name,
    pub body: syntax::Name,
    /// Its origin in the body frame.
    pub translation: [f64; 3],
    /// Its rotation in the body frame (rows).
    pub rotation: [[f64; 3]; 3],
    pub rotation_span: SpanRange,
}

/// The whole declaration, resolved.
pub(crate) struct Resolved {
    pub parameters: Vec<Parameter>,
    pub parameter_used: Vec<bool>,
    pub bodies: Vec<ResolvedBody>,
    pub joints: Vec<ResolvedJoint>,
    pub outputs: Outputs,
    pub skip_triangle_inequality: bool,
    pub gravity: [f64; 3],
    /// Each load's point of application, in declaration order (`None`: the origin).
    pub load_points: Vec<Option<Vec3>>,
    /// The declared operational frames, in declaration order.
    pub frames: Vec<ResolvedFrame>,
}

impl Resolved {
    /// Nominal values of the parameters.
    pub fn nominal_parameters(&self) -> Vec<f64> {
        self.parameters.iter().map(|p| p.nominal).collect()
    }
}
