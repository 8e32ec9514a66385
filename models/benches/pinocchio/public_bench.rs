//! The generated code of one example-robot-data robot, timed for `public.sh`.
//!
//! `public.sh` builds this benchmark in a throwaway crate (`build/public/<robot>/`) whose
//! library is one declaration, `mechanism! { pub struct Robot; urdf: "<robot>.urdf"; .. }`,
//! of a URDF installed at benchmark time: the code generator never saw the robot before.
//! It reads the states and Pinocchio's outputs from the JSON file named by
//! `PUBLIC_ROBOT_JSON` (written by `public_robots.py`), checks every timed output against
//! Pinocchio's at every state (max |Δ| / (1 + max |Pinocchio|) ≤ 1e-10: the same model and
//! the same numbers, or the benchmark stops; the Coriolis matrix, which is not unique, by
//! C v; with a `rotation_tolerance` T, which changes the model by up to T, ≤ 1e-10 + 100 T,
//! from `PUBLIC_ROTATION_TOLERANCE`), prints the states' fingerprint (matched by
//! `public.sh` against the timing program's), then times each output as `benches/dynamics.rs`
//! does: one call per state, the states in turn, `<robot>/<output>/generated`. The large
//! matrices are timed again written into the caller's storage, `<output>_into` (checked
//! first to write, bit for bit, what their functions return), as Pinocchio writes into its
//! `Data`.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use dynamics_runtime::Mechanism;
use public_robot::Robot;
use serde_json::Value;
use std::hint::black_box;
use std::time::{Duration, Instant};

const NQ: usize = <Robot as Mechanism>::NQ;
const NV: usize = <Robot as Mechanism>::NV;

/// One state: q, v, a and τ.
struct State {
    q: [f64; NQ],
    v: [f64; NV],
    a: [f64; NV],
    tau: [f64; NV],
}

fn numbers(value: &Value, what: &str) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("{what}: not an array"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("{what}: not a number")))
        .collect()
}

fn rows(value: &Value, what: &str) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("{what}: not an array of rows"))
        .iter()
        .flat_map(|row| numbers(row, what))
        .collect()
}

fn array<const N: usize>(value: &Value, what: &str) -> [f64; N] {
    numbers(value, what)
        .try_into()
        .unwrap_or_else(|v: Vec<f64>| panic!("{what}: {} numbers, the robot has {N}", v.len()))
}

/// Generated against Pinocchio: max |Δ| / (1 + max |Pinocchio|) ≤ 1e-10, or 1e-10 + 100 T
/// when the declaration sets `rotation_tolerance: T` (public.sh passes T as
/// `PUBLIC_ROTATION_TOLERANCE`): a quarter turn written 1.5708 and taken as exact moves the
/// model by 3.7e-6.
fn check(what: &str, sample: usize, generated: &[f64], pinocchio: &[f64]) {
    let rotation_tolerance: f64 = std::env::var("PUBLIC_ROTATION_TOLERANCE")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(0.0);
    let bound = 1e-10 + 100.0 * rotation_tolerance;
    assert_eq!(generated.len(), pinocchio.len(), "{what}: sizes");
    let scale = 1.0 + pinocchio.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let error = generated
        .iter()
        .zip(pinocchio)
        .fold(0.0_f64, |m, (g, p)| m.max((g - p).abs()))
        / scale;
    assert!(
        error <= bound,
        "sample {sample}: {what} differs from Pinocchio's by {error:.1e} (relative): not the \
         same model (joint order? merged links?)"
    );
}

