//! The number type that the reference algorithms and the generated code compute with.
//!
//! Contract: a `Scalar` is a copyable field element with `sin`, `cos` and `sqrt`, plus an
//! exact-or-nearest conversion from `f64` for the model's constants. It deliberately has no
//! comparison and no branching operation, so that SIMD lanes (four states at once), dual
//! numbers (derivatives) and double-double (about 32 digits) can implement it later: the
//! dynamics never branch on data.

use nalgebra::{ClosedAddAssign, ClosedDivAssign, ClosedMulAssign, ClosedSubAssign};
use num_traits::{One, Zero};
use std::ops::Neg;

/// Arithmetic needed by the dynamics, generic over the number representation.
///
/// Implemented for `f32` and `f64`. The nalgebra bounds let the reference algorithms use
/// `Vector3<T>`, `Matrix3<T>` and `Matrix6<T>` arithmetic without any further trait.
pub trait Scalar:
    nalgebra::Scalar
    + Copy
    + Zero
    + One
    + ClosedAddAssign
    + ClosedSubAssign
    + ClosedMulAssign
    + ClosedDivAssign
    + Neg<Output = Self>
    + Send
    + Sync
{
    /// The value nearest to `x` (exact for `f64`, rounded to nearest for `f32`).
    fn from_f64(x: f64) -> Self;
    /// Sine of an angle in radians.
    fn sin(self) -> Self;
    /// Cosine of an angle in radians.
    fn cos(self) -> Self;
    /// Square root (NaN for negative input, as IEEE floats do).
    fn sqrt(self) -> Self;
    /// Sine and cosine together; implementations may share work.
    #[inline]
    fn sin_cos(self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    /// Sines and cosines of N angles at once, `([sin x₀, …], [cos x₀, …])`; implementations
    /// may evaluate them together. For `f64` this is [`crate::fast_trig::sin_cos_array`]:
    /// vectorized, within 1 ulp of `sin_cos` (not always equal to it), and 1.2× faster
    /// UR5 inverse dynamics and gravity when the joints' angles go through one call
    /// (BENCHMARKS.md). The default calls `sin_cos` on each.
    #[inline]
    fn sin_cos_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        let mut sin = x;
        let mut cos = x;
        for i in 0..N {
            (sin[i], cos[i]) = x[i].sin_cos();
        }
        (sin, cos)
    }
    /// `self · a + b`. The generated code writes every product that only one sum or
    /// difference uses this way. The default, and `f32`/`f64` built without FMA (baseline
    /// x86-64), compute `self * a + b`: two roundings, bit for bit the separate operations.
    /// `f32`/`f64` built for a CPU with fused multiply-add (`-C target-cpu=native`, or
    /// `-C target-feature=+fma`) use it: one instruction, one rounding.
    #[inline(always)]
    #[must_use]
    fn mul_add(self, a: Self, b: Self) -> Self {
        self * a + b
    }
    #[doc(hidden)]
    /// `self · a + b` in the `WIDE` copy of a generated kernel ([`crate::isa`]): the
    /// baseline copy (`WIDE = false`) calls [`Scalar::mul_add`]; the wide copy of `f32` and
    /// `f64`, compiled for FMA, fuses (one instruction, one rounding). The default is
    /// `mul_add` in both.
    #[inline(always)]
    #[must_use]
    fn mul_add_for<const WIDE: bool>(self, a: Self, b: Self) -> Self {
        self.mul_add(a, b)
    }
    #[doc(hidden)]
    /// [`Scalar::sin_cos_array`] in the `WIDE` copy of a generated kernel: for `f64` the
    /// wide copy takes four angles per AVX register with fused Estrin steps
    /// ([`crate::fast_trig::avx2::sin_cos_array`]). The default is `sin_cos_array` in both.
    #[inline(always)]
    fn sin_cos_array_for<const WIDE: bool, const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        Self::sin_cos_array(x)
    }
    #[doc(hidden)]
    /// For generated code, not for users (hidden from the docs): runs a whole generated
    /// function, `wide` (its `WIDE = true` kernel) or `narrow`. `f32`
    /// and `f64` choose at run time with [`crate::isa::run`]; the default runs `narrow`, so
    /// other types never instantiate the wide kernel.
    #[inline(always)]
    fn run_kernel<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
        let _ = wide;
        narrow()
    }
    #[doc(hidden)]
    /// Runs one piece of a split generated function like [`Scalar::run_kernel`], each copy
    /// out of line ([`crate::isa::run_piece`]), so that the pieces stay separate functions.
    #[inline(always)]
    fn run_piece<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
        let _ = wide;
        crate::isa::out_of_line(narrow)
    }
}

/// A [`Scalar`] that the run-time solvers (Newton's method, pivoting) can test and report:
/// ordered, with a nearest `f64`. Implemented for `f32`, `f64` and [`crate::DoubleDouble`].
pub trait Real: Scalar + PartialOrd {
    /// The nearest `f64` (for finiteness tests and error reports).
    fn to_f64(self) -> f64;
}

