#!/usr/bin/env bash
# The generated code against Pinocchio, side by side: tables of ns/call and speedups, one
# for the dynamics and one for the kinematics.
#
#   bash models/benches/pinocchio/compare.sh [--quick] [--native] [--models "ur5 panda quadruped"]
#                                            [--setup-only]
#
# Needs Python >= 3.9 (with venv), g++ (C++17) and the Rust toolchain, and the network for
# the first run. Steps:
#   1. installs Pinocchio from PyPI (`pin`, which ships its C++ headers, and `cmeel-eigen`
#      for Eigen's) into ./venv, next to this script;
#   2. builds ./build/timing from timing.cpp once (header-only Pinocchio, -O3 -march=native
#      -DNDEBUG, the compile definitions Pinocchio's CMake package gives its users), and
#      rebuilds it only when the source, the flags, the compiler or Pinocchio change;
#   3. writes the quadruped and its states with `cargo run --example export_model`;
#   4. runs Pinocchio (./build/timing) and the project's criterion benchmark
#      (`cargo bench -p models --bench dynamics`) on the same models and the same states:
#      the 20 samples of tests/data/pinocchio/<model>.json, and of quadruped.json here.
#      Both sides make one call per state, the states in turn, on one thread, and report
#      the median over repetitions; the script checks that both read bit-identical states.
#      It goes model by model, Pinocchio then ours, first the dynamics and then (UR5,
#      Panda and quadruped only) the kinematics, so a change of the machine's load between
#      the two sides of a ratio is unlikely; the load average of each is printed;
#   5. prints the tables (also written to build/comparison.md).
# Dynamics: Pinocchio's crba and aba are timed in both of its conventions and the faster one
# is compared. The quadruped's foot loads are zero for the generated code and Pinocchio gets
# no external forces.
# Kinematics: each Pinocchio call beside the generated function(s) a user would call
# instead (models/src/kinematics.rs): forwardKinematics(q) ~ joint_placements;
# forwardKinematics(q, v, a) ~ forward_kinematics (placements, velocities, accelerations);
# computeJointJacobians ~ joint_jacobians_world (both give data.J, WORLD);
# computeJointJacobiansTimeVariation ~ joint_jacobians_world_time_variation (data.J, data.dJ);
# forwardKinematics(q, v, a) ~ joint_velocities + joint_acceleration_biases (ours gives
# v and J̇v; Pinocchio also gives the accelerations for a); computeJointJacobians ~
# joint_jacobians; computeJointJacobiansTimeVariation ~ joint_jacobians +
# joint_acceleration_biases (J and J̇v; Pinocchio computes J and J̇); centerOfMass ~
# center_of_mass; jacobianCenterOfMass ~ center_of_mass_jacobian; ccrba ~
# centroidal_momentum_matrix; forwardKinematics + updateFramePlacements ~ frame_placements;
# computeJointJacobians + getFrameJacobian per frame ~ frame_jacobians;
# forwardKinematics(q, v, 0) + getFrameClassicalAcceleration per frame ~
# frame_acceleration_biases; dccrba ~ centroidal_bias; computeRNEADerivatives ~
# inverse_dynamics_derivatives; computeABADerivatives ~ forward_dynamics_derivatives;
# computeMinverse ~ mass_matrix_inverse. The frames are those listed in
# frames.json: the arms' URDF links on fixed joints (every BODY frame whose parent is a
# fixed joint), the quadruped's four feet. Timings of a busy machine are noisy: the load average is printed with each
# table. --quick shortens both sides' measurements (for trying the script, not for
# figures). --native builds the generated code for this CPU too (RUSTFLAGS
# "-C target-cpu=native", in target/native), as Pinocchio is always built (-march=native);
# without it ours is built for baseline x86-64. --setup-only stops after step 2 (public.sh
# uses it for the same Pinocchio and timing program).
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../../.." && pwd)"
PIN_VERSION="${PIN_VERSION:-4.1.0}"
EIGEN_VERSION="${EIGEN_VERSION:-3.4.1}"
MODELS="pendulum double_pendulum planar3 ur5 panda quadruped"
QUICK=0
NATIVE=0
SETUP_ONLY=0
BASELINE=compare_pinocchio

