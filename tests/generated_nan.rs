//! Non-finite inputs: the generated code never panics, and a NaN in any input (q, v, a,
//! τ, loads, p) is NaN in every output that depends on that input.
//!
//! Which outputs depend on which input is measured, not assumed: output j of a function
//! depends on input k when changing input k changes output j at one of two random states.
//! A NaN there must come out NaN. Outputs that do not depend on the input may stay finite
//! (gravity does not read v at all), or may not: a value can be constant although computed
//! from the input (the PUMA 560's M_34 is −0 at every q, from terms in q_4; a free base's
//! total gravity force is the same at every joint angle but is summed through the joint
//! rotations), and then NaN propagates; `--nocapture` prints how often.
//! Besides, a few dependencies the physics guarantees are asserted by name (inverse
//! dynamics on a_k through M_kk > 0, forward dynamics on τ_k, kinetic energy on v_k, each
//! joint's reaction on its own a_k, everything on the parameters and loads that act).
//! Infinities (±∞) in any input do not panic either.

#[macro_use]
mod generated_support;

use dynamics_runtime::{Mechanism, Model};
use dynamics_tests::random::SplitMix;
use generated_support::{arr, random_inputs, Function, Inputs, INPUT_ARRAYS};
use models::anchors::{Panda, Ur5};
use models::puma560::Puma560;
use models::seed::{EccentricRotor, GyroscopicBody};
use std::panic::{catch_unwind, AssertUnwindSafe};

#[macro_use]
mod trees {
    //! Small random trees of `tests/build.rs`: a symbolic mass (01), a free root with a
    //! load (02), three loads and a symbolic mass on a tree with prismatic joints (06), a
    //! free root with armature and damping (08); 06 and 08 have forward dynamics by both
    //! methods too.
    #![allow(dead_code)]
    include!(concat!(env!("OUT_DIR"), "/random_tree_01.rs"));
    include!(concat!(env!("OUT_DIR"), "/random_tree_02.rs"));
    include!(concat!(env!("OUT_DIR"), "/random_tree_06.rs"));
    include!(concat!(env!("OUT_DIR"), "/random_tree_08.rs"));
}
use trees::{RandomTree01, RandomTree02, RandomTree06, RandomTree08};

/// Evaluates `f`, turning a panic into a test failure that names the input.
fn call(
    mechanism: &str,
    function: &str,
    f: fn(&Inputs<f64>) -> Vec<f64>,
    x: &Inputs<f64>,
    what: &str,
) -> Vec<f64> {
    catch_unwind(AssertUnwindSafe(|| f(x)))
        .unwrap_or_else(|_| panic!("{mechanism}: {function} panicked with {what}"))
}

/// What one non-finite input did to one function.
struct Effect {
    /// Output j depends on the input (changes when it changes).
    depends: Vec<bool>,
    /// Output j with the input set to NaN.
    with_nan: Vec<f64>,
}

/// Checks every function of a mechanism against NaN and ±∞ in each input in turn; returns
/// the effects, by (array, index, function), for the named assertions.
fn check_mechanism(
    name: &str,
    model: &Model,
    p: &[f64],
    num_loads: usize,
    functions: &[Function<f64>],
    seed: u64,
) -> Vec<(&'static str, usize, &'static str, Effect)> {
    let mut rng = SplitMix(seed);
    let states = [
        random_inputs(model, p, num_loads, &mut rng),
        random_inputs(model, p, num_loads, &mut rng),
    ];
    let baseline: Vec<Vec<Vec<f64>>> = states
        .iter()
        .map(|x| functions.iter().map(|(_, f)| f(x)).collect())
        .collect();
    for outputs in &baseline[0] {
        assert!(
            outputs.iter().all(|y| y.is_finite()),
            "{name}: finite inputs, finite outputs"
        );
    }
    let mut effects = Vec::new();
    let mut nan_but_constant = 0;
    let mut cases = 0;
    for array in INPUT_ARRAYS {
        let len = states[0].clone().array_mut(array).len();
        for k in 0..len {
            let with = |s: usize, value: f64| {
                let mut x = states[s].clone();
                x.array_mut(array)[k] = value;
                x
            };
            let shifted = |s: usize, delta: f64| {
                let mut x = states[s].clone();
                x.array_mut(array)[k] += delta;
                x
            };
            for (i, &(function, f)) in functions.iter().enumerate() {
                let mut depends = vec![false; baseline[0][i].len()];
                for s in 0..2 {
                    for delta in [0.37, -1.1] {
                        let moved = call(name, function, f, &shifted(s, delta), "finite inputs");
                        for (d, (y, y0)) in
                            depends.iter_mut().zip(moved.iter().zip(&baseline[s][i]))
                        {
                            *d |= y != y0;
                        }
                    }
                }
                let what = format!("NaN in {array}[{k}]");
                let with_nan = call(name, function, f, &with(0, f64::NAN), &what);
                for (j, (&d, y)) in depends.iter().zip(&with_nan).enumerate() {
                    assert!(
                        !d || y.is_nan(),
                        "{name}: {function}[{j}] depends on {array}[{k}] but is {y} with {what}"
                    );
                    if !d && y.is_nan() {
                        nan_but_constant += 1;
                    }
                }
                for infinity in [f64::INFINITY, f64::NEG_INFINITY] {
                    call(
                        name,
                        function,
                        f,
                        &with(0, infinity),
                        &format!("{infinity} in {array}[{k}]"),
                    );
                }
                cases += with_nan.len();
                effects.push((array, k, function, Effect { depends, with_nan }));
            }
        }
    }
    println!(
        "{name}: of {cases} (input, output) pairs, {nan_but_constant} are NaN although the \
         output does not change with the input"
    );
    effects
}

