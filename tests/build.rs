//! Writes the random trees of `generated_random_trees` as `mechanism!` declarations, so that
//! they go through the macro like any user's mechanism:
//!
//! - `$OUT_DIR/random_tree_NN.rs`: one tree of NN joints (the `mechanism!` invocation and a
//!   `impl` with the numbers the test needs to build the reference's external wrenches);
//! - `$OUT_DIR/random_trees.rs`: all of them, and `for_each_random_tree!(callback)`, which
//!   calls `callback!(test_name, Type, p: yes|no, loads: yes|no, [functions])` once per
//!   tree, `functions` the names of the functions generated for it.
//!
//! - `$OUT_DIR/random_frame_trees.rs`: four random trees with bodies welded through fixed
//!   joints and declared frames (on moving bodies, welded bodies and the ground), free roots
//!   among them, generating every kinematics output, for `generated_random_frames`.
//!
//! The trees are fixed (a deterministic generator with a fixed seed), spread over 1 to 30
//! joints: random parents (trees, one chain), revolute and prismatic joints about random and
//! coordinate axes, random placements, valid random inertias (principal moments from
//! second moments, so the triangle inequality holds, rotated), random mass centres; some
//! with armature and damping, some with a free root, some with loads, some with a symbolic
//! parameter (one with both), two with forward dynamics by both methods besides the
//! default outputs. Numbers are printed with `{:?}`, which round-trips `f64` exactly.

use std::fmt::Write as _;
use std::path::Path;

#[path = "src/default_functions.rs"]
mod default_functions;
#[path = "src/split_mix.rs"]
mod split_mix;

use default_functions::DEFAULT_FUNCTIONS;
use split_mix::SplitMix as Rng;

#[derive(Clone, Copy, PartialEq)]
enum Load {
    Force,
    Couple,
    Wrench,
}

impl Load {
    fn keyword(self) -> &'static str {
        match self {
            Load::Force => "force",
            Load::Couple => "couple",
            Load::Wrench => "wrench",
        }
    }
}

/// What one tree has.
struct Spec {
    joints: usize,
    free_root: bool,
    /// Every parent is the previous body.
    chain: bool,
    /// Armature and damping on the one-coordinate joints.
    friction: bool,
    /// Probability of a prismatic joint.
    prismatic: f64,
    loads: &'static [Load],
    /// The last body's mass is the parameter `m_tip`.
    parameter: bool,
    /// Besides the default outputs, forward dynamics by both methods
    /// (`forward_dynamics_aba`, `forward_dynamics_ldlt`).
    both_methods: bool,
}

const fn spec(joints: usize) -> Spec {
    Spec {
        joints,
        free_root: false,
        chain: false,
        friction: false,
        prismatic: 0.25,
        loads: &[],
        parameter: false,
        both_methods: false,
    }
}

/// The trees: sizes spread over 1..=30, exactly one of 30 joints.
const TREES: [Spec; 10] = [
    Spec {
        parameter: true,
        friction: true,
        ..spec(1)
    },
    Spec {
        free_root: true,
        loads: &[Load::Wrench],
        ..spec(2)
    },
    Spec {
        friction: true,
        prismatic: 0.5,
        ..spec(4)
    },
    Spec {
        friction: true,
        loads: &[Load::Wrench, Load::Force, Load::Couple],
        parameter: true,
        both_methods: true,
        ..spec(6)
    },
    Spec {
        free_root: true,
        friction: true,
        both_methods: true,
        ..spec(8)
    },
    Spec {
        chain: true,
        ..spec(11)
    },
    Spec {
        parameter: true,
        friction: true,
        ..spec(14)
    },
    Spec {
        free_root: true,
        loads: &[Load::Wrench, Load::Wrench],
        ..spec(18)
    },
    Spec {
        friction: true,
        ..spec(23)
    },
    Spec {
        friction: true,
        ..spec(30)
    },
];

/// Nominal value of `m_tip`.
const NOMINAL_TIP_MASS: f64 = 1.3;

fn vector(v: [f64; 3]) -> String {
    format!("[{:?}, {:?}, {:?}]", v[0], v[1], v[2])
}

