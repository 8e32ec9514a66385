//! A bare-metal program around the arm: `no_std`, `no_main`, its own panic handler and entry
//! point, linked for a Cortex-M4F. Built (not run) by CI to prove that the generated f32
//! dynamics link with no std, no allocator and no C library:
//!
//! ```sh
//! cargo build -p dynamics-embedded-example --example firmware --features firmware \
//!     --target thumbv7em-none-eabihf --release
//! ```
//!
//! Contract: links for `thumbv7em-none-eabihf` with the target's default linker (rust-lld)
//! and no linker script; the entry point runs the control loop forever. It needs the
//! `firmware` feature, so that host builds (`cargo test`, which links examples) skip it.

#![no_std]
#![no_main]

use core::hint::black_box;
use dynamics_embedded_example::{control_tick, simulate_step, Gains, Target, NV};

/// The entry point a reset handler would call: a computed-torque loop on the simulated arm.
// SAFETY (`no_mangle` is unsafe because two definitions of one symbol are undefined
// behaviour at link time): `_start` is defined once in this link. The program links
// `core`, `compiler_builtins` and the crates of this workspace's graph for a target with no
// C runtime (no crt0) and no std, and none of them defines `_start`; a second definition
// would in any case be a duplicate-symbol error of rust-lld, not a silent choice.
#[allow(unsafe_code)]
#[no_mangle]
pub extern "C" fn _start() -> ! {
    let gains = Gains {
        kp: [100.0; NV],
        kd: [20.0; NV],
    };
    let target = black_box(Target {
        q: [0.8, -0.6, 1.2],
        v: [0.0; NV],
        a: [0.0; NV],
    });
    let (mut q, mut v) = ([0.0_f32; NV], [0.0_f32; NV]);
    loop {
        let tick = control_tick(&q, &v, &target, &gains);
        let next = simulate_step(&q, &v, &tick.tau, 1e-3);
        (q, v) = black_box((next.q, next.v));
    }
}

/// Stops on a panic (the generated code has none; slice indexing in the runtime could).
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
