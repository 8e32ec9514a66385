//! Property-based fuzzing of the compiler library (`dynamics-codegen`), as the `mechanism!`
//! macro runs it: `syn::parse_str::<Mechanism>`, `compile`, `to_tokens`.
//!
//! What it asserts, on every input:
//!
//! - **No panic** and **bounded time**: the compiler returns, an error or a result, within
//!   [`time_limit`] (10 s in a debug build, where the largest bundled declaration takes
//!   about 2 s; 2 s optimised; `DYNAMICS_FUZZ_TIME_LIMIT=<seconds>` to change it).
//! - For an accepted input: its generated code parses as Rust items; the model its
//!   `Mechanism::model()` builds (read from the generated `model_with_parameters` by
//!   `fuzz_support/model.rs` and handed to the runtime's `ModelBuilder`) is accepted, so
//!   `model()` would not panic; and every generated function the runtime's `Reference`
//!   also computes (inverse and forward dynamics by each method, gravity, bias, mass and
//!   Coriolis matrices, energies, joint reactions), evaluated from its expression graph
//!   (`Compiled::evaluate`), equals the reference at random states, within
//!   1e-9 · (1 + max |value|), forward dynamics times cond(M). For a mutated declaration the
//!   reference's model is that generated model (as in `generated_*.rs`), and the comparison
//!   is made where its numbers are of ordinary size (masses up to 1e4, lengths up to 100)
//!   and M(q) is regular; for a random tree it is built from the tree's own description.
//!
//! The inputs:
//!
//! - `fuzz_mutated_declarations`: every `mechanism! { .. }` of the repository (the bundled
//!   models, the tests, the compile-fail catalog `tests/ui`, the examples of the language
//!   reference and the README), and random trees (below), changed by 1 to 3 token-level
//!   mutations (`fuzz_support/mutate.rs`): a token or a group deleted, duplicated, swapped
//!   or moved; a number replaced by 0, −1, 1e308, 5e-324, `0.0 / 0.0`, an overflowing
//!   expression, a 200-deep parenthesis or a 3000-term sum, or by a parameter scaled by
//!   such a value (`m / 0.0`, `m * 1e308`); an identifier replaced by another of the
//!   declaration or a word of the language; a `;` or a `,` dropped; a group emptied,
//!   unwrapped or given other delimiters; a string (the URDF path) replaced; a top-level
//!   item duplicated, deleted, swapped or moved.
//! - `fuzz_mutated_urdfs`: every URDF file of the repository, changed as text (numbers replaced
//!   by others or by garbage, elements dropped or duplicated, joints' links changed into
//!   cycles, two parents or self-joints, joint types, names and attribute values changed,
//!   attributes dropped, the file truncated, joints added, characters deleted or inserted),
//!   imported through `mechanism! { pub struct FromUrdf; urdf: "robot.urdf"; .. }` with a
//!   few settings, the file in a temporary directory given as the manifest directory.
//! - `fuzz_random_trees_agree_with_the_reference`: random mechanisms of 1 to 12 joints
//!   (`fuzz_support/trees.rs`): revolute, prismatic, fixed and free joints, fixed joints in
//!   odd places (at the root, between moving joints, at leaves, in chains), free bases with
//!   branches, parameters in masses, mass centres, inertias, placements, armatures,
//!   dampings and load points, shapes, full inertias, massless bodies welded to massive
//!   ones, loads on bodies merged through fixed joints, in body or world axes. Each is
//!   compiled and compared at 3 states, at random parameter values, with the reference
//!   built from the same description (shapes, rotations, merging all computed
//!   independently of the compiler); the compiler may reject a tree only for a coordinate
//!   without inertia (a massless body on a moving joint), or for an M(q) singular at every
//!   configuration (coordinates dependent in inertia through massless bodies), and then
//!   only if the reference's M is singular too (cond ≥ 1e12) at every state tried.
//!
//! **Budget.** By default the properties run a fixed number of cases (declarations 400,
//! URDF files 150, random trees 80): about 50 s of wall time in a debug build on two
//! cores, within the 90 s CI gives this test. `DYNAMICS_FUZZ_CASES=20000` runs that many
//! cases of each, for a longer run by hand (`--nocapture` prints each property's time, its
//! slowest input and how many inputs were accepted and compared);
//! `DYNAMICS_FUZZ_SEED=<u64>` draws another stream of cases. The seed is fixed, so CI runs
//! the same cases every time. `DYNAMICS_FUZZ_VERBOSE=1` prints every outcome.
//!
//! **A failure** names the input (the mutated text or the random declaration) after
//! proptest has shrunk it (at most two minutes), and proptest records it in
//! `tests/fuzz.proptest-regressions`, which replays it first on the next run (commit the
//! file to keep the case). Reproduce with `cargo test -p dynamics-tests --test fuzz --
//! --nocapture <property>` and the same `DYNAMICS_FUZZ_*` variables. An abort (a stack
//! overflow) ends the process before proptest can report: each property first writes the
//! input it runs to `target/tmp/fuzz-<property>.last-input`.

