//! Criterion benchmarks: every output of every bundled mechanism, the generated code against
//! the runtime reference (`dynamics_runtime::Reference`), on a fixed set of states.
//!
//! ```sh
//! cargo bench -p models --bench dynamics                      # everything (~10 min)
//! cargo bench -p models --bench dynamics -- 'Ur5/'            # one model
//! cargo bench -p models --bench dynamics -- '/generated$'     # the generated code only
//! ```
//!
//! Benchmark ids are `<Model>/<output>/generated` and `<Model>/<output>/reference`; a group
//! `sin_cos/<Model>/<pairs>` times alone the sines and cosines that the generated inverse
//! dynamics computes. One
//! measured call is one call on one state, the states taken in turn: the 20 `samples` of
//! `tests/data/pinocchio/<model>.json` for the five anchor models and their URDF twins, the
//! 20 of `benches/pinocchio/quadruped.json` (written by the `export_model` example) for the
//! quadruped, 20 seeded random states for the others. The planar chains of `models::chains`
//! (1 to 30 links) are timed for their three outputs (inverse dynamics, mass matrix, forward
//! dynamics): `cargo bench -p models --bench dynamics -- '^Chain'`. The linkages of
//! `models::linkages` are timed for their force analysis and loop-closure functions
//! (generated code only). The kinematics of the UR5, the Panda and the quadruped
//! (`models::kinematics`: `Ur5Kinematics`, `PandaKinematics`, `QuadrupedKinematics`) are
//! timed on the states of their dynamics twins, generated code only:
//! `<Name>Kinematics/<output>/generated` for each output, and
//! `<Name>Kinematics/joint_velocities+joint_acceleration_biases/generated` and
//! `<Name>Kinematics/joint_jacobians+joint_acceleration_biases/generated` for the pairs of
//! calls set beside Pinocchio's `forwardKinematics(q, v, a)` and
//! `computeJointJacobiansTimeVariation`. The Pinocchio comparison
//! (`benches/pinocchio/compare.sh`) reads the medians of the same benchmarks.
//!
//! The quadruped's foot loads are zero in the generated calls and absent (`None`) in the
//! reference calls. Before timing, each model's generated outputs are checked against the
//! values stored with the states (Pinocchio's for the anchors, the reference's for the
//! quadruped), and the states' fingerprint is printed for the comparison script. The
//! kinematics are checked against Pinocchio's values for the same states
//! (`tests/data/pinocchio_ext/<model>_kinematics.json`) for the arms, and against the
//! runtime reference's body poses and centre of mass of `Quadruped` for the quadruped.

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode};
use dynamics_runtime::Wrench;
use dynamics_runtime::{JointKind, Mechanism, Model, Reference};
use models::anchors::{DoublePendulum, Panda, Pendulum, Planar3, Ur5};
use models::chains::{Chain1, Chain10, Chain15, Chain2, Chain20, Chain25, Chain3, Chain30, Chain5};
use models::kinematics::{PandaKinematics, QuadrupedKinematics, Ur5Kinematics};
use models::linkages::{
    FourBar, FourBarLoaded, FourBarRockerDriven, GyroscopicRotor, OverhungRotor, SliderCrank,
    SupportedBeam,
};
use models::puma560::Puma560;
use models::quadruped::Quadruped;
use models::seed::{EccentricRotor, FallingRod, GyroscopicBody};
use models::urdf_anchors::{DoublePendulumUrdf, PandaUrdf, PendulumUrdf, Planar3Urdf, Ur5Urdf};
use nalgebra::{DMatrix, DVector};
use serde_json::Value;
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// One state: configuration, velocity, acceleration, torque, and the loads (zero).
#[derive(Clone, Debug)]
struct State<const NQ: usize, const NV: usize, const NL: usize> {
    q: [f64; NQ],
    v: [f64; NV],
    a: [f64; NV],
    tau: [f64; NV],
    loads: [f64; NL],
    /// The outputs stored with the state in its JSON file, if any.
    stored: Option<Value>,
}

/// Where a model's states come from.
enum Source {
    /// The `samples` of a JSON file in the anchor layout, with its path for messages.
    Json(&'static str, &'static str),
    /// `count` states from a seeded generator.
    Random(u64),
}

const UR5: Source = Source::Json(
    "tests/data/pinocchio/ur5.json",
    include_str!("../../tests/data/pinocchio/ur5.json"),
);
const PANDA: Source = Source::Json(
    "tests/data/pinocchio/panda.json",
    include_str!("../../tests/data/pinocchio/panda.json"),
);
const PLANAR3: Source = Source::Json(
    "tests/data/pinocchio/planar3.json",
    include_str!("../../tests/data/pinocchio/planar3.json"),
);
const DOUBLE_PENDULUM: Source = Source::Json(
    "tests/data/pinocchio/double_pendulum.json",
    include_str!("../../tests/data/pinocchio/double_pendulum.json"),
);
const PENDULUM: Source = Source::Json(
    "tests/data/pinocchio/pendulum.json",
    include_str!("../../tests/data/pinocchio/pendulum.json"),
);
const QUADRUPED: Source = Source::Json(
    "models/benches/pinocchio/quadruped.json",
    include_str!("pinocchio/quadruped.json"),
);