/// The states, after checking every timed output against Pinocchio's at each.
fn states(path: &str) -> Vec<State> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let file: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
    let samples = file["samples"]
        .as_array()
        .unwrap_or_else(|| panic!("{path}: no samples"));
    let mut out = Vec::with_capacity(samples.len());
    for (k, s) in samples.iter().enumerate() {
        let state = State {
            q: array(&s["q"], "q"),
            v: array(&s["v"], "v"),
            a: array(&s["a"], "a"),
            tau: array(&s["tau"], "tau"),
        };
        let (q, v, a, tau) = (&state.q, &state.v, &state.a, &state.tau);
        check(
            "inverse dynamics",
            k,
            &Robot::inverse_dynamics(q, v, a),
            &numbers(&s["rnea"], "rnea"),
        );
        check(
            "M",
            k,
            Robot::mass_matrix(q).as_flattened(),
            &rows(&s["crba"], "crba"),
        );
        check(
            "forward dynamics",
            k,
            &Robot::forward_dynamics(q, v, tau),
            &numbers(&s["aba"], "aba"),
        );
        let placements = Robot::joint_placements(q);
        let stored = s["joint_placements"].as_array().expect("joint_placements");
        assert_eq!(
            placements.len(),
            stored.len(),
            "one body per Pinocchio joint"
        );
        for (b, ((rotation, origin), p)) in placements.iter().zip(stored).enumerate() {
            let what = format!("body {b}'s placement");
            check(
                &what,
                k,
                rotation.as_flattened(),
                &rows(&p["rotation"], "rotation"),
            );
            check(&what, k, origin, &numbers(&p["translation"], "translation"));
        }
        let (poses, twists, accelerations) = Robot::forward_kinematics(q, v, a);
        let stored_twists = s["joint_velocities_world"].as_array().expect("velocities");
        let stored_accelerations = s["joint_classical_accelerations_world"]
            .as_array()
            .expect("accelerations");
        for b in 0..placements.len() {
            check(
                "forward_kinematics placement",
                k,
                poses[b].0.as_flattened(),
                placements[b].0.as_flattened(),
            );
            check(
                "body velocity",
                k,
                &twists[b],
                &numbers(&stored_twists[b], "velocity"),
            );
            let expected = numbers(&stored_accelerations[b], "acceleration");
            check("body acceleration", k, &accelerations[b], &expected);
        }
        let world = rows(&s["joint_jacobians_world_pinocchio"], "data.J");
        check(
            "data.J",
            k,
            Robot::joint_jacobians_world(q).as_flattened(),
            &world,
        );
        let (j, j_dot) = Robot::joint_jacobians_world_time_variation(q, v);
        check("data.J", k, j.as_flattened(), &world);
        let rate = rows(
            &s["joint_jacobians_world_time_variation_pinocchio"],
            "data.dJ",
        );
        check("data.dJ", k, j_dot.as_flattened(), &rate);
        let com = numbers(&s["center_of_mass"], "com");
        check("centre of mass", k, &Robot::center_of_mass(q), &com);
        let jacobian = rows(&s["com_jacobian"], "Jcom");
        check(
            "CoM Jacobian",
            k,
            Robot::center_of_mass_jacobian(q).as_flattened(),
            &jacobian,
        );
        let centroidal = rows(&s["centroidal_momentum_matrix"], "Ag");
        check(
            "A_G",
            k,
            Robot::centroidal_momentum_matrix(q).as_flattened(),
            &centroidal,
        );
        let rate = numbers(&s["centroidal_bias"], "dAg v");
        check("dA_G v", k, &Robot::centroidal_bias(q, v), &rate);
        let gravity = numbers(&s["gravity_torque"], "gravity");
        check("gravity", k, &Robot::gravity(q), &gravity);
        check("bias", k, &Robot::bias(q, v), &numbers(&s["nle"], "nle"));
        let coriolis = Robot::coriolis_matrix(q, v);
        let c_v: Vec<f64> = coriolis
            .iter()
            .map(|row| row.iter().zip(v).map(|(c, x)| c * x).sum())
            .collect();
        check("C v", k, &c_v, &numbers(&s["coriolis_v"], "C v"));
        let energies = [Robot::kinetic_energy(q, v), Robot::potential_energy(q)];
        let stored = [&s["kinetic_energy"], &s["potential_energy"]].map(|e| e.as_f64());
        let stored = stored.map(|e| e.expect("energies"));
        check("energies", k, &energies, &stored);
        let (d_tau_dq, d_tau_dv) = Robot::inverse_dynamics_derivatives(q, v, a);
        check(
            "dtau/dq",
            k,
            d_tau_dq.as_flattened(),
            &rows(&s["dtau_dq"], "dtau_dq"),
        );
        check(
            "dtau/dv",
            k,
            d_tau_dv.as_flattened(),
            &rows(&s["dtau_dv"], "dtau_dv"),
        );
        let (d_ddq_dq, d_ddq_dv) = Robot::forward_dynamics_derivatives(q, v, tau);
        check(
            "dddq/dq",
            k,
            d_ddq_dq.as_flattened(),
            &rows(&s["ddq_dq"], "ddq_dq"),
        );
        check(
            "dddq/dv",
            k,
            d_ddq_dv.as_flattened(),
            &rows(&s["ddq_dv"], "ddq_dv"),
        );
        let inverse = Robot::mass_matrix_inverse(q);
        check("M⁻¹", k, inverse.as_flattened(), &rows(&s["minv"], "minv"));
        into_twins_agree(&state, k);
        out.push(state);
    }
    assert!(!out.is_empty(), "{path}: no samples");
    out
}

