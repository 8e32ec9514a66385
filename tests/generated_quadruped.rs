//! The 18-DoF quadruped (free-floating torso, four legs, a contact force on each foot):
//! every generated output against the runtime reference, with the foot forces as external
//! wrenches on the shins.

use dynamics_runtime::Wrench;
use dynamics_runtime::{Mechanism, Reference};
use dynamics_tests::random::SplitMix;
use dynamics_tests::{assert_close, condition_number};
use models::quadruped::Quadruped;
use nalgebra::{DMatrix, Vector3};

const NQ: usize = <Quadruped as Mechanism>::NQ;
const NV: usize = <Quadruped as Mechanism>::NV;
const NL: usize = <Quadruped as Mechanism>::NUM_LOAD_INPUTS;

#[test]
fn quadruped_matches_the_reference_with_foot_forces() {
    assert_eq!((NQ, NV, NL), (19, 18, 12));
    let model = Quadruped::model();
    let mut reference = Reference::<f64>::new(&model);
    let shins: Vec<usize> = ["shin_fl", "shin_fr", "shin_hl", "shin_hr"]
        .iter()
        .map(|n| model.body_index(n).expect("a shin"))
        .collect();
    let mut rng = SplitMix(2024);
    let (mut out, mut m_ref) = (vec![0.0; NV], DMatrix::zeros(NV, NV));
    for _ in 0..30 {
        let mut q: [f64; NQ] = std::array::from_fn(|_| rng.uniform(-1.5, 1.5));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        let v: [f64; NV] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
        let a: [f64; NV] = std::array::from_fn(|_| rng.uniform(-3.0, 3.0));
        let tau: [f64; NV] = std::array::from_fn(|_| rng.uniform(-5.0, 5.0));
        let loads: [f64; NL] = std::array::from_fn(|_| rng.uniform(-20.0, 40.0));
        let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
        let foot = Vector3::new(0.0, 0.0, -0.2);
        for (leg, &shin) in shins.iter().enumerate() {
            let f = Vector3::new(loads[3 * leg], loads[3 * leg + 1], loads[3 * leg + 2]);
            wrenches[shin] = Wrench::new(f, foot.cross(&f));
        }

        reference
            .inverse_dynamics(&q, &v, &a, Some(&wrenches), &mut out)
            .expect("sizes");
        assert_close(
            "inverse_dynamics",
            &Quadruped::inverse_dynamics(&q, &v, &a, &loads),
            &out,
            1e-12,
        );
        reference.gravity(&q, &mut out).expect("sizes");
        assert_close("gravity", &Quadruped::gravity(&q), &out, 1e-12);
        reference.bias(&q, &v, &mut out).expect("sizes");
        assert_close("bias", &Quadruped::bias(&q, &v), &out, 1e-12);
        reference.mass_matrix(&q, &mut m_ref).expect("sizes");
        let rows: Vec<f64> = (0..NV)
            .flat_map(|i| (0..NV).map(move |j| (i, j)))
            .map(|(i, j)| m_ref[(i, j)])
            .collect();
        assert_close(
            "mass_matrix",
            Quadruped::mass_matrix(&q).as_flattened(),
            &rows,
            1e-12,
        );
        let mut c_ref = DMatrix::zeros(NV, NV);
        reference
            .coriolis_matrix(&q, &v, &mut c_ref)
            .expect("sizes");
        let rows: Vec<f64> = (0..NV)
            .flat_map(|i| (0..NV).map(move |j| (i, j)))
            .map(|(i, j)| c_ref[(i, j)])
            .collect();
        assert_close(
            "coriolis_matrix",
            Quadruped::coriolis_matrix(&q, &v).as_flattened(),
            &rows,
            1e-12,
        );
        reference
            .forward_dynamics(&q, &v, &tau, Some(&wrenches), &mut out)
            .expect("sizes");
        let cond = condition_number(&m_ref);
        assert_close(
            "forward_dynamics",
            &Quadruped::forward_dynamics(&q, &v, &tau, &loads),
            &out,
            1e-12 * cond,
        );
        let t = reference.kinetic_energy(&q, &v).expect("sizes");
        assert_close(
            "kinetic_energy",
            &[Quadruped::kinetic_energy(&q, &v)],
            &[t],
            1e-12,
        );
        let u = reference.potential_energy(&q).expect("sizes");
        assert_close(
            "potential_energy",
            &[Quadruped::potential_energy(&q)],
            &[u],
            1e-12,
        );
        let mut reactions = vec![Wrench::zero(); model.bodies().len()];
        reference
            .joint_reactions(&q, &v, &a, Some(&wrenches), &mut reactions)
            .expect("sizes");
        let flat: Vec<f64> = reactions
            .iter()
            .flat_map(|w| w.to_vector6().iter().copied().collect::<Vec<_>>())
            .collect();
        assert_close(
            "joint_reactions",
            Quadruped::joint_reactions(&q, &v, &a, &loads).as_flattened(),
            &flat,
            1e-12,
        );
    }
}

/// The quadruped's M⁻¹, which the compiler finishes with a loop over the columns
/// (`tree_ldlt::solve_lower_columns`, the cheaper way for an 18-dof free-base tree): the
/// inverse of the reference's mass matrix, symmetric, and in `F64x4` lanes the `f64`
/// function's values, lane by lane, bit for bit.
#[test]
fn quadruped_mass_matrix_inverse_inverts_the_reference_mass_matrix() {
    use dynamics_runtime::F64x4;
    use models::kinematics::QuadrupedKinematics;
    let model = QuadrupedKinematics::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut m_ref = DMatrix::zeros(NV, NV);
    let mut rng = SplitMix(77);
    let mut qs = Vec::new();
    for _ in 0..20 {
        let mut q: [f64; NQ] = std::array::from_fn(|_| rng.uniform(-1.5, 1.5));
        let norm = q[3..7].iter().map(|x| x * x).sum::<f64>().sqrt();
        q[3..7].iter_mut().for_each(|x| *x /= norm);
        reference.mass_matrix(&q, &mut m_ref).expect("sizes");
        let inverse = m_ref.clone().try_inverse().expect("M is positive definite");
        let rows: Vec<f64> = (0..NV)
            .flat_map(|i| (0..NV).map(move |j| (i, j)))
            .map(|(i, j)| inverse[(i, j)])
            .collect();
        let got = QuadrupedKinematics::mass_matrix_inverse(&q);
        assert_close(
            "mass_matrix_inverse",
            got.as_flattened(),
            &rows,
            1e-12 * condition_number(&m_ref),
        );
        for i in 0..NV {
            for j in 0..i {
                assert_eq!(got[i][j], got[j][i], "M⁻¹ symmetric at ({i}, {j})");
            }
        }
        qs.push(q);
    }
    for four in qs.chunks_exact(4) {
        let lanes: [F64x4; NQ] = std::array::from_fn(|i| F64x4::from_fn(|l| four[l][i]));
        let got = QuadrupedKinematics::mass_matrix_inverse(&lanes);
        for (l, q) in four.iter().enumerate() {
            let one = QuadrupedKinematics::mass_matrix_inverse(q);
            for i in 0..NV {
                for j in 0..NV {
                    assert_eq!(
                        got[i][j].get(l).map(f64::to_bits),
                        Some(one[i][j].to_bits()),
                        "lane {l} ({i}, {j})"
                    );
                }
            }
        }
    }
}
