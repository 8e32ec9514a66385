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
