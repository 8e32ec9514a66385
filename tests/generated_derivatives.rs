//! The generated derivatives of the dynamics and M⁻¹:
//! - against Pinocchio's `computeRNEADerivatives` (∂τ/∂q, ∂τ/∂v), `computeABADerivatives`
//!   (∂q̈/∂q, ∂q̈/∂v) and its M⁻¹ for the five anchor robots, imported from the same URDF
//!   files, at Pinocchio's 20 sampled states (`tests/data/pinocchio_ext/<name>_derivatives.json`),
//!   within 1e-10 · (1 + max |entry|) per matrix, and the same for the URDF import's
//!   branched robot on a free base, 13 dof (`branched_derivatives.json`, written by
//!   `models/tools/pinocchio_branched_derivatives.py`);
//! - on a free-floating branched tree with a prismatic joint, against central differences
//!   along q ⊕ t e_j (the free base moved on its manifold by `integrate_configuration`, so
//!   the q-columns are in the tangent space, as Pinocchio's) and along v, and M⁻¹ M = 1.

use dynamics_runtime::{mechanism, Mechanism};
use dynamics_tests::dual_derivatives::{
    assert_derivatives_are_the_reference_dual_numbers, dual_reference_column, GeneratedDerivatives,
};
use dynamics_tests::free_tree;
use dynamics_tests::into_twins::{assert_same, state};
use serde::Deserialize;

mechanism! {
    pub struct PendulumDerivatives;
    urdf: "../models/urdf/pendulum.urdf";
    gravity: [0.0, -9.81, 0.0];
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
}

mechanism! {
    pub struct DoublePendulumDerivatives;
    urdf: "../models/urdf/double_pendulum.urdf";
    gravity: [0.0, -9.81, 0.0];
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
}

mechanism! {
    pub struct Planar3Derivatives;
    urdf: "../models/urdf/planar3.urdf";
    gravity: [0.0, -9.81, 0.0];
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
    allow: [triangle_inequality];
}

mechanism! {
    pub struct Ur5Derivatives;
    urdf: "../models/urdf/ur5.urdf";
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
}

mechanism! {
    pub struct PandaDerivatives;
    urdf: "../models/urdf/panda.urdf";
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
}

mechanism! {
    /// The URDF import's branched test robot on a free base (13 dof, a prismatic joint), its
    /// damping left out as Pinocchio's algorithms leave it out.
    pub struct BranchedDerivatives;
    urdf: "data/urdf/branched.urdf";
    floating_base: true;
    urdf_damping: false;
    outputs: [inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse];
}

mechanism! {
    /// A free-floating base with two branches, one ending in a slider.
    pub struct FreeTreeDerivatives;
    outputs: [inverse_dynamics, forward_dynamics, mass_matrix, inverse_dynamics_derivatives,
              forward_dynamics_derivatives_into, mass_matrix_inverse, momentum_derivatives];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    joint float: free(ground -> base) { damping: 0.15, armature: 0.02 }
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3), damping: 0.2 }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0], armature: 0.05 }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
}

#[derive(Deserialize)]
struct Sample {
    q: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    tau: Vec<f64>,
    dtau_dq: Vec<Vec<f64>>,
    dtau_dv: Vec<Vec<f64>>,
    ddq_dq: Vec<Vec<f64>>,
    ddq_dv: Vec<Vec<f64>>,
    minv: Vec<Vec<f64>>,
}

fn samples(name: &str) -> Vec<Sample> {
    dynamics_tests::pinocchio_ext_samples(name, "derivatives")
}

/// Asserts every entry within `tolerance · (1 + max |expected|)`.
fn assert_matrix<const R: usize, const C: usize>(
    got: &[[f64; C]; R],
    expected: &[Vec<f64>],
    tolerance: f64,
    what: &str,
) {
    let scale = 1.0
        + expected
            .iter()
            .flatten()
            .fold(0.0_f64, |m, x| m.max(x.abs()));
    for r in 0..R {
        for c in 0..C {
            let (g, e) = (got[r][c], expected[r][c]);
            assert!(
                (g - e).abs() <= tolerance * scale,
                "{what}[{r}][{c}]: generated {g}, expected {e} (scale {scale})"
            );
        }
    }
}

type Pair<const N: usize> = ([[f64; N]; N], [[f64; N]; N]);

/// The three derivative functions of one robot.
struct Derivatives<const NQ: usize, const NV: usize> {
    inverse: fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> Pair<NV>,
    forward: fn(&[f64; NQ], &[f64; NV], &[f64; NV]) -> Pair<NV>,
    minv: fn(&[f64; NQ]) -> [[f64; NV]; NV],
}

/// The three derivative functions of a generated mechanism, at f64.
macro_rules! derivatives_of {
    ($m:ty) => {
        Derivatives {
            inverse: <$m>::inverse_dynamics_derivatives::<f64>,
            forward: <$m>::forward_dynamics_derivatives::<f64>,
            minv: <$m>::mass_matrix_inverse::<f64>,
        }
    };
}

fn check_against_pinocchio<const NQ: usize, const NV: usize>(name: &str, f: &Derivatives<NQ, NV>) {
    for (k, s) in samples(name).iter().enumerate() {
        let q: [f64; NQ] = s.q.clone().try_into().expect("nq");
        let v: [f64; NV] = s.v.clone().try_into().expect("nv");
        let a: [f64; NV] = s.a.clone().try_into().expect("nv");
        let tau: [f64; NV] = s.tau.clone().try_into().expect("nv");
        let (dtau_dq, dtau_dv) = (f.inverse)(&q, &v, &a);
        assert_matrix(
            &dtau_dq,
            &s.dtau_dq,
            1e-10,
            &format!("{name} sample {k} ∂τ/∂q"),
        );
        assert_matrix(
            &dtau_dv,
            &s.dtau_dv,
            1e-10,
            &format!("{name} sample {k} ∂τ/∂v"),
        );
        let (ddq_dq, ddq_dv) = (f.forward)(&q, &v, &tau);
        assert_matrix(
            &ddq_dq,
            &s.ddq_dq,
            1e-10,
            &format!("{name} sample {k} ∂q̈/∂q"),
        );
        assert_matrix(
            &ddq_dv,
            &s.ddq_dv,
            1e-10,
            &format!("{name} sample {k} ∂q̈/∂v"),
        );
        assert_matrix(
            &(f.minv)(&q),
            &s.minv,
            1e-10,
            &format!("{name} sample {k} M⁻¹"),
        );
    }
}