fn rpy(v: [f64; 3]) -> String {
    format!("rpy({:?}, {:?}, {:?})", v[0], v[1], v[2])
}

/// A joint axis: a coordinate axis (either sign) or a random direction, not normalized.
fn axis(rng: &mut Rng) -> String {
    if rng.chance(0.4) {
        let sign = if rng.chance(0.5) { "-" } else { "" };
        format!("{sign}{}", ["x", "y", "z"][rng.below(3)])
    } else {
        loop {
            let a = rng.vector(-1.0, 1.0);
            if a.iter().map(|x| x * x).sum::<f64>() > 0.04 {
                return vector(a);
            }
        }
    }
}

/// The `mechanism!` declaration of one tree and the loads' constants.
fn tree(name: &str, spec: &Spec, rng: &mut Rng) -> String {
    let n = spec.joints;
    let mut features = vec![format!("{n} joints")];
    if spec.free_root {
        features.push("a free root".into());
    }
    if spec.chain {
        features.push("a chain".into());
    }
    if spec.friction {
        features.push("armature and damping".into());
    }
    if !spec.loads.is_empty() {
        let plural = if spec.loads.len() == 1 { "" } else { "s" };
        features.push(format!("{} load{plural}", spec.loads.len()));
    }
    if spec.parameter {
        features.push("the last body's mass a parameter".into());
    }
    if spec.both_methods {
        features.push("forward dynamics by both methods too".into());
    }
    let mut s = String::new();
    writeln!(s, "::dynamics_runtime::mechanism! {{").expect("writing to a String");
    writeln!(
        s,
        "    /// A random tree written by `tests/build.rs`: {}.",
        features.join(", ")
    )
    .expect("writing to a String");
    writeln!(s, "    pub struct {name};").expect("writing to a String");
    writeln!(s, "    gravity: {};", vector(rng.vector(-10.0, 10.0))).expect("writing to a String");
    if spec.both_methods {
        writeln!(
            s,
            "    outputs: [inverse_dynamics, mass_matrix, coriolis, gravity, bias, forward_dynamics, \
             forward_dynamics_aba, forward_dynamics_ldlt, energy, reactions];"
        )
        .expect("writing to a String");
    }
    if spec.parameter {
        writeln!(s, "    parameters: [m_tip = {NOMINAL_TIP_MASS:?}];")
            .expect("writing to a String");
    }
    writeln!(s).expect("writing to a String");
    for k in 0..n {
        let mass = if spec.parameter && k == n - 1 {
            "m_tip".to_owned()
        } else {
            format!("{:?}", rng.uniform(0.1, 5.0))
        };
        // ∫x² dm, ∫y² dm, ∫z² dm about principal axes: the moments satisfy the triangle
        // inequality by construction.
        let [d1, d2, d3] = rng.vector(0.0005, 0.05);
        let moments = [d2 + d3, d1 + d3, d1 + d2];
        let axes = rng.vector(-3.0, 3.0);
        let com = rng.vector(-0.3, 0.3);
        writeln!(
            s,
            "    body b{k} {{ mass: {mass}, com: {}, inertia: principal({}, rotation: {}) }}",
            vector(com),
            vector(moments),
            rpy(axes)
        )
        .expect("writing to a String");
    }
    writeln!(s).expect("writing to a String");
    for k in 0..n {
        if k == 0 && spec.free_root {
            writeln!(s, "    joint j0: free(ground -> b0);").expect("writing to a String");
            continue;
        }
        // Parents: the previous body half the time (deep trees), else any earlier body (or
        // the ground, for a fixed base).
        let parent = if k == 0 {
            "ground".to_owned()
        } else if spec.chain || rng.chance(0.5) {
            format!("b{}", k - 1)
        } else if spec.free_root {
            format!("b{}", rng.below(k))
        } else {
            match rng.below(k + 1) {
                0 => "ground".to_owned(),
                p => format!("b{}", p - 1),
            }
        };
        let kind = if rng.chance(spec.prismatic) {
            "prismatic"
        } else {
            "revolute"
        };
        let mut fields = vec![
            format!("axis: {}", axis(rng)),
            format!("at: {}", vector(rng.vector(-0.5, 0.5))),
            format!("rotation: {}", rpy(rng.vector(-3.0, 3.0))),
        ];
        if spec.friction {
            fields.push(format!("armature: {:?}", rng.uniform(0.0, 0.2)));
            fields.push(format!("damping: {:?}", rng.uniform(0.0, 0.5)));
        }
        writeln!(
            s,
            "    joint j{k}: {kind}({parent} -> b{k}) {{ {} }}",
            fields.join(", ")
        )
        .expect("writing to a String");
    }
    let loads: Vec<(usize, Load, [f64; 3])> = spec
        .loads
        .iter()
        .map(|&kind| (rng.below(n), kind, rng.vector(-0.3, 0.3)))
        .collect();
    if !loads.is_empty() {
        writeln!(s).expect("writing to a String");
    }
    for (k, (body, kind, point)) in loads.iter().enumerate() {
        let at = if *kind == Load::Couple {
            String::new()
        } else {
            format!(" at {}", vector(*point))
        };
        writeln!(s, "    load l{k}: {} on b{body}{at};", kind.keyword())
            .expect("writing to a String");
    }
    writeln!(s, "}}").expect("writing to a String");
    writeln!(s).expect("writing to a String");
    writeln!(s, "impl {name} {{").expect("writing to a String");
    writeln!(
        s,
        "    /// The declared loads, in input order: loaded body, `force`, `couple` or \
         `wrench`, point of application in the body frame."
    )
    .expect("writing to a String");
    write!(
        s,
        "    pub const DECLARED_LOADS: &'static [(&'static str, &'static str, [f64; 3])] = &["
    )
    .expect("writing to a String");
    for (body, kind, point) in &loads {
        let point = if *kind == Load::Couple {
            [0.0; 3]
        } else {
            *point
        };
        write!(
            s,
            "(\"b{body}\", \"{}\", {}), ",
            kind.keyword(),
            vector(point)
        )
        .expect("writing to a String");
    }
    writeln!(s, "];").expect("writing to a String");
    writeln!(s, "}}").expect("writing to a String");
    s
}

