//! The functions a mechanism can generate: [`CATALOG`] is the one list, in the order they
//! are emitted. Each entry names the function, says when the model asks for it, which input
//! arrays it reads, and how its graph is expanded from the textbook's recursions
//! ([`crate::expand`]), with the base-parameter pass ([`crate::passes::base_parameters`])
//! for the functions of the Lagrangian alone.
//!
//! | function | computes | from |
//! | --- | --- | --- |
//! | `inverse_dynamics(q, v, a)` | τ = M q̈ + C q̇ + g + b q̇ − Q | [`rnea`] |
//! | `gravity(q)` | g(q) | [`rnea`] with q̇ = q̈ = 0 |
//! | `bias(q, v)` | C q̇ + g + b q̇ | [`rnea`] with q̈ = 0 |
//! | `mass_matrix(q)` | M(q) (armature on the diagonal) | [`crba`] |
//! | `coriolis_matrix(q, v)` | C(q, q̇) with Ṁ − 2C skew-symmetric | [`coriolis`] |
//! | `forward_dynamics(q, v, tau)` | q̈ = M⁻¹(τ + Q − C q̇ − g − b q̇) | [`aba`] or [`crba`] + [`ldlt`], whichever costs fewer operations |
//! | `kinetic_energy(q, v)`, `potential_energy(q)` | T, V | [`energy`] |
//! | `joint_reactions(q, v, a)` | [F; M_P] each joint transmits to its body | [`rnea`] |
//! | `center_of_mass(q)`, `center_of_mass_jacobian(q)` | c, J_c in the world frame (asked for by name) | [`kinematics`] |
//! | `centroidal_momentum_matrix(q)` | A_G: momentum and angular momentum about the centre of mass (asked for by name) | [`kinematics`] |
//! | `joint_velocities(q, v)`, `joint_acceleration_biases(q, v)` | each body's [v_P; ω] and J̇ q̇, world axes at its origin (asked for by name) | [`kinematics`] + [`rnea`]'s forward sweep |
//! | `joint_placements(q)`, `joint_jacobians(q)` | each body's (R, p) in the world and its 6 × nv Jacobian, world-aligned at its origin (asked for by name) | [`kinematics`] |
//! | `forward_kinematics(q, v, a)` | each body's (R, p), [v_P; ω] and classical [a_P; α] in world axes (asked for by name) | [`kinematics`] |
//! | `joint_jacobians_world(q)`, `joint_jacobians_world_time_variation(q, v)` | all joint Jacobians in one 6 × nv matrix, WORLD convention (Pinocchio's `data.J`), and its rate J̇ (asked for by name) | [`kinematics`] |
//! | `frame_placements(q)`, `frame_jacobians(q)`, `frame_jacobians_local(q)` | each operational frame's (R, p) in the world and its 6 × nv Jacobian, world-aligned at its origin or in its own axes (asked for by name) | [`frames`] |
//! | `frame_velocities(q, v)`, `frame_acceleration_biases(q, v)` | each operational frame's [v; ω] and J̇ q̇, world axes at its origin (asked for by name) | [`frames`] + [`rnea`]'s forward sweep |
//! | `centroidal_bias(q, v)` | Ȧ_G q̇ (asked for by name) | [`kinematics`] + [`rnea`]'s forward sweep |
//! | `inverse_dynamics_derivatives(q, v, a)` | (∂τ/∂q, ∂τ/∂q̇), q in the tangent space (asked for by name) | [`rnea`] + [`derivatives`]; where that is cheaper, ∂τ/∂q̇ = 2 C + diag(b) by [`coriolis`] in the joint coordinates' columns and a free joint's columns of ∂τ/∂q̇ and ∂τ/∂q from M and C ([`free_joint_derivatives`]), and with it ∂τ/∂q by the analytical recursion ([`rnea_derivatives`]) |
//! | `forward_dynamics_derivatives(q, v, tau)` | (∂q̈/∂q, ∂q̈/∂q̇) (asked for by name) | the cheapest of: [`derivatives`] of `forward_dynamics`' expansion, or −M⁻¹ ∂τ/∂x by [`rnea`] + [`derivatives`] + [`ldlt`] with q̈ by `forward_dynamics`' method or by the solves' own factorization, solved column by column in straight-line code or all columns at once by a loop (`dynamics_runtime::tree_ldlt`, SIMD across the columns) |
//! | `mass_matrix_inverse(q)` | M(q)⁻¹ (asked for by name) | [`crba`] + [`ldlt`], in straight-line code or, where that is cheaper, up to D⁻¹ L⁻ᵀ and then the last sweep L X = D⁻¹ L⁻ᵀ as a loop (`dynamics_runtime::tree_ldlt`, SIMD across the columns) |
//! | `momentum_derivatives(q, v)` | (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇) of p = M(q) q̇ and ṗ = τ + Ṁ q̇ − (C q̇ + g + b q̇ − Q) (asked for by name) | [`crba`] + [`rnea`] + [`derivatives`] (Ṁ q̇ along q̇, then forward mode) |
//! | `force_analysis(q, v, a)` | every reaction component and driving effort, with the pivots of R | [`statics`] + [`qr`] |
//! | `constraint_residual(q)`, `constraint_jacobian(q)`, `constraint_bias(q, v)` | φ, Φ_q, γ of the loop closures | [`statics`] |
//!
//! Symbolic parameters add a `p` argument, declared loads a `loads` argument (Q).
//!
//! Inverse dynamics, gravity, bias, the mass matrix, the Coriolis matrix (Christoffel's,
//! determined by M(q)) and forward dynamics depend on the inertias only through the
//! Lagrangian, and are expanded over base inertial parameters; the energies, joint reactions
//! and force analysis use the inertias as declared.
//!
//! To add a function: write its expansion (a module of [`crate::expand`]), then one
//! [`Entry`] here.

use crate::expand::derivatives::{self, With};
use crate::expand::frames::{self, JacobianAxes};
use crate::expand::geometry::{BodyInertia, JointTransform};
use crate::expand::rnea::{self, SweepInputs};
use crate::expand::{
    aba, coriolis, crba, energy, free_joint_derivatives, fresh_graph, inputs, kinematics, ldlt, qr,
    rnea_derivatives, statics,
};
use crate::ir::{Arg, Function, FunctionSpec, Output, Sweeps, TreeSolve};
use crate::model::{JointKind, LoadFrame, Model};
use crate::passes::base_parameters;
use crate::sym::{Array, Graph, Mat3, Node, Vec3};

/// One function of the catalog.
pub(crate) struct Entry {
    /// Its name in the generated code.
    pub name: &'static str,
    /// Whether the model asks for it.
    pub wanted: fn(&Model) -> bool,
    /// The input arrays it reads besides the parameters `p` (which every function takes
    /// when the model declares any).
    pub arrays: &'static [Array],
    /// Whether it takes the `loads` input (when the model declares loads).
    pub loads: bool,
    /// Its graph, output and doc text.
    pub expand: fn(&Model) -> Expanded,
}

/// What an expansion gives: the graph, the output's nodes and the doc text.
pub(crate) struct Expanded {
    /// The expression DAG.
    pub graph: Graph,
    /// The returned nodes.
    pub output: Output,
    /// What the function computes, for its doc comment.
    pub doc: String,
}

/// Every function the language generates, in the order they are emitted.
pub(crate) const CATALOG: &[Entry] = &[
    Entry {
        name: "inverse_dynamics",
        wanted: |m| m.outputs.inverse_dynamics && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        expand: inverse_dynamics,
    },
    Entry {
        name: "gravity",
        wanted: |m| m.outputs.gravity && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: gravity,
    },
    Entry {
        name: "bias",
        wanted: |m| m.outputs.bias && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: bias,
    },
    Entry {
        name: "mass_matrix",
        wanted: |m| m.outputs.mass_matrix && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: mass_matrix,
    },
    Entry {
        name: "coriolis_matrix",
        wanted: |m| m.outputs.coriolis && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: coriolis_matrix,
    },
    Entry {
        name: "forward_dynamics",
        wanted: |m| m.outputs.forward_dynamics && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        expand: forward_dynamics,
    },
    Entry {
        name: "forward_dynamics_aba",
        wanted: |m| m.outputs.forward_dynamics_aba && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        expand: |m| forward_dynamics_named(m, ForwardMethod::ArticulatedBody),
    },
    Entry {
        name: "forward_dynamics_ldlt",
        wanted: |m| m.outputs.forward_dynamics_ldlt && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        expand: |m| forward_dynamics_named(m, ForwardMethod::MassMatrixLdlt),
    },
    Entry {
        name: "kinetic_energy",
        wanted: |m| m.outputs.energy,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: kinetic_energy,
    },
    Entry {
        name: "potential_energy",
        wanted: |m| m.outputs.energy,
        arrays: &[Array::Q],
        loads: false,
        expand: potential_energy,
    },
    Entry {
        name: "joint_reactions",
        wanted: |m| m.outputs.reactions && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        expand: joint_reactions,
    },
    Entry {
        name: "center_of_mass",
        wanted: |m| m.outputs.center_of_mass,
        arrays: &[Array::Q],
        loads: false,
        expand: center_of_mass,
    },
    Entry {
        name: "center_of_mass_jacobian",
        wanted: |m| m.outputs.center_of_mass_jacobian && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: center_of_mass_jacobian,
    },
    Entry {
        name: "joint_placements",
        wanted: |m| m.outputs.joint_placements && !m.bodies.is_empty(),
        arrays: &[Array::Q],
        loads: false,
        expand: joint_placements,
    },
    Entry {
        name: "joint_jacobians",
        wanted: |m| m.outputs.joint_jacobians && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: joint_jacobians,
    },
    Entry {
        name: "joint_jacobians_world",
        wanted: |m| m.outputs.joint_jacobians_world && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: joint_jacobians_world,
    },
    Entry {
        name: "joint_jacobians_world_time_variation",
        wanted: |m| m.outputs.joint_jacobians_world_time_variation && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: joint_jacobians_world_time_variation,
    },
    Entry {
        name: "forward_kinematics",
        wanted: |m| m.outputs.forward_kinematics && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: false,
        expand: forward_kinematics,
    },
    Entry {
        name: "joint_velocities",
        wanted: |m| m.outputs.joint_velocities && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: joint_velocities,
    },
    Entry {
        name: "joint_acceleration_biases",
        wanted: |m| m.outputs.joint_acceleration_biases && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: joint_acceleration_biases,
    },
    Entry {
        name: "centroidal_momentum_matrix",
        wanted: |m| m.outputs.centroidal_momentum_matrix && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: centroidal_momentum_matrix,
    },
    Entry {
        name: "centroidal_bias",
        wanted: |m| m.outputs.centroidal_bias && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: centroidal_bias,
    },
    Entry {
        name: "frame_placements",
        wanted: |m| m.outputs.frame_placements && !m.frames.is_empty(),
        arrays: &[Array::Q],
        loads: false,
        expand: frame_placements,
    },
    Entry {
        name: "frame_jacobians",
        wanted: |m| m.outputs.frame_jacobians && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: |m| frame_jacobians(m, JacobianAxes::WorldAligned),
    },
    Entry {
        name: "frame_jacobians_local",
        wanted: |m| m.outputs.frame_jacobians_local && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: |m| frame_jacobians(m, JacobianAxes::Local),
    },
    Entry {
        name: "frame_velocities",
        wanted: |m| m.outputs.frame_velocities && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: frame_velocities,
    },
    Entry {
        name: "frame_acceleration_biases",
        wanted: |m| m.outputs.frame_acceleration_biases && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: frame_acceleration_biases,
    },
    Entry {
        name: "inverse_dynamics_derivatives",
        wanted: |m| m.outputs.inverse_dynamics_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        expand: inverse_dynamics_derivatives,
    },
    Entry {
        name: "forward_dynamics_derivatives",
        wanted: |m| m.outputs.forward_dynamics_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        expand: forward_dynamics_derivatives,
    },
    Entry {
        name: "mass_matrix_inverse",
        wanted: |m| m.outputs.mass_matrix_inverse && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        expand: mass_matrix_inverse,
    },
    Entry {
        name: "momentum_derivatives",
        wanted: |m| m.outputs.momentum_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: true,
        expand: momentum_derivatives,
    },
    Entry {
        name: "force_analysis",
        wanted: |m| m.outputs.force_analysis && m.statics.is_some(),
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        expand: force_analysis,
    },
    Entry {
        name: "constraint_residual",
        wanted: wants_constraints,
        arrays: &[Array::Q],
        loads: false,
        expand: constraint_residual,
    },
    Entry {
        name: "constraint_jacobian",
        wanted: wants_constraints,
        arrays: &[Array::Q],
        loads: false,
        expand: constraint_jacobian,
    },
    Entry {
        name: "constraint_bias",
        wanted: wants_constraints,
        arrays: &[Array::Q, Array::V],
        loads: false,
        expand: constraint_bias,
    },
];

