//! Writes a bundled mechanism as JSON in the layout of the Pinocchio anchor files
//! (`tests/data/pinocchio/*.json`: a `model` section and `samples`), so that a program built
//! on another library can rebuild the identical model and time it on the identical states.
//!
//! ```sh
//! cargo run --release -p models --example export_model -- quadruped            # the default
//! cargo run --release -p models --example export_model -- puma560 --out puma.json
//! ```
//!
//! Without `--out` the file goes to `models/benches/pinocchio/<model>.json`, where the
//! benchmark (`benches/dynamics.rs`) and the Pinocchio comparison (`benches/pinocchio/`)
//! read it. The states are random but fixed (`--seed`, default 2024; `--samples`, default
//! 20). Every sample also carries what the runtime reference computes for it, with the
//! loads (e.g. the quadruped's foot forces) at zero: inverse dynamics `rnea`, `nle`
//! (C v + g), `gravity_torque`, forward dynamics `aba` for the sample's `tau`, `crba_a`
//! (M a), `coriolis_v` (C v) and both energies. A program that rebuilds the model checks
//! itself against them before it measures anything.

use dynamics_runtime::{JointKind, Mechanism, Model, Reference};
use models::anchors::{DoublePendulum, Panda, Pendulum, Planar3, Ur5};
use models::puma560::Puma560;
use models::quadruped::Quadruped;
use models::seed::{FallingRod, GyroscopicBody};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::process::ExitCode;

/// The exportable models: command-line name and the file's `source` line.
const MODELS: &[(&str, &str)] = &[
    ("quadruped", "models::quadruped::Quadruped"),
    ("puma560", "models::puma560::Puma560"),
    ("ur5", "models::anchors::Ur5"),
    ("panda", "models::anchors::Panda"),
    ("planar3", "models::anchors::Planar3"),
    ("double_pendulum", "models::anchors::DoublePendulum"),
    ("pendulum", "models::anchors::Pendulum"),
    ("falling_rod", "models::seed::FallingRod"),
    ("gyroscopic_body", "models::seed::GyroscopicBody"),
];

/// A model's runtime description and its joint-space sizes.
fn model_named(name: &str) -> Option<Model> {
    Some(match name {
        "quadruped" => Quadruped::model(),
        "puma560" => Puma560::model(),
        "ur5" => Ur5::model(),
        "panda" => Panda::model(),
        "planar3" => Planar3::model(),
        "double_pendulum" => DoublePendulum::model(),
        "pendulum" => Pendulum::model(),
        "falling_rod" => FallingRod::model(),
        "gyroscopic_body" => GyroscopicBody::model(),
        _ => return None,
    })
}

struct Options {
    model: String,
    out: Option<PathBuf>,
    samples: usize,
    seed: u64,
}

fn parse_options() -> Result<Options, String> {
    let mut options = Options {
        model: "quadruped".to_owned(),
        out: None,
        samples: 20,
        seed: 2024,
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = |what: &str| args.next().ok_or(format!("{arg} needs {what}"));
        match arg.as_str() {
            "--out" => options.out = Some(PathBuf::from(value("a path")?)),
            "--samples" => {
                options.samples = value("a count")?
                    .parse()
                    .map_err(|e| format!("--samples: {e}"))?;
            }
            "--seed" => {
                options.seed = value("a number")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?;
            }
            "-h" | "--help" => return Err(String::new()),
            _ if arg.starts_with('-') => return Err(format!("unknown option {arg}")),
            _ => options.model = arg,
        }
    }
    Ok(options)
}

fn main() -> ExitCode {
    let options = match parse_options() {
        Ok(options) => options,
        Err(message) => {
            if !message.is_empty() {
                eprintln!("export_model: {message}");
            }
            let names: Vec<&str> = MODELS.iter().map(|(name, _)| *name).collect();
            eprintln!(
                "usage: export_model [MODEL] [--out PATH] [--samples N] [--seed S]\n  MODEL: {}",
                names.join(", ")
            );
            return ExitCode::from(2);
        }
    };
    let Some(model) = model_named(&options.model) else {
        eprintln!("export_model: no bundled model named {:?}", options.model);
        return ExitCode::from(2);
    };
    let source = MODELS
        .iter()
        .find(|(name, _)| *name == options.model)
        .map_or("", |(_, source)| *source);
    let out = options.out.clone().unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("benches/pinocchio")
            .join(format!("{}.json", options.model))
    });
    let text = document(&options, source, &model);
    if let Err(e) = std::fs::write(&out, text) {
        eprintln!("export_model: cannot write {}: {e}", out.display());
        return ExitCode::FAILURE;
    }
    println!(
        "wrote {} ({}: nq = {}, nv = {}, {} samples)",
        out.display(),
        options.model,
        model.nq(),
        model.nv(),
        options.samples
    );
    ExitCode::SUCCESS
}

