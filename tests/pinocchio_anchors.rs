//! The reference against Pinocchio 4.1.0 on the anchor vectors
//! (`tests/data/pinocchio/*.json`, copied from the shared anchors; their `conventions` field
//! matches the runtime's): for every sample, rnea, crba, nle, gravity torque, aba, the full
//! Coriolis matrix (and so C v), kinetic and potential energy, each within
//! `1e-11 · (1 + max |value|)` of Pinocchio's.

use dynamics_runtime::{Model, ModelError, Reference};
use dynamics_tests::anchors::{self, AnchorFile};
use dynamics_tests::{max_abs_diff, tolerance_scale};
use nalgebra::DMatrix;

const TOLERANCE: f64 = 1e-11;

fn load(name: &str) -> AnchorFile {
    anchors::load(name).unwrap_or_else(|e| panic!("anchor file: {e}"))
}

/// Row-major copy of a square matrix.
fn rows_of(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// Checks one quantity; returns its error relative to the tolerance's scale.
fn check(model: &str, sample: usize, what: &str, ours: &[f64], pinocchio: &[f64]) -> f64 {
    let scale = tolerance_scale(pinocchio);
    let error = max_abs_diff(ours, pinocchio);
    assert!(
        error <= TOLERANCE * scale,
        "{model} sample {sample} {what}: max error {error:e} > {TOLERANCE:e} · {scale}\n \
         ours     {ours:?}\n pinocchio {pinocchio:?}"
    );
    error / scale
}

/// Runs every sample of one anchor model; prints the largest scaled error per quantity.
fn check_anchor(file: &AnchorFile, model: &Model) {
    assert_eq!(model.nq(), file.model.nq);
    assert_eq!(model.nv(), file.model.nv);
    for (k, joint) in file.model.joints.iter().enumerate() {
        assert_eq!(model.bodies()[k].joint.name, joint.name, "same joint order");
        assert_eq!(model.bodies()[k].joint.idx_q, joint.idx_q);
        assert_eq!(model.bodies()[k].joint.idx_v, joint.idx_v);
    }
    let nv = model.nv();
    let mut reference = Reference::<f64>::new(model);
    let mut out = vec![0.0; nv];
    let mut matrix = DMatrix::zeros(nv, nv);
    let names = [
        "rnea",
        "crba",
        "nle",
        "gravity",
        "aba",
        "coriolis",
        "C v",
        "kinetic",
        "potential",
    ];
    let mut worst = [0.0_f64; 9];
    let name = &file.name;
    for (s, sample) in file.samples.iter().enumerate() {
        let (q, v) = (&sample.q, &sample.v);
        let mut errors = [0.0; 9];
        reference
            .inverse_dynamics(q, v, &sample.a, None, &mut out)
            .expect("sizes match");
        errors[0] = check(name, s, "rnea", &out, &sample.rnea);
        reference.mass_matrix(q, &mut matrix).expect("sizes match");
        errors[1] = check(
            name,
            s,
            "crba",
            &rows_of(&matrix),
            &anchors::flatten(&sample.crba),
        );
        reference
            .nonlinear_effects(q, v, &mut out)
            .expect("sizes match");
        errors[2] = check(name, s, "nle", &out, &sample.nle);
        reference.gravity(q, &mut out).expect("sizes match");
        errors[3] = check(name, s, "gravity", &out, &sample.gravity_torque);
        reference
            .forward_dynamics(q, v, &sample.tau, None, &mut out)
            .expect("sizes match");
        errors[4] = check(name, s, "aba", &out, &sample.aba);
        reference
            .coriolis_matrix(q, v, &mut matrix)
            .expect("sizes match");
        errors[5] = check(
            name,
            s,
            "coriolis",
            &rows_of(&matrix),
            &anchors::flatten(&sample.coriolis),
        );
        let pinocchio_c = DMatrix::from_row_slice(nv, nv, &anchors::flatten(&sample.coriolis));
        let v_vec = nalgebra::DVector::from_column_slice(v);
        let ours_cv = &matrix * &v_vec;
        let pinocchio_cv = pinocchio_c * &v_vec;
        errors[6] = check(name, s, "C v", ours_cv.as_slice(), pinocchio_cv.as_slice());
        let kinetic = reference.kinetic_energy(q, v).expect("sizes match");
        errors[7] = check(name, s, "kinetic", &[kinetic], &[sample.kinetic_energy]);
        let potential = reference.potential_energy(q).expect("sizes match");
        errors[8] = check(
            name,
            s,
            "potential",
            &[potential],
            &[sample.potential_energy],
        );
        for (w, e) in worst.iter_mut().zip(errors) {
            *w = w.max(e);
        }
    }
    let report: Vec<String> = names
        .iter()
        .zip(worst)
        .map(|(n, w)| format!("{n} {w:.1e}"))
        .collect();
    println!(
        "{name}: max error / (1 + max |value|): {}",
        report.join(", ")
    );
}

fn strict_model(name: &str) -> (AnchorFile, Model) {
    let file = load(name);
    let model = file
        .model
        .builder()
        .build()
        .unwrap_or_else(|e| panic!("{name} must build: {e}"));
    (file, model)
}

#[test]
fn pendulum_matches_pinocchio() {
    let (file, model) = strict_model("pendulum");
    check_anchor(&file, &model);
}

#[test]
fn double_pendulum_matches_pinocchio() {
    let (file, model) = strict_model("double_pendulum");
    check_anchor(&file, &model);
}

/// planar3's inertias violate the triangle inequality by about 7e-5 kg·m² (Pinocchio does not
/// check it): the strict build rejects them, and the dynamics are checked with the rule
/// skipped.
#[test]
fn planar3_matches_pinocchio() {
    let file = load("planar3");
    let errors = file
        .model
        .builder()
        .build()
        .expect_err("planar3 violates the triangle inequality");
    assert!(
        errors
            .0
            .iter()
            .any(|e| matches!(e, ModelError::TriangleInequality { .. })),
        "expected a TriangleInequality error, got {errors}"
    );
    let model = file
        .model
        .builder()
        .skip_triangle_inequality()
        .build()
        .unwrap_or_else(|e| panic!("planar3 must build without the triangle rule: {e}"));
    check_anchor(&file, &model);
}

#[test]
fn ur5_matches_pinocchio() {
    let (file, model) = strict_model("ur5");
    check_anchor(&file, &model);
}

#[test]
fn panda_matches_pinocchio() {
    let (file, model) = strict_model("panda");
    check_anchor(&file, &model);
}
