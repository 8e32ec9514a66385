//! The number type that the reference algorithms and the generated code compute with.
//!
//! Contract: a `Scalar` is a copyable field element with `sin`, `cos` and `sqrt`, plus an
//! exact-or-nearest conversion from `f64` for the model's constants. It deliberately has no
//! comparison and no branching operation, so that SIMD lanes (four states at once), dual
//! numbers (derivatives) and double-double (about 32 digits) can implement it later: the
//! dynamics never branch on data.

use crate::float::Math;
use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use num_traits::{One, Zero};

/// Arithmetic needed by the dynamics, generic over the number representation.
///
/// Implemented for `f32` and `f64`. The bounds are those of `nalgebra::Scalar` (`'static`,
/// `Clone`, `PartialEq`, `Debug`) and of its `ClosedAddAssign`, `ClosedSubAssign`,
/// `ClosedMulAssign` and `ClosedDivAssign`, written with `core`'s traits so that the trait
/// exists without std and nalgebra; nalgebra implements its traits for every type with
/// these bounds, so the reference algorithms (and users) use `Vector3<T>`, `Matrix3<T>` and
/// `Matrix6<T>` arithmetic on any `T: Scalar` without any further bound.
pub trait Scalar:
    'static
    + Clone
    + PartialEq
    + Debug
    + Copy
    + Zero
    + One
    + Add<Output = Self>
    + AddAssign
    + Sub<Output = Self>
    + SubAssign
    + Mul<Output = Self>
    + MulAssign
    + Div<Output = Self>
    + DivAssign
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
    /// `self · a + b` in the copy of a generated kernel that `isa` stands for
    /// ([`crate::isa::Isa::mul_add`], which generated code and the solve loops of
    /// [`crate::tree_ldlt`] call). The default is [`Scalar::mul_add`] in both copies; the
    /// wide copy of `f32` and `f64`, compiled for FMA, fuses (one instruction, one
    /// rounding), and [`crate::F64x4`]'s uses the proof an `Isa<true>` carries to fuse its
    /// four lanes in one AVX instruction.
    #[inline(always)]
    #[must_use]
    fn mul_add_on<const WIDE: bool>(self, a: Self, b: Self, isa: crate::isa::Isa<WIDE>) -> Self {
        let _ = isa;
        self.mul_add(a, b)
    }
    #[doc(hidden)]
    /// [`Scalar::sin_cos_array`] in the `WIDE` copy of a generated kernel: for `f64` the
    /// wide copy takes four angles per AVX register with fused steps
    /// ([`crate::fast_trig::avx2::sin_cos_array`]). The default is `sin_cos_array` in both.
    #[inline(always)]
    fn sin_cos_array_for<const WIDE: bool, const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        Self::sin_cos_array(x)
    }
    #[doc(hidden)]
    /// For generated code, not for users (hidden from the docs): runs a whole generated
    /// function, `wide` (its `WIDE = true` kernel) or `narrow`, handing it its copy's
    /// [`crate::isa::Isa`]. `f32` and `f64` choose at run time with [`crate::isa::run`];
    /// the default runs `narrow`, so other types never instantiate the wide kernel.
    #[inline(always)]
    fn run_kernel<R>(
        wide: impl FnOnce(crate::isa::Isa<true>) -> R,
        narrow: impl FnOnce(crate::isa::Isa<false>) -> R,
    ) -> R {
        let _ = wide;
        narrow(crate::isa::Isa::BASELINE)
    }
    #[doc(hidden)]
    /// [`Scalar::run_kernel`] for a generated `_into` function: the same choice of copy,
    /// `out` (the caller's output) handed to the copy that runs.
    #[inline(always)]
    fn run_kernel_into<O: ?Sized>(
        out: &mut O,
        wide: impl FnOnce(crate::isa::Isa<true>, &mut O),
        narrow: impl FnOnce(crate::isa::Isa<false>, &mut O),
    ) {
        let _ = wide;
        narrow(crate::isa::Isa::BASELINE, out);
    }
    #[doc(hidden)]
    /// [`Scalar::run_piece`] for a piece of a generated `_into` function: `out` handed to
    /// the copy that runs.
    #[inline(always)]
    fn run_piece_into<O: ?Sized, R>(
        out: &mut O,
        wide: impl FnOnce(crate::isa::Isa<true>, &mut O) -> R,
        narrow: impl FnOnce(crate::isa::Isa<false>, &mut O) -> R,
    ) -> R {
        let _ = wide;
        crate::isa::out_of_line(|| narrow(crate::isa::Isa::BASELINE, out))
    }
    #[doc(hidden)]
    /// For generated code, not for users: runs a generated function (of a mechanism declared
    /// with `lanes: true;`) whose expansion computes isomorphic limbs (or a matrix's
    /// columns) side by side in [`crate::pack::P4`]s, either
    /// that `packed` body or its `unpacked` twin, the same operations one lane at a time.
    /// The default runs `packed`, which fills the SIMD unit with one state's limbs; types
    /// that are already several states side by side ([`crate::F64x4`], [`crate::F32x8`])
    /// run `unpacked`, whose every operation fills their lanes, where four limbs of four
    /// states would be four registers to an operation. The body not run is never
    /// instantiated. `arg` is handed to the body that runs: `out` for an `_into` function,
    /// `()` for one that returns its result.
    #[inline(always)]
    fn run_packed<A, R>(arg: A, packed: impl FnOnce(A) -> R, unpacked: impl FnOnce(A) -> R) -> R {
        let _ = unpacked;
        packed(arg)
    }
    #[doc(hidden)]
    /// Runs one piece of a split generated function like [`Scalar::run_kernel`], each copy
    /// out of line ([`crate::isa::run_piece`]), so that the pieces stay separate functions.
    #[inline(always)]
    fn run_piece<R>(
        wide: impl FnOnce(crate::isa::Isa<true>) -> R,
        narrow: impl FnOnce(crate::isa::Isa<false>) -> R,
    ) -> R {
        let _ = wide;
        crate::isa::out_of_line(|| narrow(crate::isa::Isa::BASELINE))
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
                <$t as Math>::sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                <$t as Math>::cos(self)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t as Math>::sqrt(self)
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                <$t as Math>::sin_cos(self)
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                if cfg!(target_feature = "fma") {
                    <$t as Math>::mul_add(self, a, b)
                } else {
                    self * a + b
                }
            }
            #[inline(always)]
            fn mul_add_on<const WIDE: bool>(
                self,
                a: Self,
                b: Self,
                isa: crate::isa::Isa<WIDE>,
            ) -> Self {
                let _ = isa;
                if WIDE {
                    <$t as Math>::mul_add(self, a, b)
                } else {
                    Scalar::mul_add(self, a, b)
                }
            }
            #[inline(always)]
            fn run_kernel<R>(
                wide: impl FnOnce(crate::isa::Isa<true>) -> R,
                narrow: impl FnOnce(crate::isa::Isa<false>) -> R,
            ) -> R {
                crate::isa::run(wide, narrow)
            }
            #[inline(always)]
            fn run_kernel_into<O: ?Sized>(
                out: &mut O,
                wide: impl FnOnce(crate::isa::Isa<true>, &mut O),
                narrow: impl FnOnce(crate::isa::Isa<false>, &mut O),
            ) {
                crate::isa::run_with(out, wide, narrow);
            }
            #[inline(always)]
            fn run_piece_into<O: ?Sized, R>(
                out: &mut O,
                wide: impl FnOnce(crate::isa::Isa<true>, &mut O) -> R,
                narrow: impl FnOnce(crate::isa::Isa<false>, &mut O) -> R,
            ) -> R {
                crate::isa::run_piece_with(out, wide, narrow)
            }
            #[inline(always)]
            fn run_piece<R>(
                wide: impl FnOnce(crate::isa::Isa<true>) -> R,
                narrow: impl FnOnce(crate::isa::Isa<false>) -> R,
            ) -> R {
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
        #[cfg(all(target_arch = "x86_64", feature = "std"))]
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
    /// when the build targets FMA hardware, `mul_add_on` with the wide copy's `Isa` (the
    /// AVX2 + FMA kernels') always.
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
        // The kernels' copies: the baseline one as `mul_add`, the wide one always fused
        // (where the CPU has a wide copy to run).
        let baseline = crate::isa::Isa::BASELINE;
        assert_eq!(
            <f64 as Scalar>::mul_add_on(a, b, c, baseline).to_bits(),
            expected.to_bits()
        );
        let wide = crate::isa::run(
            |isa| Some(<f64 as Scalar>::mul_add_on(a, b, c, isa)),
            |_| None,
        );
        if let Some(wide) = wide {
            assert_eq!(wide.to_bits(), f64::mul_add(a, b, c).to_bits());
        }
    }

    #[test]
    fn f32_rounds_to_nearest() {
        assert_eq!(<f32 as Scalar>::from_f64(0.1), 0.1_f32);
        assert_eq!(<f64 as Scalar>::from_f64(0.1), 0.1_f64);
    }

    /// sin x and cos x to 36 digits, computed for this test by their Taylor series in
    /// 200-digit decimal arithmetic (no libm involved). Every x is exact in f32 and f64.
    const TRUE_SIN_COS: [(f64, &str, &str); 9] = [
        (
            0.5,
            "4.79425538604203000273287935215571388e-1",
            "8.77582561890372716116281582603829652e-1",
        ),
        (
            1.0,
            "8.41470984807896506652502321630299000e-1",
            "5.40302305868139717400936607442976604e-1",
        ),
        (
            2.0,
            "9.09297426825681695396019865911744843e-1",
            "-4.16146836547142386997568229500762190e-1",
        ),
        (
            3.0,
            "1.41120008059867222100744802808110280e-1",
            "-9.89992496600445457271572794731261302e-1",
        ),
        (
            -0.25,
            "-2.47403959254522929596848704849389196e-1",
            "9.68912421710644784144595449494189200e-1",
        ),
        (
            10.0,
            "-5.44021110889369813404747661851377282e-1",
            "-8.39071529076452452258863947824064835e-1",
        ),
        (
            100.0,
            "-5.06365641109758793656557610459785432e-1",
            "8.62318872287683934101938513950842536e-1",
        ),
        (
            0.0009765625,
            "9.76562344779578298906910168119786367e-4",
            "9.99999523162879692486369202949889069e-1",
        ),
        (
            -7.5,
            "-9.37999976774738857948463798149047236e-1",
            "3.46635317835025810971619336171895578e-1",
        ),
    ];

    /// Distance in units in the last place: how many representable f64 lie between a and b
    /// (0 when equal, 1 for neighbours), across zero too.
    fn ulps_f64(a: f64, b: f64) -> u64 {
        let ordered = |x: f64| {
            let bits = x.to_bits() as i64;
            if bits < 0 {
                i64::MIN - bits
            } else {
                bits
            }
        };
        ordered(a).abs_diff(ordered(b))
    }

    /// [`ulps_f64`] for f32.
    fn ulps_f32(a: f32, b: f32) -> u64 {
        let ordered = |x: f32| {
            let bits = i64::from(x.to_bits() as i32);
            if bits < 0 {
                i64::from(i32::MIN) - bits
            } else {
                bits
            }
        };
        ordered(a).abs_diff(ordered(b))
    }

    /// The nearest float to a decimal string of [`TRUE_SIN_COS`] (Rust's parsing rounds
    /// correctly; 36 digits decide the rounding of every entry).
    fn nearest<F: std::str::FromStr>(digits: &str) -> F {
        match digits.parse() {
            Ok(x) => x,
            Err(_) => panic!("`{digits}` is a number"),
        }
    }

    /// The scalar trigonometry against the true values: std's `f64::sin`/`f64::cos` (what
    /// `Scalar::sin`, `cos` and `sin_cos` are for f64 and f32) within 1 ulp of the correctly
    /// rounded value, as the platform's libm promises; the generated code's batched
    /// `sin_cos_array` (both kernel copies) within 2 ulp, its documented 1 ulp from std plus
    /// std's own. f32 within 1 ulp of the correctly rounded f32.
    #[test]
    fn trig_is_within_an_ulp_of_the_true_values() {
        let x: [f64; 9] = TRUE_SIN_COS.map(|(x, _, _)| x);
        let arrays = [
            <f64 as Scalar>::sin_cos_array(x),
            <f64 as Scalar>::sin_cos_array_for::<false, 9>(x),
            <f64 as Scalar>::sin_cos_array_for::<true, 9>(x),
        ];
        for (i, (x, sin, cos)) in TRUE_SIN_COS.into_iter().enumerate() {
            let (sin64, cos64) = (nearest::<f64>(sin), nearest::<f64>(cos));
            let pair = Scalar::sin_cos(x);
            let scalar = [
                ("std sin", x.sin(), sin64),
                ("std cos", x.cos(), cos64),
                ("Scalar::sin", Scalar::sin(x), sin64),
                ("Scalar::cos", Scalar::cos(x), cos64),
                ("Scalar::sin_cos.0", pair.0, sin64),
                ("Scalar::sin_cos.1", pair.1, cos64),
            ];
            for (what, got, truth) in scalar {
                let ulps = ulps_f64(got, truth);
                assert!(
                    ulps <= 1,
                    "{what}({x}) = {got:e}, true {truth:e}: {ulps} ulp"
                );
            }
            for (copy, (s, c)) in arrays.iter().enumerate() {
                for (what, got, truth) in [("sin", s[i], sin64), ("cos", c[i], cos64)] {
                    let ulps = ulps_f64(got, truth);
                    assert!(
                        ulps <= 2,
                        "sin_cos_array copy {copy}: {what}({x}) = {got:e}, true {truth:e}: {ulps} ulp"
                    );
                }
            }
            let x32 = x as f32;
            let (sin32, cos32) = (nearest::<f32>(sin), nearest::<f32>(cos));
            let pair32 = Scalar::sin_cos(x32);
            for (what, got, truth) in [
                ("Scalar::sin", Scalar::sin(x32), sin32),
                ("Scalar::cos", Scalar::cos(x32), cos32),
                ("Scalar::sin_cos.0", pair32.0, sin32),
                ("Scalar::sin_cos.1", pair32.1, cos32),
            ] {
                let ulps = ulps_f32(got, truth);
                assert!(
                    ulps <= 1,
                    "f32 {what}({x}) = {got:e}, true {truth:e}: {ulps} ulp"
                );
            }
        }
    }

    #[test]
    fn ulp_distance_counts_representable_numbers() {
        assert_eq!(ulps_f64(1.0, 1.0), 0);
        assert_eq!(ulps_f64(1.0, 1.0 + f64::EPSILON), 1);
        assert_eq!(ulps_f64(-0.0, 0.0), 0);
        assert_eq!(ulps_f64(-f64::from_bits(1), f64::from_bits(1)), 2);
        assert_eq!(ulps_f32(1.0, 1.0 + f32::EPSILON), 1);
        assert_eq!(ulps_f32(-f32::from_bits(1), f32::from_bits(1)), 2);
    }

    #[test]
    fn sqrt_of_a_negative_number_is_nan() {
        assert!(Scalar::sqrt(-1.0_f64).is_nan());
        assert!(Scalar::sqrt(-1.0_f32).is_nan());
        assert_eq!(Scalar::sqrt(2.25_f64), 1.5);
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
