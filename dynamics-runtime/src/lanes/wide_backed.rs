//! The `wide`-backed lanes: [`F32x8`] always, [`F64x4`] in a build with AVX
//! (`-C target-cpu=native` on an AVX CPU): `wide::f32x8` and `wide::f64x4` in a newtype,
//! every generated kernel run in its baseline copy ([`Scalar::run_kernel`]'s default); the
//! sines and cosines by the runtime's `fast_trig` kernel on the lanes ([`super`]).

use super::Lanes;
use crate::fast_trig::{self, Lane, LaneBits};
use crate::Scalar;
use core::fmt;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use num_traits::{One, Zero};

impl Lane for wide::f64x4 {
    type Bits = wide::u64x4;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        wide::f64x4::splat(x)
    }
    /// Lane by lane through `f64::mul_add` (one rounding on every target; slow without
    /// FMA): only the fused kernel calls it, and the lanes use the other one.
    #[inline(always)]
    fn fused_mul_add(self, a: Self, b: Self) -> Self {
        let (x, a, b) = (self.to_array(), a.to_array(), b.to_array());
        wide::f64x4::new(core::array::from_fn(|i| {
            <f64 as crate::float::Math>::mul_add(x[i], a[i], b[i])
        }))
    }
    #[inline(always)]
    fn to_bits(self) -> wide::u64x4 {
        wide::f64x4::to_bits(self)
    }
    #[inline(always)]
    fn from_bits(bits: wide::u64x4) -> Self {
        wide::f64x4::from_bits(bits)
    }
}

impl LaneBits for wide::u64x4 {
    #[inline(always)]
    fn splat(x: u64) -> Self {
        wide::u64x4::splat(x)
    }
    #[inline(always)]
    fn wrapping_add(self, other: Self) -> Self {
        self + other // wide's integer `+` wraps
    }
    #[inline(always)]
    fn wrapping_sub(self, other: Self) -> Self {
        self - other // wide's integer `−` wraps
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

/// The sines and cosines of eight `f32` angles: each widened to `f64` (exact), the `f64`
/// kernel on two vectors of four, each result rounded to `f32`.
#[inline(always)]
fn sin_cos_f32x8(x: wide::f32x8) -> (wide::f32x8, wide::f32x8) {
    let x = x.to_array();
    let half = |h: usize| wide::f64x4::new(core::array::from_fn(|i| f64::from(x[4 * h + i])));
    let (s0, c0) = fast_trig::sin_cos_lanes(half(0));
    let (s1, c1) = fast_trig::sin_cos_lanes(half(1));
    let narrow = |lo: wide::f64x4, hi: wide::f64x4| {
        let (lo, hi) = (lo.to_array(), hi.to_array());
        let mut out = [0.0_f32; 8];
        for i in 0..4 {
            (out[i], out[i + 4]) = (lo[i] as f32, hi[i] as f32);
        }
        wide::f32x8::new(out)
    };
    (narrow(s0, s1), narrow(c0, c1))
}

macro_rules! lanes_type {
    (
        $(#[$doc:meta])*
        $name:ident, $wide:ident, $elem:ident, $n:literal,
        sin_cos: $sin_cos:expr
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Default)]
        #[repr(transparent)]
        pub struct $name(wide::$wide);

        impl $name {
            /// The number of lanes.
            pub const LANES: usize = $n;

            /// The lanes, in order.
            #[inline(always)]
            #[must_use]
            pub const fn new(lanes: [$elem; $n]) -> Self {
                Self(wide::$wide::new(lanes))
            }

            /// Every lane `x`.
            #[inline(always)]
            #[must_use]
            pub const fn splat(x: $elem) -> Self {
                Self(wide::$wide::splat(x))
            }

            /// Lane `i` is `f(i)`, called for `i` = 0, 1, … in order.
            #[inline(always)]
            #[must_use]
            pub fn from_fn(f: impl FnMut(usize) -> $elem) -> Self {
                Self::new(core::array::from_fn(f))
            }

            /// The lanes, in order.
            #[inline(always)]
            #[must_use]
            pub const fn to_array(self) -> [$elem; $n] {
                self.0.to_array()
            }

            /// Lane `i`, or `None` when `i` is not below [`Self::LANES`].
            #[inline(always)]
            #[must_use]
            pub fn get(self, i: usize) -> Option<$elem> {
                self.to_array().get(i).copied()
            }
        }

        impl From<[$elem; $n]> for $name {
            #[inline(always)]
            fn from(lanes: [$elem; $n]) -> Self {
                Self::new(lanes)
            }
        }

        impl From<$name> for [$elem; $n] {
            #[inline(always)]
            fn from(x: $name) -> Self {
                x.to_array()
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_tuple(stringify!($name)).field(&self.to_array()).finish()
            }
        }

        /// Every lane equal (IEEE: a NaN lane is unequal to everything, `+0 == −0`).
        impl PartialEq for $name {
            #[inline]
            fn eq(&self, other: &Self) -> bool {
                self.to_array() == other.to_array()
            }
        }

        lanes_type!(@binary $name, Add, add, AddAssign, add_assign, +);
        lanes_type!(@binary $name, Sub, sub, SubAssign, sub_assign, -);
        lanes_type!(@binary $name, Mul, mul, MulAssign, mul_assign, *);
        lanes_type!(@binary $name, Div, div, DivAssign, div_assign, /);

        /// Flips each lane's sign bit (as `-x` on the scalar type: `−(+0) = −0`).
        impl Neg for $name {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Self(-self.0)
            }
        }

        impl Zero for $name {
            #[inline(always)]
            fn zero() -> Self {
                Self::splat(0.0)
            }
            /// Every lane ±0.
            #[inline]
            fn is_zero(&self) -> bool {
                self.to_array().iter().all(|x| *x == 0.0)
            }
        }

        impl One for $name {
            #[inline(always)]
            fn one() -> Self {
                Self::splat(1.0)
            }
        }

        impl Scalar for $name {
            /// The unpacked body: the lanes already hold several states.
            #[inline(always)]
            fn run_packed<A, R>(arg: A, packed: impl FnOnce(A) -> R, unpacked: impl FnOnce(A) -> R) -> R {
                let _ = packed;
                unpacked(arg)
            }
            /// Every lane `x` as the scalar type's `from_f64` gives it.
            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                Self::splat(<$elem as Scalar>::from_f64(x))
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
                Self(self.0.sqrt())
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                let (s, c) = $sin_cos(self.0);
                (Self(s), Self(c))
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                // The scalar type's rule (`impl_float_scalar!` in scalar.rs); with FMA in
                // the build, `wide` fuses lane by lane.
                if cfg!(target_feature = "fma") {
                    Self(self.0.mul_add(a.0, b.0))
                } else {
                    self * a + b
                }
            }
        }

