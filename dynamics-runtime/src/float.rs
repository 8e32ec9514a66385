//! The `f32`/`f64` functions that std provides as inherent methods and `core` does not:
//! sine, cosine, both together, square root, fused multiply-add and rounding.
//!
//! Contract: with the `std` feature each function *is* std's method (`f64::sin`, …), so the
//! runtime computes bit for bit what it computed before it could build without std. Without
//! `std` each is the `libm` crate's function of the same name (a pure-Rust port of musl's
//! libm: `sin`, `cos`, `sincos`, `sqrt`, `fma`, `round` and their `f32` twins): correctly
//! rounded for `sqrt`, `fma` and `round`, within an ulp for the trigonometry, like std's.
//!
//! They are associated functions of [`Math`], not methods, and called as
//! `<f64 as Math>::sin(x)`, so that no method lookup can pick one over an inherent method of
//! the same name (or the reverse).

/// The float functions of this module, for `f32` and `f64`.
pub(crate) trait Math: Copy {
    /// Sine (radians).
    fn sin(x: Self) -> Self;
    /// Cosine (radians).
    fn cos(x: Self) -> Self;
    /// `(sin x, cos x)`.
    fn sin_cos(x: Self) -> (Self, Self);
    /// Square root (NaN below zero).
    fn sqrt(x: Self) -> Self;
    /// `x · a + b` with one rounding.
    fn mul_add(x: Self, a: Self, b: Self) -> Self;
    /// The nearest integer, halves away from zero.
    fn round(x: Self) -> Self;
}

/// `Math` for a float type: std's methods with `std`, else the named `libm` functions.
macro_rules! impl_math {
    ($t:ty, $sin:ident, $cos:ident, $sin_cos:ident, $sqrt:ident, $fma:ident, $round:ident) => {
        #[cfg(feature = "std")]
        impl Math for $t {
            #[inline(always)]
            fn sin(x: Self) -> Self {
                x.sin()
            }
            #[inline(always)]
            fn cos(x: Self) -> Self {
                x.cos()
            }
            #[inline(always)]
            fn sin_cos(x: Self) -> (Self, Self) {
                x.sin_cos()
            }
            #[inline(always)]
            fn sqrt(x: Self) -> Self {
                x.sqrt()
            }
            #[inline(always)]
            fn mul_add(x: Self, a: Self, b: Self) -> Self {
                x.mul_add(a, b)
            }
            #[inline(always)]
            fn round(x: Self) -> Self {
                x.round()
            }
        }

        #[cfg(not(feature = "std"))]
        impl Math for $t {
            #[inline(always)]
            fn sin(x: Self) -> Self {
                libm::$sin(x)
            }
            #[inline(always)]
            fn cos(x: Self) -> Self {
                libm::$cos(x)
            }
            #[inline(always)]
            fn sin_cos(x: Self) -> (Self, Self) {
                libm::$sin_cos(x)
            }
            #[inline(always)]
            fn sqrt(x: Self) -> Self {
                libm::$sqrt(x)
            }
            #[inline(always)]
            fn mul_add(x: Self, a: Self, b: Self) -> Self {
                libm::$fma(x, a, b)
            }
            #[inline(always)]
            fn round(x: Self) -> Self {
                libm::$round(x)
            }
        }
    };
}

impl_math!(f64, sin, cos, sincos, sqrt, fma, round);
impl_math!(f32, sinf, cosf, sincosf, sqrtf, fmaf, roundf);

#[cfg(test)]
mod tests {
    use super::Math;

    /// The functions against values exact in binary (or whose rounding is known), in
    /// whichever build this is: std's methods or libm's.
    #[test]
    fn exact_cases() {
        assert_eq!(<f64 as Math>::sqrt(2.25), 1.5);
        assert_eq!(<f32 as Math>::sqrt(2.25), 1.5);
        assert!(<f64 as Math>::sqrt(-1.0).is_nan());
        assert_eq!(<f64 as Math>::round(2.5), 3.0);
        assert_eq!(<f64 as Math>::round(-2.5), -3.0);
        assert_eq!(<f32 as Math>::round(0.49), 0.0);
        // 0.1 · 10 − 1 is 5.55e-17 with one rounding, 0 with two.
        assert_eq!(
            <f64 as Math>::mul_add(0.1, 10.0, -1.0),
            5.551_115_123_125_783e-17
        );
        assert_eq!(<f64 as Math>::sin(0.0), 0.0);
        assert_eq!(<f64 as Math>::cos(0.0), 1.0);
        assert_eq!(<f32 as Math>::sin_cos(0.0), (0.0, 1.0));
        let (s, c) = <f64 as Math>::sin_cos(0.5);
        assert_eq!((s, c), (<f64 as Math>::sin(0.5), <f64 as Math>::cos(0.5)));
        assert!((s - 0.479_425_538_604_203).abs() < 1e-16);
    }
}