/// The kinematics outputs the frame trees generate.
const FRAME_OUTPUTS: &str = "frame_placements, frame_jacobians, frame_jacobians_local, \
    frame_velocities, frame_acceleration_biases, centroidal_bias, joint_placements, \
    joint_jacobians, joint_velocities, joint_acceleration_biases, center_of_mass, \
    center_of_mass_jacobian, centroidal_momentum_matrix";

/// A random tree with welded bodies and declared frames, for `generated_random_frames`:
/// `joints` moving joints (a free root when `free_root`), a welded body on every third
/// body, and frames on random bodies, on welded ones and on the ground.
fn frame_tree(name: &str, joints: usize, free_root: bool, rng: &mut Rng) -> String {
    let mut s = String::new();
    let mut line = |text: String| writeln!(s, "{text}").expect("writing to a String");
    line("::dynamics_runtime::mechanism! {".into());
    line(format!(
        "    /// A random tree with frames written by `tests/build.rs`: {joints} joints{}.",
        if free_root { ", a free root" } else { "" }
    ));
    line(format!("    pub struct {name};"));
    line(format!("    outputs: [{FRAME_OUTPUTS}];"));
    let welded: Vec<usize> = (0..joints).filter(|k| k % 3 == 2).collect();
    let body = |s: &mut Vec<String>, name: String, rng: &mut Rng| {
        let [d1, d2, d3] = rng.vector(0.0005, 0.05);
        s.push(format!(
            "    body {name} {{ mass: {:?}, com: {}, inertia: principal({}, rotation: {}) }}",
            rng.uniform(0.1, 5.0),
            vector(rng.vector(-0.3, 0.3)),
            vector([d2 + d3, d1 + d3, d1 + d2]),
            rpy(rng.vector(-3.0, 3.0))
        ));
    };
    let mut items = Vec::new();
    for k in 0..joints {
        body(&mut items, format!("b{k}"), rng);
    }
    for &k in &welded {
        body(&mut items, format!("w{k}"), rng);
    }
    for k in 0..joints {
        if k == 0 && free_root {
            items.push("    joint j0: free(ground -> b0);".into());
            continue;
        }
        let parent = match (k, free_root) {
            (0, _) => "ground".to_owned(),
            (_, true) => format!("b{}", rng.below(k)),
            _ => match rng.below(k + 1) {
                0 => "ground".to_owned(),
                p => format!("b{}", p - 1),
            },
        };
        let kind = if rng.chance(0.25) {
            "prismatic"
        } else {
            "revolute"
        };
        items.push(format!(
            "    joint j{k}: {kind}({parent} -> b{k}) {{ axis: {}, at: {}, rotation: {} }}",
            axis(rng),
            vector(rng.vector(-0.5, 0.5)),
            rpy(rng.vector(-3.0, 3.0))
        ));
    }
    for &k in &welded {
        items.push(format!(
            "    joint weld{k}: fixed(b{k} -> w{k}) {{ at: {}, rotation: {} }}",
            vector(rng.vector(-0.3, 0.3)),
            rpy(rng.vector(-3.0, 3.0))
        ));
    }
    for f in 0..joints.div_ceil(2) {
        let on = match f % 4 {
            0 if !welded.is_empty() => format!("w{}", welded[rng.below(welded.len())]),
            3 => "ground".to_owned(),
            _ => format!("b{}", rng.below(joints)),
        };
        items.push(format!(
            "    frame f{f}: on {on} at {} rotation {};",
            vector(rng.vector(-0.4, 0.4)),
            rpy(rng.vector(-3.0, 3.0))
        ));
    }
    for item in items {
        line(item);
    }
    line("}".into());
    s
}

