//! The generated code against the independent reference, on every model in `models/`.
//!
//! For each model and 40 random states: every generated output equals the runtime
//! reference within 1e-12 · (1 + max |value|) in f64; forward dynamics within
//! 1e-12 · cond(M) · (1 + max |value|); and every output in f32 within 1e-4 (scaled
//! likewise), against the reference at the inputs rounded to f32.
//!
//! What the two sides share: the reference runs on `<M as Mechanism>::model()`, which
//! `mechanism!` emits (`dynamics-codegen/src/declare.rs`) as a `ModelBuilder` call on the
//! numbers the code generator resolved from the declaration: the literals and constant
//! expressions, rotations (`rpy`, `axis_angle`, matrices; entries within 1e-15 of 0 or ±1
//! made exact), I_G from `diag`, `principal` and the shapes, the parameters' affine values,
//! and what a URDF file says. A mistake in that resolution would reach both sides and pass
//! here. From there on nothing is shared: the runtime merges fixed joints, normalizes axes,
//! validates and computes the dynamics with its own algorithms. The resolution itself is
//! checked elsewhere: against Pinocchio's numbers (`anchor_models.rs`, both front ends), the
//! inertia forms against textbook formulas (`shape_inertias.rs`), and here, for a double
//! pendulum, a shape and a spatial arm with quarter-turn `rpy` placements (the PUMA 560),
//! against a reference run on a model built by hand with `ModelBuilder` from the
//! declaration's numbers (`*_matches_a_hand_built_reference`).

#[macro_use]
mod generated_support;

use dynamics_runtime::{
    BodySpec, Inertia, JointSpec, Mechanism, Model, ModelBuilder, Reference, Wrench, GROUND,
};
use dynamics_tests::condition_number;
use dynamics_tests::random::SplitMix;
use generated_support::{arr, check_against_reference, random_inputs, Function, Inputs, UnderTest};
use models::anchors::{DoublePendulum, Panda, Pendulum, Planar3, Ur5};
use models::puma560::Puma560;
use models::quadruped::Quadruped;
use models::scenes::{PlanarArm, PlanarArmGravityOnly, PlanarArmIn3d};
use models::seed::{EccentricRotor, FallingRod, GyroscopicBody};
use models::urdf_anchors::{DoublePendulumUrdf, PandaUrdf, PendulumUrdf, Planar3Urdf, Ur5Urdf};
use nalgebra::DMatrix;

const STATES: usize = 40;

/// A random state (q with unit quaternions for free joints, v, a, τ) for a model.
fn random_state(model: &Model, rng: &mut SplitMix) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let x = random_inputs(model, &[], 0, rng);
    (x.q, x.v, x.a, x.tau)
}

/// [`dynamics_tests::assert_close`] for output `what` of mechanism `model`.
#[track_caller]
fn assert_close(what: &str, model: &str, generated: &[f64], reference: &[f64], tolerance: f64) {
    dynamics_tests::assert_close(&format!("{model}: {what}"), generated, reference, tolerance);
}

/// A mechanism without parameters or loads, for [`check_against_reference`].
fn under_test<'a>(
    name: &'a str,
    model: &'a Model,
    f64: Vec<Function<f64>>,
    f32: Vec<Function<f32>>,
) -> UnderTest<'a> {
    UnderTest {
        name,
        model: Box::new(|_: &[f64]| model.clone()),
        num_parameters: 0,
        loads: &[],
        num_load_inputs: 0,
        f64,
        f32,
    }
}

