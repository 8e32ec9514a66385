//! [`F64x4`] for a build without AVX (the default x86-64 target, and other architectures):
//! four `f64` in an array, every operation written lane by lane, and every generated
//! kernel run in the copy `f64` runs ([`Scalar::run_kernel`] is `f64`'s).
//!
//! Lane `i` is then the `f64` computation on lane `i`, operation for operation, in the
//! same copy of the kernel: bit for bit the `f64` call, whichever copy
//! ([`crate::isa`]) runs. The compiler turns the four lanes of each operation into one
//! SIMD instruction: one AVX register in the AVX2 + FMA copy, two SSE2 registers in the
//! baseline one. Not left to it, in the wide copy: the fused products (`mul_add_on`, one
//! `vfmadd` with the proof the kernel's `Isa<true>` carries; four scalar ones did not come
//! back together in long functions) and the sines and cosines (one AVX register per
//! `F64x4`). A `wide::f64x4` (the backing of the AVX build, [`super`]) cannot take
//! the AVX2 copy: `wide` picks SSE2 instructions when the crate is compiled, whatever
//! function they are inlined into. (An eight-lane `f32` type built the same way was tried
//! and not kept: [`super`], "Backing".)
//!
//! The lane-by-lane helpers are free functions on arrays: written as methods taking the
//! lanes by value, a debug build's frames grew past the 2 MB of a test thread on the
//! quadruped's functions (tests/lanes.rs), where these stay under it.

use super::Lanes;
use crate::fast_trig;
use crate::isa::Isa;
use crate::Scalar;
use core::fmt;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use num_traits::{One, Zero};

/// Four `f64` lanes: a [`Scalar`] that runs a generated function on four states at once,
/// each lane bit for bit the `f64` call on its state (see the [module
/// documentation](super) for the exact contract, sines and cosines included).
///
/// ```
/// use dynamics_runtime::{F64x4, Scalar};
/// let x = F64x4::new([0.0, 0.5, 1.0, 2.0]);
/// let y = x * x + F64x4::splat(1.0);
/// assert_eq!(y.to_array(), [1.0, 1.25, 2.0, 5.0]);
/// assert_eq!(y.get(3), Some(5.0));
/// assert_eq!(Scalar::sqrt(y).to_array()[3], 5.0_f64.sqrt());
/// ```
#[derive(Clone, Copy, Default)]
#[repr(C, align(32))]
pub struct F64x4([f64; 4]);

/// `[f(x₀), f(x₁), f(x₂), f(x₃)]`, written out so that each lane is the same operation.
#[inline(always)]
fn each(x: [f64; 4], f: impl Fn(f64) -> f64) -> [f64; 4] {
    [f(x[0]), f(x[1]), f(x[2]), f(x[3])]
}

/// `[f(x₀, y₀), …, f(x₃, y₃)]`.
#[inline(always)]
fn pairs(x: [f64; 4], y: [f64; 4], f: impl Fn(f64, f64) -> f64) -> [f64; 4] {
    [f(x[0], y[0]), f(x[1], y[1]), f(x[2], y[2]), f(x[3], y[3])]
}

/// `[f(x₀, y₀, z₀), …, f(x₃, y₃, z₃)]`.
#[inline(always)]
fn triples(x: [f64; 4], y: [f64; 4], z: [f64; 4], f: impl Fn(f64, f64, f64) -> f64) -> [f64; 4] {
    [
        f(x[0], y[0], z[0]),
        f(x[1], y[1], z[1]),
        f(x[2], y[2], z[2]),
        f(x[3], y[3], z[3]),
    ]
}

impl F64x4 {
    /// The number of lanes.
    pub const LANES: usize = 4;

    /// The lanes, in order.
    #[inline(always)]
    #[must_use]
    pub const fn new(lanes: [f64; 4]) -> Self {
        Self(lanes)
    }

    /// Every lane `x`.
    #[inline(always)]
    #[must_use]
    pub const fn splat(x: f64) -> Self {
        Self([x; 4])
    }

