#!/usr/bin/env bash
# What a mechanism costs to compile, against its number of joints.
#
#   bash models/tools/compile_cost.sh                       # chains 5 10 20 30 and the quadruped
#   bash models/tools/compile_cost.sh --chains "5 10"       # other chains
#   bash models/tools/compile_cost.sh --repeat 1            # one build each (default 3)
#   bash models/tools/compile_cost.sh --keep                # keep the temporary folder
#   bash models/tools/compile_cost.sh --isa baseline        # declared with `isa: baseline;`
#                                                           # (one copy of each function)
#
# In a fresh folder under /tmp it extracts the committed toolkit (`git archive HEAD`: the
# workspace manifest and lock file, dynamics-runtime, dynamics-macros, dynamics-codegen; so
# edits in progress in the working tree neither change the figures nor rebuild anything)
# and adds to that workspace one throwaway crate per mechanism, with a path dependency on
# dynamics-runtime: the planar chains of models::chains (same links and joints) declared
# with every output, and the committed models/src/quadruped.rs. Each crate is a binary
# whose `main.rs` is the declaration; with the feature `call` it also calls every generated
# function at f64, so that LLVM compiles them (generic functions that nobody calls cost
# only expansion and type checking).
#
# 1. Expansion: models/tools/expansion_time.rs times dynamics_codegen's parse, compile, emit
#    and print on each declaration (median of 5), built twice: optimized, and with the
#    settings Cargo gives proc macros in `cargo build --release` (its `build-override`:
#    opt-level 0, 256 codegen units), which is the speed of the macro inside the build.
# 2. Build: the dependencies are built first (a stub member with the same dependencies),
#    then `cargo build --release -p <crate>` is timed, without and with `--features call`,
#    each build from scratch (`main.rs` touched) and repeated; each compiles that one crate
#    only (the script checks), so the figure is the mechanism's own cost. The least wall
#    and the least CPU (user + sys, rustc included) seconds of the repeats, and the 1-minute
#    load average before the first: on a shared machine CPU time is the figure that other
#    jobs inflate least.
#
# The release profile is the workspace's (opt-level 3, 16 codegen units, thin LTO).
# Needs git, GNU time (/usr/bin/time) and the Rust toolchain; takes 5 to 15 minutes.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
CHAINS="5 10 20 30"
KEEP=0
REPEAT=3
ISA=""
while [ $# -gt 0 ]; do
    case "$1" in
        --chains) CHAINS="$2"; shift 2 ;;
        --repeat) REPEAT="$2"; shift 2 ;;
        --keep) KEEP=1; shift ;;
        --isa)
            case "$2" in
                dispatch|baseline) ISA="$2"; shift 2 ;;
                *) echo "--isa takes dispatch or baseline, not: $2" >&2; exit 2 ;;
            esac ;;
        -h|--help) sed -n '2,/^set /{/^set /d;p}' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "unknown argument: $1" >&2; exit 2 ;;
    esac
done

WORK=$(mktemp -d /tmp/compile-cost.XXXXXX)
if [ "$KEEP" = 0 ]; then trap 'rm -rf "$WORK"' EXIT; fi
export CARGO_TARGET_DIR="$WORK/target"
COMMIT=$(git -C "$ROOT" rev-parse --short HEAD)
echo "working in $WORK, toolkit at commit $COMMIT${ISA:+, every mechanism declared with isa: $ISA;}"
git -C "$ROOT" archive HEAD Cargo.toml Cargo.lock dynamics-runtime dynamics-macros dynamics-codegen \
    | tar -x -C "$WORK"