#[test]
fn derivatives_match_pinocchio() {
    check_against_pinocchio("pendulum", &derivatives_of!(PendulumDerivatives));
    check_against_pinocchio(
        "double_pendulum",
        &derivatives_of!(DoublePendulumDerivatives),
    );
    check_against_pinocchio("planar3", &derivatives_of!(Planar3Derivatives));
    check_against_pinocchio("ur5", &derivatives_of!(Ur5Derivatives));
    check_against_pinocchio("panda", &derivatives_of!(PandaDerivatives));
}

/// A URDF robot on a free base: Pinocchio's free flyer (q = [x, y, z, qx, qy, qz, qw],
/// v = [v_lin, ω] in the body frame) and its q-derivative in the tangent space, the
/// increment in the body frame, are the generated code's conventions too.
#[test]
fn free_base_derivatives_match_pinocchio() {
    check_against_pinocchio("branched", &derivatives_of!(BranchedDerivatives));
}

/// Central differences of `f` along q ⊕ t e_j and along v + t e_j, column by column.
fn central_differences(
    f: impl Fn(&[f64; 10], &[f64; 9]) -> [f64; 9],
    q: &[f64; 10],
    v: &[f64; 9],
) -> Pair<9> {
    let h = 1e-6;
    let (mut by_q, mut by_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9]);
    for col in 0..9 {
        let (plus, minus) = (
            f(&free_tree::moved(q, &free_tree::unit(col), h), v),
            f(&free_tree::moved(q, &free_tree::unit(col), -h), v),
        );
        let (mut v_plus, mut v_minus) = (*v, *v);
        v_plus[col] += h;
        v_minus[col] -= h;
        let (dv_plus, dv_minus) = (f(q, &v_plus), f(q, &v_minus));
        for row in 0..9 {
            by_q[row][col] = (plus[row] - minus[row]) / (2.0 * h);
            by_v[row][col] = (dv_plus[row] - dv_minus[row]) / (2.0 * h);
        }
    }
    (by_q, by_v)
}

fn rows(m: &[[f64; 9]; 9]) -> Vec<Vec<f64>> {
    m.iter().map(|r| r.to_vec()).collect()
}

#[test]
fn derivatives_of_a_free_tree_are_the_central_differences() {
    for k in 0..6 {
        let (q, v, a) = (
            free_tree::configuration(k),
            free_tree::velocity(k),
            free_tree::acceleration(k),
        );
        let (dtau_dq, dtau_dv) = FreeTreeDerivatives::inverse_dynamics_derivatives(&q, &v, &a);
        let (fd_q, fd_v) = central_differences(
            |q, v| FreeTreeDerivatives::inverse_dynamics(q, v, &a),
            &q,
            &v,
        );
        assert_matrix(&dtau_dq, &rows(&fd_q), 1e-7, &format!("state {k} ∂τ/∂q"));
        assert_matrix(&dtau_dv, &rows(&fd_v), 1e-7, &format!("state {k} ∂τ/∂v"));
        let tau = FreeTreeDerivatives::inverse_dynamics(&q, &v, &a);
        let (ddq_dq, ddq_dv) = FreeTreeDerivatives::forward_dynamics_derivatives(&q, &v, &tau);
        let (fd_q, fd_v) = central_differences(
            |q, v| FreeTreeDerivatives::forward_dynamics(q, v, &tau),
            &q,
            &v,
        );
        assert_matrix(&ddq_dq, &rows(&fd_q), 1e-6, &format!("state {k} ∂q̈/∂q"));
        assert_matrix(&ddq_dv, &rows(&fd_v), 1e-6, &format!("state {k} ∂q̈/∂v"));
        // M⁻¹ M = 1.
        let (m, m_inv) = (
            FreeTreeDerivatives::mass_matrix(&q),
            FreeTreeDerivatives::mass_matrix_inverse(&q),
        );
        let mut product = [[0.0; 9]; 9];
        for r in 0..9 {
            for c in 0..9 {
                product[r][c] = (0..9).map(|i| m_inv[r][i] * m[i][c]).sum();
            }
        }
        let identity: Vec<Vec<f64>> = (0..9)
            .map(|r| (0..9).map(|c| if r == c { 1.0 } else { 0.0 }).collect())
            .collect();
        assert_matrix(&product, &identity, 1e-12, &format!("state {k} M⁻¹ M"));
    }
}

