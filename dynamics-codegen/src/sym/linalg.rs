//! 3-vectors and 3×3 matrices of nodes, for writing the textbook's equations.
//!
//! Every operation goes through the graph's builders, so zero and unit entries fold away:
//! a rotation about `z` times a vector costs four products and two sums, not nine and six.
//! Sums are evaluated left to right (`a₀b₀ + a₁b₁ + a₂b₂` as `(a₀b₀ + a₁b₁) + a₂b₂`).

use super::{Graph, Node};

/// A column 3-vector of nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Vec3(pub [Node; 3]);

/// A 3×3 matrix of nodes, row-major: `self.0[row][col]`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Mat3(pub [[Node; 3]; 3]);

impl Vec3 {
    /// The vector `(x, y, z)`.
    #[must_use]
    pub fn new(x: Node, y: Node, z: Node) -> Self {
        Vec3([x, y, z])
    }

    /// The zero vector.
    pub fn zero(g: &Graph) -> Self {
        let z = g.zero();
        Vec3([z; 3])
    }

    /// A constant vector.
    pub fn constant(g: &Graph, v: [f64; 3]) -> Self {
        Vec3(v.map(|x| g.constant(x)))
    }

    /// Component `i`.
    #[must_use]
    pub fn get(self, i: usize) -> Node {
        self.0[i]
    }

    /// `self + other`.
    pub fn add(self, g: &Graph, other: Vec3) -> Vec3 {
        Vec3([0, 1, 2].map(|i| g.add(self.0[i], other.0[i])))
    }

    /// `self − other`.
    pub fn sub(self, g: &Graph, other: Vec3) -> Vec3 {
        Vec3([0, 1, 2].map(|i| g.sub(self.0[i], other.0[i])))
    }

    /// `−self`.
    pub fn neg(self, g: &Graph) -> Vec3 {
        Vec3(self.0.map(|x| g.neg(x)))
    }

    /// Lane k of each component (`Graph::lane`: a scalar component is its own every lane).
    pub fn lane(self, g: &Graph, k: usize) -> Vec3 {
        Vec3(self.0.map(|x| g.lane(x, k)))
    }

    /// `s · self`.
    pub fn scale(self, g: &Graph, s: Node) -> Vec3 {
        Vec3(self.0.map(|x| g.mul(s, x)))
    }

    /// `selfᵀ other`.
    pub fn dot(self, g: &Graph, other: Vec3) -> Node {
        let [a, b] = [self.0, other.0];
        g.sum(&[g.mul(a[0], b[0]), g.mul(a[1], b[1]), g.mul(a[2], b[2])])
    }

    /// `self × other`.
    pub fn cross(self, g: &Graph, other: Vec3) -> Vec3 {
        let [a, b] = [self.0, other.0];
        let term = |i: usize, j: usize| g.sub(g.mul(a[i], b[j]), g.mul(a[j], b[i]));
        Vec3([term(1, 2), term(2, 0), term(0, 1)])
    }

    /// The skew-symmetric matrix `[self×]` with `[self×] w = self × w`.
    pub fn cross_matrix(self, g: &Graph) -> Mat3 {
        let [x, y, z] = self.0;
        let o = g.zero();
        Mat3([
            [o, g.neg(z), y], //
            [z, o, g.neg(x)],
            [g.neg(y), x, o],
        ])
    }
}

impl Mat3 {
    /// Lane k of each entry (`Graph::lane`: a scalar entry is its own every lane).
    pub fn lane(self, g: &Graph, k: usize) -> Mat3 {
        Mat3(self.0.map(|row| row.map(|x| g.lane(x, k))))
    }

    /// The matrix with these rows.
    #[must_use]
    pub fn from_rows(rows: [Vec3; 3]) -> Self {
        Mat3(rows.map(|r| r.0))
    }

    /// The zero matrix.
    pub fn zero(g: &Graph) -> Self {
        let z = g.zero();
        Mat3([[z; 3]; 3])
    }