    /// Lane `i` is `f(i)`, called for `i` = 0, 1, … in order.
    #[inline(always)]
    #[must_use]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> Self {
        Self(core::array::from_fn(f))
    }

    /// The lanes, in order.
    #[inline(always)]
    #[must_use]
    pub const fn to_array(self) -> [f64; 4] {
        self.0
    }

    /// Lane `i`, or `None` when `i` is not below [`Self::LANES`].
    #[inline(always)]
    #[must_use]
    pub fn get(self, i: usize) -> Option<f64> {
        self.0.get(i).copied()
    }
}

impl From<[f64; 4]> for F64x4 {
    #[inline(always)]
    fn from(lanes: [f64; 4]) -> Self {
        Self(lanes)
    }
}

impl From<F64x4> for [f64; 4] {
    #[inline(always)]
    fn from(x: F64x4) -> Self {
        x.0
    }
}

impl fmt::Debug for F64x4 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_tuple("F64x4").field(&self.0).finish()
    }
}

/// Every lane equal (IEEE: a NaN lane is unequal to everything, `+0 == −0`).
impl PartialEq for F64x4 {
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

macro_rules! binary {
    ($op:ident, $f:ident, $op_assign:ident, $f_assign:ident, $sym:tt) => {
        impl $op for F64x4 {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                Self(pairs(self.0, rhs.0, |x, y| x $sym y))
            }
        }
        impl $op_assign for F64x4 {
            #[inline(always)]
            fn $f_assign(&mut self, rhs: Self) {
                *self = *self $sym rhs;
            }
        }
    };
}

binary!(Add, add, AddAssign, add_assign, +);
binary!(Sub, sub, SubAssign, sub_assign, -);
binary!(Mul, mul, MulAssign, mul_assign, *);
binary!(Div, div, DivAssign, div_assign, /);

/// Flips each lane's sign bit (as `-x` on `f64`: `−(+0) = −0`).
impl Neg for F64x4 {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self(each(self.0, |x| -x))
    }
}

impl Zero for F64x4 {
    #[inline(always)]
    fn zero() -> Self {
        Self::splat(0.0)
    }
    /// Every lane ±0.
    #[inline]
    fn is_zero(&self) -> bool {
        self.0.iter().all(|x| *x == 0.0)
    }
}

impl One for F64x4 {
    #[inline(always)]
    fn one() -> Self {
        Self::splat(1.0)
    }
}

