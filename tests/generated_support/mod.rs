//! Shared by the tests of generated code (`generated_*.rs`): one uniform signature for every
//! generated function, the reference's value of the same quantity, random inputs, and the
//! comparison with its record of the largest errors.
//!
//! A generated function is seen as `fn(&Inputs<S>) -> Vec<S>` (matrices flattened by rows,
//! scalars as one element), built by [`generated_functions!`] from the mechanism's type, so
//! that one loop can check every output of every mechanism.
//!
//! The reference's model is whatever [`UnderTest::model`] returns. For
//! `<M as Mechanism>::model_with_parameters` that is the code generator's resolution of the
//! declaration (rotations, inertia forms, parameter values) handed to `ModelBuilder`, shared
//! with the generated code; see `generated_vs_reference.rs` for what that leaves unchecked and
//! where it is checked independently.

// Each test binary uses part of this module.
#![allow(dead_code, unused_macros)]

use dynamics_runtime::Wrench;
use dynamics_runtime::{Model, Reference};
use dynamics_tests::random::{self, SplitMix};
use dynamics_tests::{max_abs_diff, tolerance_scale};
use nalgebra::{DMatrix, Vector3};
use std::collections::BTreeMap;

/// Every input a generated function can take; a function reads the ones in its signature.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs<S> {
    /// Configuration.
    pub q: Vec<S>,
    /// Velocity.
    pub v: Vec<S>,
    /// Acceleration (inverse dynamics, reactions).
    pub a: Vec<S>,
    /// Joint forces (forward dynamics).
    pub tau: Vec<S>,
    /// Symbolic parameters.
    pub p: Vec<S>,
    /// Applied loads.
    pub loads: Vec<S>,
}

impl Inputs<f64> {
    /// The inputs rounded to single precision.
    pub fn to_f32(&self) -> Inputs<f32> {
        let round = |x: &[f64]| x.iter().map(|&y| y as f32).collect();
        Inputs {
            q: round(&self.q),
            v: round(&self.v),
            a: round(&self.a),
            tau: round(&self.tau),
            p: round(&self.p),
            loads: round(&self.loads),
        }
    }

    /// The inputs as the single-precision code sees them, back in double precision.
    pub fn rounded_to_f32(&self) -> Inputs<f64> {
        let x = self.to_f32();
        let widen = |x: &[f32]| x.iter().map(|&y| f64::from(y)).collect();
        Inputs {
            q: widen(&x.q),
            v: widen(&x.v),
            a: widen(&x.a),
            tau: widen(&x.tau),
            p: widen(&x.p),
            loads: widen(&x.loads),
        }
    }

    /// The input array called `name` (`q`, `v`, `a`, `tau`, `p`, `loads`).
    pub fn array_mut(&mut self, name: &str) -> &mut Vec<f64> {
        match name {
            "q" => &mut self.q,
            "v" => &mut self.v,
            "a" => &mut self.a,
            "tau" => &mut self.tau,
            "p" => &mut self.p,
            "loads" => &mut self.loads,
            _ => panic!("no input array `{name}`"),
        }
    }
}

/// The names of the input arrays.
pub const INPUT_ARRAYS: [&str; 6] = ["q", "v", "a", "tau", "p", "loads"];