mod fuzz_support;
mod generated_support;

use dynamics_runtime::{LoadFrame, LoadType, Model, Reference, Wrench};
use dynamics_tests::random::SplitMix;
use fuzz_support::model;
use fuzz_support::mutate::{mutate_declaration, mutate_urdf, Mutation};
use fuzz_support::trees::{Features, Tree};
use generated_support::{mass_matrix_condition, random_inputs, reference_output, Inputs};
use nalgebra::Vector3;
use proc_macro2::{TokenStream, TokenTree};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{
    Config, FileFailurePersistence, RngSeed, TestCaseError, TestError, TestRunner,
};
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, OnceLock};
use std::time::{Duration, Instant};

/// The default seed of every property (CI runs the same cases every time).
const DEFAULT_SEED: u64 = 0xf022_2026;

/// States per random tree.
const STATES: usize = 3;

/// Tolerance of the comparison with the reference, relative to `1 + max |value|` (forward
/// dynamics: times cond(M)).
const TOLERANCE: f64 = 1e-9;

fn env_number<T: FromStr>(name: &str) -> Option<T> {
    let value = std::env::var(name).ok()?;
    match value.trim().parse() {
        Ok(v) => Some(v),
        Err(_) => panic!("{name}={value:?} is not a number"),
    }
}

/// The longest the compiler may take on one input: 10 s in a debug build (the largest
/// bundled declaration, 18 coordinates with kinematics outputs, takes about 2 s there),
/// 2 s optimised; `DYNAMICS_FUZZ_TIME_LIMIT` seconds when set.
fn time_limit() -> Duration {
    let default = if cfg!(debug_assertions) { 10.0 } else { 2.0 };
    Duration::from_secs_f64(env_number("DYNAMICS_FUZZ_TIME_LIMIT").unwrap_or(default))
}

/// The configuration of a property: `default_cases` cases (`DYNAMICS_FUZZ_CASES` when set),
/// a fixed seed (`DYNAMICS_FUZZ_SEED`), failures recorded next to this file, and at most two
/// minutes of shrinking.
fn config(test: &'static str, default_cases: u32) -> Config {
    Config {
        cases: env_number("DYNAMICS_FUZZ_CASES").unwrap_or(default_cases),
        rng_seed: RngSeed::Fixed(env_number("DYNAMICS_FUZZ_SEED").unwrap_or(DEFAULT_SEED)),
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        source_file: Some(file!()),
        test_name: Some(test),
        max_shrink_time: 120_000,
        ..Config::default()
    }
}

/// Runs a property; panics with the minimal failing input and proptest's message.
fn run<S: Strategy>(
    test: &'static str,
    default_cases: u32,
    strategy: S,
    property: impl Fn(S::Value) -> Result<(), TestCaseError>,
) where
    S::Value: std::fmt::Debug,
{
    let start = Instant::now();
    let mut runner = TestRunner::new(config(test, default_cases));
    match runner.run(&strategy, property) {
        Ok(()) => {}
        Err(TestError::Fail(reason, value)) => {
            panic!("{test}: {reason}\n(proptest's minimal input: {value:?})")
        }
        Err(TestError::Abort(reason)) => panic!("{test}: aborted: {reason}"),
    }
    println!(
        "{test}: {:.1?}, the slowest input {:.1?}",
        start.elapsed(),
        SLOWEST.with(std::cell::Cell::get)
    );
}

thread_local! {
    /// The longest one input took, on this test's thread.
    static SLOWEST: std::cell::Cell<Duration> = const { std::cell::Cell::new(Duration::ZERO) };
}

/// Runs `work` on its own thread (8 MiB of stack, as rustc gives a procedural macro):
/// `Ok` with its result if it returns within [`time_limit`], a failure naming `input` if it
/// panics or takes longer. `input` is first written to `target/tmp/fuzz-<test>.last-input`,
/// for the one failure that cannot be caught, an abort.
fn guarded<R: Send + 'static>(
    test: &str,
    input: &str,
    work: impl FnOnce() -> R + Send + 'static,
) -> Result<R, TestCaseError> {
    let last = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz-{test}.last-input"));
    // Best effort: a read-only target directory only loses the record.
    let _ = std::fs::write(&last, input);
    let limit = time_limit();
    let (sender, receiver) = mpsc::channel();
    let start = Instant::now();
    std::thread::Builder::new()
        .name(format!("fuzz-{test}"))
        .stack_size(8 << 20)
        .spawn(move || {
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            // The receiver is gone only after a timeout, which is reported already.
            let _ = sender.send(result);
        })
        .map_err(|e| TestCaseError::fail(format!("cannot spawn a thread: {e}")))?;
    match receiver.recv_timeout(limit) {
        Ok(Ok(result)) => {
            let elapsed = start.elapsed();
            if elapsed > limit {
                return Err(TestCaseError::fail(format!(
                    "the compiler (and the evaluation of its functions) took {elapsed:.1?} \
                     (> {limit:?}) on\n{input}"
                )));
            }
            SLOWEST.with(|slowest| slowest.set(slowest.get().max(elapsed)));
            Ok(result)
        }
        Ok(Err(payload)) => {
            let message = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "(not a string)".into());
            Err(TestCaseError::fail(format!(
                "the compiler panicked: {message}\non\n{input}"
            )))
        }
        Err(_) => Err(TestCaseError::fail(format!(
            "the compiler (and the evaluation of its functions) took longer than {limit:?} \
             (still running) on\n{input}"
        ))),
    }
}

