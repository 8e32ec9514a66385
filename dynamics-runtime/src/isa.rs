//! Which instruction set a generated kernel runs on, chosen at run time.
//!
//! Contract: each generated function (or each piece of a split one) is a straight-line
//! kernel instantiated twice, `WIDE = true` and `WIDE = false`. The runtime calls the wide copy,
//! compiled here for AVX2 and FMA, when the CPU has both (std's `cpuid` detection, done
//! once) and `DYNAMICS_ISA` is not `baseline`; otherwise it calls the baseline copy,
//! compiled for whatever the crate targets (SSE2 on baseline x86-64). On other
//! architectures the baseline copy always runs.
//!
//! The wide copy fuses each product into its sum (`a·b + c` with one rounding instead of
//! two) and takes sines and cosines four angles at a time with a fused polynomial, so
//! its results differ from the baseline copy's in the last bits (both stay within the
//! accuracy the tests state). `DYNAMICS_ISA=baseline` in the environment, read once per
//! process, pins every kernel to the baseline copy: bit-identical results on every
//! x86-64 machine. Any other value, or none, means "the widest the CPU has".
//!
//! The choice is a relaxed load of one byte and a branch that never changes within a
//! process (perfectly predicted); it depends on the CPU, never on data. It is made at the
//! first call of [`wide()`] (or of any generated function), which reads the environment and
//! so allocates once: a real-time program calls [`wide()`] during its start-up, before its
//! loop (as `models/examples/control_loop.rs` does).
//!
//! # Without std
//!
//! Built without the `std` feature there is no run-time feature detection (and no
//! environment to read): every kernel runs its baseline copy, compiled for whatever the
//! crate targets (with `-C target-feature=+fma` that copy fuses its products too, see
//! [`crate::Scalar::mul_add`]), [`wide()`] is always false, [`choose`] grants nothing, and
//! this module has no `unsafe`. The wide copies are never called, so never instantiated.

#![cfg_attr(feature = "std", allow(unsafe_code))] // one call of a `#[target_feature]` function; proof at the call

#[cfg(feature = "std")]
use std::sync::atomic::{AtomicU8, Ordering};

#[cfg(feature = "std")]
/// Not decided yet.
const UNKNOWN: u8 = 0;
#[cfg(feature = "std")]
/// The baseline copies run.
const BASELINE: u8 = 1;
#[cfg(feature = "std")]
/// The AVX2 + FMA copies run.
const WIDE: u8 = 2;

#[cfg(feature = "std")]
static CHOICE: AtomicU8 = AtomicU8::new(UNKNOWN);

/// Whether the wide (AVX2 + FMA) kernels run in this process: the CPU has both features
/// and `DYNAMICS_ISA` is not `baseline`. Decided at the first call and fixed after it.
/// Always false without the `std` feature.
#[cfg(feature = "std")]
#[inline]
#[must_use]
pub fn wide() -> bool {
    match CHOICE.load(Ordering::Relaxed) {
        WIDE => true,
        BASELINE => false,
        _ => decide(),
    }
}

/// Asks for the wide kernels (`true`) or the baseline ones (`false`) from now on in this
/// process, overriding `DYNAMICS_ISA`: to compare the two in one program, or to pin a
/// program to bit-identical results on every machine. The wide kernels are granted only
/// on a CPU with AVX2 and FMA (never without the `std` feature). Returns whether they run
/// now.
#[cfg(feature = "std")]
pub fn choose(wide: bool) -> bool {
    let granted = wide && cpu_has_avx2_fma();
    CHOICE.store(if granted { WIDE } else { BASELINE }, Ordering::Relaxed);
    granted
}

/// Detects the features and reads `DYNAMICS_ISA`. Threads racing here store the same
/// answer.
#[cfg(feature = "std")]
#[cold]
#[inline(never)]
fn decide() -> bool {
    let pinned = std::env::var_os("DYNAMICS_ISA").is_some_and(|v| v == "baseline");
    let wide = !pinned && cpu_has_avx2_fma();
    CHOICE.store(if wide { WIDE } else { BASELINE }, Ordering::Relaxed);
    wide
}

