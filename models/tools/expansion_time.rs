//! Times the expansion of `mechanism!` declarations by the compiler library
//! (`dynamics_codegen`), stage by stage, without rustc around it.
//!
//! ```text
//! expansion_time <file.rs>...
//! ```
//!
//! Each file's top-level `mechanism! { ... }` invocations are expanded at least `REPEATS`
//! times and for at least `MIN_SECONDS`, and a Markdown row printed: the median wall time
//! of every stage, parse (tokens → syntax tree), compile (validation, symbolic expansion,
//! optimized graphs: `dynamics_codegen::compile`), emit (graphs → Rust tokens: `to_tokens`)
//! and print (the tokens as text, about what the macro hands back to rustc); their total;
//! the process's CPU time per expansion (user + sys from `/proc/self/stat`, in ticks of
//! `CLK_TCK`, 100 unless the environment says otherwise), which other jobs on the machine
//! do not inflate; the size of the generated text and the operation count of all the
//! generated functions together.
//!
//! `models/tools/compile_cost.sh` builds this file twice: optimized, and with the settings
//! Cargo gives proc macros in a release build (`opt-level = 0`, its `build-override`), which
//! is how fast the expansion runs inside `cargo build --release`.

use dynamics_codegen::{compile, to_tokens, Mechanism};
use std::path::Path;
use std::time::Instant;

/// Fewest expansions per declaration.
const REPEATS: usize = 5;
/// Fewest seconds of expansions per declaration, for the CPU time's 10 ms ticks.
const MIN_SECONDS: f64 = 2.0;

/// CPU seconds (user + sys) used by this process so far.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name (which may hold spaces, inside parentheses): state is
    // field 3 of the line, utime and stime fields 14 and 15.
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or("", |(_, rest)| rest)
        .split_whitespace()
        .collect();
    let ticks: f64 = [11, 12]
        .iter()
        .filter_map(|&i| fields.get(i)?.parse::<f64>().ok())
        .sum();
    let per_second: f64 = std::env::var("CLK_TCK")
        .ok()
        .and_then(|t| t.parse().ok())
        .unwrap_or(100.0);
    ticks / per_second
}

/// The top-level `mechanism!` invocations of a Rust file, as token streams.
fn declarations(path: &Path) -> Vec<proc_macro2::TokenStream> {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let file = syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    file.items
        .into_iter()
        .filter_map(|item| match item {
            syn::Item::Macro(m)
                if m.mac
                    .path
                    .segments
                    .last()
                    .is_some_and(|s| s.ident == "mechanism") =>
            {
                Some(m.mac.tokens)
            }
            _ => None,
        })
        .collect()
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

fn main() {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        eprintln!("usage: expansion_time <file.rs>...");
        std::process::exit(2);
    }
    println!("| mechanism | dof | parse ms | compile ms | emit ms | print ms | total ms | CPU ms | generated KiB | ops |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    for file in &files {
        let path = Path::new(file);
        let dir = path.parent().unwrap_or(Path::new("."));
        for tokens in declarations(path) {
            let mut stages: [Vec<f64>; 4] = Default::default();
            let (mut name, mut dof, mut bytes, mut ops) = (String::new(), 0, 0, 0);
            let (start, cpu_start) = (Instant::now(), cpu_seconds());
            let mut repeats = 0;
            while repeats < REPEATS || start.elapsed().as_secs_f64() < MIN_SECONDS {
                repeats += 1;
                let t0 = Instant::now();
                let mechanism: Mechanism =
                    syn::parse2(tokens.clone()).unwrap_or_else(|e| panic!("{file}: {e}"));
                let t1 = Instant::now();
                let compiled = compile(mechanism, dir).unwrap_or_else(|e| panic!("{file}: {e}"));
                let t2 = Instant::now();
                let emitted = to_tokens(&compiled);
                let t3 = Instant::now();
                let text = emitted.to_string();
                let t4 = Instant::now();
                for (stage, (a, b)) in
                    stages
                        .iter_mut()
                        .zip([(t0, t1), (t1, t2), (t2, t3), (t3, t4)])
                {
                    stage.push((b - a).as_secs_f64() * 1e3);
                }
                name = compiled.name();
                dof = compiled.nv();
                bytes = text.len();
                ops = compiled
                    .functions()
                    .iter()
                    .map(|f| {
                        let c = f.ops;
                        c.mul + c.add + c.div + c.neg + c.sqrt + c.trig
                    })
                    .sum::<usize>();
            }
            let cpu_ms = (cpu_seconds() - cpu_start) * 1e3 / repeats as f64;
            let [parse, compile, emit, print] = stages.map(median);
            println!(
                "| {name} | {dof} | {parse:.1} | {compile:.1} | {emit:.1} | {print:.1} | {:.1} | {cpu_ms:.1} | {:.0} | {ops} |",
                parse + compile + emit + print,
                bytes as f64 / 1024.0
            );
        }
    }
}
