#!/usr/bin/env bash
# Two commits' generated code for one robot, timed against each other in one process.
#
#   bash models/tools/generated_ab.sh <commit-a> <commit-b> [quadruped|panda|ur5]
#
# Builds the command-line compiler of each commit (from `git archive`, in a temporary
# directory), writes the robot's generated code with each, and runs
# generated_ab/main.rs over both: paired rounds (models/examples/support/paired.rs), so a
# drift of the machine's speed does not bias the ratio. Both versions are compiled against this checkout's
# dynamics-runtime, so the commits must generate code for the same runtime API. Run it on
# an idle machine and quote the B/A column; run it twice to see the spread.
set -euo pipefail

if [ $# -lt 2 ]; then
    echo "usage: $0 <commit-a> <commit-b> [quadruped|panda|ur5]" >&2
    exit 2
fi
a=$1
b=$2
model=${3:-quadruped}
case $model in
    quadruped) file=models/src/quadruped.rs struct=Quadruped
        call='paired::states::<19, 18>(Some(3)), loads' ;;
    panda) file=models/src/anchors.rs struct=Panda call='paired::states::<7, 7>(None), none' ;;
    ur5) file=models/src/anchors.rs struct=Ur5 call='paired::states::<6, 6>(None), none' ;;
    *) echo "$0: unknown model '$model' (quadruped, panda or ur5)" >&2; exit 2 ;;
esac

root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target=${CARGO_TARGET_DIR:-$root/target}/generated_ab

mkdir -p "$work/ab/src"
for side in a b; do
    rev=${!side}
    echo "==> $side = $(git -C "$root" rev-parse --short "$rev"): building its compiler" >&2
    mkdir -p "$work/$side"
    git -C "$root" archive "$rev" | tar -x -C "$work/$side"
    CARGO_TARGET_DIR="$target/$side" cargo build --quiet --release \
        --manifest-path "$work/$side/Cargo.toml" -p dynamics-codegen
    "$target/$side/release/dynamics-codegen" "$work/$side/$file" --only "$struct" \
        > "$work/ab/src/$side.rs"
done

cp "$root/models/tools/generated_ab/main.rs" "$work/ab/src/main.rs"
cp "$root/models/examples/support/paired.rs" "$work/ab/src/paired.rs"
cat > "$work/ab/src/run.rs" <<RUST
use crate::{close, line, paired};
pub fn run() {
    compare!(crate::a::$struct, crate::b::$struct, $call);
}
RUST
cat > "$work/ab/Cargo.toml" <<TOML
[package]
name = "generated-ab"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
dynamics-runtime = { path = "$root/dynamics-runtime" }

[workspace]
TOML
echo "==> timing $model: A = $a, B = $b" >&2
CARGO_TARGET_DIR="$target/harness" cargo run --quiet --release \
    --manifest-path "$work/ab/Cargo.toml"
