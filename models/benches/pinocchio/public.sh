#!/usr/bin/env bash
# The generated code against Pinocchio on robots the project never declared: URDFs of
# example-robot-data, installed at benchmark time, compiled by the macro as a user's crate
# would, timed beside Pinocchio on the same states.
#
#   bash models/benches/pinocchio/public.sh [--quick] [--isa] [--robots "go2 xarm7 g1"]
#                                           [--rotation-tolerance 1e-10] [--avx512] [--lanes]
#
# Steps:
#   1. `compare.sh --setup-only`: Pinocchio (pin) in ./venv and ./build/timing, as for the
#      main comparison;
#   2. installs example-robot-data into the same venv and, with public_robots.py, writes
#      build/public/<robot>.urdf (the package's file, joint damping and friction removed:
#      Pinocchio's rnea ignores them) and build/public/<robot>.json (the model Pinocchio
#      builds from that file, free-flyer root for the legged robots, and 20 seeded states
#      with Pinocchio's outputs);
#   3. per robot, a throwaway crate build/public/<robot>/ whose library is one declaration,
#      `mechanism! { pub struct Robot; urdf: ".."; floating_base: ..; outputs: [..]; }`,
#      and whose benchmark is public_bench.rs: it checks every timed output against
#      Pinocchio's at every state (1e-10 relative) before timing;
#   4. robot by robot, Pinocchio (build/timing) then the generated code, each output one call
#      per state, medians; the two sides' state fingerprints must match;
#   5. prints the table (also build/public/comparison.md).
# --isa: after each robot's benchmark, its two kernel copies too, AVX2 + FMA against
# baseline (SSE2), each dynamics output in paired rounds in one process (public_isa.rs,
# an example of the robot's crate); the table goes to build/public/isa.md.
# --rotation-tolerance T: each declaration also says `rotation_tolerance: T;`, which takes
# the rotation entries within T of 0 or ±1 as exact (a quarter turn written 1.57079632679
# leaves 4.9e-12, which the default keeps, as Pinocchio does; the outputs are then checked
# against Pinocchio's within 1e-10 + 100 T, as the model moves by up to T).
# --avx512: the robots' crates depend on dynamics-runtime with its `avx512` feature, so on a
# CPU with AVX-512F/VL the wide copy that runs is the build with 32 vector registers (the
# table's code kB stays the AVX2 + FMA copy's).
# --lanes: each declaration also says `lanes: true;`, and after each robot's benchmark its
# inverse dynamics, mass matrix (in place) and forward dynamics run on 64 states one f64
# call per state against F64x4 and F32x8 lanes (public_lanes.rs, an example of the robot's
# crate, which checks the lanes' results against f64 first); the table goes to
# build/public/lanes.md.
# Robots: go2 (Unitree quadruped, free base, 18 dof), xarm7 (7-dof arm), g1 (Unitree humanoid,
# 29 joints, free base, 35 dof); by name also the 18-dof quadrupeds anymal (ANYmal C),
# solo12, a1 and hyq, the arm z1 (Unitree Z1: 6 joints and a revolute gripper joint,
# 7 dof) and the humanoid talos (PAL's Talos, talos_reduced.urdf: 32 joints and a free
# base, 38 dof, its grippers' mimic joints independent coordinates, as Pinocchio's
# buildModel makes them; every declaration says `urdf_mimic: false;`, which changes
# nothing for a file without mimic joints). Nothing of example-robot-data is committed.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
ROBOTS="go2 xarm7 g1"
QUICK=0
ISA=0
LANES=0
TOLERANCE=""
RUNTIME_FEATURES=""
ERD_VERSION="${ERD_VERSION:-6.0.0}"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) QUICK=1 ;;
    --isa) ISA=1 ;;
    --lanes) LANES=1 ;;
    --robots) ROBOTS="$2"; shift ;;
    --rotation-tolerance) TOLERANCE="$2"; shift ;;
    --avx512) RUNTIME_FEATURES='"avx512"'; export PUBLIC_AVX512=1 ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "public.sh: unknown argument $1 (try --help)" >&2; exit 2 ;;
  esac
  shift
done

STEP="starting"
fail() { echo "public.sh: FAILED while $STEP${1:+: $1}" >&2; exit 1; }
trap 'fail "command exited with status $? (see the output above)"' ERR
step() { STEP="$1"; echo "==> $1" >&2; }

step "setting up Pinocchio and the timing program (compare.sh --setup-only)"
bash "$HERE/compare.sh" --setup-only
VENV="$HERE/venv"
OUT="$HERE/build/public"
mkdir -p "$OUT"

