//! The `dynamics-codegen` command as a user runs it.

use std::io::Read;
use std::process::{Command, Stdio};

fn cli() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dynamics-codegen"))
}

const QUADRUPED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/src/quadruped.rs");

/// `dynamics-codegen f.rs | head`: the reader stops early; the command ends quietly and
/// successfully instead of panicking on the broken pipe.
#[test]
fn a_reader_that_stops_early_is_no_error() {
    let mut child = cli()
        .arg(QUADRUPED)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the command starts");
    let mut first = [0u8; 64];
    let mut stdout = child.stdout.take().expect("piped stdout");
    stdout.read_exact(&mut first).expect("some output");
    drop(stdout); // closes the pipe: the remaining ~400 KiB cannot be written
    let output = child.wait_with_output().expect("the command ends");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{:?}: {stderr}", output.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(String::from_utf8_lossy(&first).starts_with("// Quadruped (18 dof):"));
}

/// A missing file is a message and a nonzero exit.
#[test]
fn a_missing_file_is_a_message_and_a_nonzero_exit() {
    let output = cli().arg("no/such/file.rs").output().expect("runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.starts_with("dynamics-codegen: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// A fresh temporary directory for one test.
fn temporary(test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "dynamics-codegen-cli-{test}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

/// Runs the command on `file`: (exit code, stderr).
fn run_on(file: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    let output = cli().arg(file).args(args).output().expect("runs");
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// A syntax error, in the Rust around `mechanism!` or in its declaration, and a model error
/// are each reported at `file:line:column:` (1-based, as compilers print them), with a
/// nonzero exit.
#[test]
fn errors_name_the_file_line_and_column() {
    let dir = temporary("located");
    let cases = [
        ("rust.rs", "fn main( {}\n", ":1:8: "),
        (
            "dsl.rs",
            "use x;\n\nmechanism! {\n    pub struct P;\n    body rod { mass 1.0 }\n}\n",
            ":5:21: expected `:`",
        ),
        (
            "model.rs",
            "mechanism! {\n    pub struct P;\n    joint pin: revolute(ground -> rod) { axis: [0, 0, 1] }\n}\n",
            ":3:35: unknown child `rod`",
        ),
    ];
    for (name, text, expected) in cases {
        let file = dir.join(name);
        std::fs::write(&file, text).expect("write");
        let (code, stderr) = run_on(&file, &["--ops"]);
        assert_eq!(code, Some(2), "{name}: {stderr}");
        let located = format!("{}{expected}", file.display());
        assert!(stderr.contains(&located), "{name}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
    std::fs::remove_dir_all(&dir).expect("remove temporary directory");
}

/// A URDF file whose name is not an identifier (a leading digit, a keyword) still compiles:
/// the struct takes a `Urdf` prefix.
#[test]
fn urdf_file_names_that_are_not_identifiers_are_prefixed() {
    let dir = temporary("names");
    let pendulum = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/urdf/pendulum.urdf");
    for (file, name) in [("2link.urdf", "Urdf2link"), ("self.urdf", "UrdfSelf")] {
        let path = dir.join(file);
        std::fs::copy(pendulum, &path).expect("copy");
        let output = cli().arg(&path).arg("--ops").output().expect("runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{file}: {stderr}");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(stdout.starts_with(&format!("{name} (")), "{file}: {stdout}");
    }
    std::fs::remove_dir_all(&dir).expect("remove temporary directory");
}
