//! A branch-free, table-free `sin_cos` for `f64`, within 1 ulp of std.
//!
//! glibc's `sincos` took 36–60 % of the small generated functions (BENCHMARKS.md, "Where
//! the generated code spends its time"). This one is straight-line arithmetic that inlines:
//! about 50 additions and multiplications, a few integer operations, no comparison, no
//! lookup table, no fused multiply-add (the workspace builds for baseline x86-64, where
//! `mul_add` is a call to the C library's `fma`: twice as slow, measured).
//!
//! **It is not what `<f64 as Scalar>::sin_cos` uses**, because one at a time it is not
//! faster than glibc here: 8.5 ns against 7.6 ns per pair for independent angles, 16.5
//! against 16.8 ns in a dependent chain (`cargo bench -p dynamics-runtime --bench
//! sin_cos`), and level with it inside the generated functions (BENCHMARKS.md). glibc's
//! `__sincos_fma` uses FMA and a table; scalar SSE2 code needs about 50 operations on two
//! floating-point ports. What is faster is [`sin_cos_array`], several angles at once: the
//! loop vectorizer evaluates two angles per SSE2 instruction, 5.1 ns per pair (1.5× glibc).
//! Using it takes the generated code gathering its joint angles into one call.
//!
//! # Method
//!
//! 1. **Quadrant.** `n` = the integer nearest to x·2/π, by adding and subtracting
//!    1.5·2⁵² (the sum's last two bits are n mod 4, in two's complement for n < 0). Exact
//!    as long as |x·2/π| < 2⁵¹.
//! 2. **Cody–Waite reduction** r = x − n·π/2 with π/2 split in three,
//!    `PIO2_1 + PIO2_2 + PIO2_3`: two 33-bit heads and a 53-bit tail (122 bits in all;
//!    produced by `tools/fit_sin_cos.py`). For |n| ≤ 2²⁰ the products n·PIO2_1 and
//!    n·PIO2_2 are exact (33 + 20 bits ≤ 53), x − n·PIO2_1 is exact (Sterbenz: the two
//!    are within a factor of two). The rest, n·(PIO2_2 + PIO2_3), is summed first into a
//!    double-double `tail + tail_low` (Fast2Sum: |n·PIO2_2| > |n·PIO2_3|), then
//!    `(a − r) − tail` recovers exactly the rounding error of r = a − tail (Fast2Sum again;
//!    when |a| < |tail| the subtraction is itself exact, because a is a multiple of ulp(x)
//!    and of 2⁻³², hence of ulp(tail) ≤ |n|·2⁻⁸⁶). Summing the tail first keeps rl below
//!    an ulp of r (n·PIO2_3 alone reaches 2⁻⁴⁹, many ulps of r, and a first-order tail that
//!    large costs ulps in cos). The reduced argument is the double-double r + rl, in error
//!    by the rounding of n·PIO2_3 and the truncation of π/2: at most |n|·2⁻¹²⁰ ≤ 2⁻¹⁰⁰.
//! 3. **Polynomials** on |r| ≤ π/4 (fitted to 1.0001·π/4, since the rounded n can leave r a
//!    hair outside): sin r = r + r z P(z), cos r = 1 − z/2 + z² Q(z), z = r², P and Q of
//!    six coefficients each (degrees 13 and 14 in r), weighted-minimax for the relative
//!    error and rounded to f64 one coefficient at a time, refitting the rest
//!    (`tools/fit_sin_cos.py`, Remez exchange in 60-digit mpmath): relative error
//!    3.7·10⁻¹⁸ (2⁻⁵⁷·⁹) for sin and 5.7·10⁻²⁰ (2⁻⁶³·⁹) for cos. The tail rl enters to first
//!    order, sin(r + rl) ≈ sin r + rl (1 − z/2), cos(r + rl) ≈ cos r − r·rl, and 1 − z/2 is
//!    computed with its rounding error carried, so the last rounding of each result is the
//!    only large one. The two polynomials are evaluated side by side with Estrin's scheme.
//!    (Written lane by lane, [sin, cos], but LLVM does not pair the lanes into SSE2 on its
//!    own; it does vectorize across angles, in [`sin_cos_array`].)
//! 4. **Quadrant selection by bits.** (sin x, cos x) = (s, c), (c, −s), (−s, −c), (−c, s)
//!    for n mod 4 = 0, 1, 2, 3: an xor-swap under an all-ones-or-zero mask and two sign-bit
//!    xors, on `to_bits`.
//!
//! The kernel is written once, generic over [`Lane`]: `f64` here, and the `wide` SIMD
//! lanes of [`crate::lanes`] (`F32x8` widened to `f64`, and `F64x4` in a build with AVX),
//! where every operation is the same `f64` operation on each lane, so each lane is bit for
//! bit [`sin_cos`] of its angle (tested there). Making it generic left the `f64` machine
//! code as it was (the assembly of `sin_cos`, `sin_cos_mul_add` and `sin_cos_array`
//! compared before and after).
//!
//! # Accuracy (measured by the tests below, against std, i.e. glibc)
//!
//! - |x| ≤ 2²⁰·π/2 ≈ 1.6·10⁶ (exact n·PIO2_1, n·PIO2_2): at most 1 ulp from std in the
//!   tests' 14 million points (up to 6 % of them 1 ulp away in sin or cos, none further),
//!   including the seven doubles around the one nearest to k·π/2 for every |k| ≤ 2¹⁶ and
//!   every 61st k up to 2²⁰, and tiny arguments (sin x = x and cos x = 1 exactly for
//!   |x| ≤ 2⁻²⁷). Near k·π/2 the reduction adds a relative error of at most
//!   |n|·2⁻¹²⁰/|r| to the small result: under a tenth of an ulp while |r| ≥ |n|·2⁻⁶³.
//!   Only some doubles near k·π/2 with large k come closer, and there the tests measured
//!   at most 1 ulp.
//! - 1.6·10⁶ < |x| < 2⁵⁰ ≈ 1.1·10¹⁵: n·PIO2_1 is rounded, and the absolute error grows
//!   like |x|·2⁻⁵², i.e. like the spacing of the doubles around x (the angle itself is not
//!   known better than that); measured: at most half that spacing, and |sin|, |cos| ≤ 1 + 10⁻¹⁵.
//! - |x| ≥ 2⁵⁰, ±∞ and NaN: NaN (a mask on the exponent, no branch). Never a panic.
//! - Signed zero: `sin_cos(-0.0)` is `(+0.0, 1.0)` (std gives −0.0); every other input
//!   keeps the sign std gives.