step "installing example-robot-data $ERD_VERSION and writing the robots' files"
if ! grep -qx "example-robot-data==$ERD_VERSION" "$VENV/.installed-erd" 2>/dev/null; then
  "$VENV/bin/python" -m pip install -q "example-robot-data==$ERD_VERSION" ||
    fail "pip install example-robot-data==$ERD_VERSION failed (network?)"
  echo "example-robot-data==$ERD_VERSION" > "$VENV/.installed-erd"
fi
# shellcheck disable=SC2086
"$VENV/bin/python" "$HERE/public_robots.py" "$OUT" $ROBOTS > "$OUT/robots.tsv"

if [ "$QUICK" = 1 ]; then
  PIN_ARGS=(--reps 5 --min-rep-ms 20 --warmup-ms 50)
  CRIT_ARGS=(--warm-up-time 0.3 --measurement-time 0.5 --sample-size 10)
else
  PIN_ARGS=(--reps 21 --min-rep-ms 100 --warmup-ms 300)
  CRIT_ARGS=(--warm-up-time 1 --measurement-time 3 --sample-size 21)
fi
BASELINE=public_pinocchio
# Every output of a URDF robot without frames or constraints (joint_reactions and the
# single kinematics outputs are built and counted, not timed: Pinocchio has no
# counterpart call).
OUTPUTS="inverse_dynamics, mass_matrix_into, forward_dynamics, gravity, bias, coriolis_matrix_into,
              kinetic_energy, joint_reactions, joint_placements, forward_kinematics,
              joint_velocities, joint_acceleration_biases, joint_jacobians,
              joint_jacobians_world, joint_jacobians_world_time_variation, center_of_mass,
              center_of_mass_jacobian, centroidal_momentum_matrix_into, centroidal_bias,
              inverse_dynamics_derivatives_into, forward_dynamics_derivatives_into,
              mass_matrix_inverse_into, mass_matrix_sparse_into, coriolis_matrix_sparse_into,
              inverse_dynamics_derivatives_sparse_into, mass_matrix_inverse_sparse_into,
              joint_jacobians_sparse_into"

: > "$OUT/pinocchio.tsv"
: > "$OUT/build.tsv"
: > "$OUT/criterion.log"
: > "$OUT/load.tsv"
if [ "$LANES" = 1 ]; then
  printf '| robot | function | f64 ns | F64x4 ns (gain) | F64x4 prepacked ns (gain) | F32x8 ns (gain) |\n| --- | --- | ---: | ---: | ---: | ---: |\n' > "$OUT/lanes.md"
fi
if [ "$ISA" = 1 ]; then
  printf '| robot | output | baseline ns | AVX2 + FMA ns | wide / baseline |\n| --- | --- | ---: | ---: | ---: |\n' > "$OUT/isa.md"
fi
# v0 symbol mangling keeps the generic arguments in the symbols (for the code sizes); it
# changes no code.
export RUSTFLAGS="-C symbol-mangling-version=v0"
while IFS=$'\t' read -r robot nq nv base urdf; do
  CRATE="$OUT/$robot"
  step "$robot ($nv dof, $base base): writing its crate ($CRATE)"
  mkdir -p "$CRATE/src"
  cat > "$CRATE/Cargo.toml" <<EOF
# Written by public.sh: the generated code of $robot, benchmarked. Not part of the workspace.
[package]
name = "public-robot"
version = "0.0.0"
edition = "2021"
publish = false

[workspace]

[dependencies]
dynamics-runtime = { path = "$ROOT/dynamics-runtime", features = [$RUNTIME_FEATURES] }

[dev-dependencies]
criterion = { version = "0.7", default-features = false, features = ["cargo_bench_support"] }
serde_json = { version = "1", features = ["float_roundtrip"] }

[[bench]]
name = "public"
path = "$HERE/public_bench.rs"
harness = false

[[example]]
name = "isa"
path = "$HERE/public_isa.rs"

[[example]]
name = "lanes"
path = "$HERE/public_lanes.rs"

[profile.release]
opt-level = 3
codegen-units = 16
debug = false
lto = "thin"

[profile.bench]
inherits = "release"
EOF
  floating=false
  LANES_SETTING=""
  [ "$LANES" = 1 ] && LANES_SETTING="
    lanes: true;"
  [ "$base" = free ] && floating=true
  cat > "$CRATE/src/lib.rs" <<EOF
