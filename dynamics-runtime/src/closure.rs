//! Kinematics and dynamics of closed loops from the generated closure functions.
//!
//! A mechanism with declared constraints has tree coordinates q (NV of them) tied by NC
//! closure equations φ(q) = 0. Given the driving coordinates, [`Closure`] solves for the
//! dependent ones: positions by Newton's method on φ (an iteration bound, failure as an
//! error), velocities from Φ_q q̇ = 0 and accelerations from Φ_q q̈ = γ, each a linear solve
//! in the dependent columns of Φ_q.
//!
//! [`constrained_acceleration`] is the forward dynamics of the closed mechanism (index
//! reduction with Baumgarte stabilization):
//!
//! ```text
//! M q̈ − Φ_qᵀ λ = τ − h,     Φ_q q̈ = γ − 2 ζ ω Φ_q q̇ − ω² φ,
//! ```
//!
//! solved through the Schur complement S = Φ_q M⁻¹ Φ_qᵀ (Cholesky of M, then of S), so that
//! every array is fixed-size: no allocation. λ are the constraint forces along the closure
//! components (the generalized forces Φ_qᵀ λ they exert).
//!
//! These are run-time loops over small fixed arrays with pivoting, for `T: Scalar +
//! PartialOrd` (f32, f64, double-double), not straight-line code.

use crate::scalar::{abs, Real, Scalar};
use core::fmt;

/// Why a closure or a constrained solve failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClosureError {
    /// The driving coordinates do not leave exactly NC dependent ones (their number, the
    /// number of closure equations).
    WrongDrivingCount {
        /// Dependent coordinates left.
        dependent: usize,
        /// Closure equations.
        equations: usize,
    },
    /// A driving coordinate index is out of range or repeated.
    BadDrivingIndex(usize),
    /// Newton's method did not bring |φ| below the tolerance (the residual reached).
    NotConverged {
        /// max |φ_i| after the last iteration.
        residual: f64,
        /// Iterations done.
        iterations: usize,
    },
    /// A matrix to be factored is singular (pivot smaller than 1e-13 of the largest):
    /// a singular configuration of the loop, or M not positive definite.
    Singular,
    /// Coordinate `q[index]` given to [`Closure::positions`] is NaN or infinite.
    NonFiniteCoordinate {
        /// Its index in q.
        index: usize,
    },
    /// Component `component` of the residual φ(q) is NaN or infinite after `iterations`
    /// Newton iterations: the closure functions blew up, or a step diverged.
    NonFiniteResidual {
        /// The first non-finite component of φ.
        component: usize,
        /// Newton iterations done before φ was evaluated.
        iterations: usize,
    },
    /// A solve's result is NaN or infinite: a non-finite entry in the Jacobian, the
    /// right-hand side or the known coordinates.
    NonFiniteSolution,
    /// An argument outside its domain; `what` says which and what it must be.
    InvalidArgument {
        /// The argument and its domain, e.g. "tolerance must be finite and positive".
        what: &'static str,
    },
}

impl fmt::Display for ClosureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ClosureError::WrongDrivingCount {
                dependent,
                equations,
            } => write!(
                f,
                "the driving coordinates leave {dependent} dependent coordinates for \
                 {equations} closure equations"
            ),
            ClosureError::BadDrivingIndex(i) => {
                write!(f, "driving coordinate {i} is out of range or repeated")
            }
            ClosureError::NotConverged {
                residual,
                iterations,
            } => write!(
                f,
                "the loop did not close: |φ| = {residual:e} after {iterations} Newton iterations \
                 (no assembly at these driving coordinates, or a poor starting guess)"
            ),
            ClosureError::Singular => write!(
                f,
                "singular matrix: the loop is at a singular configuration"
            ),
            ClosureError::NonFiniteCoordinate { index } => {
                write!(f, "coordinate q[{index}] is not a finite number")
            }
            ClosureError::NonFiniteResidual {
                component,
                iterations,
            } => write!(
                f,
                "closure residual φ[{component}] is not a finite number after {iterations} \
                 Newton iterations"
            ),
            ClosureError::NonFiniteSolution => write!(
                f,
                "the linear solve gave a non-finite value (a NaN or infinite input)"
            ),
            ClosureError::InvalidArgument { what } => write!(f, "invalid argument: {what}"),
        }
    }
}

impl core::error::Error for ClosureError {}