// The AVX2 + FMA copy's batch: only with `std`, whose run-time feature detection
// (`crate::isa`) is what makes running it sound.
#[cfg(all(target_arch = "x86_64", feature = "std"))]
pub mod avx2;

/// 2/π, rounded.
const FRAC_2_PI: f64 = core::f64::consts::FRAC_2_PI;
/// 1.5·2⁵²: adding it rounds a number of magnitude < 2⁵¹ to an integer.
const ROUND: f64 = 6_755_399_441_055_744.0;
/// π/2 = PIO2_1 + PIO2_2 + PIO2_3 + 1.0·10⁻³⁷: 6746518852·2⁻³², 2242054355·2⁻⁶⁵ (33 bits
/// each), and the rest rounded to 53 bits (`tools/fit_sin_cos.py`).
const PIO2_1: f64 = 1.570_796_326_734_125_6;
const PIO2_2: f64 = 6.077_100_506_303_966e-11;
const PIO2_3: f64 = 2.022_266_248_795_950_6e-21;
/// Bits of |x| from which the result is NaN: 2⁵⁰ (x·2/π would reach 2⁵¹ near 3.5·10¹⁵;
/// the spacing of the doubles there is 0.25 already).
const HUGE_BITS: u64 = 0x4310_0000_0000_0000;

/// P(z) of sin r = r + r z P(z), constant term first (`tools/fit_sin_cos.py`).
const S: [f64; 6] = [
    -0.166_666_666_666_666_3,
    0.008_333_333_333_321_84,
    -0.000_198_412_698_293_585_28,
    2.755_731_353_851_428e-6,
    -2.505_073_438_928_488_6e-8,
    1.589_543_329_293_865e-10,
];
/// Q(z) of cos r = 1 − z/2 + z² Q(z), constant term first (`tools/fit_sin_cos.py`).
const C: [f64; 6] = [
    0.041_666_666_666_666_595,
    -0.001_388_888_888_887_333_8,
    2.480_158_728_899_748e-5,
    -2.755_731_421_529_913_4e-7,
    2.087_570_511_500_054e-9,
    -1.135_873_277_663_583_8e-11,
];