/// The same derivatives by dual numbers, exact to rounding: the generated inverse and
/// forward dynamics evaluated at `Dual<f64>` (q moved along q ⊕ t e_j with a dual t, v
/// along e_j), and, independently of the generated code, the runtime reference's
/// Newton–Euler and articulated-body algorithms at `Dual<f64>`; both within 1e-12 of the
/// generated derivative outputs.
#[test]
fn derivatives_of_a_free_tree_are_the_dual_number_derivatives() {
    use dynamics_runtime::{integrate_configuration, Dual, Mechanism, Reference};
    type D = Dual<f64>;
    let model = FreeTreeDerivatives::model();
    let mut reference = Reference::<D>::new(&model);
    let constant = |x: &[f64]| -> Vec<D> { x.iter().map(|&x| D::constant(x)).collect() };
    for k in 0..6 {
        let (q, v, a) = (
            free_tree::configuration(k),
            free_tree::velocity(k),
            free_tree::acceleration(k),
        );
        let tau = FreeTreeDerivatives::inverse_dynamics(&q, &v, &a);
        let (dtau_dq, dtau_dv) = FreeTreeDerivatives::inverse_dynamics_derivatives(&q, &v, &a);
        let (ddq_dq, ddq_dv) = FreeTreeDerivatives::forward_dynamics_derivatives(&q, &v, &tau);
        let (mut by_q, mut by_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9]);
        let (mut ref_q, mut ref_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9]);
        let (mut acc_q, mut acc_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9]);
        let (mut acc_ref_q, mut acc_ref_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9]);
        for col in 0..9 {
            // q ⊕ t e_col at t = 0 + ε: the tangent-space direction of the generated outputs.
            let mut q_moved = [D::constant(0.0); 10];
            let unit = constant(&free_tree::unit(col));
            integrate_configuration(
                &constant(&q),
                &unit,
                D::variable(0.0),
                &[(0, 0)],
                &mut q_moved,
            );
            let mut v_moved: [D; 9] = std::array::from_fn(|i| D::constant(v[i]));
            v_moved[col] = D::variable(v[col]);
            let (q_d, v_d): ([D; 10], [D; 9]) = (
                std::array::from_fn(|i| D::constant(q[i])),
                std::array::from_fn(|i| D::constant(v[i])),
            );
            let (a_d, tau_d): ([D; 9], [D; 9]) = (
                std::array::from_fn(|i| D::constant(a[i])),
                std::array::from_fn(|i| D::constant(tau[i])),
            );
            let columns = [
                (
                    FreeTreeDerivatives::inverse_dynamics(&q_moved, &v_d, &a_d),
                    &mut by_q,
                ),
                (
                    FreeTreeDerivatives::inverse_dynamics(&q_d, &v_moved, &a_d),
                    &mut by_v,
                ),
                (
                    FreeTreeDerivatives::forward_dynamics(&q_moved, &v_d, &tau_d),
                    &mut acc_q,
                ),
                (
                    FreeTreeDerivatives::forward_dynamics(&q_d, &v_moved, &tau_d),
                    &mut acc_v,
                ),
            ];
            for (out, matrix) in columns {
                for row in 0..9 {
                    matrix[row][col] = out[row].derivative;
                }
            }
            // The reference's τ (inverse) or q̈ (forward) at the moved inputs: its ε parts.
            let mut reference_column = |q_in: &[D], v_in: &[D], inverse: bool| {
                dual_reference_column::<9>(&mut reference, (q_in, v_in), (&a_d, &tau_d), inverse)
            };
            let columns = [
                (reference_column(&q_moved, &v_d, true), &mut ref_q),
                (reference_column(&q_d, &v_moved, true), &mut ref_v),
                (reference_column(&q_moved, &v_d, false), &mut acc_ref_q),
                (reference_column(&q_d, &v_moved, false), &mut acc_ref_v),
            ];
            for (out, matrix) in columns {
                for row in 0..9 {
                    matrix[row][col] = out[row];
                }
            }
        }
        let state = |what: &str| format!("state {k} {what}");
        assert_matrix(
            &dtau_dq,
            &rows(&by_q),
            1e-12,
            &state("∂τ/∂q, generated at Dual"),
        );
        assert_matrix(
            &dtau_dv,
            &rows(&by_v),
            1e-12,
            &state("∂τ/∂v, generated at Dual"),
        );
        assert_matrix(
            &dtau_dq,
            &rows(&ref_q),
            1e-12,
            &state("∂τ/∂q, reference at Dual"),
        );
        assert_matrix(
            &dtau_dv,
            &rows(&ref_v),
            1e-12,
            &state("∂τ/∂v, reference at Dual"),
        );
        assert_matrix(
            &ddq_dq,
            &rows(&acc_q),
            1e-11,
            &state("∂q̈/∂q, generated at Dual"),
        );
        assert_matrix(
            &ddq_dv,
            &rows(&acc_v),
            1e-11,
            &state("∂q̈/∂v, generated at Dual"),
        );
        assert_matrix(
            &ddq_dq,
            &rows(&acc_ref_q),
            1e-11,
            &state("∂q̈/∂q, reference at Dual"),
        );
        assert_matrix(
            &ddq_dv,
            &rows(&acc_ref_v),
            1e-11,
            &state("∂q̈/∂v, reference at Dual"),
        );
    }
}

