//! The `mechanism!` language: a reference.
//!
//! This module holds no items; it is the reference of what [`mechanism!`](crate::mechanism)
//! accepts and what it generates. Every example below is a doc test.
//!
//! A declaration is a list of items, each optionally preceded by doc comments (`///`):
//!
//! | item | form |
//! | --- | --- |
//! | the type | `pub struct Name;` (exactly once; any visibility) |
//! | a setting | `gravity: ..;`, `outputs: [..];`, `frames: [..];`, `parameters: [..];`, `allow: [..];`, `urdf: "..";`, `floating_base: ..;`, `urdf_damping: ..;`, `urdf_mimic: ..;`, `force_analysis: ..;`, `isa: ..;`, `lanes: ..;`, `rotation_tolerance: ..;` (each at most once) |
//! | a body | `body name { mass: .., com: [..], inertia: .. }` or `{ .., shape: .. }` |
//! | a joint | `joint name: kind(parent -> child) { .. }` or `joint name: kind(parent -> child);` |
//! | a load | `load name: force on body at [x, y, z] in world;` (also `couple`, `wrench`; `at` and `in world` / `in body` optional) |
//! | a constraint | `constraint name: kind(a at [..], b at [..]) { .. };` |
//! | a frame | `frame name: on body at [x, y, z] rotation ..;` (`at`, `rotation` optional) |
//!
//! The macro expands to the type, its implementations of [`Mechanism`](crate::Mechanism)
//! (and, as the outputs allow, [`Dynamics`](crate::Dynamics),
//! [`Lagrangian`](crate::Lagrangian), [`Energy`](crate::Energy)), and one inherent function
//! per generated output, each generic over [`Scalar`](crate::Scalar) and each with a `_na`
//! twin taking and returning nalgebra types. The type's rustdoc lists its joints and
//! coordinates, its loads and the docs of its bodies and joints.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     /// A point mass on a massless rod of length 0.5 m, hanging along −z.
//!     pub struct Pendulum;
//!     body bob { mass: 2.0, com: [0.0, 0.0, -0.5], shape: point }
//!     joint pivot: revolute(ground -> bob) { axis: y }
//! }
//!
//! assert_eq!((Pendulum::NQ, Pendulum::NV), (1, 1));
//! assert_eq!(Pendulum::JOINT_NAMES, ["pivot"]);
//! // No `gravity:` means (0, 0, −9.81): g(q) = m g l sin q.
//! let q = 0.3_f64;
//! let g = Pendulum::gravity(&[q]);
//! assert!((g[0] - 2.0 * 9.81 * 0.5 * q.sin()).abs() < 1e-12);
//! ```
//!
//! # Settings
//!
//! ## `gravity`
//!
//! `gravity: [x, y, z];` is the acceleration of gravity in the world frame (m/s²).
//! Without it, gravity is **(0, 0, −9.81)**, the default of Pinocchio, MuJoCo and Drake; the
//! command-line compiler applies the same default to a `.urdf` file. `gravity: none;` is zero
//! gravity (so is `gravity: [0.0, 0.0, 0.0];`). Gravity's components are constants (not
//! parameters).
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Planar;
//!     gravity: [0.0, -9.81, 0.0];
//!     body bob { mass: 2.0, com: [0.0, -0.5, 0.0], shape: point }
//!     joint pivot: revolute(ground -> bob) { axis: z }
//! }
//! mechanism! {
//!     pub struct Weightless;
//!     gravity: none;
//!     body bob { mass: 2.0, com: [0.0, -0.5, 0.0], shape: point }
//!     joint pivot: revolute(ground -> bob) { axis: z }
//! }
//!
//! let q = 0.3_f64;
//! assert!((Planar::gravity(&[q])[0] - 2.0 * 9.81 * 0.5 * q.sin()).abs() < 1e-12);
//! assert_eq!(Weightless::gravity(&[q]), [0.0]);
//! assert_eq!(Weightless::model().gravity_in_world(), dynamics_runtime::nalgebra::Vector3::zeros());
//! assert_eq!(Planar::model().gravity_in_world(), dynamics_runtime::nalgebra::Vector3::new(0.0, -9.81, 0.0));
//! ```
//!
//! ## `outputs`
//!
//! `outputs: [name, ...];` chooses the functions generated. Without it, a mechanism without
//! constraints gets `inverse_dynamics`, `gravity`, `bias`, `mass_matrix`, `coriolis_matrix`,
//! `forward_dynamics`, `kinetic_energy`, `potential_energy` and `joint_reactions`; a
//! mechanism with constraints gets `force_analysis`, the three constraint functions,
//! `mass_matrix`, `bias` and the two energies (the other open-tree functions would ignore
//! the constraints, so they are generated only when named). An unknown name is an error
//! that suggests the closest one.
//!
//! A name with `_into` (`mass_matrix_into`) asks for the function and a twin,
//! `Robot::mass_matrix_into(q, &mut out)`, with the same arguments and a last one, `out: &mut`
//! the function's result type, into which it writes that result (every entry, bit for bit
//! what the function returns): nothing is returned or copied, and each entry is stored as
//! soon as it is computed instead of being held to the end (in a function cut into pieces,
//! by the piece that computes it). For a large matrix that is the faster call: the 18-dof
//! quadruped's mass matrix takes 0.74 of the time on `f64` and 0.61 on `F64x4` lanes, 64
//! results in memory (BENCHMARKS.md, "Many states per call"). An output finished by a
//! solve loop (`forward_dynamics_derivatives`, M⁻¹ of a large tree) has its right-hand
//! sides written into `out` and solved there in place.
//!
//! A name with `_sparse_into` (`mass_matrix_sparse_into`) asks for a twin that writes only
//! the entries that can be nonzero, and of a symmetric matrix (`mass_matrix`,
//! `mass_matrix_inverse`) only those on and above the diagonal, and leaves the others as
//! they are: give it a matrix zeroed once and keep passing the same one, as Pinocchio's
//! `crba` fills the upper triangle of `data.M`. On a branched robot most of a large
//! matrix is zero (between two legs, between a leg and an arm) and stores cost time: this
//! is the call to make when only M's upper triangle is read (a Cholesky or LDLᵀ
//! factorization) or when the zeros are known. Its doc comment says how many entries it
//! writes. An output finished by a solve loop writes every entry, as its `_into` twin.
//! `batch::map1_into(&q, &mut m, Robot::mass_matrix_sparse_into)` takes it as it takes
//! the `_into` twins (its packed buffer starts at zero): each state's M then holds its
//! upper triangle, zeros below.
//!
//! Every function's arguments come in the order `q`, `v`, then `a` or `tau`, then `p` (only
//! when the mechanism declares `parameters`), then `loads` (only for the functions marked
//! *loads* below, and only when the mechanism declares loads). `q: &[T; NQ]`, `v`, `a`,
//! `tau: &[T; NV]`, `p: &[T; number of parameters]`, `loads: &[T; NUM_LOAD_INPUTS]`.
//!
//! | output name | function | arguments | returns |
//! | --- | --- | --- | --- |
//! | `inverse_dynamics` | τ = M q̈ + C q̇ + g + b q̇ − Q | `q, v, a` (+ loads) | `[T; NV]` |
//! | `gravity` | g(q) | `q` | `[T; NV]` |
//! | `bias` | C(q, q̇) q̇ + g(q) + b q̇ | `q, v` | `[T; NV]` |
//! | `mass_matrix` | M(q), armature on the diagonal | `q` | `[[T; NV]; NV]` |
//! | `coriolis_matrix` (or `coriolis`) | the Christoffel-consistent C(q, q̇) | `q, v` | `[[T; NV]; NV]` |
//! | `forward_dynamics` | q̈ = M⁻¹ (τ + Q − C q̇ − g − b q̇), by whichever of the two methods below has fewer operations | `q, v, tau` (+ loads) | `[T; NV]` |
//! | `forward_dynamics_aba` | the same by the articulated-body algorithm | `q, v, tau` (+ loads) | `[T; NV]` |
//! | `forward_dynamics_ldlt` | the same by M and its tree-sparse LDLᵀ | `q, v, tau` (+ loads) | `[T; NV]` |
//! | `kinetic_energy` (or `energy`: both energies) | T = ½ q̇ᵀ M q̇ | `q, v` | `T` |
//! | `potential_energy` (or `energy`) | V = −Σ m g·c (zero at the world origin) | `q` | `T` |
//! | `joint_reactions` (or `reactions`) | per body, the wrench [F; M_P] its joint transmits to it from the parent, in the body frame about the joint point | `q, v, a` (+ loads) | `[[T; 6]; number of moving bodies]` |
//! | `force_analysis` | reaction components and driving efforts, and the pivots of the QR solve (see [Force analysis](#force-analysis)) | `q, v, a` (+ loads) | `([T; N], [T; N])` |
//! | `constraint_residual` (or `constraints`: all three) | φ(q), zero when the constraints hold | `q` | `[T; NUM_CLOSURE_EQUATIONS]` |
//! | `constraint_jacobian` (or `constraints`) | Φ_q = ∂φ/∂q | `q` | `[[T; NV]; NUM_CLOSURE_EQUATIONS]` |
//! | `constraint_bias` (or `constraints`) | γ with Φ_q q̈ = γ | `q, v` | `[T; NUM_CLOSURE_EQUATIONS]` |
//! | `joint_placements` | per body (`BODY_NAMES`), its frame's pose in the world (R, p): x_world = R x_body + p | `q` | `[([[T; 3]; 3], [T; 3]); NB]` |
//! | `joint_jacobians` | per body, J (6 × nv, rows [linear; angular]) with [v_P; ω] = J q̇ at the body origin in world axes (Pinocchio's `LOCAL_WORLD_ALIGNED`) | `q` | `[[[T; NV]; 6]; NB]` |
//! | `joint_jacobians_world` | every joint's Jacobian in one matrix, Pinocchio's WORLD convention (its `data.J`): column k is the motion [v_O; ω] coordinate k gives its body, v_O the velocity of the body point at the world origin; body i's WORLD Jacobian is the columns of the joints from the root to i | `q` | `[[T; NV]; 6]` |
//! | `joint_jacobians_world_time_variation` | (J, J̇): that matrix and its time derivative along v (Pinocchio's `data.J`, `data.dJ`) | `q, v` | `([[T; NV]; 6], [[T; NV]; 6])` |
//! | `forward_kinematics` | per body, its pose (R, p), velocity [v_P; ω] and classical acceleration [a_P; α] (world axes, without gravity) at (q, v, a): what Pinocchio's `forwardKinematics(q, v, a)` gives | `q, v, a` | `([([[T; 3]; 3], [T; 3]); NB], [[T; 6]; NB], [[T; 6]; NB])` |
//! | `joint_velocities` | per body, [v_P; ω] = J q̇, world axes | `q, v` | `[[T; 6]; NB]` |
//! | `joint_acceleration_biases` | per body, J̇ q̇: the classical acceleration [a_P; α] at q̈ = 0 without gravity, world axes | `q, v` | `[[T; 6]; NB]` |
//! | `center_of_mass` | c, world frame | `q` | `[T; 3]` |
//! | `center_of_mass_jacobian` | J_c with ċ = J_c q̇ | `q` | `[[T; NV]; 3]` |
//! | `centroidal_momentum_matrix` | A_G (6 × nv, rows [linear; angular about c], world axes) | `q` | `[[T; NV]; 6]` |
//! | `centroidal_bias` | Ȧ_G q̇: the rate of h_G = A_G q̇ at q̈ = 0 (angular part about the moving c) | `q, v` | `[T; 6]` |
//! | `frame_placements` | per operational frame (`FRAME_NAMES`, see [Frames](#frames)), its pose (R, p) in the world | `q` | `[([[T; 3]; 3], [T; 3]); NF]` |
//! | `frame_jacobians` | per frame, J (6 × nv) with [v; ω] of the frame = J q̇, world axes at the frame's origin (`LOCAL_WORLD_ALIGNED`) | `q` | `[[[T; NV]; 6]; NF]` |
//! | `frame_jacobians_local` | the same in the frame's own axes (`LOCAL`) | `q` | `[[[T; NV]; 6]; NF]` |
//! | `frame_velocities` | per frame, [v; ω] = J q̇, world axes | `q, v` | `[[T; 6]; NF]` |
//! | `frame_acceleration_biases` | per frame, J̇ q̇: its classical acceleration [a; α] at q̈ = 0 without gravity, world axes | `q, v` | `[[T; 6]; NF]` |
//! | `inverse_dynamics_derivatives` | (∂τ/∂q, ∂τ/∂q̇); ∂τ/∂q̈ = M; with loads also ∂τ/∂loads | `q, v, a` (+ loads) | `([[T; NV]; NV], [[T; NV]; NV])`, with loads `(.., .., [[T; NUM_LOAD_INPUTS]; NV])` |
//! | `forward_dynamics_derivatives` | (∂q̈/∂q, ∂q̈/∂q̇); ∂q̈/∂τ = M⁻¹; with loads also ∂q̈/∂loads | `q, v, tau` (+ loads) | as `inverse_dynamics_derivatives` |
//! | `mass_matrix_inverse` | M(q)⁻¹ | `q` | `[[T; NV]; NV]` |
//! | `momentum_derivatives` | (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇) of the generalized momentum p = M(q) q̇ and its rate ṗ = τ + Ṁ q̇ − (C q̇ + g + b q̇ − Q) (= τ + Cᵀ q̇ − g + Q − b q̇ in joint coordinates); ∂p/∂q̇ = M, ∂ṗ/∂τ = 1; with loads also ∂ṗ/∂loads. Second derivatives of M: the variational midpoint integrator's exact Newton Jacobian (through [`Lagrangian::momentum_derivatives`](crate::Lagrangian::momentum_derivatives)) | `q, v` (+ loads) | as `inverse_dynamics_derivatives`, three matrices (four with loads) |
//!
//! `kinetic_energy` and `potential_energy` come together, as do the three constraint
//! functions. The kinematics and derivative outputs (from `joint_placements` on) are
//! generated only when named. A derivative with respect to q is taken in the tangent space,
//! as Pinocchio's: column j is the derivative along q ⊕ t e_j, which for a free base is the
//! increment [δv; δω] in the base's own frame (the order of v), not the quaternion's four
//! numbers; a free base's columns are its velocity [v_P; ω] in its own frame. NB is the number
//! of moving bodies (bodies welded by fixed joints count as one), NF the number of frames.
//!
//! **Size.** The functions of linear size (inverse dynamics, forward dynamics, gravity, bias,
//! the energies, the joint reactions and the kinematics of one frame) grow with the number of
//! joints; the matrices (M, C, M⁻¹, Jacobians of every body) with its square and the
//! derivatives faster. One function's expansion takes at most 4 million graph nodes: a
//! function that needs more (say the derivatives of a 200-joint chain) is a compile error at
//! its name in `outputs:` saying to leave it out, rather than a build that exhausts the
//! machine. Inverse dynamics of a 1,000-joint chain expands in 1.5 s with the macro compiled
//! optimised (BENCHMARKS.md, "What large mechanisms cost to expand").
//!
//! ```rust
//! use dynamics_runtime::mechanism;
//!
//! mechanism! {
//!     /// A two-link planar arm in the xy plane.
//!     pub struct Planar;
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [joint_placements, joint_jacobians, center_of_mass];
//!     body upper { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
//!     body lower { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
//!     joint shoulder: revolute(ground -> upper) { axis: z }
//!     joint elbow: revolute(upper -> lower) { axis: z, at: [1.0, 0.0, 0.0] }
//! }
//!
//! let q = [std::f64::consts::FRAC_PI_2, 0.0];
//! let placements = Planar::joint_placements(&q);
//! let (_, elbow) = placements[1];
//! assert!(elbow[0].abs() < 1e-15 && (elbow[1] - 1.0).abs() < 1e-15);
//! // The elbow's origin moves at ẋ = −1 per unit shoulder rate (it is at (0, 1)).
//! let jacobians = Planar::joint_jacobians(&q);
//! assert!((jacobians[1][0][0] + 1.0).abs() < 1e-15 && jacobians[1][5][0] == 1.0);
//! let c = Planar::center_of_mass(&q);
//! assert!(c[0].abs() < 1e-15 && (c[1] - 1.0).abs() < 1e-15);
//! ```
//!
//! ```rust
//! use dynamics_runtime::mechanism;
//!
//! mechanism! {
//!     pub struct Slider;
//!     gravity: none;
//!     outputs: [mass_matrix, forward_dynamics, energy];
//!     body cart { mass: 4.0, shape: point }
//!     joint rail: prismatic(ground -> cart) { axis: x }
//! }
//!
//! assert_eq!(Slider::mass_matrix(&[0.0]), [[4.0]]);
//! assert_eq!(Slider::forward_dynamics(&[0.0], &[0.0], &[2.0]), [0.5]);
//! assert_eq!(Slider::kinetic_energy(&[0.0], &[3.0]), 18.0);
//! assert_eq!(Slider::potential_energy(&[0.0]), 0.0);
//! ```
//!
//! ## `parameters`
//!
//! `parameters: [name = nominal, ...];` declares symbolic parameters: each generated function
//! then takes `p`, their values in the declared order, and the parameters'
//! names and nominal values are `Mechanism::PARAMETER_NAMES` and `NOMINAL_PARAMETERS`. A
//! parameter may stand, scaled by a constant (`m`, `2.0 * m`, `m / 2.0`, `-m`), wherever a
//! number may, except in axes, rotations, gravity and shape dimensions, which must be
//! constants. A parameter declared and never used is an error.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Payload;
//!     parameters: [m = 2.0];
//!     outputs: [gravity];
//!     body bob { mass: m, com: [0.0, 0.0, -0.5], shape: point }
//!     joint pivot: revolute(ground -> bob) { axis: y }
//! }
//!
//! assert_eq!(Payload::PARAMETER_NAMES, ["m"]);
//! assert_eq!(Payload::NOMINAL_PARAMETERS, [2.0]);
//! let q = 0.3_f64;
//! let g = Payload::gravity(&[q], &[3.0]);
//! assert!((g[0] - 3.0 * 9.81 * 0.5 * q.sin()).abs() < 1e-12);
//! ```
//!
//! ## `allow`
//!
//! `allow: [triangle_inequality];` waives the one check that can be waived: that the
//! principal moments of every body's inertia (as merged through fixed joints) satisfy the
//! triangle inequality (I1 + I2 ≥ I3, which every physical body does). Any other name is
//! an error.
//!
//! ## `urdf`, `floating_base`, `urdf_damping` and `urdf_mimic`
//!
//! `urdf: "path";` adds a URDF file's links (as bodies) and joints (as joints) to the
//! declaration. The path is relative to the directory of the `Cargo.toml` of the crate that
//! invokes the macro. `revolute` and `continuous` joints become revolute joints (one
//! coordinate, the angle), `prismatic` prismatic, `fixed` fixed; the root link is welded to
//! the ground by a joint `ground_weld`, or, with `floating_base: true;`, given a free joint
//! `root_joint`. Planar, floating and spherical joints are refused, and so are mimic joints
//! (a `<mimic>` couples one coordinate to another) unless `urdf_mimic: false;`, which
//! ignores the `<mimic>` elements: each such joint is then an independent coordinate, as
//! Pinocchio's `buildModel` makes it by default (Talos' and Romeo's grippers, say). Every
//! rule of the language applies to the imported bodies and joints, with errors at the path.
//!
//! What each joint's elements become:
//!
//! | URDF | here |
//! | --- | --- |
//! | `<origin>`, `<axis>` | `at`, `rotation`, `axis` |
//! | `<dynamics damping>` | `damping`: viscous friction b, in the dynamics (see below) |
//! | `<dynamics friction>` | `friction`: Coulomb friction, in `JOINT_FRICTION` only |
//! | `<limit lower upper velocity effort>` | `limits`, in `JOINT_LIMITS` only; `lower` and `upper` 0 when absent, `velocity` and `effort` required, as URDF defines them; a `continuous` joint's position unbounded; no `<limit>`, no limits |
//!
//! **Damping and Pinocchio.** The URDF's damping b enters the dynamics as a declared
//! `damping` does: `inverse_dynamics` and `bias` include b q̇, `forward_dynamics` subtracts
//! it. Pinocchio reads the same number into `model.damping` but its `rnea`, `nle` and `aba`
//! leave it out, so on a damped URDF `inverse_dynamics` is Pinocchio's `rnea` + b q̇.
//! `urdf_damping: false;` drops the file's damping (the default, `true`, keeps it), and the
//! functions then match Pinocchio's. `floating_base`, `urdf_damping` and `urdf_mimic` take
//! `true` or `false` and apply to the `urdf:` file: any of them without one is an error.
//!
//! **Joint order.** The bodies, joints and coordinates are ordered depth first from the
//! ground, each subtree contiguous, as Pinocchio orders them: a URDF link's child joints in
//! the order of their names (byte by byte, `B` before `a`), which is the order Pinocchio's
//! URDF parser takes them in (from urdfdom, which keeps them sorted by name), whatever their
//! order in the file. So `JOINT_NAMES`, q and v are Pinocchio's, and a Pinocchio state can
//! be used as it is (but for `continuous` joints, whose (cos θ, sin θ) is θ here). A
//! declared mechanism's children come in declaration order.
//!
//! **Fixed joints.** A link welded through a fixed joint is merged into the body it is
//! welded to (masses, mass centres and inertias combined), and the inertia rules judge the
//! merged body, not each link: a link's placeholder inertia (a tiny diagonal that alone
//! violates the triangle inequality, say) is accepted when the body it is welded into is
//! physical, and the generated docs of that body say so. A merged body that is itself
//! unphysical is an error.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     /// A 2 kg rod, its mass centre 0.3 m from its pivot (this repository's fixture).
//!     pub struct FromUrdf;
//!     urdf: "../models/urdf/pendulum.urdf";
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [gravity];
//! }
//!
//! assert_eq!(FromUrdf::JOINT_NAMES, ["joint1"]);
//! let q = 0.3_f64;
//! assert!((FromUrdf::gravity(&[q])[0] - 2.0 * 9.81 * 0.3 * q.sin()).abs() < 1e-12);
//! // The file's `<limit lower="-6.28" upper="6.28" effort="100" velocity="10"/>`.
//! let limits = FromUrdf::JOINT_LIMITS[0];
//! assert_eq!((limits.lower, limits.upper, limits.velocity, limits.effort), (-6.28, 6.28, 10.0, 100.0));
//! assert_eq!(FromUrdf::JOINT_FRICTION, [0.0]);
//!
//! mechanism! {
//!     /// A gripper whose right finger mimics the left (this repository's fixture): with
//!     /// `urdf_mimic: false;`, two independent coordinates.
//!     pub struct Gripper;
//!     urdf: "../tests/ui/urdf/mimic_joint.urdf";
//!     urdf_mimic: false;
//!     outputs: [mass_matrix];
//! }
//!
//! assert_eq!(Gripper::JOINT_NAMES, ["left_slide", "right_slide"]);
//! let m = Gripper::mass_matrix(&[0.01, 0.02]);
//! assert_eq!((m[0][0], m[1][1], m[0][1]), (0.05, 0.05, 0.0));
//! ```
//!
//! ## `force_analysis`
//!
//! `force_analysis: planar;` (motion in the world xy plane, three balance equations per
//! body; the default when the mechanism has constraints) or `force_analysis: spatial;` (six
//! per body). Declaring it (with no `outputs:`) asks for the `force_analysis` output. In a
//! planar analysis gravity must lie in the xy plane, so a planar mechanism with constraints
//! declares `gravity: [0.0, -9.81, 0.0];` (or another in-plane vector) or `gravity: none;`:
//! the default (0, 0, −9.81) is an error there. See [Force analysis](#force-analysis).
//!
//! ## `isa`
//!
//! `isa: dispatch;` (the default) generates two copies of each function, one for the
//! crate's target and one for AVX2 + FMA, chosen at run time (see [`isa`](crate::isa));
//! `isa: baseline;` generates the crate's target's copy only.
//!
//! ## `lanes`
//!
//! `lanes: true;` is for mechanisms evaluated on many states at once, through the SIMD
//! lane types [`F64x4`](crate::F64x4) and [`F32x8`](crate::F32x8) (the [`batch`](crate::batch)
//! helpers). Where the generated code computes isomorphic limbs side by side (a
//! quadruped's four legs in the lanes of one AVX register), or a matrix's columns four to a
//! value, every operation of an `f64` call fills the register with one state's limbs; on
//! a lane type that already holds four states, a value of four limbs is four registers.
//! With `lanes: true;` each such function (the mass and Coriolis matrices, forward
//! dynamics, the derivatives, as the mechanism has them) also carries the same function
//! expanded with no packed value, the cheapest such expansion (for the quadruped's
//! forward dynamics CRBA + LDLᵀ where `f64` runs the articulated-body algorithm), and the
//! lane types run that body: `f32` and `f64` still run the packed one, and no type
//! instantiates both. The results agree with `f64`'s to rounding (1e-14 relative,
//! measured 1.3e-15), not bit for bit as the other functions' lanes do; the function's
//! docs give both op counts. It costs compile time (this repository's `models` crate, where
//! the quadruped and the UR5 declare it, rebuilt in release: 6.2 s without, 6.8 s with),
//! so it is off by default, and lane types then run the packed body.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, F64x4};
//!
//! mechanism! {
//!     /// A three-link arm whose mass matrix carries its columns four to a value.
//!     pub struct Batched;
//!     lanes: true;
//!     outputs: [mass_matrix];
//!     body a { mass: 1.0, com: [0.2, 0.0, 0.0], inertia: diag([0.01, 0.02, 0.02]) }
//!     body b { mass: 0.8, com: [0.2, 0.0, 0.0], inertia: diag([0.01, 0.02, 0.02]) }
//!     body c { mass: 0.5, com: [0.1, 0.0, 0.0], inertia: diag([0.01, 0.01, 0.01]) }
//!     joint j1: revolute(ground -> a) { axis: z }
//!     joint j2: revolute(a -> b) { axis: y, at: [0.4, 0.0, 0.0] }
//!     joint j3: revolute(b -> c) { axis: y, at: [0.4, 0.0, 0.0] }
//! }
//!
//! let states = [[0.1, 0.2, 0.3], [0.4, -0.5, 0.6], [0.7, 0.8, -0.9], [1.0, 1.1, 1.2]];
//! let q: [F64x4; 3] = std::array::from_fn(|j| F64x4::from_fn(|k| states[k][j]));
//! let m = Batched::mass_matrix(&q);
//! for (k, state) in states.iter().enumerate() {
//!     let one = Batched::mass_matrix(state);
//!     for (i, j) in (0..3).flat_map(|i| (0..3).map(move |j| (i, j))) {
//!         assert!((m[i][j].to_array()[k] - one[i][j]).abs() < 1e-14);
//!     }
//! }
//! ```
//!
//! ## `rotation_tolerance`
//!
//! `rotation_tolerance: 1e-10;` takes every angle of an `rpy` or axis-angle rotation
//! within 1e-10 of a multiple of a quarter turn as exactly that multiple (so the rotation
//! stays orthonormal), and every entry of a rotation given as a matrix within 1e-10 of 0
//! or ±1 as exactly that: the joints' placements, DH rows and a URDF's inertial frames
//! (the default is 1e-15 and changes no angle; it must lie between 1e-15 and 1e-4: 1e-5
//! takes the 1.5708 of an angle written to four decimals, 3.7e-6 off, as π/2). Many URDFs
//! write π/2 as 1.57079632679,
//! which leaves 4.9e-12 in a cosine: by default it is kept, as Pinocchio keeps it, and
//! every term it multiplies costs operations; with the setting those terms fold (on
//! HyQ's URDF the mass matrix drops from 1,368 to 756 operations). The price is the
//! residue itself: positions and inertias differ from the file's by about that much.
//! The generated type's docs (under "Rotations") and `dynamics-codegen file.rs --ops`
//! count such entries and name the tolerance that clears them.
//!
//! ```rust
//! use dynamics_runtime::mechanism;
//!
//! // The same arm three times: its elbow placed by a quarter turn about x written exactly,
//! // written to 11 decimals, and written to 11 decimals with the tolerance.
//! macro_rules! arm {
//!     ($name:ident, $roll:expr $(, $setting:ident: $value:expr)?) => {
//!         mechanism! {
//!             pub struct $name;
//!             $($setting: $value;)?
//!             outputs: [mass_matrix];
//!             body upper { mass: 1.0, com: [0.2, 0.0, 0.0], shape: rod(length: 0.4, axis: x) }
//!             body lower { mass: 1.0, com: [0.2, 0.0, 0.1], shape: rod(length: 0.4, axis: x) }
//!             joint shoulder: revolute(ground -> upper) { axis: z }
//!             joint elbow: revolute(upper -> lower) { axis: z, at: [0.4, 0.0, 0.0], rotation: rpy($roll, 0.0, 0.0) }
//!         }
//!     };
//! }
//! arm!(Exact, pi / 2.0);
//! arm!(Written, 1.57079632679);
//! arm!(Cleared, 1.57079632679, rotation_tolerance: 1e-10);
//!
//! let q = [0.3, -0.7];
//! assert_eq!(Cleared::mass_matrix(&q), Exact::mass_matrix(&q));
//! assert_ne!(Written::mass_matrix(&q), Exact::mass_matrix(&q));
//! ```
//!
//! # Numbers
//!
//! Wherever a number is expected, a constant expression is accepted: integer and float
//! literals, `pi` (or `PI`), unary minus, `+ - * /` and parentheses. An identifier other
//! than `pi` is a parameter, which may only be multiplied or divided by a constant. A
//! literal takes no type suffix (`300u8`, `1.1f32` and `2.0f64` are errors): the generated
//! code is generic over its scalar type and converts every number to it. Every number is
//! finite: a constant, a parameter's factor (`m / 0.0` is not) and a parameter's number at
//! the nominal values (`1e308 * m` with m = 1e308 is not).
//!
//! ```rust
//! use dynamics_runtime::mechanism;
//!
//! mechanism! {
//!     pub struct Expressions;
//!     gravity: none;
//!     outputs: [mass_matrix];
//!     body bob { mass: 2 * (0.5 + 0.5), com: [1.0 / 2.0, 0.0, 0.0], shape: point }
//!     joint pivot: revolute(ground -> bob) { axis: z, rotation: rpy(0, 0, pi / 2) }
//! }
//!
//! // M = m l² = 2 · 0.25, whatever the placement's rotation about the axis.
//! assert!((Expressions::mass_matrix(&[0.0_f64])[0][0] - 0.5).abs() < 1e-15);
//! ```
//!
//! # Bodies
//!
//! `body name { mass: m, com: [x, y, z], inertia: .. }`: the mass (kg); the mass centre
//! c = PG in the body frame (m; the body frame's origin when `com` is absent); and I_G, the
//! inertia about the mass centre in the body frame (kg·m²), given in one of these forms:
//!
//! | form | I_G |
//! | --- | --- |
//! | `inertia: [[a, b, c], [d, e, f], [g, h, i]]` | the matrix, by rows (symmetric, positive semi-definite) |
//! | `inertia: diag([i1, i2, i3])` | diag(i1, i2, i3) |
//! | `inertia: principal([i1, i2, i3], rotation: R)` | R diag(i1, i2, i3) Rᵀ: the principal axes are the columns of R (any [rotation form](#rotations)) |
//! | `shape: point` | 0 |
//! | `shape: sphere(radius: r)` | ⅖ m r² about every axis |
//! | `shape: box(size: [a, b, c])` | diag(m (b² + c²)/12, m (a² + c²)/12, m (a² + b²)/12) |
//! | `shape: rod(length: l, axis: x)` | 0 about the axis, m l²/12 about the two others |
//! | `shape: cylinder(radius: r, length: l, axis: z)` | m r²/2 about the axis, m (3 r² + l²)/12 about the two others |
//!
//! A shape is a uniform solid centred at the mass centre; a shape's axis is a body axis,
//! `x`, `y` or `z` (use `inertia: principal(..)` for another orientation). A body gives
//! either `inertia` or `shape`, and the fields are `mass`, `com`, `inertia` (or `shape`),
//! each at most once. Masses are not negative, inertias are symmetric, shape dimensions
//! are not negative (each body as declared), and the inertia of every body of the
//! dynamics is positive semi-definite and satisfies the triangle inequality, judged on the
//! bodies as merged through fixed joints: the bodies welded to one body (or to the ground)
//! are one body, whose mass, mass centre and I_G combine theirs, and a body that alone
//! would fail (a placeholder inertia) is accepted when the merged body passes. The type's
//! docs note such a body.
//!
//! Every joint coordinate moves some inertia, or M(q) would be singular: a revolute joint's
//! bodies (with everything they carry) have a moment of inertia about its axis, a
//! prismatic joint's have mass, a free joint's have mass and inertia about every axis
//! through their centre of mass, in some configuration, or the joint has `armature`. The
//! rule applies when the mechanism asks for an output that needs M(q) (dynamics, gravity,
//! bias, the mass and Coriolis matrices, their derivatives and inverse); a mechanism that
//! asks only for kinematics, energies, reactions or the force analysis may move massless
//! links (a URDF's links without `<inertial>`), and so may its `Mechanism::model()`
//! ([`ModelBuilder::allow_coordinates_without_inertia`](crate::ModelBuilder::allow_coordinates_without_inertia)).
//! The coordinates must also be independent in inertia together: M(q), evaluated at a few
//! random configurations, must be positive definite at one of them, or the error names the
//! joints whose coordinates are dependent (a massless body on a free joint carrying one
//! body: 7 coordinates for the 6 that one rigid body has; massless links ending at a point
//! mass). Singular at special configurations only (a stretched arm) compiles.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Shapes;
//!     gravity: none;
//!     outputs: [mass_matrix];
//!     body rod { mass: 3.0, shape: rod(length: 2.0, axis: x) }
//!     body disc { mass: 2.0, shape: cylinder(radius: 0.5, length: 0.1, axis: z) }
//!     body ball { mass: 5.0, shape: sphere(radius: 0.2) }
//!     body brick { mass: 12.0, shape: box(size: [1.0, 2.0, 3.0]) }
//!     body tilted { mass: 1.0, inertia: principal([1.0, 2.0, 3.0], rotation: rpy(0, 0, pi / 2)) }
//!     joint a: revolute(ground -> rod) { axis: z }
//!     joint b: revolute(ground -> disc) { axis: z }
//!     joint c: revolute(ground -> ball) { axis: z }
//!     joint d: revolute(ground -> brick) { axis: z }
//!     joint e: revolute(ground -> tilted) { axis: z }
//! }
//!
//! let model = Shapes::model();
//! let inertia = |i: usize| model.bodies()[i].inertia.inertia_com_in_body;
//! let near = |x: f64, y: f64| (x - y).abs() < 1e-12;
//! assert!(near(inertia(0)[(0, 0)], 0.0) && near(inertia(0)[(2, 2)], 3.0 * 4.0 / 12.0));
//! assert!(near(inertia(1)[(2, 2)], 2.0 * 0.25 / 2.0));
//! assert!(near(inertia(2)[(1, 1)], 0.4 * 5.0 * 0.04));
//! assert!(near(inertia(3)[(0, 0)], 13.0) && near(inertia(3)[(2, 2)], 5.0));
//! // A quarter turn about z swaps the principal moments about x and y.
//! assert!(near(inertia(4)[(0, 0)], 2.0) && near(inertia(4)[(1, 1)], 1.0));
//! let m = Shapes::mass_matrix(&[0.0; 5]);
//! assert!(near(m[3][3], 5.0));
//! ```
//!
//! # Joints
//!
//! `joint name: kind(parent -> child) { field: value, .. }` (or `;` instead of the braces
//! when there are no fields). The parent is a body or `ground`; every body has exactly one
//! parent joint and the bodies form a tree rooted at the ground. The bodies, joints and
//! coordinates (`BODY_NAMES`, `JOINT_NAMES`, q, v) are numbered depth first from the
//! ground, each subtree contiguous, a body's children in declaration order.
//!
//! | kind | coordinates |
//! | --- | --- |
//! | `revolute` (also `continuous`) | one angle about `axis` (rad) |
//! | `prismatic` | one displacement along `axis` (m) |
//! | `fixed` | none: the child is welded to the parent (merged into one composite body) |
//! | `free` | a free-flying body, from the ground only: q = [position; quaternion x y z w] (7), v = [linear velocity; ω] in the body frame (6) |
//!
//! | field | meaning |
//! | --- | --- |
//! | `axis` | revolute and prismatic (required), in the joint frame: `x`, `y`, `z`, `-x`, `-y`, `-z` or `[a, b, c]` (not zero) |
//! | `at: [x, y, z]` | the joint frame's origin in the parent frame (the origin when absent) |
//! | `rotation` | the joint frame's orientation in the parent frame ([rotation forms](#rotations); the identity when absent) |
//! | `placement: dh(a: .., alpha: .., d: .., theta: ..)` or `mdh(..)` | revolute and prismatic: the joint placed by a row of a Denavit–Hartenberg table, instead of `axis`, `at` and `rotation` (see [Denavit–Hartenberg placements](#denavithartenberg-placements)) |
//! | `armature` | rotor inertia reflected to the coordinate, added to M's diagonal (not negative) |
//! | `damping` | viscous friction b: the joint force b q̇ enters `bias` and `inverse_dynamics` and opposes the motion in `forward_dynamics` (not negative) |
//! | `friction` | Coulomb friction (N·m or N; not negative): carried to `JOINT_FRICTION`, in no generated function (as Pinocchio's `model.friction`) |
//! | `limits: { lower: .., upper: .., velocity: .., effort: .. }` | the coordinate's limits (each optional, unbounded when absent; lower ≤ upper, velocity and effort not negative): carried to `JOINT_LIMITS`, enforced by no generated function |
//! | `driven: true` | an actuator drives the coordinate: the force analysis solves for its effort |
//!
//! `friction` and `limits` are constants, and only on revolute and prismatic joints. The
//! type's `Mechanism::JOINT_LIMITS` (a [`JointLimits`](crate::JointLimits) per velocity
//! coordinate, in the order of v: ±∞, that is [`f64::INFINITY`], where none is given; a free
//! joint's six unbounded) and `Mechanism::JOINT_FRICTION` (one per velocity coordinate, 0
//! where none is given) list them, and its docs have a `# Limits and friction` table.
//!
//! At q = 0 the child's frame is the joint frame.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Arm;
//!     gravity: none;
//!     outputs: [mass_matrix, bias];
//!     body link { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
//!     body tip { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
//!     joint shoulder: revolute(ground -> link) { axis: z, armature: 0.1, damping: 0.5 }
//!     joint elbow: revolute(link -> tip) { axis: z, at: [1.0, 0.0, 0.0] }
//! }
//! mechanism! {
//!     pub struct Drone;
//!     body frame { mass: 1.0, inertia: diag([0.1, 0.1, 0.2]) }
//!     joint flight: free(ground -> frame);
//! }
//!
//! // M₀₀ = armature + m (0.5 m)² + m (1.5 m)², the tip 0.5 m beyond the elbow at 1 m.
//! let m = Arm::mass_matrix(&[0.0_f64, 0.0]);
//! assert!((m[0][0] - (0.1 + 0.25 + 2.25)).abs() < 1e-12);
//! // Outstretched and turning at the shoulder only: the bias is the damping b q̇.
//! assert!((Arm::bias(&[0.0_f64, 0.0], &[2.0, 0.0])[0] - 0.5 * 2.0).abs() < 1e-12);
//! assert_eq!((Drone::NQ, Drone::NV), (7, 6));
//! ```
//!
//! ```rust
//! use dynamics_runtime::{mechanism, JointLimits, Mechanism};
//!
//! mechanism! {
//!     pub struct Limited;
//!     outputs: [gravity];
//!     body link { mass: 1.0, com: [0.5, 0.0, 0.0], shape: point }
//!     body slide { mass: 1.0, shape: point }
//!     joint shoulder: revolute(ground -> link) {
//!         axis: y,
//!         friction: 0.2,
//!         limits: { lower: -pi / 2, upper: pi / 2, velocity: 3.0, effort: 40.0 },
//!     }
//!     joint rail: prismatic(link -> slide) { axis: x, limits: { upper: 0.3 } }
//! }
//!
//! let [shoulder, rail] = [Limited::JOINT_LIMITS[0], Limited::JOINT_LIMITS[1]];
//! assert_eq!((shoulder.upper, shoulder.effort), (std::f64::consts::FRAC_PI_2, 40.0));
//! assert_eq!(rail, JointLimits { upper: 0.3, ..JointLimits::UNBOUNDED });
//! assert!(rail.contains_position(-5.0) && !rail.contains_position(0.4));
//! assert_eq!(Limited::JOINT_FRICTION, [0.2, 0.0]);
//! ```
//!
//! ## Denavit–Hartenberg placements
//!
//! A revolute or prismatic joint may be placed by a row of a Denavit–Hartenberg table:
//! `placement: dh(a: .., alpha: .., d: .., theta: ..)` in the standard (distal) convention,
//! `placement: mdh(..)` in the modified (proximal) one of Craig's *Introduction to
//! Robotics*. The entries come in any order, each at most once, 0 when absent; lengths in
//! metres, angles in radians. The joint moves about (revolute) or along (prismatic) the z
//! axis of its DH frame: the coordinate q adds to θ (revolute) or to d (prismatic), so θ and
//! d are the offsets at q = 0. The row replaces `axis`, `at` and `rotation`, which are
//! errors on the same joint; fixed and free joints take no row. The angles α and θ are
//! constants; the lengths a and d may be [parameters](#parameters).
//!
//! | form | row on joint i | frame i in frame i−1 | the joint's axis |
//! | --- | --- | --- | --- |
//! | `mdh(..)` | (a_{i−1}, α_{i−1}, d_i, θ_i) | Rx(α) Tx(a) Rz(θ + q) Tz(d) | z of frame i |
//! | `dh(..)` | (a_i, α_i, d_i, θ_i) | Rz(θ + q) Tz(d) Tx(a) Rx(α) | z of frame i−1 |
//!
//! (For a prismatic joint, θ + q becomes θ and d becomes d + q.) Frame i is the DH frame of
//! the joint's child body, frame i−1 its parent's (the ground's frame for a joint on the
//! ground). The child's mass centre, inertia (and shape axes), the loads and frames declared
//! on it, the constraint points on it and the placements of the joints whose parent it is
//! are all given in frame i, as DH tables publish them.
//!
//! `mdh(..)` is `at: [a, −d sin α, d cos α]`, `rotation: Rx(α) Rz(θ)`, `axis: z`: frame i
//! is the joint frame after the motion, the child's frame as for any joint.
//!
//! With `dh(..)`, the joint frame is Rz(θ) Tz(d) in frame i−1 and the body's frame *in the
//! generated code* is that frame after the motion, the frame on joint i's axis (Craig's
//! frame i): `joint_placements` gives it, and so do the reactions and Jacobians given "at
//! the body origin". The DH link frame i, at the next joint's axis, is that frame times the
//! constant C = Tx(a) Rx(α): x_body = Rx(α) x_DH + (a, 0, 0). Naming the body in
//! `frames: [..]` makes the frame outputs give the DH link frame itself (a body's frame
//! there is the frame its data are declared in), and so does the runtime `Model`'s frame
//! of the body (its joint carries C as
//! [`JointSpec::with_child_frame`](crate::JointSpec::with_child_frame)). A table declared
//! both ways generates the same functions (`tests/dh_placements.rs` checks it on the
//! PUMA 560, token for token).
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     /// Two links of 0.5 m, the second twisted by α₁ = π/2 (standard DH), point masses
//!     /// at 0.1 m before the end of each link, along its DH x axis.
//!     pub struct Standard;
//!     outputs: [mass_matrix, gravity, joint_placements, frame_placements];
//!     frames: [upper, lower];
//!     body upper { mass: 2.0, com: [-0.1, 0.0, 0.0], shape: point }
//!     body lower { mass: 1.0, com: [-0.1, 0.0, 0.0], shape: point }
//!     joint shoulder: revolute(ground -> upper) { placement: dh(a: 0.5, alpha: pi / 2, d: 0.3) }
//!     joint elbow: revolute(upper -> lower) { placement: dh(a: 0.5) }
//! }
//! mechanism! {
//!     /// The same arm in Craig's convention: row i takes a and α from standard row i − 1,
//!     /// and the mass centres move to Craig's frames: (a_i − 0.1, 0, 0).
//!     pub struct Modified;
//!     outputs: [mass_matrix, gravity, joint_placements];
//!     body upper { mass: 2.0, com: [0.5 - 0.1, 0.0, 0.0], shape: point }
//!     body lower { mass: 1.0, com: [0.5 - 0.1, 0.0, 0.0], shape: point }
//!     joint shoulder: revolute(ground -> upper) { placement: mdh(d: 0.3) }
//!     joint elbow: revolute(upper -> lower) { placement: mdh(a: 0.5, alpha: pi / 2) }
//! }
//!
//! let q = [0.4_f64, -1.1];
//! assert_eq!(Standard::mass_matrix(&q), Modified::mass_matrix(&q));
//! assert_eq!(Standard::gravity(&q), Modified::gravity(&q));
//! // The bodies' poses are Craig's frames; the frames named in `frames: [..]` are the DH
//! // link frames, 0.5 m further along their x axis (and turned by α about it).
//! let (r, p) = Standard::joint_placements(&q)[1];
//! assert_eq!((r, p), Modified::joint_placements(&q)[1]);
//! let (_, tip) = Standard::frame_placements(&q)[Standard::FRAME_LOWER];
//! for k in 0..3 {
//!     assert!((tip[k] - (p[k] + 0.5 * r[k][0])).abs() < 1e-15);
//! }
//! ```
//!
//! ## Rotations
//!
//! | form | rotation |
//! | --- | --- |
//! | `rpy(roll, pitch, yaw)` | R = Rz(yaw) Ry(pitch) Rx(roll) (about fixed axes, as URDF's `rpy`; radians) |
//! | `axis_angle([x, y, z], angle)` | by `angle` (rad) about the axis (normalized; not zero) |
//! | `[[a, b, c], [d, e, f], [g, h, i]]` | the matrix, by rows (orthonormal, determinant +1) |
//!
//! Entries within 1e-15 of 0 or ±1 (or the declaration's
//! [`rotation_tolerance`](#rotation_tolerance)) are made exact, so `rpy(pi / 2, 0, 0)` is
//! exactly a quarter turn. Rotations are constants (not parameters).
//!
//! Inside the generated code a moving body's frame may be turned about its joint's axis by
//! a constant angle, where that makes the placements and the inertia sparser (a turn about
//! the axis commutes with the joint's motion, so the physics is the same): ANYmal's URDF
//! turns each hip by 150° about its axis and the next link back, which then costs what an
//! axis-aligned description costs. Every output still reports the frames as declared:
//! `joint_placements` and `forward_kinematics` give the joint frame, `joint_reactions` its
//! axes. Mechanisms with a force analysis keep their frames.
//!
//! # Loads
//!
//! `load name: force on body at [x, y, z];`, `load name: couple on body;` or
//! `load name: wrench on body at [x, y, z];` declares a run-time input. A force has 3
//! inputs, a couple 3, a wrench 6 (the force, then the couple). The loads' inputs are
//! consecutive entries of the `loads` argument, in the order of declaration, each given
//! **in the axes of the body it is declared on**; a force acts through the point `at` (in
//! that body's frame; the body's origin when absent), a couple is free.
//! `inverse_dynamics`, `forward_dynamics` (and its `_aba`, `_ldlt` and `_derivatives`
//! forms), `inverse_dynamics_derivatives`, `joint_reactions` and `force_analysis` take
//! `loads`; the generated type's rustdoc lists each load's entries and axes, and
//! `Mechanism::model()` holds the loads as declared ([`LoadSpec`](crate::LoadSpec), with
//! [`Reference::generalized_load_forces`](crate::Reference::generalized_load_forces) for
//! their generalized force).
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Pushed;
//!     gravity: none;
//!     outputs: [inverse_dynamics];
//!     body bar { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
//!     joint pivot: revolute(ground -> bar) { axis: z }
//!     load push: force on bar at [1.0, 0.0, 0.0];
//!     load twist: couple on bar;
//! }
//!
//! assert_eq!(Pushed::LOAD_NAMES, ["push", "twist"]);
//! assert_eq!(Pushed::NUM_LOAD_INPUTS, 6);
//! // 2 N along the bar's y at its tip, and 0.5 N·m about z: holding it still takes −2.5 N·m.
//! let loads = [0.0, 2.0, 0.0, 0.0, 0.0, 0.5];
//! let tau = Pushed::inverse_dynamics(&[0.7_f64], &[0.0], &[0.0], &loads);
//! assert!((tau[0] + 2.5).abs() < 1e-12);
//! ```
//!
//! A trailing `in world` gives the components in the world's fixed axes instead (a cable
//! pulling in a fixed direction, a contact force measured in the world); the point stays
//! fixed on the body, given in its frame. The generated code turns the components into the
//! body's axes, F_in_body = R_bodyᵀ F_in_world, with the body's orientation at `q`. `in body`
//! says the default explicitly. The two may come in either order after the body; `in` takes
//! `world` or `body` and is given once.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, LoadFrame, Mechanism};
//!
//! mechanism! {
//!     pub struct Pulled;
//!     gravity: none;
//!     outputs: [inverse_dynamics];
//!     body bar { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
//!     joint pivot: revolute(ground -> bar) { axis: z }
//!     /// A cable at the tip, pulling along the world's y whatever the bar's angle.
//!     load cable: force on bar at [1.0, 0.0, 0.0] in world;
//!     /// The same force in the bar's axes.
//!     load push: force on bar at [1.0, 0.0, 0.0] in body;
//! }
//!
//! assert_eq!(Pulled::model().loads()[0].frame, LoadFrame::World);
//! // At angle q the tip is at (cos q, sin q, 0): 2 N along the world's y has the moment
//! // 2 cos q about the pivot, along the bar's y the moment 2.
//! let q = 0.7_f64;
//! let in_world = Pulled::inverse_dynamics(&[q], &[0.0], &[0.0], &[0.0, 2.0, 0.0, 0.0, 0.0, 0.0]);
//! assert!((in_world[0] + 2.0 * q.cos()).abs() < 1e-12);
//! let in_body = Pulled::inverse_dynamics(&[q], &[0.0], &[0.0], &[0.0, 0.0, 0.0, 0.0, 2.0, 0.0]);
//! assert!((in_body[0] + 2.0).abs() < 1e-12);
//! ```
//!
//! # Frames
//!
//! `frame name: on body at [x, y, z] rotation ..;` attaches an operational frame (a tool
//! centre point, a foot, a camera) to a body or to `ground`: its origin `at` and its
//! `rotation` (any [rotation form](#rotations)) are given in the body's frame,
//! x_body = R x_frame + p (the body's origin and axes when absent). Every body welded to
//! another through a fixed joint is a frame too, named after it, so a URDF's end effectors,
//! flanges and feet need no declaration. The frame outputs cover the welded bodies (in the
//! tree's depth-first order) then the declared frames; `frames: [a, b];` chooses which, in
//! that order (a moving body's name is accepted there too: its own frame, the one its data
//! are declared in, which for the child of a `dh(..)` joint is its DH link frame).
//! `FRAME_NAMES` lists them and `Type::FRAME_<NAME>` (upper case) is each one's index. A
//! frame's name differs from every body's and every other frame's. In the Jacobians, a
//! column of a joint that does not move the frame is a constant zero, and nothing is
//! computed for it.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, Mechanism};
//!
//! mechanism! {
//!     pub struct Planar;
//!     gravity: [0.0, -9.81, 0.0];
//!     outputs: [frame_placements, frame_jacobians, frame_acceleration_biases];
//!     body upper { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
//!     body lower { mass: 1.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
//!     joint shoulder: revolute(ground -> upper) { axis: z }
//!     joint elbow: revolute(upper -> lower) { axis: z, at: [1.0, 0.0, 0.0] }
//!     /// The tip of the lower link, its x axis along the link.
//!     frame tip: on lower at [1.0, 0.0, 0.0];
//! }
//!
//! assert_eq!(Planar::FRAME_NAMES, ["tip"]);
//! let q = [0.0, std::f64::consts::FRAC_PI_2];
//! let (rotation, origin) = Planar::frame_placements(&q)[Planar::FRAME_TIP];
//! assert!((origin[0] - 1.0).abs() < 1e-15 && (origin[1] - 1.0).abs() < 1e-15);
//! assert!((rotation[1][0] - 1.0).abs() < 1e-15); // x_tip points along world y
//! // The tip moves at −1 along x per unit shoulder rate, and per unit elbow rate.
//! let jacobian = Planar::frame_jacobians(&q)[Planar::FRAME_TIP];
//! assert!((jacobian[0][0] + 1.0).abs() < 1e-15 && (jacobian[0][1] + 1.0).abs() < 1e-15);
//! // Spinning the elbow at 2 rad/s: the tip accelerates toward the elbow at 2² · 1 m.
//! let bias = Planar::frame_acceleration_biases(&q, &[0.0, 2.0])[Planar::FRAME_TIP];
//! assert!(bias[0].abs() < 1e-14 && (bias[1] + 4.0).abs() < 1e-14);
//! ```
//!
//! # Constraints
//!
//! `constraint name: kind(a at [x, y, z], b at [x, y, z]) { field: .. };` connects two
//! bodies (either may be `ground`) at a point of each, given in that body's frame (its
//! origin when `at` is absent); the braces and the final `;` are optional. Constraints close
//! loops (a four-bar) or add supports (a beam on a pin and a roller); the tree of joints
//! stays the mechanism's coordinates, and the constraints give the closure functions
//! (`constraint_residual`, `constraint_jacobian`, `constraint_bias`, with
//! `NUM_CLOSURE_EQUATIONS` equations) and the reactions of the force analysis.
//!
//! | kind | holds | reactions |
//! | --- | --- | --- |
//! | `pin` | the two points together (spatial: a hinge about `axis`) | planar: two forces; spatial: three forces and the two couples normal to `axis` |
//! | `ball` | the two points together (spatial) | three forces |
//! | `roller` (also `slider`) | the second point on the line through the first point normal to `normal` | one force along `normal` |
//! | `prismatic` | sliding along `axis` | the forces normal to the axis and every couple (planar: one normal force and the couple about z) |
//! | `weld` | no relative motion | every force and couple component |
//!
//! Fields: `normal` (roller) and `axis` (prismatic, spatial pin), in the first body's frame,
//! written as a joint's axis.
//!
//! # Force analysis
//!
//! A mechanism with constraints, or with `force_analysis:` declared, gets `force_analysis(q,
//! v, a[, p][, loads])`: each body's balance equations A(q) x = b(q, q̇, q̈), solved by
//! Givens QR. It returns (x, the diagonal of R); [`ForceAnalysis`](crate::ForceAnalysis)
//! turns the pair into the unknowns, refusing an ill-conditioned configuration
//! ([`ForceAnalysis::checked`](crate::ForceAnalysis::checked)). The unknowns are the
//! reaction components of every joint and constraint, along the axes of the connection's
//! first body, each acting on the second body (and, opposite, on the first), then the
//! efforts of the driven joints; their names are the inherent constant `FORCE_UNKNOWNS`. In a
//! mechanism without constraints every joint is driven; with constraints, the joints marked
//! `driven: true`. The unknowns must match the equations, in number and body by body: a
//! statically indeterminate structure, a motion with no input and a redundant constraint
//! are compile-time errors. The macro also evaluates A(q), and the loop-closure Jacobian Φ_q,
//! with the declaration's numbers at a few pseudo-random configurations: a matrix that
//! loses rank at all of them (a roller whose normal a joint already holds, a support on the
//! pivot it should brace) is a compile-time error naming the unknowns that cannot be found
//! or the closure equations that are redundant. One singular at special configurations only
//! (a toggle, a dead centre) compiles, and `ForceAnalysis::checked` refuses those at run
//! time.
//!
//! ```rust
//! use dynamics_runtime::{mechanism, ForceAnalysis};
//!
//! mechanism! {
//!     /// A 1 m beam on a pin at A and a roller at B, its weight neglected.
//!     pub struct Beam;
//!     gravity: none;
//!     body beam { mass: 4.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }
//!     joint A: revolute(ground -> beam) { axis: z }
//!     constraint B: roller(ground at [1.0, 0.0, 0.0], beam at [1.0, 0.0, 0.0]) { normal: y };
//!     load P1: force on beam at [0.2, 0.0, 0.0];
//!     load P2: force on beam at [0.8, 0.0, 0.0];
//! }
//!
//! assert_eq!(Beam::FORCE_UNKNOWNS, ["A.x", "A.y", "B.normal"]);
//! let loads = [0.0, -100.0, 0.0, 0.0, -200.0, 0.0];
//! let analysis = ForceAnalysis::from(Beam::force_analysis(&[0.0_f64], &[0.0], &[0.0], &loads));
//! let [a_x, a_y, b_y] = analysis.checked(1e-9).expect("a determinate structure");
//! assert!(a_x.abs() < 1e-12 && (a_y - 120.0).abs() < 1e-12 && (b_y - 180.0).abs() < 1e-12);
//! assert_eq!(Beam::constraint_residual(&[0.0]), [0.0]);
//! ```