/// What the kernel asks of its number type: `f64` itself, or a SIMD vector of f64 lanes
/// (`crate::lanes`) whose `+`, `−` and `×` are, lane by lane, those of `f64` (IEEE-754
/// binary64, rounding to nearest), so that each lane is bit for bit [`sin_cos`] of its
/// angle. One kernel, [`sin_cos_impl`], serves both: the polynomials and the order of the
/// operations exist once.
pub(crate) trait Lane:
    Copy + core::ops::Add<Output = Self> + core::ops::Sub<Output = Self> + core::ops::Mul<Output = Self>
{
    /// The bits of the lanes, as unsigned 64-bit integers.
    type Bits: LaneBits;
    /// Every lane `x`.
    fn splat(x: f64) -> Self;
    /// `self · a + b` with one rounding per lane (only the `FUSED` kernel calls it).
    fn fused_mul_add(self, a: Self, b: Self) -> Self;
    /// Each lane's bits (`f64::to_bits`).
    fn to_bits(self) -> Self::Bits;
    /// Each lane from its bits (`f64::from_bits`).
    fn from_bits(bits: Self::Bits) -> Self;
}

/// Lane-wise integer operations on the bits of [`Lane`]s, as `u64`'s.
pub(crate) trait LaneBits:
    Copy
    + core::ops::BitAnd<Output = Self>
    + core::ops::BitOr<Output = Self>
    + core::ops::BitXor<Output = Self>
{
    /// Every lane `x`.
    fn splat(x: u64) -> Self;
    /// `u64::wrapping_add`, lane by lane.
    fn wrapping_add(self, other: Self) -> Self;
    /// `u64::wrapping_sub`, lane by lane.
    fn wrapping_sub(self, other: Self) -> Self;
    /// `self << n` (n < 64), lane by lane.
    fn shift_left(self, n: u32) -> Self;
    /// `self >> n` (logical, n < 64), lane by lane.
    fn shift_right(self, n: u32) -> Self;
}

impl Lane for f64 {
    type Bits = u64;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn fused_mul_add(self, a: Self, b: Self) -> Self {
        <f64 as crate::float::Math>::mul_add(self, a, b)
    }
    #[inline(always)]
    fn to_bits(self) -> u64 {
        f64::to_bits(self)
    }
    #[inline(always)]
    fn from_bits(bits: u64) -> Self {
        f64::from_bits(bits)
    }
}

impl LaneBits for u64 {
    #[inline(always)]
    fn splat(x: u64) -> Self {
        x
    }
    #[inline(always)]
    fn wrapping_add(self, other: Self) -> Self {
        u64::wrapping_add(self, other)
    }
    #[inline(always)]
    fn wrapping_sub(self, other: Self) -> Self {
        u64::wrapping_sub(self, other)
    }
    #[inline(always)]
    fn shift_left(self, n: u32) -> Self {
        self << n
    }
    #[inline(always)]
    fn shift_right(self, n: u32) -> Self {
        self >> n
    }
}

/// One Horner step on both lanes: [p₀ z + c₀, p₁ z + c₁].
#[inline(always)]
fn step<V: Lane>(p: [f64; 2], z: V, c0: f64, c1: f64) -> [V; 2] {
    [
        V::splat(p[0]) * z + V::splat(c0),
        V::splat(p[1]) * z + V::splat(c1),
    ]
}

/// Sine and cosine of `x` (radians), within 1 ulp of the correctly rounded values for
/// |x| ≤ 1.6·10⁶; see the module documentation for the method and larger |x|.
#[inline(always)]
pub fn sin_cos(x: f64) -> (f64, f64) {
    sin_cos_impl::<f64, false>(x)
}

/// Angles per SIMD register: four with AVX (`-C target-cpu=native` on a current x86-64),
/// two otherwise (SSE2, baseline x86-64).
const LANES: usize = if cfg!(target_feature = "avx") { 4 } else { 2 };

