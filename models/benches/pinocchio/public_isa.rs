//! The two copies of one example-robot-data robot's generated code side by side, for
//! `public.sh --isa`: the AVX2 + FMA kernels against the baseline (SSE2) ones, each output
//! in paired rounds in one process (`models/examples/support/paired.rs`, as the `isa_ab`
//! example does for the bundled robots), switching with `dynamics_runtime::isa::choose`.
//!
//! `public.sh` builds it as an example of the robot's throwaway crate
//! (`build/public/<robot>/`), whose library is the robot's declaration. The states are 20
//! seeded random ones (the free base's quaternion normalized), not Pinocchio's: only the
//! ratio of the two copies is read here. Prints one Markdown row per output: the
//! baseline copy's and the wide copy's median ns, and the median of the per-round ratios
//! wide / baseline.

use dynamics_runtime::{isa, Mechanism};
use public_robot::Robot;

#[path = "../../examples/support/paired.rs"]
mod paired;

const NQ: usize = <Robot as Mechanism>::NQ;
const NV: usize = <Robot as Mechanism>::NV;

/// Times `f` over `states` in the baseline and the wide copies; prints one row.
fn both_copies<S, R>(robot: &str, name: &str, states: &[S], f: impl Fn(&S) -> R) {
    let [baseline, wide, ratio] = paired::copies(states, f);
    println!("| {robot} | {name} | {baseline:.1} | {wide:.1} | {ratio:.3} |");
}

fn main() {
    let robot = std::env::var("PUBLIC_ROBOT").unwrap_or_else(|_| "robot".to_owned());
    if !isa::choose(true) {
        eprintln!("public_isa: this CPU lacks AVX2 or FMA, so only the baseline copies can run");
        std::process::exit(1);
    }
    // A free base adds one configuration coordinate (the quaternion's fourth number) at 3.
    let quaternion = (NQ == NV + 1).then_some(3);
    let s = paired::states::<NQ, NV>(quaternion);
    let r = robot.as_str();
    both_copies(r, "inverse_dynamics", &s, |(q, v, a)| {
        Robot::inverse_dynamics(q, v, a)
    });
    both_copies(r, "bias", &s, |(q, v, _)| Robot::bias(q, v));
    both_copies(r, "gravity", &s, |(q, _, _)| Robot::gravity(q));
    both_copies(r, "mass_matrix", &s, |(q, _, _)| Robot::mass_matrix(q));
    both_copies(r, "forward_dynamics", &s, |(q, v, t)| {
        Robot::forward_dynamics(q, v, t)
    });
    both_copies(r, "coriolis_matrix", &s, |(q, v, _)| {
        Robot::coriolis_matrix(q, v)
    });
    both_copies(r, "mass_matrix_inverse", &s, |(q, _, _)| {
        Robot::mass_matrix_inverse(q)
    });
    both_copies(r, "inverse_dynamics_derivatives", &s, |(q, v, a)| {
        Robot::inverse_dynamics_derivatives(q, v, a)
    });
    both_copies(r, "forward_dynamics_derivatives", &s, |(q, v, t)| {
        Robot::forward_dynamics_derivatives(q, v, t)
    });
}
