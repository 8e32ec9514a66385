//! [`super::sin_cos_mul_add`] on four angles per AVX register, for the generated kernels'
//! AVX2 + FMA copy ([`crate::isa`]).
//!
//! The same operations in the same order as the scalar code, one 256-bit instruction for
//! four angles each, so every lane is bit for bit `sin_cos_mul_add` of its angle (tested).
//! Written with `core::arch` rather than left to LLVM's vectorizers: on four angles the
//! loop vectorizer sees a loop it has already unrolled, and the SLP vectorizer paired the
//! sine and cosine polynomials of one angle instead of four angles, half of the code
//! scalar.
//!
//! Every product that one sum uses is fused into it (`vfmadd`, `vfnmadd`): 36
//! floating-point instructions for four angles, where the separate steps of the baseline
//! copy take 49. In a loop of independent groups (built for x86-64-v3 so that the kernel
//! inlines, 21 medians of 500,000 calls) four angles took 7.35 ns against 9.6 ns with the
//! Estrin steps alone fused (2026-11-29), within 1 ulp of std on the same 14 million points.
//!
//! Tried and not kept (2026-11-29): the quadrant's swap as two `blendv` on n's bit 0, with
//! cos's sign as sin's xor that bit, 12 integer-domain instructions instead of 17, the same
//! bits. Alone it was faster (12.1 → 11.4 ns a group, a throwaway harness), but inside the
//! generated code slower: the UR5's `f64` inverse dynamics 53.5 → 56.6 ns and the
//! quadruped's mass matrix 122 → 125 ns (medians, binaries run alternately, four rounds),
//! and cos's sign alone changed nothing measurable.

#![allow(unsafe_code)] // two transmutes between `[f64; 4]` and `__m256d`; proofs below

use super::{C, FRAC_2_PI, HUGE_BITS, PIO2_1, PIO2_2, PIO2_3, ROUND, S};
use core::arch::x86_64::{
    __m256d, _mm256_add_epi64, _mm256_add_pd, _mm256_and_si256, _mm256_castpd_si256,
    _mm256_castsi256_pd, _mm256_cmpgt_epi64, _mm256_fmadd_pd, _mm256_fnmadd_pd, _mm256_mul_pd,
    _mm256_or_si256, _mm256_set1_epi64x, _mm256_set1_pd, _mm256_slli_epi64, _mm256_sub_epi64,
    _mm256_sub_pd, _mm256_xor_si256,
};

/// Sines and cosines of N angles, four at a time, the last group padded with zeros: each
/// lane bit for bit [`super::sin_cos_mul_add`] (tested with the SSE2 batch, in
/// `fast_trig`'s `array_is_elementwise`). `None` when this CPU lacks AVX2 or FMA
/// (or [`crate::isa`] is pinned to the baseline); the generated kernels call it only from
/// their AVX2 + FMA copy, where it is always `Some`.
#[inline]
#[must_use]
pub fn sin_cos_array<const N: usize>(x: &[f64; N]) -> Option<([f64; N], [f64; N])> {
    if !crate::isa::wide() {
        return None;
    }
    let mut sin = [0.0; N];
    let mut cos = [0.0; N];
    let mut start = 0;
    while start < N {
        // Conditions on the length, known at compile time: no branch on data.
        let len = 4.min(N - start);
        let mut group = [0.0; 4];
        group[..len].copy_from_slice(&x[start..start + len]);
        // SAFETY: `crate::isa::wide()` returned true, which it does only after std's
        // `is_x86_feature_detected!` found AVX2 and FMA on this CPU; `sin_cos_x4`
        // requires nothing else.
        let (s, c) = unsafe { sin_cos_x4(group) };
        sin[start..start + len].copy_from_slice(&s[..len]);
        cos[start..start + len].copy_from_slice(&c[..len]);
        start += 4;
    }
    Some((sin, cos))
}

/// N groups of four angles (or of their sines or cosines).
pub type Groups<const N: usize> = [[f64; 4]; N];

/// Sines and cosines of N groups of four angles, one AVX register per group (the lanes
/// of [`crate::F64x4`]): each lane bit for bit [`super::sin_cos_mul_add`], as in
/// [`sin_cos_array`], without moving any angle between groups. `None` when this CPU lacks
/// AVX2 or FMA (or [`crate::isa`] is pinned to the baseline).
#[inline(always)]
#[must_use]
pub fn sin_cos_groups<const N: usize>(x: &Groups<N>) -> Option<(Groups<N>, Groups<N>)> {
    if !crate::isa::wide() {
        return None;
    }
    let mut sin = [[0.0; 4]; N];
    let mut cos = [[0.0; 4]; N];
    for (k, group) in x.iter().enumerate() {
        // SAFETY: as in `sin_cos_array`: `crate::isa::wide()` returned true, which it does
        // only after std's `is_x86_feature_detected!` found AVX2 and FMA on this CPU.
        (sin[k], cos[k]) = unsafe { sin_cos_x4(*group) };
    }
    Some((sin, cos))
}