/// How many random states a model without a JSON file gets.
const RANDOM_STATES: usize = 20;

fn numbers(value: &Value, what: &str) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("{what}: not an array"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("{what}: not a number")))
        .collect()
}

fn array<const N: usize>(value: &Value, what: &str) -> [f64; N] {
    let x = numbers(value, what);
    x.try_into()
        .unwrap_or_else(|x: Vec<f64>| panic!("{what}: {} numbers, expected {N}", x.len()))
}

/// SplitMix64, for the models without stored states.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

/// The states of a model, read or drawn; a JSON file's model must have the same sizes.
fn states<const NQ: usize, const NV: usize, const NL: usize>(
    name: &str,
    model: &Model,
    source: &Source,
) -> Vec<State<NQ, NV, NL>> {
    match source {
        Source::Json(path, text) => {
            let doc: Value = serde_json::from_str(text).unwrap_or_else(|e| panic!("{path}: {e}"));
            let samples = doc["samples"]
                .as_array()
                .unwrap_or_else(|| panic!("{path}: no samples"));
            let states: Vec<State<NQ, NV, NL>> = samples
                .iter()
                .map(|s| State {
                    q: array(&s["q"], path),
                    v: array(&s["v"], path),
                    a: array(&s["a"], path),
                    tau: array(&s["tau"], path),
                    loads: [0.0; NL],
                    stored: Some(s.clone()),
                })
                .collect();
            eprintln!(
                "states {name} {} {:016x} ({path})",
                states.len(),
                fingerprint(&states)
            );
            states
        }
        Source::Random(seed) => {
            let mut rng = SplitMix(*seed);
            (0..RANDOM_STATES)
                .map(|_| {
                    let mut q = [0.0; NQ];
                    for body in model.bodies() {
                        let i = body.joint.idx_q;
                        match body.joint.kind {
                            JointKind::Revolute { .. } => q[i] = rng.uniform(-PI, PI),
                            JointKind::Prismatic { .. } => q[i] = rng.uniform(-0.5, 0.5),
                            JointKind::FreeFlyer => {
                                let c: [f64; 7] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
                                let norm = c[3..].iter().map(|x| x * x).sum::<f64>().sqrt();
                                q[i..i + 3].copy_from_slice(&c[..3]);
                                for k in 3..7 {
                                    q[i + k] = c[k] / norm;
                                }
                            }
                        }
                    }
                    State {
                        q,
                        v: std::array::from_fn(|_| rng.uniform(-2.0, 2.0)),
                        a: std::array::from_fn(|_| rng.uniform(-5.0, 5.0)),
                        tau: std::array::from_fn(|_| rng.uniform(-10.0, 10.0)),
                        loads: [0.0; NL],
                        stored: None,
                    }
                })
                .collect()
        }
    }
}

