//! The result of a generated force analysis, A(q) x = b(q, q̇, q̈), and its conditioning.
//!
//! `force_analysis` returns the unknowns x (reaction components and driving efforts) and the
//! diagonal of the R factor of A = QᵀR. Since σ_min(A) ≤ |R_jj| ≤ σ_max(A), the pivot ratio
//! min |R_jj| / max |R_jj| is at least the reciprocal condition number 1/κ₂(A): zero at a
//! singular configuration (a toggle or dead-centre position, a redundant support), small
//! near one. [`ForceAnalysis::checked`] turns a ratio below a threshold (or a non-finite
//! value) into an error instead of silently returning huge or NaN forces.

use crate::scalar::{abs, Scalar};
use core::fmt;

/// The unknowns of a force analysis and the pivots of its QR factorization.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceAnalysis<T, const N: usize> {
    /// x: reaction components and efforts, in the order of the mechanism's
    /// `FORCE_UNKNOWNS`.
    pub unknowns: [T; N],
    /// The diagonal of R (signed).
    pub pivots: [T; N],
}

impl<T, const N: usize> From<([T; N], [T; N])> for ForceAnalysis<T, N> {
    fn from((unknowns, pivots): ([T; N], [T; N])) -> Self {
        ForceAnalysis { unknowns, pivots }
    }
}

/// A force analysis whose matrix is singular or too poorly conditioned to trust.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IllConditioned<T> {
    /// min |R_jj| / max |R_jj| (NaN when a value was not finite).
    pub pivot_ratio: T,
    /// The threshold it was checked against.
    pub threshold: T,
}

impl<T: fmt::Display> fmt::Display for IllConditioned<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the force analysis is singular or ill-conditioned here (pivot ratio {} < {}): a \
             special configuration, a redundant constraint or missing load information",
            self.pivot_ratio, self.threshold
        )
    }
}

impl<T: fmt::Debug + fmt::Display> core::error::Error for IllConditioned<T> {}

impl<T: Scalar + PartialOrd, const N: usize> ForceAnalysis<T, N> {
    /// min |R_jj| / max |R_jj| ≥ 1/κ₂(A); NaN if any pivot or unknown is not finite.
    /// (1 for an empty analysis.)
    pub fn pivot_ratio(&self) -> T {
        let mut smallest: Option<T> = None;
        let mut largest = T::zero();
        for &p in &self.pivots {
            let p = abs(p);
            // NaN fails every comparison: propagate it explicitly.
            if p.partial_cmp(&p).is_none() {
                return p;
            }
            smallest = Some(match smallest {
                Some(s) if s < p => s,
                _ => p,
            });
            if p > largest {
                largest = p;
            }
        }
        let finite = |x: T| abs(x) <= T::from_f64(f64::MAX);
        if !self.unknowns.iter().all(|&x| finite(x)) {
            return T::from_f64(f64::NAN);
        }
        match smallest {
            None => T::one(),
            Some(s) => s / largest,
        }
    }

    /// The unknowns, or an error when the pivot ratio is below `threshold` (or NaN).
    /// A threshold around 1e-9 in f64 flags configurations within about 1e-9 rad of a
    /// toggle position.
    pub fn checked(&self, threshold: T) -> Result<[T; N], IllConditioned<T>> {
        let pivot_ratio = self.pivot_ratio();
        if pivot_ratio >= threshold {
            Ok(self.unknowns)
        } else {
            Err(IllConditioned {
                pivot_ratio,
                threshold,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    // std's prelude, for the build without the `std` feature (lib.rs).
    use super::*;
    #[allow(unused_imports)]
    use std::prelude::rust_2021::*;

    #[test]
    fn ratio_and_checks() {
        let good = ForceAnalysis::from(([1.0, 2.0], [-4.0, 2.0]));
        assert_eq!(good.pivot_ratio(), 0.5);
        assert_eq!(good.checked(1e-9), Ok([1.0, 2.0]));
        let singular = ForceAnalysis::from(([f64::INFINITY, 2.0], [0.0, 2.0]));
        assert!(singular.pivot_ratio().is_nan());
        assert!(singular.checked(1e-9).is_err());
        let nan = ForceAnalysis::from(([f64::NAN, 2.0], [f64::NAN, 2.0]));
        let error = nan.checked(1e-9).expect_err("NaN is an error");
        assert!(error.pivot_ratio.is_nan());
        assert!(error.to_string().contains("special configuration"));
    }
}
