//! The generated code against Pinocchio 4.1.0 on the anchor vectors
//! (`tests/data/pinocchio/<name>.json`): for the anchor models declared with `mechanism!`
//! (`models::anchors`) and every sample of their file, the generated inverse dynamics
//! (rnea), mass matrix (crba), bias (nle: these models have no damping), gravity, forward
//! dynamics (aba), full Coriolis matrix, kinetic and potential energy, each within
//! `1e-11 · (1 + max |value|)` of Pinocchio's. Run with `--nocapture` to see the largest
//! errors.

#[macro_use]
mod generated_support;

use dynamics_runtime::Mechanism;
use dynamics_tests::anchors::{self, AnchorFile};
use dynamics_tests::{max_abs_diff, tolerance_scale};
use generated_support::{arr, Function, Inputs};
use models::anchors::{DoublePendulum, Panda, Pendulum, Planar3, Ur5};

const TOLERANCE: f64 = 1e-11;

/// Each generated function and the field of an anchor sample it must reproduce.
const PAIRS: [(&str, &str); 8] = [
    ("inverse_dynamics", "rnea"),
    ("mass_matrix", "crba"),
    ("bias", "nle"),
    ("gravity", "gravity_torque"),
    ("forward_dynamics", "aba"),
    ("coriolis_matrix", "coriolis"),
    ("kinetic_energy", "kinetic_energy"),
    ("potential_energy", "potential_energy"),
];

fn pinocchio(sample: &anchors::AnchorSample, field: &str) -> Vec<f64> {
    match field {
        "rnea" => sample.rnea.clone(),
        "crba" => anchors::flatten(&sample.crba),
        "nle" => sample.nle.clone(),
        "gravity_torque" => sample.gravity_torque.clone(),
        "aba" => sample.aba.clone(),
        "coriolis" => anchors::flatten(&sample.coriolis),
        "kinetic_energy" => vec![sample.kinetic_energy],
        "potential_energy" => vec![sample.potential_energy],
        _ => panic!("no field `{field}`"),
    }
}

/// Checks every sample of the anchor file `file_name` against the generated functions of
/// the mechanism `M`.
fn check<M: Mechanism>(file_name: &str, functions: &[Function<f64>]) {
    let file: AnchorFile = anchors::load(file_name).unwrap_or_else(|e| panic!("{e}"));
    let joints: Vec<&str> = file.model.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        M::JOINT_NAMES,
        joints,
        "{}: the file's joint order",
        M::NAME
    );
    let model = M::model();
    assert!(
        model.bodies().iter().all(|b| b.joint.damping == 0.0),
        "{}: nle is the bias only without damping",
        M::NAME
    );
    let mut worst = vec![0.0_f64; PAIRS.len()];
    for (k, sample) in file.samples.iter().enumerate() {
        let x = Inputs {
            q: sample.q.clone(),
            v: sample.v.clone(),
            a: sample.a.clone(),
            tau: sample.tau.clone(),
            p: Vec::new(),
            loads: Vec::new(),
        };
        for (w, (function, field)) in worst.iter_mut().zip(PAIRS) {
            let (_, f) = functions
                .iter()
                .find(|(name, _)| *name == function)
                .unwrap_or_else(|| panic!("{}: `{function}` generated", M::NAME));
            let (ours, theirs) = (f(&x), pinocchio(sample, field));
            let scale = tolerance_scale(&theirs);
            let error = max_abs_diff(&ours, &theirs);
            assert!(
                error <= TOLERANCE * scale,
                "{} sample {k}: {function} vs Pinocchio's {field}: error {error:e} > \
                 {TOLERANCE:e} · {scale}\n generated {ours:?}\n pinocchio {theirs:?}",
                M::NAME
            );
            *w = w.max(error / scale);
        }
    }
    println!(
        "{} ({} samples): largest error / (1 + max |value|)",
        M::NAME,
        file.samples.len()
    );
    for ((function, _), w) in PAIRS.iter().zip(&worst) {
        println!("  {function:<18} {w:9.2e}");
    }
}

macro_rules! anchor_tests {
    ($($test:ident: $m:ty, $file:literal;)*) => {$(
        #[test]
        fn $test() {
            let functions: Vec<Function<f64>> = generated_functions!(f64, $m, p: no, loads: no);
            check::<$m>($file, &functions);
        }
    )*};
}

anchor_tests! {
    pendulum: Pendulum, "pendulum";
    double_pendulum: DoublePendulum, "double_pendulum";
    planar3: Planar3, "planar3";
    ur5: Ur5, "ur5";
    panda: Panda, "panda";
}
