#!/usr/bin/env bash
# What batching the joints' sines and cosines would gain the generated code (issue #5).
#
#   bash dynamics-runtime/tools/batched_trig_experiment.sh [MODEL_FILE] [MECHANISM]
#                                                   (default: models/src/anchors.rs Ur5)
#
# Prints the generated code of one mechanism with the codegen CLI, and builds, in a scratch
# crate outside the workspace (same release profile: opt-level 3, thin LTO, 16 codegen
# units), three copies of its gravity, inverse_dynamics and mass_matrix for f64 (a fixed-base
# mechanism without parameters or loads, such as Ur5 or Panda):
#   std    as generated: one `T::sin_cos` per joint angle (glibc's sincos);
#   poly   each `T::sin_cos` replaced by `fast_trig::sin_cos` (the polynomial, one at a time);
#   batch  the `T::sin_cos` lines removed and one `T::sin_cos_array([q..])` of the same
#          angles put first, which is what the emitter would write to use it.
# All three are checked against each other (1e-12 relative), then timed in turn: 15 rounds
# of 200 000 calls over 20 fixed random states, min and median ns per call.
# Needs python3 and the Rust toolchain; the scratch crate is left in $TMPDIR.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
FILE="${1:-models/src/anchors.rs}"
MECH="${2:-Ur5}"
WORK="${TMPDIR:-/tmp}/batched_trig_experiment"
mkdir -p "$WORK/src"
cd "$ROOT"
cargo run -q -p dynamics-codegen -- "$FILE" --only "$MECH" > "$WORK/generated.rs"
cat > "$WORK/Cargo.toml" <<TOML
[package]
name = "batched-trig-experiment"
version = "0.1.0"
edition = "2021"
publish = false

[dependencies]
dynamics-runtime = { path = "$ROOT/dynamics-runtime" }

[profile.release]
opt-level = 3
codegen-units = 16
lto = "thin"

[workspace]
TOML
cp "$ROOT/Cargo.lock" "$WORK/Cargo.lock"
python3 - "$WORK" <<'PYTHON'
import re, sys
work = sys.argv[1]
src = open(f"{work}/generated.rs").read()
SIN_COS = re.compile(r"        let \((v\d+), (v\d+)\) = T::sin_cos\((v\d+)\);\n")

def extract(name):
    m = re.search(r"\n    pub fn " + name + r"<T: ::dynamics_runtime::Scalar>\(", src)
    start = m.start() + 1
    return src[start:src.index("\n    }\n", start) + 7]

nq = re.search(r"pub fn gravity<T: ::dynamics_runtime::Scalar>\(q: &\[T; (\d+)\]", src).group(1)
out = ["#![allow(clippy::all, unused)]", "use dynamics_runtime::{fast_trig, Scalar};", "type T = f64;",
       f"pub const NQ: usize = {nq};"]
for name in ["gravity", "inverse_dynamics", "mass_matrix"]:
    body = extract(name).replace("<T: ::dynamics_runtime::Scalar>", "")
    out.append(body.replace("pub fn " + name, f"#[inline(never)] pub fn {name}_std")
               .replace("T::sin_cos(", "f64::sin_cos("))
    out.append(body.replace("pub fn " + name, f"#[inline(never)] pub fn {name}_poly")
               .replace("T::sin_cos(", "fast_trig::sin_cos("))
    angles = dict(re.findall(r"let (v\d+) = q\[(\d+)\];", body))
    pairs = SIN_COS.findall(body)
    lines = SIN_COS.sub("", body).split("\n")
    first = next(i for i, line in enumerate(lines) if line.rstrip().endswith("{"))
    sines = ", ".join(p[0] for p in pairs)
    cosines = ", ".join(p[1] for p in pairs)
    qs = ", ".join(f"q[{angles[p[2]]}]" for p in pairs)
    lines.insert(first + 1, f"        let ([{sines}], [{cosines}]) = T::sin_cos_array([{qs}]);")
    out.append("\n".join(lines).replace("pub fn " + name, f"#[inline(never)] pub fn {name}_batch"))
open(f"{work}/src/lib.rs", "w").write("\n".join(out))
PYTHON
cat > "$WORK/src/main.rs" <<'RUST'
use batched_trig_experiment::*;
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 * std::f64::consts::PI - std::f64::consts::PI
    };
    let qs: Vec<[f64; NQ]> = (0..20).map(|_| std::array::from_fn(|_| next())).collect();
    let v = [0.3; NQ];
    let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs()));
    for q in &qs {
        assert!(close(&gravity_std(q), &gravity_batch(q)) && close(&gravity_std(q), &gravity_poly(q)));
        let (a, b) = (inverse_dynamics_std(q, &v, &v), inverse_dynamics_batch(q, &v, &v));
        assert!(close(&a, &b));
        assert!(close(mass_matrix_std(q).as_flattened(), mass_matrix_batch(q).as_flattened()));
    }
    macro_rules! time {
        ($f:expr) => {{
            let n = 200_000;
            let t = Instant::now();
            for k in 0..n {
                black_box($f(black_box(&qs[k % 20])));
            }
            t.elapsed().as_nanos() as f64 / n as f64
        }};
    }
    let names = ["gravity", "inverse_dynamics", "mass_matrix"];
    let mut ns = vec![vec![Vec::new(); 3]; 3];
    for _ in 0..15 {
        ns[0][0].push(time!(gravity_std));
        ns[0][1].push(time!(gravity_poly));
        ns[0][2].push(time!(gravity_batch));
        ns[1][0].push(time!(|q| inverse_dynamics_std(q, &v, &v)));
        ns[1][1].push(time!(|q| inverse_dynamics_poly(q, &v, &v)));
        ns[1][2].push(time!(|q| inverse_dynamics_batch(q, &v, &v)));
        ns[2][0].push(time!(mass_matrix_std));
        ns[2][1].push(time!(mass_matrix_poly));
        ns[2][2].push(time!(mass_matrix_batch));
    }
    println!("{:18} {:>16} {:>16} {:>16} {:>12}", "ns per call", "std min/median", "poly min/median", "batch min/median", "std/batch");
    for (i, name) in names.iter().enumerate() {
        let mut row = format!("{name:18}");
        let mut medians = [0.0; 3];
        for j in 0..3 {
            let r = &mut ns[i][j];
            r.sort_by(|a, b| a.total_cmp(b));
            medians[j] = r[r.len() / 2];
            row += &format!(" {:>16}", format!("{:.1}/{:.1}", r[0], medians[j]));
        }
        println!("{row} {:>12.2}", medians[0] / medians[2]);
    }
}
RUST
cd "$WORK"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
cargo run -q --release --offline 2>/dev/null || cargo run -q --release
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