//! Written by public.sh: $robot from example-robot-data, as a user would declare it.
dynamics_runtime::mechanism! {
    /// $robot (example-robot-data), joint damping and friction removed.
    pub struct Robot;
    urdf: "$(realpath "$urdf")";
    floating_base: $floating;
    urdf_mimic: false;${TOLERANCE:+
    rotation_tolerance: $TOLERANCE;}${LANES_SETTING}
    outputs: [$OUTPUTS];
}
EOF
  [ -f "$CRATE/Cargo.lock" ] || cp "$ROOT/Cargo.lock" "$CRATE/Cargo.lock"
  step "$robot: building the generated code and its benchmark"
  cargo bench -q --manifest-path "$CRATE/Cargo.toml" --bench public --no-run 2> "$CRATE/cargo.log" ||
    { tail -30 "$CRATE/cargo.log" >&2; fail "$robot's crate does not build (log: $CRATE/cargo.log)"; }
  # The robot's own build, dependencies built: the library (the macro's expansion and
  # rustc on the generated code, in the release profile) and the benchmark that
  # instantiates its functions in f64. Wall time and peak memory of the largest process.
  touch "$CRATE/src/lib.rs"
  /usr/bin/time -f "%e %M" -o "$CRATE/build-cost" \
    cargo bench -q --manifest-path "$CRATE/Cargo.toml" --bench public --no-run 2>> "$CRATE/cargo.log" ||
    fail "$robot's crate does not rebuild (log: $CRATE/cargo.log)"
  read -r SECONDS_BUILD KB_BUILD < "$CRATE/build-cost"
  printf '%s\t%s\t%s\n' "$robot" "$SECONDS_BUILD" "$KB_BUILD" >> "$OUT/build.tsv"
  echo "    rebuilt in $SECONDS_BUILD s, peak $((KB_BUILD / 1024)) MB" >&2
  # The machine code of each generated function, from the benchmark binary's symbols (v0
  # mangling names the function each kernel copy was instantiated for).
  # The newest: earlier builds of the same crate leave their binaries beside it.
  BIN="$(find "$CRATE/target/release/deps" -maxdepth 1 -type f -executable -name 'public-*' \
    -printf '%T@ %p\n' | sort -rn | head -1 | cut -d' ' -f2-)"
  nm -S --size-sort -C "$BIN" | grep 'public_robot::Robot>::' > "$CRATE/code-size.txt" || true

  LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
  step "$robot: Pinocchio (load average $LOAD)"
  printf '%s\tpinocchio\t%s\n' "$robot" "$LOAD" >> "$OUT/load.tsv"
  for group in dynamics kinematics; do
    "$HERE/build/timing" "${PIN_ARGS[@]}" --group "$group" "$OUT/$robot.json" >> "$OUT/pinocchio.tsv" ||
      fail "the timing program failed on $robot.json"
  done
  LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
  step "$robot: generated code (load average $LOAD)"
  printf '%s\tgenerated\t%s\n' "$robot" "$LOAD" >> "$OUT/load.tsv"
  find "$CRATE/target/criterion" -type d -name "$BASELINE" -prune -exec rm -rf {} + 2>/dev/null || true
  PUBLIC_ROBOT="$robot" PUBLIC_ROBOT_JSON="$OUT/$robot.json" PUBLIC_ROTATION_TOLERANCE="$TOLERANCE" \
    cargo bench -q --manifest-path "$CRATE/Cargo.toml" --bench public -- \
    "${CRIT_ARGS[@]}" --save-baseline "$BASELINE" >> "$OUT/criterion.log" 2>&1 ||
    { tail -30 "$OUT/criterion.log" >&2; fail "$robot's benchmark failed (log: $OUT/criterion.log)"; }
  if [ "$ISA" = 1 ]; then
    step "$robot: the baseline and the AVX2 + FMA copies, paired (load average $(cut -d' ' -f1-3 /proc/loadavg))"
    PUBLIC_ROBOT="$robot" cargo run -q --release --manifest-path "$CRATE/Cargo.toml" --example isa \
      >> "$OUT/isa.md" 2>> "$CRATE/cargo.log" ||
      { tail -30 "$CRATE/cargo.log" >&2; fail "$robot's isa example failed (log: $CRATE/cargo.log)"; }
  fi
  if [ "$LANES" = 1 ]; then
    step "$robot: many states per call, f64 against lanes (load average $(cut -d' ' -f1-3 /proc/loadavg))"
    PUBLIC_ROBOT="$robot" cargo run -q --release --manifest-path "$CRATE/Cargo.toml" --example lanes \
      >> "$OUT/lanes.md" 2>> "$CRATE/cargo.log" ||
      { tail -30 "$CRATE/cargo.log" >&2; fail "$robot's lanes example failed (log: $CRATE/cargo.log)"; }
  fi
done < "$OUT/robots.tsv"

