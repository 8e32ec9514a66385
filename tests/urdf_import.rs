//! The URDF import on a branched robot, `tests/data/urdf/branched.urdf` on a free base,
//! against Pinocchio 4.1.0's model and dynamics of the same file
//! (`tests/data/pinocchio/branched.json`, written by `models/tools/pinocchio_branched.py`):
//!
//! - joint order: the joints, listed in the file neither depth first nor by name, come depth
//!   first with each link's child joints in name order, Pinocchio's order (`JOINT_NAMES`,
//!   the coordinates' offsets, the welded bodies' frames);
//! - merged bodies: the root link's placeholder inertia, which alone violates the triangle
//!   inequality, is welded to the physical trunk: the file compiles without `allow:`, and
//!   the merged body is Pinocchio's (mass, mass centre, I_G), in the runtime model too;
//! - with `urdf_damping: false;` every generated function of the default outputs matches
//!   Pinocchio's (rnea, crba, nle, gravity, aba, Coriolis matrix, energies), which leave
//!   the damping out; with the damping kept (the default), inverse dynamics and the bias
//!   are Pinocchio's plus b q̇, forward dynamics Pinocchio's aba at τ − b q̇, and the runtime
//!   reference agrees;
//! - `JOINT_LIMITS` and `JOINT_FRICTION` are Pinocchio's limits and friction (its largest
//!   double where ours is ±∞), and the runtime model's damping is Pinocchio's.
//!
//! Each comparison within `1e-11 · (1 + max |value|)`.

#[macro_use]
mod generated_support;

use dynamics_runtime::{mechanism, Mechanism, Reference};
use dynamics_tests::anchors::{self, AnchorFile, AnchorSample};
use dynamics_tests::assert_close;
use generated_support::{arr, Function, Inputs};
use serde::Deserialize;

mechanism! {
    /// `branched.urdf` on a free base, its damping kept (the default).
    pub struct Branched;
    urdf: "data/urdf/branched.urdf";
    floating_base: true;
    outputs: [inverse_dynamics, bias, forward_dynamics];
}

mechanism! {
    /// `branched.urdf` on a free base, its damping dropped, as Pinocchio's algorithms do.
    pub struct BranchedUndamped;
    urdf: "data/urdf/branched.urdf";
    floating_base: true;
    urdf_damping: false;
}

const TOLERANCE: f64 = 1e-11;

/// The anchor file, and the extra model fields of this one.
fn pinocchio() -> (AnchorFile, Extra) {
    let file = anchors::load("branched").unwrap_or_else(|e| panic!("{e}"));
    let path = anchors::path("branched");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let extra: ExtraFile = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}"));
    (file, extra.model)
}

#[derive(Deserialize)]
struct ExtraFile {
    model: Extra,
}

/// What `branched.json` gives beyond the anchor format: Pinocchio's frame names, limits,
/// damping and friction.
#[derive(Deserialize)]
struct Extra {
    frames: Vec<String>,
    lower_position_limit: Vec<f64>,
    upper_position_limit: Vec<f64>,
    velocity_limit: Vec<f64>,
    effort_limit: Vec<f64>,
    damping: Vec<f64>,
    friction: Vec<f64>,
}

/// Pinocchio writes an unbounded limit as its largest double; ours is ±∞.
fn same_limit(ours: f64, pinocchio: f64) -> bool {
    if pinocchio.abs() == f64::MAX {
        ours == pinocchio.signum() * f64::INFINITY
    } else {
        ours == pinocchio
    }
}

/// A quantity of a Pinocchio sample, as a generated function returns it.
type Field = fn(&AnchorSample) -> Vec<f64>;

fn inputs(sample: &AnchorSample) -> Inputs<f64> {
    Inputs {
        q: sample.q.clone(),
        v: sample.v.clone(),
        a: sample.a.clone(),
        tau: sample.tau.clone(),
        p: Vec::new(),
        loads: Vec::new(),
    }
}

