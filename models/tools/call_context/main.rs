//! The Panda's generated functions timed called back to back, and each call preceded by a
//! `rep stosb` of 256 or 3000 bytes to a scratch buffer (see `../call_context.sh`). Each
//! figure is the median of 15 rounds of 10 000 calls over the 20 states of
//! `models/examples/support/paired.rs`.

#![allow(dead_code)] // the generated file holds more than the harness times

mod paired;

mod generated {
    include!("generated.rs");
}
use generated::Panda;
use std::hint::black_box;
use std::time::Instant;

/// The scratch buffer both kinds of stores write (u64 elements: 8-byte aligned).
static mut SCRATCH: [u64; 512] = [0; 512];

/// The same bytes written by ordinary 8-byte stores, the control.
#[inline(never)]
fn plain_store(bytes: usize) {
    let scratch = core::ptr::addr_of_mut!(SCRATCH).cast::<u64>();
    for i in 0..bytes.min(4096) / 8 {
        // SAFETY: i < 512, an element of SCRATCH; the single-threaded harness is its only
        // user.
        unsafe { core::ptr::write_volatile(scratch.add(i), 0) };
    }
}

/// `rep stosb` of `bytes` zeros into [`SCRATCH`].
#[inline(never)]
fn string_store(bytes: usize) {
    let bytes = bytes.min(4096);
    // SAFETY: writes `bytes` ≤ 4096 bytes from the start of SCRATCH, which is 4096 bytes
    // long; the single-threaded harness is its only user.
    unsafe {
        core::arch::asm!(
            "rep stosb",
            inout("rdi") core::ptr::addr_of_mut!(SCRATCH).cast::<u8>() => _,
            inout("rcx") bytes => _,
            in("al") 0u8,
            options(nostack),
        );
    }
}

fn median_ns(mut call: impl FnMut(usize)) -> f64 {
    let mut rounds: Vec<f64> = (0..15)
        .map(|_| {
            let start = Instant::now();
            for k in 0..10_000 {
                call(black_box(k));
            }
            start.elapsed().as_nanos() as f64 / 10_000.0
        })
        .collect();
    rounds.sort_by(f64::total_cmp);
    rounds[7]
}

macro_rules! row {
    ($states:expr, $name:ident, |$s:ident| $call:expr) => {{
        let states = $states;
        let plain = median_ns(|k| {
            let $s = &states[k % 20];
            black_box($call);
        });
        let after = |bytes: usize| {
            median_ns(|k| {
                let $s = &states[k % 20];
                string_store(bytes);
                black_box($call);
            })
        };
        let (small, large) = (after(256), after(3000));
        let control = median_ns(|k| {
            let $s = &states[k % 20];
            plain_store(3000);
            black_box($call);
        });
        println!(
            "| {} | {plain:.1} | {small:.1} | {large:.1} | {:.2} | {control:.1} |",
            stringify!($name),
            large / plain
        );
    }};
}

fn main() {
    let _ = dynamics_runtime::isa::wide();
    let states = &paired::states::<7, 7>(None);
    println!(
        "rep stosb alone: 256 bytes {:.1} ns, 3000 bytes {:.1} ns; 3000 bytes by 8-byte stores {:.1} ns",
        median_ns(|_| string_store(256)),
        median_ns(|_| string_store(3000)),
        median_ns(|_| plain_store(3000))
    );
    println!(
        "| function | back to back ns | after rep stosb 256 B | after rep stosb 3000 B | ratio | after 3000 B of plain stores |"
    );
    println!("| --- | ---: | ---: | ---: | ---: | ---: |");
    row!(states, inverse_dynamics, |s| Panda::inverse_dynamics(
        &s.0, &s.1, &s.2
    ));
    row!(states, mass_matrix, |s| Panda::mass_matrix(&s.0));
    row!(states, coriolis_matrix, |s| Panda::coriolis_matrix(
        &s.0, &s.1
    ));
    row!(states, forward_dynamics, |s| Panda::forward_dynamics(
        &s.0, &s.1, &s.2
    ));
    row!(states, mass_matrix_inverse, |s| Panda::mass_matrix_inverse(
        &s.0
    ));
    row!(states, inverse_dynamics_derivatives, |s| {
        Panda::inverse_dynamics_derivatives(&s.0, &s.1, &s.2)
    });
    row!(states, forward_dynamics_derivatives, |s| {
        Panda::forward_dynamics_derivatives(&s.0, &s.1, &s.2)
    });
}