/// Solves the square system a x = b (by rows, the first `n` rows and columns) in place by
/// Gaussian elimination with partial pivoting; `Singular` if a pivot is below 1e-13 of the
/// largest entry or `a` has a NaN entry, `NonFiniteSolution` if x is not finite.
fn solve_square<T: Scalar + PartialOrd, const K: usize>(
    a: &mut [[T; K]; K],
    b: &mut [T; K],
) -> Result<(), ClosureError> {
    let mut scale = T::zero();
    for row in a.iter() {
        for &x in row {
            if abs(x) > scale {
                scale = abs(x);
            } else if !is_number(x) {
                // `>` is false for NaN, which would otherwise be passed over.
                return Err(ClosureError::Singular);
            }
        }
    }
    let tiny = scale * T::from_f64(1e-13);
    for j in 0..K {
        let mut best = j;
        for i in j + 1..K {
            if abs(a[i][j]) > abs(a[best][j]) {
                best = i;
            }
        }
        // A NaN pivot is singular too.
        if abs(a[best][j]).partial_cmp(&tiny) != Some(core::cmp::Ordering::Greater) {
            return Err(ClosureError::Singular);
        }
        a.swap(j, best);
        b.swap(j, best);
        for i in j + 1..K {
            let factor = a[i][j] / a[j][j];
            for k in j..K {
                let delta = factor * a[j][k];
                a[i][k] -= delta;
            }
            let delta = factor * b[j];
            b[i] -= delta;
        }
    }
    for j in (0..K).rev() {
        let mut sum = b[j];
        for k in j + 1..K {
            sum -= a[j][k] * b[k];
        }
        b[j] = sum / a[j][j];
    }
    if b.iter().all(|&x| is_finite(x)) {
        Ok(())
    } else {
        Err(ClosureError::NonFiniteSolution)
    }
}

/// Whether `x` is not NaN (NaN is the one value unequal to itself).
fn is_number<T: PartialOrd>(x: T) -> bool {
    x.partial_cmp(&x).is_some()
}

/// Whether `x` is neither NaN nor infinite (0 · x is NaN for both, ±0 otherwise).
fn is_finite<T: Scalar + PartialOrd>(x: T) -> bool {
    x * T::zero() == T::zero()
}

/// Which coordinates are dependent, for NC closure equations over NV coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Closure<const NC: usize, const NV: usize> {
    dependent: [usize; NC],
}

impl<const NC: usize, const NV: usize> Closure<NC, NV> {
    /// The driving (independent) coordinates; all others are solved for.
    pub fn new(driving: &[usize]) -> Result<Self, ClosureError> {
        let mut is_driving = [false; NV];
        for &i in driving {
            if i >= NV || is_driving[i] {
                return Err(ClosureError::BadDrivingIndex(i));
            }
            is_driving[i] = true;
        }
        let count = NV - driving.len();
        if count != NC {
            return Err(ClosureError::WrongDrivingCount {
                dependent: count,
                equations: NC,
            });
        }
        let mut dependent = [0; NC];
        let mut k = 0;
        for (i, d) in is_driving.iter().enumerate() {
            if !d {
                dependent[k] = i;
                k += 1;
            }
        }
        Ok(Closure { dependent })
    }

    /// The dependent coordinates' indices.
    pub fn dependent(&self) -> [usize; NC] {
        self.dependent
    }

    /// Solves Φ_d x_d = rhs − Φ_i x_i for the dependent entries of `x` (the others kept).
    fn solve_dependent<T: Scalar + PartialOrd>(
        &self,
        jacobian: &[[T; NV]; NC],
        rhs: &[T; NC],
        x: &mut [T; NV],
    ) -> Result<(), ClosureError> {
        let mut a = [[T::zero(); NC]; NC];
        let mut b = *rhs;
        for r in 0..NC {
            for c in 0..NV {
                match self.dependent.iter().position(|&d| d == c) {
                    Some(k) => a[r][k] = jacobian[r][c],
                    None => {
                        let known = jacobian[r][c] * x[c];
                        b[r] -= known;
                    }
                }
            }
        }
        solve_square(&mut a, &mut b)?;
        for (k, &d) in self.dependent.iter().enumerate() {
            x[d] = b[k];
        }
        Ok(())
    }