#[test]
fn the_joints_come_in_pinocchios_order() {
    let (file, extra) = pinocchio();
    let joints: Vec<&str> = file.model.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        joints,
        [
            "root_joint",
            "fl_hip",
            "fl_knee",
            "fr_hip",
            "fr_aux",
            "fr_knee",
            "hl_hip",
            "hl_knee"
        ]
    );
    assert_eq!(Branched::JOINT_NAMES, joints);
    assert_eq!(BranchedUndamped::JOINT_NAMES, joints);
    assert_eq!((Branched::NQ, Branched::NV), (file.model.nq, file.model.nv));
    let model = Branched::model();
    for (body, joint) in model.bodies().iter().zip(&file.model.joints) {
        assert_eq!(body.joint.name, joint.name);
        assert_eq!(
            (body.joint.idx_q, body.joint.idx_v),
            (joint.idx_q, joint.idx_v)
        );
        let parent = body.parent.map_or(-1, |p| p as i64);
        assert_eq!(parent, joint.parent, "{}", joint.name);
    }
    // The welded bodies' frames, in Pinocchio's order of its frames.
    let pinocchio_frames: Vec<&str> = extra
        .frames
        .iter()
        .map(String::as_str)
        .filter(|f| Branched::FRAME_NAMES.contains(f))
        .collect();
    assert_eq!(Branched::FRAME_NAMES, ["trunk", "fl_foot"]);
    assert_eq!(Branched::FRAME_NAMES, pinocchio_frames);
}

#[test]
fn the_placeholder_base_is_merged_into_pinocchios_body() {
    let (file, _) = pinocchio();
    for model in [Branched::model(), BranchedUndamped::model()] {
        for (body, expected) in model.bodies().iter().zip(&file.model.bodies) {
            let i = &body.inertia;
            let what = format!("body `{}`", body.name);
            assert_close(&what, &[i.mass], &[expected.mass], TOLERANCE);
            assert_close(&what, i.com_in_body.as_slice(), &expected.com, TOLERANCE);
            let rows: Vec<f64> = expected.inertia_com.iter().flatten().copied().collect();
            let ours: Vec<f64> = (0..3)
                .flat_map(|r| (0..3).map(move |c| (r, c)))
                .map(|(r, c)| i.inertia_com_in_body[(r, c)])
                .collect();
            assert_close(&what, &ours, &rows, TOLERANCE);
        }
    }
    // By hand: 0.001 kg at the base origin, 6 kg at R_z(0.1) (0.01, −0.005, 0.02) +
    // (0.02, 0, 0.01).
    let trunk = Branched::model().bodies()[0].inertia.clone();
    let (s, c) = 0.1_f64.sin_cos();
    let trunk_com = [
        c * 0.01 - s * -0.005 + 0.02,
        s * 0.01 + c * -0.005,
        0.02 + 0.01,
    ];
    let expected: Vec<f64> = trunk_com.iter().map(|x| 6.0 * x / 6.001).collect();
    assert_close("merged mass", &[trunk.mass], &[6.001], 1e-15);
    assert_close(
        "merged mass centre",
        trunk.com_in_body.as_slice(),
        &expected,
        1e-14,
    );
}

#[test]
fn without_urdf_damping_every_function_is_pinocchios() {
    let (file, _) = pinocchio();
    assert!(BranchedUndamped::model()
        .bodies()
        .iter()
        .all(|b| b.joint.damping == 0.0));
    let functions: Vec<Function<f64>> =
        generated_functions!(f64, BranchedUndamped, p: no, loads: no);
    let pairs: [(&str, Field); 8] = [
        ("inverse_dynamics", |s| s.rnea.clone()),
        ("mass_matrix", |s| anchors::flatten(&s.crba)),
        ("bias", |s| s.nle.clone()),
        ("gravity", |s| s.gravity_torque.clone()),
        ("forward_dynamics", |s| s.aba.clone()),
        ("coriolis_matrix", |s| anchors::flatten(&s.coriolis)),
        ("kinetic_energy", |s| vec![s.kinetic_energy]),
        ("potential_energy", |s| vec![s.potential_energy]),
    ];
    for (k, sample) in file.samples.iter().enumerate() {
        let x = inputs(sample);
        for (name, pinocchio) in pairs {
            let (_, f) = functions
                .iter()
                .find(|(n, _)| *n == name)
                .unwrap_or_else(|| panic!("`{name}` generated"));
            assert_close(
                &format!("sample {k}: {name}"),
                &f(&x),
                &pinocchio(sample),
                TOLERANCE,
            );
        }
    }
}