fn flatten<const N: usize>(m: &[[f64; N]]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

fn array<const N: usize>(v: &[f64]) -> [f64; N] {
    std::array::from_fn(|i| v[i])
}

/// Checks every output a model with all outputs generates.
macro_rules! all_outputs_match {
    ($($test:ident: $m:ty,)*) => {$(
        #[test]
        fn $test() {
            const NQ: usize = <$m as Mechanism>::NQ;
            const NV: usize = <$m as Mechanism>::NV;
            let model = <$m as Mechanism>::model();
            let name = <$m as Mechanism>::NAME;
            let mut reference = Reference::<f64>::new(&model);
            let mut rng = SplitMix(0x5eed ^ NQ as u64);
            let (mut out, mut m_ref) = (vec![0.0; NV], DMatrix::zeros(NV, NV));
            for _ in 0..STATES {
                let (q, v, a, tau) = random_state(&model, &mut rng);
                let (q, v, a, tau): ([f64; NQ], [f64; NV], [f64; NV], [f64; NV]) =
                    (array(&q), array(&v), array(&a), array(&tau));

                reference.inverse_dynamics(&q, &v, &a, None, &mut out).expect("sizes");
                assert_close("inverse_dynamics", name, &<$m>::inverse_dynamics(&q, &v, &a), &out, 1e-12);

                reference.gravity(&q, &mut out).expect("sizes");
                assert_close("gravity", name, &<$m>::gravity(&q), &out, 1e-12);

                reference.bias(&q, &v, &mut out).expect("sizes");
                assert_close("bias", name, &<$m>::bias(&q, &v), &out, 1e-12);

                reference.mass_matrix(&q, &mut m_ref).expect("sizes");
                let m_gen = <$m>::mass_matrix(&q);
                let m_ref_rows: Vec<f64> = (0..NV).flat_map(|i| (0..NV).map(move |j| (i, j))).map(|(i, j)| m_ref[(i, j)]).collect();
                assert_close("mass_matrix", name, &flatten(&m_gen), &m_ref_rows, 1e-12);

                let mut c_ref = DMatrix::zeros(NV, NV);
                reference.coriolis_matrix(&q, &v, &mut c_ref).expect("sizes");
                let c_ref_rows: Vec<f64> = (0..NV).flat_map(|i| (0..NV).map(move |j| (i, j))).map(|(i, j)| c_ref[(i, j)]).collect();
                assert_close("coriolis_matrix", name, &flatten(&<$m>::coriolis_matrix(&q, &v)), &c_ref_rows, 1e-12);

                reference.forward_dynamics(&q, &v, &tau, None, &mut out).expect("sizes");
                let cond = condition_number(&m_ref);
                assert_close("forward_dynamics", name, &<$m>::forward_dynamics(&q, &v, &tau), &out, 1e-12 * cond);

                let t_ref = reference.kinetic_energy(&q, &v).expect("sizes");
                assert_close("kinetic_energy", name, &[<$m>::kinetic_energy(&q, &v)], &[t_ref], 1e-12);
                let v_ref = reference.potential_energy(&q).expect("sizes");
                assert_close("potential_energy", name, &[<$m>::potential_energy(&q)], &[v_ref], 1e-12);

                let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
                reference.joint_reactions(&q, &v, &a, None, &mut wrenches).expect("sizes");
                let w_ref: Vec<f64> = wrenches.iter().flat_map(|w| w.to_vector6().iter().copied().collect::<Vec<_>>()).collect();
                assert_close("joint_reactions", name, &flatten(&<$m>::joint_reactions(&q, &v, &a)), &w_ref, 1e-12);

            }
            // Every function again, through one loop, in f64 and in f32 (against the
            // reference at the inputs rounded to f32).
            let outputs = under_test(
                name,
                &model,
                generated_functions!(f64, $m, p: no, loads: no),
                generated_functions!(f32, $m, p: no, loads: no),
            );
            check_against_reference(&outputs, STATES, 0x5eed ^ NQ as u64).print(name);
        }
    )*};
}

all_outputs_match! {
    falling_rod: FallingRod,
    pendulum: Pendulum,
    double_pendulum: DoublePendulum,
    planar3: Planar3,
    ur5: Ur5,
    panda: Panda,
    pendulum_urdf: PendulumUrdf,
    double_pendulum_urdf: DoublePendulumUrdf,
    planar3_urdf: Planar3Urdf,
    ur5_urdf: Ur5Urdf,
    panda_urdf: PandaUrdf,
    puma560: Puma560,
    planar_arm: PlanarArm,
    planar_arm_in_3d: PlanarArmIn3d,
}

#[test]
fn gyroscopic_body_free_flyer() {
    let model = GyroscopicBody::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(7);
    let (mut out, mut m_ref) = (vec![0.0; 6], DMatrix::zeros(6, 6));
    for _ in 0..STATES {
        let (q, v, a, _) = random_state(&model, &mut rng);
        let (q, v, a): ([f64; 7], [f64; 6], [f64; 6]) = (array(&q), array(&v), array(&a));
        reference
            .inverse_dynamics(&q, &v, &a, None, &mut out)
            .expect("sizes");
        assert_close(
            "inverse_dynamics",
            "GyroscopicBody",
            &GyroscopicBody::inverse_dynamics(&q, &v, &a),
            &out,
            1e-12,
        );
        reference.mass_matrix(&q, &mut m_ref).expect("sizes");
        let rows: Vec<f64> = (0..6)
            .flat_map(|i| (0..6).map(move |j| (i, j)))
            .map(|(i, j)| m_ref[(i, j)])
            .collect();
        assert_close(
            "mass_matrix",
            "GyroscopicBody",
            &flatten(&GyroscopicBody::mass_matrix(&q)),
            &rows,
            1e-12,
        );
        let t = reference.kinetic_energy(&q, &v).expect("sizes");
        assert_close(
            "kinetic_energy",
            "GyroscopicBody",
            &[GyroscopicBody::kinetic_energy(&q, &v)],
            &[t],
            1e-12,
        );
    }
    // Every output it generates, in f64 and f32 (forward dynamics and potential energy too).
    let outputs = under_test(
        "GyroscopicBody",
        &model,
        generated_functions!(f64, GyroscopicBody, p: no, loads: no,
            [inverse_dynamics, mass_matrix, forward_dynamics, kinetic_energy, potential_energy]),
        generated_functions!(f32, GyroscopicBody, p: no, loads: no,
            [inverse_dynamics, mass_matrix, forward_dynamics, kinetic_energy, potential_energy]),
    );
    check_against_reference(&outputs, STATES, 7).print("GyroscopicBody");
}

#[test]
fn eccentric_rotor_reactions() {
    let model = EccentricRotor::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut rng = SplitMix(11);
    let mut wrenches = vec![Wrench::zero(); 1];
    for _ in 0..STATES {
        let (q, v, a, _) = random_state(&model, &mut rng);
        let (q, v, a): ([f64; 1], [f64; 1], [f64; 1]) = (array(&q), array(&v), array(&a));
        reference
            .joint_reactions(&q, &v, &a, None, &mut wrenches)
            .expect("sizes");
        let w_ref: Vec<f64> = wrenches[0].to_vector6().iter().copied().collect();
        assert_close(
            "joint_reactions",
            "EccentricRotor",
            &EccentricRotor::joint_reactions(&q, &v, &a)[0],
            &w_ref,
            1e-12,
        );
    }
    // Every output it generates, in f64 and f32.
    let outputs = under_test(
        "EccentricRotor",
        &model,
        generated_functions!(f64, EccentricRotor, p: no, loads: no,
            [inverse_dynamics, mass_matrix, kinetic_energy, potential_energy, joint_reactions]),
        generated_functions!(f32, EccentricRotor, p: no, loads: no,
            [inverse_dynamics, mass_matrix, kinetic_energy, potential_energy, joint_reactions]),
    );
    check_against_reference(&outputs, STATES, 11).print("EccentricRotor");
    // The textbook's inertia-force scale: m e ω² = 20 N at 100 rad/s, 80 N at 200 rad/s.
    for (omega, expected) in [(100.0_f64, 20.0_f64), (200.0, 80.0)] {
        let w = EccentricRotor::joint_reactions(&[0.0_f64], &[omega], &[0.0]);
        let force = (w[0][0].powi(2) + w[0][1].powi(2) + w[0][2].powi(2)).sqrt();
        assert!(
            (force - expected).abs() < 1e-12 * expected,
            "{force} N at {omega} rad/s"
        );
    }
}

#[test]
fn op_counts_are_exported_for_the_requested_functions_only() {
    let names = |functions: &[dynamics_runtime::FunctionCost]| -> Vec<&str> {
        functions.iter().map(|f| f.name).collect()
    };
    // Ur5 lists no outputs: it gets the defaults.
    assert_eq!(names(Ur5::FUNCTIONS), dynamics_tests::DEFAULT_FUNCTIONS);
    // EccentricRotor asks for inverse dynamics, reactions, mass matrix and energy only.
    assert_eq!(
        names(EccentricRotor::FUNCTIONS),
        [
            "inverse_dynamics",
            "mass_matrix",
            "kinetic_energy",
            "potential_energy",
            "joint_reactions"
        ]
    );
    let puma = models::puma560::Puma560::FUNCTIONS
        .iter()
        .find(|f| f.name == "inverse_dynamics")
        .expect("generated");
    // Murray and Neuman's ARM: 224 multiplications, 174 additions.
    assert!(
        puma.mul <= 224 && puma.add <= 174 && puma.div == 0,
        "{puma:?}"
    );
}

#[test]
fn nalgebra_wrappers_match_the_array_functions() {
    use nalgebra::{SMatrix, SVector};
    let q = SVector::<f64, 6>::from([0.1, -0.4, 0.9, 1.3, -2.0, 0.3]);
    let v = SVector::<f64, 6>::from([0.5, 0.2, -0.1, 0.7, -0.3, 1.1]);
    let a = SVector::<f64, 6>::from([-1.0, 0.4, 0.3, 0.0, 2.0, -0.6]);
    let tau: SVector<f64, 6> = Ur5::inverse_dynamics_na(&q, &v, &a);
    assert_eq!(
        tau.as_slice(),
        Ur5::inverse_dynamics(&q.into(), &v.into(), &a.into())
    );
    let m: SMatrix<f64, 6, 6> = Ur5::mass_matrix_na(&q);
    let rows = Ur5::mass_matrix(&q.into());
    for (i, row) in rows.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            assert_eq!(m[(i, j)], *x);
        }
    }
    let c = Ur5::coriolis_matrix_na(&q, &v);
    assert_eq!(c[(0, 1)], Ur5::coriolis_matrix(&q.into(), &v.into())[0][1]);
    assert_eq!(
        Ur5::kinetic_energy_na(&q, &v),
        Ur5::kinetic_energy(&q.into(), &v.into())
    );
}

