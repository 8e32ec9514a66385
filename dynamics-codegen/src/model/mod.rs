//! The validated model: names resolved, bodies ordered so that `parent[i] < i`, bodies
//! joined by fixed joints merged into composite bodies, every physical and structural rule
//! checked.
//!
//! `lower` runs resolution and every rule, collecting all errors (each at the span of the
//! offending tokens) before giving up, so the user sees every mistake at once. A model that
//! comes out of `lower` is well-posed for the outputs it asks for.
//!
//! Frames and symbols are the textbook's and the runtime's: a body's mass m, mass centre
//! c = PG and I_G are expressed in the body frame; a joint's placement (R, p) is the pose of
//! the joint frame in the parent body's frame; the body frame is the joint frame after the
//! motion. A standard Denavit–Hartenberg row declares its child's data in another frame, the
//! DH link frame, a constant placement C away from the body frame ([`dh`]): the tree builder
//! carries everything declared in it by C, as it carries a welded body's.

mod dh;
mod diagnostics;
mod frame_turns;
pub(crate) mod linear;
mod resolve;
mod resolved;
mod rules;
pub mod statics;
mod tree;
pub mod value;

pub use diagnostics::Diagnostics;
pub use value::{Mat3, Value, Vec3};

use crate::syntax;
use proc_macro2::Span;

/// Which functions to generate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Outputs {
    /// τ = M q̈ + C q̇ + g − Q.
    pub inverse_dynamics: bool,
    /// M(q).
    pub mass_matrix: bool,
    /// C(q, q̇) with Ṁ − 2C skew-symmetric.
    pub coriolis: bool,
    /// g(q).
    pub gravity: bool,
    /// C(q, q̇) q̇ + g(q).
    pub bias: bool,
    /// q̈ = M⁻¹ (τ + Q − C q̇ − g), by the cheaper of the two methods.
    pub forward_dynamics: bool,
    /// The same by the articulated-body algorithm, as `forward_dynamics_aba`.
    pub forward_dynamics_aba: bool,
    /// The same by LDLᵀ of the mass matrix, as `forward_dynamics_ldlt`.
    pub forward_dynamics_ldlt: bool,
    /// Kinetic and potential energy.
    pub energy: bool,
    /// The wrench each joint transmits to its child body.
    pub reactions: bool,
    /// Statics and mechanism force analysis: A(q) x = b for every reaction component and
    /// driving effort, from each body's balance equations.
    pub force_analysis: bool,
    /// The loop-closure equations φ(q) = 0 of the declared constraints, their Jacobian Φ_q
    /// and the acceleration term γ with Φ_q q̈ = γ.
    pub constraints: bool,
    /// The centre of mass in the world frame.
    pub center_of_mass: bool,
    /// Its Jacobian, 3 × nv.
    pub center_of_mass_jacobian: bool,
    /// Every body frame's pose in the world.
    pub joint_placements: bool,
    /// Every body frame's Jacobian, world-aligned at its origin.
    pub joint_jacobians: bool,
    /// All joint Jacobians in one 6 × nv matrix, WORLD convention (Pinocchio's data.J).
    pub joint_jacobians_world: bool,
    /// That matrix and its time derivative (data.J and data.dJ).
    pub joint_jacobians_world_time_variation: bool,
    /// The centroidal momentum matrix A_G.
    pub centroidal_momentum_matrix: bool,
    /// Every body frame's pose, velocity and acceleration at (q, v, a).
    pub forward_kinematics: bool,
    /// Every body frame's velocity [v_P; ω], world-aligned at its origin.
    pub joint_velocities: bool,
    /// Every body frame's J̇ q̇, world-aligned at its origin.
    pub joint_acceleration_biases: bool,
    /// Every operational frame's pose in the world.
    pub frame_placements: bool,
    /// Every operational frame's Jacobian, world-aligned at its origin.
    pub frame_jacobians: bool,
    /// Every operational frame's Jacobian in its own axes.
    pub frame_jacobians_local: bool,
    /// Every operational frame's velocity, world-aligned at its origin.
    pub frame_velocities: bool,
    /// Every operational frame's J̇ q̇, world-aligned at its origin.
    pub frame_acceleration_biases: bool,
    /// Ȧ_G q̇, the rate of the centroidal momentum at q̈ = 0.
    pub centroidal_bias: bool,
    /// ∂τ/∂q and ∂τ/∂q̇ of inverse dynamics.
    pub inverse_dynamics_derivatives: bool,
    /// ∂q̈/∂q and ∂q̈/∂q̇ of forward dynamics.
    pub forward_dynamics_derivatives: bool,
    /// M(q)⁻¹.
    pub mass_matrix_inverse: bool,
    /// ∂p/∂q, ∂ṗ/∂q and ∂ṗ/∂q̇ of the generalized momentum p = M(q) q̇.
    pub momentum_derivatives: bool,
    /// The functions asked for with `_into` (`mass_matrix_into`), which get a twin that
    /// writes into the caller's `out`: bit `i` for [`Outputs::NAMES`]`[i]`.
    pub into: u64,
    /// The functions asked for with `_sparse_into` (`mass_matrix_sparse_into`), whose twin
    /// writes only the entries that can be nonzero (of a symmetric matrix, those on and
    /// above the diagonal): bit `i` for [`Outputs::NAMES`]`[i]`.
    pub sparse_into: u64,
}