    /// Closes the loops: Newton's method on φ(q) = 0 over the dependent coordinates, from
    /// the values in `q`, until max |φ_i| ≤ `tolerance`; returns the iterations used (0 when
    /// `q` already closes the loops).
    ///
    /// Errors: [`ClosureError::InvalidArgument`] unless `tolerance` is finite and positive;
    /// [`ClosureError::NonFiniteCoordinate`] if a coordinate of `q` is NaN or infinite on
    /// entry; [`ClosureError::NonFiniteResidual`] if φ has a NaN or infinite component (never
    /// read as closed); [`ClosureError::NotConverged`] after `max_iterations` Newton steps
    /// (0 only tests `q`); [`ClosureError::Singular`] at a singular configuration. On error
    /// `q` holds the last iterate.
    pub fn positions<T: Real>(
        &self,
        q: &mut [T; NV],
        residual: impl Fn(&[T; NV]) -> [T; NC],
        jacobian: impl Fn(&[T; NV]) -> [[T; NV]; NC],
        tolerance: T,
        max_iterations: usize,
    ) -> Result<usize, ClosureError> {
        if !(is_finite(tolerance) && tolerance > T::zero()) {
            return Err(ClosureError::InvalidArgument {
                what: "the closure tolerance must be finite and positive",
            });
        }
        if let Some(index) = q.iter().position(|&x| !is_finite(x)) {
            return Err(ClosureError::NonFiniteCoordinate { index });
        }
        for iteration in 0..=max_iterations {
            let phi = residual(q);
            // max |φ_i|, with a NaN or infinite component an error rather than passed over
            // (`>` is false for NaN).
            let mut size = T::zero();
            for (component, &x) in phi.iter().enumerate() {
                if !is_finite(x) {
                    return Err(ClosureError::NonFiniteResidual {
                        component,
                        iterations: iteration,
                    });
                }
                if abs(x) > size {
                    size = abs(x);
                }
            }
            if size <= tolerance {
                return Ok(iteration);
            }
            if iteration == max_iterations {
                return Err(ClosureError::NotConverged {
                    residual: size.to_f64(),
                    iterations: iteration,
                });
            }
            // Newton step: Φ_d Δ_d = −φ.
            let j = jacobian(q);
            let mut step = [T::zero(); NV];
            let minus_phi = phi.map(|x| -x);
            self.solve_dependent(&j, &minus_phi, &mut step)?;
            for &d in &self.dependent {
                q[d] += step[d];
            }
        }
        Err(ClosureError::NotConverged {
            residual: f64::NAN,
            iterations: max_iterations,
        })
    }

    /// The dependent velocities that keep the loops closed, Φ_q q̇ = 0, given the driving
    /// ones in `v`: [`ClosureError::Singular`] at a singular configuration (or a NaN in the
    /// dependent columns), [`ClosureError::NonFiniteSolution`] if a result is not finite.
    pub fn velocities<T: Scalar + PartialOrd>(
        &self,
        jacobian: &[[T; NV]; NC],
        v: &mut [T; NV],
    ) -> Result<(), ClosureError> {
        self.solve_dependent(jacobian, &[T::zero(); NC], v)
    }

    /// The dependent accelerations with Φ_q q̈ = γ, given the driving ones in `a`; errors as
    /// for [`Closure::velocities`].
    pub fn accelerations<T: Scalar + PartialOrd>(
        &self,
        jacobian: &[[T; NV]; NC],
        gamma: &[T; NC],
        a: &mut [T; NV],
    ) -> Result<(), ClosureError> {
        self.solve_dependent(jacobian, gamma, a)
    }
}

/// Baumgarte's stabilization of the closure at the acceleration level: φ̈ + 2ζω φ̇ + ω² φ = 0
/// (ω = 0: none; the constraint drift then grows with the integration error).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Baumgarte<T> {
    /// Damping ratio ζ.
    pub damping_ratio: T,
    /// Natural frequency ω (rad/s).
    pub frequency: T,
}

/// Cholesky factor L (lower, by rows) of a symmetric positive definite matrix.
fn cholesky<T: Scalar + PartialOrd, const K: usize>(
    m: &[[T; K]; K],
) -> Result<[[T; K]; K], ClosureError> {
    let mut l = [[T::zero(); K]; K];
    let mut largest = T::zero();
    for i in 0..K {
        if abs(m[i][i]) > largest {
            largest = abs(m[i][i]);
        }
    }
    for i in 0..K {
        for j in 0..=i {
            let mut sum = m[i][j];
            for k in 0..j {
                sum -= l[i][k] * l[j][k];
            }
            if i == j {
                let floor = largest * T::from_f64(1e-13);
                if sum.partial_cmp(&floor) != Some(core::cmp::Ordering::Greater) {
                    return Err(ClosureError::Singular);
                }
                l[i][i] = sum.sqrt();
            } else {
                l[i][j] = sum / l[j][j];
            }
        }
    }
    Ok(l)
}