while [ $# -gt 0 ]; do
  case "$1" in
    --quick) QUICK=1 ;;
    --native) NATIVE=1 ;;
    --setup-only) SETUP_ONLY=1 ;;
    --models) MODELS="$2"; shift ;;
    -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "compare.sh: unknown argument $1 (try --help)" >&2; exit 2 ;;
  esac
  shift
done

# The model files and the benchmarks' names, in the order of $MODELS; the kinematics
# mechanisms (models/src/kinematics.rs) of the models that have one, "-" for the others.
FILES=()
NAMES=()
KINEMATICS=()
for m in $MODELS; do
  k=-
  case "$m" in
    pendulum) f=tests/data/pinocchio/pendulum.json; n=Pendulum ;;
    double_pendulum) f=tests/data/pinocchio/double_pendulum.json; n=DoublePendulum ;;
    planar3) f=tests/data/pinocchio/planar3.json; n=Planar3 ;;
    ur5) f=tests/data/pinocchio/ur5.json; n=Ur5; k=Ur5Kinematics ;;
    panda) f=tests/data/pinocchio/panda.json; n=Panda; k=PandaKinematics ;;
    quadruped) f="$HERE/quadruped.json"; n=Quadruped; k=QuadrupedKinematics ;;
    *) echo "compare.sh: unknown model $m (pendulum double_pendulum planar3 ur5 panda quadruped)" >&2; exit 2 ;;
  esac
  FILES+=("$f")
  NAMES+=("$n")
  KINEMATICS+=("$k")
done
# The generated kinematics benchmarks (benches/dynamics.rs), as a regex alternation: each
# function alone, and the pairs timed as one call each.
KIN_OUTPUTS='joint_placements|joint_velocities|joint_acceleration_biases|joint_jacobians'
KIN_OUTPUTS+='|joint_jacobians_world|joint_jacobians_world_time_variation|forward_kinematics'
KIN_OUTPUTS+='|joint_velocities\+joint_acceleration_biases|joint_jacobians\+joint_acceleration_biases'
KIN_OUTPUTS+='|center_of_mass|center_of_mass_jacobian|centroidal_momentum_matrix'
KIN_OUTPUTS+='|frame_placements|frame_jacobians|frame_acceleration_biases|centroidal_bias'
KIN_OUTPUTS+='|inverse_dynamics_derivatives|forward_dynamics_derivatives|mass_matrix_inverse'

STEP="starting"
fail() { echo "compare.sh: FAILED while $STEP${1:+: $1}" >&2; exit 1; }
trap 'fail "command exited with status $? (see the output above)"' ERR
step() { STEP="$1"; echo "==> $1" >&2; }

# ---- 0. tools -----------------------------------------------------------------------------
step "checking the tools (python3 with venv, g++, cargo)"
PYTHON=""
for candidate in python3.11 python3.12 python3.13 python3.10 python3.9 python3; do
  if command -v "$candidate" >/dev/null 2>&1 &&
     "$candidate" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 9) else 1)' 2>/dev/null; then
    PYTHON="$candidate"; break
  fi
done
[ -n "$PYTHON" ] || fail "no Python >= 3.9 found (python3.11 is what this was written with)"
command -v g++ >/dev/null 2>&1 || fail "g++ not found (a C++17 compiler is needed)"
command -v cargo >/dev/null 2>&1 || fail "cargo not found (install the Rust toolchain)"

# ---- 1. Pinocchio ---------------------------------------------------------------------------
step "installing Pinocchio $PIN_VERSION (pin) and Eigen $EIGEN_VERSION (cmeel-eigen) into $HERE/venv"
VENV="$HERE/venv"
if [ ! -x "$VENV/bin/python" ]; then
  "$PYTHON" -m venv "$VENV" ||
    fail "$PYTHON -m venv failed (on Debian/Ubuntu: apt-get install python3-venv)"
fi
WANT="pin==$PIN_VERSION cmeel-eigen==$EIGEN_VERSION"
if [ "$(cat "$VENV/.installed" 2>/dev/null || true)" != "$WANT" ]; then
  "$VENV/bin/python" -m pip install -q --upgrade pip || fail "pip could not upgrade itself (network?)"
  # shellcheck disable=SC2086
  "$VENV/bin/python" -m pip install -q $WANT || fail "pip install $WANT failed (network? Python version?)"
  echo "$WANT" > "$VENV/.installed"