impl Scalar for F64x4 {
    /// The unpacked body: four states already fill the lanes.
    #[inline(always)]
    fn run_packed<A, R>(arg: A, packed: impl FnOnce(A) -> R, unpacked: impl FnOnce(A) -> R) -> R {
        let _ = packed;
        unpacked(arg)
    }
    /// Every lane `x`.
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Self::splat(x)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    #[inline(always)]
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(each(self.0, <f64 as Scalar>::sqrt))
    }
    /// The runtime's `fast_trig::sin_cos` on each lane.
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let x = self.0;
        let s: [(f64, f64); 4] = core::array::from_fn(|i| fast_trig::sin_cos(x[i]));
        (
            Self(core::array::from_fn(|i| s[i].0)),
            Self(core::array::from_fn(|i| s[i].1)),
        )
    }
    #[inline(always)]
    fn sin_cos_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        Self::sin_cos_array_for::<false, N>(x)
    }
    /// `f64`'s `mul_add` on each lane.
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        Self(triples(self.0, a.0, b.0, Scalar::mul_add))
    }
    /// `f64`'s batch on each lane's N angles: in the wide copy one AVX register per
    /// `F64x4` (four angles, one of each lane), bit for bit what `f64`'s wide batch gives
    /// each angle; in the baseline copy `f64`'s batch of each lane's angles in turn.
    #[inline(always)]
    fn sin_cos_array_for<const WIDE: bool, const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        #[cfg(all(target_arch = "x86_64", feature = "std"))]
        if WIDE {
            if let Some((sin, cos)) = fast_trig::avx2::sin_cos_groups(&x.map(|v| v.0)) {
                return (sin.map(Self), cos.map(Self));
            }
        }
        let mut sin = [Self::zero(); N];
        let mut cos = [Self::zero(); N];
        for lane in 0..4 {
            let (s, c) = <f64 as Scalar>::sin_cos_array_for::<WIDE, N>(core::array::from_fn(|i| {
                x[i].0[lane]
            }));
            for i in 0..N {
                sin[i].0[lane] = s[i];
                cos[i].0[lane] = c[i];
            }
        }
        (sin, cos)
    }
    /// In the wide copy one AVX fused multiply-add, `vfmadd` on the four lanes (the
    /// `Isa<true>` proves the CPU has it), bit for bit `f64`'s on each lane; in the
    /// baseline copy `f64`'s on each lane.
    #[inline(always)]
    fn mul_add_on<const WIDE: bool>(self, a: Self, b: Self, isa: Isa<WIDE>) -> Self {
        #[cfg(all(target_arch = "x86_64", feature = "std"))]
        if let Some(proof) = isa.avx2_fma() {
            return fused(proof, self, a, b);
        }
        Self(triples(self.0, a.0, b.0, |x, y, z| {
            <f64 as Scalar>::mul_add_on(x, y, z, isa)
        }))
    }
    /// `f64`'s choice of copy.
    #[inline(always)]
    fn run_kernel<R>(wide: impl FnOnce(Isa<true>) -> R, narrow: impl FnOnce(Isa<false>) -> R) -> R {
        <f64 as Scalar>::run_kernel(wide, narrow)
    }
    /// `f64`'s choice of copy.
    #[inline(always)]
    fn run_kernel_into<O: ?Sized>(
        out: &mut O,
        wide: impl FnOnce(Isa<true>, &mut O),
        narrow: impl FnOnce(Isa<false>, &mut O),
    ) {
        <f64 as Scalar>::run_kernel_into(out, wide, narrow);
    }
    /// `f64`'s choice of copy.
    #[inline(always)]
    fn run_piece_into<O: ?Sized, R>(
        out: &mut O,
        wide: impl FnOnce(Isa<true>, &mut O) -> R,
        narrow: impl FnOnce(Isa<false>, &mut O) -> R,
    ) -> R {
        <f64 as Scalar>::run_piece_into(out, wide, narrow)
    }
    /// `f64`'s choice of copy.
    #[inline(always)]
    fn run_piece<R>(wide: impl FnOnce(Isa<true>) -> R, narrow: impl FnOnce(Isa<false>) -> R) -> R {
        <f64 as Scalar>::run_piece(wide, narrow)
    }
}

impl Lanes for F64x4 {
    type Element = f64;
    const LANES: usize = 4;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Self::splat(x)
    }
    #[inline(always)]
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self {
        Self::from_fn(f)
    }
    #[inline(always)]
    fn get(self, i: usize) -> Option<f64> {
        Self::get(self, i)
    }
    /// The four lanes as they are stored.
    #[inline(always)]
    fn first4(self) -> [f64; 4] {
        self.0
    }
}

/// `a · b + c`, one rounding per lane: one `vfmadd` on one AVX register, each lane bit for
/// bit `f64::mul_add` of its lanes. Inlined into the wide copy of a kernel (compiled for
/// AVX2 and FMA) it is that one instruction.
#[cfg(all(target_arch = "x86_64", feature = "std"))]
#[allow(unsafe_code)] // the intrinsic and two transmutes; proofs below
#[inline(always)]
fn fused(proof: crate::isa::Avx2Fma, a: F64x4, b: F64x4, c: F64x4) -> F64x4 {
    use core::arch::x86_64::{__m256d, _mm256_fmadd_pd};
    let _ = proof;
    // SAFETY: `F64x4` (`repr(C, align(32))` over `[f64; 4]`) and `__m256d` are both 32
    // bytes with the same alignment, and every bit pattern is a valid value of either.
    // `_mm256_fmadd_pd` needs AVX and FMA, which `proof` shows this CPU has: an
    // `Avx2Fma` exists only after the run-time detection found both (`crate::isa`).
    unsafe {
        core::mem::transmute::<__m256d, F64x4>(_mm256_fmadd_pd(
            core::mem::transmute::<F64x4, __m256d>(a),
            core::mem::transmute::<F64x4, __m256d>(b),
            core::mem::transmute::<F64x4, __m256d>(c),
        ))
    }
}