impl Outputs {
    /// The output names the language accepts: the names of the functions they generate
    /// (`kinetic_energy` and `potential_energy` come together, as do the three constraint
    /// functions).
    pub const NAMES: [&'static str; 35] = [
        "inverse_dynamics",
        "gravity",
        "bias",
        "mass_matrix",
        "coriolis_matrix",
        "forward_dynamics",
        "forward_dynamics_aba",
        "forward_dynamics_ldlt",
        "kinetic_energy",
        "potential_energy",
        "joint_reactions",
        "force_analysis",
        "constraint_residual",
        "constraint_jacobian",
        "constraint_bias",
        "center_of_mass",
        "center_of_mass_jacobian",
        "joint_placements",
        "joint_jacobians",
        "joint_jacobians_world",
        "joint_jacobians_world_time_variation",
        "centroidal_momentum_matrix",
        "forward_kinematics",
        "joint_velocities",
        "joint_acceleration_biases",
        "frame_placements",
        "frame_jacobians",
        "frame_jacobians_local",
        "frame_velocities",
        "frame_acceleration_biases",
        "centroidal_bias",
        "inverse_dynamics_derivatives",
        "forward_dynamics_derivatives",
        "mass_matrix_inverse",
        "momentum_derivatives",
    ];

    /// Short names accepted too, each with the name it stands for.
    pub const ALIASES: [(&'static str, &'static str); 4] = [
        ("coriolis", "coriolis_matrix"),
        ("energy", "kinetic_energy"),
        ("reactions", "joint_reactions"),
        ("constraints", "constraint_residual"),
    ];

    /// The default: the dynamics, energies and joint reactions (the forward-dynamics
    /// variants, the force analysis, the loop closures and the kinematics are asked for by
    /// name).
    pub fn all() -> Self {
        Outputs {
            inverse_dynamics: true,
            mass_matrix: true,
            coriolis: true,
            gravity: true,
            bias: true,
            forward_dynamics: true,
            forward_dynamics_aba: false,
            forward_dynamics_ldlt: false,
            energy: true,
            reactions: true,
            force_analysis: false,
            constraints: false,
            center_of_mass: false,
            center_of_mass_jacobian: false,
            joint_placements: false,
            joint_jacobians: false,
            joint_jacobians_world: false,
            joint_jacobians_world_time_variation: false,
            centroidal_momentum_matrix: false,
            forward_kinematics: false,
            joint_velocities: false,
            joint_acceleration_biases: false,
            frame_placements: false,
            frame_jacobians: false,
            frame_jacobians_local: false,
            frame_velocities: false,
            frame_acceleration_biases: false,
            centroidal_bias: false,
            inverse_dynamics_derivatives: false,
            forward_dynamics_derivatives: false,
            mass_matrix_inverse: false,
            momentum_derivatives: false,
            into: 0,
            sparse_into: 0,
        }
    }