fi
PREFIX="$("$VENV/bin/python" -c 'import cmeel, os; print(os.path.join(os.path.dirname(cmeel.__path__[0]), "cmeel.prefix"))')" ||
  fail "cannot locate the cmeel prefix of the venv"
[ -f "$PREFIX/include/pinocchio/config.hpp" ] || fail "no Pinocchio headers under $PREFIX/include"
[ -d "$PREFIX/include/eigen3/Eigen" ] || fail "no Eigen headers under $PREFIX/include/eigen3"

# ---- 2. the timing program ------------------------------------------------------------------
step "building the Pinocchio timing program (build/timing)"
mkdir -p "$HERE/build"
# The definitions are those of the pinocchio::pinocchio_headers target in Pinocchio's CMake
# package (lib/cmake/pinocchio/pinocchioTargets.cmake).
CXXFLAGS=(-std=c++17 -O3 -march=native -DNDEBUG
          -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30
          -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12
          -isystem "$PREFIX/include" -isystem "$PREFIX/include/eigen3")
STAMP="$( { cat "$HERE/timing.cpp"; echo "${CXXFLAGS[*]}"; g++ --version | head -1; echo "$WANT"; } | sha256sum | cut -c1-16)"
if [ ! -x "$HERE/build/timing" ] || [ "$(cat "$HERE/build/timing.stamp" 2>/dev/null || true)" != "$STAMP" ]; then
  echo "    g++ ${CXXFLAGS[*]} timing.cpp   (about 2 minutes)" >&2
  g++ "${CXXFLAGS[@]}" "$HERE/timing.cpp" -o "$HERE/build/timing.tmp" 2> "$HERE/build/timing.log" ||
    { tail -30 "$HERE/build/timing.log" >&2; fail "g++ could not build timing.cpp (log: build/timing.log)"; }
  mv "$HERE/build/timing.tmp" "$HERE/build/timing"
  echo "$STAMP" > "$HERE/build/timing.stamp"
fi

if [ "$SETUP_ONLY" = 1 ]; then exit 0; fi

# ---- 3. the quadruped's file ------------------------------------------------------------------
cd "$ROOT"
if [[ " $MODELS " == *" quadruped "* ]]; then
  step "exporting the quadruped and its states (cargo run --release -p models --example export_model)"
  mkdir -p "$HERE/build"
  cargo run --release -q -p models --example export_model -- quadruped --out "$HERE/build/quadruped.json" >&2
  # Replaced only when it changed: the benchmark embeds it, and a new mtime rebuilds it.
  if ! cmp -s "$HERE/build/quadruped.json" "$HERE/quadruped.json"; then
    cp "$HERE/build/quadruped.json" "$HERE/quadruped.json"
    echo "    quadruped.json changed (the model or the exporter did): commit it" >&2
  fi
fi

if [ "$QUICK" = 1 ]; then
  PIN_ARGS=(--reps 5 --min-rep-ms 20 --warmup-ms 50)
  CRIT_ARGS=(--warm-up-time 0.3 --measurement-time 0.5 --sample-size 10)
else
  PIN_ARGS=(--reps 21 --min-rep-ms 100 --warmup-ms 300)
  CRIT_ARGS=(--warm-up-time 1 --measurement-time 3 --sample-size 21)
fi

# ---- 4. both sides ----------------------------------------------------------------------------
RUST_BUILD="baseline x86-64"
if [ "$NATIVE" = 1 ]; then
  export RUSTFLAGS="-C target-cpu=native"
  export CARGO_TARGET_DIR="$ROOT/target/native"
  RUST_BUILD="-C target-cpu=native"
fi
step "building the Rust benchmark (cargo bench -p models --bench dynamics --no-run)"
cargo bench -q -p models --bench dynamics --no-run 2> "$HERE/build/cargo.log" ||
  { tail -30 "$HERE/build/cargo.log" >&2; fail "the benchmark does not build (log: build/cargo.log)"; }
TARGET="$(cargo metadata --format-version 1 --no-deps |
          "$VENV/bin/python" -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')"
CRITERION="$TARGET/criterion"
if [ -d "$CRITERION" ]; then
  find "$CRITERION" -type d -name "$BASELINE" -prune -exec rm -rf {} +
fi

