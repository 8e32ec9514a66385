//! Solves M X = B for many columns at once by a tree-sparse factorization M = Lᵀ D L
//! (Featherstone, *Rigid Body Dynamics Algorithms*, §6.5): L unit lower triangular, L_ki
//! nonzero only when coordinate i is an ancestor of coordinate k in the mechanism's tree.
//!
//! ```text
//! Lᵀ Z = B:  for j = n−1 … 0:  Z_j = B_j − Σ_{k descends from j} L_kj Z_k
//! Y = D⁻¹ Z
//! L X = Y:   for k = 0 … n−1:  X_k = Y_k − Σ_{i ancestor of k} L_ki X_i
//! ```
//!
//! Each row X_k is a whole row of C columns, updated by one multiply-add per column, so the
//! loop over the columns is what runs in SIMD registers (four `f64` per AVX2 instruction in
//! the wide copy of a generated function, [`crate::isa`]). Both sweeps gather into a row
//! held in registers and store it once (the rows of several matrices together when they
//! fit, else one matrix after another), and the second scales each row by 1 / D_k as it
//! reaches it. The loop is bound by its loads, about one per multiply-add (`cargo bench -p
//! dynamics-runtime --bench tree_ldlt`), so where two rows fit in registers (an 18-dof
//! robot's), a row and the next row of its chain gather together, each row they share
//! loaded once for both. Generated code calls this for the chain rule of
//! the forward-dynamics derivatives, ∂q̈/∂x = −M⁻¹ ∂τ/∂x, where the same factor solves
//! 2 nv columns: a loop instead of nv straight-line solves keeps the code small enough for
//! the instruction cache on large trees. The last sweep alone ([`solve_lower_columns`])
//! finishes M⁻¹ = L⁻¹ (D⁻¹ L⁻ᵀ) on large trees, [`mirror_upper_triangle`] making it
//! exactly symmetric.
//!
//! The coordinates are numbered depth first (every coordinate after its parent, each
//! subtree contiguous), as the generated code numbers them; [`CoordinateTree::new`] checks
//! that when it is evaluated as a constant, at compile time.

use crate::isa::Isa;
use crate::Scalar;

/// The tree of a mechanism's `N` velocity coordinates, as the sweeps walk it: each
/// coordinate's ancestors (for L X = Y) and descendants (for Lᵀ Z = B), with where L_ki
/// sits in the factor of `P` entries (one per coordinate and ancestor). Built once, as a
/// constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CoordinateTree<const N: usize, const P: usize> {
    /// Row k of L, `ancestors[row_end[k − 1]..row_end[k]]`: k's ancestors i from its parent
    /// towards the root, each with the position of L_ki in the factor (its own position).
    ancestors: [(usize, usize); P],
    row_end: [usize; N],
    /// How many coordinates have each coordinate as their parent.
    children: [usize; N],
    /// For j = N − 1 down to 0 in turn, its descendants k, deepest number first, each with
    /// the position of L_kj in the factor; j's end at `descendants_end[j]`.
    descendants: [(usize, usize); P],
    descendants_end: [usize; N],
}