/// A generated function under one signature: its name and an adapter.
pub type Function<S> = (&'static str, fn(&Inputs<S>) -> Vec<S>);

/// A slice as the fixed-size array a generated function takes.
pub fn arr<S, const N: usize>(x: &[S]) -> &[S; N] {
    match x.try_into() {
        Ok(a) => a,
        Err(_) => panic!("an input of length {} where {N} is expected", x.len()),
    }
}

/// The generated functions of a mechanism as [`Function`]s over one scalar type:
/// `generated_functions!(f64, Ur5, p: no, loads: no, [inverse_dynamics, gravity, ...])`.
/// `p: yes` passes the parameters to every function, `loads: yes` the loads to inverse
/// dynamics, forward dynamics (and its `_aba` and `_ldlt` twins) and joint reactions (after
/// `p`, the documented order). Without a list, the default outputs.
macro_rules! generated_functions {
    ($s:ty, $m:ty, p: $p:tt, loads: $l:tt, [$($f:ident),* $(,)?]) => {
        vec![$(generated_functions!(@one $s, $m, $p, $l, $f)),*]
    };
    ($s:ty, $m:ty, p: $p:tt, loads: $l:tt) => {
        generated_functions!($s, $m, p: $p, loads: $l, [
            inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics,
            kinetic_energy, potential_energy, joint_reactions,
        ])
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, inverse_dynamics) => {
        generated_functions!(@adapt $s, inverse_dynamics, |x| generated_functions!(
            @call <$m>::inverse_dynamics, [arr(&x.q), arr(&x.v), arr(&x.a)], $p, $l, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, gravity) => {
        generated_functions!(@adapt $s, gravity, |x| generated_functions!(
            @call <$m>::gravity, [arr(&x.q)], $p, no, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, bias) => {
        generated_functions!(@adapt $s, bias, |x| generated_functions!(
            @call <$m>::bias, [arr(&x.q), arr(&x.v)], $p, no, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, mass_matrix) => {
        generated_functions!(@adapt $s, mass_matrix, |x| generated_functions!(
            @call <$m>::mass_matrix, [arr(&x.q)], $p, no, x).iter().flatten().copied().collect())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, coriolis_matrix) => {
        generated_functions!(@adapt $s, coriolis_matrix, |x| generated_functions!(
            @call <$m>::coriolis_matrix, [arr(&x.q), arr(&x.v)], $p, no, x)
            .iter().flatten().copied().collect())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, forward_dynamics) => {
        generated_functions!(@adapt $s, forward_dynamics, |x| generated_functions!(
            @call <$m>::forward_dynamics, [arr(&x.q), arr(&x.v), arr(&x.tau)], $p, $l, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, forward_dynamics_aba) => {
        generated_functions!(@adapt $s, forward_dynamics_aba, |x| generated_functions!(
            @call <$m>::forward_dynamics_aba, [arr(&x.q), arr(&x.v), arr(&x.tau)], $p, $l, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, forward_dynamics_ldlt) => {
        generated_functions!(@adapt $s, forward_dynamics_ldlt, |x| generated_functions!(
            @call <$m>::forward_dynamics_ldlt, [arr(&x.q), arr(&x.v), arr(&x.tau)], $p, $l, x).to_vec())
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, kinetic_energy) => {
        generated_functions!(@adapt $s, kinetic_energy, |x| vec![generated_functions!(
            @call <$m>::kinetic_energy, [arr(&x.q), arr(&x.v)], $p, no, x)])
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, potential_energy) => {
        generated_functions!(@adapt $s, potential_energy, |x| vec![generated_functions!(
            @call <$m>::potential_energy, [arr(&x.q)], $p, no, x)])
    };
    (@one $s:ty, $m:ty, $p:tt, $l:tt, joint_reactions) => {
        generated_functions!(@adapt $s, joint_reactions, |x| generated_functions!(
            @call <$m>::joint_reactions, [arr(&x.q), arr(&x.v), arr(&x.a)], $p, $l, x)
            .iter().flatten().copied().collect())
    };
    (@adapt $s:ty, $name:ident, |$x:ident| $body:expr) => {
        (
            stringify!($name),
            (|$x: &Inputs<$s>| -> Vec<$s> { $body }) as fn(&Inputs<$s>) -> Vec<$s>,
        )
    };
    (@call $f:expr, [$($arg:expr),*], no, no, $x:ident) => { $f($($arg),*) };
    (@call $f:expr, [$($arg:expr),*], yes, no, $x:ident) => { $f($($arg,)* arr(&$x.p)) };
    (@call $f:expr, [$($arg:expr),*], no, yes, $x:ident) => { $f($($arg,)* arr(&$x.loads)) };
    (@call $f:expr, [$($arg:expr),*], yes, yes, $x:ident) => {
        $f($($arg,)* arr(&$x.p), arr(&$x.loads))
    };
}

/// A random state for `model`: q (angles in ±π, prismatic coordinates in ±0.5 m, unit
/// quaternions), v in ±2, a in ±3, τ in ±5, the given parameters, and `num_loads` load
/// inputs in ±3.
pub fn random_inputs(
    model: &Model,
    p: &[f64],
    num_loads: usize,
    rng: &mut SplitMix,
) -> Inputs<f64> {
    let (q, v, a) = random::random_state(model, rng);
    let tau = (0..model.nv()).map(|_| rng.uniform(-5.0, 5.0)).collect();
    let loads = (0..num_loads).map(|_| rng.uniform(-3.0, 3.0)).collect();
    Inputs {
        q,
        v,
        a,
        tau,
        p: p.to_vec(),
        loads,
    }
}

/// The external wrench on each body of `model` that the declared loads (loaded body,
/// `force` | `couple` | `wrench`, point in the body frame) apply for the load inputs
/// `loads`: a force f at r and a couple n give F = f and M_P = r × f + n.
pub fn external_wrenches(
    model: &Model,
    declared: &[(&str, &str, [f64; 3])],
    loads: &[f64],
) -> Vec<Wrench<f64>> {
    let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
    let mut inputs = loads.iter().copied();
    let mut next3 = || {
        let mut v = Vector3::zeros();
        for k in 0..3 {
            v[k] = inputs.next().expect("enough load inputs");
        }
        v
    };
    for &(body, kind, point) in declared {
        let (force, couple) = match kind {
            "force" => (next3(), Vector3::zeros()),
            "couple" => (Vector3::zeros(), next3()),
            "wrench" => {
                let force = next3();
                (force, next3())
            }
            _ => panic!("unknown load kind `{kind}`"),
        };
        let b = model
            .body_index(body)
            .unwrap_or_else(|| panic!("no body `{body}`"));
        wrenches[b].force += force;
        wrenches[b].moment += Vector3::from(point).cross(&force) + couple;
    }
    wrenches
}

fn rows(m: &DMatrix<f64>) -> Vec<f64> {
    let n = m.nrows();
    (0..n)
        .flat_map(|i| (0..m.ncols()).map(move |j| (i, j)))
        .map(|(i, j)| m[(i, j)])
        .collect()
}

/// The reference's value of the quantity the generated function `name` computes, in the
/// same layout (matrices by rows).
pub fn reference_output(
    reference: &mut Reference<f64>,
    name: &str,
    x: &Inputs<f64>,
    wrenches: Option<&[Wrench<f64>]>,
) -> Vec<f64> {
    let model = reference.model();
    let nv = model.nv();
    let mut out = vec![0.0; nv];
    let mut matrix = DMatrix::zeros(nv, nv);
    let sizes = "the inputs have the model's sizes";
    match name {
        "inverse_dynamics" => {
            reference
                .inverse_dynamics(&x.q, &x.v, &x.a, wrenches, &mut out)
                .expect(sizes);
            out
        }
        "gravity" => {
            reference.gravity(&x.q, &mut out).expect(sizes);
            out
        }
        "bias" => {
            reference.bias(&x.q, &x.v, &mut out).expect(sizes);
            out
        }
        "mass_matrix" => {
            reference.mass_matrix(&x.q, &mut matrix).expect(sizes);
            rows(&matrix)
        }
        "coriolis_matrix" => {
            reference
                .coriolis_matrix(&x.q, &x.v, &mut matrix)
                .expect(sizes);
            rows(&matrix)
        }
        // The method-specific twins compute the same q̈.
        "forward_dynamics" | "forward_dynamics_aba" | "forward_dynamics_ldlt" => {
            reference
                .forward_dynamics(&x.q, &x.v, &x.tau, wrenches, &mut out)
                .expect(sizes);
            out
        }
        "kinetic_energy" => vec![reference.kinetic_energy(&x.q, &x.v).expect(sizes)],
        "potential_energy" => vec![reference.potential_energy(&x.q).expect(sizes)],
        "joint_reactions" => {
            let mut reactions = vec![Wrench::zero(); model.bodies().len()];
            reference
                .joint_reactions(&x.q, &x.v, &x.a, wrenches, &mut reactions)
                .expect(sizes);
            reactions
                .iter()
                .flat_map(|w| w.to_vector6().iter().copied().collect::<Vec<_>>())
                .collect()
        }
        _ => panic!("no reference for `{name}`"),
    }
}

/// The 2-norm condition number of the symmetric positive-definite M(q).
pub fn mass_matrix_condition(reference: &mut Reference<f64>, q: &[f64]) -> f64 {
    let nv = reference.model().nv();
    let mut m = DMatrix::zeros(nv, nv);
    reference
        .mass_matrix(q, &mut m)
        .expect("q has the model's size");
    dynamics_tests::condition_number(&m)
}

/// The largest errors seen, per output, relative to `1 + max |reference|` (and, for forward
/// dynamics, also relative to cond(M)).
#[derive(Debug, Default)]
pub struct Worst(BTreeMap<String, (f64, f64)>);

impl Worst {
    fn record(&mut self, what: &str, relative: f64, per_condition: f64) {
        let entry = self.0.entry(what.to_owned()).or_insert((0.0, 0.0));
        entry.0 = entry.0.max(relative);
        entry.1 = entry.1.max(per_condition);
    }

    /// Prints the table (visible with `--nocapture`).
    pub fn print(&self, title: &str) {
        println!(
            "{title}: largest error / (1 + max |reference|) [and / cond(M) for forward dynamics]"
        );
        for (what, (relative, per_condition)) in &self.0 {
            if what.starts_with("forward_dynamics") {
                println!("  {what:<28} {relative:9.2e}  [{per_condition:9.2e}]");
            } else {
                println!("  {what:<28} {relative:9.2e}");
            }
        }
    }
}

/// Asserts `max |generated − reference| ≤ tolerance · cond · (1 + max |reference|)`, with
/// `cond` = 1 except for forward dynamics, and records the error.
#[track_caller]
pub fn assert_close(
    mechanism: &str,
    what: &str,
    generated: &[f64],
    reference: &[f64],
    tolerance: f64,
    cond: f64,
    worst: &mut Worst,
) {
    let scale = tolerance_scale(reference);
    let error = max_abs_diff(generated, reference);
    worst.record(what, error / scale, error / scale / cond);
    dynamics_tests::assert_close(
        &format!("{mechanism}: {what} (cond {cond:.3e})"),
        generated,
        reference,
        tolerance * cond,
    );
}

/// Tolerances of the comparison with the reference, relative to `1 + max |value|` (forward
/// dynamics: times cond(M)).
pub const F64_TOLERANCE: f64 = 1e-12;
/// The same in single precision.
pub const F32_TOLERANCE: f64 = 1e-4;

/// The runtime model of a mechanism for given parameter values.
pub type ModelFor<'a> = Box<dyn Fn(&[f64]) -> Model + 'a>;

/// A mechanism under test: its functions in both precisions and how to build its model.
pub struct UnderTest<'a> {
    /// The type's name.
    pub name: &'a str,
    /// The runtime model for given parameter values.
    pub model: ModelFor<'a>,
    /// Number of parameters (each drawn in [0.5, 2] per state).
    pub num_parameters: usize,
    /// The declared loads (see [`external_wrenches`]).
    pub loads: &'a [(&'a str, &'a str, [f64; 3])],
    /// Number of load inputs.
    pub num_load_inputs: usize,
    /// The generated functions in double precision.
    pub f64: Vec<Function<f64>>,
    /// The same in single precision.
    pub f32: Vec<Function<f32>>,
}

/// Checks every generated function of `m`, in f64 and f32, against the reference at
/// `states` random states (parameters drawn in [0.5, 2] each time, never the nominal value
/// exactly); returns the largest errors.
pub fn check_against_reference(m: &UnderTest<'_>, states: usize, seed: u64) -> Worst {
    let mut worst = Worst::default();
    let mut rng = SplitMix(seed);
    for _ in 0..states {
        let p: Vec<f64> = (0..m.num_parameters)
            .map(|_| rng.uniform(0.5, 2.0))
            .collect();
        let model = (m.model)(&p);
        let x = random_inputs(&model, &p, m.num_load_inputs, &mut rng);
        compare_all(m, &x, &x, &m.f64, F64_TOLERANCE, "", &mut worst);
        // Single precision, against the reference at exactly the inputs the f32 code sees.
        compare_all(
            m,
            &x.rounded_to_f32(),
            &x.to_f32(),
            &m.f32,
            F32_TOLERANCE,
            " (f32)",
            &mut worst,
        );
    }
    worst
}

/// Compares every function of `functions` at `x` with the reference at `exact` (`x` in
/// double precision).
fn compare_all<S: Copy + Into<f64>>(
    m: &UnderTest<'_>,
    exact: &Inputs<f64>,
    x: &Inputs<S>,
    functions: &[Function<S>],
    tolerance: f64,
    suffix: &str,
    worst: &mut Worst,
) {
    let model = (m.model)(&exact.p);
    let mut reference = Reference::<f64>::new(&model);
    let wrenches =
        (m.num_load_inputs > 0).then(|| external_wrenches(&model, m.loads, &exact.loads));
    let cond = mass_matrix_condition(&mut reference, &exact.q);
    for (name, f) in functions {
        let expected = reference_output(&mut reference, name, exact, wrenches.as_deref());
        let got: Vec<f64> = f(x).into_iter().map(Into::into).collect();
        let cond = if name.starts_with("forward_dynamics") {
            cond
        } else {
            1.0
        };
        let what = format!("{name}{suffix}");
        assert_close(m.name, &what, &got, &expected, tolerance, cond, worst);
    }
}