impl Entry {
    /// The arguments, in the fixed order q, v, a, tau, p, loads: the entry's arrays, `p`
    /// when the model declares parameters, `loads` when the entry takes them and the model
    /// declares loads.
    pub fn args(&self, model: &Model) -> Vec<Arg> {
        let order = [
            Array::Q,
            Array::V,
            Array::A,
            Array::Tau,
            Array::P,
            Array::Loads,
        ];
        order
            .iter()
            .filter(|&&a| match a {
                Array::P => true,
                Array::Loads => self.loads,
                _ => self.arrays.contains(&a),
            })
            .filter_map(|&array| {
                let len = match array {
                    Array::Q => model.nq,
                    Array::V | Array::A | Array::Tau => model.nv,
                    Array::P => model.parameters.len(),
                    Array::Loads => model.load_inputs,
                };
                (len > 0 || matches!(array, Array::Q | Array::V | Array::A | Array::Tau))
                    .then_some(Arg { array, len })
            })
            .collect()
    }

    /// The function, expanded: its graph and its spec over `scalar_trait`.
    pub fn function(&self, model: &Model, scalar_trait: &syn::Path) -> Function {
        let Expanded { graph, output, doc } = (self.expand)(model);
        let mut spec = FunctionSpec::new(self.name, scalar_trait.clone(), self.args(model), output);
        spec.doc = doc;
        Function { graph, spec }
    }
}

/// The loop-closure functions are asked for and the model has closures.
fn wants_constraints(model: &Model) -> bool {
    model.outputs.constraints
        && model
            .statics
            .as_ref()
            .is_some_and(|s| s.closure_count() > 0)
}

/// Whether the model declares loads.
fn has_loads(model: &Model) -> bool {
    model.load_inputs > 0
}

/// τ of a Newton–Euler sweep over base inertial parameters, chosen for τ.
fn joint_forces(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    inputs: &SweepInputs,
) -> Vec<Node> {
    let sweep = rnea::sweep(g, model, transforms, inertias, inputs);
    base_parameters::regroup_sweep(g, model, transforms, inputs, inertias, &sweep)
        .0
        .tau
}

/// τ = ID(q, q̇, a) on the inputs `v` and `a` (with gravity and the loads), and the
/// velocity inputs it was expanded on.
fn inverse_dynamics_on(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> (Vec<Node>, Vec<Node>) {
    let (v, a) = (inputs(g, Array::V, model.nv), inputs(g, Array::A, model.nv));
    let sweep_inputs = SweepInputs {
        velocity: &v,
        acceleration: &a,
        gravity: true,
        loads: has_loads(model),
    };
    let tau = joint_forces(g, model, transforms, inertias, &sweep_inputs);
    (tau, v)
}

fn inverse_dynamics(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let (tau, _) = inverse_dynamics_on(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Vector(tau),
        doc: "Inverse dynamics: τ = M(q) q̈ + C(q, q̇) q̇ + g(q) + b q̇ − Q, the joint forces that \
              produce the accelerations `a` at state (`q`, `v`) (recursive Newton–Euler, \
              shifted-inertia form)."
            .to_owned(),
    }
}

/// The two Jacobians of `outputs` with respect to q (tangent space) and q̇, as an output.
fn state_jacobians(g: &Graph, model: &Model, outputs: &[Node]) -> Output {
    Output::Tuple(
        derivative_inputs(model)
            .into_iter()
            .map(|with| Output::Matrix(derivatives::jacobian(g, model, outputs, with)))
            .collect(),
    )
}

/// How the derivative outputs expand ∂τ/∂q̇ (and a free joint's columns of ∂τ/∂q).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum VelocityColumns {
    /// Forward-mode differentiation of Newton–Euler, like the other columns.
    ForwardMode,
    /// 2 C(q, q̇) + diag(b) ([`velocity_jacobian_by_coriolis`]) in the columns of joint
    /// coordinates, and a free joint's columns of ∂τ/∂q̇ and ∂τ/∂q from M and C
    /// ([`free_joint_derivatives`]).
    Coriolis,
    /// As `Coriolis`, and ∂τ/∂q's other columns by the analytical recursion over C's
    /// composite terms ([`rnea_derivatives`]) where it applies (forward mode otherwise).
    Analytic,
}

/// The ways ∂τ/∂q̇ (and with it ∂τ/∂q) can be expanded for `model`: forward mode, from the
/// Coriolis and mass matrices, and that with the analytical recursion for ∂τ/∂q where it
/// applies (no loads).
fn velocity_columns(model: &Model) -> Vec<VelocityColumns> {
    let mut ways = vec![VelocityColumns::ForwardMode, VelocityColumns::Coriolis];
    if rnea_derivatives::applies(model) {
        ways.push(VelocityColumns::Analytic);
    }
    ways
}

/// ∂τ/∂q̇ = 2 C(q, q̇) + diag(b) in the columns of joint coordinates, C the
/// Christoffel-consistent Coriolis matrix (over its cheapest base parameters, as the
/// `coriolis_matrix` output). With generalized coordinates, C_kj = Σ_i Γ_kij q̇_i for the
/// Christoffel symbols Γ_kij, symmetric in i and j, so C(q, q̇) q̇ = Σ_ij Γ_kij q̇_i q̇_j and
/// ∂(C q̇)_k/∂q̇_j = 2 Σ_i Γ_kij q̇_i = 2 C_kj; M(q) q̈, g(q) and the applied loads Q(q) do
/// not depend on q̇, and damping adds b. A free joint's velocities are the body's twist, not
/// derivatives of coordinates: Γ_kij is not symmetric when i and j are both twist
/// components (the twists' commutator), and its six columns add M's columns times that
/// commutator ([`free_joint_derivatives::velocity_column`]).
fn velocity_jacobian_by_coriolis(
    g: &Graph,
    model: &Model,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    v: &[Node],
    basis: &CoriolisBasis,
) -> Vec<Vec<Node>> {
    let c_inertias = basis.get_or_init(|| coriolis_inertias(g, model, (transforms, inertias), v));
    let c = coriolis::coriolis_matrix(g, model, transforms, c_inertias, v);
    let two = g.constant(2.0);
    let mut jacobian: Vec<Vec<Node>> = c
        .iter()
        .map(|row| row.iter().map(|&x| g.mul(two, x)).collect())
        .collect();
    for body in &model.bodies {
        let k = body.joint.idx_v;
        if body.joint.kind == JointKind::Free {
            let m = regrouped_mass_matrix(g, model, transforms, inertias);
            for twist in 0..6 {
                let column =
                    free_joint_derivatives::velocity_column(g, &body.joint, (&m, &c), v, twist);
                for (row, entry) in jacobian.iter_mut().zip(column) {
                    row[k + twist] = entry;
                }
            }
        } else {
            // Damping b q̇ on the joint's one coordinate, as the backward sweep adds it.
            let damping = crate::expand::geometry::value(g, &body.joint.damping);
            jacobian[k][k] = g.add(jacobian[k][k], damping);
        }
    }
    jacobian
}

/// [`coriolis_inertias`], worked out once per expansion of ∂τ/∂x (the search for them costs
/// more than the expansion that uses them).
type CoriolisBasis = std::cell::OnceCell<Vec<BodyInertia>>;

/// The base inertial parameters over which C(q, q̇) costs least (as the `coriolis_matrix`
/// output has them), on which ∂τ/∂q̇ = 2 C + diag(b) and the analytical ∂τ/∂q are built.
fn coriolis_inertias(
    g: &Graph,
    model: &Model,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    v: &[Node],
) -> Vec<BodyInertia> {
    let build = |i: &[BodyInertia]| coriolis::coriolis_matrix(g, model, transforms, i, v);
    base_parameters::regroup(g, model, transforms, inertias, |i| build(i).concat())
}

/// ∂τ/∂q by forward mode, but for a free joint on the ground in a mechanism without loads
/// given in world axes, whose columns come from M
/// ([`free_joint_derivatives::configuration_column`]).
fn configuration_jacobian_with_free_columns(
    g: &Graph,
    model: &Model,
    expansion: (&[JointTransform], &[BodyInertia]),
    tau: &[Node],
) -> Vec<Vec<Node>> {
    let mut jacobian = derivatives::jacobian(g, model, tau, With::Configuration);
    if model
        .loads
        .iter()
        .any(|load| load.frame == LoadFrame::World)
    {
        return jacobian;
    }
    fill_free_configuration_columns(g, model, expansion, &mut jacobian);
    jacobian
}

/// ∂τ/∂q by the analytical recursion ([`rnea_derivatives`]) over C's base parameters, a
/// free joint's columns from M; by [`configuration_jacobian_with_free_columns`] where the
/// recursion does not apply (loads).
fn configuration_jacobian_analytic(
    g: &Graph,
    model: &Model,
    expansion: (&[JointTransform], &[BodyInertia]),
    (tau, v): (&[Node], &[Node]),
    basis: &CoriolisBasis,
) -> Vec<Vec<Node>> {
    if !rnea_derivatives::applies(model) {
        return configuration_jacobian_with_free_columns(g, model, expansion, tau);
    }
    let transforms = expansion.0;
    let inertias = basis.get_or_init(|| coriolis_inertias(g, model, expansion, v));
    let terms = coriolis::composite_terms(g, model, transforms, inertias, v);
    let a = inputs(g, Array::A, model.nv);
    let mut jacobian =
        rnea_derivatives::configuration_jacobian(g, model, (transforms, inertias), &terms, (v, &a));
    fill_free_configuration_columns(g, model, expansion, &mut jacobian);
    jacobian
}

