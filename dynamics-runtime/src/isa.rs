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
//! # The AVX-512 copy (feature `avx512`)
//!
//! With the runtime's feature `avx512` (off by default), the wide copy is compiled a second
//! time with AVX-512F and AVX-512VL on top of AVX2 and FMA, and runs where the CPU has
//! them (AMD Zen 4 and later, Intel's server parts): the same operations on the same
//! 256-bit vectors, but 32 vector registers instead of 16, so long kernels keep more of
//! their values in registers. Each operation is the same IEEE operation, so its results
//! are those of the AVX2 copy, bit for bit (tested). It costs a third compiled copy of
//! every generated function that runs, hence opt-in. `DYNAMICS_ISA=avx2` (or
//! [`choose_avx512`]`(false)`) keeps the AVX2 copy on such a CPU.
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
/// The AVX2 + FMA copies run, compiled with AVX-512F/VL too (feature `avx512`).
const WIDE_512: u8 = 3;

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
        WIDE | WIDE_512 => true,
        BASELINE => false,
        _ => decide(),
    }
}

/// Whether the wide kernels run in their AVX-512 copy ([the module's section](self#the-avx-512-copy-feature-avx512)):
/// the feature `avx512` is on, the CPU has AVX-512F and AVX-512VL besides AVX2 and FMA,
/// and neither `DYNAMICS_ISA` nor [`choose`] or [`choose_avx512`] asked otherwise.
#[cfg(feature = "std")]
#[inline]
#[must_use]
pub fn avx512() -> bool {
    wide() && CHOICE.load(Ordering::Relaxed) == WIDE_512
}

/// Asks for the wide kernels (`true`) or the baseline ones (`false`) from now on in this
/// process, overriding `DYNAMICS_ISA`: to compare the two in one program, or to pin a
/// program to bit-identical results on every machine. The wide kernels are granted only
/// on a CPU with AVX2 and FMA (never without the `std` feature). Returns whether they run
/// now.
#[cfg(feature = "std")]
pub fn choose(wide: bool) -> bool {
    let granted = wide && cpu_has_avx2_fma();
    CHOICE.store(widest(granted), Ordering::Relaxed);
    granted
}

/// With the wide kernels granted, asks for their AVX-512 copy (`true`) or their AVX2 one
/// (`false`) from now on in this process: to compare the two in one program. Granted only
/// with the feature `avx512` on a CPU that has AVX-512F and AVX-512VL; returns whether the
/// AVX-512 copy runs now. Leaves a process pinned to the baseline copies as it is.
#[cfg(feature = "std")]
pub fn choose_avx512(on: bool) -> bool {
    if !wide() {
        return false;
    }
    let granted = on && cpu_has_avx512();
    CHOICE.store(if granted { WIDE_512 } else { WIDE }, Ordering::Relaxed);
    granted
}

/// The choice to store when the wide copies are (or are not) `granted`: their AVX-512
/// copy where the feature and the CPU allow it.
#[cfg(feature = "std")]
fn widest(granted: bool) -> u8 {
    match (granted, cpu_has_avx512()) {
        (false, _) => BASELINE,
        (true, false) => WIDE,
        (true, true) => WIDE_512,
    }
}

/// Detects the features and reads `DYNAMICS_ISA`. Threads racing here store the same
/// answer.
#[cfg(feature = "std")]
#[cold]
#[inline(never)]
fn decide() -> bool {
    let asked = std::env::var_os("DYNAMICS_ISA");
    let pinned = asked.as_ref().is_some_and(|v| v == "baseline");
    let wide = !pinned && cpu_has_avx2_fma();
    let choice = match widest(wide) {
        WIDE_512 if asked.is_some_and(|v| v == "avx2") => WIDE,
        choice => choice,
    };
    CHOICE.store(choice, Ordering::Relaxed);
    wide
}

/// Whether the wide kernels may run in their AVX-512 copy: the feature `avx512` and a CPU
/// with AVX-512F and AVX-512VL (beside AVX2 and FMA, checked by the caller).
#[cfg(all(target_arch = "x86_64", feature = "avx512"))]
fn cpu_has_avx512() -> bool {
    std::arch::is_x86_feature_detected!("avx512f")
        && std::arch::is_x86_feature_detected!("avx512vl")
}

