//! Validation is linear in the number of links (issue 21): a URDF of 20,000 links welded
//! through fixed joints, as a chain (two revolute joints among them) and as a star, compiles
//! within a bound that the old, cubic rules could not meet (optimised, a welded chain of
//! 4,000 links took 29 s, 10,000 links 10 min).
//!
//! The tests run unoptimised. Measured so on the 2-core host of BENCHMARKS.md, loaded: the
//! 20,000-link chain compiles in about 3 s, the star in about 5 s (each asks for one output,
//! so the expansion, linear too, is one graph); the bound is 60 s, over ten times that, for
//! a loaded machine. Before, the chain did not finish within the bound (the compilation runs
//! on a thread that the test stops waiting for) and the star took 26 s. The links match
//! `models/tools/welded_urdf.py`, which the "Validation cost" section of BENCHMARKS.md times
//! with the release command-line compiler.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::{Duration, Instant};

const LINKS: usize = 20_000;
const BOUND: Duration = Duration::from_secs(60);

fn link(out: &mut String, name: &str) {
    let _ = writeln!(
        out,
        r#"  <link name="{name}"><inertial><origin xyz="0.005 0 0" rpy="0 0 0"/><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="2e-5"/></inertial></link>"#
    );
}

fn joint(out: &mut String, name: &str, revolute: bool, parent: &str, child: &str, xyz: &str) {
    let (kind, extra) = if revolute {
        (
            "revolute",
            r#"<axis xyz="0 0 1"/><limit lower="-3.14" upper="3.14" effort="10" velocity="5"/>"#,
        )
    } else {
        ("fixed", "")
    };
    let _ = writeln!(
        out,
        r#"  <joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/><origin xyz="{xyz}" rpy="0 0 0"/>{extra}</joint>"#
    );
}

/// `chain`: link0 … link{n−1} each welded to the one before, revolute at n/3 and 2n/3;
/// `star`: n links welded to `base`, which a revolute joint moves.
fn urdf(star: bool, n: usize) -> String {
    let mut out = String::from("<?xml version=\"1.0\"?>\n<robot name=\"welded\">\n");
    if star {
        link(&mut out, "world");
        link(&mut out, "base");
        joint(&mut out, "hinge", true, "world", "base", "0 0 0");
        for i in 0..n {
            let name = format!("link{i}");
            link(&mut out, &name);
            let xyz = format!("0.01 {:.4} 0", i as f64 * 1e-4);
            joint(&mut out, &format!("joint{i}"), false, "base", &name, &xyz);
        }
    } else {
        link(&mut out, "base");
        for i in 0..n {
            let name = format!("link{i}");
            let parent = if i == 0 {
                "base".to_owned()
            } else {
                format!("link{}", i - 1)
            };
            link(&mut out, &name);
            let revolute = i == n / 3 || i == 2 * n / 3;
            joint(
                &mut out,
                &format!("joint{i}"),
                revolute,
                &parent,
                &name,
                "0.01 0 0",
            );
        }
    }
    out.push_str("</robot>\n");
    out
}

/// Writes the file into a fresh directory and compiles it with one output, on a thread
/// that is given [`BOUND`]: the time taken and the number of coordinates, or a failure at
/// the bound (the old, cubic rules would have kept the test running for hours).
fn compile(shape: &'static str, star: bool) -> (Duration, usize) {
    let dir: PathBuf = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("validation-cost-{shape}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    std::fs::write(dir.join("welded.urdf"), urdf(star, LINKS)).expect("URDF written");
    let (send, receive) = std::sync::mpsc::channel();
    let at = dir.clone();
    std::thread::spawn(move || {
        let mechanism: dynamics_codegen::Mechanism =
            syn::parse_str(r#"pub struct Welded; urdf: "welded.urdf"; outputs: [kinetic_energy];"#)
                .expect("parses");
        let start = Instant::now();
        let compiled = dynamics_codegen::compile(mechanism, &at).map(|c| c.nv());
        let _ = send.send((start.elapsed(), compiled.map_err(|e| e.to_string())));
    });
    let outcome = receive.recv_timeout(BOUND);
    let _ = std::fs::remove_dir_all(&dir);
    match outcome {
        Ok((elapsed, Ok(nv))) => {
            eprintln!("the welded {shape} of {LINKS} links: {elapsed:?}");
            (elapsed, nv)
        }
        Ok((_, Err(e))) => panic!("the welded {shape} is valid: {e}"),
        Err(_) => panic!("a {shape} of {LINKS} welded links did not compile within {BOUND:?}"),
    }
}

#[test]
fn a_welded_chain_of_20000_links_validates_in_linear_time() {
    let (_, nv) = compile("chain", false);
    assert_eq!(nv, 2);
}

#[test]
fn a_welded_star_of_20000_links_validates_in_linear_time() {
    let (_, nv) = compile("star", true);
    assert_eq!(nv, 1);
}