/// Writes the columns of ∂τ/∂q of a free joint on the ground from M
/// ([`free_joint_derivatives::configuration_column`]; no loads in world axes).
fn fill_free_configuration_columns(
    g: &Graph,
    model: &Model,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    jacobian: &mut [Vec<Node>],
) {
    for (body, transform) in model.bodies.iter().zip(transforms) {
        if body.joint.kind != JointKind::Free || body.parent.is_some() {
            continue;
        }
        let m = regrouped_mass_matrix(g, model, transforms, inertias);
        for k in 0..6 {
            let column = free_joint_derivatives::configuration_column(
                g,
                model,
                (&body.joint, transform),
                &m,
                k,
            );
            for (row, entry) in jacobian.iter_mut().zip(column) {
                row[body.joint.idx_v + k] = entry;
            }
        }
    }
}

/// ∂τ/∂x for the derivative outputs: forward mode, or by `velocity` (`v`: the velocity
/// inputs `tau` was expanded on; `basis`: shared by the calls for the same expansion).
fn inverse_dynamics_jacobian(
    g: &Graph,
    model: &Model,
    expansion: (&[JointTransform], &[BodyInertia]),
    (tau, v): (&[Node], &[Node]),
    (with, velocity): (With, VelocityColumns),
    basis: &CoriolisBasis,
) -> Vec<Vec<Node>> {
    match (with, velocity) {
        (With::Array(Array::V), VelocityColumns::Coriolis | VelocityColumns::Analytic) => {
            velocity_jacobian_by_coriolis(g, model, expansion, v, basis)
        }
        (With::Configuration, VelocityColumns::Coriolis) => {
            configuration_jacobian_with_free_columns(g, model, expansion, tau)
        }
        (With::Configuration, VelocityColumns::Analytic) => {
            configuration_jacobian_analytic(g, model, expansion, (tau, v), basis)
        }
        _ => derivatives::jacobian(g, model, tau, with),
    }
}

/// What the derivative outputs differentiate with respect to, in order: q (tangent space),
/// q̇, and the loads' inputs when the mechanism declares loads.
fn derivative_inputs(model: &Model) -> Vec<With> {
    let mut with = vec![With::Configuration, With::Array(Array::V)];
    if has_loads(model) {
        with.push(With::Array(Array::Loads));
    }
    with
}

/// The doc sentence on the derivatives with respect to the loads, for a mechanism with
/// loads.
fn load_derivatives_doc(model: &Model) -> &'static str {
    if has_loads(model) {
        " The third matrix, nv × NUM_LOAD_INPUTS, is the derivative with respect to the \
         `loads` inputs (constant in them: the loads enter linearly)."
    } else {
        ""
    }
}

/// The doc sentence on the configuration derivative's convention.
const TANGENT_CONVENTION: &str = "Column j of a q-derivative is the derivative along q ⊕ t e_j \
    (Pinocchio's convention: for a free base, the increment [δv; δω] is in the base's own \
    frame, so its columns follow v, not the quaternion's four numbers).";

/// ∂τ/∂x (x = q, q̇ and the loads, [`derivative_inputs`]) expanded each way
/// [`velocity_columns`] offers, in a fresh graph each: the cheapest, with the way it took.
fn cheapest_inverse_dynamics_jacobians(model: &Model) -> (Graph, Output, VelocityColumns) {
    let expand = |velocity: VelocityColumns| {
        let (g, t, i) = fresh_graph(model);
        let (tau, v) = inverse_dynamics_on(&g, model, &t, &i);
        let basis = CoriolisBasis::new();
        let output = Output::Tuple(
            derivative_inputs(model)
                .into_iter()
                .map(|with| {
                    Output::Matrix(inverse_dynamics_jacobian(
                        &g,
                        model,
                        (&t, &i),
                        (&tau, &v),
                        (with, velocity),
                        &basis,
                    ))
                })
                .collect(),
        );
        (g, output, velocity)
    };
    // The analytical recursion must save a twentieth of the operations to be kept: on go2
    // (18 dof, free base) it saved 2 % of them and its code ran 6 % slower, paired in one
    // process against the other way's.
    let cost = |(g, output, way): &(Graph, Output, VelocityColumns)| {
        let cost = output_cost(g, output);
        match way {
            VelocityColumns::Analytic => cost * 20 / 19,
            _ => cost,
        }
    };
    let mut candidates: Vec<_> = velocity_columns(model).into_iter().map(expand).collect();
    let best = cheapest(&candidates, cost);
    candidates.swap_remove(best)
}

fn inverse_dynamics_derivatives(model: &Model) -> Expanded {
    // ∂τ/∂q̇ by forward mode or as 2 C + diag(b), ∂τ/∂q by forward mode or the analytical
    // recursion: whichever costs fewer operations, the recursion by a twentieth.
    let (graph, output, velocity) = cheapest_inverse_dynamics_jacobians(model);
    let how = match velocity {
        VelocityColumns::ForwardMode => {
            "forward-mode differentiation of the Newton–Euler \
                                         expansion"
        }
        VelocityColumns::Coriolis => {
            "forward-mode differentiation of the Newton–Euler \
                                      expansion for ∂τ/∂q, and ∂τ/∂q̇ = 2 C(q, q̇) + diag(b) \
                                      (C the Christoffel-consistent Coriolis matrix; a free \
                                      joint's columns from M and C)"
        }
        VelocityColumns::Analytic => {
            "the analytical Newton–Euler derivative recursion for ∂τ/∂q over the Coriolis \
             matrix's composite terms, and ∂τ/∂q̇ = 2 C(q, q̇) + diag(b) (C the \
             Christoffel-consistent Coriolis matrix; a free joint's columns from M and C)"
        }
    };
    Expanded {
        graph,
        output,
        doc: format!(
            "Derivatives of inverse dynamics: (∂τ/∂q, ∂τ/∂q̇), each nv × nv (row i: τ_i), at \
             (`q`, `v`, `a`); ∂τ/∂q̈ = M(q). By {how}, the cheaper way for this mechanism \
             (Pinocchio's `computeRNEADerivatives`). {TANGENT_CONVENTION}{}",
            load_derivatives_doc(model)
        ),
    }
}

/// The index of the candidate of least `cost` (each costed once), the first of equal costs.
fn cheapest<T>(candidates: &[T], cost: impl Fn(&T) -> usize) -> usize {
    (0..candidates.len())
        .min_by_key(|&k| cost(&candidates[k]))
        .unwrap_or(0)
}

fn forward_dynamics_derivatives(model: &Model) -> Expanded {
    // Differentiating the forward-dynamics expansion itself, or by the chain rule through
    // inverse dynamics (ID(q, q̇, FD(q, q̇, τ)) = τ, so ∂q̈/∂x = −M⁻¹ ∂ID/∂x at a = q̈, as
    // Pinocchio's computeABADerivatives): whichever costs fewer operations.
    let (g, qdd, method) = cheapest_forward_dynamics(model);
    let direct = {
        let output = state_jacobians(&g, model, &qdd);
        (
            g,
            output,
            "forward-mode differentiation of the forward-dynamics expansion".to_owned(),
        )
    };
    let chain = |method: ForwardMethod, velocity: VelocityColumns| {
        let (g, t, i) = fresh_graph(model);
        let mut outputs =
            forward_dynamics_derivatives_by_chain_rule(&g, &t, &i, model, method, velocity);
        let best = cheapest(&outputs, |(output, _)| output_cost(&g, output));
        let (output, solves) = outputs.swap_remove(best);
        let tau_by = match velocity {
            VelocityColumns::ForwardMode => "forward-mode derivatives of Newton–Euler",
            VelocityColumns::Coriolis => {
                "forward-mode derivatives of Newton–Euler for ∂τ/∂q, ∂τ/∂q̇ = 2 C(q, q̇) + diag(b), \
                 a free joint's columns from M and C"
            }
            VelocityColumns::Analytic => {
                "the analytical derivative recursion of Newton–Euler for ∂τ/∂q, \
                 ∂τ/∂q̇ = 2 C(q, q̇) + diag(b), a free joint's columns from M and C"
            }
        };
        let qdd_by = match method {
            ForwardMethod::ArticulatedBody => "the articulated-body algorithm",
            ForwardMethod::MassMatrixLdlt => "the same factorization",
        };
        let solves_by = match solves {
            Solves::Unrolled => "tree-sparse LDLᵀ solves",
            Solves::Loop => "a tree-sparse LDLᵀ solve of all columns at once, run as a loop",
        };
        let how = format!(
            "the chain rule through inverse dynamics, ∂q̈/∂x = −M⁻¹ ∂τ/∂x at q̈ ({tau_by}, then \
             {solves_by}; q̈ by {qdd_by})"
        );
        (g, output, how)
    };
    // The solves factor M anyway, so q̈ by that factorization can be the cheaper chain even
    // where the articulated-body algorithm is cheaper alone (the 35-dof g1 humanoid: 6 %
    // fewer operations): both are tried, each with the cheaper of its two ways to solve.
    // The first of equal costs is kept.
    let mut methods = vec![method];
    if method == ForwardMethod::ArticulatedBody {
        methods.push(ForwardMethod::MassMatrixLdlt);
    }
    // The chain takes ∂τ/∂x the way that is cheapest alone (expanding every way with
    // every method would double the compile time for a few operations at most).
    let (_, _, velocity) = cheapest_inverse_dynamics_jacobians(model);
    let mut candidates = vec![direct];
    for &method in &methods {
        candidates.push(chain(method, velocity));
    }
    let best = cheapest(&candidates, |(g, output, _)| output_cost(g, output));
    let (graph, output, how) = candidates.swap_remove(best);
    Expanded {
        graph,
        output,
        doc: format!(
            "Derivatives of forward dynamics: (∂q̈/∂q, ∂q̈/∂q̇), each nv × nv (row i: q̈_i), \
             at (`q`, `v`, `tau`); ∂q̈/∂τ = M(q)⁻¹ (`mass_matrix_inverse`). By {how}, the \
             cheapest of the ways tried for this mechanism (Pinocchio's \
             `computeABADerivatives`). \
             {TANGENT_CONVENTION}{}",
            load_derivatives_doc(model)
        ),
    }
}

