//! Property tests of the reference on random trees of up to 30 joints (random parents,
//! placements, axes and valid inertias; revolute and prismatic joints; sometimes a
//! free-flyer root; sometimes armature and damping): the identities that tie its algorithms
//! together (DESIGN.md, "Checks").

use dynamics_runtime::{Model, Reference, Wrench};
use dynamics_tests::random::{integrate, random_state, random_tree, SplitMix};
use dynamics_tests::{max_abs_diff, tolerance_scale};
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
        let eigen = m.symmetric_eigenvalues();
        let condition = eigen.max() / eigen.min();
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

    /// Energy balance (the seed's Ė = τ θ̇, generalized): along a motion with velocity v and
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

    /// The named variants of inverse dynamics agree: bias = ID(q, v, 0) = nle + b v, and
    /// g = ID(q, 0, 0).
    #[test]
    fn bias_and_gravity_are_inverse_dynamics(tree in random_tree(30), seed in any::<u64>()) {
        let model = tree.model();
        let mut reference = Reference::<f64>::new(&model);
        let (q, v, _) = random_state(&model, &mut SplitMix(seed));
        let nv = model.nv();
        let zero = vec![0.0; nv];
        let (mut id, mut bias, mut nle, mut g) =
            (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
        reference.inverse_dynamics(&q, &v, &zero, None, &mut id).expect("sizes match");
        reference.bias(&q, &v, &mut bias).expect("sizes match");
        reference.nonlinear_effects(&q, &v, &mut nle).expect("sizes match");
        prop_assert_eq!(&bias, &id);
        let mut damped = nle.clone();
        for body in model.bodies() {
            for k in body.joint.idx_v..body.joint.idx_v + body.joint.kind.nv() {
                damped[k] += body.joint.damping * v[k];
            }
        }
        prop_assert!(max_abs_diff(&damped, &bias) <= 1e-12 * tolerance_scale(&bias));
        reference.inverse_dynamics(&q, &zero, &zero, None, &mut id).expect("sizes match");
        reference.gravity(&q, &mut g).expect("sizes match");
        prop_assert_eq!(&g, &id);
    }
}