/// FNV-1a (64 bits) of the states' bit patterns, sample by sample, q then v, a, tau: the
/// Pinocchio timing program prints the same number for the states it read.
fn fingerprint<const NQ: usize, const NV: usize, const NL: usize>(
    states: &[State<NQ, NV, NL>],
) -> u64 {
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

/// Generated output against a stored one: max |Δ| / (1 + max |stored|).
fn check_stored(model: &str, what: &str, generated: &[f64], stored: &[f64]) {
    assert_eq!(generated.len(), stored.len(), "{model} {what}: sizes");
    let scale = 1.0 + stored.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let error = generated
        .iter()
        .zip(stored)
        .fold(0.0_f64, |m, (g, s)| m.max((g - s).abs()))
        / scale;
    assert!(
        error < 1e-9,
        "{model} {what}: the generated code disagrees with the stored values ({error:e}): \
         the benchmark would time the wrong thing"
    );
}

fn mat_vec<const N: usize>(m: &[[f64; N]; N], x: &[f64; N]) -> Vec<f64> {
    m.iter()
        .map(|row| row.iter().zip(x).map(|(a, b)| a * b).sum())
        .collect()
}

/// Warns about the outputs a model has and this file does not time.
fn check_coverage<M: Mechanism>(benched: &[&str]) {
    for function in M::FUNCTIONS {
        if !benched.contains(&function.name) {
            eprintln!(
                "warning: {}::{} has no benchmark: add it to models/benches/dynamics.rs",
                M::NAME,
                function.name
            );
        }
    }
}

/// Total time of `iters` calls, one per state, the states in turn. The result is kept in
/// memory by reference: `black_box(result)` by value would copy it (a 2.6 kB memmove for an
/// 18 × 18 matrix, 10 % of the quadruped's mass matrix), which Pinocchio, writing into its
/// `Data`, does not pay either.
fn cycle<S, R>(states: &[S], iters: u64, mut call: impl FnMut(&S) -> R) -> Duration {
    let n = states.len();
    let mut k = 0;
    let start = Instant::now();
    for _ in 0..iters {
        let result = call(black_box(&states[k]));
        black_box(&result);
        k += 1;
        if k == n {
            k = 0;
        }
    }
    start.elapsed()
}

/// Output buffers for the reference.
struct Outputs {
    vector: Vec<f64>,
    matrix: DMatrix<f64>,
    wrenches: Vec<Wrench<f64>>,
}

/// The generated call of one output; `[loads]` for the models with loads, else `[]`.
macro_rules! generated {
    ($m:ty, inverse_dynamics, $s:ident, [$($l:ident)?]) => {
        <$m>::inverse_dynamics(&$s.q, &$s.v, &$s.a $(, &$s.$l)?)
    };
    ($m:ty, gravity, $s:ident, [$($l:ident)?]) => { <$m>::gravity(&$s.q) };
    ($m:ty, bias, $s:ident, [$($l:ident)?]) => { <$m>::bias(&$s.q, &$s.v) };
    ($m:ty, mass_matrix, $s:ident, [$($l:ident)?]) => { <$m>::mass_matrix(&$s.q) };
    ($m:ty, coriolis_matrix, $s:ident, [$($l:ident)?]) => { <$m>::coriolis_matrix(&$s.q, &$s.v) };
    ($m:ty, forward_dynamics, $s:ident, [$($l:ident)?]) => {
        <$m>::forward_dynamics(&$s.q, &$s.v, &$s.tau $(, &$s.$l)?)
    };
    ($m:ty, kinetic_energy, $s:ident, [$($l:ident)?]) => { <$m>::kinetic_energy(&$s.q, &$s.v) };
    ($m:ty, potential_energy, $s:ident, [$($l:ident)?]) => { <$m>::potential_energy(&$s.q) };
    ($m:ty, joint_reactions, $s:ident, [$($l:ident)?]) => {
        <$m>::joint_reactions(&$s.q, &$s.v, &$s.a $(, &$s.$l)?)
    };
}

/// The reference's call of one output, into `o`'s buffers.
macro_rules! reference {
    (inverse_dynamics, $r:ident, $s:ident, $o:ident) => {
        $r.inverse_dynamics(&$s.q, &$s.v, &$s.a, None, &mut $o.vector)
    };
    (gravity, $r:ident, $s:ident, $o:ident) => {
        $r.gravity(&$s.q, &mut $o.vector)
    };
    (bias, $r:ident, $s:ident, $o:ident) => {
        $r.bias(&$s.q, &$s.v, &mut $o.vector)
    };
    (mass_matrix, $r:ident, $s:ident, $o:ident) => {
        $r.mass_matrix(&$s.q, &mut $o.matrix)
    };
    (coriolis_matrix, $r:ident, $s:ident, $o:ident) => {
        $r.coriolis_matrix(&$s.q, &$s.v, &mut $o.matrix)
    };
    (forward_dynamics, $r:ident, $s:ident, $o:ident) => {
        $r.forward_dynamics(&$s.q, &$s.v, &$s.tau, None, &mut $o.vector)
    };
    (kinetic_energy, $r:ident, $s:ident, $o:ident) => {
        $r.kinetic_energy(&$s.q, &$s.v).map(|e| $o.vector[0] = e)
    };
    (potential_energy, $r:ident, $s:ident, $o:ident) => {
        $r.potential_energy(&$s.q).map(|e| $o.vector[0] = e)
    };
    (joint_reactions, $r:ident, $s:ident, $o:ident) => {
        $r.joint_reactions(&$s.q, &$s.v, &$s.a, None, &mut $o.wrenches)
    };
}

/// Checks the generated outputs against the values stored with a state.
macro_rules! check {
    ($m:ty, $s:ident, [$($l:ident)?]) => {{
        let name = <$m as Mechanism>::NAME;
        if let Some(stored) = &$s.stored {
            let vector = |key: &str| numbers(&stored[key], key);
            if stored.get("rnea").is_some() {
                check_stored(name, "inverse_dynamics", &generated!($m, inverse_dynamics, $s, [$($l)?]), &vector("rnea"));
                check_stored(name, "gravity", &generated!($m, gravity, $s, [$($l)?]), &vector("gravity_torque"));
                check_stored(name, "bias", &generated!($m, bias, $s, [$($l)?]), &vector("nle"));
                check_stored(name, "forward_dynamics", &generated!($m, forward_dynamics, $s, [$($l)?]), &vector("aba"));
                let mass = generated!($m, mass_matrix, $s, [$($l)?]);
                let ma = mat_vec(&mass, &$s.a);
                let cv = mat_vec(&generated!($m, coriolis_matrix, $s, [$($l)?]), &$s.v);
                if stored.get("crba").is_some() {
                    let rows: Vec<f64> = stored["crba"].as_array().into_iter().flatten()
                        .flat_map(|row| numbers(row, "crba")).collect();
                    check_stored(name, "mass_matrix", mass.as_flattened(), &rows);
                    let rows = DMatrix::from_row_slice($s.v.len(), $s.v.len(), &rows);
                    check_stored(name, "mass_matrix a", &ma, (rows * DVector::from_column_slice(&$s.a)).as_slice());
                } else {
                    check_stored(name, "mass_matrix a", &ma, &vector("crba_a"));
                }
                if stored.get("coriolis").is_some() {
                    let rows: Vec<f64> = stored["coriolis"].as_array().into_iter().flatten()
                        .flat_map(|row| numbers(row, "coriolis")).collect();
                    let rows = DMatrix::from_row_slice($s.v.len(), $s.v.len(), &rows);
                    check_stored(name, "coriolis_matrix v", &cv, (rows * DVector::from_column_slice(&$s.v)).as_slice());
                } else {
                    check_stored(name, "coriolis_matrix v", &cv, &vector("coriolis_v"));
                }
            }
        }
    }};
}

/// A model's benchmarks: `bench_model!(function, Type, states source, [loads] or [],
/// [outputs] or all, checked)`; `checked` (the models whose states come with stored outputs) checks
/// the generated code against them first.
macro_rules! bench_model {
    ($fn_name:ident, $m:ty, $source:expr, $loads:tt, all $(, $checked:ident)?) => {
        bench_model!($fn_name, $m, $source, $loads, [
            inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics,
            kinetic_energy, potential_energy, joint_reactions,
        ] $(, $checked)?);
    };
    ($fn_name:ident, $m:ty, $source:expr, $loads:tt, [$($out:ident),* $(,)?] $(, $checked:ident)?) => {
        fn $fn_name(c: &mut Criterion) {
            const NQ: usize = <$m as Mechanism>::NQ;
            const NV: usize = <$m as Mechanism>::NV;
            const NL: usize = <$m as Mechanism>::NUM_LOAD_INPUTS;
            let name = <$m as Mechanism>::NAME;
            check_coverage::<$m>(&[$(stringify!($out)),*]);
            let model = <$m>::model();
            let states: Vec<State<NQ, NV, NL>> = states(name, &model, &$source);
            $(
                let _ = stringify!($checked);
                for s in &states {
                    check!($m, s, $loads);
                }
            )?
            let mut reference = Reference::<f64>::new(&model);
            let mut o = Outputs {
                vector: vec![0.0; NV.max(1)],
                matrix: DMatrix::zeros(NV, NV),
                wrenches: vec![Wrench::zero(); model.bodies().len()],
            };
            let mut group = c.benchmark_group(name);
            group.sampling_mode(SamplingMode::Flat);
            $(
                group.bench_function(concat!(stringify!($out), "/generated"), |b| {
                    b.iter_custom(|iters| cycle(&states, iters, |s| generated!($m, $out, s, $loads)))
                });
                group.bench_function(concat!(stringify!($out), "/reference"), |b| {
                    b.iter_custom(|iters| {
                        cycle(&states, iters, |s| {
                            let result = reference!($out, reference, s, o);
                            black_box(&o);
                            result
                        })
                    })
                });
            )*
            group.finish();
            bench_sin_cos::<$m, NQ, NV, NL>(c, &model, &states);
        }
    };
}

/// The sines and cosines alone, to set beside the generated functions: per state, as many
/// `sin_cos` calls as the generated inverse dynamics makes (its `trig` count / 2), on the
/// last revolute coordinates of the state (the first joint of an arm turning about the
/// gravity axis drops out of the dynamics). Id `sin_cos/<Model>/<pairs>`.
fn bench_sin_cos<M: Mechanism, const NQ: usize, const NV: usize, const NL: usize>(
    c: &mut Criterion,
    model: &Model,
    states: &[State<NQ, NV, NL>],
) {
    let pairs = M::FUNCTIONS
        .iter()
        .find(|f| f.name == "inverse_dynamics")
        .map_or(0, |f| f.trig / 2);
    let mut revolute: Vec<usize> = model
        .bodies()
        .iter()
        .filter(|b| matches!(b.joint.kind, JointKind::Revolute { .. }))
        .map(|b| b.joint.idx_q)
        .collect();
    revolute.drain(..revolute.len().saturating_sub(pairs));
    if revolute.is_empty() {
        return;
    }
    let mut group = c.benchmark_group("sin_cos");
    group.sampling_mode(SamplingMode::Flat);
    group.bench_function(format!("{}/{}", M::NAME, revolute.len()), |b| {
        b.iter_custom(|iters| {
            cycle(states, iters, |s| {
                let mut sum = 0.0;
                for &i in &revolute {
                    let (sin, cos) = s.q[i].sin_cos();
                    sum += sin * cos;
                }
                sum
            })
        })
    });
    group.finish();
}

bench_model!(pendulum, Pendulum, PENDULUM, [], all, checked);
bench_model!(
    double_pendulum,
    DoublePendulum,
    DOUBLE_PENDULUM,
    [],
    all,
    checked
);
bench_model!(planar3, Planar3, PLANAR3, [], all, checked);
bench_model!(ur5, Ur5, UR5, [], all, checked);
bench_model!(panda, Panda, PANDA, [], all, checked);
bench_model!(quadruped, Quadruped, QUADRUPED, [loads], all, checked);
bench_model!(puma560, Puma560, Source::Random(560), [], all);
bench_model!(falling_rod, FallingRod, Source::Random(1), [], all);
bench_model!(
    eccentric_rotor,
    EccentricRotor,
    Source::Random(2),
    [],
    [
        inverse_dynamics,
        mass_matrix,
        kinetic_energy,
        potential_energy,
        joint_reactions,
    ]
);
bench_model!(
    gyroscopic_body,
    GyroscopicBody,
    Source::Random(3),
    [],
    [
        inverse_dynamics,
        mass_matrix,
        forward_dynamics,
        kinetic_energy,
        potential_energy,
    ]
);

/// The planar chains (`models::chains`): their three outputs, 20 seeded random states each.
macro_rules! bench_chains {
    ($($fn_name:ident: $m:ty, $seed:literal;)*) => {
        $(
            bench_model!(
                $fn_name,
                $m,
                Source::Random($seed),
                [],
                [inverse_dynamics, mass_matrix, forward_dynamics]
            );
        )*
    };
}

bench_chains! {
    chain1: Chain1, 1001;
    chain2: Chain2, 1002;
    chain3: Chain3, 1003;
    chain5: Chain5, 1005;
    chain10: Chain10, 1010;
    chain15: Chain15, 1015;
    chain20: Chain20, 1020;
    chain25: Chain25, 1025;
    chain30: Chain30, 1030;
}

bench_model!(pendulum_urdf, PendulumUrdf, PENDULUM, [], all, checked);
bench_model!(
    double_pendulum_urdf,
    DoublePendulumUrdf,
    DOUBLE_PENDULUM,
    [],
    all,
    checked
);
bench_model!(planar3_urdf, Planar3Urdf, PLANAR3, [], all, checked);
bench_model!(ur5_urdf, Ur5Urdf, UR5, [], all, checked);
bench_model!(panda_urdf, PandaUrdf, PANDA, [], all, checked);

// ---- kinematics -------------------------------------------------------------------------

/// Pinocchio's kinematics of the anchor arms at the states of their `samples` (same q and
/// v, in the same order), to check the generated kinematics against before timing them.
const UR5_KINEMATICS: Source = Source::Json(
    "tests/data/pinocchio_ext/ur5_kinematics.json",
    include_str!("../../tests/data/pinocchio_ext/ur5_kinematics.json"),
);
const PANDA_KINEMATICS: Source = Source::Json(
    "tests/data/pinocchio_ext/panda_kinematics.json",
    include_str!("../../tests/data/pinocchio_ext/panda_kinematics.json"),
);

/// What the generated kinematics are checked against before they are timed.
enum KinematicsCheck {
    /// Pinocchio's values stored for the same states (a `Source::Json` in the layout of
    /// `tests/data/pinocchio_ext/<model>_kinematics.json`).
    Pinocchio(Source),
    /// The runtime reference's body poses and centre of mass of the dynamics twin.
    Reference(Model),
}

/// Each body's pose in the world, (R, p), as `joint_placements` returns them.
type Placements<const NB: usize> = [([[f64; 3]; 3], [f64; 3]); NB];

/// A kinematics mechanism's generated functions at f64, for the checks.
struct KinematicsFns<const NQ: usize, const NV: usize, const NB: usize> {
    placements: fn(&[f64; NQ]) -> Placements<NB>,
    jacobians: fn(&[f64; NQ]) -> [[[f64; NV]; 6]; NB],
    velocities: fn(&[f64; NQ], &[f64; NV]) -> [[f64; 6]; NB],
    biases: fn(&[f64; NQ], &[f64; NV]) -> [[f64; 6]; NB],
    com: fn(&[f64; NQ]) -> [f64; 3],
    com_jacobian: fn(&[f64; NQ]) -> [[f64; NV]; 3],
    centroidal: fn(&[f64; NQ]) -> [[f64; NV]; 6],
}

/// The rows of a stored matrix (a JSON array of arrays), flattened.
fn rows(value: &Value, what: &str) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("{what}: not an array"))
        .iter()
        .flat_map(|row| numbers(row, what))
        .collect()
}