#[test]
fn planar_arm_gravity_only() {
    let model = PlanarArmGravityOnly::model();
    let outputs = under_test(
        "PlanarArmGravityOnly",
        &model,
        generated_functions!(f64, PlanarArmGravityOnly, p: no, loads: no, [gravity]),
        generated_functions!(f32, PlanarArmGravityOnly, p: no, loads: no, [gravity]),
    );
    check_against_reference(&outputs, STATES, 13).print("PlanarArmGravityOnly");
}

/// The quadruped's loads, as `models/src/quadruped.rs` declares them: a force on each
/// shin at its foot.
const QUADRUPED_LOADS: [(&str, &str, [f64; 3]); 4] = [
    ("shin_fl", "force", [0.0, 0.0, -0.2]),
    ("shin_fr", "force", [0.0, 0.0, -0.2]),
    ("shin_hl", "force", [0.0, 0.0, -0.2]),
    ("shin_hr", "force", [0.0, 0.0, -0.2]),
];

#[test]
fn quadruped_every_output_with_foot_forces() {
    assert_eq!(
        Quadruped::LOAD_NAMES,
        ["foot_fl", "foot_fr", "foot_hl", "foot_hr"]
    );
    let model = Quadruped::model();
    let outputs = UnderTest {
        loads: &QUADRUPED_LOADS,
        num_load_inputs: Quadruped::NUM_LOAD_INPUTS,
        ..under_test(
            "Quadruped",
            &model,
            generated_functions!(f64, Quadruped, p: no, loads: yes),
            generated_functions!(f32, Quadruped, p: no, loads: yes),
        )
    };
    check_against_reference(&outputs, STATES, 17).print("Quadruped");
}

