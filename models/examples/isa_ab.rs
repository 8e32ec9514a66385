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
use std::hint::black_box;
use std::time::Instant;

const ROUNDS: usize = 41;
const CALLS: usize = 20_000;

/// Times `f` over `states` with the baseline and the wide copies; prints one line.
fn paired<S, R>(name: &str, states: &[S], f: impl Fn(&S) -> R) {
    let (mut baseline, mut wide, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..ROUNDS {
        let mut ns = [0.0; 2];
        for k in 0..2 {
            let side = if round % 2 == 0 { k } else { 1 - k };
            isa::choose(side == 1);
            let start = Instant::now();
            for c in 0..CALLS {
                black_box(f(black_box(&states[c % states.len()])));
            }
            ns[side] = start.elapsed().as_nanos() as f64 / CALLS as f64;
        }
        baseline.push(ns[0]);
        wide.push(ns[1]);
        ratio.push(ns[1] / ns[0]);
    }
    println!(
        "{name:<28} {:>9.1} {:>9.1} {:>10.3}",
        median(baseline),
        median(wide),
        median(ratio)
    );
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// 20 states of uniform numbers in [−2, 2) (a fixed xorshift stream); the quadruped's
/// foot loads zero, as in the comparison with Pinocchio.
fn states<const NQ: usize, const NV: usize>() -> Vec<([f64; NQ], [f64; NV], [f64; NV])> {
    let mut s = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
    };
    (0..20)
        .map(|_| {
            let q = std::array::from_fn(|_| next());
            let v = std::array::from_fn(|_| next());
            (q, v, std::array::from_fn(|_| next()))
        })
        .collect()
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
        let s = states::<6, 6>();
        paired("UR5 inverse_dynamics", &s, |(q, v, a)| {
            Ur5::inverse_dynamics(q, v, a)
        });
        paired("UR5 mass_matrix", &s, |(q, _, _)| Ur5::mass_matrix(q));
        paired("UR5 gravity", &s, |(q, _, _)| Ur5::gravity(q));
        paired("UR5 forward_dynamics", &s, |(q, v, t)| {
            Ur5::forward_dynamics(q, v, t)
        });
        paired("UR5 coriolis_matrix", &s, |(q, v, _)| {
            Ur5::coriolis_matrix(q, v)
        });
    }
    if wanted("panda") {
        let s = states::<7, 7>();
        paired("Panda inverse_dynamics", &s, |(q, v, a)| {
            Panda::inverse_dynamics(q, v, a)
        });
        paired("Panda mass_matrix", &s, |(q, _, _)| Panda::mass_matrix(q));
        paired("Panda gravity", &s, |(q, _, _)| Panda::gravity(q));
        paired("Panda forward_dynamics", &s, |(q, v, t)| {
            Panda::forward_dynamics(q, v, t)
        });
        paired("Panda coriolis_matrix", &s, |(q, v, _)| {
            Panda::coriolis_matrix(q, v)
        });
    }
    if wanted("quadruped") {
        let s = states::<19, 18>();
        let loads = [0.0; 12];
        paired("quadruped inverse_dynamics", &s, |(q, v, a)| {
            Quadruped::inverse_dynamics(q, v, a, &loads)
        });
        paired("quadruped mass_matrix", &s, |(q, _, _)| {
            Quadruped::mass_matrix(q)
        });
        paired("quadruped gravity", &s, |(q, _, _)| Quadruped::gravity(q));
        paired("quadruped forward_dynamics", &s, |(q, v, t)| {
            Quadruped::forward_dynamics(q, v, t, &loads)
        });
        paired("quadruped coriolis_matrix", &s, |(q, v, _)| {
            Quadruped::coriolis_matrix(q, v)
        });
    }
}