#[test]
fn urdf_damping_adds_b_v_to_pinocchios_dynamics() {
    let (file, extra) = pinocchio();
    let damping: Vec<f64> = Branched::model()
        .bodies()
        .iter()
        .flat_map(|b| std::iter::repeat_n(b.joint.damping, b.joint.kind.nv()))
        .collect();
    assert_eq!(damping, extra.damping, "the runtime model's damping");
    assert!(damping.iter().any(|&b| b > 0.0));
    let model = Branched::model();
    let mut reference = Reference::<f64>::new(&model);
    let mut out = vec![0.0; Branched::NV];
    for (k, s) in file.samples.iter().enumerate() {
        let b_v: Vec<f64> = damping.iter().zip(&s.v).map(|(b, v)| b * v).collect();
        let plus = |x: &[f64]| -> Vec<f64> { x.iter().zip(&b_v).map(|(x, y)| x + y).collect() };
        let (q, v) = (arr(&s.q), arr(&s.v));
        let tau = Branched::inverse_dynamics(q, v, arr(&s.a));
        assert_close(&format!("sample {k}: τ"), &tau, &plus(&s.rnea), TOLERANCE);
        let undamped = BranchedUndamped::inverse_dynamics(q, v, arr(&s.a));
        assert_close(
            &format!("sample {k}: τ − b q̇"),
            &plus(&undamped),
            &tau,
            TOLERANCE,
        );
        let bias = Branched::bias(q, v);
        assert_close(
            &format!("sample {k}: bias"),
            &bias,
            &plus(&s.nle),
            TOLERANCE,
        );
        let qdd = Branched::forward_dynamics(q, v, arr(&plus(&s.tau)));
        assert_close(&format!("sample {k}: q̈"), &qdd, &s.aba, TOLERANCE);
        reference
            .inverse_dynamics(&s.q, &s.v, &s.a, None, &mut out)
            .expect("sizes match");
        assert_close(&format!("sample {k}: reference τ"), &out, &tau, TOLERANCE);
    }
}

#[test]
fn limits_and_friction_are_pinocchios() {
    let (file, extra) = pinocchio();
    assert_eq!(Branched::JOINT_LIMITS.len(), Branched::NV);
    assert_eq!(Branched::JOINT_FRICTION, extra.friction.as_slice());
    assert_eq!(BranchedUndamped::JOINT_FRICTION, extra.friction.as_slice());
    for joint in &file.model.joints {
        let one = joint.kind != "free_flyer";
        for k in 0..if one { 1 } else { 6 } {
            let limits = Branched::JOINT_LIMITS[joint.idx_v + k];
            let v = joint.idx_v + k;
            let what = format!("{} coordinate {k}: {limits:?}", joint.name);
            assert!(
                same_limit(limits.velocity, extra.velocity_limit[v]),
                "{what}"
            );
            assert!(same_limit(limits.effort, extra.effort_limit[v]), "{what}");
            if one {
                let q = joint.idx_q;
                assert!(
                    same_limit(limits.lower, extra.lower_position_limit[q]),
                    "{what}"
                );
                assert!(
                    same_limit(limits.upper, extra.upper_position_limit[q]),
                    "{what}"
                );
            } else {
                // Pinocchio's position limits of a free flyer are per q; ours unbounded.
                assert_eq!(limits, dynamics_runtime::JointLimits::UNBOUNDED, "{what}");
            }
        }
    }
}
