//! SIMD lanes as a [`Scalar`]: [`F64x4`] (four `f64`) and [`F32x8`] (eight `f32`), so that
//! every generated function evaluates four or eight states per call.
//!
//! # Contract
//!
//! Lane `i` of a result is what the scalar type computes from lane `i` of the arguments:
//!
//! - `+`, `−`, `×`, `÷`, `sqrt` and negation: bit for bit the `f64` (`f32`) operation,
//!   IEEE-754 with rounding to nearest (NaN payloads aside).
//! - [`Scalar::mul_add`]: as the scalar type's, two roundings, fused (one rounding) only
//!   when the crate is built for FMA (`-C target-cpu=native`, `-C target-feature=+fma`).
//! - `sin`, `cos` and `sin_cos` of [`F64x4`]: bit for bit the runtime's own
//!   `fast_trig::sin_cos` on each lane; within 1 ulp of std's `f64::sin_cos` for
//!   |x| ≤ 1.6·10⁶ (tested in `fast_trig`, and here on 1.5 million points). [`F32x8`]: the
//!   same kernel on the lanes widened to `f64`, rounded to `f32`: within 1 ulp of std's
//!   `f32::sin_cos` (tested here on 4 million points: 2.6 to 4.2 % of them differ, and at
//!   every point tested the lanes' value is std's `f64` one rounded to `f32`, std's `f32` one
//!   in 96 to 97 %). Both: NaN for |x| ≥ 2⁵⁰, ±∞ and NaN, and `sin(−0) = +0`.
//! - Generated code on [`F64x4`], in a build without AVX (the default x86-64 target): the
//!   lanes take `f64`'s choice of kernel copy ([`crate::isa`]), its fused multiply-adds in
//!   the AVX2 + FMA copy and its batched sines and cosines: each lane is the `f64` call on
//!   that lane's state, bit for bit, in either copy (`tests/lanes.rs`, both copies). On
//!   [`F32x8`], and on [`F64x4`] built with AVX, the generated code runs its baseline copy
//!   ([`Scalar::run_kernel`]'s default): each lane is then the scalar call with the scalar
//!   pinned to its baseline copy ([`crate::isa::choose`]`(false)` or
//!   `DYNAMICS_ISA=baseline`), bit for bit for [`F64x4`], with sines and cosines within an
//!   ulp for [`F32x8`].
//! - Equality (`==`, required of a [`Scalar`]) holds when every lane is equal; nothing else
//!   compares or branches on data.
//!
//! # Backing
//!
//! [`F64x4`] in a build without AVX (`lanes/dispatched.rs`) is four `f64` in an array, each
//! operation written lane by lane, every generated kernel run in the copy `f64` runs: the
//! compiler turns each operation's lanes into one instruction, one AVX register in the
//! AVX2 + FMA copy, two SSE2 registers in the baseline one. Two things are written for AVX
//! instead of left to the compiler: the fused products of the wide copy (one `vfmadd`,
//! sound because the kernel holds the `Isa<true>` that only [`crate::isa`] makes, after
//! detecting AVX2 and FMA) and the sines and cosines (one AVX register per [`F64x4`]).
//! [`F32x8`], and [`F64x4`] in a build with AVX (`-C target-cpu=native` on an AVX CPU),
//! are `wide::f32x8` and `wide::f64x4` in a newtype (`lanes/wide_backed.rs`). `wide` was already in the
//! dependency graph (nalgebra → simba → wide 1.7, the version locked), is maintained, and
//! gives safe, lane-wise IEEE operations on SSE2, AVX, NEON and WebAssembly SIMD with a
//! portable fallback, chosen at compile time: this module has no `unsafe`. Its cost: it
//! picks its instructions from the crate's compile-time target, so in a baseline x86-64
//! build a `wide` vector is SSE2 registers even inside the AVX2 copy of a kernel, which is
//! why [`F64x4`] there is an array instead. [`F32x8`] as an array of eight in the AVX2 copy
//! was tried (BENCHMARKS.md, "Many states per call"): the quadruped's inverse dynamics 1.8×
//! faster, but its mass matrix and forward dynamics 1.5× slower, so it stays on `wide`.
//! (`std::simd` is not stable.)
//!
//! # Speed (BENCHMARKS.md, "Many states per call")
//!
//! In the default build, on states already in lanes, [`F64x4`] evaluates the UR5's and
//! the 18-dof quadruped's inverse and forward dynamics 2.4 to 3.0× faster per state than
//! the `f64` call, their mass matrices 1.9 to 2.2×; through the batch helpers, whose
//! packing and unpacking take the rest, 1.9 to 2.4× and 1.4 to 1.9× (49ca3da). The mass
//! matrices gain least because the `f64` call is already partly four-wide. Its AVX2 copy
//! takes its sines and cosines four angles at a time, so the lanes, four states at a time,
//! save nothing on them: the quadruped's 12 angles took 33 ns a state either way (before
//! the kernel's products were all fused, 49ca3da, which cut it by a quarter), a quarter of
//! its mass matrix, which bounds that function's gain at 2.3×. And LLVM's SLP vectorizer
//! packs much of the rest (the quadruped's: 294 of its 735 arithmetic instructions work on
//! four numbers). Returned by value, the lanes' kernel also keeps its 324 results of 32
//! bytes until it returns them (1,117 of its 2,689 instructions address the stack, against
//! 540 of 1,886); its `_into` twin does not. Built with
//! `-C target-cpu=native` (AVX), 2.2 to 2.9× for inverse and forward dynamics, 1.4× for
//! the mass matrices. [`F32x8`] stays on `wide` (see "Backing").

use crate::Scalar;

#[cfg(not(target_feature = "avx"))]
mod dispatched;
#[cfg(not(target_feature = "avx"))]
pub use dispatched::F64x4;

mod wide_backed;
pub use wide_backed::F32x8;
#[cfg(target_feature = "avx")]
pub use wide_backed::F64x4;

/// A SIMD vector of lanes that is itself a [`Scalar`]: [`F64x4`] and [`F32x8`]. What the
/// batch helpers of [`crate::batch`] pack states into.
pub trait Lanes: Scalar {
    /// The number in each lane.
    type Element: Scalar;
    /// The number of lanes.
    const LANES: usize;
    /// Every lane `x`.
    fn splat(x: Self::Element) -> Self;
    /// Lane `i` is `f(i)`, for `i` = 0, 1, …, `LANES − 1`, called in that order.
    fn from_fn(f: impl FnMut(usize) -> Self::Element) -> Self;
    /// Lane `i`, or `None` when `i ≥ LANES`.
    fn get(self, i: usize) -> Option<Self::Element>;
    /// Lanes 0 to 3 (0 for a lane past [`Lanes::LANES`]): what the batch helpers' 4 × 4
    /// transposes read of each pack. [`F64x4`] of the default build (no AVX at compile
    /// time, `lanes/dispatched.rs`) overrides it with its whole array, which
    /// the compiler then loads as one vector from where the pack was stored; lane by lane,
    /// LLVM merged the sixteen reads of a transpose into loads across the halves of the
    /// packs just stored (a profile of the UR5's inverse dynamics through `batch::map3`
    /// put a quarter of the helper's time on three of them).
    #[inline(always)]
    fn first4(self) -> [Self::Element; 4] {
        core::array::from_fn(|l| {
            self.get(l)
                .unwrap_or_else(|| <Self::Element as Scalar>::from_f64(0.0))
        })
    }
}

#[cfg(test)]
mod tests;
