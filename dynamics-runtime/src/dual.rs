//! Dual numbers: forward-mode differentiation through any function generic over [`Scalar`].

use crate::scalar::Scalar;
use core::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};
use num_traits::{One, Zero};

/// A value and its derivative along one direction.
///
/// A dual number x + ε ẋ, with ε² = 0, carries a value and its derivative along one
/// direction. Every operation applies the chain rule to the derivative part:
///
/// ```text
/// (a + ε ȧ) ± (b + ε ḃ) = a ± b + ε (ȧ ± ḃ)
/// (a + ε ȧ) · (b + ε ḃ) = a b + ε (ȧ b + a ḃ)
/// (a + ε ȧ) / (b + ε ḃ) = a / b + ε (ȧ b − a ḃ) / b²
/// sin(a + ε ȧ) = sin a + ε ȧ cos a,   cos(a + ε ȧ) = cos a − ε ȧ sin a
/// √(a + ε ȧ) = √a + ε ȧ / (2 √a)
/// ```
///
/// so f(x + ε ẋ) = f(x) + ε f′(x) ẋ exactly (no step size, no truncation error), for every
/// function built from these operations: every generated function and the runtime
/// [`Reference`](crate::Reference). One call gives one column of a Jacobian: seed the
/// inputs with the direction ẋ (e.g. `Dual::variable(q[j])` for column j of ∂/∂q, the other
/// inputs `Dual::constant`) and read [`Dual::derivative`] of the outputs.
///
/// ```
/// use dynamics_runtime::{Dual, Scalar};
/// // d/dx (x sin x) at x = 2: sin 2 + 2 cos 2.
/// let x = Dual::variable(2.0_f64);
/// let y = x * x.sin();
/// assert!((y.derivative - (2.0_f64.sin() + 2.0 * 2.0_f64.cos())).abs() < 1e-15);
/// ```
///
/// For a free-floating base the derivative with respect to q in the tangent space (the one
/// the generated `*_derivatives` take) seeds the configuration through
/// [`integrate_configuration`](crate::integrate_configuration): q(t) = q ⊕ t e_j at
/// t = `Dual::variable(0.0)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<T> {
    /// The value, a.
    pub value: T,
    /// Its derivative along the seeded direction, ȧ.
    pub derivative: T,
}

impl<T: Scalar> Dual<T> {
    /// `value + ε derivative`.
    pub fn new(value: T, derivative: T) -> Self {
        Dual { value, derivative }
    }

    /// The variable differentiated by: derivative 1.
    pub fn variable(value: T) -> Self {
        Dual::new(value, T::one())
    }

    /// A constant: derivative 0.
    pub fn constant(value: T) -> Self {
        Dual::new(value, T::zero())
    }
}

impl<T: Scalar> Add for Dual<T> {
    type Output = Self;
    fn add(self, b: Self) -> Self {
        Dual::new(self.value + b.value, self.derivative + b.derivative)
    }
}

impl<T: Scalar> Sub for Dual<T> {
    type Output = Self;
    fn sub(self, b: Self) -> Self {
        Dual::new(self.value - b.value, self.derivative - b.derivative)
    }
}

impl<T: Scalar> Mul for Dual<T> {
    type Output = Self;
    fn mul(self, b: Self) -> Self {
        Dual::new(
            self.value * b.value,
            self.derivative * b.value + self.value * b.derivative,
        )
    }
}

impl<T: Scalar> Div for Dual<T> {
    type Output = Self;
    fn div(self, b: Self) -> Self {
        let quotient = self.value / b.value;
        // (ȧ − (a / b) ḃ) / b: the quotient rule with one division fewer.
        Dual::new(
            quotient,
            (self.derivative - quotient * b.derivative) / b.value,
        )
    }
}

impl<T: Scalar> Neg for Dual<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Dual::new(-self.value, -self.derivative)
    }
}

impl<T: Scalar> AddAssign for Dual<T> {
    fn add_assign(&mut self, b: Self) {
        *self = *self + b;
    }
}

impl<T: Scalar> SubAssign for Dual<T> {
    fn sub_assign(&mut self, b: Self) {
        *self = *self - b;
    }
}

impl<T: Scalar> MulAssign for Dual<T> {
    fn mul_assign(&mut self, b: Self) {
        *self = *self * b;
    }
}

impl<T: Scalar> DivAssign for Dual<T> {
    fn div_assign(&mut self, b: Self) {
        *self = *self / b;
    }
}

impl<T: Scalar> Zero for Dual<T> {
    fn zero() -> Self {
        Dual::constant(T::zero())
    }
    fn is_zero(&self) -> bool {
        self.value.is_zero() && self.derivative.is_zero()
    }
}

impl<T: Scalar> One for Dual<T> {
    fn one() -> Self {
        Dual::constant(T::one())
    }
}

impl<T: Scalar> Scalar for Dual<T> {
    fn from_f64(x: f64) -> Self {
        Dual::constant(T::from_f64(x))
    }
    fn sin(self) -> Self {
        let (sin, cos) = self.value.sin_cos();
        Dual::new(sin, self.derivative * cos)
    }
    fn cos(self) -> Self {
        let (sin, cos) = self.value.sin_cos();
        Dual::new(cos, -(self.derivative * sin))
    }
    fn sin_cos(self) -> (Self, Self) {
        let (sin, cos) = self.value.sin_cos();
        (
            Dual::new(sin, self.derivative * cos),
            Dual::new(cos, -(self.derivative * sin)),
        )
    }
    fn sqrt(self) -> Self {
        let root = self.value.sqrt();
        Dual::new(root, self.derivative / (root + root))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule against the derivative written out by hand, at a few points.
    #[test]
    fn every_operation_applies_the_chain_rule() {
        for x in [0.3_f64, 1.7, -2.2] {
            let d = Dual::variable(x);
            let c = Dual::constant(0.8);
            let close = |got: Dual<f64>, value: f64, derivative: f64| {
                (got.value - value).abs() <= 1e-14 * (1.0 + value.abs())
                    && (got.derivative - derivative).abs() <= 1e-14 * (1.0 + derivative.abs())
            };
            assert!(close(d + c, x + 0.8, 1.0));
            assert!(close(c - d, 0.8 - x, -1.0));
            assert!(close(d * d, x * x, 2.0 * x));
            assert!(close(c / d, 0.8 / x, -0.8 / (x * x)));
            assert!(close(-d, -x, -1.0));
            assert!(close(d.sin(), x.sin(), x.cos()));
            assert!(close(d.cos(), x.cos(), -x.sin()));
            let (s, k) = d.sin_cos();
            assert!(close(s, x.sin(), x.cos()) && close(k, x.cos(), -x.sin()));
            let y = Dual::variable(x * x);
            assert!(close(y.sqrt(), x.abs(), 1.0 / (2.0 * x.abs())));
            let mut z = d;
            z *= d;
            z += c;
            z -= d;
            z /= c;
            assert!(close(z, (x * x + 0.8 - x) / 0.8, (2.0 * x - 1.0) / 0.8));
            assert!(close(Dual::<f64>::from_f64(x), x, 0.0));
            assert!(Dual::<f64>::zero().is_zero() && !d.is_zero());
            assert_eq!(Dual::<f64>::one(), Dual::constant(1.0));
        }
    }
}