/// Checks the generated kinematics on every state, so that the benchmark times the robot
/// that Pinocchio times.
fn check_kinematics<const NQ: usize, const NV: usize, const NB: usize>(
    name: &str,
    states: &[State<NQ, NV, 0>],
    fns: &KinematicsFns<NQ, NV, NB>,
    against: &KinematicsCheck,
) {
    match against {
        KinematicsCheck::Pinocchio(Source::Json(path, text)) => {
            let doc: Value = serde_json::from_str(text).unwrap_or_else(|e| panic!("{path}: {e}"));
            let samples = doc["samples"]
                .as_array()
                .unwrap_or_else(|| panic!("{path}: no samples"));
            assert_eq!(samples.len(), states.len(), "{path}: one sample per state");
            for (s, stored) in states.iter().zip(samples) {
                let (q, v): ([f64; NQ], [f64; NV]) =
                    (array(&stored["q"], path), array(&stored["v"], path));
                assert!(
                    q == s.q && v == s.v,
                    "{path}: its states are not the benchmark's"
                );
                let placements = (fns.placements)(&s.q);
                let jacobians = (fns.jacobians)(&s.q);
                let velocities = (fns.velocities)(&s.q, &s.v);
                let biases = (fns.biases)(&s.q, &s.v);
                let stored_placements = stored["joint_placements"]
                    .as_array()
                    .unwrap_or_else(|| panic!("{path}: no joint_placements"));
                assert_eq!(stored_placements.len(), NB, "{name}: one body per joint");
                for (b, p) in stored_placements.iter().enumerate() {
                    let (rotation, translation) = &placements[b];
                    check_stored(
                        name,
                        "joint_placements R",
                        rotation.as_flattened(),
                        &rows(&p["rotation"], path),
                    );
                    check_stored(
                        name,
                        "joint_placements p",
                        translation,
                        &numbers(&p["translation"], path),
                    );
                    check_stored(
                        name,
                        "joint_jacobians",
                        jacobians[b].as_flattened(),
                        &rows(&stored["joint_jacobians_world"][b], path),
                    );
                    check_stored(
                        name,
                        "joint_acceleration_biases",
                        &biases[b],
                        &numbers(
                            &stored["joint_jacobian_time_derivative_times_v_world"][b],
                            path,
                        ),
                    );
                    // Pinocchio's velocities are in the body frame: turned to world axes.
                    let local = numbers(&stored["joint_velocities_local"][b], path);
                    let world: Vec<f64> = (0..6)
                        .map(|r| {
                            (0..3)
                                .map(|c| rotation[r % 3][c] * local[3 * (r / 3) + c])
                                .sum()
                        })
                        .collect();
                    check_stored(name, "joint_velocities", &velocities[b], &world);
                }
                check_stored(
                    name,
                    "center_of_mass",
                    &(fns.com)(&s.q),
                    &numbers(&stored["center_of_mass"], path),
                );
                check_stored(
                    name,
                    "center_of_mass_jacobian",
                    (fns.com_jacobian)(&s.q).as_flattened(),
                    &rows(&stored["com_jacobian"], path),
                );
                check_stored(
                    name,
                    "centroidal_momentum_matrix",
                    (fns.centroidal)(&s.q).as_flattened(),
                    &rows(&stored["centroidal_momentum_matrix"], path),
                );
            }
        }
        KinematicsCheck::Pinocchio(Source::Random(_)) => {
            panic!("{name}: Pinocchio's kinematics come from a file")
        }
        KinematicsCheck::Reference(model) => {
            let mut reference = Reference::<f64>::new(model);
            for s in states {
                let com = reference
                    .center_of_mass(&s.q)
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                check_stored(name, "center_of_mass", &(fns.com)(&s.q), com.as_slice());
                let poses = reference
                    .body_poses(&s.q)
                    .unwrap_or_else(|e| panic!("{name}: {e}"));
                assert_eq!(poses.len(), NB, "{name}: one pose per body");
                let placements = (fns.placements)(&s.q);
                for (pose, (rotation, translation)) in poses.iter().zip(&placements) {
                    let rows: Vec<f64> = (0..3)
                        .flat_map(|r| (0..3).map(move |c| pose.rotation_in_world[(r, c)]))
                        .collect();
                    check_stored(name, "joint_placements R", rotation.as_flattened(), &rows);
                    check_stored(
                        name,
                        "joint_placements p",
                        translation,
                        pose.origin_in_world.as_slice(),
                    );
                }
            }
        }
    }
}