/// The whole file: objects one key a line, arrays of objects (joints, bodies, samples) one
/// element a line, everything else on the line of its key.
fn document(options: &Options, source: &str, model: &Model) -> String {
    let floating = model
        .bodies()
        .iter()
        .any(|b| matches!(b.joint.kind, JointKind::FreeFlyer));
    let command = format!(
        "cargo run --release -p models --example export_model -- {} --samples {} --seed {}",
        options.model, options.samples, options.seed
    );
    let fields = [
        ("name", json!(options.model)),
        ("source", json!(source)),
        ("floating_base", json!(floating)),
        (
            "generator",
            json!({
                "program": "models/examples/export_model.rs",
                "command": command,
                "outputs_by": "dynamics_runtime::Reference (f64), loads at zero",
            }),
        ),
        ("conventions", conventions()),
        ("model", model_section(model)),
        (
            "samples",
            Value::Array(samples(model, options.samples, options.seed)),
        ),
    ];
    let mut text = String::from("{\n");
    for (k, (key, value)) in fields.iter().enumerate() {
        let comma = if k + 1 < fields.len() { "," } else { "" };
        text += &format!("  \"{key}\": {}{comma}\n", layout(value, 1));
    }
    text + "}\n"
}

/// `value` laid out at nesting `depth` (two spaces a level).
fn layout(value: &Value, depth: usize) -> String {
    let inner = "  ".repeat(depth + 1);
    let outer = "  ".repeat(depth);
    match value {
        Value::Object(map) if !map.is_empty() => {
            let lines: Vec<String> = map
                .iter()
                .map(|(key, v)| {
                    format!(
                        "{inner}{}: {}",
                        Value::from(key.as_str()),
                        layout(v, depth + 1)
                    )
                })
                .collect();
            format!("{{\n{}\n{outer}}}", lines.join(",\n"))
        }
        Value::Array(items) if items.iter().any(Value::is_object) => {
            let lines: Vec<String> = items.iter().map(|v| format!("{inner}{v}")).collect();
            format!("[\n{}\n{outer}]", lines.join(",\n"))
        }
        _ => value.to_string(),
    }
}

fn conventions() -> Value {
    json!({
        "units": "SI: m, kg, s, rad, N, N m",
        "joints": "tree order, parents first; parent = index into joints, -1 = the world",
        "placement": "pose of the joint frame in the parent body frame at zero motion: x_parent = rotation x_joint + translation (rotation by rows)",
        "bodies": "body i moves with joint i; com and inertia_com (about the mass centre) in the joint frame after the motion",
        "revolute": "q = angle about axis (joint frame), right-handed; v = dq/dt",
        "prismatic": "q = displacement along axis",
        "free_flyer": "nq = 7, nv = 6: q = [x, y, z, qx, qy, qz, qw] (unit quaternion, scalar last, body to parent); v = [v_linear, omega] both in the body frame; a = dv/dt of that vector",
        "outputs": "rnea = M a + C v + g; nle = C v + g; gravity_torque = g; aba = M^-1 (tau - nle); crba_a = M a; coriolis_v = C v; potential_energy = -sum m_i g . c_i",
    })
}

fn vec3(v: &Vector3<f64>) -> Value {
    json!([v.x, v.y, v.z])
}