/// The `_into` twins write, bit for bit, what their functions return (so what the checks
/// above held to Pinocchio's), into storage first filled with NaN; the `_sparse_into` twins,
/// into zeros, the same in the entries they write (of M and M⁻¹, the upper triangle).
fn into_twins_agree(state: &State, k: usize) {
    fn same<O: PartialEq + std::fmt::Debug>(
        what: &str,
        k: usize,
        returned: O,
        mut out: O,
        into: impl FnOnce(&mut O),
    ) {
        into(&mut out);
        assert!(
            format!("{returned:?}") == format!("{out:?}"),
            "{what}_into differs from {what} at sample {k}"
        );
    }
    let (q, v, a, tau) = (&state.q, &state.v, &state.a, &state.tau);
    let n = f64::NAN;
    let nan = [[n; NV]; NV];
    same("mass_matrix", k, Robot::mass_matrix(q), nan, |o| {
        Robot::mass_matrix_into(q, o)
    });
    same(
        "centroidal_momentum_matrix",
        k,
        Robot::centroidal_momentum_matrix(q),
        [[n; NV]; 6],
        |o| Robot::centroidal_momentum_matrix_into(q, o),
    );
    same(
        "coriolis_matrix",
        k,
        Robot::coriolis_matrix(q, v),
        nan,
        |o| Robot::coriolis_matrix_into(q, v, o),
    );
    same(
        "inverse_dynamics_derivatives",
        k,
        Robot::inverse_dynamics_derivatives(q, v, a),
        (nan, nan),
        |o| Robot::inverse_dynamics_derivatives_into(q, v, a, o),
    );
    same(
        "forward_dynamics_derivatives",
        k,
        Robot::forward_dynamics_derivatives(q, v, tau),
        (nan, nan),
        |o| Robot::forward_dynamics_derivatives_into(q, v, tau, o),
    );
    same(
        "mass_matrix_inverse",
        k,
        Robot::mass_matrix_inverse(q),
        nan,
        |o| Robot::mass_matrix_inverse_into(q, o),
    );
    // The sparse twins, into zeros: the upper triangles of M and M⁻¹, all of C and ∂τ.
    let upper = |m: [[f64; NV]; NV]| -> [[f64; NV]; NV] {
        std::array::from_fn(|i| std::array::from_fn(|j| if j < i { 0.0 } else { m[i][j] }))
    };
    let zero = [[0.0; NV]; NV];
    same("mass_matrix_sparse", k, upper(Robot::mass_matrix(q)), zero, |o| {
        Robot::mass_matrix_sparse_into(q, o)
    });
    same(
        "coriolis_matrix_sparse",
        k,
        Robot::coriolis_matrix(q, v),
        zero,
        |o| Robot::coriolis_matrix_sparse_into(q, v, o),
    );
    same(
        "inverse_dynamics_derivatives_sparse",
        k,
        Robot::inverse_dynamics_derivatives(q, v, a),
        (zero, zero),
        |o| Robot::inverse_dynamics_derivatives_sparse_into(q, v, a, o),
    );
    let jacobians = Robot::joint_jacobians(q);
    same(
        "joint_jacobians_sparse",
        k,
        jacobians,
        jacobians.map(|j| j.map(|r| r.map(|_| 0.0))),
        |o| Robot::joint_jacobians_sparse_into(q, o),
    );
    // M⁻¹ finished by a solve loop writes every entry: its lower triangle is either.
    let inverse = Robot::mass_matrix_inverse(q);
    let mut out = zero;
    Robot::mass_matrix_inverse_sparse_into(q, &mut out);
    let whole = (1..NV).any(|i| (0..i).any(|j| out[i][j] != 0.0));
    let want = if whole { inverse } else { upper(inverse) };
    assert!(
        format!("{want:?}") == format!("{out:?}"),
        "mass_matrix_inverse_sparse_into differs from mass_matrix_inverse at sample {k}"
    );
}