impl<const N: usize, const P: usize> CoordinateTree<N, P> {
    /// The tree whose coordinate k has the parent `parent[k]` (`None` for a coordinate
    /// moved by a joint on the ground).
    ///
    /// # Panics
    /// When a parent does not come before its child, when the coordinates are not numbered
    /// depth first (a subtree not contiguous), or when `P` is not the number of
    /// (coordinate, ancestor) pairs. Generated code builds the tree in a constant, so such
    /// a panic is a compile-time error, never a run-time one.
    #[must_use]
    pub const fn new(parent: [Option<usize>; N]) -> Self {
        let mut depth = [0; N];
        let mut children = [0; N];
        let mut ancestors = [(0, 0); P];
        let mut row_end = [0; N];
        let mut p = 0;
        let mut k = 0;
        while k < N {
            if let Some(i) = parent[k] {
                assert!(i < k, "a coordinate's parent must come before it");
                depth[k] = depth[i] + 1;
                children[i] += 1;
            }
            let mut ancestor = parent[k];
            while let Some(i) = ancestor {
                assert!(p < P, "P must count the (coordinate, ancestor) pairs");
                ancestors[p] = (i, p);
                p += 1;
                ancestor = parent[i];
            }
            row_end[k] = p;
            k += 1;
        }
        assert!(p == P, "P must count the (coordinate, ancestor) pairs");
        // Depth first, the descendants of j are the coordinates after it up to the first
        // one no deeper than j; each of them must have j as an ancestor, at distance
        // depth[k] − depth[j], so L_kj sits at row_end[k] − depth[k] + (that − 1).
        let mut descendants = [(0, 0); P];
        let mut descendants_end = [0; N];
        let mut d = 0;
        let mut j = N;
        while j > 0 {
            j -= 1;
            let mut end = j + 1;
            while end < N && depth[end] > depth[j] {
                end += 1;
            }
            let mut k = end;
            while k > j + 1 {
                k -= 1;
                let at = row_end[k] - depth[k] + (depth[k] - depth[j] - 1);
                assert!(
                    ancestors[at].0 == j,
                    "the coordinates must be numbered depth first"
                );
                descendants[d] = (k, at);
                d += 1;
            }
            descendants_end[j] = d;
        }
        assert!(d == P, "the coordinates must be numbered depth first");
        CoordinateTree {
            ancestors,
            row_end,
            children,
            descendants,
            descendants_end,
        }
    }

    /// Coordinate k's parent: the first of its row's terms.
    fn parent(&self, k: usize) -> Option<usize> {
        self.lower_terms(k).first().map(|&(i, _)| i)
    }

    /// Row k's terms in L X = Y: its ancestors, the parent first, with L_ki's positions.
    fn lower_terms(&self, k: usize) -> &[(usize, usize)] {
        let start = if k == 0 { 0 } else { self.row_end[k - 1] };
        self.ancestors.get(start..self.row_end[k]).unwrap_or(&[])
    }

    /// Row j's terms in Lᵀ Z = B: its descendants, deepest number first, with L_kj's
    /// positions.
    fn upper_terms(&self, j: usize) -> &[(usize, usize)] {
        let start = if j + 1 >= N {
            0
        } else {
            self.descendants_end[j + 1]
        };
        self.descendants
            .get(start..self.descendants_end[j])
            .unwrap_or(&[])
    }
}

/// X = M⁻¹ B for every column of the `K` matrices B in `columns`, in place (each `N` rows
/// of `C` columns, row k holding coordinate k's entries), M = Lᵀ D L given by `factor`
/// (L_ki, row after row, each row's entries from k's parent towards the root) and
/// `inverse_pivot` (1 / D_k). Each column gets the same operations as one straight-line
/// tree-sparse solve of it, in the same order except where two rows of a chain are taken
/// together (rows of at most 20 columns): there, in L X = Y, the lower row's parent term
/// comes last of its sum instead of first. In the `WIDE` copy of a generated function the
/// products are fused into their differences. In place, so that generated code solves in
/// the value it returns: taking and returning the matrices by value cost the quadruped's
/// ∂q̈ two extra copies of its 5 kB of columns (2 to 5 % of its time).
#[inline(always)]
pub fn solve_columns<
    T: Scalar,
    const WIDE: bool,
    const N: usize,
    const P: usize,
    const C: usize,
    const K: usize,