    /// The default of a mechanism with constraints (closed loops or supports): the force
    /// analysis, the loop closure, and what the closed mechanism's forward dynamics needs
    /// from the tree (M and the bias forces, combined with the closure by
    /// `dynamics_runtime::closure`), and the energies. The other open-tree functions would
    /// ignore the constraints, so they are generated only when asked for by name.
    pub fn constrained() -> Self {
        Outputs {
            force_analysis: true,
            constraints: true,
            mass_matrix: true,
            bias: true,
            energy: true,
            ..Outputs::default()
        }
    }

    /// Turns on the output with this name; `false` if the name is unknown. A known
    /// function's name with `_into` (`mass_matrix_into`) turns it on with its `_into` twin,
    /// with `_sparse_into` with its `_sparse_into` twin.
    pub fn enable(&mut self, name: &str) -> bool {
        // `_sparse_into` first: it ends with `_into` too.
        for (suffix, sparse) in [("_sparse_into", true), ("_into", false)] {
            if let Some(stem) = name.strip_suffix(suffix) {
                let stem = Self::full_name(stem);
                return match Self::NAMES.iter().position(|n| *n == stem) {
                    Some(i) if self.enable(Self::NAMES[i]) => {
                        let bits = if sparse {
                            &mut self.sparse_into
                        } else {
                            &mut self.into
                        };
                        *bits |= 1 << i;
                        true
                    }
                    _ => false,
                };
            }
        }
        let flag = match Self::full_name(name) {
            "inverse_dynamics" => &mut self.inverse_dynamics,
            "mass_matrix" => &mut self.mass_matrix,
            "coriolis_matrix" => &mut self.coriolis,
            "gravity" => &mut self.gravity,
            "bias" => &mut self.bias,
            "forward_dynamics" => &mut self.forward_dynamics,
            "forward_dynamics_aba" => &mut self.forward_dynamics_aba,
            "forward_dynamics_ldlt" => &mut self.forward_dynamics_ldlt,
            "kinetic_energy" | "potential_energy" => &mut self.energy,
            "joint_reactions" => &mut self.reactions,
            "force_analysis" => &mut self.force_analysis,
            "center_of_mass" => &mut self.center_of_mass,
            "center_of_mass_jacobian" => &mut self.center_of_mass_jacobian,
            "joint_placements" => &mut self.joint_placements,
            "joint_jacobians" => &mut self.joint_jacobians,
            "joint_jacobians_world" => &mut self.joint_jacobians_world,
            "joint_jacobians_world_time_variation" => {
                &mut self.joint_jacobians_world_time_variation
            }
            "centroidal_momentum_matrix" => &mut self.centroidal_momentum_matrix,
            "forward_kinematics" => &mut self.forward_kinematics,
            "joint_velocities" => &mut self.joint_velocities,
            "joint_acceleration_biases" => &mut self.joint_acceleration_biases,
            "frame_placements" => &mut self.frame_placements,
            "frame_jacobians" => &mut self.frame_jacobians,
            "frame_jacobians_local" => &mut self.frame_jacobians_local,
            "frame_velocities" => &mut self.frame_velocities,
            "frame_acceleration_biases" => &mut self.frame_acceleration_biases,
            "centroidal_bias" => &mut self.centroidal_bias,
            "inverse_dynamics_derivatives" => &mut self.inverse_dynamics_derivatives,
            "forward_dynamics_derivatives" => &mut self.forward_dynamics_derivatives,
            "mass_matrix_inverse" => &mut self.mass_matrix_inverse,
            "momentum_derivatives" => &mut self.momentum_derivatives,
            "constraint_residual" | "constraint_jacobian" | "constraint_bias" => {
                &mut self.constraints
            }
            _ => return false,
        };
        *flag = true;
        true
    }

    /// The output an alias stands for (`coriolis` → `coriolis_matrix`), else `name`.
    fn full_name(name: &str) -> &str {
        Self::ALIASES
            .iter()
            .find(|(alias, _)| *alias == name)
            .map_or(name, |(_, full)| full)
    }