/// x = (L Lᵀ)⁻¹ b.
fn cholesky_solve<T: Scalar, const K: usize>(l: &[[T; K]; K], b: &[T; K]) -> [T; K] {
    let mut y = *b;
    for i in 0..K {
        for k in 0..i {
            let d = l[i][k] * y[k];
            y[i] -= d;
        }
        y[i] /= l[i][i];
    }
    for i in (0..K).rev() {
        for k in i + 1..K {
            let d = l[k][i] * y[k];
            y[i] -= d;
        }
        y[i] /= l[i][i];
    }
    y
}

/// Forward dynamics of a closed mechanism: (q̈, λ) with M q̈ − Φ_qᵀ λ = τ − h and
/// Φ_q q̈ = γ − 2ζω φ̇ − ω² φ (see the module docs). `forces` is τ − h (h the bias forces
/// C q̇ + g + b q̇ of the tree), `rate` is φ̇ = Φ_q q̇.
///
/// Errors: [`ClosureError::Singular`] if M or the Schur complement is not positive definite
/// (or has a NaN entry), [`ClosureError::NonFiniteSolution`] if q̈ or λ is not finite (a NaN
/// or infinite input).
#[allow(clippy::too_many_arguments)]
pub fn constrained_acceleration<T: Scalar + PartialOrd, const NV: usize, const NC: usize>(
    mass_matrix: &[[T; NV]; NV],
    forces: &[T; NV],
    jacobian: &[[T; NV]; NC],
    gamma: &[T; NC],
    residual: &[T; NC],
    rate: &[T; NC],
    stabilization: Baumgarte<T>,
) -> Result<([T; NV], [T; NC]), ClosureError> {
    let l = cholesky(mass_matrix)?;
    let unconstrained = cholesky_solve(&l, forces);
    // Y = M⁻¹ Φᵀ, column by column; S = Φ Y.
    let mut y = [[T::zero(); NC]; NV];
    for c in 0..NC {
        let column = cholesky_solve(&l, &jacobian[c]);
        for r in 0..NV {
            y[r][c] = column[r];
        }
    }
    let mut s = [[T::zero(); NC]; NC];
    let mut rhs = [T::zero(); NC];
    let two = T::from_f64(2.0);
    let (zeta, omega) = (stabilization.damping_ratio, stabilization.frequency);
    for i in 0..NC {
        for j in 0..NC {
            s[i][j] = (0..NV).fold(T::zero(), |acc, k| acc + jacobian[i][k] * y[k][j]);
        }
        let phi_u = (0..NV).fold(T::zero(), |acc, k| acc + jacobian[i][k] * unconstrained[k]);
        rhs[i] = gamma[i] - two * zeta * omega * rate[i] - omega * omega * residual[i] - phi_u;
    }
    // Φ (u + Y λ) = target  ⇒  S λ = target − Φ u.
    let lambda = cholesky_solve(&cholesky(&s)?, &rhs);
    let mut qdd = unconstrained;
    for r in 0..NV {
        for c in 0..NC {
            let d = y[r][c] * lambda[c];
            qdd[r] += d;
        }
    }
    if qdd.iter().chain(&lambda).all(|&x| is_finite(x)) {
        Ok((qdd, lambda))
    } else {
        Err(ClosureError::NonFiniteSolution)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn newton_closes_a_unit_circle_constraint() {
        // φ = (q0² + q1² − 1): drive q0, solve q1 from 0.9.
        let closure = Closure::<1, 2>::new(&[0]).expect("one dependent");
        let mut q: [f64; 2] = [0.6, 0.9];
        let n = closure
            .positions(
                &mut q,
                |q| [q[0] * q[0] + q[1] * q[1] - 1.0],
                |q| [[2.0 * q[0], 2.0 * q[1]]],
                1e-14,
                20,
            )
            .expect("converges");
        assert!((q[1] - 0.8).abs() < 1e-14 && n < 8, "{q:?} after {n}");
        let mut v: [f64; 2] = [1.0, 0.0];
        closure
            .velocities(&[[2.0 * q[0], 2.0 * q[1]]], &mut v)
            .expect("solves");
        assert!((v[1] + 0.75).abs() < 1e-14, "{v:?}");
    }

    #[test]
    fn failures_are_errors() {
        assert_eq!(
            Closure::<1, 2>::new(&[]),
            Err(ClosureError::WrongDrivingCount {
                dependent: 2,
                equations: 1
            })
        );
        assert_eq!(
            Closure::<1, 2>::new(&[2]),
            Err(ClosureError::BadDrivingIndex(2))
        );
        let closure = Closure::<1, 2>::new(&[0]).expect("valid");
        // No solution: q0 = 2 leaves q1² = −3.
        let mut q = [2.0, 0.5];
        let e = closure
            .positions(
                &mut q,
                |q| [q[0] * q[0] + q[1] * q[1] - 1.0],
                |q| [[2.0 * q[0], 2.0 * q[1]]],
                1e-12,
                30,
            )
            .expect_err("no assembly");
        assert!(
            matches!(
                e,
                ClosureError::NotConverged { .. } | ClosureError::Singular
            ),
            "{e:?}"
        );
    }

    fn close_circle(q: &mut [f64; 2], tolerance: f64) -> Result<usize, ClosureError> {
        let closure = Closure::<1, 2>::new(&[0]).expect("valid");
        closure.positions(
            q,
            |q| [q[0] * q[0] + q[1] * q[1] - 1.0],
            |q| [[2.0 * q[0], 2.0 * q[1]]],
            tolerance,
            20,
        )
    }

    #[test]
    fn a_nan_coordinate_is_an_error_not_a_closed_loop() {
        // The max norm used to pass over NaN, so φ = NaN read as |φ| = 0: Ok(0), q unchanged.
        let mut q = [0.6, f64::NAN];
        assert_eq!(
            close_circle(&mut q, 1e-12),
            Err(ClosureError::NonFiniteCoordinate { index: 1 })
        );
        let mut q = [f64::INFINITY, 0.8];
        assert_eq!(
            close_circle(&mut q, 1e-12),
            Err(ClosureError::NonFiniteCoordinate { index: 0 })
        );
    }

    #[test]
    fn a_non_finite_residual_is_an_error() {
        let closure = Closure::<2, 3>::new(&[0]).expect("valid");
        let mut q = [0.5, 0.5, 0.5];
        let e = closure.positions(
            &mut q,
            |q| [q[1] - q[0], f64::NAN * q[2]],
            |_| [[-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            1e-12,
            20,
        );
        assert_eq!(
            e,
            Err(ClosureError::NonFiniteResidual {
                component: 1,
                iterations: 0
            })
        );
    }

    #[test]
    fn a_tolerance_that_cannot_be_met_is_an_invalid_argument() {
        for tolerance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let mut q = [0.6, 0.9];
            assert!(
                matches!(
                    close_circle(&mut q, tolerance),
                    Err(ClosureError::InvalidArgument { .. })
                ),
                "{tolerance}"
            );
        }
    }

    #[test]
    fn a_nan_in_a_solve_is_an_error_not_a_result() {
        let closure = Closure::<1, 2>::new(&[0]).expect("valid");
        // A NaN driving velocity used to give a NaN dependent one, as a success.
        let mut v = [f64::NAN, 0.0];
        assert_eq!(
            closure.velocities(&[[1.2, 1.6]], &mut v),
            Err(ClosureError::NonFiniteSolution)
        );
        // A NaN in the dependent column.
        let mut v = [1.0, 0.0];
        assert_eq!(
            closure.velocities(&[[1.2, f64::NAN]], &mut v),
            Err(ClosureError::Singular)
        );
        let none = Baumgarte {
            damping_ratio: 0.0,
            frequency: 0.0,
        };
        let m = [[1.0, 0.0], [0.0, 1.0]];
        assert_eq!(
            constrained_acceleration(
                &m,
                &[f64::NAN, 0.0],
                &[[2.0, 0.0]],
                &[-8.0],
                &[0.0],
                &[0.0],
                none
            ),
            Err(ClosureError::NonFiniteSolution)
        );
    }

    #[test]
    fn a_point_on_a_circle_accelerates_centripetally() {
        // A unit point mass at (x, y) held on the unit circle, at (1, 0) moving with ẏ = 2:
        // φ = x² + y² − 1, Φ = [2x, 2y], γ = −2(ẋ² + ẏ²) = −8, so ẍ = −4 and λ = −2 (the pull
        // toward the centre, Φᵀλ = (−4, 0)).
        let m: [[f64; 2]; 2] = [[1.0, 0.0], [0.0, 1.0]];
        let none = Baumgarte {
            damping_ratio: 0.0,
            frequency: 0.0,
        };
        let (qdd, lambda) = constrained_acceleration(
            &m,
            &[0.0, 0.0],
            &[[2.0, 0.0]],
            &[-8.0],
            &[0.0],
            &[0.0],
            none,
        )
        .expect("regular");
        assert!(
            (qdd[0] + 4.0).abs() < 1e-15 && qdd[1].abs() < 1e-15,
            "{qdd:?}"
        );
        assert!((lambda[0] + 2.0).abs() < 1e-15, "{lambda:?}");
    }
}