/// The kinematics outputs timed, each alone: `<Name>/<output>/generated` (`compare.sh`
/// pairs each with its Pinocchio call).
const KINEMATICS: [&str; 17] = [
    "joint_placements",
    "joint_velocities",
    "joint_acceleration_biases",
    "joint_jacobians",
    "joint_jacobians_world",
    "joint_jacobians_world_time_variation",
    "forward_kinematics",
    "center_of_mass",
    "center_of_mass_jacobian",
    "centroidal_momentum_matrix",
    "frame_placements",
    "frame_jacobians",
    "frame_acceleration_biases",
    "centroidal_bias",
    "inverse_dynamics_derivatives",
    "forward_dynamics_derivatives",
    "mass_matrix_inverse",
];

/// The generated call of one kinematics output.
macro_rules! kinematics_call {
    ($m:ty, joint_placements, $s:ident) => {
        <$m>::joint_placements(&$s.q)
    };
    ($m:ty, joint_jacobians, $s:ident) => {
        <$m>::joint_jacobians(&$s.q)
    };
    ($m:ty, joint_jacobians_world, $s:ident) => {
        <$m>::joint_jacobians_world(&$s.q)
    };
    ($m:ty, joint_jacobians_world_time_variation, $s:ident) => {
        <$m>::joint_jacobians_world_time_variation(&$s.q, &$s.v)
    };
    ($m:ty, forward_kinematics, $s:ident) => {
        <$m>::forward_kinematics(&$s.q, &$s.v, &$s.a)
    };
    ($m:ty, joint_velocities, $s:ident) => {
        <$m>::joint_velocities(&$s.q, &$s.v)
    };
    ($m:ty, joint_acceleration_biases, $s:ident) => {
        <$m>::joint_acceleration_biases(&$s.q, &$s.v)
    };
    ($m:ty, center_of_mass, $s:ident) => {
        <$m>::center_of_mass(&$s.q)
    };
    ($m:ty, center_of_mass_jacobian, $s:ident) => {
        <$m>::center_of_mass_jacobian(&$s.q)
    };
    ($m:ty, centroidal_momentum_matrix, $s:ident) => {
        <$m>::centroidal_momentum_matrix(&$s.q)
    };
    ($m:ty, frame_placements, $s:ident) => {
        <$m>::frame_placements(&$s.q)
    };
    ($m:ty, frame_jacobians, $s:ident) => {
        <$m>::frame_jacobians(&$s.q)
    };
    ($m:ty, frame_acceleration_biases, $s:ident) => {
        <$m>::frame_acceleration_biases(&$s.q, &$s.v)
    };
    ($m:ty, centroidal_bias, $s:ident) => {
        <$m>::centroidal_bias(&$s.q, &$s.v)
    };
    ($m:ty, inverse_dynamics_derivatives, $s:ident) => {
        <$m>::inverse_dynamics_derivatives(&$s.q, &$s.v, &$s.a)
    };
    ($m:ty, forward_dynamics_derivatives, $s:ident) => {
        <$m>::forward_dynamics_derivatives(&$s.q, &$s.v, &$s.tau)
    };
    ($m:ty, mass_matrix_inverse, $s:ident) => {
        <$m>::mass_matrix_inverse(&$s.q)
    };
}