/// [`sin_cos`] of N angles at once, bit for bit the same values. Written as a loop over a
/// multiple of `LANES` independent angles, which LLVM's loop vectorizer turns into SIMD
/// code (two angles per SSE2 instruction, four per AVX one); the last N mod LANES angles go
/// through one more such group, padded with zeros (measured with AVX: seven angles in 47 ns
/// this way, 73 ns with the last three done one at a time; with SSE2 an odd last angle costs
/// the same alone or padded). Straight-line calls of [`sin_cos`] on separate angles are not
/// vectorized (nothing ties them together), nor are angles paired by hand.
#[inline(always)]
pub fn sin_cos_array<const N: usize>(x: &[f64; N]) -> ([f64; N], [f64; N]) {
    let mut sin = [0.0; N];
    let mut cos = [0.0; N];
    let whole = N - N % LANES;
    for i in 0..whole {
        (sin[i], cos[i]) = sin_cos(x[i]);
    }
    if whole < N {
        // A condition on the length, known at compile time: no branch on data.
        let mut padded = [0.0; LANES];
        padded[..N - whole].copy_from_slice(&x[whole..]);
        let (mut s, mut c) = ([0.0; LANES], [0.0; LANES]);
        for i in 0..LANES {
            (s[i], c[i]) = sin_cos(padded[i]);
        }
        sin[whole..].copy_from_slice(&s[..N - whole]);
        cos[whole..].copy_from_slice(&c[..N - whole]);
    }
    (sin, cos)
}

/// [`sin_cos`] with every product that one sum uses fused into it (`mul_add`): the
/// scalar statement of what the AVX2 + FMA kernel (`avx2.rs`) computes four angles at a
/// time, bit for bit (tested), and the benchmark's
/// (`cargo bench -p dynamics-runtime --bench sin_cos`): without `-C target-cpu` supporting
/// FMA, as the workspace builds, each `mul_add` is a call to the C library's `fma`.
#[inline(always)]
pub fn sin_cos_mul_add(x: f64) -> (f64, f64) {
    sin_cos_impl::<f64, true>(x)
}

/// [`sin_cos`] of each lane of `x`: bit for bit, lane by lane, what [`sin_cos`] gives for
/// that lane's angle (the same operations in the same order). For the `wide` lanes
/// (`lanes/wide_backed.rs`).
#[inline(always)]
pub(crate) fn sin_cos_lanes<V: Lane>(x: V) -> (V, V) {
    sin_cos_impl::<V, false>(x)
}

/// The kernel, on one angle (`f64`) or on the lanes of a SIMD vector ([`Lane`]): the
/// separate steps of [`sin_cos`], or with `FUSED` the fused ones of [`sin_cos_mul_add`]
/// (what the AVX2 + FMA copy computes, `avx2.rs`).
#[inline(always)]
fn sin_cos_impl<V: Lane, const FUSED: bool>(x: V) -> (V, V) {
    let (shifted, sin, cos) = if FUSED {
        fused_steps(x)
    } else {
        separate_steps(x)
    };
    quadrant(x, shifted, sin, cos)
}

/// Steps 1 to 3 with separate products and sums: `x·2/π + 1.5·2⁵²` (whose last bits give
/// the quadrant), and sin r, cos r of the reduced argument.
#[inline(always)]
fn separate_steps<V: Lane>(x: V) -> (V, V, V) {
    let k = V::splat;
    // 1. n = nearest integer to x·2/π; its last two bits are those of `shifted`.
    let shifted = x * k(FRAC_2_PI) + k(ROUND);
    let n = shifted - k(ROUND);

    // 2. r + rl = x − n·π/2 (see the module documentation for why each step is exact).
    let a = x - n * k(PIO2_1);
    let (r, rl) = reduced(a, n);

    // 3. The polynomials, both lanes at once.
    let z = r * r;
    let half_z = k(0.5) * z;
    let z2 = z * z;
    // Estrin's scheme, (c0 + c1 z) + z² (c2 + c3 z) + z⁴ (c4 + c5 z): one multiplication
    // more than Horner's and a third of its latency (measured: 16 % faster in a dependent
    // chain, 5 % in a stream of independent angles).
    let lo = step::<V>([S[1], C[1]], z, S[0], C[0]);
    let mid = step::<V>([S[3], C[3]], z, S[2], C[2]);
    let hi = step::<V>([S[5], C[5]], z, S[4], C[4]);
    let z4 = z2 * z2;
    let p = [
        lo[0] + (z2 * mid[0] + z4 * hi[0]),
        lo[1] + (z2 * mid[1] + z4 * hi[1]),
    ];
    let scaled = [(r * z) * p[0], z2 * p[1]];
    let sin = r + (scaled[0] + (rl - rl * half_z));
    let w = k(1.0) - half_z;
    let cos = w + (((k(1.0) - w) - half_z) + (scaled[1] - r * rl));
    (shifted, sin, cos)
}