>(
    isa: Isa<WIDE>,
    tree: &CoordinateTree<N, P>,
    factor: &[T; P],
    inverse_pivot: &[T; N],
    mut columns: [&mut [[T; C]; N]; K],
) {
    // Lᵀ Z = B, from the leaves: row j gathers its descendants' final rows, deepest first;
    // where j is its parent's only child, the parent's row too (its terms are j's and then
    // j itself).
    let mut j = N;
    while j > 0 {
        j -= 1;
        let pair = tree
            .parent(j)
            .filter(|&i| pairs_fit(C) && tree.children[i] == 1)
            .and_then(|i| Some((i, tree.upper_terms(i).split_last()?)));
        if let Some((i, (&(_, last), shared))) = pair {
            let terms = (tree.upper_terms(j), shared, last);
            for x in columns.iter_mut() {
                gather_pair(isa, x, (j, i), (None, None), terms, factor);
            }
            j = i;
        } else {
            gather_row(isa, &mut columns, j, None, tree.upper_terms(j), factor);
        }
    }
    // Y = D⁻¹ Z and L X = Y, each row scaled as the second sweep reaches it.
    lower_sweep(isa, tree, factor, Some(inverse_pivot), columns);
}

/// X = L⁻¹ Y for every column of the `K` matrices Y in `columns`, in place: the last sweep
/// of [`solve_columns`] alone, L X = Y. Generated code calls it for M⁻¹ = L⁻¹ (D⁻¹ L⁻ᵀ),
/// where straight-line code computes D⁻¹ L⁻ᵀ cheaply from its zeros (L⁻ᵀ is upper
/// triangular and nonzero only where the column's coordinate descends from the row's) and
/// the loop does the dense part, the sums over common ancestors, a row of columns at a time.
#[inline(always)]
pub fn solve_lower_columns<
    T: Scalar,
    const WIDE: bool,
    const N: usize,
    const P: usize,
    const C: usize,
    const K: usize,
>(
    isa: Isa<WIDE>,
    tree: &CoordinateTree<N, P>,
    factor: &[T; P],
    columns: [&mut [[T; C]; N]; K],
) {
    lower_sweep(isa, tree, factor, None, columns);
}

/// L X = Y in place, from the root: row k, first scaled by `scale[k]` if given, gathers its
/// ancestors' final rows, the parent first; a row and its only child together where two
/// rows fit in registers.
#[inline(always)]
fn lower_sweep<
    T: Scalar,
    const WIDE: bool,
    const N: usize,
    const P: usize,
    const C: usize,
    const K: usize,
>(
    isa: Isa<WIDE>,
    tree: &CoordinateTree<N, P>,
    factor: &[T; P],
    scale: Option<&[T; N]>,
    mut columns: [&mut [[T; C]; N]; K],
) {
    let scale_of = |k: usize| scale.and_then(|s| s.get(k).copied());
    let mut k = 0;
    while k < N {
        // Row k + 1 below row k: its terms are k itself and then k's.
        let pair = (pairs_fit(C) && k + 1 < N && tree.parent(k + 1) == Some(k))
            .then(|| tree.lower_terms(k + 1).split_first())
            .flatten();
        if let Some((&(_, first), shared)) = pair {
            let scales = (scale_of(k), scale_of(k + 1));
            let terms = (tree.lower_terms(k), shared, first);
            for x in columns.iter_mut() {
                gather_pair(isa, x, (k, k + 1), scales, terms, factor);
            }
            k += 2;
        } else {
            gather_row(
                isa,
                &mut columns,
                k,
                scale_of(k),
                tree.lower_terms(k),
                factor,
            );
            k += 1;
        }
    }
}

/// Two rows at once, `first` and `second`, where `second`'s terms are `first`'s (the same
/// rows, in `shared` with L's positions in `second`'s row) and `first` itself (L at
/// `last`): each row of the shared terms loaded once for both (the loop is bound by its
/// loads); `first` stored, then `second` minus L times `first`'s final row. In Lᵀ Z = B
/// that is `second`'s own order; in L X = Y, whose rows take the parent first, `first`
/// moves to the end of `second`'s sum (rounding may differ in the last bits). Only for
/// rows whose two fit in registers ([`pairs_fit`]).
#[inline(always)]
fn gather_pair<T: Scalar, const WIDE: bool, const N: usize, const P: usize, const C: usize>(
    isa: Isa<WIDE>,
    x: &mut [[T; C]; N],
    (first, second): (usize, usize),
    scales: (Option<T>, Option<T>),
    (first_terms, shared, last): (&[Term], &[Term], usize),
    factor: &[T; P],
) {
    let (Some(&l_last), true, true) = (factor.get(last), first < N, second < N) else {
        return;
    };
    let (mut a0, mut a1) = (scaled(x[first], scales.0), scaled(x[second], scales.1));
    for (&(other, at0), &(_, at1)) in first_terms.iter().zip(shared) {
        if let (Some(&l0), Some(&l1), true) = (factor.get(at0), factor.get(at1), other < N) {
            for c in 0..C {
                a0[c] = isa.mul_add(-l0, x[other][c], a0[c]);
                a1[c] = isa.mul_add(-l1, x[other][c], a1[c]);
            }
        }
    }
    for c in 0..C {
        a1[c] = isa.mul_add(-l_last, a0[c], a1[c]);
    }
    x[first] = a0;
    x[second] = a1;
}