/// A kinematics mechanism's benchmarks: `bench_kinematics!(function, Type, states source,
/// check)`: each output of [`KINEMATICS`] alone, then the two pairs of calls that stand
/// for one Pinocchio call each (`forwardKinematics(q, v, a)` gives the velocities and the
/// accelerations, `computeJointJacobiansTimeVariation` J and J̇), both results kept.
macro_rules! bench_kinematics {
    ($fn_name:ident, $m:ty, $source:expr, $check:expr) => {
        fn $fn_name(c: &mut Criterion) {
            const NQ: usize = <$m as Mechanism>::NQ;
            const NV: usize = <$m as Mechanism>::NV;
            let name = <$m as Mechanism>::NAME;
            check_coverage::<$m>(&KINEMATICS);
            let model = <$m>::model();
            let states: Vec<State<NQ, NV, 0>> = states(name, &model, &$source);
            let fns = KinematicsFns {
                placements: <$m>::joint_placements::<f64>,
                jacobians: <$m>::joint_jacobians::<f64>,
                velocities: <$m>::joint_velocities::<f64>,
                biases: <$m>::joint_acceleration_biases::<f64>,
                com: <$m>::center_of_mass::<f64>,
                com_jacobian: <$m>::center_of_mass_jacobian::<f64>,
                centroidal: <$m>::centroidal_momentum_matrix::<f64>,
            };
            check_kinematics(name, &states, &fns, &$check);
            let mut group = c.benchmark_group(name);
            group.sampling_mode(SamplingMode::Flat);
            bench_kinematics!(@each group, $m, states, [
                joint_placements, joint_velocities, joint_acceleration_biases, joint_jacobians,
                joint_jacobians_world, joint_jacobians_world_time_variation, forward_kinematics,
                center_of_mass, center_of_mass_jacobian, centroidal_momentum_matrix,
                frame_placements, frame_jacobians, frame_acceleration_biases, centroidal_bias,
                inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse,
            ]);
            group.bench_function("joint_velocities+joint_acceleration_biases/generated", |b| {
                b.iter_custom(|iters| {
                    cycle(&states, iters, |s| {
                        (
                            kinematics_call!($m, joint_velocities, s),
                            kinematics_call!($m, joint_acceleration_biases, s),
                        )
                    })
                })
            });
            group.bench_function("joint_jacobians+joint_acceleration_biases/generated", |b| {
                b.iter_custom(|iters| {
                    cycle(&states, iters, |s| {
                        (
                            kinematics_call!($m, joint_jacobians, s),
                            kinematics_call!($m, joint_acceleration_biases, s),
                        )
                    })
                })
            });
            group.finish();
        }
    };
    (@each $group:ident, $m:ty, $states:ident, [$($out:ident),* $(,)?]) => {
        $(
            $group.bench_function(concat!(stringify!($out), "/generated"), |b| {
                b.iter_custom(|iters| cycle(&$states, iters, |s| kinematics_call!($m, $out, s)))
            });
        )*
    };
}

