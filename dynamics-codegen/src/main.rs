//! `dynamics-codegen`: prints the Rust that `mechanism!` generates, pretty-printed, with the
//! op count of every function.
//!
//! ```text
//! dynamics-codegen <file.rs | file.urdf> [--only NAME] [--ops] [--whole]
//! ```
//!
//! A `.rs` file is searched for `mechanism! { ... }` invocations (URDF paths inside them are
//! relative to the nearest folder with a `Cargo.toml`, as in the macro). A `.urdf` file is
//! compiled as a fixed-base mechanism with every output and the default gravity of every
//! declaration, (0, 0, −9.81).
//! `--only NAME` keeps one mechanism; `--ops` prints only the op-count table; `--whole`
//! prints long functions whole, as the macro does in a build optimized and without debug
//! info (faster code; such a file compiles only in such builds), where by default they are
//! cut into pieces, which compile in every build. Beside each
//! count: the longest chain of dependent operations, in estimated cycles
//! (`Graph::longest_chain`).

use dynamics_codegen::{compile, expand_if_std, to_tokens, Compiled, Mechanism};
use std::io::{ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

struct Options {
    file: PathBuf,
    only: Option<String>,
    ops_only: bool,
    whole: bool,
}

fn parse_args() -> Result<Options, String> {
    let mut args = std::env::args().skip(1);
    let (mut file, mut only, mut ops_only, mut whole) = (None, None, false, false);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--only" => only = Some(args.next().ok_or("--only needs a mechanism name")?),
            "--ops" => ops_only = true,
            "--whole" => whole = true,
            "-h" | "--help" => return Err(String::new()),
            _ if file.is_none() => file = Some(PathBuf::from(arg)),
            _ => return Err(format!("unexpected argument `{arg}`")),
        }
    }
    let file = file.ok_or("give a .rs file with mechanism! invocations, or a .urdf file")?;
    Ok(Options {
        file,
        only,
        ops_only,
        whole,
    })
}

/// Whether `file` is read as a URDF file (by its extension) rather than as Rust.
fn is_urdf(file: &Path) -> bool {
    file.extension().is_some_and(|e| e == "urdf")
}

/// The folder URDF paths are relative to: the nearest ancestor with a Cargo.toml.
fn manifest_dir(file: &Path) -> PathBuf {
    let start = file.parent().unwrap_or(Path::new("."));
    start
        .ancestors()
        .find(|d| d.join("Cargo.toml").is_file())
        .unwrap_or(start)
        .to_path_buf()
}

fn mechanisms(file: &Path) -> Result<Vec<(Mechanism, PathBuf)>, String> {
    let text = std::fs::read_to_string(file)
        .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
    if is_urdf(file) {
        let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("robot");
        let path = file
            .file_name()
            .and_then(|f| f.to_str())
            .unwrap_or_default();
        let tokens: proc_macro2::TokenStream =
            format!("pub struct {}; urdf: {:?};", struct_name(stem), path)
                .parse()
                .map_err(|e| format!("{e}"))?;
        let mechanism = syn::parse2(tokens).map_err(|e| e.to_string())?;
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        return Ok(vec![(mechanism, dir)]);
    }
    let parsed = syn::parse_file(&text).map_err(|e| located(file, e))?;
    let dir = manifest_dir(file);
    let mut found = Vec::new();
    for item in parsed.items {
        if let syn::Item::Macro(m) = item {
            if m.mac
                .path
                .segments
                .last()
                .is_some_and(|s| s.ident == "mechanism")
            {
                let mechanism = syn::parse2(m.mac.tokens).map_err(|e| located(file, e))?;
                found.push((mechanism, dir.clone()));
            }
        }
    }
    Ok(found)
}

/// The struct name for a URDF file's stem: its ASCII letters and digits in CamelCase
/// (`two_link` → `TwoLink`), `Robot` when there are none, prefixed with `Urdf` when that is
/// not an identifier (`2link` → `Urdf2link`, `self` → `UrdfSelf`).
fn struct_name(stem: &str) -> String {
    let name: String = stem
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(|w| w[..1].to_ascii_uppercase() + &w[1..])
        .collect();
    if name.is_empty() {
        "Robot".to_owned()
    } else if syn::parse_str::<syn::Ident>(&name).is_ok() {
        name
    } else {
        format!("Urdf{name}")
    }
}

/// `error`'s messages, each as `file:line:column: message` at the start of its span (line
/// and column counted from 1, as compilers print them).
fn located(file: &Path, error: syn::Error) -> String {
    error
        .into_iter()
        .map(|e| {
            let start = e.span().start();
            format!(
                "{}:{}:{}: {e}",
                file.display(),
                start.line,
                start.column + 1
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn op_table(compiled: &Compiled) -> String {
    let mut out = format!("{} ({} dof):\n", compiled.name(), compiled.nv());
    for f in compiled.functions() {
        out += &format!(
            "  {:<20} {}; longest chain {} cycles\n",
            f.name, f.ops, f.longest_chain
        );
    }
    if let Some(r) = compiled.rotation_residues() {
        out += &format!("  note: {}\n", r.advice());
    }
    out
}

fn run(options: &Options) -> Result<(), String> {
    let mut any = false;
    for (mechanism, dir) in mechanisms(&options.file)? {
        if options.only.as_ref().is_some_and(|n| mechanism.name != n) {
            continue;
        }
        any = true;
        let mut compiled = compile(mechanism, &dir).map_err(|e| {
            if is_urdf(&options.file) {
                // The spans are those of the declaration made up for the file, not of a
                // place in it; URDF errors name their line and column in the message.
                e.into_iter()
                    .map(|e| format!("{}: error: {e}", options.file.display()))
                    .collect::<Vec<_>>()
                    .join("\n")
            } else {
                located(&options.file, e)
            }
        })?;
        if options.whole {
            compiled.take_functions_whole();
        }
        let text = if options.ops_only {
            op_table(&compiled)
        } else {
            let mut file: syn::File =
                syn::parse2(to_tokens(&compiled)).map_err(|e| format!("internal: {e}"))?;
            expand_if_std(&mut file).map_err(|e| format!("internal: {e}"))?;
            format!(
                "// {}\n{STD_NOTE}\n{}\n",
                op_table(&compiled).trim_end().replace('\n', "\n// "),
                prettyplease::unparse(&file)
            )
        };
        if !write_out(&text)? {
            return Ok(());
        }
    }
    if any {
        Ok(())
    } else {
        Err(format!(
            "no matching mechanism! in {}",
            options.file.display()
        ))
    }
}

/// The lines under the op counts that say what [`expand_if_std`] did.
const STD_NOTE: &str = "// As the runtime's default `std` feature compiles it: the macro wraps \
`Mechanism::model*` and\n// the `*_na` wrappers in `::dynamics_runtime::__if_std! { .. }`, which \
drops them without `std`.";

/// Writes `text` to stdout: `Ok(false)` when the reader has stopped reading
/// (`dynamics-codegen f.rs | head`), which ends the output quietly; an error message for any
/// other failure to write.
fn write_out(text: &str) -> Result<bool, String> {
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(false),
        Err(e) => Err(format!("cannot write the output: {e}")),
    }
}

fn main() -> ExitCode {
    match parse_args().and_then(|o| run(&o)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            if !message.is_empty() {
                eprintln!("dynamics-codegen: {message}");
            }
            eprintln!(
                "usage: dynamics-codegen <file.rs | file.urdf> [--only NAME] [--ops] [--whole]"
            );
            ExitCode::from(2)
        }
    }
}
