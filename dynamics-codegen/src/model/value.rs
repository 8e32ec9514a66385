//! Numbers of a validated model: affine in the declared parameters,
//! `value = constant + Σ_k coefficient_k · p[k]`.
//!
//! Affine values are closed under everything the model stage does to them (rotating a
//! translation or an inertia by a constant rotation, composing placements, scaling by a
//! shape's factor), so bodies merged through fixed joints stay exact. Products of
//! parameters only arise in the symbolic expansion, which handles them itself.

use std::ops::{Add, Mul};

/// An affine function of the parameters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Value {
    /// The constant part.
    pub constant: f64,
    /// `(parameter index, coefficient)` pairs, sorted by index, no zero coefficients.
    pub terms: Vec<(usize, f64)>,
}

impl Value {
    /// A constant.
    pub fn constant(constant: f64) -> Self {
        Value {
            constant,
            terms: Vec::new(),
        }
    }

    /// `coefficient · p[index]`.
    pub fn parameter(index: usize, coefficient: f64) -> Self {
        Value {
            constant: 0.0,
            terms: vec![(index, coefficient)],
        }
        .normalized()
    }

    /// Whether the value involves no parameter.
    pub fn is_constant(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value at the parameters' nominal values.
    pub fn nominal(&self, nominal_parameters: &[f64]) -> f64 {
        self.terms.iter().fold(self.constant, |acc, &(k, c)| {
            acc + c * nominal_parameters[k]
        })
    }

    fn normalized(mut self) -> Self {
        self.terms.sort_by_key(|&(k, _)| k);
        let mut merged: Vec<(usize, f64)> = Vec::with_capacity(self.terms.len());
        for (k, c) in self.terms {
            match merged.last_mut() {
                Some(last) if last.0 == k => last.1 += c,
                _ => merged.push((k, c)),
            }
        }
        merged.retain(|&(_, c)| c != 0.0);
        self.terms = merged;
        self
    }
}

impl Add for &Value {
    type Output = Value;
    fn add(self, other: &Value) -> Value {
        let mut terms = self.terms.clone();
        terms.extend_from_slice(&other.terms);
        Value {
            constant: self.constant + other.constant,
            terms,
        }
        .normalized()
    }
}

impl Mul<f64> for &Value {
    type Output = Value;
    fn mul(self, factor: f64) -> Value {
        Value {
            constant: self.constant * factor,
            terms: self.terms.iter().map(|&(k, c)| (k, c * factor)).collect(),
        }
        .normalized()
    }
}

/// A vector of affine values.
pub type Vec3 = [Value; 3];
/// A 3×3 matrix of affine values, by rows.
pub type Mat3 = [[Value; 3]; 3];

/// `R v` for a constant rotation R (rows) and an affine vector v.
pub fn rotate(r: &[[f64; 3]; 3], v: &Vec3) -> Vec3 {
    std::array::from_fn(|i| (0..3).fold(Value::constant(0.0), |acc, j| &acc + &(&v[j] * r[i][j])))
}

/// `A B` of two constant rotations (rows), [`snapped`]: how the tree composes placements,
/// and how a modified DH row composes Rx(α) Rz(θ) (the same arithmetic, so that a table
/// declared in either convention gives the same numbers).
pub fn rotation_product(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    snapped(&super::linear::mul(a, b))
}

/// A rotation's entries within 1e-15 of 0 or ±1 taken as exactly that. `rpy = "0 0 1.5708"`
/// means a quarter turn, whose cosine is 0, not 6e-17, and a product of rotations that
/// cancel is the identity, not 1 − 1e-16: the exact zeros let the expansion fold the terms
/// they multiply, and a rotation by 1e-15 rad is no rotation.
pub fn snapped(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    snapped_within(m, DEFAULT_ROTATION_TOLERANCE)
}

/// The tolerance of [`snapped`], unless a declaration sets `rotation_tolerance`.
pub const DEFAULT_ROTATION_TOLERANCE: f64 = 1e-15;

/// An angle within `tolerance` of a multiple of a quarter turn taken as exactly that
/// multiple: how `rotation_tolerance` reads `rpy` and axis-angle rotations, so that they
/// stay orthonormal (a URDF's 1.57079632679 or 1.5708 for π/2). The default tolerance
/// changes no angle.
pub fn snapped_angle(angle: f64, tolerance: f64) -> f64 {
    if tolerance <= DEFAULT_ROTATION_TOLERANCE {
        return angle;
    }
    let quarters = (angle / std::f64::consts::FRAC_PI_2).round();
    let nearest = quarters * std::f64::consts::FRAC_PI_2;
    if (angle - nearest).abs() < tolerance {
        nearest
    } else {
        angle
    }
}

/// A rotation's entries within `tolerance` of 0 or ±1 taken as exactly that.
pub fn snapped_within(m: &[[f64; 3]; 3], tolerance: f64) -> [[f64; 3]; 3] {
    let snap = |x: f64| {
        if x.abs() < tolerance {
            0.0
        } else if (x.abs() - 1.0).abs() < tolerance {
            x.signum()
        } else {
            x
        }
    };
    m.map(|row| row.map(snap))
}

/// `R M Rᵀ` for a constant rotation R and an affine matrix M.
pub fn rotate_matrix(r: &[[f64; 3]; 3], m: &Mat3) -> Mat3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let mut acc = Value::constant(0.0);
            for k in 0..3 {
                for l in 0..3 {
                    acc = &acc + &(&m[k][l] * (r[i][k] * r[j][l]));
                }
            }
            acc
        })
    })
}