bench_kinematics!(
    ur5_kinematics,
    Ur5Kinematics,
    UR5,
    KinematicsCheck::Pinocchio(UR5_KINEMATICS)
);
bench_kinematics!(
    panda_kinematics,
    PandaKinematics,
    PANDA,
    KinematicsCheck::Pinocchio(PANDA_KINEMATICS)
);
bench_kinematics!(
    quadruped_kinematics,
    QuadrupedKinematics,
    QUADRUPED,
    KinematicsCheck::Reference(Quadruped::model())
);

/// The linkages (`models::linkages`): `<Model>/force_analysis/generated` and, for the closed
/// loops, `<Model>/constraint_{residual,jacobian,bias}/generated`, on 20 seeded random
/// states. Generated code only: the runtime reference has no force analysis. The states need
/// not close the loops: the code is straight-line, its time does not depend on the values.
macro_rules! bench_linkage {
    ($c:expr, $m:ty, $seed:literal, $loads:expr, $analysis:expr $(, $closure:ident)?) => {{
        const NQ: usize = <$m as Mechanism>::NQ;
        const NV: usize = <$m as Mechanism>::NV;
        let mut rng = SplitMix($seed);
        let states: Vec<([f64; NQ], [f64; NV], [f64; NV])> = (0..RANDOM_STATES)
            .map(|_| {
                (
                    std::array::from_fn(|_| rng.uniform(-PI, PI)),
                    std::array::from_fn(|_| rng.uniform(-2.0, 2.0)),
                    std::array::from_fn(|_| rng.uniform(-5.0, 5.0)),
                )
            })
            .collect();
        let loads = $loads;
        let analysis = $analysis;
        let mut group = $c.benchmark_group(<$m as Mechanism>::NAME);
        group.sampling_mode(SamplingMode::Flat);
        let mut k = 0;
        group.bench_function("force_analysis/generated", |b| {
            b.iter(|| {
                let (q, v, a) = &states[k % states.len()];
                k += 1;
                black_box(analysis(black_box(q), v, a, &loads))
            })
        });
        $(
            let _ = stringify!($closure);
            group.bench_function("constraint_residual/generated", |b| {
                b.iter(|| {
                    let (q, _, _) = &states[k % states.len()];
                    k += 1;
                    black_box(<$m>::constraint_residual(black_box(q)))
                })
            });
            group.bench_function("constraint_jacobian/generated", |b| {
                b.iter(|| {
                    let (q, _, _) = &states[k % states.len()];
                    k += 1;
                    black_box(<$m>::constraint_jacobian(black_box(q)))
                })
            });
            group.bench_function("constraint_bias/generated", |b| {
                b.iter(|| {
                    let (q, v, _) = &states[k % states.len()];
                    k += 1;
                    black_box(<$m>::constraint_bias(black_box(q), v))
                })
            });
        )?
        group.finish();
    }};
}