/// `row` times `scale`, if given.
#[inline(always)]
fn scaled<T: Scalar, const C: usize>(mut row: [T; C], scale: Option<T>) -> [T; C] {
    if let Some(s) = scale {
        for c in 0..C {
            row[c] *= s;
        }
    }
    row
}

/// A term of a row's sum: the other row, and where its L sits in the factor.
type Term = (usize, usize);

/// Whether two rows of `C` numbers fit in [`ROW_IN_REGISTERS`], for [`gather_pair`].
const fn pairs_fit(c: usize) -> bool {
    2 * c <= ROW_IN_REGISTERS
}

/// The upper triangle of the square matrix `x` copied onto its lower one, so that a
/// symmetric result computed row by row (M⁻¹ by [`solve_lower_columns`]) is symmetric to
/// the bit.
#[inline(always)]
pub fn mirror_upper_triangle<T: Copy, const N: usize>(x: &mut [[T; N]; N]) {
    for r in 1..N {
        for c in 0..r {
            x[r][c] = x[c][r];
        }
    }
}

/// Row `r` of every matrix, times `scale` if given, minus L · row `other` for each (other,
/// position of L in `factor`) of `terms`, in order, accumulated in a local row (registers)
/// and stored once: the rows of all `K` matrices together when their `K C` numbers fit in
/// [`ROW_IN_REGISTERS`], else one matrix's row after another's, each a pass over the terms
/// (together, g1's two rows of 35 spilled to the stack at every term: its forward-dynamics
/// derivatives' solve took 1.3 times as long). Plain indexed loops, inlined into the
/// generated kernel, so that the wide copy's multiply-adds compile to FMA instructions.
#[inline(always)]
fn gather_row<
    T: Scalar,
    const WIDE: bool,
    const N: usize,
    const P: usize,
    const C: usize,
    const K: usize,
>(
    isa: Isa<WIDE>,
    columns: &mut [&mut [[T; C]; N]; K],
    r: usize,
    scale: Option<T>,
    terms: &[(usize, usize)],
    factor: &[T; P],
) {
    if K * C <= ROW_IN_REGISTERS {
        gather_rows(isa, columns, r, scale, terms, factor);
    } else {
        for x in columns.iter_mut() {
            gather_rows(isa, &mut [&mut **x], r, scale, terms, factor);
        }
    }
}

/// The numbers a row held in registers may have: 40 `f64` are ten of the sixteen AVX2
/// registers, leaving six to the loads and the factor's entry.
const ROW_IN_REGISTERS: usize = 40;

/// [`gather_row`] on the rows of all the matrices `columns` at once.
#[inline(always)]
fn gather_rows<
    T: Scalar,
    const WIDE: bool,
    const N: usize,
    const P: usize,
    const C: usize,
    const K: usize,
>(
    isa: Isa<WIDE>,
    columns: &mut [&mut [[T; C]; N]; K],
    r: usize,
    scale: Option<T>,
    terms: &[(usize, usize)],
    factor: &[T; P],
) {
    if r >= N {
        return;
    }
    let mut row = [[T::from_f64(0.0); C]; K];
    for m in 0..K {
        row[m] = scaled(columns[m][r], scale);
    }
    for &(other, at) in terms {
        if let (Some(&l), true) = (factor.get(at), other < N) {
            for m in 0..K {
                for c in 0..C {
                    row[m][c] = isa.mul_add(-l, columns[m][other][c], row[m][c]);
                }
            }
        }
    }
    for m in 0..K {
        columns[m][r] = row[m];
    }
}

