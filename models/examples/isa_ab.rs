//! The generated code's two copies side by side in one process: the AVX2 + FMA kernels
//! against the baseline (SSE2) ones, for the UR5, the Panda and the quadruped.
//!
//! Paired rounds rather than two criterion runs, because on a shared host the machine's
//! speed drifts between runs more than the two copies differ: each of 41 rounds times
//! both copies back to back (20 000 calls each, over 20 fixed random states, the order
//! alternating), switching with `dynamics_runtime::isa::choose`; the figure is the median
//! of the 41 per-round ratios wide / baseline, with each side's median ns.
//!
//! ```sh
//! cargo run --release -p models --example isa_ab          # all three robots
//! cargo run --release -p models --example isa_ab -- panda # one
//! ```

use dynamics_runtime::isa;
use models::anchors::{Panda, Ur5};
use models::quadruped::Quadruped;

#[path = "support/paired.rs"]
mod paired;

/// Times `f` over `states` with the baseline and the wide copies; prints one line.
fn both_copies<S, R>(name: &str, states: &[S], f: impl Fn(&S) -> R) {
    let [baseline, wide, ratio] = paired::copies(states, f);
    println!("{name:<28} {baseline:>9.1} {wide:>9.1} {ratio:>10.3}");
}

fn main() {
    if !isa::choose(true) {
        eprintln!("isa_ab: this CPU lacks AVX2 or FMA, so only the baseline copies can run");
        std::process::exit(1);
    }
    let only = std::env::args().nth(1).unwrap_or_default();
    if !["", "ur5", "panda", "quadruped"].contains(&only.to_ascii_lowercase().as_str()) {
        eprintln!("isa_ab: unknown robot {only:?}; give ur5, panda, quadruped or nothing");
        std::process::exit(2);
    }
    let wanted = |robot: &str| only.is_empty() || only.eq_ignore_ascii_case(robot);
    println!(
        "{:<28} {:>9} {:>9} {:>10}",
        "function", "base ns", "wide ns", "wide/base"
    );
    if wanted("ur5") {
        let s = paired::states::<6, 6>(None);
        both_copies("UR5 inverse_dynamics", &s, |(q, v, a)| {
            Ur5::inverse_dynamics(q, v, a)
        });
        both_copies("UR5 mass_matrix", &s, |(q, _, _)| Ur5::mass_matrix(q));
        both_copies("UR5 gravity", &s, |(q, _, _)| Ur5::gravity(q));
        both_copies("UR5 forward_dynamics", &s, |(q, v, t)| {
            Ur5::forward_dynamics(q, v, t)
        });
        both_copies("UR5 coriolis_matrix", &s, |(q, v, _)| {
            Ur5::coriolis_matrix(q, v)
        });
    }
    if wanted("panda") {
        let s = paired::states::<7, 7>(None);
        both_copies("Panda inverse_dynamics", &s, |(q, v, a)| {
            Panda::inverse_dynamics(q, v, a)
        });
        both_copies("Panda mass_matrix", &s, |(q, _, _)| Panda::mass_matrix(q));
        both_copies("Panda gravity", &s, |(q, _, _)| Panda::gravity(q));
        both_copies("Panda forward_dynamics", &s, |(q, v, t)| {
            Panda::forward_dynamics(q, v, t)
        });
        both_copies("Panda coriolis_matrix", &s, |(q, v, _)| {
            Panda::coriolis_matrix(q, v)
        });
    }
    if wanted("quadruped") {
        let s = paired::states::<19, 18>(None);
        let loads = [0.0; 12];
        both_copies("quadruped inverse_dynamics", &s, |(q, v, a)| {
            Quadruped::inverse_dynamics(q, v, a, &loads)
        });
        both_copies("quadruped mass_matrix", &s, |(q, _, _)| {
            Quadruped::mass_matrix(q)
        });
        both_copies("quadruped gravity", &s, |(q, _, _)| Quadruped::gravity(q));
        both_copies("quadruped forward_dynamics", &s, |(q, v, t)| {
            Quadruped::forward_dynamics(q, v, t, &loads)
        });
        both_copies("quadruped coriolis_matrix", &s, |(q, v, _)| {
            Quadruped::coriolis_matrix(q, v)
        });
    }
}