fn mat3(m: &Matrix3<f64>) -> Value {
    json!([
        [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
        [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
        [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
    ])
}

/// Pinocchio's joint model for one of ours: the axis-aligned ones where the axis is exactly
/// a unit vector of the joint frame (as Pinocchio's URDF parser chooses), else the general.
fn pinocchio_type(kind: &JointKind) -> (&'static str, Option<Vector3<f64>>, &'static str) {
    let aligned = |axis: &Vector3<f64>| {
        [Vector3::x(), Vector3::y(), Vector3::z()]
            .iter()
            .position(|unit| unit == axis)
    };
    match kind {
        JointKind::Revolute { axis_in_joint } => (
            "revolute",
            Some(*axis_in_joint),
            match aligned(axis_in_joint) {
                Some(0) => "JointModelRX",
                Some(1) => "JointModelRY",
                Some(2) => "JointModelRZ",
                _ => "JointModelRevoluteUnaligned",
            },
        ),
        JointKind::Prismatic { axis_in_joint } => (
            "prismatic",
            Some(*axis_in_joint),
            match aligned(axis_in_joint) {
                Some(0) => "JointModelPX",
                Some(1) => "JointModelPY",
                Some(2) => "JointModelPZ",
                _ => "JointModelPrismaticUnaligned",
            },
        ),
        JointKind::FreeFlyer => ("free_flyer", None, "JointModelFreeFlyer"),
    }
}

fn model_section(model: &Model) -> Value {
    let joints: Vec<Value> = model
        .bodies()
        .iter()
        .map(|body| {
            let joint = &body.joint;
            let (kind, axis, pinocchio) = pinocchio_type(&joint.kind);
            json!({
                "name": joint.name,
                "parent": body.parent.map_or(-1, |p| p as i64),
                "type": kind,
                "axis": axis.as_ref().map(vec3),
                "pinocchio_type": pinocchio,
                "idx_q": joint.idx_q,
                "idx_v": joint.idx_v,
                "nq": joint.kind.nq(),
                "nv": joint.kind.nv(),
                "armature": joint.armature,
                "damping": joint.damping,
                "placement": {
                    "translation": vec3(&joint.placement_in_parent.translation),
                    "rotation": mat3(&joint.placement_in_parent.rotation),
                },
            })
        })
        .collect();
    let bodies: Vec<Value> = model
        .bodies()
        .iter()
        .enumerate()
        .map(|(i, body)| {
            json!({
                "joint": i,
                "name": body.name,
                "mass": body.inertia.mass,
                "com": vec3(&body.inertia.com_in_body),
                "inertia_com": mat3(&body.inertia.inertia_com_in_body),
            })
        })
        .collect();
    json!({
        "nq": model.nq(),
        "nv": model.nv(),
        "gravity": vec3(&model.gravity_in_world()),
        "joints": joints,
        "bodies": bodies,
    })
}

/// SplitMix64: a fixed, documented stream, so the same seed gives the same states anywhere.
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// A random configuration: angles in [−π, π], displacements in [−0.5, 0.5] m, a free
/// flyer's position in [−1, 1]³ m and a unit quaternion uniform on the sphere.
fn configuration(model: &Model, rng: &mut SplitMix) -> Vec<f64> {
    let mut q = vec![0.0; model.nq()];
    for body in model.bodies() {
        let i = body.joint.idx_q;
        match body.joint.kind {
            JointKind::Revolute { .. } => {
                q[i] = rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
            }
            JointKind::Prismatic { .. } => q[i] = rng.uniform(-0.5, 0.5),
            JointKind::FreeFlyer => {
                for x in &mut q[i..i + 3] {
                    *x = rng.uniform(-1.0, 1.0);
                }
                let quaternion = loop {
                    let c: [f64; 4] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
                    let norm = c.iter().map(|x| x * x).sum::<f64>().sqrt();
                    if (0.1..=1.0).contains(&norm) {
                        break c.map(|x| x / norm);
                    }
                };
                q[i + 3..i + 7].copy_from_slice(&quaternion);
            }
        }
    }
    q
}

/// The states, one JSON object each, with the reference's outputs.
fn samples(model: &Model, count: usize, seed: u64) -> Vec<Value> {
    let nv = model.nv();
    let mut rng = SplitMix(seed);
    let mut reference = Reference::<f64>::new(model);
    let (mut mass, mut coriolis) = (DMatrix::zeros(nv, nv), DMatrix::zeros(nv, nv));
    (0..count)
        .map(|_| {
            let q = configuration(model, &mut rng);
            let v: Vec<f64> = (0..nv).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let a: Vec<f64> = (0..nv).map(|_| rng.uniform(-5.0, 5.0)).collect();
            let tau: Vec<f64> = (0..nv).map(|_| rng.uniform(-10.0, 10.0)).collect();
            let mut out = |f: &mut dyn FnMut(&mut Reference<f64>, &mut [f64])| {
                let mut x = vec![0.0; nv];
                f(&mut reference, &mut x);
                x
            };
            let rnea = out(&mut |r, x| r.inverse_dynamics(&q, &v, &a, None, x).expect("sizes"));
            let nle = out(&mut |r, x| r.nonlinear_effects(&q, &v, x).expect("sizes"));
            let gravity = out(&mut |r, x| r.gravity(&q, x).expect("sizes"));
            let aba = out(&mut |r, x| r.forward_dynamics(&q, &v, &tau, None, x).expect("sizes"));
            reference.mass_matrix(&q, &mut mass).expect("sizes");
            reference
                .coriolis_matrix(&q, &v, &mut coriolis)
                .expect("sizes");
            let crba_a = &mass * DVector::from_column_slice(&a);
            let coriolis_v = &coriolis * DVector::from_column_slice(&v);
            let kinetic = reference.kinetic_energy(&q, &v).expect("sizes");
            let potential = reference.potential_energy(&q).expect("sizes");
            json!({
                "q": q, "v": v, "a": a, "tau": tau,
                "rnea": rnea, "nle": nle, "gravity_torque": gravity, "aba": aba,
                "crba_a": crba_a.as_slice(), "coriolis_v": coriolis_v.as_slice(),
                "kinetic_energy": kinetic, "potential_energy": potential,
            })
        })
        .collect()
}
