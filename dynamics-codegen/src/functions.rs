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
//! | `inverse_dynamics_derivatives(q, v, a)` | (∂τ/∂q, ∂τ/∂q̇), q in the tangent space (asked for by name) | [`rnea`] + [`derivatives`](crate::expand::derivatives); where that is cheaper, ∂τ/∂q̇ = 2 C + diag(b) by [`coriolis`] in the joint coordinates' columns and a free joint's columns of ∂τ/∂q̇ and ∂τ/∂q from M and C ([`free_joint_derivatives`](crate::expand::free_joint_derivatives)), and with it ∂τ/∂q by the analytical recursion ([`rnea_derivatives`](crate::expand::rnea_derivatives)) |
//! | `forward_dynamics_derivatives(q, v, tau)` | (∂q̈/∂q, ∂q̈/∂q̇) (asked for by name) | the cheapest of: [`derivatives`](crate::expand::derivatives) of `forward_dynamics`' expansion, or −M⁻¹ ∂τ/∂x by [`rnea`] + [`derivatives`](crate::expand::derivatives) + [`ldlt`] with q̈ by `forward_dynamics`' method or by the solves' own factorization, solved column by column in straight-line code or all columns at once by a loop (`dynamics_runtime::tree_ldlt`, SIMD across the columns) |
//! | `mass_matrix_inverse(q)` | M(q)⁻¹ (asked for by name) | [`crba`] + [`ldlt`], in straight-line code or, where that is cheaper, up to D⁻¹ L⁻ᵀ and then the last sweep L X = D⁻¹ L⁻ᵀ as a loop (`dynamics_runtime::tree_ldlt`, SIMD across the columns) |
//! | `momentum_derivatives(q, v)` | (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇) of p = M(q) q̇ and ṗ = τ + Ṁ q̇ − (C q̇ + g + b q̇ − Q) (asked for by name) | [`crba`] + [`rnea`] + [`derivatives`](crate::expand::derivatives) (Ṁ q̇ along q̇, then forward mode) |
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
//! [`Entry`] here. The derivative outputs, which choose among several expansions, are put
//! together in [`derivative_outputs`].

use crate::expand::frames::{self, JacobianAxes};
use crate::expand::geometry::{BodyInertia, JointTransform};
use crate::expand::rnea::{self, SweepInputs};
use crate::expand::{
    aba, coriolis, crba, energy, fresh_graph, inputs, kinematics, ldlt, qr, statics,
};
use crate::ir::{Arg, Function, FunctionSpec, Output};
use crate::model::Model;
use crate::passes::base_parameters;
use crate::sym::{Array, Graph, Mat3, Node, Vec3};

mod derivative_outputs;
use derivative_outputs::{
    forward_dynamics_derivatives, inverse_dynamics_derivatives, mass_matrix_inverse,
    momentum_derivatives,
};