/// The effect of input `array[k]` on `function`.
fn effect<'a>(
    effects: &'a [(&'static str, usize, &'static str, Effect)],
    array: &str,
    k: usize,
    function: &str,
) -> &'a Effect {
    effects
        .iter()
        .find(|(a, i, f, _)| *a == array && *i == k && *f == function)
        .map(|(.., e)| e)
        .unwrap_or_else(|| panic!("no effect of {array}[{k}] on {function}"))
}

/// The dependencies the physics guarantees for a mechanism with `nv` coordinates, checked
/// on what NaN did: τ_k on a_k (M_kk > 0), q̈_k on τ_k (M⁻¹_kk > 0), T on v_k, body k's
/// reaction on a_k (its joint's own coordinate; one coordinate per joint), and every
/// function that reads the parameters on each of them.
fn assert_named_dependencies(
    name: &str,
    effects: &[(&'static str, usize, &'static str, Effect)],
    functions: &[Function<f64>],
    nv: usize,
    single_coordinate_joints: bool,
) {
    let has = |f: &str| functions.iter().any(|(n, _)| *n == f);
    for k in 0..nv {
        if has("inverse_dynamics") {
            let e = effect(effects, "a", k, "inverse_dynamics");
            assert!(
                e.depends[k] && e.with_nan[k].is_nan(),
                "{name}: τ_{k} with NaN in a_{k}"
            );
        }
        for fd in [
            "forward_dynamics",
            "forward_dynamics_aba",
            "forward_dynamics_ldlt",
        ] {
            if has(fd) {
                let e = effect(effects, "tau", k, fd);
                assert!(
                    e.depends[k] && e.with_nan[k].is_nan(),
                    "{name}: {fd}: q̈_{k} with NaN in τ_{k}"
                );
            }
        }
        if has("kinetic_energy") {
            let e = effect(effects, "v", k, "kinetic_energy");
            assert!(
                e.depends[0] && e.with_nan[0].is_nan(),
                "{name}: T with NaN in v_{k}"
            );
        }
        if has("joint_reactions") && single_coordinate_joints {
            let e = effect(effects, "a", k, "joint_reactions");
            let body = &e.with_nan[6 * k..6 * k + 6];
            assert!(
                body.iter().any(|y| y.is_nan()),
                "{name}: reaction {k} with NaN in a_{k}"
            );
        }
    }
}

macro_rules! nan_tests {
    ($($test:ident: $m:ident, p: $p:tt, loads: $l:tt $(, [$($f:ident),*])?;)*) => {$(
        #[test]
        fn $test() {
            let functions: Vec<Function<f64>> =
                generated_functions!(f64, $m, p: $p, loads: $l $(, [$($f),*])?);
            assert_eq!(functions.len(), <$m as Mechanism>::FUNCTIONS.len());
            let model = <$m as Mechanism>::model();
            let p = <$m as Mechanism>::NOMINAL_PARAMETERS;
            let num_loads = <$m as Mechanism>::NUM_LOAD_INPUTS;
            let name = <$m as Mechanism>::NAME;
            let effects = check_mechanism(name, &model, p, num_loads, &functions, 0x4a4e);
            let single = model.nq() == model.nv();
            assert_named_dependencies(name, &effects, &functions, model.nv(), single);
            // Every parameter acts on every function that takes it (a mass scales the
            // energy and the dynamics), and every load input on the dynamics.
            for k in 0..p.len() {
                for (f, _) in &functions {
                    let e = effect(&effects, "p", k, f);
                    assert!(e.with_nan.iter().any(|y| y.is_nan()), "{name}: {f} with NaN in p[{k}]");
                }
            }
            for k in 0..num_loads {
                let reads_loads = |f: &str| {
                    ["inverse_dynamics", "joint_reactions"].contains(&f)
                        || f.starts_with("forward_dynamics")
                };
                for (f, _) in functions.iter().filter(|(f, _)| reads_loads(f)) {
                    let e = effect(&effects, "loads", k, f);
                    assert!(e.with_nan.iter().any(|y| y.is_nan()), "{name}: {f} with NaN in loads[{k}]");
                }
            }
        }
    )*};
}

nan_tests! {
    ur5: Ur5, p: no, loads: no;
    panda: Panda, p: no, loads: no;
    puma560: Puma560, p: no, loads: no;
    gyroscopic_body: GyroscopicBody, p: no, loads: no,
        [inverse_dynamics, mass_matrix, forward_dynamics, kinetic_energy, potential_energy];
    eccentric_rotor: EccentricRotor, p: no, loads: no,
        [inverse_dynamics, mass_matrix, kinetic_energy, potential_energy, joint_reactions];
    random_tree_01: RandomTree01, p: yes, loads: no;
    random_tree_02: RandomTree02, p: no, loads: yes;
    random_tree_06: RandomTree06, p: yes, loads: yes, [
        inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics,
        kinetic_energy, potential_energy, joint_reactions, forward_dynamics_aba,
        forward_dynamics_ldlt
    ];
    random_tree_08: RandomTree08, p: no, loads: no, [
        inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics,
        kinetic_energy, potential_energy, joint_reactions, forward_dynamics_aba,
        forward_dynamics_ldlt
    ];
}