/// The four lanes of `x`, step by step as `super::fused_steps` and `super::quadrant`.
///
/// # Safety
/// The CPU must have AVX2 and FMA.
#[target_feature(enable = "avx2,fma")]
#[inline]
unsafe fn sin_cos_x4(x: [f64; 4]) -> ([f64; 4], [f64; 4]) {
    let splat = |c: f64| _mm256_set1_pd(c);
    let (add, sub, mul, fma) = (_mm256_add_pd, _mm256_sub_pd, _mm256_mul_pd, _mm256_fmadd_pd);
    // SAFETY: `[f64; 4]` and `__m256d` are both 32 bytes, and every bit pattern is a
    // valid value of either.
    let x: __m256d = unsafe { core::mem::transmute::<[f64; 4], __m256d>(x) };

    // 1. Quadrant.
    let shifted = fma(x, splat(FRAC_2_PI), splat(ROUND));
    let n = sub(shifted, splat(ROUND));
    // 2. Cody–Waite reduction into r + rl.
    let a = fma(n, splat(-PIO2_1), x);
    let p2 = mul(n, splat(PIO2_2));
    let p3 = mul(n, splat(PIO2_3));
    let tail = add(p2, p3);
    let tail_low = add(sub(p2, tail), p3);
    let r = sub(a, tail);
    let rl = sub(sub(sub(a, r), tail), tail_low);
    // 3. Polynomials (Estrin, fused, as in `fused_steps`).
    let z = mul(r, r);
    let minus_half_z = mul(splat(-0.5), z);
    let z2 = mul(z, z);
    let z4 = mul(z2, z2);
    let estrin = |k: [f64; 6]| {
        let lo = fma(splat(k[1]), z, splat(k[0]));
        let mid = fma(splat(k[3]), z, splat(k[2]));
        let hi = fma(splat(k[5]), z, splat(k[4]));
        fma(z4, hi, fma(z2, mid, lo))
    };
    let (ps, pc) = (estrin(S), estrin(C));
    let sin = add(r, fma(mul(r, z), ps, fma(rl, minus_half_z, rl)));
    let one = splat(1.0);
    let w = add(one, minus_half_z);
    let small = _mm256_fnmadd_pd(r, rl, mul(z2, pc));
    let cos = add(w, add(add(sub(one, w), minus_half_z), small));

    // 4. Quadrant selection by bits; all ones (a NaN) where |x| ≥ 2⁵⁰ or x is NaN.
    let bits = _mm256_castpd_si256;
    let int = _mm256_set1_epi64x;
    let quadrant = bits(shifted);
    let swap = _mm256_sub_epi64(int(0), _mm256_and_si256(quadrant, int(1)));
    let sin_sign = _mm256_slli_epi64::<62>(_mm256_and_si256(quadrant, int(2)));
    let cos_sign =
        _mm256_slli_epi64::<62>(_mm256_and_si256(_mm256_add_epi64(quadrant, int(1)), int(2)));
    let magnitude = _mm256_and_si256(bits(x), int(i64::MAX));
    #[allow(clippy::cast_possible_wrap)] // 2⁵⁰'s bits are below i64::MAX
    let huge = _mm256_cmpgt_epi64(magnitude, int(HUGE_BITS as i64 - 1));
    let (sb, cb) = (bits(sin), bits(cos));
    let d = _mm256_and_si256(_mm256_xor_si256(sb, cb), swap);
    let sin = _mm256_or_si256(_mm256_xor_si256(_mm256_xor_si256(sb, d), sin_sign), huge);
    let cos = _mm256_or_si256(_mm256_xor_si256(_mm256_xor_si256(cb, d), cos_sign), huge);
    // SAFETY: as above, same size and every bit pattern valid.
    unsafe {
        (
            core::mem::transmute::<__m256d, [f64; 4]>(_mm256_castsi256_pd(sin)),
            core::mem::transmute::<__m256d, [f64; 4]>(_mm256_castsi256_pd(cos)),
        )
    }
}