#[cfg(all(target_arch = "x86_64", feature = "std"))]
fn cpu_has_avx2_fma() -> bool {
    std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma")
}

#[cfg(all(not(target_arch = "x86_64"), feature = "std"))]
fn cpu_has_avx2_fma() -> bool {
    false
}

/// Without std: the baseline copies always run (module documentation).
#[cfg(not(feature = "std"))]
#[inline(always)]
#[must_use]
pub fn wide() -> bool {
    false
}

/// Without std there is nothing to choose: the baseline copies run, and this returns false.
#[cfg(not(feature = "std"))]
pub fn choose(wide: bool) -> bool {
    let _ = wide;
    false
}

/// Runs a whole generated function: `wide()` when [`wide()`] says so, `narrow()` otherwise,
/// inlined into the caller.
#[inline(always)]
pub(crate) fn run<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
    #[cfg(all(target_arch = "x86_64", feature = "std"))]
    if self::wide() {
        // SAFETY: `avx2_fma` is compiled for AVX2 and FMA, and `self::wide()` returns true
        // only when `CHOICE` holds `WIDE`, which `decide` and `choose`, the only places
        // that store it, do only after std's `is_x86_feature_detected!` found both
        // features on this CPU. `avx2_fma` requires nothing else.
        return unsafe { avx2_fma(wide) };
    }
    let _ = wide;
    narrow()
}

/// Runs one piece of a split function like [`run`], but keeps the baseline copy out of
/// line too, so that the pieces stay separate functions either way.
#[inline(always)]
pub(crate) fn run_piece<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
    run(wide, || out_of_line(narrow))
}

/// `f()` compiled for AVX2 and FMA: the closures the generated code passes are
/// `#[inline(always)]`, so their kernels are inlined here and compiled with these features.
///
/// # Safety
/// The CPU must have AVX2 and FMA.
#[cfg(all(target_arch = "x86_64", feature = "std"))]
#[target_feature(enable = "avx2,fma")]
unsafe fn avx2_fma<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// `f()` as a function of its own.
#[inline(never)]
pub(crate) fn out_of_line<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(all(test, feature = "std"))]
mod tests {
    /// The wide copy runs exactly when the CPU has AVX2 and FMA and `DYNAMICS_ISA` is not
    /// `baseline` (CI's second pass sets it); `choose` then switches both ways, but grants
    /// the wide kernels only with the features. One test, because the choice is global.
    #[test]
    fn the_choice_follows_the_cpu_the_environment_and_choose() {
        let pinned = std::env::var_os("DYNAMICS_ISA").is_some_and(|v| v == "baseline");
        let automatic = !pinned && super::cpu_has_avx2_fma();
        assert_eq!(super::wide(), automatic);
        assert_eq!(super::run(|| 1, || 2) == 1, automatic);
        assert_eq!(super::run_piece(|| 1, || 2) == 1, automatic);

        assert!(!super::choose(false));
        assert_eq!(super::run(|| 1, || 2), 2);
        assert_eq!(super::run_piece(|| 1, || 2), 2);
        let granted = super::choose(true);
        assert_eq!(granted, super::cpu_has_avx2_fma());
        assert_eq!(super::run(|| 1, || 2) == 1, granted);
        super::choose(automatic);
    }
}

#[cfg(all(test, not(feature = "std")))]
mod tests_without_std {
    /// Without std the baseline copy always runs, and nothing can ask for the other.
    #[test]
    fn the_baseline_copy_always_runs() {
        assert!(!super::wide());
        assert_eq!(super::run(|| 1, || 2), 2);
        assert_eq!(super::run_piece(|| 1, || 2), 2);
        assert!(!super::choose(true));
        assert!(!super::wide());
    }
}
