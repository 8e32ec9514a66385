//! Property tests of the reference on random trees of up to 30 joints (random parents,
//! placements, axes and valid inertias; revolute and prismatic joints; sometimes a
//! free-flyer root; sometimes armature and damping): the identities that tie its algorithms
//! together (DESIGN.md, "Checks"), and gravity and bias against derivatives of the energies
//! by central differences, which no Newton–Euler pass computes.

use dynamics_runtime::{Model, Reference, Wrench};
use dynamics_tests::random::{integrate, random_state, random_tree, RandomTree, SplitMix};
use dynamics_tests::{condition_number, max_abs_diff, tolerance_scale};
use nalgebra::{DMatrix, DVector, Vector3};
use proptest::prelude::*;

/// Random external wrenches, one per body.
fn random_wrenches(model: &Model, rng: &mut SplitMix) -> Vec<Wrench<f64>> {
    let mut vector = || {
        Vector3::new(
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
            rng.uniform(-5.0, 5.0),
        )
    };
    (0..model.bodies().len())
        .map(|_| Wrench::new(vector(), vector()))
        .collect()
}

fn mass_matrix(reference: &mut Reference<f64>, q: &[f64]) -> DMatrix<f64> {
    let nv = reference.model().nv();
    let mut m = DMatrix::zeros(nv, nv);
    reference.mass_matrix(q, &mut m).expect("sizes match");
    m
}

/// Step of the central differences of the energies and of M.
const FINITE_DIFFERENCE_STEP: f64 = 1e-5;

/// Tolerance of a central difference with [`FINITE_DIFFERENCE_STEP`], relative to
/// `1 + max |value|`: its truncation error is h²/6 times a third derivative and its
/// rounding error ε |E| / h (~1e-11 · |E|); the largest error seen over 512 random trees
/// was 3e-10 of the scale, so this leaves a margin of 300 while a wrong term (a missing
/// damping, a gravity off by 1e-6 relative) still fails.
const FINITE_DIFFERENCE_TOLERANCE: f64 = 1e-7;

/// `d/dt f(integrate(q, e_i, t))` at t = 0 for every velocity coordinate i, by central
/// differences with step [`FINITE_DIFFERENCE_STEP`].
fn along_each_coordinate(model: &Model, q: &[f64], mut f: impl FnMut(&[f64]) -> f64) -> Vec<f64> {
    let h = FINITE_DIFFERENCE_STEP;
    let mut unit = vec![0.0; model.nv()];
    (0..model.nv())
        .map(|i| {
            unit[i] = 1.0;
            let plus = f(&integrate(model, q, &unit, h));
            let minus = f(&integrate(model, q, &unit, -h));
            unit[i] = 0.0;
            (plus - minus) / (2.0 * h)
        })
        .collect()
}

/// ∂V/∂q (along each velocity coordinate) by central differences of the potential energy.
fn potential_gradient(reference: &mut Reference<f64>, model: &Model, q: &[f64]) -> Vec<f64> {
    along_each_coordinate(model, q, |q_k| {
        reference.potential_energy(q_k).expect("sizes match")
    })
}