/// What the compiler made of one declaration.
enum Outcome {
    /// A parse error (the message).
    Unparsed(String),
    /// A compile error (the message).
    Rejected(String),
    /// Compiled.
    Accepted(Box<Accepted>),
    /// Compiled, but the generated code does not parse, or its `model_with_parameters`
    /// cannot be read (the message).
    Broken(String),
}

/// An accepted declaration, as far as it is carried out of the compiler's thread.
struct Accepted {
    /// The model the generated `Mechanism::model()` builds, or the runtime's errors.
    model: Result<Model, String>,
    /// Random states, at the nominal parameters.
    states: Vec<Inputs<f64>>,
    /// The value of every generated function the reference also computes, at each state.
    values: Values,
}

/// Per function name, its value at each state.
type Values = Vec<(String, Vec<Vec<f64>>)>;

/// The generated functions the reference computes too (`reference_output`).
const REFERENCE_FUNCTIONS: [&str; 11] = [
    "inverse_dynamics",
    "gravity",
    "bias",
    "mass_matrix",
    "coriolis_matrix",
    "forward_dynamics",
    "forward_dynamics_aba",
    "forward_dynamics_ldlt",
    "kinetic_energy",
    "potential_energy",
    "joint_reactions",
];

/// States at which accepted mutated declarations are compared with the reference.
const MUTATED_STATES: usize = 2;

/// The values of the compiled functions named in `REFERENCE_FUNCTIONS` at each state.
fn evaluate(
    compiled: &dynamics_codegen::Compiled,
    states: &[Inputs<f64>],
) -> Result<Values, String> {
    let mut values = Vec::new();
    for function in compiled.functions() {
        if !REFERENCE_FUNCTIONS.contains(&function.name.as_str()) {
            continue;
        }
        let mut per_state = Vec::new();
        for x in states {
            let inputs: [(&str, &[f64]); 6] = [
                ("q", &x.q),
                ("v", &x.v),
                ("a", &x.a),
                ("tau", &x.tau),
                ("p", &x.p),
                ("loads", &x.loads),
            ];
            per_state.push(
                compiled
                    .evaluate(&function.name, &inputs)
                    .ok_or_else(|| format!("`{}` cannot be evaluated", function.name))?,
            );
        }
        values.push((function.name, per_state));
    }
    Ok(values)
}

/// Parses, compiles and prints `text` as the macro does (errors as `compile_error!`s); for
/// an accepted declaration, parses the printed code, builds the model its
/// `model_with_parameters` builds (`fuzz_support::model`) at the nominal parameters, and
/// evaluates its functions at random states of that model.
fn compile_text(text: &str, manifest_dir: &Path) -> Outcome {
    let mechanism = match syn::parse_str::<dynamics_codegen::Mechanism>(text) {
        Ok(m) => m,
        Err(e) => {
            let _ = e.to_compile_error();
            return Outcome::Unparsed(e.to_string());
        }
    };
    let compiled = match dynamics_codegen::compile(mechanism, manifest_dir) {
        Ok(compiled) => compiled,
        Err(e) => {
            let _ = e.to_compile_error();
            return Outcome::Rejected(e.to_string());
        }
    };
    let mut file = match syn::parse2::<syn::File>(dynamics_codegen::to_tokens(&compiled)) {
        Ok(file) => file,
        Err(e) => return Outcome::Broken(format!("the generated code does not parse: {e}")),
    };
    let read =
        |what: &str, e: String| Outcome::Broken(format!("{what} of the generated code: {e}"));
    if let Err(e) = dynamics_codegen::expand_if_std(&mut file) {
        return read("__if_std!", e.to_string());
    }
    let nominal = match model::nominal_parameters(&file) {
        Ok(p) => p,
        Err(e) => return read("NOMINAL_PARAMETERS", e),
    };
    let model = match model::model_with_parameters(&file, &nominal) {
        Ok(Ok(model)) => model,
        Ok(Err(errors)) => {
            return Outcome::Accepted(Box::new(Accepted {
                model: Err(errors.to_string()),
                states: Vec::new(),
                values: Vec::new(),
            }))
        }
        Err(e) => return read("model_with_parameters", e),
    };
    let mut rng = SplitMix(DEFAULT_SEED);
    let states: Vec<Inputs<f64>> = (0..MUTATED_STATES)
        .map(|_| random_inputs(&model, &nominal, model.num_load_inputs(), &mut rng))
        .collect();
    match evaluate(&compiled, &states) {
        Ok(values) => Outcome::Accepted(Box::new(Accepted {
            model: Ok(model),
            states,
            values,
        })),
        Err(e) => Outcome::Broken(e),
    }
}