step "joining the results"
CPU="$(LC_ALL=C lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)"
PYTHONPATH="$HERE" "$VENV/bin/python" - "$OUT" "$BASELINE" "$CPU" "$(nproc)" "$QUICK" "$(rustc --version)" \
  "$(g++ --version | head -1)" "$TOLERANCE" <<'PYTHON' || fail "could not join the two sides' results"
import os, re, sys

out_dir, baseline, cpu, cores, quick, rustc, gxx, tolerance = sys.argv[1:]
import results  # results.py beside this script (PYTHONPATH)
# Pinocchio's call (the faster of its conventions where it has two) beside ours.
ROWS = [("rnea", ["rnea"], "inverse_dynamics"),
        ("crba", ["crba", "crba_world"], "mass_matrix"),
        ("aba", ["aba", "aba_world"], "forward_dynamics"),
        ("forwardKinematics(q)", ["forwardKinematics_q"], "joint_placements"),
        ("forwardKinematics(q, v, a)", ["forwardKinematics_qva"], "forward_kinematics"),
        ("computeJointJacobians", ["computeJointJacobians"], "joint_jacobians_world"),
        ("computeJointJacobians + getJointJacobian × all joints",
         ["computeJointJacobians_getJointJacobian"], "joint_jacobians"),
        ("computeJointJacobiansTimeVariation", ["computeJointJacobiansTimeVariation"],
         "joint_jacobians_world_time_variation"),
        ("centerOfMass", ["centerOfMass"], "center_of_mass"),
        ("jacobianCenterOfMass", ["jacobianCenterOfMass"], "center_of_mass_jacobian"),
        ("ccrba", ["ccrba"], "centroidal_momentum_matrix"),
        ("computeGeneralizedGravity", ["computeGeneralizedGravity"], "gravity"),
        ("nonLinearEffects", ["nonLinearEffects"], "bias"),
        ("computeCoriolisMatrix", ["computeCoriolisMatrix"], "coriolis_matrix"),
        ("dccrba", ["dccrba"], "centroidal_bias"),
        ("computeRNEADerivatives", ["computeRNEADerivatives"], "inverse_dynamics_derivatives"),
        ("computeABADerivatives", ["computeABADerivatives"], "forward_dynamics_derivatives"),
        ("computeMinverse", ["computeMinverse"], "mass_matrix_inverse"),
        # The large matrices written into the caller's storage (`_into`), as Pinocchio
        # writes into its `Data`.
        ("crba", ["crba", "crba_world"], "mass_matrix_into"),
        ("ccrba", ["ccrba"], "centroidal_momentum_matrix_into"),
        ("computeCoriolisMatrix", ["computeCoriolisMatrix"], "coriolis_matrix_into"),
        ("computeRNEADerivatives", ["computeRNEADerivatives"], "inverse_dynamics_derivatives_into"),
        ("computeABADerivatives", ["computeABADerivatives"], "forward_dynamics_derivatives_into"),
        ("computeMinverse", ["computeMinverse"], "mass_matrix_inverse_into"),
        # Only the entries that can be nonzero (`_sparse_into`), of M and M⁻¹ those on and
        # above the diagonal (what crba and computeMinverse fill), the rest of `out` zero
        # from the start, as in Pinocchio's `Data`.
        ("crba", ["crba", "crba_world"], "mass_matrix_sparse_into"),
        ("computeCoriolisMatrix", ["computeCoriolisMatrix"], "coriolis_matrix_sparse_into"),
        ("computeRNEADerivatives", ["computeRNEADerivatives"],
         "inverse_dynamics_derivatives_sparse_into"),
        ("computeMinverse", ["computeMinverse"], "mass_matrix_inverse_sparse_into"),
        # getJointJacobian writes a joint's supporting columns into a J zeroed once.
        ("computeJointJacobians + getJointJacobian × all joints",
         ["computeJointJacobians_getJointJacobian"], "joint_jacobians_sparse_into")]

robots = [line.split("\t")[:3] for line in open(os.path.join(out_dir, "robots.tsv"))]
pin, pin_states, _, header = results.pinocchio(os.path.join(out_dir, "pinocchio.tsv"))
ours_states = results.states(os.path.join(out_dir, "criterion.log"), "public.sh")
loads = {}
for line in open(os.path.join(out_dir, "load.tsv")):
    robot, side, load = line.rstrip("\n").split("\t")
    loads[(robot, side)] = load.split()[0]
ours = {}
for robot, _, _ in robots:
    ours.update(results.criterion_medians(os.path.join(out_dir, robot, "target", "criterion"),
                                          baseline))

build = {}
for line in open(os.path.join(out_dir, "build.tsv")):
    robot, seconds, kb = line.split()
    build[robot] = (float(seconds), int(kb) / 1024)