/// (∂q̈/∂q, ∂q̈/∂q̇) = −M⁻¹ (∂τ/∂q, ∂τ/∂q̇), the derivatives of τ = ID(q, q̇, a) taken at a
/// free `a` and evaluated at a = q̈ = FD(q, q̇, τ), in one graph both ways: solved column
/// by column, and as the right-hand sides of one loop.
fn forward_dynamics_derivatives_by_chain_rule(
    g: &Graph,
    t: &[JointTransform],
    i: &[BodyInertia],
    model: &Model,
    method: ForwardMethod,
    velocity: VelocityColumns,
) -> Vec<(Output, Solves)> {
    let nv = model.nv;
    let qdd = forward_dynamics_on(g, t, i, model, method);
    let (tau, v) = inverse_dynamics_on(g, model, t, i);
    let m = regrouped_mass_matrix(g, model, t, i);
    // ∂τ/∂x at a = q̈, by rows.
    let basis = CoriolisBasis::new();
    let jacobian = |with: With| {
        let rows =
            inverse_dynamics_jacobian(g, model, (t, i), (&tau, &v), (with, velocity), &basis);
        let width = rows.first().map_or(0, Vec::len);
        let flat: Vec<Node> = rows.into_iter().flatten().collect();
        let at_qdd = g.substitute(&flat, |r| {
            (r.array == Array::A).then(|| qdd[r.index as usize])
        });
        (0..nv)
            .map(|r| at_qdd[r * width..(r + 1) * width].to_vec())
            .collect::<Vec<Vec<Node>>>()
    };
    // Unrolled first, so that its nodes are numbered as they were before the loop existed;
    // the loop's then add only its negations and the factor's reordering.
    let solved = |b: &Vec<Vec<Node>>| {
        let width = b.first().map_or(0, Vec::len);
        let columns: Vec<Vec<Node>> = (0..width)
            .map(|c| {
                let column = b.iter().map(|row| g.neg(row[c])).collect();
                ldlt::solve(g, model, m.clone(), column)
            })
            .collect();
        Output::Matrix(
            (0..nv)
                .map(|r| columns.iter().map(|column| column[r]).collect())
                .collect(),
        )
    };
    // Each Jacobian solved as soon as it is expanded (the order the nodes always had).
    let (mut jacobians, mut unrolled) = (Vec::new(), Vec::new());
    for with in derivative_inputs(model) {
        let b = jacobian(with);
        unrolled.push(solved(&b));
        jacobians.push(b);
    }
    let unrolled = Output::Tuple(unrolled);
    let (parents, factor, inverse_pivot) = ldlt::factor_rows(g, model, m);
    let negated = |b: Vec<Vec<Node>>| {
        b.into_iter()
            .map(|row| row.into_iter().map(|x| g.neg(x)).collect())
            .collect()
    };
    let by_loop = Output::Solved(TreeSolve {
        parents,
        factor,
        inverse_pivot,
        rhs: jacobians.into_iter().map(negated).collect(),
        sweeps: Sweeps::All,
    });
    vec![(unrolled, Solves::Unrolled), (by_loop, Solves::Loop)]
}

/// How the chain rule of the forward-dynamics derivatives solves M X = −∂τ/∂x.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Solves {
    /// One straight-line tree-sparse solve per column, skipping the zeros of each.
    Unrolled,
    /// A loop over all columns at once in the generated code (`dynamics_runtime::tree_ldlt`),
    /// SIMD across the columns.
    Loop,
}

/// M⁻¹ from the tree-sparse LDLᵀ factorization, by the cheaper (at [`output_cost`]) of
/// straight-line code (one triangle, mirrored) and straight-line code up to D⁻¹ L⁻ᵀ, sparse,
/// then the last sweep L X = D⁻¹ L⁻ᵀ as a loop over the columns. On an 18-dof free-base
/// tree the sums over common ancestors are about half the straight-line operations, and
/// the loop does them four columns per instruction.
fn mass_matrix_inverse(model: &Model) -> Expanded {
    let mut candidates = mass_matrix_inverse_candidates(model);
    let best = cheapest(&candidates, |(g, output, _)| output_cost(g, output));
    let (graph, output, how) = candidates.swap_remove(best);
    Expanded {
        graph,
        output,
        doc: format!(
            "The inverse of the mass matrix M(q)⁻¹ (armature included), nv × nv, by the \
             tree-sparse LDLᵀ factorization of M (Pinocchio's `computeMinverse`).{how} A \
             singular M gives non-finite values, never a panic."
        ),
    }
}

/// M⁻¹ both ways, straight-line first: (graph, output, what the doc adds).
fn mass_matrix_inverse_candidates(model: &Model) -> Vec<(Graph, Output, &'static str)> {
    let straight = {
        let (g, t, i) = fresh_graph(model);
        let rows = ldlt::inverse(&g, model, regrouped_mass_matrix(&g, model, &t, &i));
        (g, Output::Matrix(rows), "")
    };
    let by_loop = {
        let (g, t, i) = fresh_graph(model);
        let half = ldlt::inverse_halfway(&g, model, regrouped_mass_matrix(&g, model, &t, &i));
        let solve = TreeSolve {
            parents: half.parents,
            factor: half.factor,
            inverse_pivot: half.inverse_pivot,
            rhs: vec![half.scaled],
            sweeps: Sweeps::LastOfInverse,
        };
        (
            g,
            Output::Solved(solve),
            " M⁻¹ = L⁻¹ (D⁻¹ L⁻ᵀ): D⁻¹ L⁻ᵀ in straight-line code, where its zeros make it \
             cheap, then L X = D⁻¹ L⁻ᵀ as a loop over the columns, the cheaper way for this \
             mechanism.",
        )
    };
    vec![straight, by_loop]
}

fn gravity(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let zero = vec![g.zero(); model.nv];
    let sweep_inputs = SweepInputs {
        velocity: &zero,
        acceleration: &zero,
        gravity: true,
        loads: false,
    };
    let tau = joint_forces(&g, model, &t, &i, &sweep_inputs);
    Expanded {
        graph: g,
        output: Output::Vector(tau),
        doc: "Gravity torques g(q): the joint forces that hold the mechanism still at `q`."
            .to_owned(),
    }
}

fn bias(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let zero = vec![g.zero(); model.nv];
    let sweep_inputs = SweepInputs {
        velocity: &v,
        acceleration: &zero,
        gravity: true,
        loads: false,
    };
    let tau = joint_forces(&g, model, &t, &i, &sweep_inputs);
    Expanded {
        graph: g,
        output: Output::Vector(tau),
        doc: "Bias forces C(q, q̇) q̇ + g(q) + b q̇: inverse dynamics at zero acceleration."
            .to_owned(),
    }
}

/// M(q) over the base inertial parameters that make it cheapest.
fn regrouped_mass_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
) -> Vec<Vec<Node>> {
    let build = |i: &[BodyInertia]| crba::mass_matrix(g, model, transforms, i);
    let regrouped = base_parameters::regroup(g, model, transforms, inertias, |i| build(i).concat());
    build(&regrouped)
}

fn mass_matrix(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let m = regrouped_mass_matrix(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Matrix(m),
        doc: "Mass matrix M(q) (symmetric, armature on the diagonal), by composite rigid bodies."
            .to_owned(),
    }
}

fn coriolis_matrix(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    // C is the Christoffel-consistent factorization, a function of M(q): base parameters
    // serve.
    let build = |i: &[BodyInertia]| coriolis::coriolis_matrix(&g, model, &t, i, &v);
    let c = build(&base_parameters::regroup(&g, model, &t, &i, |i| {
        build(i).concat()
    }));
    Expanded {
        graph: g,
        output: Output::Matrix(c),
        doc: "Coriolis matrix C(q, q̇), the Christoffel-consistent one: C q̇ is the Coriolis and \
              centrifugal force and Ṁ − 2C is skew-symmetric."
            .to_owned(),
    }
}

/// The derivatives of the generalized momentum p = M(q) q̇ and of its rate
/// ṗ = Ṁ q̇ + M q̈ = Ṁ q̇ + τ − (C q̇ + g + b q̇ − Q), the Euler–Lagrange equations
/// d/dt ∂L/∂q̇ = ∂L/∂q + τ + Q − b q̇ solved for the momentum's rate (∂L/∂q = Cᵀ q̇ − g in
/// joint coordinates, since Ṁ = C + Cᵀ). Ṁ q̇ is M(q) v differentiated along q̇ = v
/// ([`derivatives::along_velocity`]), the bracket is the Newton–Euler bias with the loads,
/// and the Jacobians are forward mode over both: second derivatives of M, which no other
/// output holds (a variational integrator's exact Newton Jacobian needs them).
fn momentum_derivatives(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let mass = regrouped_mass_matrix(&g, model, &t, &i);
    let momentum: Vec<Node> = mass
        .iter()
        .map(|row| {
            row.iter()
                .zip(&v)
                .fold(g.zero(), |sum, (&m, &vj)| g.add(sum, g.mul(m, vj)))
        })
        .collect();
    let zero = vec![g.zero(); model.nv];
    let bias = joint_forces(
        &g,
        model,
        &t,
        &i,
        &SweepInputs {
            velocity: &v,
            acceleration: &zero,
            gravity: true,
            loads: has_loads(model),
        },
    );
    // ṗ − τ = Ṁ q̇ − bias(q, q̇).
    let rate: Vec<Node> = derivatives::along_velocity(&g, model, &momentum)
        .into_iter()
        .zip(&bias)
        .map(|(m_dot_v, &b)| g.sub(m_dot_v, b))
        .collect();
    let mut matrices = vec![Output::Matrix(derivatives::jacobian(
        &g,
        model,
        &momentum,
        With::Configuration,
    ))];
    matrices.extend(
        derivative_inputs(model)
            .into_iter()
            .map(|with| Output::Matrix(derivatives::jacobian(&g, model, &rate, with))),
    );
    let loads_doc = if has_loads(model) {
        " The fourth matrix, nv × NUM_LOAD_INPUTS, is ∂ṗ/∂loads."
    } else {
        ""
    };
    Expanded {
        graph: g,
        output: Output::Tuple(matrices),
        doc: format!(
            "Derivatives of the generalized momentum p = M(q) q̇ and of its rate \
             ṗ = Ṁ q̇ + M q̈ = τ + Ṁ q̇ − (C q̇ + g + b q̇ − Q), which in joint coordinates is \
             τ + C(q, q̇)ᵀ q̇ − g(q) + Q − b q̇ (the Euler–Lagrange equations, the momentum \
             observer's model): (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇), each nv × nv (row i: p_i or ṗ_i), at \
             (`q`, `v`); ∂p/∂q̇ = M(q), ∂ṗ/∂τ = 1. Forward-mode differentiation of M(q) v, of \
             its rate along q̇ and of the Newton–Euler bias: second derivatives of M, which \
             the variational midpoint integrator's exact Newton Jacobian needs. \
             {TANGENT_CONVENTION}{loads_doc}"
        ),
    }
}

/// The two forward-dynamics algorithms the generator knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ForwardMethod {
    /// The articulated-body algorithm: linear in the number of joints.
    ArticulatedBody,
    /// M(q) by composite rigid bodies, then its tree-sparse LDLᵀ factorization: fewer
    /// operations for short chains and trees.
    MassMatrixLdlt,
}

/// q̈ = FD(q, q̇, τ) by one method, in a fresh graph, over base inertial parameters.
pub(crate) fn forward_dynamics_by(model: &Model, method: ForwardMethod) -> (Graph, Vec<Node>) {
    let (g, t, i) = fresh_graph(model);
    let qdd = forward_dynamics_on(&g, &t, &i, model, method);
    (g, qdd)
}

/// q̈ = FD(q, q̇, τ) by one method, over base inertial parameters, in `g`.
fn forward_dynamics_on(
    g: &Graph,
    t: &[JointTransform],
    i: &[BodyInertia],
    model: &Model,
    method: ForwardMethod,
) -> Vec<Node> {
    let nv = model.nv;
    let loads = has_loads(model);
    let v = inputs(g, Array::V, nv);
    let tau = inputs(g, Array::Tau, nv);
    match method {
        ForwardMethod::ArticulatedBody => {
            let external = rnea::load_wrenches(g, model, t, loads);
            let build =
                |i: &[BodyInertia]| aba::forward_dynamics(g, model, t, i, &v, &tau, &external);
            build(&base_parameters::regroup(g, model, t, i, build))
        }
        ForwardMethod::MassMatrixLdlt => {
            let zero = vec![g.zero(); nv];
            let sweep_inputs = SweepInputs {
                velocity: &v,
                acceleration: &zero,
                gravity: true,
                loads,
            };
            let bias = joint_forces(g, model, t, i, &sweep_inputs);
            let rhs: Vec<Node> = tau.iter().zip(&bias).map(|(&t, &b)| g.sub(t, b)).collect();
            let m = regrouped_mass_matrix(g, model, t, i);
            ldlt::solve(g, model, m, rhs)
        }
    }
}