/// Whether the function `name` returns a symmetric matrix (its catalog entry's
/// `symmetric`), of which a `_sparse_into` twin writes the upper triangle.
pub(crate) fn is_symmetric(name: &str) -> bool {
    CATALOG
        .iter()
        .any(|entry| entry.name == name && entry.symmetric)
}

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
    /// Whether it returns a symmetric matrix (M, M⁻¹): a `_sparse_into` twin then writes
    /// only the upper triangle.
    pub symmetric: bool,
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
        symmetric: false,
        expand: inverse_dynamics,
    },
    Entry {
        name: "gravity",
        wanted: |m| m.outputs.gravity && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: gravity,
    },
    Entry {
        name: "bias",
        wanted: |m| m.outputs.bias && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: bias,
    },
    Entry {
        name: "mass_matrix",
        wanted: |m| m.outputs.mass_matrix && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: true,
        expand: mass_matrix,
    },
    Entry {
        name: "coriolis_matrix",
        wanted: |m| m.outputs.coriolis && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: coriolis_matrix,
    },
    Entry {
        name: "forward_dynamics",
        wanted: |m| m.outputs.forward_dynamics && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        symmetric: false,
        expand: forward_dynamics,
    },
    Entry {
        name: "forward_dynamics_aba",
        wanted: |m| m.outputs.forward_dynamics_aba && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        symmetric: false,
        expand: |m| forward_dynamics_named(m, ForwardMethod::ArticulatedBody),
    },
    Entry {
        name: "forward_dynamics_ldlt",
        wanted: |m| m.outputs.forward_dynamics_ldlt && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        symmetric: false,
        expand: |m| forward_dynamics_named(m, ForwardMethod::MassMatrixLdlt),
    },
    Entry {
        name: "kinetic_energy",
        wanted: |m| m.outputs.energy,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: kinetic_energy,
    },
    Entry {
        name: "potential_energy",
        wanted: |m| m.outputs.energy,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: potential_energy,
    },
    Entry {
        name: "joint_reactions",
        wanted: |m| m.outputs.reactions && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        symmetric: false,
        expand: joint_reactions,
    },
    Entry {
        name: "center_of_mass",
        wanted: |m| m.outputs.center_of_mass,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: center_of_mass,
    },
    Entry {
        name: "center_of_mass_jacobian",
        wanted: |m| m.outputs.center_of_mass_jacobian && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: center_of_mass_jacobian,
    },
    Entry {
        name: "joint_placements",
        wanted: |m| m.outputs.joint_placements && !m.bodies.is_empty(),
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: joint_placements,
    },
    Entry {
        name: "joint_jacobians",
        wanted: |m| m.outputs.joint_jacobians && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: joint_jacobians,
    },
    Entry {
        name: "joint_jacobians_world",
        wanted: |m| m.outputs.joint_jacobians_world && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: joint_jacobians_world,
    },
    Entry {
        name: "joint_jacobians_world_time_variation",
        wanted: |m| m.outputs.joint_jacobians_world_time_variation && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: joint_jacobians_world_time_variation,
    },
    Entry {
        name: "forward_kinematics",
        wanted: |m| m.outputs.forward_kinematics && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: false,
        symmetric: false,
        expand: forward_kinematics,
    },
    Entry {
        name: "joint_velocities",
        wanted: |m| m.outputs.joint_velocities && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: joint_velocities,
    },
    Entry {
        name: "joint_acceleration_biases",
        wanted: |m| m.outputs.joint_acceleration_biases && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: joint_acceleration_biases,
    },
    Entry {
        name: "centroidal_momentum_matrix",
        wanted: |m| m.outputs.centroidal_momentum_matrix && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: centroidal_momentum_matrix,
    },
    Entry {
        name: "centroidal_bias",
        wanted: |m| m.outputs.centroidal_bias && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: centroidal_bias,
    },
    Entry {
        name: "frame_placements",
        wanted: |m| m.outputs.frame_placements && !m.frames.is_empty(),
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: frame_placements,
    },
    Entry {
        name: "frame_jacobians",
        wanted: |m| m.outputs.frame_jacobians && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: |m| frame_jacobians(m, JacobianAxes::WorldAligned),
    },
    Entry {
        name: "frame_jacobians_local",
        wanted: |m| m.outputs.frame_jacobians_local && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: |m| frame_jacobians(m, JacobianAxes::Local),
    },
    Entry {
        name: "frame_velocities",
        wanted: |m| m.outputs.frame_velocities && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: frame_velocities,
    },
    Entry {
        name: "frame_acceleration_biases",
        wanted: |m| m.outputs.frame_acceleration_biases && !m.frames.is_empty() && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
        expand: frame_acceleration_biases,
    },
    Entry {
        name: "inverse_dynamics_derivatives",
        wanted: |m| m.outputs.inverse_dynamics_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        symmetric: false,
        expand: inverse_dynamics_derivatives,
    },
    Entry {
        name: "forward_dynamics_derivatives",
        wanted: |m| m.outputs.forward_dynamics_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V, Array::Tau],
        loads: true,
        symmetric: false,
        expand: forward_dynamics_derivatives,
    },
    Entry {
        name: "mass_matrix_inverse",
        wanted: |m| m.outputs.mass_matrix_inverse && m.nv > 0,
        arrays: &[Array::Q],
        loads: false,
        symmetric: true,
        expand: mass_matrix_inverse,
    },
    Entry {
        name: "momentum_derivatives",
        wanted: |m| m.outputs.momentum_derivatives && m.nv > 0,
        arrays: &[Array::Q, Array::V],
        loads: true,
        symmetric: false,
        expand: momentum_derivatives,
    },
    Entry {
        name: "force_analysis",
        wanted: |m| m.outputs.force_analysis && m.statics.is_some(),
        arrays: &[Array::Q, Array::V, Array::A],
        loads: true,
        symmetric: false,
        expand: force_analysis,
    },
    Entry {
        name: "constraint_residual",
        wanted: wants_constraints,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: constraint_residual,
    },
    Entry {
        name: "constraint_jacobian",
        wanted: wants_constraints,
        arrays: &[Array::Q],
        loads: false,
        symmetric: false,
        expand: constraint_jacobian,
    },
    Entry {
        name: "constraint_bias",
        wanted: wants_constraints,
        arrays: &[Array::Q, Array::V],
        loads: false,
        symmetric: false,
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
        Function {
            graph,
            spec,
            unpacked: None,
        }
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

/// M(q) over the base inertial parameters that make it cheapest; `packed` by
/// [`crba::mass_matrix_packed`], else column by column.
fn regrouped_mass_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    packed: bool,
) -> Vec<Vec<Node>> {
    let build = |i: &[BodyInertia]| {
        if packed {
            crba::mass_matrix_packed(g, model, transforms, i)
        } else {
            crba::mass_matrix(g, model, transforms, i)
        }
    };
    let regrouped = base_parameters::regroup(g, model, transforms, inertias, |i| build(i).concat());
    build(&regrouped)
}