def code_kb(robot, function):
    """kB of machine code of one generated function: its AVX2 + FMA kernels (the copy that
    runs on this machine; the baseline copy is about as large), or all its symbols when it
    has none."""
    path = os.path.join(out_dir, robot, "code-size.txt")
    sizes = {"avx2": 0, "any": 0}
    for line in open(path) if os.path.exists(path) else []:
        fields = line.split(None, 3)
        if len(fields) == 4 and re.search(rf"Robot>::{function}(<|$)", fields[3]):
            size = int(fields[1], 16)
            sizes["any"] += size
            if "isa::avx2_fma::" in fields[3]:
                sizes["avx2"] += size
    return (sizes["avx2"] or sizes["any"]) / 1024

problems, lines = [], []
for robot, nq, nv in robots:
    if pin_states.get(robot) is None or pin_states.get(robot) != ours_states.get(robot):
        problems.append(f"{robot}: the states differ ({pin_states.get(robot)}, {ours_states.get(robot)})")
    for call, variants, function in ROWS:
        times = [(pin[(robot, v)], v) for v in variants if (robot, v) in pin]
        o = ours.get(f"{robot}/{function}/generated")
        if not times or o is None:
            problems.append(f"{robot} {call}: no timing")
            continue
        p, variant = min(times)
        note = " (WORLD)" if variant.endswith("_world") else ""
        size = code_kb(robot, function)
        lines.append(f"| {robot} ({nv} dof) | {call}{note} | {function.replace('+', ' + ')} "
                     f"| {o:.1f} | {p:.1f} | {p / o:.1f}× | {size:.1f} |")
if problems:
    print("public.sh: " + "; ".join(problems), file=sys.stderr)
    sys.exit(1)
text = [f"Machine: {cpu}, {cores} cores. 1-minute load average when each side started "
        "(Pinocchio/generated): "
        + ", ".join(f"{r} {loads.get((r, 'pinocchio'), '?')}/{loads.get((r, 'generated'), '?')}"
                    for r, _, _ in robots) + ".",
        f"{header}; {gxx}. Generated code: {rustc}, baseline x86-64, criterion median of flat samples.",
        "QUICK RUN (--quick): short measurements, not for figures." if quick == "1" else "",
        "Built with dynamics-runtime's `avx512` feature (--avx512): the wide copy that ran is "
        "the AVX-512F/VL build where the CPU has it; code kB is still the AVX2 + FMA copy's."
        if os.environ.get("PUBLIC_AVX512") else "",
        f"Every declaration says `rotation_tolerance: {tolerance};` (--rotation-tolerance); "
        f"checked against Pinocchio within 1e-10 + 100 × {tolerance}." if tolerance else "",
        "",
        "Build of each robot's crate (dependencies prebuilt; the macro's expansion and rustc on the "
        "generated code, release profile, with the benchmark instantiating every function in f64): "
        + ", ".join(f"{r} {build[r][0]:.0f} s, peak {build[r][1]:.0f} MB" for r, _, _ in robots
                    if r in build) + ".",
        "",
        "| robot | Pinocchio | ours | ours ns | Pinocchio ns | speedup | code kB |",
        "| --- | --- | --- | ---: | ---: | ---: | ---: |"] + lines + [
        "",
        "Same outputs on both sides, checked at every state before timing (1e-10 relative): forward_kinematics",
        "gives every body's pose, velocity and classical acceleration (world axes), Pinocchio's the same in",
        "its LOCAL convention (spatial acceleration).",
        "computeJointJacobians and joint_jacobians_world give one 6 × nv matrix (WORLD); the row with",
        "getJointJacobian gives every joint's own Jacobian (LOCAL_WORLD_ALIGNED), as joint_jacobians does.",
        "code kB: machine code of the generated function's AVX2 + FMA copy (the one that runs here),",
        "from the benchmark binary's symbols; L1 instruction cache: 32 kB per core on most x86-64."]
text = "\n".join(line for line in text if line is not None)
print(text)
open(os.path.join(out_dir, "comparison.md"), "w").write(text + "\n")
PYTHON
if [ "$ISA" = 1 ]; then
  echo
  echo "The two copies of the generated code, paired in one process (wide / baseline < 1: the"
  echo "AVX2 + FMA copy is faster):"
  cat "$OUT/isa.md"
fi
if [ "$LANES" = 1 ]; then
  echo
  echo "Many states per call, ns per state over 64 states (gain: the f64 calls' time over the"
  echo "variant's, median of 21 rounds in one process):"
  cat "$OUT/lanes.md"
fi