impl Real for f32 {
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

impl Real for f64 {
    fn to_f64(self) -> f64 {
        self
    }
}

impl Real for crate::DoubleDouble {
    fn to_f64(self) -> f64 {
        crate::DoubleDouble::to_f64(self)
    }
}

/// |x| for an ordered scalar (the run-time solvers' pivoting and convergence tests; the
/// generated code never needs it). NaN stays NaN.
pub(crate) fn abs<T: Scalar + PartialOrd>(x: T) -> T {
    if x < T::zero() {
        -x
    } else {
        x
    }
}

macro_rules! impl_float_scalar {
    ($t:ty $(, { $($extra:item)* })?) => {
        impl Scalar for $t {
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn sin(self) -> Self {
                <$t>::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                <$t>::cos(self)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                <$t>::sin_cos(self)
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                if cfg!(target_feature = "fma") {
                    <$t>::mul_add(self, a, b)
                } else {
                    self * a + b
                }
            }
            #[inline(always)]
            fn mul_add_for<const WIDE: bool>(self, a: Self, b: Self) -> Self {
                if WIDE {
                    <$t>::mul_add(self, a, b)
                } else {
                    Scalar::mul_add(self, a, b)
                }
            }
            #[inline(always)]
            fn run_kernel<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
                crate::isa::run(wide, narrow)
            }
            #[inline(always)]
            fn run_piece<R>(wide: impl FnOnce() -> R, narrow: impl FnOnce() -> R) -> R {
                crate::isa::run_piece(wide, narrow)
            }
            $($($extra)*)?
        }
    };
}

impl_float_scalar!(f32);
impl_float_scalar!(f64, {
    #[inline(always)]
    fn sin_cos_array<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
        crate::fast_trig::sin_cos_array(&x)
    }
    #[inline(always)]
    fn sin_cos_array_for<const WIDE: bool, const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
        #[cfg(target_arch = "x86_64")]
        if WIDE {
            if let Some(wide) = crate::fast_trig::avx2::sin_cos_array(&x) {
                return wide;
            }
        }
        crate::fast_trig::sin_cos_array(&x)
    }
});

#[cfg(test)]
mod tests {
    use super::Scalar;

    /// 0.1 · 10 − 1 is 0 with two roundings and 5.55e-17 with one: `mul_add` fuses only
    /// when the build targets FMA hardware, `mul_add_for::<true>` (the AVX2 + FMA kernels')
    /// always.
    #[test]
    fn mul_add_fuses_only_when_built_for_fma() {
        let (a, b, c) = (0.1_f64, 10.0, -1.0);
        assert_ne!(
            f64::mul_add(a, b, c),
            a * b + c,
            "the case tells the two apart"
        );
        let expected = if cfg!(target_feature = "fma") {
            f64::mul_add(a, b, c)
        } else {
            a * b + c
        };
        assert_eq!(
            <f64 as Scalar>::mul_add(a, b, c).to_bits(),
            expected.to_bits()
        );
        // The kernels' copies: the baseline one as `mul_add`, the wide one always fused.
        assert_eq!(
            <f64 as Scalar>::mul_add_for::<false>(a, b, c).to_bits(),
            expected.to_bits()
        );
        assert_eq!(
            <f64 as Scalar>::mul_add_for::<true>(a, b, c).to_bits(),
            f64::mul_add(a, b, c).to_bits()
        );
    }

    #[test]
    fn f32_rounds_to_nearest() {
        assert_eq!(<f32 as Scalar>::from_f64(0.1), 0.1_f32);
        assert_eq!(<f64 as Scalar>::from_f64(0.1), 0.1_f64);
    }

    #[test]
    fn trig_matches_std() {
        let (s, c) = Scalar::sin_cos(0.5_f64);
        assert_eq!(s, 0.5_f64.sin());
        assert_eq!(c, 0.5_f64.cos());
        assert!(Scalar::sqrt(-1.0_f64).is_nan());
    }

    #[test]
    fn sin_cos_array_is_within_one_ulp_of_sin_cos() {
        let x = [-3.0, -0.5, 0.0, 0.25, 1.5, 2.75, 100.0];
        let (s, c) = <f64 as Scalar>::sin_cos_array(x);
        let (s32, c32) = <f32 as Scalar>::sin_cos_array([0.5_f32, 2.0]);
        assert_eq!((s32[1], c32[1]), 2.0_f32.sin_cos());
        assert_eq!((s32[0], c32[0]), 0.5_f32.sin_cos());
        for i in 0..x.len() {
            let (s1, c1) = Scalar::sin_cos(x[i]);
            assert!((s[i] - s1).abs() <= f64::EPSILON * s1.abs().max(f64::MIN_POSITIVE));
            assert!((c[i] - c1).abs() <= f64::EPSILON * c1.abs().max(f64::MIN_POSITIVE));
        }
    }
}