fn linkages(c: &mut Criterion) {
    bench_linkage!(
        c,
        SupportedBeam,
        2001,
        [1.0; 6],
        SupportedBeam::force_analysis
    );
    let no_loads = [0.0_f64; 0];
    bench_linkage!(
        c,
        FourBar,
        2002,
        no_loads,
        |q, v, a, _: &[f64; 0]| FourBar::force_analysis(q, v, a),
        closure
    );
    bench_linkage!(
        c,
        FourBarRockerDriven,
        2003,
        no_loads,
        |q, v, a, _: &[f64; 0]| FourBarRockerDriven::force_analysis(q, v, a),
        closure
    );
    bench_linkage!(
        c,
        SliderCrank,
        2004,
        no_loads,
        |q, v, a, _: &[f64; 0]| SliderCrank::force_analysis(q, v, a),
        closure
    );
    bench_linkage!(
        c,
        FourBarLoaded,
        2005,
        [1.0; 3],
        FourBarLoaded::force_analysis,
        closure
    );
    bench_linkage!(
        c,
        GyroscopicRotor,
        2006,
        no_loads,
        |q, v, a, _: &[f64; 0]| GyroscopicRotor::force_analysis(q, v, a)
    );
    bench_linkage!(
        c,
        OverhungRotor,
        2007,
        [1.0; 3],
        OverhungRotor::force_analysis
    );
}

/// Short by default, so that the whole file runs in minutes; the command line overrides
/// these (`--warm-up-time`, `--measurement-time`, `--sample-size`), as the comparison
/// script does.
fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(50)
}

/// The groups, by kind of model (criterion's macro makes each a public function).
#[allow(missing_docs)]
mod groups {
    use super::*;

    criterion_group! {
        name = anchors;
        config = config();
        targets = pendulum, double_pendulum, planar3, ur5, panda
    }
    criterion_group! {
        name = robots;
        config = config();
        targets = quadruped, puma560
    }
    criterion_group! {
        name = seed;
        config = config();
        targets = falling_rod, eccentric_rotor, gyroscopic_body
    }
    criterion_group! {
        name = chains;
        config = config();
        targets = chain1, chain2, chain3, chain5, chain10, chain15, chain20, chain25, chain30
    }
    criterion_group! {
        name = linkages;
        config = config();
        targets = super::linkages
    }
    criterion_group! {
        name = urdf_twins;
        config = config();
        targets = pendulum_urdf, double_pendulum_urdf, planar3_urdf, ur5_urdf, panda_urdf
    }
    criterion_group! {
        name = kinematics;
        config = config();
        targets = ur5_kinematics, panda_kinematics, quadruped_kinematics
    }
}

criterion_main!(
    groups::anchors,
    groups::robots,
    groups::seed,
    groups::chains,
    groups::linkages,
    groups::urdf_twins,
    groups::kinematics
);
