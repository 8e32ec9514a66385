#!/usr/bin/env bash
# Does a change of the compiler change the code it generates?
#
#   bash models/tools/codegen_diff.sh <commit-a> [<commit-b>]   # b defaults to the working tree
#
# Builds the command-line compiler (`dynamics-codegen`, release) of each side, runs it on
# every file of models/src, on the URDF files of models/urdf, and on four chains of 20 and
# 30 links (planar as models::chains, spatial with full inertias and alternating axes),
# each declared with every output, and compares the outputs file by file: "identical"
# (byte for byte) or, where they differ, each function's operation count on both sides
# (`--ops`), marked `HIGHER` where side b needs more operations than side a. Exits 1 if any
# count is higher, 0 otherwise.
#
# Side a is extracted with `git archive` into a folder under /tmp; side b is the working
# tree as it is (uncommitted edits included) unless a commit is given. The inputs are the
# working tree's models/src and models/urdf for both sides, so both compile the same
# declarations.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
if [ $# -lt 1 ] || [ "$1" = "-h" ] || [ "$1" = "--help" ]; then
    sed -n '2,/^set /{/^set /d;p}' "${BASH_SOURCE[0]}"
    exit 2
fi
A=$1
B=${2:-}
WORK=$(mktemp -d /tmp/codegen-diff.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

# The compiler of one side: $1 = commit (empty: the working tree), $2 = folder name.
build_side() {
    local commit=$1 name=$2 src
    if [ -z "$commit" ]; then
        src=$ROOT
    else
        src=$WORK/$name-src
        mkdir -p "$src"
        git -C "$ROOT" archive "$commit" | tar -x -C "$src"
    fi
    CARGO_TARGET_DIR=$WORK/$name-target cargo build --quiet --release \
        --manifest-path "$src/Cargo.toml" -p dynamics-codegen --bin dynamics-codegen >&2
    echo "$WORK/$name-target/release/dynamics-codegen"
}

# A chain of $1 links, planar ($2 = planar) or spatial, with every output.
chain() {
    local n=$1 kind=$2 k axes=(z y x)
    echo "mechanism! {"
    echo "    pub struct Chain${n}${kind^};"
    echo "    gravity: [0.0, -9.81, 0.0];"
    echo "    outputs: [inverse_dynamics, gravity, bias, mass_matrix, coriolis, forward_dynamics, energy, reactions];"
    for k in $(seq 1 "$n"); do
        if [ "$kind" = planar ]; then
            echo "    body link$k { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }"
        else
            echo "    body link$k { mass: 1.5, com: [0.2, 0.01, 0.02], inertia: [[0.02, 0.001, 0.002], [0.001, 0.03, 0.003], [0.002, 0.003, 0.025]] }"
        fi
    done
    for k in $(seq 1 "$n"); do
        local parent=ground at="[0.0, 0.0, 0.0]" axis=z
        if [ "$k" -gt 1 ]; then parent=link$((k - 1)); fi
        if [ "$kind" = planar ]; then
            [ "$k" -gt 1 ] && at="[0.3, 0.0, 0.0]"
        else
            axis=${axes[$(((k - 1) % 3))]}
            [ "$k" -gt 1 ] && at="[0.4, 0.0, 0.05]"
        fi
        echo "    joint joint$k: revolute($parent -> link$k) { axis: $axis, at: $at }"
    done
    echo "}"
}

mkdir -p "$WORK/inputs"
for n in 20 30; do
    for kind in planar spatial; do
        chain "$n" "$kind" > "$WORK/inputs/chain_${n}_${kind}.rs"
    done
done
echo "== building side a ($A)" >&2
CLI_A=$(build_side "$A" a)
echo "== building side b (${B:-working tree})" >&2
CLI_B=$(build_side "$B" b)

status=0
identical=0
total=0
for input in "$ROOT"/models/src/*.rs "$ROOT"/models/urdf/*.urdf "$WORK"/inputs/*.rs; do
    name=${input#"$ROOT"/}
    name=${name#"$WORK"/}
    if ! "$CLI_A" "$input" > "$WORK/out-a" 2> "$WORK/err-a"; then
        if grep -q "no matching mechanism" "$WORK/err-a"; then continue; fi
        if ! "$CLI_B" "$input" > /dev/null 2> "$WORK/err-b" \
            && [ "$(head -1 "$WORK/err-a")" = "$(head -1 "$WORK/err-b")" ]; then
            echo "$name: both reject it with the same error"
        else
            echo "$name: side a fails, side b does not fail the same way: $(head -1 "$WORK/err-a")"
            status=1
        fi
        continue
    fi
    "$CLI_B" "$input" > "$WORK/out-b" 2> "$WORK/err-b" || {
        echo "$name: side b fails: $(head -1 "$WORK/err-b")"
        status=1
        continue
    }
    total=$((total + 1))
    if cmp -s "$WORK/out-a" "$WORK/out-b"; then
        identical=$((identical + 1))
        echo "$name: identical"
        continue
    fi
    echo "$name: differs; operations a -> b:"
    "$CLI_A" "$input" --ops > "$WORK/ops-a"
    "$CLI_B" "$input" --ops > "$WORK/ops-b"
    # Lines "  name   N mul, N add, ...; longest chain": compare the sum of the counts.
    paste -d '|' "$WORK/ops-a" "$WORK/ops-b" | while IFS='|' read -r la lb; do
        case "$la" in
            "  "*)
                fa=$(echo "$la" | awk '{print $1}')
                sa=$(echo "$la" | sed 's/;.*//' | grep -oE '[0-9]+' | paste -sd+ | bc)
                sb=$(echo "$lb" | sed 's/;.*//' | grep -oE '[0-9]+' | paste -sd+ | bc)
                mark=""
                if [ "$sb" -gt "$sa" ]; then mark="  HIGHER"; fi
                echo "    $fa $sa -> $sb$mark"
                ;;
        esac
    done | tee "$WORK/cmp"
    if grep -q HIGHER "$WORK/cmp"; then status=1; fi
done
echo "$identical of $total outputs identical byte for byte"
exit $status