# Model by model, Pinocchio then the generated code, so that the two sides of each ratio
# are measured within a minute of each other: the dynamics, then the kinematics.
: > "$HERE/build/pinocchio.tsv"
: > "$HERE/build/criterion.log"
: > "$HERE/build/load.tsv"
for i in "${!FILES[@]}"; do
  m="$(echo $MODELS | cut -d' ' -f$((i + 1)))"
  SECTIONS=(dynamics)
  if [ "${KINEMATICS[$i]}" != - ]; then SECTIONS+=(kinematics); fi
  for group in "${SECTIONS[@]}"; do
    if [ "$group" = dynamics ]; then
      REGEX="^${NAMES[$i]}/(inverse_dynamics|mass_matrix|bias|gravity|forward_dynamics|coriolis_matrix)/generated\$"
    else
      REGEX="^${KINEMATICS[$i]}/($KIN_OUTPUTS)/generated\$"
    fi
    LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
    step "timing $m, $group: Pinocchio (load average $LOAD)"
    printf '%s\tpinocchio\t%s\t%s\n' "$m" "$LOAD" "$group" >> "$HERE/build/load.tsv"
    "$HERE/build/timing" "${PIN_ARGS[@]}" --group "$group" --frames "$HERE/frames.json" "${FILES[$i]}" \
      >> "$HERE/build/pinocchio.tsv" ||
      fail "the timing program failed on ${FILES[$i]} (its message is above)"
    LOAD="$(cut -d' ' -f1-3 /proc/loadavg)"
    step "timing $m, $group: generated code (load average $LOAD)"
    printf '%s\tgenerated\t%s\t%s\n' "$m" "$LOAD" "$group" >> "$HERE/build/load.tsv"
    cargo bench -q -p models --bench dynamics -- "${CRIT_ARGS[@]}" --save-baseline "$BASELINE" "$REGEX" \
      >> "$HERE/build/criterion.log" 2>&1 ||
      { tail -30 "$HERE/build/criterion.log" >&2; fail "cargo bench failed (log: build/criterion.log)"; }
  done
done
printf 'end\t-\t%s\tall\n' "$(cut -d' ' -f1-3 /proc/loadavg)" >> "$HERE/build/load.tsv"

# ---- 5. the table -------------------------------------------------------------------------------
step "joining the results"
KIN_LIST="$(IFS=,; echo "${KINEMATICS[*]}")"
CPU="$(LC_ALL=C lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -1)"
PYTHONPATH="$HERE" "$VENV/bin/python" - "$HERE/build" "$CRITERION" "$BASELINE" "$CPU" "$(nproc)" \
  "$QUICK" "$(rustc --version), $RUST_BUILD" "$(g++ --version | head -1)" "$KIN_LIST" \
  $MODELS <<'PYTHON' || fail "could not join the two sides' results"
import os, sys

build, criterion, baseline, cpu, cores, quick, rustc, gxx, kinematics, *models = sys.argv[1:]
import results  # results.py beside this script (PYTHONPATH)
NAMES = {"pendulum": "Pendulum", "double_pendulum": "DoublePendulum", "planar3": "Planar3",
         "ur5": "Ur5", "panda": "Panda", "quadruped": "Quadruped"}
KINEMATICS = {m: k for m, k in zip(models, kinematics.split(",")) if k != "-"}
LABELS = {"pendulum": "pendulum", "double_pendulum": "double pendulum", "planar3": "planar 3R",
          "ur5": "UR5", "panda": "Panda", "quadruped": "quadruped"}
# Pinocchio algorithm, the faster of its conventions where it has two, ours.
ALGORITHMS = [("rnea", ["rnea"], "inverse_dynamics"),
              ("crba", ["crba", "crba_world"], "mass_matrix"),
              ("nonLinearEffects", ["nonLinearEffects"], "bias"),
              ("computeGeneralizedGravity", ["computeGeneralizedGravity"], "gravity"),
              ("aba", ["aba", "aba_world"], "forward_dynamics"),
              ("computeCoriolisMatrix", ["computeCoriolisMatrix"], "coriolis_matrix")]
# The issue's targets (speedup = Pinocchio / ours) for the robots.
TARGETS = {"rnea": {"ur5": 8, "panda": 8, "quadruped": 5}, "crba": 5, "aba": 6,
           "computeGeneralizedGravity": 10, "computeCoriolisMatrix": 5}