/// The weight of a function's operations when two expansions are compared: a division or a
/// square root counts as ten products or sums; an expansion that ran out of room
/// ([`crate::sym::NODE_BUDGET`]) costs the most.
fn weighted_cost(g: &Graph, outputs: &[Node]) -> usize {
    if g.is_exhausted() {
        return usize::MAX;
    }
    let c = g.op_count(outputs);
    c.mul + c.add + 10 * c.div + 10 * c.sqrt
}

/// About how many straight-line operations fill a 32 kB instruction cache: the go2's
/// straight-line M⁻¹ is 38 kB of x86-64 machine code for 3,600 operations, 10.5 bytes each.
const OPERATIONS_IN_INSTRUCTION_CACHE: usize = 3_000;

/// [`weighted_cost`] of what a function returns, with the solve loop of an
/// [`Output::Solved`] at [`TreeSolve::loop_cost`], and each straight-line operation past
/// [`OPERATIONS_IN_INSTRUCTION_CACHE`] counted twice: code that does not fit the
/// instruction cache waits on fetching it (the go2's straight-line M⁻¹, 3,721 weighted
/// operations, took 641 ns where its 7 operations a nanosecond in cache predict 530).
fn output_cost(g: &Graph, output: &Output) -> usize {
    let loop_cost = match output {
        Output::Solved(s) => s.loop_cost(),
        _ => 0,
    };
    let straight = weighted_cost(g, &output.nodes());
    let fetching = straight.saturating_sub(OPERATIONS_IN_INSTRUCTION_CACHE);
    straight.saturating_add(fetching).saturating_add(loop_cost)
}

/// Both forward-dynamics expansions, the one of lower [`weighted_cost`] kept (the
/// articulated-body algorithm on a tie): its graph, q̈ and method.
fn cheapest_forward_dynamics(model: &Model) -> (Graph, Vec<Node>, ForwardMethod) {
    let (aba_graph, aba) = forward_dynamics_by(model, ForwardMethod::ArticulatedBody);
    let (ldlt_graph, ldlt) = forward_dynamics_by(model, ForwardMethod::MassMatrixLdlt);
    if weighted_cost(&aba_graph, &aba) <= weighted_cost(&ldlt_graph, &ldlt) {
        (aba_graph, aba, ForwardMethod::ArticulatedBody)
    } else {
        (ldlt_graph, ldlt, ForwardMethod::MassMatrixLdlt)
    }
}

/// Forward dynamics by whichever method costs fewer operations for this model (a division
/// weighted as ten operations), with the method named in the docs.
fn forward_dynamics(model: &Model) -> Expanded {
    let (graph, qdd, method) = cheapest_forward_dynamics(model);
    let method = match method {
        ForwardMethod::ArticulatedBody => {
            "the articulated-body algorithm (fewer operations than LDLᵀ of M here)"
        }
        ForwardMethod::MassMatrixLdlt => {
            "a tree-sparse LDLᵀ factorization of M (fewer operations than the articulated-body \
             algorithm here)"
        }
    };
    Expanded {
        graph,
        output: Output::Vector(qdd),
        doc: format!(
            "Forward dynamics: q̈ = M(q)⁻¹ (τ + Q − C(q, q̇) q̇ − g(q) − b q̇), by {method}. A \
             singular M gives non-finite values, never a panic."
        ),
    }
}

/// Forward dynamics by the method its name asks for, whatever it costs.
fn forward_dynamics_named(model: &Model, method: ForwardMethod) -> Expanded {
    let phrase = match method {
        ForwardMethod::ArticulatedBody => "the articulated-body algorithm",
        ForwardMethod::MassMatrixLdlt => "a tree-sparse LDLᵀ factorization of M",
    };
    let (graph, qdd) = forward_dynamics_by(model, method);
    Expanded {
        graph,
        output: Output::Vector(qdd),
        doc: format!(
            "Forward dynamics q̈ = M(q)⁻¹ (τ + Q − C(q, q̇) q̇ − g(q) − b q̇) by {phrase}, whatever \
             it costs. A singular M gives non-finite values, never a panic."
        ),
    }
}

fn kinetic_energy(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let kinetic = energy::kinetic(&g, model, &t, &i, &v);
    Expanded {
        graph: g,
        output: Output::Scalar(kinetic),
        doc: "Kinetic energy T = ½ q̇ᵀ M(q) q̇.".to_owned(),
    }
}

fn potential_energy(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let potential = energy::potential(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Scalar(potential),
        doc: "Potential energy of gravity V(q) = −Σ m_i g·c_i (zero at the world origin)."
            .to_owned(),
    }
}

fn joint_reactions(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let (v, a) = (
        inputs(&g, Array::V, model.nv),
        inputs(&g, Array::A, model.nv),
    );
    let sweep_inputs = SweepInputs {
        velocity: &v,
        acceleration: &a,
        gravity: true,
        loads: has_loads(model),
    };
    // The joint wrenches are the declared bodies' (base parameters keep τ only).
    let sweep = rnea::sweep(&g, model, &t, &i, &sweep_inputs);
    // In the joint frame as declared: turned back where the tree turned the body's frame.
    let rows = sweep
        .wrenches()
        .iter()
        .zip(&model.bodies)
        .map(|(&(f, m), body)| match body.joint.joint_frame_in_body {
            Some(turn) => {
                let back = Mat3::constant(&g, turn).transpose();
                (back.mul_vec(&g, f), back.mul_vec(&g, m))
            }
            None => (f, m),
        })
        .map(|(f, m)| vec![f.get(0), f.get(1), f.get(2), m.get(0), m.get(1), m.get(2)])
        .collect();
    Expanded {
        graph: g,
        output: Output::Matrix(rows),
        doc: "Joint reactions: for each body, the wrench [F; M_P] its joint transmits to it from \
              the parent (actuator component included), in the body frame about the joint \
              point P."
            .to_owned(),
    }
}

fn center_of_mass(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let c = kinematics::center_of_mass(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Vector(c.0.to_vec()),
        doc: "Centre of mass c(q) = Σ m_i x_i / Σ m_i of every body, in the world frame \
              (Pinocchio's `centerOfMass`)."
            .to_owned(),
    }
}

fn center_of_mass_jacobian(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let jacobian = kinematics::center_of_mass_jacobian(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Matrix(jacobian),
        doc: "Jacobian of the centre of mass J_c(q), 3 × nv, in the world frame: ċ = J_c q̇ \
              (Pinocchio's `jacobianCenterOfMass`; a free base's columns are its velocity \
              [v_P; ω] in the base frame)."
            .to_owned(),
    }
}

fn joint_placements(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let placements = kinematics::joint_frame_poses(&g, model, &t)
        .iter()
        .map(pose_output)
        .collect();
    Expanded {
        graph: g,
        output: Output::Stack(placements),
        doc: "The pose of every body's frame (joint i's frame after its motion, indexed like \
              `BODY_NAMES`) in the world: (R, p) with x_world = R x_body + p (Pinocchio's \
              `oMi` after `forwardKinematics`)."
            .to_owned(),
    }
}

fn joint_jacobians(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let jacobians = kinematics::body_jacobians(&g, model, &t)
        .into_iter()
        .map(Output::Matrix)
        .collect();
    Expanded {
        graph: g,
        output: Output::Stack(jacobians),
        doc: "The Jacobian of every body's frame (indexed like `BODY_NAMES`), 6 × nv, rows \
              [linear; angular], at the frame's origin with the world's axes: \
              [v_P; ω] in world coordinates = J q̇ (Pinocchio's `getJointJacobian` in \
              `LOCAL_WORLD_ALIGNED`). Columns of joints that do not move the body are zero."
            .to_owned(),
    }
}

/// 6 rows [linear; angular] of nv entries from full columns.
fn rows_of(g: &Graph, columns: &[(Vec3, Vec3)]) -> Vec<Vec<Node>> {
    let columns: Vec<_> = columns.iter().copied().map(Some).collect();
    kinematics::jacobian_rows(g, &columns)
}

fn joint_jacobians_world(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let poses = kinematics::body_poses(&g, model, &t);
    let columns = kinematics::world_jacobian_columns(&g, model, &poses);
    Expanded {
        output: Output::Matrix(rows_of(&g, &columns)),
        graph: g,
        doc: "All the joint Jacobians in one 6 × nv matrix, Pinocchio's WORLD convention \
              (its `data.J` after `computeJointJacobians`): column k, rows [linear; angular], \
              is the motion velocity coordinate k gives its joint's body at unit rate, \
              [v_O; ω] with v_O the velocity of the body point at the world origin, world \
              axes. Body i's WORLD Jacobian is the columns of the joints from the root to i \
              (zero elsewhere); shifted to its origin p_i (v_P = v_O + ω × p_i) they give \
              `joint_jacobians`. One matrix instead of one per body: the compact form to \
              store, or to pick a few bodies' columns from."
            .to_owned(),
    }
}

fn joint_jacobians_world_time_variation(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let poses = kinematics::body_poses(&g, model, &t);
    let columns = kinematics::world_jacobian_columns(&g, model, &poses);
    let rates = kinematics::world_jacobian_rates(&g, model, &columns, &v);
    Expanded {
        output: Output::Tuple(vec![
            Output::Matrix(rows_of(&g, &columns)),
            Output::Matrix(rows_of(&g, &rates)),
        ]),
        graph: g,
        doc: "(J, J̇): the matrix of `joint_jacobians_world` and its time derivative along \
              the velocity v, both 6 × nv in Pinocchio's WORLD convention (its `data.J` and \
              `data.dJ` after `computeJointJacobiansTimeVariation`). Column k of J̇ is \
              V_j × J[:, k], the motion cross product with the spatial velocity V_j of \
              coordinate k's body (world axes, at the world origin)."
            .to_owned(),
    }
}

fn forward_kinematics(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let a = inputs(&g, Array::A, model.nv);
    let placements = kinematics::joint_frame_poses(&g, model, &t)
        .iter()
        .map(pose_output)
        .collect();
    let velocities = six_vectors(kinematics::body_velocities(&g, model, &t, &v));
    let accelerations = six_vectors(
        kinematics::motions_in_world(&g, model, &t, &v, &a)
            .into_iter()
            .map(|m| (m.accel, m.alpha)),
    );
    Expanded {
        graph: g,
        output: Output::Tuple(vec![
            Output::Stack(placements),
            Output::Stack(velocities),
            Output::Stack(accelerations),
        ]),
        doc: "Every body's placement, velocity and acceleration at (q, v, a), indexed like \
              `BODY_NAMES` (what Pinocchio's `forwardKinematics(q, v, a)` gives): the poses \
              (R, p) of `joint_placements`, the velocities [v_P; ω] of `joint_velocities` and \
              the classical accelerations [a_P; α] of each body's origin, world axes, \
              without gravity (J q̈ + J̇ q̇; at q̈ = 0 those of `joint_acceleration_biases`)."
            .to_owned(),
    }
}

