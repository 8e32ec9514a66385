//! The `_into` twins' check: an `out` filled with NaN, then written by the twin, holds bit
//! for bit what the function returns (every entry written, each to the same bits); and the
//! `_sparse_into` twins' check: the entries written hold the function's bits, those left
//! are zero in the result (or below the diagonal of a symmetric one).

use dynamics_runtime::F64x4;

/// The bits of every number in a value (arrays, tuples, nested), in order.
pub trait Bits {
    /// Appends the bits of every number, in order.
    fn bits(&self, out: &mut Vec<u64>);
}
impl Bits for f64 {
    fn bits(&self, out: &mut Vec<u64>) {
        out.push(self.to_bits());
    }
}
impl Bits for F64x4 {
    fn bits(&self, out: &mut Vec<u64>) {
        out.extend(self.to_array().map(f64::to_bits));
    }
}
impl<B: Bits, const N: usize> Bits for [B; N] {
    fn bits(&self, out: &mut Vec<u64>) {
        self.iter().for_each(|b| b.bits(out));
    }
}
impl<A: Bits, B: Bits> Bits for (A, B) {
    fn bits(&self, out: &mut Vec<u64>) {
        self.0.bits(out);
        self.1.bits(out);
    }
}
impl<A: Bits, B: Bits, C: Bits> Bits for (A, B, C) {
    fn bits(&self, out: &mut Vec<u64>) {
        self.0.bits(out);
        self.1.bits(out);
        self.2.bits(out);
    }
}

/// `into` wrote exactly `expected` into an `out` that held NaN everywhere.
pub fn assert_same<O: Bits>(expected: O, mut out: O, into: impl FnOnce(&mut O), what: &str) {
    let mut before = Vec::new();
    out.bits(&mut before);
    assert!(
        before.iter().all(|&b| f64::from_bits(b).is_nan()),
        "{what}: `out` starts as NaN"
    );
    into(&mut out);
    let (mut got, mut want) = (Vec::new(), Vec::new());
    out.bits(&mut got);
    expected.bits(&mut want);
    assert_eq!(got, want, "{what}: `_into` against the returned value");
}

/// A number in [-2, 2) from a counter (no randomness needed: any state will do).
pub fn wobble(k: usize) -> f64 {
    ((k as f64) * 0.618_033_988_75).fract() * 4.0 - 2.0
}

/// `N` such numbers, from `seed`.
pub fn state<const N: usize>(seed: usize) -> [f64; N] {
    std::array::from_fn(|i| wobble(seed * 31 + i))
}

/// `into`, a `_sparse_into` twin of a function returning the `rows` × `cols` matrix
/// `expected` (of any scalar, flattened by [`Bits`]), wrote into an `out` that held NaN
/// every entry of `expected` that is nonzero (`upper`: on or above the diagonal), to the
/// same bits, and left only entries that are zero in `expected` (`upper`: or below the
/// diagonal). Returns how many entries it left.
pub fn assert_sparse<O: Bits>(
    expected: O,
    mut out: O,
    (rows, cols, upper): (usize, usize, bool),
    into: impl FnOnce(&mut O),
    what: &str,
) -> usize {
    into(&mut out);
    let (mut got, mut want) = (Vec::new(), Vec::new());
    out.bits(&mut got);
    expected.bits(&mut want);
    assert_eq!(
        got.len(),
        rows * cols * (got.len() / (rows * cols)),
        "{what}: shape"
    );
    let lanes = got.len() / (rows * cols);
    let mut left = 0;
    for i in 0..rows {
        for j in 0..cols {
            let at = (i * cols + j) * lanes;
            let (got, want) = (&got[at..at + lanes], &want[at..at + lanes]);
            let written = got.iter().all(|&b| !f64::from_bits(b).is_nan());
            let zero = want.iter().all(|&b| f64::from_bits(b) == 0.0);
            if written {
                assert_eq!(
                    got, want,
                    "{what}: entry ({i}, {j}) written, not as returned"
                );
            } else {
                assert!(
                    got.iter().all(|&b| f64::from_bits(b).is_nan()),
                    "{what}: entry ({i}, {j}) written in some lanes only"
                );
                assert!(
                    zero || (upper && j < i),
                    "{what}: entry ({i}, {j}) not written, and nonzero in the result"
                );
                left += 1;
            }
        }
    }
    left
}