/// Steps 1 to 3 with every product that one sum uses fused into it (one rounding): the
/// AVX2 kernel's 36 floating-point instructions against 49, the same method (here one more
/// multiplication, by −1, stands for its `vfnmadd`). `x − n·PIO2_1` is exact either
/// way; n may differ from the separate steps' by one where x·2/π is within an ulp of a
/// half-integer (|r| is then a hair above π/4, inside the polynomials' fitted range).
#[inline(always)]
fn fused_steps<V: Lane>(x: V) -> (V, V, V) {
    let k = V::splat;
    let fma = |a: V, b: V, c: V| a.fused_mul_add(b, c);
    let shifted = fma(x, k(FRAC_2_PI), k(ROUND));
    let n = shifted - k(ROUND);
    let a = fma(n, k(-PIO2_1), x);
    let (r, rl) = reduced(a, n);
    let z = r * r;
    // −z/2, exact: the sums below add it where the separate steps subtract z/2.
    let minus_half_z = k(-0.5) * z;
    let z2 = z * z;
    let z4 = z2 * z2;
    // Estrin's scheme with fused steps: c0 + c1 z + z² (c2 + c3 z) + z⁴ (c4 + c5 z).
    let estrin = |c: [f64; 6]| {
        let lo = fma(k(c[1]), z, k(c[0]));
        let mid = fma(k(c[3]), z, k(c[2]));
        let hi = fma(k(c[5]), z, k(c[4]));
        fma(z4, hi, fma(z2, mid, lo))
    };
    let (p_sin, p_cos) = (estrin(S), estrin(C));
    // sin r + rl (1 − z/2) and cos r − r·rl, as in `separate_steps`.
    let sin = r + fma(r * z, p_sin, fma(rl, minus_half_z, rl));
    let w = k(1.0) + minus_half_z;
    // −(r·rl) + z² Q, one rounding: the AVX2 kernel's `vfnmadd` ((−r)·rl is exact).
    let small = fma(r * k(-1.0), rl, z2 * p_cos);
    let cos = w + (((k(1.0) - w) + minus_half_z) + small);
    (shifted, sin, cos)
}

/// Step 2's tail: r + rl = a − n·(PIO2_2 + PIO2_3), the double-double reduced argument
/// (module documentation).
#[inline(always)]
fn reduced<V: Lane>(a: V, n: V) -> (V, V) {
    let k = V::splat;
    let p2 = n * k(PIO2_2);
    let p3 = n * k(PIO2_3);
    let tail = p2 + p3;
    let tail_low = (p2 - tail) + p3;
    let r = a - tail;
    let rl = ((a - r) - tail) - tail_low;
    (r, rl)
}