fn joint_velocities(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let velocities = six_vectors(kinematics::body_velocities(&g, model, &t, &v));
    Expanded {
        graph: g,
        output: Output::Stack(velocities),
        doc: "The velocity of every body's frame (indexed like `BODY_NAMES`), [v_P; ω] at its \
              origin in world axes: J q̇ with J of `joint_jacobians`, by the velocity field \
              from the root (Pinocchio's joint velocity in `LOCAL_WORLD_ALIGNED`)."
            .to_owned(),
    }
}

fn joint_acceleration_biases(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let zero = vec![g.zero(); model.nv];
    let biases = six_vectors(
        kinematics::motions_in_world(&g, model, &t, &v, &zero)
            .into_iter()
            .map(|m| (m.accel, m.alpha)),
    );
    Expanded {
        graph: g,
        output: Output::Stack(biases),
        doc: "J̇ q̇ of every body's frame (indexed like `BODY_NAMES`), world axes at its \
              origin: the classical acceleration [a_P; α] at q̈ = 0 without gravity, so that \
              [a_P; α] = J q̈ + J̇ q̇ (what task-space control needs; Pinocchio's \
              `getJointJacobianTimeVariation` times v, `LOCAL_WORLD_ALIGNED`)."
            .to_owned(),
    }
}

fn centroidal_momentum_matrix(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let a = kinematics::centroidal_momentum_matrix(&g, model, &t, &i);
    Expanded {
        graph: g,
        output: Output::Matrix(a),
        doc: "Centroidal momentum matrix A_G(q), 6 × nv, rows [linear; angular]: A_G q̇ is the \
              linear momentum and the angular momentum about the centre of mass, in world \
              axes (Pinocchio's `ccrba`)."
            .to_owned(),
    }
}

fn centroidal_bias(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let bias = kinematics::centroidal_bias(&g, model, &t, &i, &v);
    Expanded {
        graph: g,
        output: Output::Vector(bias),
        doc: "Ȧ_G q̇, 6 entries [linear; angular]: the rate of the centroidal momentum \
              h_G = A_G q̇ at q̈ = 0 (world axes, angular part about the moving centre of mass), \
              so that ḣ_G = A_G q̈ + Ȧ_G q̇ (Pinocchio's `dccrba` dAg times v, or \
              `computeCentroidalMomentumTimeVariation`'s dhg at a = 0)."
            .to_owned(),
    }
}

/// Six-vectors [linear; angular], one output vector each, stacked.
fn six_vectors(vectors: impl IntoIterator<Item = (Vec3, Vec3)>) -> Vec<Output> {
    vectors
        .into_iter()
        .map(|(linear, angular)| {
            Output::Vector(linear.0.iter().chain(&angular.0).copied().collect())
        })
        .collect()
}

/// (R, p) of a pose as an output: a 3 × 3 matrix of rows and a 3-vector.
fn pose_output(pose: &kinematics::Pose) -> Output {
    let rows = pose
        .rotation_in_world
        .0
        .iter()
        .map(|r| r.to_vec())
        .collect();
    Output::Tuple(vec![
        Output::Matrix(rows),
        Output::Vector(pose.origin_in_world.0.to_vec()),
    ])
}

fn frame_placements(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let placements = frames::frame_poses(&g, model, &t)
        .iter()
        .map(pose_output)
        .collect();
    Expanded {
        graph: g,
        output: Output::Stack(placements),
        doc: "The pose of every operational frame (indexed like `FRAME_NAMES`, see the \
              `FRAME_*` constants) in the world: (R, p) with x_world = R x_frame + p \
              (Pinocchio's `oMf` after `updateFramePlacements`)."
            .to_owned(),
    }
}

fn frame_jacobians(model: &Model, axes: JacobianAxes) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let jacobians = frames::frame_jacobians(&g, model, &t, axes)
        .into_iter()
        .map(Output::Matrix)
        .collect();
    let doc = match axes {
        JacobianAxes::WorldAligned => {
            "The Jacobian of every operational frame (indexed like `FRAME_NAMES`), 6 × nv, \
             rows [linear; angular], at the frame's origin with the world's axes: [v; ω] of \
             the frame in world coordinates = J q̇ (Pinocchio's `getFrameJacobian` in \
             `LOCAL_WORLD_ALIGNED`). Columns of joints that do not move the frame are zero."
        }
        JacobianAxes::Local => {
            "The Jacobian of every operational frame (indexed like `FRAME_NAMES`), 6 × nv, \
             rows [linear; angular], in the frame's own axes: [v; ω] of the frame in its own \
             coordinates = J q̇ (Pinocchio's `getFrameJacobian` in `LOCAL`). Columns of \
             joints that do not move the frame are zero."
        }
    };
    Expanded {
        graph: g,
        output: Output::Stack(jacobians),
        doc: doc.to_owned(),
    }
}

fn frame_velocities(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let velocities = six_vectors(frames::frame_velocities(&g, model, &t, &v));
    Expanded {
        graph: g,
        output: Output::Stack(velocities),
        doc: "The velocity of every operational frame (indexed like `FRAME_NAMES`), [v; ω] \
              at its origin in world axes: J q̇ with J of `frame_jacobians` (Pinocchio's \
              `getFrameVelocity` in `LOCAL_WORLD_ALIGNED`)."
            .to_owned(),
    }
}

fn frame_acceleration_biases(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let biases = six_vectors(frames::frame_acceleration_biases(&g, model, &t, &v));
    Expanded {
        graph: g,
        output: Output::Stack(biases),
        doc: "J̇ q̇ of every operational frame (indexed like `FRAME_NAMES`), world axes at its \
              origin: the classical acceleration [a; α] of the frame at q̈ = 0 without \
              gravity, so that [a; α] = J q̈ + J̇ q̇ with J of `frame_jacobians` (what \
              task-space control needs; Pinocchio's `getFrameClassicalAcceleration` in \
              `LOCAL_WORLD_ALIGNED` at a = 0)."
            .to_owned(),
    }
}

/// The model's force-analysis data; [`CATALOG`] asks for the functions that read it only
/// when it is there.
fn statics_of(model: &Model) -> &crate::model::statics::Statics {
    match &model.statics {
        Some(statics) => statics,
        None => unreachable!("the catalog expands the force analysis only when it is declared"),
    }
}

fn force_analysis(model: &Model) -> Expanded {
    let statics = statics_of(model);
    let (g, t, i) = fresh_graph(model);
    let (v, a) = (
        inputs(&g, Array::V, model.nv),
        inputs(&g, Array::A, model.nv),
    );
    let sweep = SweepInputs {
        velocity: &v,
        acceleration: &a,
        gravity: true,
        loads: has_loads(model),
    };
    let (matrix, rhs) = statics::balance_equations(&g, model, statics, &t, &i, &sweep);
    let (x, pivots) = qr::solve(&g, matrix, rhs);
    let names: Vec<&str> = statics.unknowns.iter().map(|u| u.name.as_str()).collect();
    Expanded {
        graph: g,
        output: Output::Tuple(vec![Output::Vector(x), Output::Vector(pivots)]),
        doc: format!(
            "Force analysis: every reaction component and driving effort x = ({}) at the \
             motion (`q`, `v`, `a`), from each body's balance equations A(q) x = b(q, q̇, q̈) \
             solved by Givens QR; returns (x, diagonal of R). Components are along the axes of \
             the connection's first body; each acts on the second body and, opposite, on the \
             first. A singular A (a toggle or dead-centre position) gives a zero pivot or \
             non-finite values: check with `ForceAnalysis::checked`.",
            names.join(", ")
        ),
    }
}

fn constraint_residual(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let phi = statics::closure_residual(&g, model, statics_of(model), &t);
    Expanded {
        graph: g,
        output: Output::Vector(phi),
        doc: "Loop closure φ(q): zero when every declared constraint is satisfied (each \
              component along a reaction direction, in the first body's frame)."
            .to_owned(),
    }
}

fn constraint_jacobian(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let phi = statics::closure_residual(&g, model, statics_of(model), &t);
    let jacobian = statics::closure_jacobian(&g, model, &phi);
    Expanded {
        graph: g,
        output: Output::Matrix(jacobian),
        doc: "Constraint Jacobian Φ_q = ∂φ/∂q (one row per closure equation).".to_owned(),
    }
}