/// Counts of outcomes of a property, printed at its end (`--nocapture`).
#[derive(Default)]
struct Tally {
    unparsed: AtomicUsize,
    rejected: AtomicUsize,
    accepted: AtomicUsize,
    /// Accepted and compared with the reference.
    compared: AtomicUsize,
}

impl Tally {
    fn record(&self, outcome: &Outcome) {
        if std::env::var_os("DYNAMICS_FUZZ_VERBOSE").is_some() {
            match outcome {
                Outcome::Unparsed(e) => println!("parse error: {e}"),
                Outcome::Rejected(e) => println!("compile error: {e}"),
                Outcome::Accepted(_) => println!("compiled"),
                Outcome::Broken(e) => println!("broken: {e}"),
            }
        }
        let counter = match outcome {
            Outcome::Unparsed(_) => &self.unparsed,
            Outcome::Rejected(_) => &self.rejected,
            Outcome::Accepted(_) | Outcome::Broken(_) => &self.accepted,
        };
        counter.fetch_add(1, Ordering::Relaxed);
    }

    fn counts(&self) -> [usize; 3] {
        [&self.unparsed, &self.rejected, &self.accepted].map(|c| c.load(Ordering::Relaxed))
    }

    fn print(&self, test: &str) {
        let [unparsed, rejected, accepted] = self.counts();
        let compared = self.compared.load(Ordering::Relaxed);
        println!(
            "{test}: {unparsed} parse errors, {rejected} compile errors, {accepted} compiled, \
             {compared} of them compared with the reference (shrinking included)"
        );
    }

    /// Checks the outcome ([`check_outcome`]) and counts it.
    fn check(&self, outcome: &Outcome, input: &str) -> Result<(), TestCaseError> {
        self.record(outcome);
        if check_outcome(outcome, input)? {
            self.compared.fetch_add(1, Ordering::Relaxed);
        }
        Ok(())
    }
}

/// A failure if the outcome is broken generated code, a model the runtime rejects, or
/// functions that differ from the reference (where its numbers are of ordinary size).
/// Returns whether the functions were compared.
fn check_outcome(outcome: &Outcome, input: &str) -> Result<bool, TestCaseError> {
    let fail = |what: String| TestCaseError::fail(format!("{what}\nfor\n{input}"));
    match outcome {
        Outcome::Broken(e) => Err(fail(e.clone())),
        Outcome::Unparsed(_) | Outcome::Rejected(_) => Ok(false),
        Outcome::Accepted(accepted) => {
            let model = accepted.model.as_ref().map_err(|e| {
                fail(format!(
                    "the compiler accepts what the runtime's ModelBuilder rejects \
                     (`Mechanism::model()` would panic): {e}"
                ))
            })?;
            if !ordinary(model) {
                return Ok(false);
            }
            let models = vec![model.clone(); accepted.states.len()];
            // The reference's panics too, with the input.
            let compared =
                std::panic::catch_unwind(|| compare(&models, &accepted.states, &accepted.values))
                    .map_err(|_| fail("the comparison with the reference panicked".into()))?;
            match compared.map_err(fail)? {
                Compared::Agree => Ok(true),
                Compared::Singular(_) => Ok(false),
            }
        }
    }
}

/// Whether a mutated model's numbers are of the size a comparison's tolerance means
/// something for: masses, inertias, armatures and dampings up to 1e4, lengths up to 100,
/// gravity up to 1e3 (mutations put 1e308 in them; the generated code and the reference
/// then differ by their different roundings of sums of huge terms).
fn ordinary(model: &Model) -> bool {
    let at_most = |x: f64, bound: f64| x.abs() <= bound;
    model.gravity_in_world().iter().all(|&g| at_most(g, 1e3))
        && model.bodies().iter().all(|b| {
            let (i, j) = (&b.inertia, &b.joint);
            at_most(i.mass, 1e4)
                && i.com_in_body.iter().all(|&c| at_most(c, 100.0))
                && i.inertia_com_in_body.iter().all(|&x| at_most(x, 1e4))
                && j.placement_in_parent
                    .translation
                    .iter()
                    .all(|&t| at_most(t, 100.0))
                && at_most(j.armature, 1e4)
                && at_most(j.damping, 1e4)
        })
        && model.loads().iter().all(|l| {
            l.placement_in_body
                .translation
                .iter()
                .all(|&t| at_most(t, 100.0))
        })
}

