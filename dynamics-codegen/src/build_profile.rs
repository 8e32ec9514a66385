//! Whether the crate being compiled takes each long function whole, or cut into pieces.
//!
//! A function of more than [`crate::ir::DEFAULT_SPLIT_THRESHOLD`] statements is cut into
//! pieces ([`crate::schedule`]) for two reasons that belong to some builds only:
//!
//! - with debug info, rustc overflows its stack on a few thousand `let`s in one body,
//!   whatever the optimization level (LLVM's lexical scopes, one per `let`, are walked
//!   recursively);
//! - without optimization, rustc compiles one long body much more slowly than its pieces
//!   (ANYmal's two derivative functions: 19 s whole, 8 s in pieces).
//!
//! Pieces cost at run time: the values crossing each cut go through memory, and the
//! optimizer sees one piece at a time (ANYmal's ∂q̈ whole takes 0.83 of its time in four
//! pieces; g1's 0.56). So an optimized build without debug info (`cargo build --release`,
//! `cargo bench` with the default profiles) takes every function whole, and every other
//! build keeps the pieces.
//!
//! The `mechanism!` macro runs inside rustc, so it reads the build's settings from rustc's
//! own command line: the last `-C opt-level` and `-C debuginfo` (`-O` and `-g` are their
//! short forms; absent, rustc's defaults are no optimization and no debug info). Anything
//! it cannot read (an `@file` argument, an unknown value) keeps the pieces, which compile in
//! every build.

/// Whether a build with this rustc command line (program name first) may take long
/// functions whole: optimized, and without debug info.
#[must_use]
pub(crate) fn takes_whole_functions<I: IntoIterator<Item = String>>(rustc_args: I) -> bool {
    let mut opt_level = String::from("0");
    let mut debuginfo = String::from("0");
    let mut args = rustc_args.into_iter().skip(1);
    while let Some(arg) = args.next() {
        let setting = match arg.as_str() {
            "-O" => Some("opt-level=2".to_owned()),
            "-g" => Some("debuginfo=2".to_owned()),
            "-C" | "--codegen" => args.next(),
            _ if arg.starts_with('@') => return false,
            _ => arg
                .strip_prefix("-C")
                .or_else(|| arg.strip_prefix("--codegen="))
                .map(str::to_owned),
        };
        let Some(setting) = setting else { continue };
        match setting.split_once('=') {
            Some(("opt-level", level)) => opt_level = level.to_owned(),
            Some(("debuginfo", level)) => debuginfo = level.to_owned(),
            _ => {}
        }
    }
    let optimized = matches!(opt_level.as_str(), "1" | "2" | "3" | "s" | "z");
    let no_debug_info = matches!(
        debuginfo.as_str(),
        "0" | "none" | "n" | "no" | "off" | "false"
    );
    optimized && no_debug_info
}

#[cfg(test)]
mod tests {
    use super::takes_whole_functions;

    fn whole(line: &str) -> bool {
        takes_whole_functions(line.split_whitespace().map(str::to_owned))
    }

    #[test]
    fn cargo_release_takes_functions_whole() {
        // What cargo passes for `--release` and for `cargo bench` (no `-C debuginfo`).
        assert!(whole(
            "rustc --crate-name models --edition=2021 src/lib.rs --crate-type lib \
             -C opt-level=3 -C embed-bitcode=no -C metadata=ab12"
        ));
        assert!(whole("rustc -Copt-level=2 -Cdebuginfo=0 x.rs"));
        assert!(whole("rustc -O x.rs"));
        assert!(whole("rustc --codegen opt-level=s -C debuginfo=none x.rs"));
        assert!(whole("rustc --codegen=opt-level=1 x.rs"));
    }

    #[test]
    fn debug_info_or_no_optimization_keeps_the_pieces() {
        // `cargo build` (dev profile): no opt-level, debuginfo=2.
        assert!(!whole(
            "rustc --crate-name models src/lib.rs -C debuginfo=2"
        ));
        // Release with `debug = true` (or line tables only) would overflow rustc's stack.
        assert!(!whole("rustc -C opt-level=3 -C debuginfo=2 x.rs"));
        assert!(!whole(
            "rustc -C opt-level=3 -C debuginfo=line-tables-only x.rs"
        ));
        assert!(!whole("rustc -O -g x.rs"));
        // Dev without debug info: whole would compile slowly.
        assert!(!whole("rustc -C debuginfo=0 x.rs"));
        assert!(!whole("rustc x.rs"));
        assert!(!whole("rustc -C opt-level=0 x.rs"));
    }

    #[test]
    fn the_last_setting_wins_and_unreadable_lines_keep_the_pieces() {
        assert!(whole(
            "rustc -C debuginfo=2 -C opt-level=3 -C debuginfo=0 x.rs"
        ));
        assert!(!whole("rustc -C opt-level=3 -C opt-level=0 x.rs"));
        // Cargo may move a long command line into an argument file.
        assert!(!whole("rustc @/tmp/args -C opt-level=3"));
        // A trailing `-C` with nothing after it, and settings that are not ours.
        assert!(whole("rustc -C opt-level=3 -C target-cpu=native -C"));
        // The program name is never read as a setting.
        assert!(!whole("-O"));
    }
}