/// Diagonal I_G.
fn diag(d: [f64; 3]) -> [[f64; 3]; 3] {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// A body for [`ModelBuilder`] from its declared numbers.
fn body(name: &str, mass: f64, com: [f64; 3], inertia: [[f64; 3]; 3]) -> BodySpec {
    BodySpec::new(name, Inertia::new(mass, com, inertia))
}

/// Checks every output `$m` generates against the reference run on `$model`, a model built
/// by hand with [`ModelBuilder`] from the declaration's numbers: nothing of the code
/// generator's resolution reaches the reference (see the module docs).
macro_rules! matches_a_hand_built_reference {
    ($m:ty, $model:expr, $seed:expr) => {{
        let name = <$m as Mechanism>::NAME;
        let model: Model = $model
            .build()
            .unwrap_or_else(|e| panic!("{name}: the hand-built model: {e}"));
        assert_eq!(model.nq(), <$m as Mechanism>::NQ, "{name}: nq");
        assert_eq!(model.nv(), <$m as Mechanism>::NV, "{name}: nv");
        let outputs = under_test(
            name,
            &model,
            generated_functions!(f64, $m, p: no, loads: no),
            generated_functions!(f32, $m, p: no, loads: no),
        );
        check_against_reference(&outputs, STATES, $seed).print(name);
    }};
}

#[test]
fn double_pendulum_matches_a_hand_built_reference() {
    // models/src/anchors.rs: two uniform rods hanging along −y, 1.5 kg / 0.5 m and
    // 1.0 kg / 0.4 m, I_G = m L²/12 about x and z, the elbow at the upper rod's tip.
    let rod = |m: f64, l: f64| diag([m * l * l / 12.0, 0.0, m * l * l / 12.0]);
    let model = ModelBuilder::new()
        .gravity([0.0, -9.81, 0.0])
        .body(body("upper_rod", 1.5, [0.0, -0.25, 0.0], rod(1.5, 0.5)))
        .body(body("lower_rod", 1.0, [0.0, -0.2, 0.0], rod(1.0, 0.4)))
        .joint(JointSpec::revolute(
            "joint1",
            GROUND,
            "upper_rod",
            [0.0, 0.0, 1.0],
        ))
        .joint(
            JointSpec::revolute("joint2", "upper_rod", "lower_rod", [0.0, 0.0, 1.0])
                .at([0.0, -0.5, 0.0]),
        );
    matches_a_hand_built_reference!(DoublePendulum, model, 0x4a4d);
}

#[test]
fn falling_rod_shape_matches_a_hand_built_reference() {
    // models/src/seed.rs: `shape: rod(length: 0.6, axis: y)` of 2 kg is I_G = m L²/12 about
    // x and z, nothing about y.
    let (m, l) = (2.0, 0.6);
    let model = ModelBuilder::new()
        .gravity([0.0, -9.81, 0.0])
        .body(body(
            "rod",
            m,
            [0.0, -0.3, 0.0],
            diag([m * l * l / 12.0, 0.0, m * l * l / 12.0]),
        ))
        .joint(JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0]));
    matches_a_hand_built_reference!(FallingRod, model, 0x20d);
}

