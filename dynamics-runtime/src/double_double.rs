//! Double-double arithmetic: a number is an unevaluated sum hi + lo of two f64 with
//! |lo| ≤ ulp(hi)/2, about 106 significant bits (32 decimal digits).
//!
//! It implements [`Scalar`], so the generated code and the reference algorithms run in it
//! unchanged; their f64 and f32 errors are then measured against a value ~16 digits more
//! accurate. The operations are the error-free transformations of Dekker and Knuth
//! (two-sum, two-product with a fused multiply-add), each result renormalized; sine and
//! cosine reduce the angle by a double-double π/2 and sum their Taylor series to ~1e-32.
//! Not fast (≈10–20× f64): it is a measuring instrument.

use crate::float::Math;
use crate::scalar::Scalar;
use core::fmt;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use num_traits::{One, Zero};

/// A double-double number hi + lo.
#[derive(Clone, Copy, PartialEq, PartialOrd, Default)]
pub struct DoubleDouble {
    /// The leading part (the f64 nearest the value).
    pub hi: f64,
    /// The trailing part.
    pub lo: f64,
}

impl fmt::Debug for DoubleDouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:e} + {:e}", self.hi, self.lo)
    }
}

/// s + e = a + b exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// s + e = a + b exactly, for |a| ≥ |b|.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// p + e = a · b exactly (with a fused multiply-add).
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, <f64 as Math>::mul_add(a, b, -p))
}

impl DoubleDouble {
    /// The value of an f64, exactly.
    pub const fn new(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }

    /// π/2 to double-double precision.
    pub const HALF_PI: DoubleDouble = DoubleDouble {
        hi: core::f64::consts::FRAC_PI_2,
        lo: 6.123233995736766e-17,
    };

    /// The nearest f64.
    pub fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    fn from_parts(hi: f64, lo: f64) -> Self {
        let (hi, lo) = quick_two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }

    /// |x|.
    pub fn abs(self) -> Self {
        if self.hi < 0.0 {
            -self
        } else {
            self
        }
    }

    /// Sine and cosine by reduction to |r| ≤ π/4 and Taylor series.
    fn sin_cos_dd(self) -> (Self, Self) {
        if !self.hi.is_finite() {
            return (DoubleDouble::new(f64::NAN), DoubleDouble::new(f64::NAN));
        }
        let k = <f64 as Math>::round(self.hi / Self::HALF_PI.hi);
        let r = self - Self::HALF_PI * DoubleDouble::new(k);
        let r2 = r * r;
        // sin r = Σ (−1)ⁿ r^(2n+1)/(2n+1)!, cos r = Σ (−1)ⁿ r^(2n)/(2n)!; |r| ≤ 0.79, so 17
        // terms bring both below 1e-35.
        let (mut sin, mut cos) = (r, DoubleDouble::new(1.0));
        let (mut sin_term, mut cos_term) = (r, DoubleDouble::new(1.0));
        for n in 1..18 {
            let n = n as f64;
            sin_term = -(sin_term * r2) / DoubleDouble::new((2.0 * n) * (2.0 * n + 1.0));
            cos_term = -(cos_term * r2) / DoubleDouble::new((2.0 * n - 1.0) * (2.0 * n));
            sin += sin_term;
            cos += cos_term;
        }
        match (k as i64).rem_euclid(4) {
            0 => (sin, cos),
            1 => (cos, -sin),
            2 => (-sin, -cos),
            _ => (-cos, sin),
        }
    }
}

impl From<f64> for DoubleDouble {
    fn from(x: f64) -> Self {
        DoubleDouble::new(x)
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        let (s, e) = two_sum(self.hi, o.hi);
        let (t, f) = two_sum(self.lo, o.lo);
        let (s, e) = quick_two_sum(s, e + t);
        DoubleDouble::from_parts(s, e + f)
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let (p, e) = two_prod(self.hi, o.hi);
        DoubleDouble::from_parts(p, e + (self.hi * o.lo + self.lo * o.hi))
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        // Three quotient digits, each from the remainder of the previous.
        let q1 = self.hi / o.hi;
        let r = self - o * DoubleDouble::new(q1);
        let q2 = r.hi / o.hi;
        let r = r - o * DoubleDouble::new(q2);
        let q3 = r.hi / o.hi;
        DoubleDouble::from_parts(q1, q2) + DoubleDouble::new(q3)
    }
}