/// `max |a_k − b_k|`, NaN if any difference is (a NaN on either side), infinite if the
/// lengths differ (`dynamics_tests::max_abs_diff` passes over NaN).
fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter().zip(b).fold(0.0, |m: f64, (x, y)| {
        let d = (x - y).abs();
        if d.is_nan() || m.is_nan() {
            f64::NAN
        } else {
            m.max(d)
        }
    })
}

/// The result of a comparison with the reference.
enum Compared {
    /// Every function agrees at every state.
    Agree,
    /// M(q) is singular or nearly (its condition number) at some state: not compared there.
    Singular(f64),
}

/// Compares `values` (per function, per state) with the reference on `models[s]` at
/// `states[s]`, within [`TOLERANCE`] · (1 + max |value|), forward dynamics times cond(M).
fn compare(models: &[Model], states: &[Inputs<f64>], values: &Values) -> Result<Compared, String> {
    for (s, (model, x)) in models.iter().zip(states).enumerate() {
        let mut reference = Reference::<f64>::new(model);
        let wrenches = (model.num_load_inputs() > 0)
            .then(|| load_wrenches(&mut reference, model, &x.q, &x.loads));
        // (No M without coordinates: a mechanism asking only for its potential energy.)
        let cond = if model.nv() == 0 {
            1.0
        } else {
            mass_matrix_condition(&mut reference, &x.q)
        };
        if cond.is_nan() || cond <= 0.0 || cond >= 1e12 {
            return Ok(Compared::Singular(cond));
        }
        for (name, per_state) in values {
            let got = &per_state[s];
            let expected = reference_output(&mut reference, name, x, wrenches.as_deref());
            let scale = if name.starts_with("forward_dynamics") {
                cond
            } else {
                1.0
            };
            let error = max_difference(got, &expected);
            let allowed = TOLERANCE * scale * dynamics_tests::tolerance_scale(&expected);
            // NaN is an error too.
            if error.is_nan() || error > allowed {
                return Err(format!(
                    "`{name}` differs from the reference by {error:e} > {allowed:e} (cond(M) = \
                     {cond:.2e}) at state {s}: {x:?}\n  generated {got:?}\n  reference {expected:?}"
                ));
            }
        }
    }
    Ok(Compared::Agree)
}

// ---------------------------------------------------------------------------------------
// The corpus.

/// The repository's root.
fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ is in the repository")
}

/// A declaration of the repository.
struct Declaration {
    /// Where it is: the file and the declared type.
    origin: String,
    /// The directory its `urdf:` paths are relative to.
    manifest_dir: PathBuf,
    /// The tokens inside `mechanism! { .. }`.
    text: String,
}

/// The token runs `X` of every `mechanism! { X }` in `stream`, at any depth.
fn invocations(stream: TokenStream, out: &mut Vec<String>) {
    let tokens: Vec<TokenTree> = stream.into_iter().collect();
    for (k, t) in tokens.iter().enumerate() {
        if let TokenTree::Group(g) = t {
            let is_invocation = k >= 2
                && matches!(&tokens[k - 1], TokenTree::Punct(p) if p.as_char() == '!')
                && matches!(&tokens[k - 2], TokenTree::Ident(i) if i == "mechanism");
            if is_invocation {
                out.push(g.stream().to_string());
            } else {
                invocations(g.stream(), out);
            }
        }
    }
}

/// The `rust` code blocks of the doc comments (`///`, `//!`) of a Rust file, or of a
/// Markdown file, hidden lines (`# `) included.
fn doc_code_blocks(text: &str, markdown: bool) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut current: Option<String> = None;
    for line in text.lines() {
        let line = if markdown {
            line
        } else {
            let trimmed = line.trim_start();
            match trimmed
                .strip_prefix("///")
                .or_else(|| trimmed.strip_prefix("//!"))
            {
                Some(doc) => doc.strip_prefix(' ').unwrap_or(doc),
                None => continue,
            }
        };
        let fence = line.trim_start().starts_with("```");
        match (&mut current, fence) {
            (None, true) => {
                let lang = line.trim_start().trim_start_matches('`').trim();
                if lang.is_empty() || lang.starts_with("rust") {
                    current = Some(String::new());
                }
            }
            (Some(_), true) => blocks.extend(current.take()),
            (Some(code), false) => {
                let line = line.strip_prefix("# ").unwrap_or(line);
                code.push_str(line);
                code.push('\n');
            }
            (None, false) => {}
        }
    }
    blocks
}