    /// Whether the function `name` has its bit in `bits` ([`Outputs::into`],
    /// [`Outputs::sparse_into`]).
    fn asked(bits: u64, name: &str) -> bool {
        Self::NAMES
            .iter()
            .position(|n| *n == name)
            .is_some_and(|i| bits & (1 << i) != 0)
    }

    /// Whether the function `name` was asked for with `_into`.
    pub fn wants_into(&self, name: &str) -> bool {
        Self::asked(self.into, name)
    }

    /// Whether the function `name` was asked for with `_sparse_into`.
    pub fn wants_sparse_into(&self, name: &str) -> bool {
        Self::asked(self.sparse_into, name)
    }

    /// Whether any output needs at least one degree of freedom.
    pub fn any_dynamics(&self) -> bool {
        self.inverse_dynamics
            || self.mass_matrix
            || self.coriolis
            || self.gravity
            || self.bias
            || self.forward_dynamics
            || self.forward_dynamics_aba
            || self.forward_dynamics_ldlt
            || self.inverse_dynamics_derivatives
            || self.forward_dynamics_derivatives
            || self.mass_matrix_inverse
            || self.momentum_derivatives
    }
}

// The `_into` bits of `Outputs::into`, one per name, fit in its `u64`.
const _: () = assert!(Outputs::NAMES.len() <= 64);

/// A declared symbolic parameter: an input of the generated code.
#[derive(Clone, Debug, PartialEq)]
pub struct Parameter {
    /// Its name.
    pub name: String,
    /// The value `model()` and the compile-time checks use.
    pub nominal: f64,
}

/// The motion a moving joint allows.
#[derive(Clone, Debug, PartialEq)]
pub enum JointKind {
    /// Rotation about a unit axis fixed in the body (and in the joint frame).
    Revolute {
        /// Unit axis in the tree body's frame: the declared axis, in the joint frame, unless
        /// the frame took a half turn (`Joint::joint_frame_in_body`), which makes an axis
        /// declared along −x, −y or −z point along +x, +y or +z.
        axis_in_body: [f64; 3],
    },
    /// Translation along a unit axis fixed in the body (and in the joint frame).
    Prismatic {
        /// Unit axis in the tree body's frame, as for [`JointKind::Revolute`].
        axis_in_body: [f64; 3],
    },
    /// A free-floating base (q: position + unit quaternion, scalar last; v: [v_P; ω] in
    /// the body frame).
    Free,
}

impl JointKind {
    /// The number of velocity coordinates the joint gives its body: 6 for a free joint, 1
    /// otherwise.
    #[must_use]
    pub fn dofs(&self) -> usize {
        match self {
            JointKind::Free => 6,
            JointKind::Revolute { .. } | JointKind::Prismatic { .. } => 1,
        }
    }

    /// The same kind of joint about (or along) `axis`; a free joint stays free.
    #[must_use]
    pub fn with_axis(&self, axis: [f64; 3]) -> JointKind {
        match self {
            JointKind::Revolute { .. } => JointKind::Revolute { axis_in_body: axis },
            JointKind::Prismatic { .. } => JointKind::Prismatic { axis_in_body: axis },
            JointKind::Free => JointKind::Free,
        }
    }
}

/// A coordinate's limits, as declared or read from a URDF `<limit>`: ±∞ where none is
/// given. They constrain nothing in the generated functions; they are printed as
/// `JOINT_LIMITS`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimits {
    /// Lowest position.
    pub lower: f64,
    /// Highest position.
    pub upper: f64,
    /// Largest |velocity|.
    pub velocity: f64,
    /// Largest |effort|.
    pub effort: f64,
}

impl JointLimits {
    /// No limit at all.
    pub const UNBOUNDED: JointLimits = JointLimits {
        lower: f64::NEG_INFINITY,
        upper: f64::INFINITY,
        velocity: f64::INFINITY,
        effort: f64::INFINITY,
    };

    /// Whether any limit is finite.
    #[must_use]
    pub fn is_bounded(&self) -> bool {
        *self != Self::UNBOUNDED
    }
}