# The planar chain of models::chains with $1 links and every output.
chain_declaration() {
    local n=$1 k
    echo "use dynamics_runtime::mechanism;"
    echo
    echo "mechanism! {"
    echo "    /// A planar chain of $n links (as models::chains), every output."
    echo "    pub struct Chain$n;"
    if [ -n "$ISA" ]; then echo "    isa: $ISA;"; fi
    echo "    gravity: [0.0, -9.81, 0.0];"
    for k in $(seq 1 "$n"); do
        echo "    body link$k { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }"
    done
    echo "    joint link1: revolute(ground -> link1) { axis: z }"
    for k in $(seq 2 "$n"); do
        echo "    joint link$k: revolute(link$((k - 1)) -> link$k) { axis: z, at: [0.3, 0.0, 0.0] }"
    done
    echo "}"
}

# main.rs of a throwaway crate: the declaration, then (feature `call`) one call of every
# generated function at f64 on opaque inputs. $1 crate, $2 type, $3 loads argument or "".
crate_main() {
    local krate=$1 name=$2 loads=$3
    cat "$WORK/declarations/$krate.rs"
    cat <<EOF

#[cfg(feature = "call")]
fn call() {
    use dynamics_runtime::Mechanism;
    use std::hint::black_box;
    const NQ: usize = <$name as Mechanism>::NQ;
    const NV: usize = <$name as Mechanism>::NV;
    const NL: usize = <$name as Mechanism>::NUM_LOAD_INPUTS;
    let q: [f64; NQ] = black_box([0.1; NQ]);
    let v: [f64; NV] = black_box([0.2; NV]);
    let a: [f64; NV] = black_box([0.3; NV]);
    let l: [f64; NL] = black_box([0.0; NL]);
    let _ = &l;
    black_box($name::inverse_dynamics(&q, &v, &a$loads));
    black_box($name::gravity(&q));
    black_box($name::bias(&q, &v));
    black_box($name::mass_matrix(&q));
    black_box($name::coriolis_matrix(&q, &v));
    black_box($name::forward_dynamics(&q, &v, &a$loads));
    black_box($name::kinetic_energy(&q, &v));
    black_box($name::potential_energy(&q));
    black_box($name::joint_reactions(&q, &v, &a$loads));
}

fn main() {
    #[cfg(feature = "call")]
    call();
}
EOF
}

crate_manifest() {
    cat <<EOF
[package]
name = "$1"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
dynamics-runtime = { path = "../dynamics-runtime" }

[features]
call = []
EOF
}

mkdir -p "$WORK/declarations"
CRATES=()
for n in $CHAINS; do
    chain_declaration "$n" > "$WORK/declarations/chain$n.rs"
    CRATES+=("chain$n:Chain$n:")
done
git -C "$ROOT" show HEAD:models/src/quadruped.rs > "$WORK/declarations/quadruped.rs"
if [ -n "$ISA" ]; then
    sed -i "s/^\( *\)pub struct Quadruped;/&\n\1isa: $ISA;/" "$WORK/declarations/quadruped.rs"
    grep -q "isa: $ISA;" "$WORK/declarations/quadruped.rs" ||
        { echo "could not add isa: $ISA; to the quadruped" >&2; exit 1; }
fi
CRATES+=("quadruped:Quadruped:, &l")

MEMBERS='"stub", "expansion-time"'
for entry in "${CRATES[@]}"; do
    IFS=: read -r krate name loads <<< "$entry"
    mkdir -p "$WORK/$krate/src"
    crate_manifest "$krate" > "$WORK/$krate/Cargo.toml"
    crate_main "$krate" "$name" "$loads" > "$WORK/$krate/src/main.rs"
    MEMBERS+=", \"$krate\""
done
mkdir -p "$WORK/stub/src"
crate_manifest stub > "$WORK/stub/Cargo.toml"
echo "fn main() {}" > "$WORK/stub/src/main.rs"
mkdir -p "$WORK/expansion-time"
cp "$ROOT/models/tools/expansion_time.rs" "$WORK/expansion-time/"
cat > "$WORK/expansion-time/Cargo.toml" <<EOF
[package]
name = "expansion-time"
version = "0.0.0"
edition = "2021"
publish = false

[[bin]]
name = "expansion-time"
path = "expansion_time.rs"