#[test]
fn puma560_matches_a_hand_built_reference() {
    // models/src/puma560.rs: modified DH, `rotation: rpy(α, 0, 0)` with α = ±π/2 is the
    // quarter turn about x written out here, Rx(α) = [[1, 0, 0], [0, cos α, −sin α],
    // [0, sin α, cos α]].
    let rx_minus = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]];
    let rx_plus = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
    let z = [0.0, 0.0, 1.0];
    let model = ModelBuilder::new()
        .gravity([0.0, 0.0, -9.81])
        .skip_triangle_inequality()
        .body(body("link1", 0.0, [0.0; 3], diag([0.0, 0.0, 0.35])))
        .body(body(
            "link2",
            17.4,
            [0.068, 0.006, -0.016],
            diag([0.13, 0.524, 0.539]),
        ))
        .body(body(
            "link3",
            4.8,
            [0.0, -0.070, 0.014],
            diag([0.066, 0.0125, 0.066]),
        ))
        .body(body(
            "link4",
            0.82,
            [0.0, 0.0, -0.019],
            diag([1.8e-3, 1.8e-3, 1.3e-3]),
        ))
        .body(body(
            "link5",
            0.34,
            [0.0; 3],
            diag([0.3e-3, 0.3e-3, 0.4e-3]),
        ))
        .body(body(
            "link6",
            0.09,
            [0.0, 0.0, 0.032],
            diag([0.15e-3, 0.15e-3, 0.04e-3]),
        ))
        .joint(JointSpec::revolute("joint1", GROUND, "link1", z))
        .joint(
            JointSpec::revolute("joint2", "link1", "link2", z).placed([0.0, 0.2435, 0.0], rx_minus),
        )
        .joint(JointSpec::revolute("joint3", "link2", "link3", z).at([0.4318, 0.0, -0.0934]))
        .joint(
            JointSpec::revolute("joint4", "link3", "link4", z)
                .placed([-0.0203, -0.4331, 0.0], rx_plus),
        )
        .joint(JointSpec::revolute("joint5", "link4", "link5", z).placed([0.0; 3], rx_minus))
        .joint(JointSpec::revolute("joint6", "link5", "link6", z).placed([0.0; 3], rx_plus));
    matches_a_hand_built_reference!(Puma560, model, 0x560);
}