/// Central differences in double-double arithmetic (about 32 digits): with a step of 1e-9
/// the truncation error is ~1e-18 and the rounding error ~1e-23, so the differences are the
/// derivatives to far better than f64 resolution; the generated derivatives (in f64) agree
/// within 1e-9 · (1 + max |entry|), along q ⊕ t e_j and v + t e_j, on the free tree.
#[test]
fn derivatives_of_a_free_tree_are_the_double_double_central_differences() {
    use dynamics_runtime::{integrate_configuration, DoubleDouble};
    type Dd = DoubleDouble;
    let dd = |x: &[f64]| -> Vec<Dd> { x.iter().map(|&x| Dd::new(x)).collect() };
    let h = Dd::new(1e-9);
    for k in 0..3 {
        let (q, v, a) = (
            free_tree::configuration(k),
            free_tree::velocity(k),
            free_tree::acceleration(k),
        );
        let tau = FreeTreeDerivatives::inverse_dynamics(&q, &v, &a);
        let (dtau_dq, dtau_dv) = FreeTreeDerivatives::inverse_dynamics_derivatives(&q, &v, &a);
        let (ddq_dq, ddq_dv) = FreeTreeDerivatives::forward_dynamics_derivatives(&q, &v, &tau);
        let (q_dd, v_dd, a_dd, tau_dd) = (dd(&q), dd(&v), dd(&a), dd(&tau));
        let arrays = |q: &[Dd], v: &[Dd]| -> ([Dd; 10], [Dd; 9]) {
            (std::array::from_fn(|i| q[i]), std::array::from_fn(|i| v[i]))
        };
        let (a9, tau9): ([Dd; 9], [Dd; 9]) = (
            std::array::from_fn(|i| a_dd[i]),
            std::array::from_fn(|i| tau_dd[i]),
        );
        let mut columns = [[[0.0; 9]; 9]; 4];
        for col in 0..9 {
            let unit = dd(&free_tree::unit(col));
            let moved = |t: Dd| {
                let mut out = [Dd::new(0.0); 10];
                integrate_configuration(&q_dd, &unit, t, &[(0, 0)], &mut out);
                out
            };
            let shifted = |t: Dd| {
                let mut out = v_dd.clone();
                out[col] += t;
                out
            };
            let (q_plus, q_minus) = (moved(h), moved(-h));
            let (v_plus, v_minus) = (shifted(h), shifted(-h));
            let (qv, vv) = arrays(&q_dd, &v_dd);
            let (vp, vm): ([Dd; 9], [Dd; 9]) =
                (arrays(&q_dd, &v_plus).1, arrays(&q_dd, &v_minus).1);
            let differences = [
                (
                    FreeTreeDerivatives::inverse_dynamics(&q_plus, &vv, &a9),
                    FreeTreeDerivatives::inverse_dynamics(&q_minus, &vv, &a9),
                ),
                (
                    FreeTreeDerivatives::inverse_dynamics(&qv, &vp, &a9),
                    FreeTreeDerivatives::inverse_dynamics(&qv, &vm, &a9),
                ),
                (
                    FreeTreeDerivatives::forward_dynamics(&q_plus, &vv, &tau9),
                    FreeTreeDerivatives::forward_dynamics(&q_minus, &vv, &tau9),
                ),
                (
                    FreeTreeDerivatives::forward_dynamics(&qv, &vp, &tau9),
                    FreeTreeDerivatives::forward_dynamics(&qv, &vm, &tau9),
                ),
            ];
            for (matrix, (plus, minus)) in columns.iter_mut().zip(differences) {
                for row in 0..9 {
                    matrix[row][col] = ((plus[row] - minus[row]) / (h + h)).to_f64();
                }
            }
        }
        let [by_q, by_v, acc_q, acc_v] = columns;
        let state = |what: &str| format!("state {k} {what}, double-double differences");
        assert_matrix(&dtau_dq, &rows(&by_q), 1e-9, &state("∂τ/∂q"));
        assert_matrix(&dtau_dv, &rows(&by_v), 1e-9, &state("∂τ/∂v"));
        assert_matrix(&ddq_dq, &rows(&acc_q), 1e-9, &state("∂q̈/∂q"));
        assert_matrix(&ddq_dv, &rows(&acc_v), 1e-9, &state("∂q̈/∂v"));
    }
}

mechanism! {
    /// A three-joint arm with a force in world axes, a body-axes wrench and a couple: its
    /// derivatives have a third matrix, with respect to the `loads` inputs.
    pub struct LoadedArmDerivatives;
    outputs: [inverse_dynamics, forward_dynamics, mass_matrix_into, coriolis_matrix,
              inverse_dynamics_derivatives_into, forward_dynamics_derivatives, momentum_derivatives,
              joint_placements_into];
    body upper { mass: 2.0, com: [0.0, 0.0, 0.2], shape: cylinder(radius: 0.04, length: 0.4, axis: z) }
    body fore { mass: 1.2, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }
    body tip { mass: 0.3, com: [0.05, 0.0, 0.01], shape: box(size: [0.1, 0.04, 0.03]) }
    joint shoulder: revolute(ground -> upper) { axis: z }
    joint elbow: revolute(upper -> fore) { axis: y, at: [0.0, 0.0, 0.4], damping: 0.1 }
    joint wrist: prismatic(fore -> tip) { axis: x, at: [0.3, 0.0, 0.0] }
    load push: force on tip at [0.1, 0.01, 0.0] in world;
    load grip: wrench on fore at [0.2, 0.0, 0.02];
    load spin: couple on upper;
}

/// `x` as dual numbers, element `at` (if any) the variable: ε parts are then derivatives
/// with respect to that element.
fn seeded<const N: usize>(x: &[f64; N], at: Option<usize>) -> [dynamics_runtime::Dual<f64>; N] {
    use dynamics_runtime::Dual;
    std::array::from_fn(|i| {
        if Some(i) == at {
            Dual::variable(x[i])
        } else {
            Dual::constant(x[i])
        }
    })
}