ROBOTS = {"ur5", "panda", "quadruped"}
# Kinematics: the Pinocchio call as printed (N: the number of frames), its record in
# timing's output, our generated benchmark (two functions joined by "+": one benchmark
# calling both), whether it must exist on our side, and whether it is a frame row (left out
# for a model without frames on Pinocchio's side).
KIN_ROWS = [("forwardKinematics(q)", "forwardKinematics_q", "joint_placements", True, False),
            ("forwardKinematics(q, v, a)", "forwardKinematics_qva", "forward_kinematics", True, False),
            ("forwardKinematics(q, v, a)", "forwardKinematics_qva",
             "joint_velocities+joint_acceleration_biases", True, False),
            ("computeJointJacobians", "computeJointJacobians", "joint_jacobians_world", True, False),
            ("computeJointJacobians", "computeJointJacobians", "joint_jacobians", True, False),
            ("computeJointJacobians + getJointJacobian × all joints", "computeJointJacobians_getJointJacobian",
             "joint_jacobians", True, False),
            ("computeJointJacobiansTimeVariation", "computeJointJacobiansTimeVariation",
             "joint_jacobians_world_time_variation", True, False),
            ("computeJointJacobiansTimeVariation", "computeJointJacobiansTimeVariation",
             "joint_jacobians+joint_acceleration_biases", True, False),
            ("computeJointJacobiansTimeVariation + getJointJacobian, getJointJacobianTimeVariation × all joints, × v",
             "computeJointJacobiansTimeVariation_perJoint", "joint_jacobians+joint_acceleration_biases",
             True, False),
            ("centerOfMass", "centerOfMass", "center_of_mass", True, False),
            ("jacobianCenterOfMass", "jacobianCenterOfMass", "center_of_mass_jacobian", True, False),
            ("ccrba", "ccrba", "centroidal_momentum_matrix", True, False),
            ("forwardKinematics + updateFramePlacements", "framePlacements", "frame_placements",
             True, True),
            ("computeJointJacobians + getFrameJacobian × N", "frameJacobians", "frame_jacobians",
             True, True),
            ("forwardKinematics(q, v, 0) + getFrameClassicalAcceleration × N",
             "frameClassicalAccelerations", "frame_acceleration_biases", True, True),
            ("dccrba", "dccrba", "centroidal_bias", True, False),
            ("computeRNEADerivatives", "computeRNEADerivatives", "inverse_dynamics_derivatives",
             True, False),
            ("computeABADerivatives", "computeABADerivatives", "forward_dynamics_derivatives",
             True, False),
            ("computeMinverse", "computeMinverse", "mass_matrix_inverse", True, False)]

pin, pin_states, frames, header = results.pinocchio(os.path.join(build, "pinocchio.tsv"))
ours_states = results.states(os.path.join(build, "criterion.log"), "compare.sh")

loads = {}
for line in open(os.path.join(build, "load.tsv")):
    model, side, load, group = line.rstrip("\n").split("\t")
    loads[(model, side, group)] = load.split()[0]

ours = results.criterion_medians(criterion, baseline)

problems = []
for m in models:
    for name in [NAMES[m]] + ([KINEMATICS[m]] if m in KINEMATICS else []):
        a, b = pin_states.get(m), ours_states.get(name)
        if a is None or b is None or a != b:
            problems.append(f"{m}: the states differ (Pinocchio {a}, Rust {name} {b})")
rows, verdicts = [], []
for m in models:
    for algorithm, variants, function in ALGORITHMS:
        times = [(pin[(m, v)], v) for v in variants if (m, v) in pin]
        key = f"{NAMES[m]}/{function}/generated"
        if not times or key not in ours:
            problems.append(f"{m} {algorithm}: no timing ({'Pinocchio' if not times else key})")
            continue
        p, variant = min(times)
        o = ours[key]
        speedup = p / o
        target = TARGETS.get(algorithm)
        if isinstance(target, dict):
            target = target.get(m)
        if m not in ROBOTS:
            target = None
        verdict = "" if target is None else ("met" if speedup >= target else "NOT met")
        if target is not None:
            verdicts.append((m, algorithm, speedup, target))
        note = " (WORLD)" if variant.endswith("_world") else ""
        rows.append((LABELS[m], f"{algorithm}{note}", function, o, p, speedup,
                     "" if target is None else f"≥ {target}×", verdict))