fn mass_matrix(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let m = regrouped_mass_matrix(&g, model, &t, &i, true);
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
    let build = |i: &[BodyInertia]| coriolis::coriolis_matrix_packed(&g, model, &t, i, &v);
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
            // Over slots: isomorphic limbs side by side (every body alone where none are).
            let build =
                |i: &[BodyInertia]| aba::forward_dynamics(g, model, t, i, (&v, &tau), &external);
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
            let m = regrouped_mass_matrix(g, model, t, i, false);
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
/// [`Output::Solved`] at [`TreeSolve::loop_cost`](crate::ir::TreeSolve::loop_cost), and
/// each straight-line operation past [`OPERATIONS_IN_INSTRUCTION_CACHE`] counted twice:
/// code that does not fit the
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

    pub(crate) fn compile(tokens: TokenStream) -> Vec<Function> {
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

    /// The quadruped's four legs share lanes (a slot per level of a leg, four lanes each),
    /// most of its mass matrix's operations are packed, and M(q) so computed is inverse
    /// dynamics' columns: M e_k = τ(q, 0, e_k) − τ(q, 0, 0).
    #[test]
    fn the_quadruped_s_legs_share_lanes_and_m_is_inverse_dynamics_by_columns() {
        assert_legs_share_lanes_and_m_is_inverse_dynamics_by_columns(quadruped_tokens());
    }

    /// Legs that are mirror images, declared about −x and −y where their twins turn about
    /// +x and +y (as ANYmal's are), share lanes as well: each such body's frame takes a half
    /// turn (`model::frame_turns::axis_half_turn`), so every leg turns about +x, +y, +y.
    #[test]
    fn mirror_image_legs_share_lanes_too() {
        assert_legs_share_lanes_and_m_is_inverse_dynamics_by_columns(quote! {
            struct Mirrored;
            outputs: [inverse_dynamics, mass_matrix];
            body torso { mass: 20.0, com: [0.01, 0.0, 0.02], inertia: diag([0.3, 0.6, 0.7]) }
            joint base: free(ground -> torso);
            body hip_lf { mass: 1.5, com: [0.05, 0.02, 0.0], inertia: [[0.002, 0.0001, 0.0], [0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
            body thigh_lf { mass: 1.2, com: [0.0, 0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
            body shank_lf { mass: 0.4, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
            joint haa_lf: revolute(torso -> hip_lf) { axis: [1.0, 0.0, 0.0], at: [0.28, 0.1, 0.0] }
            joint hfe_lf: revolute(hip_lf -> thigh_lf) { axis: [0.0, 1.0, 0.0], at: [0.06, 0.05, 0.0] }
            joint kfe_lf: revolute(thigh_lf -> shank_lf) { axis: [0.0, 1.0, 0.0], at: [0.0, 0.02, -0.28] }
            body hip_rf { mass: 1.5, com: [0.05, -0.02, 0.0], inertia: [[0.002, -0.0001, 0.0], [-0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
            body thigh_rf { mass: 1.2, com: [0.0, -0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
            body shank_rf { mass: 0.4, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
            joint haa_rf: revolute(torso -> hip_rf) { axis: [-1.0, 0.0, 0.0], at: [0.28, -0.1, 0.0] }
            joint hfe_rf: revolute(hip_rf -> thigh_rf) { axis: [0.0, -1.0, 0.0], at: [0.06, -0.05, 0.0] }
            joint kfe_rf: revolute(thigh_rf -> shank_rf) { axis: [0.0, -1.0, 0.0], at: [0.0, -0.02, -0.28] }
            body hip_lh { mass: 1.4, com: [-0.05, 0.02, 0.0], inertia: [[0.002, -0.0001, 0.0], [-0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
            body thigh_lh { mass: 1.2, com: [0.0, 0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
            body shank_lh { mass: 0.45, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
            joint haa_lh: revolute(torso -> hip_lh) { axis: [-1.0, 0.0, 0.0], at: [-0.28, 0.1, 0.0] }
            joint hfe_lh: revolute(hip_lh -> thigh_lh) { axis: [0.0, 1.0, 0.0], at: [-0.06, 0.05, 0.0] }
            joint kfe_lh: revolute(thigh_lh -> shank_lh) { axis: [0.0, 1.0, 0.0], at: [0.0, 0.02, -0.28] }
            body hip_rh { mass: 1.4, com: [-0.05, -0.02, 0.0], inertia: [[0.002, 0.0001, 0.0], [0.0001, 0.003, 0.0], [0.0, 0.0, 0.003]] }
            body thigh_rh { mass: 1.2, com: [0.0, -0.03, -0.1], inertia: diag([0.01, 0.011, 0.002]) }
            body shank_rh { mass: 0.45, com: [0.0, 0.0, -0.12], inertia: diag([0.004, 0.004, 0.0005]) }
            joint haa_rh: revolute(torso -> hip_rh) { axis: [1.0, 0.0, 0.0], at: [-0.28, -0.1, 0.0] }
            joint hfe_rh: revolute(hip_rh -> thigh_rh) { axis: [0.0, -1.0, 0.0], at: [-0.06, -0.05, 0.0] }
            joint kfe_rh: revolute(thigh_rh -> shank_rh) { axis: [0.0, -1.0, 0.0], at: [0.0, -0.02, -0.28] }
        });
    }

    /// [`the_quadruped_s_legs_share_lanes_and_m_is_inverse_dynamics_by_columns`] for the
    /// quadruped declared by `tokens`.
    fn assert_legs_share_lanes_and_m_is_inverse_dynamics_by_columns(tokens: TokenStream) {
        let mechanism: crate::syntax::Mechanism = syn::parse2(tokens.clone()).expect("parses");
        let model = crate::model::lower(&mechanism).expect("valid");
        let slots = crate::expand::slots::Slots::of(&model);
        let lanes: Vec<usize> = slots.slots.iter().map(|s| s.lanes.len()).collect();
        assert_eq!(
            lanes,
            [1, 4, 4, 4],
            "the base, then hips, thighs and calves side by side"
        );
        let functions = compile(tokens);
        let find = |name: &str| {
            functions
                .iter()
                .find(|f| f.spec.name == name)
                .expect("generated")
        };
        let (m, tau) = (find("mass_matrix"), find("inverse_dynamics"));
        let count = m.op_count();
        assert!(2 * count.packed > count.total(), "{count}");
        let mut q: Vec<f64> = (0..model.nq).map(|k| (0.37 * k as f64).sin()).collect();
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let at = |a: &[f64]| {
            tau.spec.output.values(|nodes| {
                tau.graph.eval(
                    |r| match r.array {
                        Array::Q => q[r.index as usize],
                        Array::A => a[r.index as usize],
                        _ => 0.0,
                    },
                    nodes,
                )
            })
        };
        let m_values = m
            .spec
            .output
            .values(|nodes| m.graph.eval(|r| q[r.index as usize], nodes));
        let bias = at(&vec![0.0; model.nv]);
        for k in 0..model.nv {
            let mut e = vec![0.0; model.nv];
            e[k] = 1.0;
            let column = at(&e);
            for i in 0..model.nv {
                let (got, want) = (m_values[i * model.nv + k], column[i] - bias[i]);
                assert!(
                    (got - want).abs() < 1e-12,
                    "M[{i}][{k}] = {got}, τ says {want}"
                );
            }
        }
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

    /// The entries marked `symmetric` (whose sparse twins write the upper triangle) are
    /// M and M⁻¹, and they return symmetric matrices; the Coriolis matrix is not marked.
    #[test]
    fn the_entries_marked_symmetric_return_symmetric_matrices() {
        let marked: Vec<&str> = CATALOG
            .iter()
            .filter(|e| e.symmetric)
            .map(|e| e.name)
            .collect();
        assert_eq!(marked, ["mass_matrix", "mass_matrix_inverse"]);
        let functions = compile(chain(
            4,
            true,
            quote!([mass_matrix, mass_matrix_inverse, coriolis_matrix]),
        ));
        let input = |r: crate::sym::InputRef| 0.3 + 0.7 * f64::from(r.index);
        let mut checked = 0;
        for f in &functions {
            let Output::Matrix(rows) = &f.spec.output else {
                continue;
            };
            let values: Vec<Vec<f64>> = rows.iter().map(|row| f.graph.eval(input, row)).collect();
            let symmetric = (0..rows.len())
                .all(|i| (0..i).all(|j| (values[i][j] - values[j][i]).abs() < 1e-12));
            assert_eq!(
                symmetric,
                is_symmetric(&f.spec.name.to_string()),
                "{}",
                f.spec.name
            );
            checked += 1;
        }
        assert_eq!(checked, 3);
    }
}