/// The joint that moves a body of the tree.
#[derive(Clone, Debug)]
pub struct Joint {
    /// Its name.
    pub name: String,
    /// Its doc comments.
    pub docs: Vec<String>,
    /// Its motion.
    pub kind: JointKind,
    /// Rotation of the joint frame in the parent body frame (rows).
    pub rotation_in_parent: [[f64; 3]; 3],
    /// Origin of the joint frame in the parent body frame.
    pub translation_in_parent: Vec3,
    /// The rotation from the joint frame after the motion (the body frame as declared:
    /// Pinocchio's joint frame) to the tree body's frame: `None` when they are the same,
    /// else a constant turn about the joint's axis that makes the placements sparser, then
    /// a half turn that makes an axis pointing the negative way along a coordinate axis
    /// point the positive way (see `frame_turns`). `rotation_in_parent` already includes
    /// it, and `kind`'s axis is in the tree body's frame; outputs that report the joint
    /// frame (placements, reactions) turn back with it.
    pub joint_frame_in_body: Option<[[f64; 3]; 3]>,
    /// Rotor inertia reflected to each coordinate.
    pub armature: Value,
    /// Viscous friction coefficient of each coordinate.
    pub damping: Value,
    /// Coulomb friction of each coordinate (in no generated function).
    pub friction: f64,
    /// The limits of each coordinate (a free joint's are unbounded).
    pub limits: JointLimits,
    /// First coordinate in q.
    pub idx_q: usize,
    /// First coordinate in v.
    pub idx_v: usize,
}

/// One declared body that is part of a (composite) body of the tree, already expressed in
/// the tree body's frame.
#[derive(Clone, Debug)]
pub struct Part {
    /// The declared body's name.
    pub name: String,
    /// Its doc comments.
    pub docs: Vec<String>,
    /// The fixed joint that welds it (its name and doc comments); `None` for a tree body's
    /// own part, which its moving joint moves.
    pub weld: Option<(String, Vec<String>)>,
    /// Mass m.
    pub mass: Value,
    /// Mass centre in the tree body's frame.
    pub com_in_body: Vec3,
    /// I_G about the part's own mass centre, in the tree body's frame.
    pub inertia_com_in_body: Mat3,
}

/// A (composite) body of the tree.
#[derive(Clone, Debug)]
pub struct Body {
    /// The moving body's name.
    pub name: String,
    /// Its doc comments.
    pub docs: Vec<String>,
    /// The parent body (`None`: the ground); always smaller than this body's index.
    pub parent: Option<usize>,
    /// The joint that moves it.
    pub joint: Joint,
    /// The declared bodies it is made of (itself first, then bodies merged through fixed
    /// joints).
    pub parts: Vec<Part>,
}

/// The axes an applied load's components are given in.
pub use syntax::LoadFrame;

impl Body {
    /// Its doc comments, then, when a part welded into it has an inertia the rules would
    /// reject alone (a URDF link's placeholder), a note that the rules judged the merged
    /// body.
    #[must_use]
    pub fn documented(&self, p: &[f64], skip_triangle_inequality: bool) -> Vec<String> {
        let mut docs = self.docs.clone();
        if self.parts.len() < 2 {
            return docs;
        }
        let others: Vec<String> = self.parts[1..]
            .iter()
            .map(|part| format!("`{}`", part.name))
            .collect();
        for part in &self.parts {
            let inertia = value::nominal33(&part.inertia_com_in_body, p);
            if let Some(defect) = rules::inertia_defect(&inertia, !skip_triangle_inequality) {
                docs.push(format!(
                    " Note: the inertia of `{}` alone {}, as a placeholder inertia in a URDF \
                     file may; the inertia rules judge the body merged with {} (welded to it \
                     through fixed joints), which is physical.",
                    part.name,
                    defect.describe(),
                    others.join(", ")
                ));
            }
        }
        docs
    }
}

/// Kind of an applied load.
pub use syntax::LoadKind;