fn total_energy(reference: &mut Reference<f64>, q: &[f64], v: &[f64]) -> f64 {
    reference.kinetic_energy(q, v).expect("sizes match")
        + reference.potential_energy(q).expect("sizes match")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// CRBA against RNEA (as Pinocchio's tests do): column i of M is
    /// ID(q, 0, e_i) − ID(q, 0, 0), armature included.
    #[test]
    fn mass_matrix_columns_are_inverse_dynamics_differences(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, _, _) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let m = mass_matrix(&mut reference, &q);
        let zero = vec![0.0; nv];
        let mut gravity = vec![0.0; nv];
        reference.inverse_dynamics(&q, &zero, &zero, None, &mut gravity).expect("sizes match");
        let scale = tolerance_scale(m.iter());
        let mut unit = vec![0.0; nv];
        let mut tau = vec![0.0; nv];
        for i in 0..nv {
            unit[i] = 1.0;
            reference.inverse_dynamics(&q, &zero, &unit, None, &mut tau).expect("sizes match");
            unit[i] = 0.0;
            for k in 0..nv {
                let column_entry = tau[k] - gravity[k];
                prop_assert!(
                    (column_entry - m[(k, i)]).abs() <= 1e-11 * scale,
                    "M[{k}][{i}] = {} but ID difference = {column_entry}", m[(k, i)]
                );
            }
        }
    }

    /// M(q) is exactly symmetric and positive definite (a Cholesky factor exists).
    #[test]
    fn mass_matrix_is_symmetric_positive_definite(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, _, _) = random_state(&model, &mut SplitMix(seed));
        let m = mass_matrix(&mut reference, &q);
        prop_assert_eq!(&m, &m.transpose());
        prop_assert!(m.clone().cholesky().is_some(), "M is not positive definite: {m}");
    }

    /// ABA against RNEA: FD(q, v, ID(q, v, a, f), f) = a, with external wrenches, armature and
    /// damping. The error bound scales with the conditioning of M (random trees can be
    /// ill-conditioned), so the torque residual ID(q, v, FD) − τ is checked tightly too.
    #[test]
    fn forward_dynamics_inverts_inverse_dynamics(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let mut rng = SplitMix(seed);
        let (q, v, a) = random_state(&model, &mut rng);
        let wrenches = random_wrenches(&model, &mut rng);
        let nv = model.nv();
        let mut tau = vec![0.0; nv];
        reference.inverse_dynamics(&q, &v, &a, Some(&wrenches), &mut tau).expect("sizes match");
        let mut qdd = vec![0.0; nv];
        reference.forward_dynamics(&q, &v, &tau, Some(&wrenches), &mut qdd).expect("sizes match");
        let mut tau_again = vec![0.0; nv];
        reference
            .inverse_dynamics(&q, &v, &qdd, Some(&wrenches), &mut tau_again)
            .expect("sizes match");
        let torque_residual = max_abs_diff(&tau_again, &tau);
        prop_assert!(
            torque_residual <= 1e-10 * tolerance_scale(&tau),
            "ID(FD(τ)) − τ = {torque_residual:e}"
        );
        let m = mass_matrix(&mut reference, &q);
        let condition = condition_number(&m);
        let error = max_abs_diff(&qdd, &a);
        prop_assert!(
            error <= 1e-13 * condition.max(1.0) * tolerance_scale(&a) * nv as f64,
            "FD(ID(a)) − a = {error:e} (cond M = {condition:e})"
        );
    }

    /// The Coriolis matrix: C v = nle − g, and Ṁ − 2C is skew-symmetric, with Ṁ by a central
    /// difference of M along the motion (a free flyer's quaternion moved by the exponential
    /// map; M does not depend on the base pose anyway).
    #[test]
    fn coriolis_matrix_is_christoffel_consistent(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, v, _) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let mut c = DMatrix::zeros(nv, nv);
        reference.coriolis_matrix(&q, &v, &mut c).expect("sizes match");
        let mut nle = vec![0.0; nv];
        let mut gravity = vec![0.0; nv];
        reference.nonlinear_effects(&q, &v, &mut nle).expect("sizes match");
        reference.gravity(&q, &mut gravity).expect("sizes match");
        let c_v = &c * DVector::from_column_slice(&v);
        let velocity_product: Vec<f64> = nle.iter().zip(&gravity).map(|(n, g)| n - g).collect();
        let error = max_abs_diff(c_v.as_slice(), &velocity_product);
        prop_assert!(
            error <= 1e-11 * tolerance_scale(&nle),
            "C v − (nle − g) = {error:e}"
        );

        let h = 1e-6;
        let m_plus = mass_matrix(&mut reference, &integrate(&model, &q, &v, h));
        let m_minus = mass_matrix(&mut reference, &integrate(&model, &q, &v, -h));
        let m_dot = (m_plus - m_minus) / (2.0 * h);
        let n = &m_dot - &c * 2.0;
        let asymmetry = (&n + n.transpose()).amax();
        prop_assert!(
            asymmetry <= 1e-6 * tolerance_scale(m_dot.iter()),
            "Ṁ − 2C is not skew: max |N + Nᵀ| = {asymmetry:e}"
        );
    }

    /// Energy balance (the textbook's Ė = τ θ̇, generalized): along a motion with velocity v and
    /// acceleration a, dE/dt = τ · v for τ = ID(q, v, a), no damping (armature included: its
    /// kinetic energy and its torque). dE/dt by a central difference along q(t) with tangent
    /// v and v(t) = v + a t.
    #[test]
    fn energy_rate_is_joint_power(tree in random_tree(30), seed in any::<u64>()) {
        let model = tree.model_with_damping(false);
        let mut reference = Reference::<f64>::new(&model);
        let (q, v, a) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let mut tau = vec![0.0; nv];
        reference.inverse_dynamics(&q, &v, &a, None, &mut tau).expect("sizes match");
        let power: f64 = tau.iter().zip(&v).map(|(t, w)| t * w).sum();
        let h = 1e-5;
        let mut energy_at = |t: f64| {
            let q_t = integrate(&model, &q, &v, t);
            let v_t: Vec<f64> = v.iter().zip(&a).map(|(w, b)| w + b * t).collect();
            total_energy(&mut reference, &q_t, &v_t)
        };
        let energy_rate = (energy_at(h) - energy_at(-h)) / (2.0 * h);
        let scale = 1.0 + tau.iter().zip(&v).map(|(t, w)| (t * w).abs()).sum::<f64>();
        prop_assert!(
            (energy_rate - power).abs() <= 1e-6 * scale,
            "dE/dt = {energy_rate} but τ·v = {power}"
        );
    }

    /// Gravity is the gradient of the potential energy: g_i = dV/dt along the motion with
    /// velocity e_i (for a free flyer's coordinates, the body-frame twist e_i moving the
    /// quaternion by the exponential map), by a central difference of V(q), which the
    /// reference sums from the mass centres' heights without any Newton–Euler pass. Both
    /// `gravity(q)` and `inverse_dynamics(q, 0, 0)` must equal it.
    #[test]
    fn gravity_is_the_gradient_of_potential_energy(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, _, _) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let gradient = potential_gradient(&mut reference, &model, &q);
        let zero = vec![0.0; nv];
        let (mut g, mut id) = (vec![0.0; nv], vec![0.0; nv]);
        reference.gravity(&q, &mut g).expect("sizes match");
        reference.inverse_dynamics(&q, &zero, &zero, None, &mut id).expect("sizes match");
        let scale = tolerance_scale(&gradient);
        for (what, value) in [("gravity", &g), ("ID(q, 0, 0)", &id)] {
            let error = max_abs_diff(value, &gradient);
            prop_assert!(
                error <= FINITE_DIFFERENCE_TOLERANCE * scale,
                "{what} − ∂V/∂q = {error:e} (scale {scale:e})\n{value:?}\n{gradient:?}"
            );
        }
    }

    /// The bias from Lagrange's equations, on fixed-base trees (joint coordinates, q̇ = v):
    /// d/dt ∂T/∂q̇ − ∂T/∂q + ∂V/∂q + b q̇ at q̈ = 0 gives
    /// bias = Ṁ(q) v − ∂(½ vᵀ M v)/∂q + ∂V/∂q + b v, with Ṁ by a central difference of the
    /// CRBA's M along v and the two gradients by central differences of the energies: no
    /// Newton–Euler pass on this side. Both `bias(q, v)` and `inverse_dynamics(q, v, 0)`
    /// must equal it.
    #[test]
    fn bias_is_lagranges_velocity_and_gravity_terms(
        tree in random_tree(30), seed in any::<u64>(),
    ) {
        let tree = RandomTree { free_flyer_root: false, ..tree };
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, v, _) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let h = FINITE_DIFFERENCE_STEP;
        let m_plus = mass_matrix(&mut reference, &integrate(&model, &q, &v, h));
        let m_minus = mass_matrix(&mut reference, &integrate(&model, &q, &v, -h));
        let m_dot_v = (m_plus - m_minus) / (2.0 * h) * DVector::from_column_slice(&v);
        let kinetic_gradient = along_each_coordinate(&model, &q, |q_k| {
            reference.kinetic_energy(q_k, &v).expect("sizes match")
        });
        let potential = potential_gradient(&mut reference, &model, &q);
        let mut expected = vec![0.0; nv];
        for body in model.bodies() {
            for k in body.joint.idx_v..body.joint.idx_v + body.joint.kind.nv() {
                expected[k] = m_dot_v[k] - kinetic_gradient[k] + potential[k]
                    + body.joint.damping * v[k];
            }
        }
        let zero = vec![0.0; nv];
        let (mut bias, mut id) = (vec![0.0; nv], vec![0.0; nv]);
        reference.bias(&q, &v, &mut bias).expect("sizes match");
        reference.inverse_dynamics(&q, &v, &zero, None, &mut id).expect("sizes match");
        let scale = tolerance_scale(&expected);
        for (what, value) in [("bias", &bias), ("ID(q, v, 0)", &id)] {
            let error = max_abs_diff(value, &expected);
            prop_assert!(
                error <= FINITE_DIFFERENCE_TOLERANCE * scale,
                "{what} − Lagrange's terms = {error:e} (scale {scale:e})\n{value:?}\n{expected:?}"
            );
        }
    }
}