#[cfg(all(feature = "std", not(all(target_arch = "x86_64", feature = "avx512"))))]
fn cpu_has_avx512() -> bool {
    false
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

/// Which copy of a generated kernel is running, as a value the kernel is handed by
/// [`crate::Scalar::run_kernel`] (and `run_piece`) and passes to its fused products
/// ([`Isa::mul_add`]).
///
/// `Isa<false>` is the baseline copy's ([`Isa::BASELINE`], anyone may make it).
/// `Isa<true>` is the wide copy's, and only this module makes one: in `isa::run`, after
/// [`wide()`] said yes, that is after std's run-time detection found AVX2 and FMA on this
/// CPU. Holding an `Isa<true>` therefore proves the CPU has both, which lets a lane type
/// ([`crate::F64x4`]) issue AVX2 + FMA instructions in the wide copy without a check per
/// operation. It has no public constructor, no `Default`, and its field is private;
/// copying one that exists proves nothing new. Without the `std` feature none is ever made.
///
/// ```compile_fail,E0451
/// // Outside the runtime the wide copy's value cannot be made: its field is private.
/// let proof = dynamics_runtime::isa::Isa::<true> { _proof: () };
/// ```
///
/// ```
/// // The baseline copy's value is anyone's; its products are the scalar type's `mul_add`.
/// use dynamics_runtime::isa::Isa;
/// assert_eq!(Isa::BASELINE.mul_add(2.0_f64, 3.0, 1.0), 7.0);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct Isa<const WIDE: bool> {
    _proof: (),
}

impl Isa<false> {
    /// The baseline copy's value.
    pub const BASELINE: Self = Self { _proof: () };
}

impl<const WIDE: bool> Isa<WIDE> {
    /// `a · b + c` as this copy computes it ([`crate::Scalar::mul_add_on`]): two roundings
    /// in the baseline copy (unless the build targets FMA), one fused instruction in the
    /// wide copy of `f32`, `f64` and [`crate::F64x4`]. Generated code writes every product
    /// that only one sum or difference uses this way.
    ///
    /// `#[inline]`, not `#[inline(always)]`: in an unoptimised build each call then keeps
    /// its temporaries in its own frame, where always-inlined into a kernel of a thousand
    /// products they made the frame of the quadruped's `F64x4` kernels outgrow a 2 MB
    /// test thread. Optimised, it is inlined like any function of its size.
    #[inline]
    #[must_use]
    pub fn mul_add<T: crate::Scalar>(self, a: T, b: T, c: T) -> T {
        a.mul_add_on(b, c, self)
    }

    /// The proof that this CPU has AVX2 and FMA, when this is the wide copy's value.
    #[cfg(all(target_arch = "x86_64", feature = "std"))]
    #[inline(always)]
    pub(crate) fn avx2_fma(self) -> Option<Avx2Fma> {
        // An `Isa<true>` exists only where `run` made it (see the type's documentation).
        WIDE.then_some(Avx2Fma { _proof: () })
    }
}

/// Proof that this CPU has AVX2 and FMA: made only from an `Isa<true>`
/// ([`Isa::avx2_fma`]), itself made only after the run-time detection found both. Code
/// holding one may call AVX2 and FMA intrinsics (`crate::lanes`' `F64x4` does).
#[cfg(all(target_arch = "x86_64", feature = "std"))]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2Fma {
    _proof: (),
}

/// Runs a whole generated function: `wide` when [`wide()`] says so, `narrow` otherwise,
/// each handed its copy's [`Isa`], inlined into the caller.
#[inline(always)]
pub(crate) fn run<R>(wide: impl FnOnce(Isa<true>) -> R, narrow: impl FnOnce(Isa<false>) -> R) -> R {
    run_with(
        (),
        #[inline(always)]
        |isa, ()| wide(isa),
        #[inline(always)]
        |isa, ()| narrow(isa),
    )
}

/// [`run`] handing `arg` to the copy that runs (a generated `_into` function's `&mut`
/// output, which two closures could not both hold).
#[inline(always)]
pub(crate) fn run_with<A, R>(
    arg: A,
    wide: impl FnOnce(Isa<true>, A) -> R,
    narrow: impl FnOnce(Isa<false>, A) -> R,
) -> R {
    run_with_in::<A, R, true>(arg, wide, narrow)
}

/// [`run_with`], the wide copy's AVX-512 build allowed or not (`AVX512`).
#[inline(always)]
fn run_with_in<A, R, const AVX512: bool>(
    arg: A,
    wide: impl FnOnce(Isa<true>, A) -> R,
    narrow: impl FnOnce(Isa<false>, A) -> R,
) -> R {
    #[cfg(all(target_arch = "x86_64", feature = "std"))]
    if self::wide() {
        // The only place an `Isa<true>` is made: `self::wide()` returned true, see below.
        let proof = Isa::<true> { _proof: () };
        #[cfg(feature = "avx512")]
        if AVX512 && CHOICE.load(Ordering::Relaxed) == WIDE_512 {
            // SAFETY: `avx2_fma_avx512` is compiled for AVX2, FMA, AVX-512F and AVX-512VL;
            // `CHOICE` holds `WIDE_512` only where `widest` or `choose_avx512` stored it,
            // after `cpu_has_avx2_fma` and `cpu_has_avx512` (std's
            // `is_x86_feature_detected!`) found all four on this CPU.
            return unsafe {
                avx2_fma_avx512(
                    #[inline(always)]
                    || wide(proof, arg),
                )
            };
        }
        // SAFETY: `avx2_fma` is compiled for AVX2 and FMA, and `self::wide()` returns true
        // only when `CHOICE` holds `WIDE` or `WIDE_512`, which `decide`, `choose` and
        // `choose_avx512`, the only places that store them, do only after std's
        // `is_x86_feature_detected!` found both features on this CPU. `avx2_fma` requires
        // nothing else.
        return unsafe {
            avx2_fma(
                #[inline(always)]
                || wide(proof, arg),
            )
        };
    }
    let _ = wide;
    narrow(Isa::BASELINE, arg)
}