/// An applied load: run-time inputs acting on a body of the tree.
#[derive(Clone, Debug)]
pub struct Load {
    /// Its name.
    pub name: String,
    /// Its doc comments.
    pub docs: Vec<String>,
    /// The body it was declared on (its inputs are in that body's axes unless `frame` is
    /// the world).
    pub declared_body: String,
    /// The point of application as declared, in the declared body's frame.
    pub declared_point: Vec3,
    /// Force, couple or wrench.
    pub kind: LoadKind,
    /// The body of the tree it acts on.
    pub body: usize,
    /// The axes its inputs are given in: the declared body's, or the world's.
    pub frame: LoadFrame,
    /// Rotation from the declared body's frame (in which body-frame inputs are given) to
    /// the tree body's frame.
    pub rotation_in_body: [[f64; 3]; 3],
    /// Point of application in the tree body's frame.
    pub point_in_body: Vec3,
    /// Index of the load's first component in the load input array.
    pub input_offset: usize,
}

impl LoadKind {
    /// Number of run-time inputs: 3 for a force or a couple, 6 for a wrench.
    pub fn input_count(self) -> usize {
        match self {
            LoadKind::Wrench => 6,
            LoadKind::Force | LoadKind::Couple => 3,
        }
    }
}

/// An operational frame: a body welded to another through a fixed joint, or a declared
/// `frame`, or a tree body named in `frames: [..]`.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Its name (a declared frame's, or the body's).
    pub name: String,
    /// Its doc comments.
    pub docs: Vec<String>,
    /// The tree body it moves with (`None`: the ground).
    pub body: Option<usize>,
    /// Rotation from the frame to the tree body's frame (rows).
    pub rotation_in_body: [[f64; 3]; 3],
    /// Its origin in the tree body's frame.
    pub origin_in_body: Vec3,
}

/// A declared `frame` as written, for the runtime `Model`.
#[derive(Clone, Debug, PartialEq)]
pub struct DeclaredFrame {
    /// Name.
    pub name: String,
    /// The declared body it is on, or `ground`.
    pub body: String,
    /// Its origin in that body's frame.
    pub translation: [f64; 3],
    /// Its rotation in that body's frame (rows).
    pub rotation: [[f64; 3]; 3],
}

/// A declared body as written (before merging), for the runtime `Model`.
#[derive(Clone, Debug, PartialEq)]
pub struct DeclaredBody {
    /// Name.
    pub name: String,
    /// Mass.
    pub mass: Value,
    /// Mass centre in its frame.
    pub com: Vec3,
    /// I_G in its frame.
    pub inertia: Mat3,
}

/// A declared joint as written (including fixed ones), for the runtime `Model`.
#[derive(Clone, Debug, PartialEq)]
pub struct DeclaredJoint {
    /// Name.
    pub name: String,
    /// Kind.
    pub kind: syntax::JointKind,
    /// Parent name (or `ground`).
    pub parent: String,
    /// Child name.
    pub child: String,
    /// Axis as given (zero for fixed and free joints).
    pub axis: [f64; 3],
    /// Translation in the parent frame.
    pub translation: Vec3,
    /// Rotation in the parent frame (rows).
    pub rotation: [[f64; 3]; 3],
    /// The child's declared frame in the joint frame after the motion, as (translation,
    /// rotation rows): a standard DH row's Tx(a) Rx(α); `None` when they coincide.
    pub child_frame: Option<(Vec3, [[f64; 3]; 3])>,
    /// Armature.
    pub armature: Value,
    /// Damping.
    pub damping: Value,
}

