#!/usr/bin/env bash
# Two commits' generated code for one robot, timed against each other in one process.
#
#   bash models/tools/generated_ab.sh <commit-a> <commit-b> [quadruped|panda|ur5|<public robot>]
#
# Builds the command-line compiler of each commit (from `git archive`, in a temporary
# directory), writes the robot's generated code with each, and runs
# generated_ab/main.rs over both: paired rounds (models/examples/support/paired.rs), so a
# drift of the machine's speed does not bias the ratio. Both versions are compiled against this checkout's
# dynamics-runtime, so the commits must generate code for the same runtime API. Run it on
# an idle machine and quote the B/A column; run it twice to see the spread.
#
# A public robot is one that `models/benches/pinocchio/public.sh --robots "<name>"` has
# written (its URDF and its row in build/public/robots.tsv; nothing of it is committed):
# declared as public.sh declares it, with the six timed outputs (the mass and Coriolis
# matrices with their `_into` twins, timed too), M⁻¹ and ∂τ, and printed `--whole`, as the
# macro expands it in an optimized build (both commits' compilers must know `--whole`).
# For example, g1's code against itself, to see the harness's spread: A/A ratios within
# 0.5 % (2026-11-29).
set -euo pipefail

if [ $# -lt 2 ]; then
    echo "usage: $0 <commit-a> <commit-b> [quadruped|panda|ur5|<public robot>]" >&2
    exit 2
fi
a=$1
b=$2
model=${3:-quadruped}
root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
public_robots="$root/models/benches/pinocchio/build/public/robots.tsv"
public=""
case $model in
    quadruped) file=models/src/quadruped.rs struct=Quadruped
        call='paired::states::<19, 18>(Some(3)), loads' ;;
    panda) file=models/src/anchors.rs struct=Panda call='paired::states::<7, 7>(None), none' ;;
    ur5) file=models/src/anchors.rs struct=Ur5 call='paired::states::<6, 6>(None), none' ;;
    *)
        row=$(awk -F'\t' -v robot="$model" '$1 == robot' "$public_robots" 2>/dev/null || true)
        if [ -z "$row" ]; then
            echo "$0: unknown model '$model' (quadruped, panda, ur5, or a robot that" \
                "models/benches/pinocchio/public.sh has written to $public_robots)" >&2
            exit 2
        fi
        IFS=$'\t' read -r _ nq nv base urdf <<< "$row"
        if [ "$base" = free ]; then floating=true quaternion='Some(3)'; else floating=false quaternion=None; fi
        struct=Robot
        call="paired::states::<$nq, $nv>($quaternion), none, public"
        public="mechanism! {
    pub struct Robot;
    urdf: \"$urdf\";
    floating_base: $floating;
    outputs: [inverse_dynamics, mass_matrix_into, forward_dynamics, gravity, bias, coriolis_matrix_into,
              mass_matrix_inverse, inverse_dynamics_derivatives];
}" ;;
esac

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target=${CARGO_TARGET_DIR:-$root/target}/generated_ab

mkdir -p "$work/ab/src"
if [ -n "$public" ]; then
    printf '%s\n' "$public" > "$work/public.rs"
fi
for side in a b; do
    rev=${!side}
    echo "==> $side = $(git -C "$root" rev-parse --short "$rev"): building its compiler" >&2
    mkdir -p "$work/$side"
    # Extracted with fresh modification times (-m): `git archive` stamps files with the
    # commit's time, which cargo would take as older than a later build of another commit
    # in the same target directory, and reuse that compiler.
    git -C "$root" archive "$rev" | tar -x -m -C "$work/$side"
    CARGO_TARGET_DIR="$target/$side" cargo build --quiet --release \
        --manifest-path "$work/$side/Cargo.toml" -p dynamics-codegen
    if [ -n "$public" ]; then
        "$target/$side/release/dynamics-codegen" "$work/public.rs" --whole > "$work/ab/src/$side.rs"
    else
        "$target/$side/release/dynamics-codegen" "$work/$side/$file" --only "$struct" \
            > "$work/ab/src/$side.rs"
    fi
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
