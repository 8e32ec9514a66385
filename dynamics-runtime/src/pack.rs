//! Four values of one scalar type side by side, for generated code that computes several
//! columns of a matrix, or a robot's isomorphic limbs, in one pass: [`P4`].
//!
//! Each operation on a `P4<T>` is `T`'s operation on every lane, lane k of the result from
//! lane k of the operands: bit for bit the four scalar operations, so a packed generated
//! function returns what the same function expanded one value at a time returns. For
//! `T = f64` the four lanes go through [`crate::F64x4`] (itself lane by lane `f64`'s
//! arithmetic, the fused product included): in the AVX2 + FMA copy of a kernel one AVX
//! instruction does the four, where the compiler left to itself with four separate `f64`
//! kept most of them scalar (measured on the humanoid's mass matrix: 0.94 of the unpacked
//! function's time, against 0.83 through `F64x4`). Other types run lane by lane.
//!
//! Not for users: the generated code names it.

use crate::isa::Isa;
use crate::{F64x4, Scalar};
use core::any::Any;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// Four lanes of `T`; see the [module documentation](self).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct P4<T>(pub [T; 4]);

/// `[x, y, z]` as `F64x4`s when `T` is `f64`.
#[inline]
fn as_f64x4<T: Scalar>(x: [&[T; 4]; 3]) -> Option<[F64x4; 3]> {
    let one = |v: &[T; 4]| {
        (v as &dyn Any)
            .downcast_ref::<[f64; 4]>()
            .map(|v| F64x4::new(*v))
    };
    Some([one(x[0])?, one(x[1])?, one(x[2])?])
}

/// The lanes of an `F64x4` result as `[T; 4]` (`T` is `f64` where this is called).
#[inline]
fn from_f64x4<T: Scalar>(r: F64x4) -> Option<[T; 4]> {
    (&r.to_array() as &dyn Any)
        .downcast_ref::<[T; 4]>()
        .copied()
}

/// `on_f64x4` when `T` is `f64`, else `lane` on each lane of `x`, `y`, `z`.
#[inline]
fn lanes<T: Scalar>(
    [x, y, z]: [[T; 4]; 3],
    on_f64x4: impl Fn(F64x4, F64x4, F64x4) -> F64x4,
    lane: impl Fn(T, T, T) -> T,
) -> P4<T> {
    if let Some([a, b, c]) = as_f64x4([&x, &y, &z]) {
        if let Some(r) = from_f64x4(on_f64x4(a, b, c)) {
            return P4(r);
        }
    }
    P4([
        lane(x[0], y[0], z[0]),
        lane(x[1], y[1], z[1]),
        lane(x[2], y[2], z[2]),
        lane(x[3], y[3], z[3]),
    ])
}

impl<T: Scalar> P4<T> {
    /// `x` in every lane.
    #[inline]
    #[must_use]
    pub fn splat(x: T) -> Self {
        P4([x; 4])
    }

    /// `x · a + b` lane by lane, fused where [`Isa::mul_add`] fuses.
    #[inline]
    #[must_use]
    pub fn mul_add_on<const WIDE: bool>(x: Self, a: Self, b: Self, isa: Isa<WIDE>) -> Self {
        lanes(
            [x.0, a.0, b.0],
            |x, a, b| isa.mul_add(x, a, b),
            |x, a, b| isa.mul_add(x, a, b),
        )
    }
}

impl<T: Scalar> Add for P4<T> {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        lanes([self.0, b.0, b.0], |x, y, _| x + y, |x, y, _| x + y)
    }
}

impl<T: Scalar> Sub for P4<T> {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        lanes([self.0, b.0, b.0], |x, y, _| x - y, |x, y, _| x - y)
    }
}

impl<T: Scalar> Mul for P4<T> {
    type Output = Self;
    #[inline]
    fn mul(self, b: Self) -> Self {
        lanes([self.0, b.0, b.0], |x, y, _| x * y, |x, y, _| x * y)
    }
}

impl<T: Scalar> Div for P4<T> {
    type Output = Self;
    #[inline]
    fn div(self, b: Self) -> Self {
        lanes([self.0, b.0, b.0], |x, y, _| x / y, |x, y, _| x / y)
    }
}

impl<T: Scalar> Neg for P4<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        lanes([self.0, self.0, self.0], |x, _, _| -x, |x, _, _| -x)
    }
}

#[cfg(test)]
mod tests {
    use super::P4;
    use crate::isa::Isa;

    /// Awkward values: signed zeros, subnormals, huge and tiny magnitudes, NaN.
    fn values() -> [[f64; 4]; 3] {
        [
            [1.0 / 3.0, -0.0, 1e300, f64::MIN_POSITIVE / 3.0],
            [3.0, 7.5e-310, -1e10, f64::NAN],
            [-2.0 / 7.0, 0.0, 1e290, 1.0],
        ]
    }

    fn same<T: PartialEq + Copy + Into<f64>>(a: [T; 4], b: [T; 4]) -> bool {
        a.iter().zip(&b).all(|(&x, &y)| {
            let (x, y): (f64, f64) = (x.into(), y.into());
            x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan())
        })
    }

    #[test]
    fn f64_lanes_are_the_scalar_operations_bit_for_bit() {
        let [x, y, z] = values();
        let (px, py, pz) = (P4(x), P4(y), P4(z));
        let each = |f: fn(f64, f64, f64) -> f64| std::array::from_fn(|k| f(x[k], y[k], z[k]));
        assert!(same((px + py).0, each(|a, b, _| a + b)));
        assert!(same((px - py).0, each(|a, b, _| a - b)));
        assert!(same((px * py).0, each(|a, b, _| a * b)));
        assert!(same((px / py).0, each(|a, b, _| a / b)));
        assert!(same((-px).0, each(|a, _, _| -a)));
        let isa = Isa::BASELINE;
        let fused = P4::mul_add_on(px, py, pz, isa).0;
        assert!(same(
            fused,
            std::array::from_fn(|k| isa.mul_add(x[k], y[k], z[k]))
        ));
        assert!(same(P4::splat(2.5).0, [2.5; 4]));
    }

    #[test]
    fn other_types_run_lane_by_lane() {
        let [x, y, _] = values().map(|v| v.map(|a| a as f32));
        let each = |f: fn(f32, f32) -> f32| std::array::from_fn(|k| f(x[k], y[k]));
        assert!(same((P4(x) * P4(y)).0, each(|a, b| a * b)));
        assert!(same((P4(x) - P4(y)).0, each(|a, b| a - b)));
    }
}
