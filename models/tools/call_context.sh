#!/usr/bin/env bash
# The same generated code timed in two call contexts: called back to back (as every
# benchmark of this project does), and right after a 3000-byte `rep stosb` to a scratch
# buffer (a long string instruction, as memset and memcpy of a few kB run on current x86
# cores).
#
#   bash models/tools/call_context.sh
#
# Builds this checkout's command-line compiler, writes the Panda's generated code (the
# dynamics, the Coriolis matrix, both derivatives and M⁻¹) into a throwaway crate and runs
# call_context/main.rs in it. On the machine of BENCHMARKS.md the derivatives, the two
# functions whose code exceeds the 32 kB L1 instruction cache, ran 18 % faster after the
# string instruction, although it costs 22 ns itself; the small functions only paid its
# cost. See BENCHMARKS.md, "Where the generated code spends its time".
set -euo pipefail

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target=${CARGO_TARGET_DIR:-$root/target}

echo "==> building the command-line compiler" >&2
cargo build --quiet --release --manifest-path "$root/Cargo.toml" -p dynamics-codegen
mkdir -p "$work/crate/src"
cat > "$work/panda.rs" <<RUST
mechanism! {
    pub struct Panda;
    urdf: "$root/models/urdf/panda.urdf";
    outputs: [inverse_dynamics, mass_matrix, coriolis_matrix, forward_dynamics,
              mass_matrix_inverse, inverse_dynamics_derivatives, forward_dynamics_derivatives];
}
RUST
"$target/release/dynamics-codegen" "$work/panda.rs" > "$work/crate/src/generated.rs"
cp "$root/models/tools/call_context/main.rs" "$work/crate/src/main.rs"
cp "$root/models/examples/support/paired.rs" "$work/crate/src/paired.rs"
cat > "$work/crate/Cargo.toml" <<TOML
[package]
name = "call-context"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
dynamics-runtime = { path = "$root/dynamics-runtime" }

[workspace]
TOML
echo "==> timing" >&2
CARGO_TARGET_DIR="$target/call_context" cargo run --quiet --release \
    --manifest-path "$work/crate/Cargo.toml"