/// Step 4 on (sin r, cos r): the quadrant's swap and signs, and NaN for |x| ≥ 2⁵⁰.
#[inline(always)]
fn quadrant<V: Lane>(x: V, shifted: V, sin: V, cos: V) -> (V, V) {
    let b = <V::Bits as LaneBits>::splat;
    let n_bits = shifted.to_bits();
    // 4. Quadrant: swap when n is odd, negate sin when n mod 4 ∈ {2, 3}, cos when ∈ {1, 2}.
    let swap = b(0).wrapping_sub(n_bits & b(1));
    let sin_sign = (n_bits & b(2)).shift_left(62);
    let cos_sign = (n_bits.wrapping_add(b(1)) & b(2)).shift_left(62);
    // All ones when |x| ≥ 2⁵⁰ (or NaN): or-ing them in makes a NaN. (2⁵⁰ − 1 − |x|'s bits
    // is negative exactly then; its sign bit, negated, is the mask.)
    let huge = b(0).wrapping_sub(
        b(HUGE_BITS - 1)
            .wrapping_sub(x.to_bits() & b(!(1 << 63)))
            .shift_right(63),
    );
    let (sb, cb) = (sin.to_bits(), cos.to_bits());
    let d = (sb ^ cb) & swap;
    (
        V::from_bits((sb ^ d ^ sin_sign) | huge),
        V::from_bits((cb ^ d ^ cos_sign) | huge),
    )
}

#[cfg(test)]
mod tests {
    // std's prelude, for the build without the `std` feature (lib.rs).
    use super::sin_cos;
    use std::f64::consts::PI;
    #[allow(unused_imports)]
    use std::prelude::rust_2021::*;

    /// Distance in units in the last place: how many doubles lie between `a` and `b`
    /// (+0 and −0 count as one point).
    fn ulps(a: f64, b: f64) -> u64 {
        fn ordered(x: f64) -> i128 {
            let bits = x.to_bits();
            if bits >> 63 == 1 {
                -i128::from(bits & !(1 << 63))
            } else {
                i128::from(bits)
            }
        }
        (ordered(a) - ordered(b)).unsigned_abs() as u64
    }

    /// Worst distance of `f` from std over `points`, with the argument where it happens,
    /// the number of points and how many of them differ from std at all.
    fn worst(
        f: fn(f64) -> (f64, f64),
        points: impl Iterator<Item = f64>,
    ) -> (u64, f64, usize, usize) {
        let (mut max, mut at, mut count, mut differ) = (0, 0.0, 0, 0);
        for x in points {
            let (s, c) = f(x);
            let (s_std, c_std) = x.sin_cos();
            let e = ulps(s, s_std).max(ulps(c, c_std));
            if e > max {
                (max, at) = (e, x);
            }
            count += 1;
            differ += usize::from(e > 0);
        }
        (max, at, count, differ)
    }

