//! The 4 × 4 transpose that unpacks four entries of four results at once:
//! `rows[j][l]`, lane `l` of the pack of entry `j`, becomes `out[l][j]`, entry `j` of
//! result `l`. Where the AVX2 + FMA copies run it is four loads, eight shuffles and four
//! stores of AVX registers; LLVM does not find that on its own from the portable form
//! (it moves the sixteen numbers one by one), so it is written with `core::arch`.

// Shuffle intrinsics called from a `#[target_feature]` function; proof at the call.
#![cfg_attr(all(target_arch = "x86_64", feature = "std"), allow(unsafe_code))]

/// `out[l][j] = rows[j][l]` for `j, l` in 0..4; the numbers are moved, not changed.
#[inline(always)]
pub(super) fn transpose4(rows: [[f64; 4]; 4]) -> [[f64; 4]; 4] {
    #[cfg(all(target_arch = "x86_64", feature = "std"))]
    if crate::isa::wide() {
        // SAFETY: `transpose4_avx` is compiled for AVX and requires nothing else;
        // `crate::isa::wide()` returns true only after std's `is_x86_feature_detected!`
        // found AVX2 (which implies AVX) and FMA on this CPU.
        return unsafe { transpose4_avx(rows) };
    }
    transpose4_portable(rows)
}

/// [`transpose4`] number by number, for any number type: `f64` without AVX, and `f32`,
/// whose [`crate::F32x8`] fills a pack of four results only as a last pack.
#[inline(always)]
pub(super) fn transpose4_portable<T: Copy>(rows: [[T; 4]; 4]) -> [[T; 4]; 4] {
    core::array::from_fn(|l| core::array::from_fn(|j| rows[j][l]))
}

/// [`transpose4`] in AVX registers: inlined into the batch loop's AVX2 + FMA copy
/// (`crate::isa::run_loop`), a call elsewhere.
///
/// # Safety
/// The CPU must have AVX.
#[cfg(all(target_arch = "x86_64", feature = "std"))]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn transpose4_avx(rows: [[f64; 4]; 4]) -> [[f64; 4]; 4] {
    use core::arch::x86_64::{
        _mm256_loadu_pd, _mm256_permute2f128_pd, _mm256_storeu_pd, _mm256_unpackhi_pd,
        _mm256_unpacklo_pd,
    };
    // SAFETY: each pointer is to an `[f64; 4]`, the 32 bytes the unaligned load and store
    // read and write; the shuffles only need AVX, which the caller guarantees.
    unsafe {
        let [r0, r1, r2, r3] = rows.map(|r| _mm256_loadu_pd(r.as_ptr()));
        // Within each 128-bit half: [r0₀ r1₀ | r0₂ r1₂], [r0₁ r1₁ | r0₃ r1₃], and for r2, r3.
        let (low01, high01) = (_mm256_unpacklo_pd(r0, r1), _mm256_unpackhi_pd(r0, r1));
        let (low23, high23) = (_mm256_unpacklo_pd(r2, r3), _mm256_unpackhi_pd(r2, r3));
        // Across halves: lanes 0 and 1 from the low halves, 2 and 3 from the high ones.
        let lanes = [
            _mm256_permute2f128_pd::<0x20>(low01, low23),
            _mm256_permute2f128_pd::<0x20>(high01, high23),
            _mm256_permute2f128_pd::<0x31>(low01, low23),
            _mm256_permute2f128_pd::<0x31>(high01, high23),
        ];
        let mut out = [[0.0; 4]; 4];
        for (o, lane) in out.iter_mut().zip(lanes) {
            _mm256_storeu_pd(o.as_mut_ptr(), lane);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    fn check(label: &str, transpose: impl Fn([[f64; 4]; 4]) -> [[f64; 4]; 4]) {
        let rows: [[f64; 4]; 4] =
            core::array::from_fn(|j| core::array::from_fn(|l| (10 * j + l) as f64 + 0.5));
        let out = transpose(rows);
        for j in 0..4 {
            for l in 0..4 {
                assert_eq!(
                    out[l][j].to_bits(),
                    rows[j][l].to_bits(),
                    "{label}: {j}, {l}"
                );
            }
        }
    }

    /// Every number lands where the transpose puts it: number by number, in AVX registers
    /// (on a CPU with AVX), and through the dispatch.
    #[test]
    fn every_form_transposes() {
        check("portable", super::transpose4_portable::<f64>);
        #[cfg(all(target_arch = "x86_64", feature = "std"))]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX, just checked.
            check("avx", |rows| unsafe { super::transpose4_avx(rows) });
        }
        check("dispatched", super::transpose4);
    }
}
