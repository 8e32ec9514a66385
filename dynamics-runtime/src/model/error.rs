//! What can be wrong with a declared mechanism, and with the sizes of run-time inputs.
//!
//! Every error names the body or joint at fault and carries the offending numbers, so the
//! message can say what is wrong and what would fix it.

use std::fmt;

/// One reason a declared mechanism is ill-posed.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// A number that must be finite is NaN or infinite.
    NonFinite {
        /// "body `x`", "joint `y`" or "gravity".
        item: String,
        /// Which field.
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// A body's mass is negative.
    NegativeMass {
        /// The body.
        body: String,
        /// The mass (kg).
        mass: f64,
    },
    /// I_G is not symmetric.
    InertiaNotSymmetric {
        /// The body.
        body: String,
        /// Row and column of the mismatch.
        row: usize,
        /// Column.
        col: usize,
        /// `I[row][col]`.
        upper: f64,
        /// `I[col][row]`.
        lower: f64,
    },
    /// I_G of a body, as merged with the bodies welded to it, has a negative principal
    /// moment.
    InertiaNotPositive {
        /// The body.
        body: String,
        /// The bodies welded to it through fixed joints (merged into it; empty for a body
        /// judged alone).
        welded: Vec<String>,
        /// Principal moments of the merged I_G, ascending.
        principal_moments: [f64; 3],
    },
    /// The principal moments of a body, as merged with the bodies welded to it, violate
    /// I1 + I2 ≥ I3 (no real mass distribution has them).
    TriangleInequality {
        /// The body.
        body: String,
        /// The bodies welded to it through fixed joints (merged into it; empty for a body
        /// judged alone).
        welded: Vec<String>,
        /// Principal moments of the merged I_G, ascending.
        principal_moments: [f64; 3],
    },
    /// A body moved by a joint has, with everything it carries, zero mass and zero inertia:
    /// M(q) would be singular.
    MasslessSubtree {
        /// The body.
        body: String,
        /// The joint moving it.
        joint: String,
    },
    /// A revolute or prismatic axis is zero.
    ZeroAxis {
        /// The joint.
        joint: String,
        /// The axis as given.
        axis: [f64; 3],
    },
    /// A placement rotation is not orthonormal.
    RotationNotOrthonormal {
        /// The joint.
        joint: String,
        /// max |RᵀR − 1|.
        deviation: f64,
    },
    /// A placement rotation is a reflection (determinant −1).
    RotationImproper {
        /// The joint.
        joint: String,
        /// det R.
        determinant: f64,
    },
    /// Armature or damping is negative.
    NegativeJointCoefficient {
        /// The joint.
        joint: String,
        /// "armature" or "damping".
        field: &'static str,
        /// The value.
        value: f64,
    },
    /// A joint names a body that was not declared.
    UnknownBody {
        /// The joint.
        joint: String,
        /// "parent" or "child".
        role: &'static str,
        /// The name it used.
        name: String,
    },
    /// Two bodies, two joints or two loads share a name.
    DuplicateName {
        /// "body", "joint" or "load".
        kind: &'static str,
        /// The name.
        name: String,
    },
    /// A body is the child of two joints (a closed loop not declared as one).
    TwoParents {
        /// The body.
        body: String,
        /// The first joint that moves it.
        first_joint: String,
        /// The second joint that moves it.
        second_joint: String,
    },
    /// Joints form a cycle that does not reach the ground.
    Cycle {
        /// The bodies on the cycle.
        bodies: Vec<String>,
    },
    /// A body is not connected to the ground through joints.
    NotConnected {
        /// The body.
        body: String,
    },
    /// A joint attaches a body to itself.
    SelfJoint {
        /// The joint.
        joint: String,
    },
    /// The ground cannot be a joint's child.
    GroundAsChild {
        /// The joint.
        joint: String,
    },
    /// A mechanism was given the wrong number of parameter values.
    ParameterCount {
        /// How many it declares.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// A free-floating joint must attach its body to the ground.
    FreeFlyerNotOnGround {
        /// The joint.
        joint: String,
        /// Its parent.
        parent: String,
    },
    /// A declared frame is attached to a body that was not declared.
    UnknownFrameBody {
        /// The frame.
        frame: String,
        /// The body name it used.
        body: String,
    },
    /// A load acts on a body that was not declared.
    UnknownLoadBody {
        /// The load.
        load: String,
        /// The body name it used.
        body: String,
    },
    /// A declared frame's name is already taken: by a declared body (every body is a
    /// frame), by the ground, or by another declared frame.
    DuplicateFrameName {
        /// The frame.
        frame: String,
        /// "a body (every declared body is a frame)", "the ground" or "another frame".
        taken_by: &'static str,
    },
    /// A declared frame's rotation is not orthonormal.
    FrameRotationNotOrthonormal {
        /// The frame.
        frame: String,
        /// max |RᵀR − 1|.
        deviation: f64,
    },
    /// A declared frame's rotation is a reflection (determinant −1).
    FrameRotationImproper {
        /// The frame.
        frame: String,
        /// det R.
        determinant: f64,
    },
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use ModelError::*;
        match self {
            NonFinite { item, field, value } => write!(
                f,
                "{item}: {field} is {value}, which is not a finite number; give a finite value"
            ),
            NegativeMass { body, mass } => write!(
                f,
                "body `{body}`: mass is {mass} kg, which is negative; a mass must be ≥ 0"
            ),
            InertiaNotSymmetric {
                body,
                row,
                col,
                upper,
                lower,
            } => write!(
                f,
                "body `{body}`: inertia is not symmetric: I[{row}][{col}] = {upper} but \
                 I[{col}][{row}] = {lower}; give the same product of inertia on both sides"
            ),
            InertiaNotPositive {
                body,
                welded,
                principal_moments: p,
            } => write!(
                f,
                "body `{body}`{}: inertia is not positive semi-definite: principal moments are \
                 {}, {}, {} kg·m²; every principal moment must be ≥ 0 (check the signs of the \
                 products of inertia)",
                merged_with(welded),
                p[0],
                p[1],
                p[2]
            ),
            TriangleInequality {
                body,
                welded,
                principal_moments: p,
            } => write!(
                f,
                "body `{body}`{}: principal moments {}, {}, {} kg·m² violate the triangle \
                 inequality I1 + I2 ≥ I3 ({} < {}); no mass distribution has this inertia",
                merged_with(welded),
                p[0],
                p[1],
                p[2],
                p[0] + p[1],
                p[2]
            ),
            MasslessSubtree { body, joint } => write!(
                f,
                "joint `{joint}` moves body `{body}`, which with everything it carries has zero \
                 mass and zero inertia: the mass matrix would be singular; give the body mass \
                 or make the joint fixed"
            ),
            ZeroAxis { joint, axis } => write!(
                f,
                "joint `{joint}`: axis [{}, {}, {}] has zero length; give a nonzero direction",
                axis[0], axis[1], axis[2]
            ),
            RotationNotOrthonormal { joint, deviation } => write!(
                f,
                "joint `{joint}`: placement rotation is not orthonormal (max |RᵀR − 1| = \
                 {deviation:e}); give a rotation matrix, roll-pitch-yaw or axis-angle"
            ),
            RotationImproper { joint, determinant } => write!(
                f,
                "joint `{joint}`: placement rotation has determinant {determinant}, a \
                 reflection; a rotation has determinant +1"
            ),
            NegativeJointCoefficient {
                joint,
                field,
                value,
            } => write!(
                f,
                "joint `{joint}`: {field} is {value}, which is negative; it must be ≥ 0"
            ),
            UnknownBody { joint, role, name } => write!(
                f,
                "joint `{joint}`: {role} `{name}` is not a declared body (nor `ground`)"
            ),
            DuplicateName { kind, name } => {
                write!(f, "two {kind}s are named `{name}`; names must be unique")
            }
            TwoParents {
                body,
                first_joint,
                second_joint,
            } => write!(
                f,
                "body `{body}` is moved by two joints, `{first_joint}` and `{second_joint}`: \
                 a tree gives each body one parent (a closed loop must be declared as one)"
            ),
            Cycle { bodies } => write!(
                f,
                "joints form a cycle through bodies {} that never reaches the ground",
                bodies
                    .iter()
                    .map(|b| format!("`{b}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            NotConnected { body } => write!(
                f,
                "body `{body}` is not connected to the ground: no joint moves it; add a joint \
                 (fixed, if it does not move)"
            ),
            SelfJoint { joint } => {
                write!(f, "joint `{joint}` attaches a body to itself")
            }
            GroundAsChild { joint } => {
                write!(f, "joint `{joint}`: the ground cannot be a joint's child")
            }
            ParameterCount { expected, got } => write!(
                f,
                "the mechanism declares {expected} parameters but {got} values were given"
            ),
            FreeFlyerNotOnGround { joint, parent } => write!(
                f,
                "joint `{joint}`: a free-floating joint must attach its body to the ground, \
                 not to `{parent}`"
            ),
            UnknownFrameBody { frame, body } => write!(
                f,
                "frame `{frame}`: body `{body}` is not a declared body (nor `ground`); attach \
                 the frame to a declared body"
            ),
            UnknownLoadBody { load, body } => write!(
                f,
                "load `{load}`: body `{body}` is not a declared body; a load acts on a declared \
                 body"
            ),
            DuplicateFrameName { frame, taken_by } => write!(
                f,
                "frame `{frame}`: the name is already taken by {taken_by}; frame names must \
                 be unique"
            ),
            FrameRotationNotOrthonormal { frame, deviation } => write!(
                f,
                "frame `{frame}`: placement rotation is not orthonormal (max |RᵀR − 1| = \
                 {deviation:e}); give a rotation matrix, roll-pitch-yaw or axis-angle"
            ),
            FrameRotationImproper { frame, determinant } => write!(
                f,
                "frame `{frame}`: placement rotation has determinant {determinant}, a \
                 reflection; a rotation has determinant +1"
            ),
        }
    }
}

impl std::error::Error for ModelError {}

/// All the errors found in one mechanism (never empty).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelErrors(pub Vec<ModelError>);

impl fmt::Display for ModelErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for ModelErrors {}

/// A run-time input or output slice has the wrong length for the model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SizeError {
    /// Which argument ("q", "v", "a", "tau", "external wrenches", ...).
    pub what: &'static str,
    /// The length the model needs.
    pub expected: usize,
    /// The length given.
    pub got: usize,
}

impl fmt::Display for SizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` has length {} but the model needs {}",
            self.what, self.got, self.expected
        )
    }
}

impl std::error::Error for SizeError {}

impl SizeError {
    /// `Ok` if `got == expected`, else the error naming `what`.
    pub fn check(what: &'static str, expected: usize, got: usize) -> Result<(), SizeError> {
        if expected == got {
            Ok(())
        } else {
            Err(SizeError {
                what,
                expected,
                got,
            })
        }
    }
}

/// ` merged with `a`, `b` (welded through fixed joints)` for the bodies welded to one, or
/// nothing.
fn merged_with(welded: &[String]) -> String {
    if welded.is_empty() {
        return String::new();
    }
    let names: Vec<String> = welded.iter().map(|w| format!("`{w}`")).collect();
    format!(
        " merged with {} (welded through fixed joints)",
        names.join(", ")
    )
}