    /// A reproducible stream of uniform numbers in [0, 1) (xorshift64*).
    fn uniform(mut state: u64) -> impl Iterator<Item = f64> {
        std::iter::from_fn(move || {
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            Some((state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64)
        })
    }

    /// The stated bound: within 1 ulp of std (glibc, itself within an ulp of the exact value
    /// and almost always correctly rounded) for |x| ≤ 2²⁰·π/2, with separate and with fused
    /// steps (`sin_cos_mul_add`, what the AVX2 + FMA kernels compute). Measured on 14 million
    /// points: uniform on a joint's range and on ±10⁵, log-uniform magnitudes from 10⁻³⁰⁰ to
    /// 1.6·10⁶, a dense grid on [−10, 10], and the seven doubles around the double nearest
    /// to k·π/2 for every 0 < |k| ≤ 2¹⁶ and every 61st k up to 2²⁰ (where the reduction
    /// cancels most). The worst case
    /// measured is 1 ulp (`cargo test -p dynamics-runtime sin_cos -- --nocapture` prints
    /// each sweep's).
    #[test]
    fn f64_sin_cos_within_one_ulp_of_std() {
        one_ulp_sweeps("sin_cos", sin_cos);
    }

    #[test]
    fn f64_sin_cos_mul_add_within_one_ulp_of_std() {
        one_ulp_sweeps("sin_cos_mul_add", super::sin_cos_mul_add);
    }

    fn one_ulp_sweeps(label: &str, f: fn(f64) -> (f64, f64)) {
        let sweeps: [(&str, Box<dyn Iterator<Item = f64>>); 6] = [
            (
                "uniform, |x| <= 2 pi",
                Box::new(
                    uniform(1)
                        .take(4_000_000)
                        .map(|u| (2.0 * u - 1.0) * 2.0 * PI),
                ),
            ),
            (
                "uniform, |x| <= 1e5",
                Box::new(uniform(2).take(3_000_000).map(|u| (2.0 * u - 1.0) * 1e5)),
            ),
            (
                "log-uniform, 1e-300 <= |x| <= 1.6e6",
                Box::new(uniform(3).take(2_000_000).enumerate().map(|(i, u)| {
                    let x = 10f64.powf(-300.0 + u * 306.2);
                    if i % 2 == 0 {
                        x
                    } else {
                        -x
                    }
                })),
            ),
            (
                "grid on [-10, 10]",
                Box::new((0..4_000_000).map(|i| -10.0 + f64::from(i) * 5.000_000_1e-6)),
            ),
            (
                "around k pi/2, |k| <= 2^16",
                Box::new(near_multiples_of_half_pi(1..=1 << 16)),
            ),
            (
                "around k pi/2, every 61st k up to 2^20",
                Box::new(near_multiples_of_half_pi((1 << 16..=1 << 20).step_by(61))),
            ),
        ];
        for (name, points) in sweeps {
            let (max, at, count, differ) = worst(f, points);
            println!(
                "{label}, {name}: {count} points, {:.2} % differ from std, worst {max} ulp (at x = {at:e})",
                100.0 * differ as f64 / count as f64
            );
            assert!(
                max <= 1,
                "{label}, {name}: {max} ulp from std at x = {at:e}"
            );
        }
    }

    /// For each k of `ks` (positive), and −k: the double nearest to k·π/2 (from a 122-bit π/2) and the three
    /// doubles on either side.
    fn near_multiples_of_half_pi(ks: impl Iterator<Item = i32>) -> impl Iterator<Item = f64> {
        ks.flat_map(|k| [k, -k]).flat_map(|k| {
            let k = f64::from(k);
            // k·PIO2_1 and k·PIO2_2 are exact; their sum rounds once, and the tail is below
            // a tenth of an ulp of it for k ≠ 0.
            let head = k * 1.570_796_326_734_125_6;
            let tail = k * 6.077_100_506_303_966e-11 + k * 2.022_266_248_795_950_6e-21;
            let nearest = head + tail;
            (-3i64..=3).map(move |m| f64::from_bits((nearest.to_bits() as i64 + m) as u64))
        })
    }

    /// Every length from 0 to 10 (whole groups, padded last groups), bit for bit: the
    /// SSE2 batch against `sin_cos`, and on x86-64 the AVX2 + FMA batch against
    /// `sin_cos_mul_add` (or `None` on a CPU without AVX2 and FMA), including NaN, −0, a
    /// large angle and one beyond 2⁵⁰.
    #[test]
    fn array_is_elementwise() {
        fn check<const N: usize>(all: &[f64; 10]) {
            let x: [f64; N] = std::array::from_fn(|i| all[i]);
            let bits = |(s, c): (f64, f64)| (s.to_bits(), c.to_bits());
            let (s, c) = super::sin_cos_array(&x);
            for i in 0..N {
                assert_eq!(bits((s[i], c[i])), bits(sin_cos(x[i])), "angle {i} of {N}");
            }
            #[cfg(all(target_arch = "x86_64", feature = "std"))]
            match super::avx2::sin_cos_array(&x) {
                Some((s, c)) => {
                    for i in 0..N {
                        assert_eq!(
                            bits((s[i], c[i])),
                            bits(super::sin_cos_mul_add(x[i])),
                            "AVX2, angle {i} of {N}"
                        );
                    }
                }
                None => assert!(!crate::isa::wide()),
            }
            // The lanes' batch: N groups of four angles, the angles taken in turn.
            #[cfg(all(target_arch = "x86_64", feature = "std"))]
            {
                let groups: [[f64; 4]; N] =
                    std::array::from_fn(|k| std::array::from_fn(|l| all[(k + 3 * l) % 10]));
                match super::avx2::sin_cos_groups(&groups) {
                    Some((s, c)) => {
                        for (k, group) in groups.iter().enumerate() {
                            for (l, &angle) in group.iter().enumerate() {
                                assert_eq!(
                                    bits((s[k][l], c[k][l])),
                                    bits(super::sin_cos_mul_add(angle)),
                                    "AVX2 groups, angle {l} of group {k} of {N}"
                                );
                            }
                        }
                    }
                    None => assert!(!crate::isa::wide()),
                }
            }
        }
        let x = [
            -3.0,
            -1.0,
            0.1,
            PI / 4.0,
            2.0,
            1e5,
            f64::NAN,
            -0.0,
            7.5,
            1e16,
        ];
        check::<0>(&x);
        check::<1>(&x);
        check::<2>(&x);
        check::<3>(&x);
        check::<4>(&x);
        check::<5>(&x);
        check::<6>(&x);
        check::<7>(&x);
        check::<8>(&x);
        check::<9>(&x);
        check::<10>(&x);
    }

    /// The AVX2 + FMA batch against its scalar statement `sin_cos_mul_add`, bit for bit, on
    /// 400,000 angles of every quadrant and sign (joint ranges to 1.6·10⁶), the doubles
    /// around k·π/2 for |k| ≤ 2¹⁰, and the special values (or `None` on a CPU without
    /// AVX2 and FMA).
    #[cfg(all(target_arch = "x86_64", feature = "std"))]
    #[test]
    fn avx2_batch_is_its_scalar_statement_on_a_sweep() {
        let specials = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.0,
            0.0,
            2.0_f64.powi(50),
            f64::from_bits(2.0_f64.powi(50).to_bits() - 1),
            -1e16,
        ];
        let angles: Vec<f64> = uniform(11)
            .take(200_000)
            .map(|u| (u - 0.5) * 40.0)
            .chain(uniform(12).take(200_000).map(|u| (u - 0.5) * 3.2e6))
            .chain(near_multiples_of_half_pi(1..=1024))
            .chain(specials)
            .collect();
        let bits = |(s, c): (f64, f64)| (s.to_bits(), c.to_bits());
        for group in angles.chunks(8) {
            let mut x = [0.0; 8];
            x[..group.len()].copy_from_slice(group);
            let Some((s, c)) = super::avx2::sin_cos_array(&x) else {
                assert!(!crate::isa::wide());
                return;
            };
            for i in 0..8 {
                assert_eq!(
                    bits((s[i], c[i])),
                    bits(super::sin_cos_mul_add(x[i])),
                    "x = {:e}",
                    x[i]
                );
            }
        }
    }