macro_rules! assign_ops {
    ($($trait:ident $method:ident $op:tt),*) => {$(
        impl $trait for DoubleDouble {
            #[inline]
            fn $method(&mut self, o: Self) {
                *self = *self $op o;
            }
        }
    )*};
}

assign_ops!(AddAssign add_assign +, SubAssign sub_assign -, MulAssign mul_assign *, DivAssign div_assign /);

impl Zero for DoubleDouble {
    fn zero() -> Self {
        DoubleDouble::new(0.0)
    }
    fn is_zero(&self) -> bool {
        self.hi == 0.0 && self.lo == 0.0
    }
}

impl One for DoubleDouble {
    fn one() -> Self {
        DoubleDouble::new(1.0)
    }
}

impl Scalar for DoubleDouble {
    fn from_f64(x: f64) -> Self {
        DoubleDouble::new(x)
    }
    fn sin(self) -> Self {
        self.sin_cos_dd().0
    }
    fn cos(self) -> Self {
        self.sin_cos_dd().1
    }
    fn sin_cos(self) -> (Self, Self) {
        self.sin_cos_dd()
    }
    fn sqrt(self) -> Self {
        if self.hi <= 0.0 {
            return DoubleDouble::new(<f64 as Math>::sqrt(self.hi));
        }
        // One Newton step from the f64 root doubles its 53 bits.
        let y = DoubleDouble::new(<f64 as Math>::sqrt(self.hi));
        y + (self - y * y) / (y * DoubleDouble::new(2.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dd(x: f64) -> DoubleDouble {
        DoubleDouble::new(x)
    }

    fn close(a: DoubleDouble, b: DoubleDouble, tolerance: f64) -> bool {
        (a - b).abs().to_f64() <= tolerance
    }

    #[test]
    fn arithmetic_carries_about_32_digits() {
        // 1/3 · 3 = 1 to 1e-32; (1 + 2⁻⁶⁰) − 1 = 2⁻⁶⁰, invisible in f64.
        assert!(close(dd(1.0) / dd(3.0) * dd(3.0), dd(1.0), 1e-32));
        let tiny = 2f64.powi(-60);
        assert_eq!((dd(1.0) + dd(tiny) - dd(1.0)).to_f64(), tiny);
        let two = dd(2.0);
        let root = two.sqrt();
        assert!(close(root * root, two, 1e-31));
        assert!(Scalar::sqrt(dd(-1.0)).hi.is_nan());
    }

    #[test]
    fn sine_and_cosine_to_about_1e_31() {
        for x in [-7.3, -1.0, 0.0, 0.3, 1.2, 2.5, 4.0, 10.0, 100.0] {
            let (s, c) = Scalar::sin_cos(dd(x));
            assert!(close(s * s + c * c, dd(1.0), 1e-30), "x = {x}");
            assert!(
                (s.to_f64() - x.sin()).abs() <= 2e-16 * (1.0 + x.abs()),
                "x = {x}"
            );
            assert!(
                (c.to_f64() - x.cos()).abs() <= 2e-16 * (1.0 + x.abs()),
                "x = {x}"
            );
        }
        // sin(π/6) = 1/2 with π/6 = (π/2)/3 in double-double.
        let (s, _) = Scalar::sin_cos(DoubleDouble::HALF_PI / dd(3.0));
        assert!(close(s, dd(0.5), 1e-31), "{s:?}");
        assert!(Scalar::sin(dd(f64::INFINITY)).hi.is_nan());
    }
}