fn constraint_bias(model: &Model) -> Expanded {
    let (g, t, _) = fresh_graph(model);
    let phi = statics::closure_residual(&g, model, statics_of(model), &t);
    let (_, gamma) = statics::closure_rates(&g, &phi);
    Expanded {
        graph: g,
        output: Output::Vector(gamma),
        doc: "Constraint acceleration term γ(q, q̇) = −(∂(Φ_q q̇)/∂q) q̇: the accelerations \
              that keep the loops closed satisfy Φ_q q̈ = γ."
            .to_owned(),
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::sym::OpCount;
    use proc_macro2::TokenStream;
    use quote::{format_ident, quote};

    fn compile(tokens: TokenStream) -> Vec<Function> {
        let mechanism: crate::syntax::Mechanism = syn::parse2(tokens).expect("parses");
        let model = crate::model::lower(&mechanism).expect("valid");
        let scalar: syn::Path = syn::parse_quote!(Scalar);
        CATALOG
            .iter()
            .filter(|entry| (entry.wanted)(&model))
            .map(|entry| entry.function(&model, &scalar))
            .collect()
    }

    fn ops(functions: &[Function], name: &str) -> OpCount {
        let f = functions
            .iter()
            .find(|f| f.spec.name == name)
            .expect("generated");
        f.graph.op_count(&f.spec.output.nodes())
    }

    /// A chain of `n` links. Spatial: alternating joint axes (z, y, x, ...), offset mass
    /// centres and full inertias, no structure to exploit beyond what any arm has. Planar:
    /// every axis z, links along x (the benchmark's planar chains).
    pub(crate) fn chain(n: usize, spatial: bool, outputs: TokenStream) -> TokenStream {
        let bodies = (0..n).map(|i| {
            let name = format_ident!("link{i}");
            if spatial {
                quote! { body #name { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] } }
            } else {
                quote! { body #name { mass: 1.0, com: [0.25, 0.0, 0.0], shape: rod(length: 0.5, axis: x) } }
            }
        });
        let joints = (0..n).map(|i| {
            let (name, child) = (format_ident!("joint{i}"), format_ident!("link{i}"));
            let parent = if i == 0 {
                format_ident!("ground")
            } else {
                format_ident!("link{}", i - 1)
            };
            let axis = if spatial {
                [quote!(z), quote!(y), quote!(x)][i % 3].clone()
            } else {
                quote!(z)
            };
            let at = match (i, spatial) {
                (0, _) => quote!([0.0, 0.0, 0.0]),
                (_, true) => quote!([0.4, 0.0, 0.05]),
                (_, false) => quote!([0.5, 0.0, 0.0]),
            };
            quote! { joint #name: revolute(#parent -> #child) { axis: #axis, at: #at } }
        });
        quote! {
            pub struct Chain;
            gravity: [0.0, -9.81, 0.0];
            outputs: #outputs;
            #(#bodies)*
            #(#joints)*
        }
    }

    fn total(functions: &[Function], name: &str) -> usize {
        let c = ops(functions, name);
        c.mul + c.add + c.div + c.trig
    }

    /// The tokens of the PUMA 560's `mechanism!` invocation.
    pub(crate) fn puma_tokens() -> TokenStream {
        invocation_tokens(include_str!("../../models/src/puma560.rs"))
    }

    /// The tokens of the bundled quadruped's `mechanism!` invocation (a free base, four
    /// legs).
    pub(crate) fn quadruped_tokens() -> TokenStream {
        invocation_tokens(include_str!("../../models/src/quadruped.rs"))
    }

    /// The tokens of the first `mechanism!` invocation in `source`.
    fn invocation_tokens(source: &str) -> TokenStream {
        let file = syn::parse_file(source).expect("parses");
        file.items
            .into_iter()
            .find_map(|item| match item {
                syn::Item::Macro(m) => Some(m.mac.tokens),
                _ => None,
            })
            .expect("a mechanism! invocation")
    }

    #[test]
    fn puma_inverse_dynamics_meets_the_customized_newton_euler_count() {
        let count = ops(&compile(puma_tokens()), "inverse_dynamics");
        // Murray and Neuman's ARM: 224 multiplications, 174 additions (199 and 160 here, with
        // the inertial parameters regrouped into base parameters).
        assert!(count.mul <= 224, "{count}");
        assert!(count.add <= 174, "{count}");
        assert_eq!(count.div, 0, "{count}");
    }

    #[test]
    fn inverse_and_forward_dynamics_grow_linearly() {
        let outputs = quote!([inverse_dynamics, forward_dynamics, mass_matrix]);
        for spatial in [false, true] {
            let at = |n: usize| compile(chain(n, spatial, outputs.clone()));
            let (c10, c13, c20, c23, c30) = (at(10), at(13), at(20), at(23), at(30));
            // Linear: links added cost the same wherever they are added (compared over three
            // links, one period of the spatial chain's z, y, x axes).
            let near = total(&c13, "inverse_dynamics") - total(&c10, "inverse_dynamics");
            let far = total(&c23, "inverse_dynamics") - total(&c20, "inverse_dynamics");
            assert_eq!(
                near, far,
                "inverse dynamics (spatial: {spatial}): links 11-13 cost {near}, links 21-23 {far}"
            );
            // Forward dynamics: the articulated-body graph is linear; the generated function
            // (the cheaper method) never costs more than it.
            let aba = |n: usize| {
                let mechanism: crate::syntax::Mechanism =
                    syn::parse2(chain(n, spatial, outputs.clone())).expect("parses");
                let model = crate::model::lower(&mechanism).expect("valid");
                let (g, qdd) = forward_dynamics_by(&model, ForwardMethod::ArticulatedBody);
                let c = g.op_count(&qdd);
                c.mul + c.add + c.div + c.trig
            };
            let (near, far) = (aba(13) - aba(10), aba(23) - aba(20));
            assert_eq!(
                near, far,
                "articulated body (spatial: {spatial}): links 11-13 cost {near}, links 21-23 {far}"
            );
            assert!(total(&c30, "forward_dynamics") <= aba(30));
            let ratio =
                total(&c30, "inverse_dynamics") as f64 / total(&c10, "inverse_dynamics") as f64;
            // The first links are cheaper (fixed base), so the ratio sits a little above 3:
            // 3.32 for the spatial chain, below 3.3 for the planar one.
            let bound = if spatial { 3.33 } else { 3.3 };
            assert!(
                ratio <= bound,
                "ops(30)/ops(10) = {ratio} (spatial: {spatial})"
            );
            // The mass matrix has n² entries: quadratic, not worse.
            let m_ratio = total(&c30, "mass_matrix") as f64 / total(&c10, "mass_matrix") as f64;
            assert!(m_ratio <= 9.9, "mass matrix ops(30)/ops(10) = {m_ratio}");
        }
    }

    #[test]
    fn only_requested_functions_are_generated() {
        let functions = compile(chain(3, true, quote!([gravity])));
        let names: Vec<String> = functions.iter().map(|f| f.spec.name.to_string()).collect();
        assert_eq!(names, ["gravity"]);
        // Gravity reads only q: no velocity or acceleration input survives.
        let live = functions[0].graph.live(&functions[0].spec.output.nodes());
        for node in live.nodes() {
            if let crate::sym::Op::Input(input) = functions[0].graph.op(node) {
                assert_eq!(input.array, Array::Q, "{input}");
            }
        }
    }

    #[test]
    fn coordinate_axes_and_zero_offsets_cost_nothing() {
        // A planar pendulum about z with its mass centre on the link's x axis: the
        // inverse dynamics is I_O q̈ + m g l cos q (+ nothing else).
        let functions = compile(quote! {
            struct P;
            gravity: [0.0, -9.81, 0.0];
            outputs: [inverse_dynamics];
            body rod { mass: 2.0, com: [0.3, 0.0, 0.0], inertia: diag([0.0, 0.06, 0.06]) }
            joint pin: revolute(ground -> rod) { axis: z }
        });
        let count = ops(&functions, "inverse_dynamics");
        assert!(count.mul <= 3 && count.add <= 1, "{count}");
    }

    #[test]
    fn articulated_body_and_ldlt_agree() {
        let free_tree = quote! {
            struct FreeTree;
            gravity: [0.0, 0.0, -9.81];
            outputs: [forward_dynamics];
            body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
            body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
            body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
            body slider { mass: 0.4, shape: sphere(radius: 0.03) }
            joint float: free(ground -> base);
            joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3), armature: 0.01, damping: 0.2 }
            joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0] }
            joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0], damping: 0.5 }
            load push: wrench on slider at [0.01, 0.0, 0.02];
            load twist: couple on right;
            load wind: wrench on left at [0.05, 0.0, 0.01] in world;
        };
        for tokens in [free_tree, chain(6, true, quote!([forward_dynamics]))] {
            let mechanism: crate::syntax::Mechanism = syn::parse2(tokens).expect("parses");
            let model = crate::model::lower(&mechanism).expect("valid");
            let by = |method| forward_dynamics_by(&model, method);
            let (aba, ldlt) = (
                by(ForwardMethod::ArticulatedBody),
                by(ForwardMethod::MassMatrixLdlt),
            );
            for state in 0..5 {
                let input = |r: crate::sym::InputRef| {
                    let k = r.index as f64;
                    let s = state as f64;
                    match r.array {
                        // A unit quaternion for the free joint (q[3..7]); angles elsewhere.
                        Array::Q if model.nq == 7 + 3 && (3..7).contains(&r.index) => {
                            [0.1, -0.2, 0.3 + 0.1 * s, 0.9][r.index as usize - 3]
                                / (0.95_f64 + 0.06 * s + 0.01 * s * s).sqrt()
                        }
                        Array::Q => (0.7 * k + 0.3 * s).sin(),
                        Array::V => (1.3 * k - 0.5 * s).cos(),
                        Array::Tau => 2.0 * (0.4 * k + s).sin(),
                        Array::Loads => 0.5 * (k - s).cos(),
                        _ => 0.0,
                    }
                };
                let a = aba.0.eval(input, &aba.1);
                let b = ldlt.0.eval(input, &ldlt.1);
                let scale = 1.0 + b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
                for (x, y) in a.iter().zip(&b) {
                    assert!(
                        (x - y).abs() <= 1e-10 * scale,
                        "{} state {state}: ABA {a:?} vs LDLᵀ {b:?}",
                        model.name
                    );
                }
            }
        }
    }

    #[test]
    fn arguments_come_in_the_documented_order() {
        let functions = compile(quote! {
            struct P;
            parameters: [tip = 1.0];
            body b { mass: tip, com: [0.1, 0.0, 0.0], shape: point }
            joint j: revolute(ground -> b) { axis: z }
            load push: force on b;
        });
        let order = |name: &str| -> Vec<&str> {
            let f = functions
                .iter()
                .find(|f| f.spec.name == name)
                .expect("generated");
            f.spec.args.iter().map(|a| a.array.name()).collect()
        };
        assert_eq!(order("inverse_dynamics"), ["q", "v", "a", "p", "loads"]);
        assert_eq!(order("forward_dynamics"), ["q", "v", "tau", "p", "loads"]);
        assert_eq!(order("mass_matrix"), ["q", "p"]);
    }

    /// A free base (`pelvis`) carrying a 12-link spatial chain, with `outputs`.
    fn free_chain(outputs: TokenStream) -> TokenStream {
        let bodies = (0..12).map(|i| {
            let name = format_ident!("link{i}");
            quote! { body #name { mass: 1.5, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] } }
        });
        let joints = (0..12).map(|i| {
            let (name, child) = (format_ident!("joint{i}"), format_ident!("link{i}"));
            let parent = if i == 0 {
                format_ident!("pelvis")
            } else {
                format_ident!("link{}", i - 1)
            };
            let axis = [quote!(x), quote!(y), quote!(z)][i % 3].clone();
            quote! { joint #name: revolute(#parent -> #child) { axis: #axis, at: [0.02, 0.0, -0.2] } }
        });
        quote! {
            struct FreeChain;
            outputs: #outputs;
            body pelvis { mass: 5.0, inertia: diag([0.05, 0.04, 0.03]) }
            joint base: free(ground -> pelvis);
            #(#bodies)*
            #(#joints)*
        }
    }

    /// A free base carrying a 12-link spatial chain: forward dynamics by the
    /// articulated-body algorithm, but its derivatives' chain rule takes q̈ from the LDLᵀ
    /// factorization the solves need (fewer operations than with the articulated-body
    /// algorithm beside it); the values are checked in tests/generated_derivatives.rs.
    #[test]
    fn forward_dynamics_derivatives_take_the_cheaper_chain() {
        let functions = compile(free_chain(quote!([
            forward_dynamics,
            forward_dynamics_derivatives
        ])));
        let doc = |name: &str| {
            functions
                .iter()
                .find(|f| f.spec.name == name)
                .map(|f| f.spec.doc.clone())
                .expect("generated")
        };
        assert!(doc("forward_dynamics").contains("articulated-body algorithm"));
        assert!(doc("forward_dynamics_derivatives").contains("q̈ by the same factorization"));
        // And ∂τ/∂q̇ by 2 C + diag(b) in the joints' columns, from M and C in the base's.
        assert!(doc("forward_dynamics_derivatives").contains("2 C(q, q̇) +"));
        assert!(doc("forward_dynamics_derivatives").contains("free joint's columns from M and C"));
    }

    /// The chain rule's solves run as one loop over all columns where that is cheaper (a free
    /// base carrying a 12-link chain: 2 × 18 columns), as straight-line solves where not (a
    /// 3-link arm), and both ways give the same values, the loop's evaluated as the
    /// generated code runs it (`Output::values`). The generated loop is checked against
    /// dual numbers in tests/generated_derivatives.rs and against Pinocchio for the Panda and
    /// the quadruped.
    #[test]
    fn forward_dynamics_derivatives_solve_by_a_loop_where_cheaper() {
        let tokens = free_chain(quote!([forward_dynamics_derivatives]));
        let solved_by_loop = |functions: &[Function]| {
            functions
                .iter()
                .any(|f| matches!(f.spec.output, Output::Solved(_)) && f.spec.doc.contains("loop"))
        };
        assert!(solved_by_loop(&compile(tokens.clone())));
        assert!(!solved_by_loop(&compile(chain(
            3,
            true,
            quote!([forward_dynamics_derivatives])
        ))));

        let mechanism: crate::syntax::Mechanism = syn::parse2(tokens).expect("parses");
        let model = crate::model::lower(&mechanism).expect("valid");
        let (g, t, i) = fresh_graph(&model);
        let outputs = forward_dynamics_derivatives_by_chain_rule(
            &g,
            &t,
            &i,
            &model,
            ForwardMethod::MassMatrixLdlt,
            VelocityColumns::ForwardMode,
        );
        let input = |r: crate::sym::InputRef| {
            let x = 0.3 + 0.17 * f64::from(r.index) + 0.05 * f64::from(r.array as u8);
            if r.array == Array::Q && (3..7).contains(&r.index) {
                0.5 // a unit quaternion
            } else {
                x.sin()
            }
        };
        let [unrolled, by_loop] = [0, 1].map(|k| outputs[k].0.values(|n| g.eval(input, n)));
        assert_eq!(unrolled.len(), 2 * 18 * 18);
        assert_eq!(by_loop.len(), unrolled.len());
        for (a, b) in unrolled.iter().zip(&by_loop) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{a} vs {b}");
        }
    }

    /// M⁻¹ is finished by a loop over the columns (the last sweep of the solve) where that
    /// is cheaper, instruction cache included (a free base carrying a 12-link chain,
    /// 18 dof), and is straight-line code where not (a 6-link arm); both ways give the same
    /// values, the loop's as the generated code runs it (`Output::values`), and M⁻¹ M = 1.
    #[test]
    fn mass_matrix_inverse_by_a_loop_where_cheaper() {
        let output = |tokens: TokenStream| {
            compile(tokens)
                .into_iter()
                .find(|f| f.spec.name == "mass_matrix_inverse")
                .map(|f| (f.spec.output, f.spec.doc))
                .expect("generated")
        };
        let (free, doc) = output(free_chain(quote!([mass_matrix_inverse])));
        assert!(
            matches!(&free, Output::Solved(s) if s.sweeps == Sweeps::LastOfInverse),
            "{free:?}"
        );
        assert!(doc.contains("as a loop over the columns"), "{doc}");
        let (arm, doc) = output(chain(6, true, quote!([mass_matrix_inverse])));
        assert!(matches!(arm, Output::Matrix(_)));
        assert!(!doc.contains("loop"), "{doc}");

        let tokens = free_chain(quote!([mass_matrix, mass_matrix_inverse]));
        let mechanism: crate::syntax::Mechanism = syn::parse2(tokens).expect("parses");
        let model = crate::model::lower(&mechanism).expect("valid");
        let input = |r: crate::sym::InputRef| {
            let x = 0.3 + 0.17 * f64::from(r.index);
            if (3..7).contains(&r.index) {
                0.5 // a unit quaternion
            } else {
                x.sin()
            }
        };
        let [straight, by_loop]: [Vec<f64>; 2] = mass_matrix_inverse_candidates(&model)
            .into_iter()
            .map(|(g, output, _)| output.values(|n| g.eval(input, n)))
            .collect::<Vec<_>>()
            .try_into()
            .expect("two ways");
        let (g, t, i) = fresh_graph(&model);
        let m = regrouped_mass_matrix(&g, &model, &t, &i);
        let m = g.eval(input, &m.concat());
        assert_eq!(by_loop.len(), 18 * 18);
        for r in 0..18 {
            for c in 0..18 {
                let (a, b) = (straight[18 * r + c], by_loop[18 * r + c]);
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + a.abs()),
                    "({r}, {c}): {a} vs {b}"
                );
                assert_eq!(b.to_bits(), by_loop[18 * c + r].to_bits(), "symmetric");
                let product: f64 = (0..18).map(|k| by_loop[18 * r + k] * m[18 * k + c]).sum();
                let identity = if r == c { 1.0 } else { 0.0 };
                assert!(
                    (product - identity).abs() < 1e-9,
                    "M⁻¹ M at ({r}, {c}): {product}"
                );
            }
        }
    }

    /// ∂τ/∂q̇ as 2 C + diag(b) where that is cheaper (a spatial arm; a free base carrying
    /// a 12-link chain, in its joints' columns), forward mode where that is (a free body
    /// carrying one link); the values are checked in tests/generated_derivatives.rs and
    /// against Pinocchio's for the Panda.
    #[test]
    fn velocity_columns_by_the_coriolis_matrix_where_cheaper() {
        let doc = |functions: &[Function], name: &str| {
            functions
                .iter()
                .find(|f| f.spec.name == name)
                .map(|f| f.spec.doc.clone())
                .expect("generated")
        };
        let arm = compile(chain(
            7,
            true,
            quote!([inverse_dynamics_derivatives, forward_dynamics_derivatives]),
        ));
        assert!(doc(&arm, "inverse_dynamics_derivatives").contains("2 C(q, q̇) + diag(b)"));
        assert!(doc(&arm, "forward_dynamics_derivatives").contains("2 C(q, q̇) +"));
        let free = compile(quote! {
            struct Floating;
            outputs: [inverse_dynamics_derivatives];
            body base { mass: 2.0, inertia: diag([0.05, 0.04, 0.03]) }
            body arm { mass: 1.0, com: [0.2, 0.0, 0.0], inertia: diag([0.01, 0.02, 0.02]) }
            joint float: free(ground -> base);
            joint hinge: revolute(base -> arm) { axis: z, at: [0.1, 0.0, 0.0] }
        });
        assert!(!doc(&free, "inverse_dynamics_derivatives").contains("2 C(q, q̇)"));
    }

    /// A free base carrying two branches: a twisted revolute joint and a wrist, and a
    /// prismatic joint; damping and armature on the free joint and the wrist, gravity off
    /// the axes.
    fn floating_branches() -> Model {
        let mechanism: crate::syntax::Mechanism = syn::parse2(quote! {
            struct Floating;
            gravity: [0.5, -1.0, -9.0];
            outputs: [inverse_dynamics_derivatives];
            body base { mass: 2.0, com: [0.01, -0.02, 0.03], inertia: [[0.05, 0.002, 0.001], [0.002, 0.04, 0.003], [0.001, 0.003, 0.03]] }
            body arm { mass: 1.0, com: [0.2, 0.01, 0.0], inertia: diag([0.01, 0.02, 0.02]) }
            body hand { mass: 0.5, com: [0.05, 0.0, 0.02], inertia: diag([0.003, 0.002, 0.004]) }
            body slider { mass: 0.3, com: [0.02, 0.01, 0.0], inertia: diag([0.001, 0.002, 0.002]) }
            joint float: free(ground -> base) { damping: 0.3, armature: 0.1 }
            joint hinge: revolute(base -> arm) { axis: [0.2, 0.5, 1.0], at: [0.1, 0.05, 0.0], rotation: rpy(0.3, -0.2, 0.1) }
            joint wrist: revolute(arm -> hand) { axis: y, at: [0.3, 0.0, 0.0], damping: 0.2, armature: 0.05 }
            joint slide: prismatic(base -> slider) { axis: [1.0, 0.2, 0.0], at: [-0.1, 0.0, 0.05] }
        })
        .expect("parses");
        crate::model::lower(&mechanism).expect("valid")
    }

    /// An input value for [`Graph::eval`]: a unit quaternion for a free base's q[3..7],
    /// numbers of order one elsewhere.
    fn sample_input(r: crate::sym::InputRef) -> f64 {
        let x = 0.3 + 0.17 * f64::from(r.index) + 0.05 * f64::from(r.array as u8);
        if r.array == Array::Q && (3..7).contains(&r.index) {
            0.5
        } else {
            3.0 * x.sin()
        }
    }

    /// A free joint's columns of ∂τ/∂q and ∂τ/∂q̇ from M and C (with the joint's own damping
    /// and armature, gravity off the axes; [`floating_branches`]) take the values forward
    /// mode gives them, and the other columns are untouched.
    #[test]
    fn free_joint_columns_from_the_mass_and_coriolis_matrices_are_forward_modes() {
        let model = floating_branches();
        let (g, t, i) = fresh_graph(&model);
        let (tau, v) = inverse_dynamics_on(&g, &model, &t, &i);
        for with in [With::Configuration, With::Array(Array::V)] {
            let [forward, from_m_and_c] = [VelocityColumns::ForwardMode, VelocityColumns::Coriolis]
                .map(|way| {
                    let basis = CoriolisBasis::new();
                    inverse_dynamics_jacobian(&g, &model, (&t, &i), (&tau, &v), (with, way), &basis)
                });
            let free_columns_differ =
                (0..8).any(|row| (0..6).any(|col| forward[row][col] != from_m_and_c[row][col]));
            assert!(free_columns_differ, "{with:?}: built another way");
            let [forward, from_m_and_c] =
                [forward, from_m_and_c].map(|rows| g.eval(sample_input, &rows.concat()));
            for (a, b) in forward.iter().zip(&from_m_and_c) {
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + a.abs()),
                    "{with:?}: {a} vs {b}"
                );
            }
            assert!(forward.iter().any(|x| x.abs() > 0.1));
        }
    }

    /// The analytical recursion's ∂τ/∂q takes the values forward mode gives, on a free base
    /// carrying two branches ([`floating_branches`]) at a state with accelerations; and it
    /// is what a spatial 7-link arm chooses, while loads keep forward mode.
    #[test]
    fn analytic_configuration_columns_are_forward_modes() {
        let model = floating_branches();
        assert!(rnea_derivatives::applies(&model));
        let (g, t, i) = fresh_graph(&model);
        let (tau, v) = inverse_dynamics_on(&g, &model, &t, &i);
        let [forward, analytic] =
            [VelocityColumns::ForwardMode, VelocityColumns::Analytic].map(|way| {
                inverse_dynamics_jacobian(
                    &g,
                    &model,
                    (&t, &i),
                    (&tau, &v),
                    (With::Configuration, way),
                    &CoriolisBasis::new(),
                )
            });
        let [forward, analytic] =
            [forward, analytic].map(|rows| g.eval(sample_input, &rows.concat()));
        for (k, (a, b)) in forward.iter().zip(&analytic).enumerate() {
            assert!(
                (a - b).abs() <= 1e-12 * (1.0 + a.abs()),
                "∂τ/∂q entry {k}: forward mode {a}, analytical {b}"
            );
        }
        // Joint columns (not only the free base's) carry values.
        assert!((0..model.nv).any(|row| forward[row * model.nv + 7].abs() > 0.1));
        let doc = |functions: &[Function]| {
            functions
                .iter()
                .find(|f| f.spec.name == "inverse_dynamics_derivatives")
                .map(|f| f.spec.doc.clone())
                .expect("generated")
        };
        let arm = compile(chain(7, true, quote!([inverse_dynamics_derivatives])));
        assert!(doc(&arm).contains("analytical"));
        let loaded = compile(quote! {
            struct Loaded;
            outputs: [inverse_dynamics_derivatives];
            body upper { mass: 2.0, com: [0.0, 0.0, 0.2], inertia: diag([0.02, 0.02, 0.01]) }
            body fore { mass: 1.2, com: [0.15, 0.0, 0.0], inertia: diag([0.01, 0.02, 0.02]) }
            joint shoulder: revolute(ground -> upper) { axis: z }
            joint elbow: revolute(upper -> fore) { axis: y, at: [0.0, 0.0, 0.4] }
            load push: force on fore at [0.1, 0.01, 0.0] in world;
        });
        assert!(!doc(&loaded).contains("analytical"));
    }
}
