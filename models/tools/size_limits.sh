#!/usr/bin/env bash
# What the largest mechanisms cost to expand: time and peak memory against size.
#
#   bash models/tools/size_limits.sh
#
# Spatial revolute chains (full inertias, offset mass centres, axes z, y, x in turn; the
# chains of codegen_diff.sh) expanded by the compiler library, optimised, as
# models/tools/expansion_time.rs does it (parse, compile, emit, print: what the macro does
# inside `cargo build` with the README's `build-override`), with GNU time's peak memory:
#
# 1. inverse dynamics alone, 250 to 2000 joints;
# 2. the default outputs (the eight of the dynamics: inverse dynamics, gravity, bias, M, C,
#    forward dynamics, energies, joint reactions), 50 to 200 joints;
# 3. every output the language has (but frames and constraints, which need declarations)
#    on a 200-joint chain: the command-line compiler stops with the error that names the
#    functions past the node budget (dynamics_codegen's NODE_BUDGET); its time and memory.
#
# Builds in $CARGO_TARGET_DIR/size_limits (default target/size_limits); a few minutes.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
WORK=$(mktemp -d /tmp/size-limits.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
TARGET=${CARGO_TARGET_DIR:-$ROOT/target}/size_limits

mkdir -p "$WORK/tool"
cat > "$WORK/tool/Cargo.toml" <<TOML
[package]
name = "expansion-time"
version = "0.0.0"
edition = "2021"
publish = false

[[bin]]
name = "expansion-time"
path = "$ROOT/models/tools/expansion_time.rs"

[dependencies]
dynamics-codegen = { path = "$ROOT/dynamics-codegen" }
proc-macro2 = "1"
syn = { version = "2", features = ["full"] }

[workspace]
TOML
echo "== building the expansion timer and the command-line compiler (release)" >&2
CARGO_TARGET_DIR=$TARGET cargo build --quiet --release --manifest-path "$WORK/tool/Cargo.toml"
CARGO_TARGET_DIR=$TARGET cargo build --quiet --release --manifest-path "$ROOT/Cargo.toml" \
    -p dynamics-codegen --bin dynamics-codegen
TIMER=$TARGET/release/expansion-time
CLI=$TARGET/release/dynamics-codegen

# A spatial chain of $1 links with the outputs $2 (a `mechanism!` invocation).
chain() {
    local n=$1 outputs=$2 k axes=(z y x)
    echo "mechanism! {"
    echo "    pub struct Chain;"
    echo "    gravity: [0.0, -9.81, 0.0];"
    echo "    outputs: [$outputs];"
    for k in $(seq 1 "$n"); do
        echo "    body link$k { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }"
    done
    for k in $(seq 1 "$n"); do
        local parent=ground at="[0.0, 0.0, 0.0]"
        if [ "$k" -gt 1 ]; then parent=link$((k - 1)); at="[0.4, 0.0, 0.05]"; fi
        echo "    joint joint$k: revolute($parent -> link$k) { axis: ${axes[$(((k - 1) % 3))]}, at: $at }"
    done
    echo "}"
}

# One row: the timer's medians (ms) and the process's peak memory (MB).
row() {
    local file=$1 line peak
    line=$( { /usr/bin/time -f "%M" "$TIMER" "$file" > "$WORK/out" ; } 2> "$WORK/err" && tail -1 "$WORK/out")
    peak=$(tail -1 "$WORK/err")
    echo "$line $((peak / 1024)) |"
}

DEFAULTS="inverse_dynamics, gravity, bias, mass_matrix, coriolis_matrix, forward_dynamics, kinetic_energy, joint_reactions"
EVERY="$DEFAULTS, forward_dynamics_aba, forward_dynamics_ldlt, center_of_mass, center_of_mass_jacobian, joint_placements, joint_jacobians, joint_jacobians_world, joint_jacobians_world_time_variation, centroidal_momentum_matrix, forward_kinematics, joint_velocities, joint_acceleration_biases, centroidal_bias, inverse_dynamics_derivatives, forward_dynamics_derivatives, mass_matrix_inverse"

echo "| outputs | dof | parse ms | compile ms | emit ms | print ms | total ms | CPU ms | generated KiB | ops | peak MB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for n in 250 500 1000 2000; do
    chain "$n" inverse_dynamics > "$WORK/id$n.rs"
    echo "| inverse dynamics |$(row "$WORK/id$n.rs" | cut -d'|' -f3-)"
done
for n in 50 100 200; do
    chain "$n" "$DEFAULTS" > "$WORK/defaults$n.rs"
    echo "| the defaults |$(row "$WORK/defaults$n.rs" | cut -d'|' -f3-)"
done
chain 200 "$EVERY" > "$WORK/every200.rs"
echo
echo "Every output, 200 joints, command-line compiler (--ops):"
if /usr/bin/time -f "%e s, peak %M kB" "$CLI" "$WORK/every200.rs" --ops > "$WORK/out" 2> "$WORK/err"; then
    echo "compiled (no function past the budget)"
else
    grep -o '`[a-z_]*` is too large' "$WORK/err" | sort -u | sed 's/^/  /'
fi
tail -1 "$WORK/err"