/// FNV-1a over the bits of q, v, a, τ, state by state (as the timing program's).
fn fingerprint(states: &[State]) -> u64 {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for s in states {
        for x in s.q.iter().chain(&s.v).chain(&s.a).chain(&s.tau) {
            for byte in x.to_bits().to_le_bytes() {
                hash = (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    hash
}

/// Total time of `iters` calls, one per state, the states in turn; the result kept by
/// reference (as `benches/dynamics.rs`).
fn cycle<R>(states: &[State], iters: u64, mut call: impl FnMut(&State) -> R) -> Duration {
    let mut k = 0;
    let start = Instant::now();
    for _ in 0..iters {
        let result = call(black_box(&states[k]));
        black_box(&result);
        k = if k + 1 == states.len() { 0 } else { k + 1 };
    }
    start.elapsed()
}

macro_rules! timed {
    ($group:ident, $states:ident, $($name:literal => |$s:ident| $call:expr),* $(,)?) => {
        $(
            $group.bench_function(concat!($name, "/generated"), |b| {
                b.iter_custom(|iters| cycle(&$states, iters, |$s| $call))
            });
        )*
    };
}

/// As `timed!`, for the `_into` twins: `$out` (made by `$init`, once per benchmark) the
/// caller's storage they write into, kept by reference after each call.
macro_rules! timed_into {
    ($group:ident, $states:ident, $($name:literal => $init:expr, |$s:ident, $out:ident| $call:expr),* $(,)?) => {
        $(
            $group.bench_function(concat!($name, "/generated"), |b| {
                let mut $out = $init;
                b.iter_custom(|iters| {
                    cycle(&$states, iters, |$s| {
                        $call;
                        black_box(&mut $out);
                    })
                })
            });
        )*
    };
}

fn public(c: &mut Criterion) {
    let path = std::env::var("PUBLIC_ROBOT_JSON")
        .expect("PUBLIC_ROBOT_JSON names the robot's file (public.sh sets it)");
    let name = std::env::var("PUBLIC_ROBOT").unwrap_or_else(|_| "robot".to_owned());
    let states = states(&path);
    println!(
        "states {name} {} {:016x}",
        states.len(),
        fingerprint(&states)
    );
    let mut group = c.benchmark_group(name);
    group.sampling_mode(SamplingMode::Flat);
    timed!(group, states,
        "inverse_dynamics" => |s| Robot::inverse_dynamics(&s.q, &s.v, &s.a),
        "mass_matrix" => |s| Robot::mass_matrix(&s.q),
        "forward_dynamics" => |s| Robot::forward_dynamics(&s.q, &s.v, &s.tau),
        "joint_placements" => |s| Robot::joint_placements(&s.q),
        "forward_kinematics" => |s| Robot::forward_kinematics(&s.q, &s.v, &s.a),
        "joint_jacobians_world" => |s| Robot::joint_jacobians_world(&s.q),
        "joint_jacobians" => |s| Robot::joint_jacobians(&s.q),
        "joint_jacobians_world_time_variation" => |s| {
            Robot::joint_jacobians_world_time_variation(&s.q, &s.v)
        },
        "center_of_mass" => |s| Robot::center_of_mass(&s.q),
        "center_of_mass_jacobian" => |s| Robot::center_of_mass_jacobian(&s.q),
        "centroidal_momentum_matrix" => |s| Robot::centroidal_momentum_matrix(&s.q),
        "gravity" => |s| Robot::gravity(&s.q),
        "bias" => |s| Robot::bias(&s.q, &s.v),
        "coriolis_matrix" => |s| Robot::coriolis_matrix(&s.q, &s.v),
        "centroidal_bias" => |s| Robot::centroidal_bias(&s.q, &s.v),
        "inverse_dynamics_derivatives" => |s| Robot::inverse_dynamics_derivatives(&s.q, &s.v, &s.a),
        "forward_dynamics_derivatives" => |s| {
            Robot::forward_dynamics_derivatives(&s.q, &s.v, &s.tau)
        },
        "mass_matrix_inverse" => |s| Robot::mass_matrix_inverse(&s.q),
    );
    let matrix = || [[0.0; NV]; NV];
    // Every joint's 6 × nv Jacobian, zero, as timing.cpp's matrices for getJointJacobian.
    let jacobians_zero = Robot::joint_jacobians(&states[0].q).map(|j| j.map(|r| r.map(|_| 0.0)));
    timed_into!(group, states,
        "mass_matrix_into" => matrix(), |s, out| Robot::mass_matrix_into(&s.q, &mut out),
        "centroidal_momentum_matrix_into" => [[0.0; NV]; 6],
            |s, out| Robot::centroidal_momentum_matrix_into(&s.q, &mut out),
        "coriolis_matrix_into" => matrix(), |s, out| Robot::coriolis_matrix_into(&s.q, &s.v, &mut out),
        "inverse_dynamics_derivatives_into" => (matrix(), matrix()),
            |s, out| Robot::inverse_dynamics_derivatives_into(&s.q, &s.v, &s.a, &mut out),
        "forward_dynamics_derivatives_into" => (matrix(), matrix()),
            |s, out| Robot::forward_dynamics_derivatives_into(&s.q, &s.v, &s.tau, &mut out),
        "mass_matrix_inverse_into" => matrix(), |s, out| Robot::mass_matrix_inverse_into(&s.q, &mut out),
        // Zeroed once, as Pinocchio's `Data`: the sparse twins leave the zeros there.
        "mass_matrix_sparse_into" => matrix(), |s, out| Robot::mass_matrix_sparse_into(&s.q, &mut out),
        "coriolis_matrix_sparse_into" => matrix(),
            |s, out| Robot::coriolis_matrix_sparse_into(&s.q, &s.v, &mut out),
        "inverse_dynamics_derivatives_sparse_into" => (matrix(), matrix()),
            |s, out| Robot::inverse_dynamics_derivatives_sparse_into(&s.q, &s.v, &s.a, &mut out),
        "mass_matrix_inverse_sparse_into" => matrix(),
            |s, out| Robot::mass_matrix_inverse_sparse_into(&s.q, &mut out),
        "joint_jacobians_sparse_into" => jacobians_zero,
            |s, out| Robot::joint_jacobians_sparse_into(&s.q, &mut out),
    );
    group.finish();
}

criterion_group!(benches, public);
criterion_main!(benches);