    #[test]
    fn f64_sin_cos_tiny_and_exact_cases() {
        for x in [0.0, 5e-324, 1e-300, 1e-20, 1e-9, 2.0_f64.powi(-27), -1e-12] {
            let (s, c) = sin_cos(x);
            assert_eq!(s, x, "sin {x:e}");
            assert_eq!(c, 1.0, "cos {x:e}");
        }
        assert_eq!(sin_cos(-0.0_f64), (0.0, 1.0));
        let (s, c) = sin_cos(PI);
        assert_eq!((s, c), PI.sin_cos());
    }

    /// Beyond the exact-reduction range the absolute error grows like the spacing of the
    /// doubles around x; beyond 2⁵⁰, and for infinities and NaN, the result is NaN.
    #[test]
    fn f64_sin_cos_large_and_non_finite_arguments() {
        let mut worst = 0.0_f64;
        for u in uniform(4).take(200_000) {
            let x = 10f64.powf(6.2 + u * 8.8); // 1.6e6 .. 1e15
            let (s, c) = sin_cos(x);
            let (s_std, c_std) = x.sin_cos();
            let spacing = f64::from_bits(x.to_bits() + 1) - x;
            worst = worst
                .max((s - s_std).abs() / spacing)
                .max((c - c_std).abs() / spacing);
            assert!(
                s.abs() <= 1.0 + 1e-15 && c.abs() <= 1.0 + 1e-15,
                "x = {x:e}"
            );
        }
        println!("sin_cos, 1.6e6 < |x| < 1e15: worst absolute error {worst:.3} x spacing of doubles at x");
        assert!(worst <= 1.0, "{worst}");
        for x in [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            2.0_f64.powi(50),
            -1e16,
            1e300,
            f64::MAX,
        ] {
            let (s, c) = sin_cos(x);
            assert!(s.is_nan() && c.is_nan(), "sin_cos({x:e}) = ({s}, {c})");
        }
        let below = f64::from_bits(2.0_f64.powi(50).to_bits() - 1);
        assert!(!sin_cos(below).0.is_nan());
    }
}
