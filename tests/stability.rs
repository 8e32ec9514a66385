//! Where forward dynamics is hard: a mass matrix spanning eight orders of magnitude, and an
//! arm at a kinematic singularity. Both generated methods (articulated body, LDLᵀ of M) in
//! f64 and f32 against the reference in double-double; errors are asserted against the
//! condition number of M and printed.

use dynamics_runtime::{mechanism, DoubleDouble, Mechanism, Reference};
use dynamics_tests::random::SplitMix;
use dynamics_tests::{condition_number, max_abs_dd, max_abs_diff_dd};
use models::anchors::Ur5;
use nalgebra::DMatrix;

mechanism! {
    /// A five-link spatial chain whose link masses span 1 kg to 1e-8 kg (inertias scaled
    /// alike): M(q) spans as many orders of magnitude.
    pub struct GradedChain;
    gravity: [0.0, 0.0, -9.81];
    outputs: [forward_dynamics_aba, forward_dynamics_ldlt, mass_matrix];
    body l0 { mass: 1.0, com: [0.2, 0.0, 0.0], inertia: diag([1e-3, 2e-2, 2e-2]) }
    body l1 { mass: 1e-2, com: [0.2, 0.0, 0.0], inertia: diag([1e-5, 2e-4, 2e-4]) }
    body l2 { mass: 1e-4, com: [0.2, 0.0, 0.0], inertia: diag([1e-7, 2e-6, 2e-6]) }
    body l3 { mass: 1e-6, com: [0.2, 0.0, 0.0], inertia: diag([1e-9, 2e-8, 2e-8]) }
    body l4 { mass: 1e-8, com: [0.2, 0.0, 0.0], inertia: diag([1e-11, 2e-10, 2e-10]) }
    joint j0: revolute(ground -> l0) { axis: z }
    joint j1: revolute(l0 -> l1) { axis: y, at: [0.4, 0.0, 0.0] }
    joint j2: revolute(l1 -> l2) { axis: x, at: [0.4, 0.0, 0.0] }
    joint j3: revolute(l2 -> l3) { axis: z, at: [0.4, 0.0, 0.0] }
    joint j4: revolute(l3 -> l4) { axis: y, at: [0.4, 0.0, 0.0] }
}

type Dd = DoubleDouble;

/// Relative error of an f64 result against a double-double one.
fn relative_error(got: &[f64], exact: &[Dd]) -> f64 {
    max_abs_diff_dd(got, exact) / max_abs_dd(exact)
}

#[test]
fn mass_matrix_spanning_eight_orders_both_methods_hold() {
    let model = GradedChain::model();
    let mut reference = Reference::<Dd>::new(&model);
    let mut rng = SplitMix(5);
    let (mut worst_aba, mut worst_ldlt, mut worst_cond) = (0.0_f64, 0.0_f64, 0.0_f64);
    let (mut worst_aba32, mut worst_ldlt32) = (0.0_f64, 0.0_f64);
    for _ in 0..20 {
        let draw = |rng: &mut SplitMix, s: f64| -> [f64; 5] {
            std::array::from_fn(|_| rng.uniform(-s, s))
        };
        let (q, v) = (draw(&mut rng, 3.0), draw(&mut rng, 1.0));
        // Torques scaled to the links they drive, so every acceleration is O(1).
        let tau: [f64; 5] =
            std::array::from_fn(|i| rng.uniform(-1.0, 1.0) * 10f64.powi(-2 * i as i32) * 0.05);
        let mut exact = vec![Dd::new(0.0); 5];
        reference
            .forward_dynamics(
                &q.map(Dd::new),
                &v.map(Dd::new),
                &tau.map(Dd::new),
                None,
                &mut exact,
            )
            .expect("sizes");
        let cond = condition_number(&DMatrix::from_fn(5, 5, |i, j| {
            GradedChain::mass_matrix(&q)[i][j]
        }));
        worst_cond = worst_cond.max(cond);
        worst_aba = worst_aba.max(relative_error(
            &GradedChain::forward_dynamics_aba(&q, &v, &tau),
            &exact,
        ));
        worst_ldlt = worst_ldlt.max(relative_error(
            &GradedChain::forward_dynamics_ldlt(&q, &v, &tau),
            &exact,
        ));
        let (q32, v32, t32) = (
            q.map(|x| x as f32),
            v.map(|x| x as f32),
            tau.map(|x| x as f32),
        );
        let widen = |x: [f32; 5]| x.map(f64::from);
        let aba32 = widen(GradedChain::forward_dynamics_aba(&q32, &v32, &t32));
        let ldlt32 = widen(GradedChain::forward_dynamics_ldlt(&q32, &v32, &t32));
        worst_aba32 = worst_aba32.max(relative_error(&aba32, &exact));
        worst_ldlt32 = worst_ldlt32.max(relative_error(&ldlt32, &exact));
    }
    println!(
        "graded chain, cond(M) up to {worst_cond:.1e}: relative error f64 ABA {worst_aba:.1e}, LDLᵀ {worst_ldlt:.1e}; \
         f32 ABA {worst_aba32:.1e}, LDLᵀ {worst_ldlt32:.1e}"
    );
    assert!(
        worst_cond > 1e8,
        "the chain should be ill-conditioned: {worst_cond}"
    );
    // Both stay within the backward-stable bound ε · cond(M), far from garbage.
    for (method, error) in [("articulated body", worst_aba), ("LDLᵀ", worst_ldlt)] {
        assert!(
            error < 1e-15 * worst_cond,
            "{method}: {error} with cond {worst_cond}"
        );
    }
}

#[test]
fn arm_at_a_wrist_singularity_keeps_full_accuracy() {
    // q5 = 0 aligns the UR5's first and last wrist axes (a kinematic singularity: the
    // Jacobian loses rank). M(q) stays well-conditioned and the dynamics exact there.
    let model = Ur5::model();
    let mut reference = Reference::<Dd>::new(&model);
    for q5 in [0.0, 1e-9, 1e-5] {
        let q = [0.3, -1.2, 1.1, 0.4, q5, -0.7];
        let (v, tau) = (
            [0.5, -0.3, 0.2, 1.0, 0.8, -0.6],
            [2.0, -10.0, 3.0, 0.5, -0.2, 0.1],
        );
        let mut exact = vec![Dd::new(0.0); 6];
        reference
            .forward_dynamics(
                &q.map(Dd::new),
                &v.map(Dd::new),
                &tau.map(Dd::new),
                None,
                &mut exact,
            )
            .expect("sizes");
        let error = relative_error(&Ur5::forward_dynamics(&q, &v, &tau), &exact);
        let cond = condition_number(&DMatrix::from_fn(6, 6, |i, j| Ur5::mass_matrix(&q)[i][j]));
        println!(
            "UR5 at q5 = {q5:e}: cond(M) {cond:.1e}, forward dynamics relative error {error:.1e}"
        );
        assert!(error < 1e-14 * cond, "{error} at cond {cond}");
    }
}