/// The files with extension `ext` in `dir` (not recursive), sorted.
fn files(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let entries =
        std::fs::read_dir(dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()));
    let mut files: Vec<PathBuf> = entries
        .map(|e| {
            e.unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
                .path()
        })
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    files
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// Every declaration of the repository, each once.
fn declarations() -> &'static [Declaration] {
    static CORPUS: OnceLock<Vec<Declaration>> = OnceLock::new();
    CORPUS.get_or_init(|| {
        let root = root();
        // (directory, crate directory the `urdf:` paths are relative to). The compile-fail
        // cases name their fixtures `urdf/<file>.urdf` from `tests/ui` (see `ui.rs`).
        let sources = [
            ("models/src", "models"),
            ("models/examples", "models"),
            ("tests", "tests"),
            ("tests/ui", "tests/ui"),
            ("dynamics-runtime/src", "dynamics-runtime"),
        ];
        let mut corpus: Vec<Declaration> = Vec::new();
        let mut add = |origin: &Path, manifest: &str, text: String| {
            if corpus.iter().any(|d| d.text == text) {
                return;
            }
            let origin = origin
                .strip_prefix(root)
                .unwrap_or(origin)
                .display()
                .to_string();
            corpus.push(Declaration {
                origin,
                manifest_dir: root.join(manifest),
                text,
            });
        };
        for (dir, manifest) in sources {
            for path in files(&root.join(dir), "rs") {
                let text = read(&path);
                let mut found = Vec::new();
                if let Ok(stream) = TokenStream::from_str(&text) {
                    invocations(stream, &mut found);
                }
                for block in doc_code_blocks(&text, false) {
                    if let Ok(stream) = TokenStream::from_str(&block) {
                        invocations(stream, &mut found);
                    }
                }
                for declaration in found {
                    add(&path, manifest, declaration);
                }
            }
        }
        let readme = root.join("README.md");
        for block in doc_code_blocks(&read(&readme), true) {
            let mut found = Vec::new();
            if let Ok(stream) = TokenStream::from_str(&block) {
                invocations(stream, &mut found);
            }
            for declaration in found {
                add(&readme, ".", declaration);
            }
        }
        corpus
    })
}

/// Every URDF file of the repository: its path from the root and its text.
fn urdf_files() -> &'static [(String, String)] {
    static FILES: OnceLock<Vec<(String, String)>> = OnceLock::new();
    FILES.get_or_init(|| {
        let root = root();
        ["models/urdf", "tests/data/urdf", "tests/ui/urdf"]
            .iter()
            .flat_map(|dir| files(&root.join(dir), "urdf"))
            .map(|path| {
                let text = read(&path);
                let origin = path
                    .strip_prefix(root)
                    .unwrap_or(&path)
                    .display()
                    .to_string();
                (origin, text)
            })
            .collect()
    })
}

/// The corpus is what the module's docs say: the bundled models, the compile-fail catalog,
/// the language reference's examples, the URDF files.
#[test]
fn fuzz_corpus_holds_the_repository_s_declarations() {
    let corpus = declarations();
    let from = |prefix: &str| {
        corpus
            .iter()
            .filter(|d| d.origin.starts_with(prefix))
            .count()
    };
    assert!(
        from("models/src") >= 25,
        "{} from models/src",
        from("models/src")
    );
    assert!(from("tests/ui") >= 55, "{} from tests/ui", from("tests/ui"));
    assert!(
        from("dynamics-runtime/src/language.rs") >= 10,
        "{} from the language reference",
        from("dynamics-runtime/src/language.rs")
    );
    assert!(corpus.len() >= 150, "{} declarations", corpus.len());
    assert!(
        urdf_files().len() >= 10,
        "{} URDF files",
        urdf_files().len()
    );
    println!(
        "{} declarations, {} URDF files",
        corpus.len(),
        urdf_files().len()
    );
}

// ---------------------------------------------------------------------------------------
// Mutated declarations and URDF files.

fn mutation() -> impl Strategy<Value = Mutation> {
    (any::<u8>(), any::<u32>(), any::<u32>(), any::<u32>()).prop_map(|(kind, at, other, pick)| {
        Mutation {
            kind,
            at,
            other,
            pick,
        }
    })
}

fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    prop::collection::vec(mutation(), 1..=3)
}

/// What a mutated declaration starts from.
#[derive(Clone, Debug)]
enum Source {
    /// A declaration of the repository.
    Corpus(Index),
    /// A random tree (`fuzz_random_trees_agree_with_the_reference`'s), whose parameters, loads
    /// and fixed joints the repository's declarations have few of.
    Tree(u64, Features),
}

fn source() -> impl Strategy<Value = Source> {
    prop_oneof![
        3 => any::<Index>().prop_map(Source::Corpus),
        1 => (any::<u64>(), features()).prop_map(|(seed, f)| Source::Tree(seed, f)),
    ]
}

