//! The catalog of ill-posed mechanisms: one compile-fail case per rule of the `mechanism!`
//! language, `ui/<rule>.rs`, with the compiler's output in `ui/<rule>.stderr` (the caret
//! under the offending tokens, the message with the numbers). Regenerate a changed message
//! with `TRYBUILD=overwrite cargo test -p dynamics-tests --test ui`, then read the diff.
//!
//! URDF paths. `urdf: "..."` is relative to `CARGO_MANIFEST_DIR` of the crate that invokes
//! the macro. Under trybuild that is not this crate but the crate trybuild generates and
//! builds, `<target dir>/tests/trybuild/dynamics-tests/`, whose place follows the target
//! directory (`target/` of the workspace in CI, `$CARGO_TARGET_DIR` when set), so no
//! relative path from it reaches `tests/ui/urdf/` in every layout. The test therefore
//! copies the fixtures `ui/urdf/*.urdf` into `<generated crate>/urdf/` before running the
//! cases, which name them `urdf/<file>.urdf`; the generated crate's directory is found from
//! `CARGO_TARGET_TMPDIR` (`<target dir>/tmp`), the same target directory trybuild uses. The
//! missing-file case names an absolute path instead: its message repeats the path it looked
//! for, which must not depend on where the target directory is.

use std::path::{Path, PathBuf};

/// The directory of the crate trybuild generates for this package (its `CARGO_MANIFEST_DIR`).
fn trybuild_crate_dir() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .join("tests")
        .join("trybuild")
        .join(env!("CARGO_PKG_NAME"))
}

/// Copies the URDF fixtures where the cases' relative paths resolve.
fn install_urdf_fixtures() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("ui")
        .join("urdf");
    let destination = trybuild_crate_dir().join("urdf");
    std::fs::create_dir_all(&destination)
        .unwrap_or_else(|e| panic!("creating {}: {e}", destination.display()));
    let entries =
        std::fs::read_dir(&source).unwrap_or_else(|e| panic!("reading {}: {e}", source.display()));
    for entry in entries {
        let path = entry
            .unwrap_or_else(|e| panic!("reading {}: {e}", source.display()))
            .path();
        if let Some(name) = path.file_name() {
            std::fs::copy(&path, destination.join(name))
                .unwrap_or_else(|e| panic!("copying {}: {e}", path.display()));
        }
    }
}

#[test]
fn ui() {
    install_urdf_fixtures();
    let t = trybuild::TestCases::new();
    t.compile_fail("ui/*.rs");
}
