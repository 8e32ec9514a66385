//! The derivative outputs of the catalog ([`super::CATALOG`]): how
//! `inverse_dynamics_derivatives`, `forward_dynamics_derivatives`, `mass_matrix_inverse` and
//! `momentum_derivatives` are put together from the expansions, each the cheapest of its
//! candidate methods by operation count.
//!
//! - ∂τ/∂q and ∂τ/∂q̇ of τ = M(q) q̈ + C(q, q̇) q̇ + g(q) + b q̇ − Q: forward-mode
//!   differentiation of Newton–Euler ([`derivatives`]); or ∂τ/∂q̇ = 2 C + diag(b) in the
//!   joint coordinates' columns, a free joint's columns from M and C
//!   ([`free_joint_derivatives`]), and ∂τ/∂q by the analytical recursion
//!   ([`rnea_derivatives`]) where it applies.
//! - ∂q̈/∂x = −M⁻¹ ∂τ/∂x at τ = ID(q, q̇, q̈) (the chain rule through inverse dynamics), or
//!   forward mode through `forward_dynamics`' own expansion; the solves in straight-line
//!   code or as a loop over the columns ([`crate::ir::TreeSolve`]).
//! - M⁻¹ by the tree-sparse LDLᵀ of M ([`ldlt`]).
//! - (∂p/∂q, ∂ṗ/∂q, ∂ṗ/∂q̇) of the generalized momentum p = M(q) q̇.
//!
//! q-derivatives are taken in the tangent space (q ⊕ δ, a free joint's δ in its body's
//! frame), Pinocchio's convention.

use super::{
    cheapest_forward_dynamics, forward_dynamics_on, has_loads, inverse_dynamics_on, joint_forces,
    output_cost, regrouped_mass_matrix, Expanded, ForwardMethod,
};
use crate::expand::derivatives::{self, With};
use crate::expand::geometry::{BodyInertia, JointTransform};
use crate::expand::rnea::SweepInputs;
use crate::expand::{
    coriolis, crba, free_joint_derivatives, fresh_graph, inputs, ldlt, rnea_derivatives,
};
use crate::ir::{Output, Sweeps, TreeSolve};
use crate::model::{JointKind, LoadFrame, Model};
use crate::passes::base_parameters;
use crate::sym::{Array, Graph, Node};

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
    /// composite terms ([`rnea_derivatives`]) where it applies (forward mode otherwise);
    /// `packed`: both over isomorphic limbs side by side, C by
    /// [`coriolis::coriolis_matrix_packed`] and ∂τ/∂q by
    /// [`rnea_derivatives::configuration_jacobian_packed`].
    Analytic { packed: bool },
}