        impl Lanes for $name {
            type Element = $elem;
            const LANES: usize = $n;
            #[inline(always)]
            fn splat(x: $elem) -> Self {
                Self::splat(x)
            }
            #[inline(always)]
            fn from_fn(f: impl FnMut(usize) -> $elem) -> Self {
                Self::from_fn(f)
            }
            #[inline(always)]
            fn get(self, i: usize) -> Option<$elem> {
                Self::get(self, i)
            }
        }
    };
    (@binary $name:ident, $op:ident, $f:ident, $op_assign:ident, $f_assign:ident, $sym:tt) => {
        impl $op for $name {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                Self(self.0 $sym rhs.0)
            }
        }
        impl $op_assign for $name {
            #[inline(always)]
            fn $f_assign(&mut self, rhs: Self) {
                *self = *self $sym rhs;
            }
        }
    };
}

#[cfg(target_feature = "avx")]
lanes_type!(
    /// Four `f64` lanes: a [`Scalar`] that runs a generated function on four states at once,
    /// each lane bit for bit the `f64` computation (see the [module documentation](super) for
    /// the exact contract, sines and cosines included).
    ///
    /// ```
    /// use dynamics_runtime::{F64x4, Scalar};
    /// let x = F64x4::new([0.0, 0.5, 1.0, 2.0]);
    /// let y = x * x + F64x4::splat(1.0);
    /// assert_eq!(y.to_array(), [1.0, 1.25, 2.0, 5.0]);
    /// assert_eq!(y.get(3), Some(5.0));
    /// assert_eq!(Scalar::sqrt(y).to_array()[3], 5.0_f64.sqrt());
    /// ```
    F64x4, f64x4, f64, 4,
    sin_cos: fast_trig::sin_cos_lanes
);

lanes_type!(
    /// Eight `f32` lanes: a [`Scalar`] that runs a generated function on eight states at
    /// once, each lane's arithmetic bit for bit the `f32` computation, its sines and cosines
    /// within 1 ulp of `f32`'s (see the [module documentation](super)).
    ///
    /// ```
    /// use dynamics_runtime::F32x8;
    /// let x = F32x8::from_fn(|i| i as f32);
    /// assert_eq!((x + x).to_array(), [0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0]);
    /// ```
    F32x8, f32x8, f32, 8,
    sin_cos: sin_cos_f32x8
);