[dependencies]
dynamics-codegen = { path = "../dynamics-codegen" }
proc-macro2 = "1"
syn = { version = "2", features = ["full"] }
EOF
# The committed workspace manifest (its release profile included), with these members.
sed -i "/^members = \[/,/^\]/c\\members = [\"dynamics-runtime\", \"dynamics-macros\", \"dynamics-codegen\", $MEMBERS]" \
    "$WORK/Cargo.toml"
cat >> "$WORK/Cargo.toml" <<EOF

# What Cargo builds proc macros with in a release build (its default build-override).
[profile.macro]
inherits = "release"
opt-level = 0
codegen-units = 256
lto = false
EOF
cd "$WORK"

echo
echo "## Expansion (dynamics_codegen called directly; wall: medians, CPU: means)"
cargo build -q --release -p expansion-time
cargo build -q --profile macro -p expansion-time
DECLS=()
for entry in "${CRATES[@]}"; do DECLS+=("$WORK/declarations/${entry%%:*}.rs"); done
echo
echo "### optimized (opt-level 3)"
echo
CLK_TCK=$(getconf CLK_TCK) "$CARGO_TARGET_DIR/release/expansion-time" "${DECLS[@]}"
echo
echo "### as inside cargo build --release (proc macro at opt-level 0)"
echo
CLK_TCK=$(getconf CLK_TCK) "$CARGO_TARGET_DIR/macro/expansion-time" "${DECLS[@]}"

echo
echo "## Build (cargo build --release of the one crate, dependencies already built; least of $REPEAT)"
cargo build -q --release -p stub
cargo build -q --release -p stub --features call

# Times `cargo build --release -p $1 ${@:2}` REPEAT times, the crate rebuilt from scratch
# each time (its main.rs touched; release builds are not incremental). Sets WALL and CPU,
# the least wall and the least CPU seconds, and LOAD, the 1-minute load average before.
timed_build() {
    local krate=$1 log r best_wall="" best_cpu=""
    shift
    LOAD=$(cut -d' ' -f1 /proc/loadavg)
    log="$WORK/build.log"
    for r in $(seq "$REPEAT"); do
        touch "$WORK/$krate/src/main.rs"
        /usr/bin/time -f "%e %U %S" -o "$WORK/time.txt" cargo build --release -p "$krate" "$@" \
            > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
        local compiled
        compiled=$(grep -c '^ *Compiling' "$log" || true)
        if [ "$compiled" != 1 ]; then
            echo "warning: $compiled crates compiled by cargo build --release -p $krate $*" >&2
            grep '^ *Compiling' "$log" >&2 || true
        fi
        read -r best_wall best_cpu <<< "$(awk -v bw="$best_wall" -v bc="$best_cpu" \
            '{ w = $1; c = $2 + $3; if (bw == "" || w < bw) bw = w; if (bc == "" || c < bc) bc = c }
             END { print bw, bc }' "$WORK/time.txt")"
    done
    WALL=$(printf "%.1f" "$best_wall")
    CPU=$(printf "%.1f" "$best_cpu")
}

echo
echo "| mechanism | dof | declared: wall s | CPU s | load | + every function called at f64: wall s | CPU s | load |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
# The same build of an empty crate (the stub): what any binary crate costs here.
timed_build stub
row="| (empty crate) | 0 | $WALL | $CPU | $LOAD"
timed_build stub --features call
echo "$row | $WALL | $CPU | $LOAD |"
for entry in "${CRATES[@]}"; do
    IFS=: read -r krate name _ <<< "$entry"
    dof=$(grep -c 'revolute\|prismatic' "$WORK/declarations/$krate.rs")
    if grep -q 'free(' "$WORK/declarations/$krate.rs"; then dof=$((dof + 6)); fi
    timed_build "$krate"
    row="| $name | $dof | $WALL | $CPU | $LOAD"
    timed_build "$krate" --features call
    echo "$row | $WALL | $CPU | $LOAD |"
done
echo
echo "$(nproc) cores; load average now: $(cut -d' ' -f1-3 /proc/loadavg)"