/// [`run_piece`] handing `arg` to the copy that runs, as [`run_with`].
#[inline(always)]
pub(crate) fn run_piece_with<A, R>(
    arg: A,
    wide: impl FnOnce(Isa<true>, A) -> R,
    narrow: impl FnOnce(Isa<false>, A) -> R,
) -> R {
    run_with(
        arg,
        wide,
        #[inline(always)]
        |isa, arg| out_of_line(|| narrow(isa, arg)),
    )
}

/// Runs one piece of a split function like [`run`], but keeps the baseline copy out of
/// line too, so that the pieces stay separate functions either way.
#[inline(always)]
pub(crate) fn run_piece<R>(
    wide: impl FnOnce(Isa<true>) -> R,
    narrow: impl FnOnce(Isa<false>) -> R,
) -> R {
    run(
        wide,
        #[inline(always)]
        |isa| out_of_line(|| narrow(isa)),
    )
}

/// Runs a loop that calls generated functions (the batch helpers' packing, calls and
/// unpacking) in the copy [`run`] would choose: compiled for AVX2 and FMA when [`wide()`]
/// says so, so that the packing and unpacking around the calls move whole AVX registers
/// (the quadruped's inverse dynamics through `batch::map4`: 0.76 to 0.81 of the time).
/// The loop only moves numbers, and each generated function it calls still runs the copy
/// it chooses itself, with that copy's operations: the results are the same either way.
///
/// Never in the AVX-512 build of the wide copy (feature `avx512`): the loop gains nothing
/// from more registers, and the `F32x8` kernels, which run their baseline code inlined into
/// it, took 1.3 to 1.4× their time there (lanes benchmark, 2026-11-29); the `F64x4`
/// kernels it calls still choose that build themselves.
#[inline(always)]
pub(crate) fn run_loop<R>(f: impl FnOnce() -> R) -> R {
    // `f` is the argument handed on, so that one closure can own it in either copy.
    run_with_in::<_, _, false>(
        f,
        #[inline(always)]
        |_, f| f(),
        #[inline(always)]
        |_, f| f(),
    )
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

/// `f()` compiled for AVX2, FMA, AVX-512F and AVX-512VL (feature `avx512`): the wide copy
/// with 32 vector registers.
///
/// # Safety
/// The CPU must have AVX2, FMA, AVX-512F and AVX-512VL.
#[cfg(all(target_arch = "x86_64", feature = "avx512"))]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
unsafe fn avx2_fma_avx512<R>(f: impl FnOnce() -> R) -> R {
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
        assert_eq!(super::run(|_| 1, |_| 2) == 1, automatic);
        assert_eq!(super::run_piece(|_| 1, |_| 2) == 1, automatic);

        assert!(!super::choose(false));
        assert_eq!(super::run(|_| 1, |_| 2), 2);
        assert_eq!(super::run_piece(|_| 1, |_| 2), 2);
        let granted = super::choose(true);
        assert_eq!(granted, super::cpu_has_avx2_fma());
        assert_eq!(super::run(|_| 1, |_| 2) == 1, granted);
        // The AVX-512 copy (feature `avx512`): granted only with the wide kernels, on a CPU
        // that has it; switched off and on without leaving the wide kernels.
        let with_512 = granted && super::cpu_has_avx512();
        assert_eq!(super::avx512(), with_512);
        assert!(!super::choose_avx512(false));
        assert!(super::wide() == granted && !super::avx512());
        assert_eq!(super::choose_avx512(true), with_512);
        assert_eq!(super::run(|_| 1, |_| 2) == 1, granted);
        super::choose(false);
        assert!(!super::choose_avx512(true) && !super::wide());
        super::choose(automatic);
    }
}

#[cfg(all(test, not(feature = "std")))]
mod tests_without_std {
    /// Without std the baseline copy always runs, and nothing can ask for the other.
    #[test]
    fn the_baseline_copy_always_runs() {
        assert!(!super::wide());
        assert_eq!(super::run(|_| 1, |_| 2), 2);
        assert_eq!(super::run_piece(|_| 1, |_| 2), 2);
        assert!(!super::choose(true));
        assert!(!super::wide());
    }
}