/// `a + b` componentwise.
pub fn add(a: &Vec3, b: &Vec3) -> Vec3 {
    std::array::from_fn(|i| &a[i] + &b[i])
}

/// Nominal values of a vector.
pub fn nominal3(v: &Vec3, p: &[f64]) -> [f64; 3] {
    std::array::from_fn(|i| v[i].nominal(p))
}

/// A vector rotated by a turn, with the rounding left where an entry should cancel made
/// exact: see [`snapped_together`].
pub fn snapped_vector(v: &Vec3) -> Vec3 {
    let mut entries = snapped_together(v).into_iter();
    std::array::from_fn(|_| entries.next().unwrap_or_default())
}

/// An inertia rotated by a turn, with the rounding left where an entry should cancel made
/// exact: see [`snapped_together`].
pub fn snapped_matrix(m: &Mat3) -> Mat3 {
    let flat: Vec<Value> = m.iter().flatten().cloned().collect();
    let mut entries = snapped_together(&flat).into_iter();
    std::array::from_fn(|_| std::array::from_fn(|_| entries.next().unwrap_or_default()))
}

/// Values that one rotation produced, with the parts below 1e-14 of the largest of their
/// kind dropped: the constant parts apart, and each parameter's coefficients apart.
fn snapped_together(values: &[Value]) -> Vec<Value> {
    let largest = |part: &dyn Fn(&Value) -> f64| values.iter().map(part).fold(0.0_f64, f64::max);
    let constant_scale = largest(&|x| x.constant.abs());
    let coefficient = |x: &Value, k: usize| x.terms.iter().find(|t| t.0 == k).map_or(0.0, |t| t.1);
    values
        .iter()
        .map(|x| Value {
            constant: if x.constant.abs() < 1e-14 * constant_scale {
                0.0
            } else {
                x.constant
            },
            terms: x
                .terms
                .iter()
                .copied()
                .filter(|&(k, c)| c.abs() >= 1e-14 * largest(&|y| coefficient(y, k).abs()))
                .collect(),
        })
        .collect()
}

/// Nominal values of a matrix.
pub fn nominal33(m: &Mat3, p: &[f64]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| nominal3(&m[i], p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_arithmetic_merges_terms() {
        let a = &Value::parameter(1, 2.0) + &Value::constant(3.0);
        let b = &Value::parameter(1, -2.0) + &Value::parameter(0, 1.0);
        let s = &a + &b;
        assert_eq!(
            s,
            Value {
                constant: 3.0,
                terms: vec![(0, 1.0)]
            }
        );
        assert_eq!(s.nominal(&[10.0, 100.0]), 13.0);
        assert_eq!((&a * 0.5).nominal(&[0.0, 4.0]), 5.5);
    }

    #[test]
    fn rotation_of_affine_vector() {
        let rz90 = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let v = [
            Value::parameter(0, 1.0),
            Value::constant(0.0),
            Value::constant(2.0),
        ];
        let w = rotate(&rz90, &v);
        assert_eq!(nominal3(&w, &[3.0]), [0.0, 3.0, 2.0]);
    }
}