/// A generated derivative `got` within 1e-12 · (1 + |expected|) of the dual numbers' one.
fn assert_dual(got: f64, expected: f64, what: &str) {
    assert!(
        (got - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
        "{what}: generated {got}, dual numbers {expected}"
    );
}

/// With loads the derivative outputs have a third matrix, ∂/∂loads (nv × 12 here); all
/// three of each output against dual numbers through the generated functions (loads
/// nonzero), within 1e-12.
#[test]
fn derivatives_with_loads_include_the_loads_and_are_the_dual_number_derivatives() {
    let (q, v, a) = ([0.4, -0.7, 0.12], [1.1, -0.3, 0.5], [0.2, 0.9, -1.4]);
    let loads: [f64; 12] = std::array::from_fn(|i| ((i as f64) * 0.77 + 0.1).sin() * 3.0);
    let tau = LoadedArmDerivatives::inverse_dynamics(&q, &v, &a, &loads);
    let (dtau_dq, dtau_dv, dtau_dl) =
        LoadedArmDerivatives::inverse_dynamics_derivatives(&q, &v, &a, &loads);
    let (ddq_dq, ddq_dv, ddq_dl) =
        LoadedArmDerivatives::forward_dynamics_derivatives(&q, &v, &tau, &loads);
    // (which input is seeded: 0 q, 1 v, 2 loads; its element) → the ε parts of τ and q̈.
    let column = |input: usize, j: usize| {
        let (qd, vd, ld) = (
            seeded(&q, (input == 0).then_some(j)),
            seeded(&v, (input == 1).then_some(j)),
            seeded(&loads, (input == 2).then_some(j)),
        );
        let (ad, taud) = (seeded(&a, None), seeded(&tau, None));
        (
            LoadedArmDerivatives::inverse_dynamics(&qd, &vd, &ad, &ld).map(|x| x.derivative),
            LoadedArmDerivatives::forward_dynamics(&qd, &vd, &taud, &ld).map(|x| x.derivative),
        )
    };
    for row in 0..3 {
        for j in 0..3 {
            let (by_q, acc_q) = column(0, j);
            let (by_v, acc_v) = column(1, j);
            assert_dual(dtau_dq[row][j], by_q[row], &format!("∂τ/∂q[{row}][{j}]"));
            assert_dual(dtau_dv[row][j], by_v[row], &format!("∂τ/∂v[{row}][{j}]"));
            assert_dual(ddq_dq[row][j], acc_q[row], &format!("∂q̈/∂q[{row}][{j}]"));
            assert_dual(ddq_dv[row][j], acc_v[row], &format!("∂q̈/∂v[{row}][{j}]"));
        }
        for j in 0..12 {
            let (by_l, acc_l) = column(2, j);
            assert_dual(
                dtau_dl[row][j],
                by_l[row],
                &format!("∂τ/∂loads[{row}][{j}]"),
            );
            assert_dual(
                ddq_dl[row][j],
                acc_l[row],
                &format!("∂q̈/∂loads[{row}][{j}]"),
            );
        }
    }
    // The loads do work: their derivative is not all zero.
    assert!(dtau_dl.iter().flatten().any(|x| x.abs() > 1e-3));
}

mechanism! {
    /// A free base carrying a 12-link chain, pushed by a force in world axes and a couple:
    /// its forward dynamics is the articulated-body algorithm, but its forward-dynamics
    /// derivatives take q̈ from the LDLᵀ factorization their solves need anyway (the cheaper
    /// chain rule here), and end in the solve loop over all columns, the loads' six columns
    /// in a call of their own beside the 2 × 18 of q and q̇.
    pub struct FreeChainDerivatives;
    outputs: [forward_dynamics, forward_dynamics_derivatives];
    body pelvis { mass: 5.0, inertia: diag([0.05, 0.04, 0.03]) }
    joint base: free(ground -> pelvis);
    body link0 { mass: 1.0, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link1 { mass: 1.1, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link2 { mass: 1.2, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link3 { mass: 1.3, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link4 { mass: 1.4, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link5 { mass: 1.5, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link6 { mass: 1.6, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link7 { mass: 1.7, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link8 { mass: 1.8, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link9 { mass: 1.9, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link10 { mass: 2.0, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    body link11 { mass: 2.1, com: [0.01, 0.02, -0.1], inertia: [[0.01, 0.001, 0.0], [0.001, 0.012, 0.0005], [0.0, 0.0005, 0.008]] }
    joint joint0: revolute(pelvis -> link0) { axis: x, at: [0.0, 0.1, -0.1] }
    joint joint1: revolute(link0 -> link1) { axis: y, at: [0.02, 0.0, -0.2] }
    joint joint2: revolute(link1 -> link2) { axis: z, at: [0.02, 0.0, -0.2] }
    joint joint3: revolute(link2 -> link3) { axis: x, at: [0.02, 0.0, -0.2], damping: 0.3 }
    joint joint4: revolute(link3 -> link4) { axis: y, at: [0.02, 0.0, -0.2] }
    joint joint5: revolute(link4 -> link5) { axis: z, at: [0.02, 0.0, -0.2] }
    joint joint6: revolute(link5 -> link6) { axis: x, at: [0.02, 0.0, -0.2] }
    joint joint7: revolute(link6 -> link7) { axis: y, at: [0.02, 0.0, -0.2], damping: 0.7 }
    joint joint8: revolute(link7 -> link8) { axis: z, at: [0.02, 0.0, -0.2] }
    joint joint9: revolute(link8 -> link9) { axis: x, at: [0.02, 0.0, -0.2] }
    joint joint10: revolute(link9 -> link10) { axis: y, at: [0.02, 0.0, -0.2] }
    joint joint11: revolute(link10 -> link11) { axis: z, at: [0.02, 0.0, -0.2] }
    load push: force on link11 at [0.05, 0.0, -0.1] in world;
    load twist: couple on pelvis;
}

/// The three forward-dynamics derivatives of [`FreeChainDerivatives`] (q̈ from the
/// factorization of the solves, not from the articulated-body algorithm its
/// `forward_dynamics` uses; the solves as one loop, the loads' matrix of another width)
/// against dual numbers through that `forward_dynamics`, within 1e-12.
#[test]
fn forward_dynamics_derivatives_through_the_solves_factorization_are_the_dual_ones() {
    use dynamics_runtime::{integrate_configuration, Dual};
    type D = Dual<f64>;
    const NQ: usize = 19;
    const NV: usize = 18;
    const NL: usize = 6;
    let mut rng = dynamics_tests::random::SplitMix(7);
    for _ in 0..4 {
        let mut q: [f64; NQ] = std::array::from_fn(|_| rng.uniform(-1.5, 1.5));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let v: [f64; NV] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let tau: [f64; NV] = std::array::from_fn(|_| rng.uniform(-5.0, 5.0));
        let loads: [f64; NL] = std::array::from_fn(|_| rng.uniform(-20.0, 20.0));
        let (ddq_dq, ddq_dv, ddq_dl) =
            FreeChainDerivatives::forward_dynamics_derivatives(&q, &v, &tau, &loads);
        let q_d: [D; NQ] = q.map(D::constant);
        let (v_d, tau_d, l_d) = (
            v.map(D::constant),
            tau.map(D::constant),
            loads.map(D::constant),
        );
        let (mut by_q, mut by_v, mut by_l) = ([[0.0; NV]; NV], [[0.0; NV]; NV], [[0.0; NL]; NV]);
        for col in 0..NV {
            let mut unit = [D::constant(0.0); NV];
            unit[col] = D::constant(1.0);
            let mut q_moved = [D::constant(0.0); NQ];
            integrate_configuration(&q_d, &unit, D::variable(0.0), &[(0, 0)], &mut q_moved);
            let mut v_moved = v_d;
            v_moved[col] = D::variable(v[col]);
            let along_q = FreeChainDerivatives::forward_dynamics(&q_moved, &v_d, &tau_d, &l_d);
            let along_v = FreeChainDerivatives::forward_dynamics(&q_d, &v_moved, &tau_d, &l_d);
            for row in 0..NV {
                by_q[row][col] = along_q[row].derivative;
                by_v[row][col] = along_v[row].derivative;
            }
        }
        for col in 0..NL {
            let mut l_moved = l_d;
            l_moved[col] = D::variable(loads[col]);
            let along_l = FreeChainDerivatives::forward_dynamics(&q_d, &v_d, &tau_d, &l_moved);
            for row in 0..NV {
                by_l[row][col] = along_l[row].derivative;
            }
        }
        let to_rows = |m: &[[f64; NV]; NV]| m.iter().map(|r| r.to_vec()).collect::<Vec<_>>();
        assert_matrix(&ddq_dq, &to_rows(&by_q), 1e-12, "∂q̈/∂q");
        assert_matrix(&ddq_dv, &to_rows(&by_v), 1e-12, "∂q̈/∂v");
        let loads_rows = by_l.iter().map(|r| r.to_vec()).collect::<Vec<_>>();
        assert_matrix(&ddq_dl, &loads_rows, 1e-12, "∂q̈/∂loads");
        assert!(ddq_dl.iter().flatten().any(|x| x.abs() > 1e-3));
    }
}

mechanism! {
    /// A damped spatial arm with a load in world axes: its ∂τ/∂q̇ is 2 C(q, q̇) + diag(b)
    /// (cheaper here than forward mode).
    pub struct DampedArmDerivatives;
    outputs: [inverse_dynamics, inverse_dynamics_derivatives];
    body link0 { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }
    body link1 { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }
    body link2 { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }
    body link3 { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }
    body link4 { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }
    joint joint0: revolute(ground -> link0) { axis: z, at: [0.0, 0.0, 0.0], damping: 0.1 }
    joint joint1: revolute(link0 -> link1) { axis: y, at: [0.4, 0.0, 0.05], damping: 0.2 }
    joint joint2: revolute(link1 -> link2) { axis: x, at: [0.4, 0.0, 0.05], damping: 0.3 }
    joint joint3: revolute(link2 -> link3) { axis: z, at: [0.4, 0.0, 0.05], damping: 0.4 }
    joint joint4: revolute(link3 -> link4) { axis: y, at: [0.4, 0.0, 0.05], damping: 0.5 }
    load push: force on link4 at [0.1, 0.0, 0.0] in world;
}

/// ∂τ/∂q, ∂τ/∂q̇ (expanded as 2 C + diag(b)) and ∂τ/∂loads of [`DampedArmDerivatives`]
/// against dual numbers through its generated inverse dynamics, within 1e-12.
#[test]
fn velocity_derivatives_by_the_coriolis_matrix_are_the_dual_ones() {
    use dynamics_runtime::Dual;
    type D = Dual<f64>;
    const N: usize = 5;
    let mut rng = dynamics_tests::random::SplitMix(11);
    for _ in 0..4 {
        let q: [f64; N] = std::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let v: [f64; N] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let a: [f64; N] = std::array::from_fn(|_| rng.uniform(-5.0, 5.0));
        let loads: [f64; 3] = std::array::from_fn(|_| rng.uniform(-20.0, 20.0));
        let (by_q, by_v, by_loads) =
            DampedArmDerivatives::inverse_dynamics_derivatives(&q, &v, &a, &loads);
        let (q_d, v_d, a_d, l_d) = (
            q.map(D::constant),
            v.map(D::constant),
            a.map(D::constant),
            loads.map(D::constant),
        );
        let column = |q: &[D; N], v: &[D; N], l: &[D; 3]| {
            DampedArmDerivatives::inverse_dynamics(q, v, &a_d, l).map(|t| t.derivative)
        };
        let (mut dual_q, mut dual_v, mut dual_loads) =
            ([[0.0; N]; N], [[0.0; N]; N], [[0.0; 3]; N]);
        for col in 0..N {
            let (mut q_moved, mut v_moved) = (q_d, v_d);
            q_moved[col] = D::variable(q[col]);
            v_moved[col] = D::variable(v[col]);
            let (along_q, along_v) = (column(&q_moved, &v_d, &l_d), column(&q_d, &v_moved, &l_d));
            for row in 0..N {
                dual_q[row][col] = along_q[row];
                dual_v[row][col] = along_v[row];
            }
        }
        for col in 0..3 {
            let mut l_moved = l_d;
            l_moved[col] = D::variable(loads[col]);
            let along = column(&q_d, &v_d, &l_moved);
            for row in 0..N {
                dual_loads[row][col] = along[row];
            }
        }
        let to_rows = |m: &[[f64; N]; N]| m.iter().map(|r| r.to_vec()).collect::<Vec<_>>();
        assert_matrix(&by_q, &to_rows(&dual_q), 1e-12, "∂τ/∂q");
        assert_matrix(&by_v, &to_rows(&dual_v), 1e-12, "∂τ/∂q̇");
        for row in 0..N {
            for col in 0..3 {
                let (g, e) = (by_loads[row][col], dual_loads[row][col]);
                assert!(
                    (g - e).abs() <= 1e-12 * (1.0 + e.abs()),
                    "∂τ/∂loads[{row}][{col}]: {g} against {e}"
                );
            }
        }
    }
}

/// The momentum derivatives of the free tree against dual numbers through the runtime
/// reference, independently of the generated code: with p = M(q) v and
/// ṗ − τ = (C + Cᵀ) v − ID(q, v, 0) (Ṁ = C + Cᵀ for the reference's Christoffel-consistent
/// C, whose Ṁ − 2C is skew), each column is the ε part of the reference's M, C and
/// Newton–Euler at q ⊕ ε e_j (the free base on its manifold) or at v + ε e_j; within 1e-12.
#[test]
fn momentum_derivatives_of_a_free_tree_are_the_reference_dual_numbers() {
    use dynamics_runtime::{integrate_configuration, Dual, Mechanism, Reference};
    use nalgebra::DMatrix;
    type D = Dual<f64>;
    let model = FreeTreeDerivatives::model();
    let mut reference = Reference::<D>::new(&model);
    let constant = |x: &[f64]| -> Vec<D> { x.iter().map(|&x| D::constant(x)).collect() };
    for k in 0..6 {
        let (q, v) = (free_tree::configuration(k), free_tree::velocity(k));
        let (dp_dq, dpdot_dq, dpdot_dv) = FreeTreeDerivatives::momentum_derivatives(&q, &v);
        // (p, ṗ − τ) of the reference at (q, v), dual.
        let mut momentum_and_rate = |q: &[D], v: &[D]| {
            let (mut mass, mut coriolis) = (DMatrix::<D>::zeros(9, 9), DMatrix::<D>::zeros(9, 9));
            reference.mass_matrix(q, &mut mass).expect("sizes");
            reference
                .coriolis_matrix(q, v, &mut coriolis)
                .expect("sizes");
            let mut bias = [D::constant(0.0); 9];
            let zero = [D::constant(0.0); 9];
            reference
                .inverse_dynamics(q, v, &zero, None, &mut bias)
                .expect("sizes");
            let mut p = [D::constant(0.0); 9];
            let mut rate = [D::constant(0.0); 9];
            for i in 0..9 {
                for j in 0..9 {
                    p[i] += mass[(i, j)] * v[j];
                    rate[i] += (coriolis[(i, j)] + coriolis[(j, i)]) * v[j];
                }
                rate[i] -= bias[i];
            }
            (p, rate)
        };
        let (mut by_q, mut rate_q, mut rate_v) = ([[0.0; 9]; 9], [[0.0; 9]; 9], [[0.0; 9]; 9]);
        for col in 0..9 {
            let mut q_moved = [D::constant(0.0); 10];
            integrate_configuration(
                &constant(&q),
                &constant(&free_tree::unit(col)),
                D::variable(0.0),
                &[(0, 0)],
                &mut q_moved,
            );
            let mut v_moved = constant(&v);
            v_moved[col] = D::variable(v[col]);
            let (p, rate) = momentum_and_rate(&q_moved, &constant(&v));
            let (_, rate_by_v) = momentum_and_rate(&constant(&q), &v_moved);
            for row in 0..9 {
                by_q[row][col] = p[row].derivative;
                rate_q[row][col] = rate[row].derivative;
                rate_v[row][col] = rate_by_v[row].derivative;
            }
        }
        let state = |what: &str| format!("state {k} {what}, reference at Dual");
        assert_matrix(&dp_dq, &rows(&by_q), 1e-12, &state("∂p/∂q"));
        assert_matrix(&dpdot_dq, &rows(&rate_q), 1e-12, &state("∂ṗ/∂q"));
        assert_matrix(&dpdot_dv, &rows(&rate_v), 1e-12, &state("∂ṗ/∂v"));
    }
}

/// With loads and damping, ṗ = τ + Cᵀ v − g + Q − b v: the momentum derivatives against dual
/// numbers through the generated M, C and inverse dynamics (ṗ − τ = (C + Cᵀ) v − ID(q, v, 0)),
/// the fourth matrix, ∂ṗ/∂loads, included; within 1e-12.
#[test]
fn momentum_derivatives_with_loads_are_the_dual_number_derivatives() {
    use dynamics_runtime::Dual;
    type D = Dual<f64>;
    let (q, v) = ([0.4, -0.7, 0.12], [1.1, -0.3, 0.5]);
    let loads: [f64; 12] = std::array::from_fn(|i| ((i as f64) * 0.77 + 0.1).sin() * 3.0);
    let (dp_dq, dpdot_dq, dpdot_dv, dpdot_dl) =
        LoadedArmDerivatives::momentum_derivatives(&q, &v, &loads);
    // (which input is seeded: 0 q, 1 v, 2 loads; its element) → the ε parts of p and ṗ − τ.
    let column = |input: usize, j: usize| {
        let (qd, vd, ld) = (
            seeded(&q, (input == 0).then_some(j)),
            seeded(&v, (input == 1).then_some(j)),
            seeded(&loads, (input == 2).then_some(j)),
        );
        let mass = LoadedArmDerivatives::mass_matrix(&qd);
        let coriolis = LoadedArmDerivatives::coriolis_matrix(&qd, &vd);
        let bias = LoadedArmDerivatives::inverse_dynamics(&qd, &vd, &[D::constant(0.0); 3], &ld);
        let p: [f64; 3] = std::array::from_fn(|i| {
            (0..3)
                .fold(D::constant(0.0), |s, j| s + mass[i][j] * vd[j])
                .derivative
        });
        let rate: [f64; 3] = std::array::from_fn(|i| {
            ((0..3).fold(D::constant(0.0), |s, j| {
                s + (coriolis[i][j] + coriolis[j][i]) * vd[j]
            }) - bias[i])
                .derivative
        });
        (p, rate)
    };
    for row in 0..3 {
        for j in 0..3 {
            let (p_q, rate_q) = column(0, j);
            let (_, rate_v) = column(1, j);
            assert_dual(dp_dq[row][j], p_q[row], &format!("∂p/∂q[{row}][{j}]"));
            assert_dual(dpdot_dq[row][j], rate_q[row], &format!("∂ṗ/∂q[{row}][{j}]"));
            assert_dual(dpdot_dv[row][j], rate_v[row], &format!("∂ṗ/∂v[{row}][{j}]"));
        }
        for j in 0..12 {
            let (_, rate_l) = column(2, j);
            assert_dual(
                dpdot_dl[row][j],
                rate_l[row],
                &format!("∂ṗ/∂loads[{row}][{j}]"),
            );
        }
    }
    // Neither the second derivatives of M nor the loads' part is all zero.
    assert!(dpdot_dq.iter().flatten().any(|x| x.abs() > 1e-3));
    assert!(dpdot_dl.iter().flatten().any(|x| x.abs() > 1e-3));
}

/// The `_into` twins (`tests/generated_into.rs` has the rest): with loads, ∂τ is a triple
/// and joint placements a stack of poses, both written whole.
#[test]
fn the_loaded_arms_into_twins_write_a_triple_of_matrices_and_a_stack_of_poses_whole() {
    const N: usize = <LoadedArmDerivatives as Mechanism>::NV;
    const L: usize = <LoadedArmDerivatives as Mechanism>::NUM_LOAD_INPUTS;
    let n = f64::NAN;
    for seed in 0..10 {
        let (q, v, a, loads): ([f64; N], [f64; N], [f64; N], [f64; L]) = (
            state(seed),
            state(seed + 7),
            state(seed + 11),
            state(seed + 13),
        );
        let what = |f: &str| format!("loaded arm {f}, state {seed}");
        assert_same(
            LoadedArmDerivatives::mass_matrix(&q),
            [[n; N]; N],
            |o| LoadedArmDerivatives::mass_matrix_into(&q, o),
            &what("mass_matrix"),
        );
        assert_same(
            LoadedArmDerivatives::inverse_dynamics_derivatives(&q, &v, &a, &loads),
            ([[n; N]; N], [[n; N]; N], [[n; L]; N]),
            |o| LoadedArmDerivatives::inverse_dynamics_derivatives_into(&q, &v, &a, &loads, o),
            &what("∂τ"),
        );
        let poses = LoadedArmDerivatives::joint_placements(&q);
        let nan_poses = poses.map(|(r, t)| (r.map(|row| row.map(|_| n)), t.map(|_| n)));
        assert_same(
            poses,
            nan_poses,
            |o| LoadedArmDerivatives::joint_placements_into(&q, o),
            &what("joint_placements"),
        );
    }
}

/// The free tree's ∂q̈ is one piece ending in a solve loop: its twin writes the right-hand
/// sides into `out` and solves them there.
#[test]
fn the_free_trees_into_twin_solves_its_one_piece_solve_loop_in_place() {
    const NQ: usize = <FreeTreeDerivatives as Mechanism>::NQ;
    const N: usize = <FreeTreeDerivatives as Mechanism>::NV;
    let n = f64::NAN;
    for seed in 0..5 {
        let (mut q, v, tau): ([f64; NQ], [f64; N], [f64; N]) =
            (state(seed + 600), state(seed + 700), state(seed + 800));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        assert_same(
            FreeTreeDerivatives::forward_dynamics_derivatives(&q, &v, &tau),
            ([[n; N]; N], [[n; N]; N]),
            |o| FreeTreeDerivatives::forward_dynamics_derivatives_into(&q, &v, &tau, o),
            &format!("free tree ∂q̈, state {seed}"),
        );
    }
}

mechanism! {
    /// A free base on two isomorphic legs (mirror images) and an arm, without loads: its
    /// derivatives take the analytical recursion over slots, the legs side by side in the
    /// lanes of packed values, and the free base's columns from the packed mass matrix.
    pub struct BipedDerivatives;
    gravity: [0.4, -0.3, -9.81];
    outputs: [inverse_dynamics, forward_dynamics, inverse_dynamics_derivatives,
              forward_dynamics_derivatives];
    body pelvis { mass: 3.0, com: [0.01, -0.02, 0.03], inertia: [[0.04, 0.002, 0.001], [0.002, 0.03, 0.003], [0.001, 0.003, 0.035]] }
    joint base: free(ground -> pelvis) { damping: 0.1, armature: 0.02 }
    body thigh_l { mass: 1.1, com: [0.01, 0.01, -0.12], inertia: diag([0.012, 0.011, 0.002]) }
    body shin_l { mass: 0.6, com: [0.0, 0.0, -0.15], inertia: diag([0.008, 0.008, 0.001]) }
    joint hip_l: revolute(pelvis -> thigh_l) { axis: x, at: [0.0, 0.09, -0.05], rotation: rpy(0.1, 0.0, 0.0) }
    joint knee_l: revolute(thigh_l -> shin_l) { axis: y, at: [0.0, 0.0, -0.3], damping: 0.2 }
    body thigh_r { mass: 1.1, com: [0.01, -0.01, -0.12], inertia: diag([0.012, 0.011, 0.002]) }
    body shin_r { mass: 0.6, com: [0.0, 0.0, -0.15], inertia: diag([0.008, 0.008, 0.001]) }
    joint hip_r: revolute(pelvis -> thigh_r) { axis: x, at: [0.0, -0.09, -0.05], rotation: rpy(-0.1, 0.0, 0.0) }
    joint knee_r: revolute(thigh_r -> shin_r) { axis: y, at: [0.0, 0.0, -0.3], armature: 0.03 }
    body arm { mass: 0.5, com: [0.0, 0.02, 0.1], inertia: diag([0.003, 0.003, 0.0005]) }
    body hand { mass: 0.2, com: [0.05, 0.0, 0.0], shape: sphere(radius: 0.04) }
    joint shoulder: revolute(pelvis -> arm) { axis: [0.2, 1.0, 0.1], at: [0.05, 0.0, 0.2] }
    joint wrist: prismatic(arm -> hand) { axis: z, at: [0.0, 0.0, 0.25] }
}

/// The biped's ∂τ and ∂q̈ (the recursion over slots, the legs packed) are the runtime
/// reference's Newton–Euler and articulated-body algorithms at `Dual<f64>`, along
/// q ⊕ t e_j and v + t e_j, at states with velocities and accelerations.
#[test]
fn derivatives_of_a_biped_over_slots_are_the_reference_dual_numbers() {
    assert_derivatives_are_the_reference_dual_numbers(
        &BipedDerivatives::model(),
        &GeneratedDerivatives::<13, 12> {
            inverse_dynamics: BipedDerivatives::inverse_dynamics,
            inverse_dynamics_derivatives: BipedDerivatives::inverse_dynamics_derivatives,
            forward_dynamics_derivatives: BipedDerivatives::forward_dynamics_derivatives,
        },
    );
}