#[test]
fn fuzz_mutated_declarations() {
    let corpus = declarations();
    let tally = Tally::default();
    run(
        "mutated_declarations",
        400,
        (source(), mutations()),
        |(source, mutations)| {
            let (origin, original, manifest_dir) = match &source {
                Source::Corpus(which) => {
                    let d = &corpus[which.index(corpus.len())];
                    (d.origin.clone(), d.text.clone(), d.manifest_dir.clone())
                }
                Source::Tree(seed, features) => (
                    "a random tree".to_owned(),
                    Tree::generate(*seed, *features).declaration(),
                    root().to_owned(),
                ),
            };
            let text = mutate_declaration(&original, &mutations);
            let input = format!("{origin} after {mutations:?}:\n{text}");
            let outcome = guarded("mutated_declarations", &input, move || {
                compile_text(&text, &manifest_dir)
            })?;
            tally.check(&outcome, &input)
        },
    );
    tally.print("mutated_declarations");
    let [unparsed, rejected, accepted] = tally.counts();
    assert!(
        unparsed > 0 && rejected > 0 && accepted > 0,
        "every outcome occurs"
    );
}

/// The settings a mutated URDF file is imported with.
const URDF_SETTINGS: &[&str] = &[
    "outputs: [gravity, mass_matrix];",
    "floating_base: true; outputs: [inverse_dynamics, forward_dynamics];",
    "urdf_damping: false; gravity: none; outputs: [bias, energy];",
    "outputs: [joint_placements, frame_placements, center_of_mass];",
    "",
];

#[test]
fn fuzz_mutated_urdfs() {
    let files = urdf_files();
    let directory = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-urdf");
    std::fs::create_dir_all(&directory)
        .unwrap_or_else(|e| panic!("creating {}: {e}", directory.display()));
    let tally = Tally::default();
    run(
        "mutated_urdfs",
        150,
        (any::<Index>(), any::<Index>(), mutations()),
        |(which, settings, mutations)| {
            let (origin, original) = &files[which.index(files.len())];
            let text = mutate_urdf(original, &mutations);
            let settings = URDF_SETTINGS[settings.index(URDF_SETTINGS.len())];
            let declaration = format!("pub struct FromUrdf; urdf: \"robot.urdf\"; {settings}");
            let input =
                format!("`{declaration}` with robot.urdf = {origin} after {mutations:?}:\n{text}");
            std::fs::write(directory.join("robot.urdf"), &text)
                .map_err(|e| TestCaseError::fail(format!("writing the URDF file: {e}")))?;
            let manifest_dir = directory.clone();
            let outcome = guarded("mutated_urdfs", &input, move || {
                compile_text(&declaration, &manifest_dir)
            })?;
            tally.check(&outcome, &input)
        },
    );
    tally.print("mutated_urdfs");
    let [_, rejected, accepted] = tally.counts();
    assert!(rejected > 0 && accepted > 0, "both outcomes occur");
}

// ---------------------------------------------------------------------------------------
// Random trees against the reference.

fn features() -> impl Strategy<Value = Features> {
    (1..=12_usize, prop::array::uniform9(any::<bool>())).prop_map(|(joints, f)| Features {
        joints,
        free_base: f[0],
        fixed: f[1],
        parameters: f[2],
        shapes: f[3],
        massless: f[4],
        loads: f[5],
        friction: f[6],
        both_methods: f[7],
        shuffled: f[8],
    })
}

/// The external wrench on each body of `model` (in its frame, about its origin) from its
/// loads for the load inputs `loads` at configuration `q`: the components in the declared
/// body's axes turned into the tree body's, or in the world's turned by the body's
/// orientation at q; a force F at r adds the moment r × F.
fn load_wrenches(
    reference: &mut Reference<'_, f64>,
    model: &Model,
    q: &[f64],
    loads: &[f64],
) -> Vec<Wrench<f64>> {
    let poses = reference
        .body_poses(q)
        .expect("q has the model's size")
        .to_vec();
    let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
    for load in model.loads() {
        let Some(b) = load.body else {
            continue;
        };
        let placement = &load.placement_in_body;
        let component = |offset: usize| {
            let k = load.input_offset + offset;
            let given = Vector3::new(loads[k], loads[k + 1], loads[k + 2]);
            match load.frame {
                LoadFrame::Body => placement.rotation * given,
                LoadFrame::World => poses[b].rotation_in_world.transpose() * given,
            }
        };
        let (force, couple) = match load.kind {
            LoadType::Force => (component(0), Vector3::zeros()),
            LoadType::Couple => (Vector3::zeros(), component(0)),
            LoadType::Wrench => (component(0), component(3)),
        };
        wrenches[b].force += force;
        wrenches[b].moment += placement.translation.cross(&force) + couple;
    }
    wrenches
}