/// The ways ∂τ/∂q̇ (and with it ∂τ/∂q) can be expanded for `model`: forward mode, from the
/// Coriolis and mass matrices, and that with the analytical recursion for ∂τ/∂q where it
/// applies (no loads).
fn velocity_columns(model: &Model) -> Vec<VelocityColumns> {
    let mut ways = vec![VelocityColumns::ForwardMode, VelocityColumns::Coriolis];
    if rnea_derivatives::applies(model) {
        ways.push(VelocityColumns::Analytic { packed: false });
        if model.packs {
            ways.push(VelocityColumns::Analytic { packed: true });
        }
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
    (basis, packed): (&CoriolisBasis, bool),
) -> Vec<Vec<Node>> {
    let c_inertias = basis.get_or_init(|| coriolis_inertias(g, model, (transforms, inertias), v));
    let c = if packed {
        coriolis::coriolis_matrix_packed(g, model, transforms, c_inertias, v)
    } else {
        coriolis::coriolis_matrix(g, model, transforms, c_inertias, v)
    };
    let two = g.constant(2.0);
    let mut jacobian: Vec<Vec<Node>> = c
        .iter()
        .map(|row| {
            row.iter()
                .map(|&x| g.lanewise(&[x], |x| g.mul(two, x[0])))
                .collect()
        })
        .collect();
    for body in &model.bodies {
        let k = body.joint.idx_v;
        if body.joint.kind == JointKind::Free {
            let m = free_columns_mass_matrix(g, model, (transforms, inertias), v, (basis, packed));
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
    let mass = || regrouped_mass_matrix(g, model, expansion.0, expansion.1, false);
    fill_free_configuration_columns(g, model, expansion.0, mass, &mut jacobian);
    jacobian
}

/// ∂τ/∂q by the analytical recursion ([`rnea_derivatives`]) over C's base parameters,
/// `packed` over isomorphic limbs side by side, a free joint's columns from M; by
/// [`configuration_jacobian_with_free_columns`] where the recursion does not apply (loads).
fn configuration_jacobian_analytic(
    g: &Graph,
    model: &Model,
    expansion: (&[JointTransform], &[BodyInertia]),
    (tau, v): (&[Node], &[Node]),
    (basis, packed): (&CoriolisBasis, bool),
) -> Vec<Vec<Node>> {
    if !rnea_derivatives::applies(model) {
        return configuration_jacobian_with_free_columns(g, model, expansion, tau);
    }
    let transforms = expansion.0;
    let inertias = basis.get_or_init(|| coriolis_inertias(g, model, expansion, v));
    let a = inputs(g, Array::A, model.nv);
    let mut jacobian = if packed {
        rnea_derivatives::configuration_jacobian_packed(g, model, (transforms, inertias), (v, &a))
    } else {
        let terms = coriolis::composite_terms(g, model, transforms, inertias, v);
        rnea_derivatives::configuration_jacobian(g, model, (transforms, inertias), &terms, (v, &a))
    };
    let mass = || free_columns_mass_matrix(g, model, expansion, v, (basis, packed));
    fill_free_configuration_columns(g, model, transforms, mass, &mut jacobian);
    jacobian
}

/// The mass matrix whose free-joint columns the derivatives use: over C's base parameters
/// by [`crba::mass_matrix_packed`] when `packed` (its columns' wrenches are the ones the
/// packed recursion carries, I^C_j s_j), else over its own, column by column.
fn free_columns_mass_matrix(
    g: &Graph,
    model: &Model,
    expansion: (&[JointTransform], &[BodyInertia]),
    v: &[Node],
    (basis, packed): (&CoriolisBasis, bool),
) -> Vec<Vec<Node>> {
    let (transforms, inertias) = expansion;
    if packed {
        let c_inertias = basis.get_or_init(|| coriolis_inertias(g, model, expansion, v));
        crba::mass_matrix_packed(g, model, transforms, c_inertias)
    } else {
        regrouped_mass_matrix(g, model, transforms, inertias, false)
    }
}

/// Writes the columns of ∂τ/∂q of a free joint on the ground from M (`mass`, built when
/// there is one; [`free_joint_derivatives::configuration_column`]; no loads in world axes).
fn fill_free_configuration_columns(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    mass: impl Fn() -> Vec<Vec<Node>>,
    jacobian: &mut [Vec<Node>],
) {
    for (body, transform) in model.bodies.iter().zip(transforms) {
        if body.joint.kind != JointKind::Free || body.parent.is_some() {
            continue;
        }
        let m = mass();
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
        (With::Array(Array::V), VelocityColumns::Coriolis) => {
            velocity_jacobian_by_coriolis(g, model, expansion, v, (basis, false))
        }
        (With::Array(Array::V), VelocityColumns::Analytic { packed }) => {
            velocity_jacobian_by_coriolis(g, model, expansion, v, (basis, packed))
        }
        (With::Configuration, VelocityColumns::Coriolis) => {
            configuration_jacobian_with_free_columns(g, model, expansion, tau)
        }
        (With::Configuration, VelocityColumns::Analytic { packed }) => {
            configuration_jacobian_analytic(g, model, expansion, (tau, v), (basis, packed))
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
            VelocityColumns::Analytic { .. } => cost * 20 / 19,
            _ => cost,
        }
    };
    let candidates: Vec<_> = velocity_columns(model).into_iter().map(expand).collect();
    take_cheapest(candidates, cost)
}

pub(super) fn inverse_dynamics_derivatives(model: &Model) -> Expanded {
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
        VelocityColumns::Analytic { packed } => &format!(
            "the analytical Newton–Euler derivative recursion for ∂τ/∂q over the Coriolis \
             matrix's composite terms, and ∂τ/∂q̇ = 2 C(q, q̇) + diag(b) (C the \
             Christoffel-consistent Coriolis matrix; a free joint's columns from M and C){}",
            side_by_side(packed)
        ),
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

/// The candidate of least `cost` (each costed once), the first of equal costs, taken out
/// of `candidates`, which holds at least one.
fn take_cheapest<T>(mut candidates: Vec<T>, cost: impl Fn(&T) -> usize) -> T {
    let best = (0..candidates.len())
        .min_by_key(|&k| cost(&candidates[k]))
        .unwrap_or(0);
    candidates.swap_remove(best)
}

pub(super) fn forward_dynamics_derivatives(model: &Model) -> Expanded {
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
        let outputs =
            forward_dynamics_derivatives_by_chain_rule(&g, &t, &i, model, method, velocity);
        let (output, solves) = take_cheapest(outputs, |(output, _)| output_cost(&g, output));
        let tau_by = match velocity {
            VelocityColumns::ForwardMode => "forward-mode derivatives of Newton–Euler",
            VelocityColumns::Coriolis => {
                "forward-mode derivatives of Newton–Euler for ∂τ/∂q, ∂τ/∂q̇ = 2 C(q, q̇) + diag(b), \
                 a free joint's columns from M and C"
            }
            VelocityColumns::Analytic { packed } => &format!(
                "the analytical derivative recursion of Newton–Euler for ∂τ/∂q, \
                 ∂τ/∂q̇ = 2 C(q, q̇) + diag(b), a free joint's columns from M and C{}",
                side_by_side(packed)
            ),
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
    let (graph, output, how) = take_cheapest(candidates, |(g, output, _)| output_cost(g, output));
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

/// What the docs add for the recursion over isomorphic limbs side by side.
fn side_by_side(packed: bool) -> &'static str {
    if packed {
        ", isomorphic limbs computed side by side"
    } else {
        ""
    }
}

/// −x, on the pack `x` is a lane of where it is one (a packed ∂τ's rows share it).
fn negated_entry(g: &Graph, x: Node) -> Node {
    g.lanewise(&[x], |x| g.neg(x[0]))
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
    let m = regrouped_mass_matrix(g, model, t, i, false);
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
                let column = b.iter().map(|row| negated_entry(g, row[c])).collect();
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
            .map(|row| row.into_iter().map(|x| negated_entry(g, x)).collect())
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
pub(super) fn mass_matrix_inverse(model: &Model) -> Expanded {
    let (graph, output, how) =
        take_cheapest(mass_matrix_inverse_candidates(model), |(g, output, _)| {
            output_cost(g, output)
        });
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
        let rows = ldlt::inverse(&g, model, regrouped_mass_matrix(&g, model, &t, &i, true));
        (g, Output::Matrix(rows), "")
    };
    let by_loop = {
        let (g, t, i) = fresh_graph(model);
        let half = ldlt::inverse_halfway(&g, model, regrouped_mass_matrix(&g, model, &t, &i, true));
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

/// The derivatives of the generalized momentum p = M(q) q̇ and of its rate
/// ṗ = Ṁ q̇ + M q̈ = Ṁ q̇ + τ − (C q̇ + g + b q̇ − Q), the Euler–Lagrange equations
/// d/dt ∂L/∂q̇ = ∂L/∂q + τ + Q − b q̇ solved for the momentum's rate (∂L/∂q = Cᵀ q̇ − g in
/// joint coordinates, since Ṁ = C + Cᵀ). Ṁ q̇ is M(q) v differentiated along q̇ = v
/// ([`derivatives::along_velocity`]), the bracket is the Newton–Euler bias with the loads,
/// and the Jacobians are forward mode over both: second derivatives of M, which no other
/// output holds (a variational integrator's exact Newton Jacobian needs them).
pub(super) fn momentum_derivatives(model: &Model) -> Expanded {
    let (g, t, i) = fresh_graph(model);
    let v = inputs(&g, Array::V, model.nv);
    let mass = regrouped_mass_matrix(&g, model, &t, &i, false);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::functions::tests::{chain, compile};
    use crate::ir::Function;
    use proc_macro2::TokenStream;
    use quote::{format_ident, quote};

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
        let m = regrouped_mass_matrix(&g, &model, &t, &i, false);
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

    /// The analytical recursion's ∂τ/∂q, body by body and packed, takes the values forward
    /// mode gives, on a free base carrying two branches ([`floating_branches`]) at a state
    /// with accelerations; and it is what a spatial 7-link arm chooses, while loads keep
    /// forward mode.
    #[test]
    fn analytic_configuration_columns_are_forward_modes() {
        let model = floating_branches();
        assert!(rnea_derivatives::applies(&model));
        let (g, t, i) = fresh_graph(&model);
        let (tau, v) = inverse_dynamics_on(&g, &model, &t, &i);
        let [forward, analytic, packed] = [
            VelocityColumns::ForwardMode,
            VelocityColumns::Analytic { packed: false },
            VelocityColumns::Analytic { packed: true },
        ]
        .map(|way| {
            let rows = inverse_dynamics_jacobian(
                &g,
                &model,
                (&t, &i),
                (&tau, &v),
                (With::Configuration, way),
                &CoriolisBasis::new(),
            );
            g.eval(sample_input, &rows.concat())
        });
        for (k, a) in forward.iter().enumerate() {
            for (way, b) in [("analytical", analytic[k]), ("packed", packed[k])] {
                assert!(
                    (a - b).abs() <= 1e-12 * (1.0 + a.abs()),
                    "∂τ/∂q entry {k}: forward mode {a}, {way} {b}"
                );
            }
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
        // Mirrored legs and arms on a free base: the recursion over slots, side by side.
        let biped = compile(crate::expand::tests::humanoid_declaration(quote! {
            outputs: [inverse_dynamics_derivatives];
        }));
        assert!(doc(&biped).contains("side by side"), "{}", doc(&biped));
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