    /// The identity matrix.
    pub fn identity(g: &Graph) -> Self {
        Self::constant(g, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    }

    /// A constant matrix, row-major.
    pub fn constant(g: &Graph, m: [[f64; 3]; 3]) -> Self {
        Mat3(m.map(|row| row.map(|x| g.constant(x))))
    }

    /// Entry `(row, col)`.
    #[must_use]
    pub fn get(self, row: usize, col: usize) -> Node {
        self.0[row][col]
    }

    /// Row `i` as a vector.
    #[must_use]
    pub fn row(self, i: usize) -> Vec3 {
        Vec3(self.0[i])
    }

    /// Column `j` as a vector.
    #[must_use]
    pub fn col(self, j: usize) -> Vec3 {
        Vec3([self.0[0][j], self.0[1][j], self.0[2][j]])
    }

    /// `selfᵀ` (free: no node is created).
    #[must_use]
    pub fn transpose(self) -> Mat3 {
        Mat3([0, 1, 2].map(|i| self.col(i).0))
    }

    /// `self + other`.
    pub fn add(self, g: &Graph, other: Mat3) -> Mat3 {
        Mat3([0, 1, 2].map(|i| self.row(i).add(g, other.row(i)).0))
    }

    /// `self − other`.
    pub fn sub(self, g: &Graph, other: Mat3) -> Mat3 {
        Mat3([0, 1, 2].map(|i| self.row(i).sub(g, other.row(i)).0))
    }

    /// `s · self`.
    pub fn scale(self, g: &Graph, s: Node) -> Mat3 {
        Mat3(self.0.map(|row| Vec3(row).scale(g, s).0))
    }

    /// `self · v`.
    pub fn mul_vec(self, g: &Graph, v: Vec3) -> Vec3 {
        Vec3([0, 1, 2].map(|i| self.row(i).dot(g, v)))
    }

    /// `self · other`.
    pub fn mul(self, g: &Graph, other: Mat3) -> Mat3 {
        Mat3([0, 1, 2].map(|i| [0, 1, 2].map(|j| self.row(i).dot(g, other.col(j)))))
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Array, Graph, Node};
    use super::{Mat3, Vec3};

    fn symbols(g: &Graph, array: Array) -> Vec3 {
        Vec3([0, 1, 2].map(|i| g.input(array, i)))
    }

    fn values(g: &Graph, v: Vec3, x: &[f64], y: &[f64]) -> Vec<f64> {
        g.eval(
            |r| match r.array {
                Array::Q => x[r.index as usize],
                _ => y[r.index as usize],
            },
            &v.0,
        )
    }

    #[test]
    fn vector_algebra_matches_hand_values() {
        let g = Graph::new();
        let (a, b) = (symbols(&g, Array::Q), symbols(&g, Array::V));
        let (x, y) = ([1.0, 2.0, 3.0], [-4.0, 0.5, 2.0]);
        assert_eq!(values(&g, a.cross(&g, b), &x, &y), vec![2.5, -14.0, 8.5]);
        assert_eq!(values(&g, a.add(&g, b), &x, &y), vec![-3.0, 2.5, 5.0]);
        assert_eq!(values(&g, a.sub(&g, b), &x, &y), vec![5.0, 1.5, 1.0]);
        let dot = a.dot(&g, b);
        assert_eq!(
            g.eval(|r| [x, y][r.array as usize][r.index as usize], &[dot]),
            vec![3.0]
        );
        let cm = a.cross_matrix(&g).mul_vec(&g, b);
        assert_eq!(values(&g, cm, &x, &y), vec![2.5, -14.0, 8.5]);
    }

    #[test]
    fn zero_entries_cost_nothing() {
        let g = Graph::new();
        let c = g.cos(g.input(Array::Q, 0));
        let s = g.sin(g.input(Array::Q, 0));
        let o = g.zero();
        let l = g.one();
        let rz = Mat3([[c, g.neg(s), o], [s, c, o], [o, o, l]]);
        let v = symbols(&g, Array::V);
        let w = rz.mul_vec(&g, v);
        assert_eq!(w.get(2), v.get(2));
        let count = g.op_count(&w.0);
        assert_eq!((count.mul, count.add, count.neg), (4, 2, 0));

        // A rotation about z leaves a vector along z unchanged, at no cost.
        let ez = Vec3::new(o, o, g.input(Array::A, 0));
        assert_eq!(rz.mul_vec(&g, ez), ez);
        assert_eq!(g.op_count(&Vec3::zero(&g).cross(&g, v).0).mul, 0);
    }

    #[test]
    fn matrix_products_and_transpose() {
        let g = Graph::new();
        let m = Mat3::constant(&g, [[1.0, 2.0, 0.0], [0.0, 1.0, -1.0], [3.0, 0.0, 1.0]]);
        let id = Mat3::identity(&g);
        assert_eq!(m.mul(&g, id), m);
        assert_eq!(id.mul(&g, m), m);
        assert_eq!(m.transpose().transpose(), m);
        assert_eq!(m.transpose().get(0, 2), m.get(2, 0));
        let mm = m.mul(&g, m.transpose());
        let expected = [[5.0, 2.0, 3.0], [2.0, 2.0, -1.0], [3.0, -1.0, 10.0]];
        assert_eq!(mm, Mat3::constant(&g, expected));
        assert_eq!(m.add(&g, m), m.scale(&g, g.constant(2.0)));
        assert_eq!(m.sub(&g, m), Mat3::zero(&g));
        let v: Vec3 = Vec3::constant(&g, [1.0, 1.0, 1.0]);
        assert_eq!(m.mul_vec(&g, v), Vec3::constant(&g, [3.0, 0.0, 4.0]));
        let n: Node = v.neg(&g).dot(&g, v);
        assert_eq!(g.constant_value(n), Some(-3.0));
    }
}