/// The frame trees: (moving joints, free root).
const FRAME_TREES: [(usize, bool); 4] = [(3, false), (8, true), (14, false), (22, true)];

fn main() {
    // This file and the two it includes.
    for file in ["build.rs", "src/default_functions.rs", "src/split_mix.rs"] {
        println!("cargo:rerun-if-changed={file}");
    }
    let out = std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR");
    let out = Path::new(&out);
    let mut rng = Rng(0x7e57_7ee5_2026);
    let mut all = String::from(
        "// Written by tests/build.rs: every random tree, and a macro that visits them.\n\n",
    );
    let mut visits = String::new();
    for spec in &TREES {
        let n = spec.joints;
        let name = format!("RandomTree{n:02}");
        let file = format!("random_tree_{n:02}.rs");
        std::fs::write(out.join(&file), tree(&name, spec, &mut rng)).expect("OUT_DIR writable");
        writeln!(all, "include!(concat!(env!(\"OUT_DIR\"), \"/{file}\"));")
            .expect("writing to a String");
        let yes = |b: bool| if b { "yes" } else { "no" };
        let mut functions = DEFAULT_FUNCTIONS.to_vec();
        if spec.both_methods {
            functions.extend(["forward_dynamics_aba", "forward_dynamics_ldlt"]);
        }
        writeln!(
            visits,
            "        $callback!(random_tree_{n:02}, {name}, p: {}, loads: {}, [{}]);",
            yes(spec.parameter),
            yes(!spec.loads.is_empty()),
            functions.join(", ")
        )
        .expect("writing to a String");
    }
    writeln!(
        all,
        "\n/// Calls `$callback!(test_name, Type, p: yes|no, loads: yes|no, [generated functions])`\n\
         /// for every random tree.\n\
         #[allow(unused_macros)]\n\
         macro_rules! for_each_random_tree {{\n    ($callback:ident) => {{\n{visits}    }};\n}}"
    )
    .expect("writing to a String");
    std::fs::write(out.join("random_trees.rs"), all).expect("OUT_DIR writable");

    let mut rng = Rng(0x00f4_a3e5_2026);
    let mut frames =
        String::from("// Written by tests/build.rs: the random trees with frames.\n\n");
    for (joints, free_root) in FRAME_TREES {
        frames.push_str(&frame_tree(
            &format!("FrameTree{joints:02}"),
            joints,
            free_root,
            &mut rng,
        ));
        frames.push('\n');
    }
    std::fs::write(out.join("random_frame_trees.rs"), frames).expect("OUT_DIR writable");
}