/// A validated mechanism, ready for expansion.
#[derive(Clone, Debug)]
pub struct Model {
    /// The generated type's name.
    pub name: syn::Ident,
    /// Its visibility.
    pub visibility: syn::Visibility,
    /// Doc comments on the mechanism.
    pub docs: Vec<String>,
    /// Gravity in the world frame.
    pub gravity_in_world: [f64; 3],
    /// Symbolic parameters, in declaration order (the generated code's `p` input).
    pub parameters: Vec<Parameter>,
    /// Functions to generate.
    pub outputs: Outputs,
    /// Bodies of the tree, parents first.
    pub bodies: Vec<Body>,
    /// Applied loads, in declaration order.
    pub loads: Vec<Load>,
    /// The declared bodies welded to the ground through fixed joints (each in the world
    /// frame), in depth-first order: they enter no dynamics.
    pub ground_parts: Vec<Part>,
    /// The operational frames the frame outputs cover: every body welded through a fixed
    /// joint (in the tree's depth-first order) then every declared `frame`, or those
    /// `frames: [..]` lists, in its order.
    pub frames: Vec<Frame>,
    /// Total number of load inputs.
    pub load_inputs: usize,
    /// Length of q.
    pub nq: usize,
    /// Length of v.
    pub nv: usize,
    /// The declared bodies (before merging), for the runtime `Model`.
    pub declared_bodies: Vec<DeclaredBody>,
    /// The declared joints, including fixed ones.
    pub declared_joints: Vec<DeclaredJoint>,
    /// The declared frames, selected or not.
    pub declared_frames: Vec<DeclaredFrame>,
    /// Whether the triangle inequality was waived with `allow: [triangle_inequality]`.
    pub skip_triangle_inequality: bool,
    /// Whether the expansions may compute isomorphic limbs, and partly filled columns of a
    /// tree matrix, side by side in packed values ([`crate::expand::slots`]): true as
    /// lowered; off for the unpacked twin of a packed function, the body that scalar types
    /// holding several states side by side run.
    pub packs: bool,
    /// Files the declaration was read from (URDF), for rebuild tracking.
    pub source_files: Vec<String>,
    /// The connections, unknowns and balance equations of the force analysis, and the
    /// declared constraints' closure equations (present when a constraint is declared or
    /// a force-analysis output is asked for).
    pub statics: Option<statics::Statics>,
}

/// Rotation entries that lie within 1e-4 of 0 or ±1 without being exactly that: rounding
/// left by angles written to a few decimals (a quarter turn written 1.57079632679 leaves
/// 4.9e-12). The expansion keeps them, as Pinocchio does; a `rotation_tolerance` above the
/// largest would make them exact and the code shorter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationResidues {
    /// How many entries of the joints' rotations.
    pub count: usize,
    /// The largest distance to 0 or ±1 among them.
    pub largest: f64,
    /// The power of ten above `largest` (at most 1e-4): a `rotation_tolerance` that clears
    /// them all.
    pub tolerance: f64,
}

impl RotationResidues {
    /// What they are and what to do, in one sentence: the CLI's `--ops` and the generated
    /// type's docs say it.
    pub fn advice(&self) -> String {
        format!(
            "{} entries of the joints' rotations lie within {:.1e} of 0 or ±1 (angles written \
             to a few decimals, such as 1.57079632679 for π/2); the generated code keeps them, \
             as Pinocchio does, and pays for every term they multiply; `rotation_tolerance: \
             {:e};` in the declaration takes them as exact, and the code is shorter.",
            self.count, self.largest, self.tolerance
        )
    }
}

impl Model {
    /// The joints' [`RotationResidues`], `None` when there are none.
    pub fn rotation_residues(&self) -> Option<RotationResidues> {
        let residue = |x: f64| x.abs().min((x.abs() - 1.0).abs());
        let residues: Vec<f64> = self
            .declared_joints
            .iter()
            .flat_map(|j| j.rotation.iter().flatten())
            .map(|&x| residue(x))
            .filter(|&r| r > 0.0 && r < rules::MAX_ROTATION_TOLERANCE)
            .collect();
        let largest = residues.iter().copied().fold(0.0_f64, f64::max);
        (!residues.is_empty()).then(|| RotationResidues {
            count: residues.len(),
            largest,
            tolerance: 10f64
                .powf(largest.log10().floor() + 1.0)
                .min(rules::MAX_ROTATION_TOLERANCE),
        })
    }
}

/// Validates a parsed mechanism. Every rule runs; all errors are returned together.
pub fn lower(mechanism: &syntax::Mechanism) -> Result<Model, syn::Error> {
    let mut diagnostics = Diagnostics::default();
    let resolved = resolve::resolve(mechanism, &mut diagnostics);
    rules::check_all(mechanism, &resolved, &mut diagnostics);
    diagnostics.take_result()?;
    let model = tree::build(mechanism, &resolved, &mut diagnostics);
    diagnostics.take_result()?;
    model.ok_or_else(|| syn::Error::new(Span::call_site(), "the mechanism could not be built"))
}

#[cfg(test)]
mod tests;