#[cfg(test)]
mod tests {
    use super::{mirror_upper_triangle, solve_columns, solve_lower_columns, CoordinateTree, Isa};

    /// A free base's six coordinates in a chain, then two legs of two.
    const PARENTS: [Option<usize>; 10] = [
        None,
        Some(0),
        Some(1),
        Some(2),
        Some(3),
        Some(4),
        Some(5),
        Some(6),
        Some(5),
        Some(8),
    ];

    /// The (coordinate, ancestor) pairs: the base's 15, each leg's 6 + 7.
    const PAIRS: usize = 15 + 2 * (6 + 7);

    /// L, dense, from the factor.
    fn dense_l(factor: &[f64; PAIRS]) -> [[f64; 10]; 10] {
        let mut l = [[0.0; 10]; 10];
        let mut at = 0;
        for (k, row) in l.iter_mut().enumerate() {
            row[k] = 1.0;
            let mut a = PARENTS[k];
            while let Some(i) = a {
                row[i] = factor[at];
                at += 1;
                a = PARENTS[i];
            }
        }
        l
    }

    /// M = Lᵀ D L built densely from the factor, for checking the solve.
    fn dense(factor: &[f64; PAIRS], d: &[f64; 10]) -> [[f64; 10]; 10] {
        let l = dense_l(factor);
        let mut m = [[0.0; 10]; 10];
        for (r, m_row) in m.iter_mut().enumerate() {
            for (c, x) in m_row.iter_mut().enumerate() {
                *x = (0..10).map(|k| l[k][r] * d[k] * l[k][c]).sum();
            }
        }
        m
    }

    #[test]
    fn solves_every_column() {
        const TREE: CoordinateTree<10, PAIRS> = CoordinateTree::new(PARENTS);
        let factor: [f64; PAIRS] = core::array::from_fn(|k| 0.3 * (k as f64 * 0.7).sin());
        let d: [f64; 10] = core::array::from_fn(|k| 1.0 + 0.1 * k as f64);
        let b: [[f64; 3]; 10] =
            core::array::from_fn(|r| core::array::from_fn(|c| ((r * 3 + c) as f64).cos()));
        let (mut x, mut twice) = (b, b);
        solve_columns(
            Isa::BASELINE,
            &TREE,
            &factor,
            &d.map(|x| 1.0 / x),
            [&mut x, &mut twice],
        );
        assert_eq!(x, twice);
        let m = dense(&factor, &d);
        for c in 0..3 {
            for r in 0..10 {
                let mx: f64 = (0..10).map(|k| m[r][k] * x[k][c]).sum();
                assert!(
                    (mx - b[r][c]).abs() < 1e-12,
                    "row {r} column {c}: {mx} vs {}",
                    b[r][c]
                );
            }
        }
        // The wide copy's fused products change the last bits only.
        let wide = crate::isa::run(
            |isa| {
                let mut wide = b;
                solve_columns(isa, &TREE, &factor, &d.map(|x| 1.0 / x), [&mut wide]);
                wide
            },
            |_| x,
        );
        for (a, b) in x.iter().flatten().zip(wide.iter().flatten()) {
            assert!((a - b).abs() < 1e-13);
        }
    }