kin_rows = []
for m in models:
    if m not in KINEMATICS:
        continue
    for call, record, function, required, per_frame in KIN_ROWS:
        if per_frame and not frames.get(m):
            continue
        p = pin.get((m, record))
        o = ours.get(f"{KINEMATICS[m]}/{function}/generated")
        if p is None or (required and o is None):
            problems.append(f"{m} {call}: no timing "
                            f"({'Pinocchio' if p is None else KINEMATICS[m] + '/' + function})")
            continue
        kin_rows.append((LABELS[m], call.replace("× N", f"× {frames.get(m, 0)}"),
                         function.replace("+", " + "), o, p))
if problems:
    print("compare.sh: " + "; ".join(problems), file=sys.stderr)
    sys.exit(1)

def load_list(group, which):
    return ", ".join(f"{LABELS[m]} {loads.get((m, 'pinocchio', group), '?')}/"
                     f"{loads.get((m, 'generated', group), '?')}" for m in which)

out = []
out.append(f"Machine: {cpu}, {cores} cores. 1-minute load average when each side started "
           f"(Pinocchio/generated): {load_list('dynamics', models)}; at the end "
           f"{loads.get(('end', '-', 'all'), '?')}.")
out.append(f"{header}; {gxx}. Generated code: {rustc}, criterion median of flat samples.")
if quick == "1":
    out.append("QUICK RUN (--quick): short measurements, not for figures.")
out.append("")
out.append("### Dynamics")
out.append("")
out.append("| model | Pinocchio | ours | ours ns | Pinocchio ns | speedup | target | |")
out.append("| --- | --- | --- | ---: | ---: | ---: | ---: | --- |")
for label, algorithm, function, o, p, s, target, verdict in rows:
    out.append(f"| {label} | {algorithm} | {function} | {o:.1f} | {p:.1f} | {s:.1f}× | {target} | {verdict} |")
out.append("")
out.append("speedup = Pinocchio ns / ours ns (medians, same states, one thread). crba and aba: the faster of")
out.append("Pinocchio's LOCAL and WORLD conventions. Quadruped: foot loads zero, no external forces in Pinocchio.")
if kin_rows:
    which = [m for m in models if m in KINEMATICS]
    out.append("")
    out.append("### Kinematics and derivatives")
    out.append("")
    out.append("1-minute load average when each side of the kinematics started (Pinocchio/generated): "
               f"{load_list('kinematics', which)}.")
    out.append("")
    out.append("| model | Pinocchio | ours | ours ns | Pinocchio ns | speedup |")
    out.append("| --- | --- | --- | ---: | ---: | ---: |")
    for label, call, function, o, p in kin_rows:
        ours_ns, speedup = ("—", "—") if o is None else (f"{o:.1f}", f"{p / o:.1f}×")
        out.append(f"| {label} | {call} | {function} | {ours_ns} | {p:.1f} | {speedup} |")
    out.append("")
    out.append("Ours: the mechanisms of models/src/kinematics.rs; \"a + b\": one benchmark calling both. Same")
    out.append("outputs: forward_kinematics (poses, velocities, accelerations at a), joint_jacobians_world")
    out.append("(data.J) and joint_jacobians_world_time_variation (data.J, data.dJ). Not the same outputs: the pair")
    out.append("joint_velocities + joint_acceleration_biases gives v and J̇v (the acceleration at q̈ = 0); the rows")
    out.append("with joint_jacobians give every joint's Jacobian (LOCAL_WORLD_ALIGNED) where computeJointJacobians")
    out.append("gives one 6 × nv matrix, the same outputs only with getJointJacobian for each joint; ccrba also")
    out.append("gives h_g = A_g v, ours A_G alone. Frames: every BODY frame whose parent is a fixed joint in the")
    out.append("URDF, and the quadruped's feet (frames.json). computeRNEADerivatives also gives ∂τ/∂a = M,")
    out.append("computeABADerivatives M⁻¹ (ours: mass_matrix_inverse); computeMinverse")
    out.append("fills the upper triangle, ours the whole matrix.")
text = "\n".join(out)
print(text)
open(os.path.join(build, "comparison.md"), "w").write(text + "\n")
met = sum(1 for _, _, s, t in verdicts if s >= t)
print(f"\ntargets met: {met} of {len(verdicts)}")
PYTHON