/// Compiles a random tree's declaration and evaluates its functions at `states`: `Ok(Err)`
/// with the compiler's message if it rejects the tree; `Err` if the generated code does not
/// parse or the model its `model()` builds is rejected by the runtime.
fn compile_and_evaluate(
    text: &str,
    states: &[Inputs<f64>],
) -> Result<Result<Values, String>, String> {
    let mechanism = syn::parse_str::<dynamics_codegen::Mechanism>(text)
        .map_err(|e| format!("the random declaration does not parse: {e}"))?;
    let compiled = match dynamics_codegen::compile(mechanism, Path::new(".")) {
        Ok(c) => c,
        Err(e) => return Ok(Err(e.to_string())),
    };
    let mut file = syn::parse2::<syn::File>(dynamics_codegen::to_tokens(&compiled))
        .map_err(|e| format!("the generated code does not parse: {e}"))?;
    dynamics_codegen::expand_if_std(&mut file).map_err(|e| e.to_string())?;
    let nominal = model::nominal_parameters(&file)?;
    model::model_with_parameters(&file, &nominal)?.map_err(|e| {
        format!("the runtime rejects the generated model (`Mechanism::model()` would panic): {e}")
    })?;
    evaluate(&compiled, states).map(Ok)
}

#[test]
fn fuzz_random_trees_agree_with_the_reference() {
    let tally = Tally::default();
    run(
        "random_trees",
        80,
        (any::<u64>(), features()),
        |(seed, features)| {
            let tree = Tree::generate(seed, features);
            let text = tree.declaration();
            let fail = |what: String| TestCaseError::fail(format!("{what}\nfor\n{text}"));
            // Parameters drawn in [0.5, 2] per state, never the nominal values exactly.
            let mut rng = SplitMix(seed ^ 0x0057_47e5);
            let nominal = tree.builder(tree.nominal()).build();
            let states: Vec<Inputs<f64>> = match &nominal {
                Ok(model) => (0..STATES)
                    .map(|_| {
                        let p: Vec<f64> = (0..tree.num_parameters())
                            .map(|_| rng.uniform(0.5, 2.0))
                            .collect();
                        random_inputs(model, &p, model.num_load_inputs(), &mut rng)
                    })
                    .collect(),
                Err(_) => Vec::new(),
            };
            let (source, inputs) = (text.clone(), states.clone());
            let evaluated = guarded("random_trees", &text, move || {
                compile_and_evaluate(&source, &inputs)
            })?
            .map_err(&fail)?;
            let values = match evaluated {
                // The one rule a random tree may break: massless bodies on moving joints give
                // a coordinate no inertia (a massless leaf, or one carrying only massless
                // bodies), or make coordinates dependent in inertia (massless links in a
                // chain ending at one body), so M(q) is singular. The latter is believed only
                // if the reference's M, at the compiler's nominal parameters, is singular
                // too at every state. Any other error is the generator's or the compiler's
                // mistake.
                Err(message) => {
                    if message.contains("the mass matrix M(q) is singular at every configuration") {
                        let model = nominal.as_ref().map_err(|e| {
                            fail(format!(
                                "the compiler finds M(q) singular, and the runtime rejects the \
                                 model: {e}"
                            ))
                        })?;
                        for x in &states {
                            let cond = mass_matrix_condition(&mut Reference::new(model), &x.q);
                            if !(cond.is_nan() || cond >= 1e12) {
                                return Err(fail(format!(
                                    "the compiler rejects the tree, but the reference's M(q) is \
                                     regular (cond {cond:e}) at q = {:?}: {message}",
                                    x.q
                                )));
                            }
                        }
                    } else if !message.contains("has no inertia") {
                        return Err(fail(format!("the compiler rejects the tree: {message}")));
                    }
                    tally.rejected.fetch_add(1, Ordering::Relaxed);
                    return Ok(());
                }
                Ok(values) => values,
            };
            tally.accepted.fetch_add(1, Ordering::Relaxed);
            if let Err(e) = &nominal {
                return Err(fail(format!(
                    "the compiler accepts what the runtime's ModelBuilder rejects: {e}"
                )));
            }
            let names: Vec<&str> = values.iter().map(|(name, _)| name.as_str()).collect();
            prop_assert_eq!(names, tree.functions(), "for\n{}", text);
            let models = states
                .iter()
                .map(|x| tree.builder(&x.p).build())
                .collect::<Result<Vec<Model>, _>>()
                .map_err(|e| fail(format!("the runtime rejects a parameter value: {e}")))?;
            match compare(&models, &states, &values).map_err(&fail)? {
                Compared::Agree => {
                    tally.compared.fetch_add(1, Ordering::Relaxed);
                }
                Compared::Singular(cond) => {
                    return Err(fail(format!(
                        "M(q) is singular (cond {cond:e}), and the compiler accepts the \
                         mechanism"
                    )))
                }
            }
            Ok(())
        },
    );
    tally.print("random_trees");
    let [_, rejected, accepted] = tally.counts();
    assert!(
        accepted >= 3 * rejected,
        "most random trees should compile: {accepted} compiled, {rejected} rejected"
    );
}