    /// Two matrices of 24 columns are more than a row in registers holds, so each is swept
    /// on its own: the same bits as solving each alone, and M X = B.
    #[test]
    fn matrices_too_wide_to_hold_together_are_solved_one_after_the_other() {
        const TREE: CoordinateTree<10, PAIRS> = CoordinateTree::new(PARENTS);
        const { assert!(2 * 24 > super::ROW_IN_REGISTERS && 24 <= super::ROW_IN_REGISTERS) };
        let factor: [f64; PAIRS] = core::array::from_fn(|k| 0.3 * (k as f64 * 0.7).sin());
        let d: [f64; 10] = core::array::from_fn(|k| 1.0 + 0.1 * k as f64);
        let inverse_pivot = d.map(|x| 1.0 / x);
        let b: [[f64; 24]; 10] =
            core::array::from_fn(|r| core::array::from_fn(|c| ((r * 24 + c) as f64).cos()));
        let b2: [[f64; 24]; 10] =
            core::array::from_fn(|r| core::array::from_fn(|c| ((r * 24 + c) as f64).sin()));
        let (mut x, mut y) = (b, b2);
        solve_columns(
            Isa::BASELINE,
            &TREE,
            &factor,
            &inverse_pivot,
            [&mut x, &mut y],
        );
        let (mut x_alone, mut y_alone) = (b, b2);
        solve_columns(
            Isa::BASELINE,
            &TREE,
            &factor,
            &inverse_pivot,
            [&mut x_alone],
        );
        solve_columns(
            Isa::BASELINE,
            &TREE,
            &factor,
            &inverse_pivot,
            [&mut y_alone],
        );
        assert_eq!((x, y), (x_alone, y_alone));
        let m = dense(&factor, &d);
        for (solved, rhs) in [(&x, &b), (&y, &b2)] {
            for c in 0..24 {
                for r in 0..10 {
                    let mx: f64 = (0..10).map(|k| m[r][k] * solved[k][c]).sum();
                    assert!((mx - rhs[r][c]).abs() < 1e-12, "row {r} column {c}");
                }
            }
        }
    }

    /// M⁻¹ = L⁻¹ (D⁻¹ L⁻ᵀ) by the last sweep alone, mirrored: M times it is the identity,
    /// and it is symmetric to the bit.
    #[test]
    fn the_last_sweep_finishes_the_inverse() {
        const TREE: CoordinateTree<10, PAIRS> = CoordinateTree::new(PARENTS);
        let factor: [f64; PAIRS] = core::array::from_fn(|k| 0.3 * (k as f64 * 0.7).sin());
        let d: [f64; 10] = core::array::from_fn(|k| 1.0 + 0.1 * k as f64);
        // D⁻¹ L⁻ᵀ = L M⁻¹, column j from the full solve of M x = e_j.
        let l = dense_l(&factor);
        let mut halfway = [[0.0; 10]; 10];
        for j in 0..10 {
            let mut x = [[0.0; 1]; 10];
            x[j][0] = 1.0;
            solve_columns(Isa::BASELINE, &TREE, &factor, &d.map(|x| 1.0 / x), [&mut x]);
            for (r, row) in halfway.iter_mut().enumerate() {
                row[j] = (0..10).map(|c| l[r][c] * x[c][0]).sum();
            }
        }
        let mut x = halfway;
        solve_lower_columns(Isa::BASELINE, &TREE, &factor, [&mut x]);
        mirror_upper_triangle(&mut x);
        let m = dense(&factor, &d);
        for r in 0..10 {
            for c in 0..10 {
                let mx: f64 = (0..10).map(|k| m[r][k] * x[k][c]).sum();
                let identity = if r == c { 1.0 } else { 0.0 };
                assert!((mx - identity).abs() < 1e-12, "({r}, {c}): {mx}");
                assert_eq!(x[r][c].to_bits(), x[c][r].to_bits());
            }
        }
    }

    #[test]
    #[should_panic(expected = "depth first")]
    fn rejects_a_tree_not_numbered_depth_first() {
        // 0 → 1, 0 → 2, 1 → 3: coordinate 3 descends from 1 but comes after 2.
        let _ = CoordinateTree::<4, 4>::new([None, Some(0), Some(0), Some(1)]);
    }

    #[test]
    #[should_panic(expected = "pairs")]
    fn rejects_a_wrong_factor_length() {
        let _ = CoordinateTree::<3, 2>::new([None, Some(0), Some(1)]);
    }
}
