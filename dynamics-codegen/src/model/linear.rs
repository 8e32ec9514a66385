//! The compile-time f64 linear algebra of the model stage: 3-vectors and 3×3 matrices as
//! plain arrays (a matrix is its rows, `m[i][j]` = row i, column j), rotations from
//! roll-pitch-yaw and axis-angle, and the eigenvalues of a symmetric 3×3 matrix.
//!
//! Rotations feed the generated code's constants, so they are computed in a fixed order of
//! operations: a sum of products always runs left to right, `(a0·b0 + a1·b1) + a2·b2`, and
//! each rotation formula is written out term by term. (These are the orders nalgebra uses
//! for small fixed-size matrices, which this module replaced, so generated code did not
//! change by a bit.) Eigenvalues only feed diagnostics.

/// A 3-vector.
pub(crate) type Vector3 = [f64; 3];
/// A 3×3 matrix, as its rows.
pub(crate) type Matrix3 = [[f64; 3]; 3];

/// The identity matrix.
pub(crate) const IDENTITY: Matrix3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
/// The zero matrix.
pub(crate) const ZERO: Matrix3 = [[0.0; 3]; 3];

/// `a · b`, summed left to right.
pub(crate) fn dot(a: &Vector3, b: &Vector3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// |v|².
pub(crate) fn norm_squared(v: &Vector3) -> f64 {
    dot(v, v)
}

/// The factor that brings v's largest |component| m to 1 when a square of m would overflow
/// or underflow (m above 1e150 or below 1e-150), else 1, so that ordinary vectors are
/// computed as before, bit for bit.
fn rescale(v: &Vector3) -> f64 {
    let m = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if m.is_finite() && m > 0.0 && !(1e-150..=1e150).contains(&m) {
        m
    } else {
        1.0
    }
}

/// |v|, as m·|v/m| when v's components are so large (above 1e154) or small that their
/// squares would overflow or underflow (see [`rescale`]).
pub(crate) fn norm(v: &Vector3) -> f64 {
    let m = rescale(v);
    m * norm_squared(&v.map(|x| x / m)).sqrt()
}

/// v / |v| (not finite for v = 0: callers check the norm first), rescaled first when a
/// square would overflow or underflow (see [`rescale`]).
pub(crate) fn normalize(v: &Vector3) -> Vector3 {
    let m = rescale(v);
    let scaled = v.map(|x| x / m);
    let n = norm_squared(&scaled).sqrt();
    scaled.map(|x| x / n)
}

/// `a + b`.
pub(crate) fn add_vectors(a: &Vector3, b: &Vector3) -> Vector3 {
    std::array::from_fn(|i| a[i] + b[i])
}

/// `a − b`.
pub(crate) fn sub_vectors(a: &Vector3, b: &Vector3) -> Vector3 {
    std::array::from_fn(|i| a[i] - b[i])
}

/// `s · v`.
pub(crate) fn scale_vector(v: &Vector3, s: f64) -> Vector3 {
    v.map(|x| x * s)
}

/// `a b`: entry (i, j) is `(a_i0 b_0j + a_i1 b_1j) + a_i2 b_2j`.
pub(crate) fn mul(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j])
    })
}

/// `a v`.
pub(crate) fn mul_vector(a: &Matrix3, v: &Vector3) -> Vector3 {
    std::array::from_fn(|i| dot(&a[i], v))
}

/// `vᵀ a` (a row vector): entry j is `(v_0 a_0j + v_1 a_1j) + v_2 a_2j`.
pub(crate) fn vector_mul(v: &Vector3, a: &Matrix3) -> Vector3 {
    std::array::from_fn(|j| v[0] * a[0][j] + v[1] * a[1][j] + v[2] * a[2][j])
}

/// `aᵀ`.
pub(crate) fn transpose(a: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

/// `a + b`.
pub(crate) fn add(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| add_vectors(&a[i], &b[i]))
}

/// `a − b`.
pub(crate) fn sub(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| sub_vectors(&a[i], &b[i]))
}

/// `s · a`.
pub(crate) fn scale(a: &Matrix3, s: f64) -> Matrix3 {
    a.map(|row| scale_vector(&row, s))
}

/// The outer product `a bᵀ`.
pub(crate) fn outer(a: &Vector3, b: &Vector3) -> Matrix3 {
    std::array::from_fn(|i| std::array::from_fn(|j| a[i] * b[j]))
}

/// `|x|² 1 − x xᵀ`: the parallel-axis term of a unit mass at `x`, whose inertia about the
/// origin it is (−x̂²).
pub(crate) fn parallel_axis(x: &Vector3) -> Matrix3 {
    sub(&scale(&IDENTITY, norm_squared(x)), &outer(x, x))
}

/// `R a Rᵀ`, computed as `(R a) Rᵀ`.
pub(crate) fn rotate(r: &Matrix3, a: &Matrix3) -> Matrix3 {
    mul(&mul(r, a), &transpose(r))
}

/// The trace, `(a00 + a11) + a22`.
pub(crate) fn trace(a: &Matrix3) -> f64 {
    a[0][0] + a[1][1] + a[2][2]
}

/// The determinant, expanded along the first row.
pub(crate) fn determinant(a: &Matrix3) -> f64 {
    let minor_12_23 = a[1][1] * a[2][2] - a[2][1] * a[1][2];
    let minor_11_23 = a[1][0] * a[2][2] - a[2][0] * a[1][2];
    let minor_11_22 = a[1][0] * a[2][1] - a[2][0] * a[1][1];
    a[0][0] * minor_12_23 - a[0][1] * minor_11_23 + a[0][2] * minor_11_22
}

/// The largest |a_ij|. A NaN entry is skipped unless it comes last in column order (the
/// order in which the rules have always scanned): `max` here is "the first unless the
/// second is larger or unordered".
pub(crate) fn max_abs_entry(a: &Matrix3) -> f64 {
    let mut entries = (0..3).flat_map(|j| (0..3).map(move |i| a[i][j].abs()));
    let first = entries.next().unwrap_or(0.0);
    entries.fold(first, |m, x| if m >= x { m } else { x })
}

/// The rotation of roll r about x, then pitch p about y, then yaw y about z (all about the
/// fixed axes, as URDF's `rpy`): R = Rz(y) Ry(p) Rx(r).
pub(crate) fn rotation_from_rpy(roll: f64, pitch: f64, yaw: f64) -> Matrix3 {
    let (sr, cr) = roll.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let (sy, cy) = yaw.sin_cos();
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// The rotation by `angle` about the unit vector `u` (Rodrigues):
/// R = cos θ · 1 + sin θ · \[u\]× + (1 − cos θ) u uᵀ. A zero angle gives exactly the identity.
pub(crate) fn rotation_from_axis_angle(u: &Vector3, angle: f64) -> Matrix3 {
    if angle == 0.0 {
        return IDENTITY;
    }
    let [ux, uy, uz] = *u;
    let (sqx, sqy, sqz) = (ux * ux, uy * uy, uz * uz);
    let (sin, cos) = angle.sin_cos();
    let one_m_cos = 1.0 - cos;
    [
        [
            sqx + (1.0 - sqx) * cos,
            ux * uy * one_m_cos - uz * sin,
            ux * uz * one_m_cos + uy * sin,
        ],
        [
            ux * uy * one_m_cos + uz * sin,
            sqy + (1.0 - sqy) * cos,
            uy * uz * one_m_cos - ux * sin,
        ],
        [
            ux * uz * one_m_cos - uy * sin,
            uy * uz * one_m_cos + ux * sin,
            sqz + (1.0 - sqz) * cos,
        ],
    ]
}

/// `a × b`.
fn cross(a: &Vector3, b: &Vector3) -> Vector3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The eigenvalues of a symmetric matrix, ascending. Only the lower triangle is read.
///
/// A diagonal matrix gives its diagonal exactly. Otherwise the matrix is scaled by its
/// largest entry and the eigenvalues come in closed form (Smith, "Eigenvalues of a
/// symmetric 3 × 3 matrix", Comm. ACM 4(4), 1961): with q = tr A / 3,
/// p = √(tr (A − q)² / 6) and cos 3φ = det((A − q) / p) / 2 (0 ≤ φ ≤ π/3), they are
/// q + 2p cos(φ + 2πk/3), k = 0, 1, 2.
///
/// The formula alone loses half the digits of two close eigenvalues: there cos 3φ ≈ ±1 and
/// the rounding of the determinant moves φ by up to √ε, splitting a double eigenvalue by
/// ~1e-8 of the spread (enough to make a rank-one inertia look indefinite). So only the
/// eigenvalue standing apart from the other two is taken from it (the largest, k = 0, when
/// cos 3φ ≥ 0, the smallest, k = 1, otherwise; its error is a few ulps), and the other two are the eigenvalues of the
/// 2×2 restriction of A − q to the plane across its eigenvector, in the closed form of a
/// symmetric 2×2 matrix, which has no such cancellation. Every eigenvalue then comes within
/// a few ulps of the largest |a_ij|.
pub(crate) fn symmetric_eigenvalues(a: &Matrix3) -> [f64; 3] {
    let diagonal = [a[0][0], a[1][1], a[2][2]];
    let (a10, a20, a21) = (a[1][0], a[2][0], a[2][1]);
    let sorted = |mut lambda: [f64; 3]| {
        lambda.sort_by(f64::total_cmp);
        lambda
    };
    if a10 == 0.0 && a20 == 0.0 && a21 == 0.0 {
        return sorted(diagonal);
    }
    let s = [diagonal[0], diagonal[1], diagonal[2], a10, a20, a21]
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let (b10, b20, b21) = (a10 / s, a20 / s, a21 / s);
    let d = diagonal.map(|x| x / s);
    let q = (d[0] + d[1] + d[2]) / 3.0;
    // c = A / s − q, symmetric, from the lower triangle.
    let c = [
        [d[0] - q, b10, b20],
        [b10, d[1] - q, b21],
        [b20, b21, d[2] - q],
    ];
    let off = b10 * b10 + b20 * b20 + b21 * b21;
    let p = ((c[0][0] * c[0][0] + c[1][1] * c[1][1] + c[2][2] * c[2][2] + 2.0 * off) / 6.0).sqrt();
    if p == 0.0 {
        // Off-diagonal entries below 1e-154 of the largest, squared to zero.
        return sorted(diagonal);
    }
    let r = (determinant(&c) / (2.0 * p * p * p)).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let k = if r >= 0.0 { 0.0 } else { 1.0 };
    // The eigenvalue of c standing apart, and its eigenvector: the direction that c − apart
    // (rank two) takes to zero, the longest cross product of two of its rows.
    let apart = 2.0 * p * (phi + k * 2.0 * std::f64::consts::FRAC_PI_3).cos();
    let n = sub(&c, &scale(&IDENTITY, apart));
    let v = [
        cross(&n[0], &n[1]),
        cross(&n[0], &n[2]),
        cross(&n[1], &n[2]),
    ]
    .into_iter()
    .max_by(|x, y| norm_squared(x).total_cmp(&norm_squared(y)))
    .unwrap_or_default();
    let length = norm(&v);
    if length.is_nan() {
        return [f64::NAN; 3];
    }
    if length == 0.0 {
        // Not reached in exact arithmetic (p > 0: the eigenvalues are not all equal); should
        // rounding get here, the formula's own three values.
        let largest = 2.0 * p * phi.cos();
        let smallest = 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos();
        return sorted([smallest, -largest - smallest, largest].map(|x| (x + q) * s));
    }
    let v = v.map(|x| x / length);
    // An orthonormal basis (u, w) of the plane across v, u along the cross product with the
    // coordinate axis least aligned with v.
    let least = (0..3)
        .min_by(|&i, &j| v[i].abs().total_cmp(&v[j].abs()))
        .unwrap_or(0);
    let mut axis = [0.0; 3];
    axis[least] = 1.0;
    let u = normalize(&cross(&v, &axis));
    let w = cross(&v, &u);
    let (cu, cw) = (mul_vector(&c, &u), mul_vector(&c, &w));
    let (uu, ww, uw) = (
        dot(&u, &cu),
        dot(&w, &cw),
        (dot(&u, &cw) + dot(&w, &cu)) / 2.0,
    );
    let mean = (uu + ww) / 2.0;
    let radius = ((uu - ww) / 2.0).hypot(uw);
    sorted([apart, mean - radius, mean + radius].map(|x| (x + q) * s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    fn assert_close(a: &Matrix3, b: &Matrix3, tolerance: f64) {
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (a[i][j] - b[i][j]).abs() <= tolerance,
                    "entry ({i}, {j}): {a:?} vs {b:?}"
                );
            }
        }
    }

    /// The rotation about one coordinate axis, written out.
    fn about(axis: usize, angle: f64) -> Matrix3 {
        let (s, c) = angle.sin_cos();
        match axis {
            0 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
            1 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
            _ => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
        }
    }

    /// A small deterministic generator (xorshift), uniform in [-1, 1).
    struct Random(u64);
    impl Random {
        fn next(&mut self) -> f64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    #[test]
    fn quarter_turns_of_rpy() {
        let e = 1e-15;
        // A quarter roll takes y to z; a quarter pitch takes z to x; a quarter yaw x to y.
        assert_close(
            &rotation_from_rpy(FRAC_PI_2, 0.0, 0.0),
            &[[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
            e,
        );
        assert_close(
            &rotation_from_rpy(0.0, FRAC_PI_2, 0.0),
            &[[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
            e,
        );
        assert_close(
            &rotation_from_rpy(0.0, 0.0, FRAC_PI_2),
            &[[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            e,
        );
        // Roll first, then pitch, then yaw, about the fixed axes: Rz Ry Rx.
        assert_close(
            &rotation_from_rpy(FRAC_PI_2, FRAC_PI_2, 0.0),
            &[[0.0, 1.0, 0.0], [0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]],
            e,
        );
        assert_eq!(rotation_from_rpy(0.0, 0.0, 0.0), IDENTITY);
    }

    #[test]
    fn rpy_is_yaw_pitch_roll_product() {
        let mut random = Random(0x9e37_79b9_7f4a_7c15);
        for _ in 0..200 {
            let [r, p, y] = [random.next() * PI, random.next() * PI, random.next() * PI];
            let expected = mul(&mul(&about(2, y), &about(1, p)), &about(0, r));
            let rotation = rotation_from_rpy(r, p, y);
            assert_close(&rotation, &expected, 4e-16);
            assert_close(&mul(&transpose(&rotation), &rotation), &IDENTITY, 4e-15);
            assert!((determinant(&rotation) - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn axis_angle_about_coordinate_axes_and_in_general() {
        for axis in 0..3 {
            let mut u = [0.0; 3];
            u[axis] = 1.0;
            for angle in [FRAC_PI_2, -0.3, PI, 2.5] {
                assert_close(
                    &rotation_from_axis_angle(&u, angle),
                    &about(axis, angle),
                    4e-16,
                );
            }
        }
        assert_eq!(rotation_from_axis_angle(&[0.0, 0.6, 0.8], 0.0), IDENTITY);
        let mut random = Random(12345);
        for _ in 0..200 {
            let u = normalize(&[random.next(), random.next(), random.next()]);
            let angle = random.next() * PI;
            let rotation = rotation_from_axis_angle(&u, angle);
            // The axis is fixed, a vector across it turns by the angle.
            assert!(sub_vectors(&mul_vector(&rotation, &u), &u)
                .iter()
                .all(|x| x.abs() < 1e-15));
            let across = normalize(&[u[1], -u[0], 0.0]);
            let turned = mul_vector(&rotation, &across);
            assert!((dot(&turned, &across) - angle.cos()).abs() < 1e-15);
            assert_close(&mul(&transpose(&rotation), &rotation), &IDENTITY, 4e-15);
            // Rodrigues' formula assembled from matrices: cos θ 1 + sin θ [u]× + (1 − cos θ) u uᵀ.
            let cross = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
            let expected = add(
                &add(&scale(&IDENTITY, angle.cos()), &scale(&cross, angle.sin())),
                &scale(&outer(&u, &u), 1.0 - angle.cos()),
            );
            assert_close(&rotation, &expected, 4e-16);
        }
    }

    #[test]
    fn products_sum_left_to_right() {
        let a = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0], [7.0, 8.0, 10.0]];
        let b = [[0.5, 0.0, -1.0], [2.0, 1.0, 0.0], [0.0, 3.0, 1.0]];
        assert_eq!(
            mul(&a, &b),
            [[4.5, 11.0, 2.0], [12.0, 23.0, 2.0], [19.5, 38.0, 3.0]]
        );
        assert_eq!(mul_vector(&a, &[1.0, 0.0, -1.0]), [-2.0, -2.0, -3.0]);
        assert_eq!(vector_mul(&[1.0, 0.0, -1.0], &a), [-6.0, -6.0, -7.0]);
        assert_eq!(determinant(&a), -3.0);
        assert_eq!(trace(&a), 16.0);
        assert_eq!(rotate(&IDENTITY, &a), a);
        // (0.1 + 0.2) + 0.3 ≠ 0.1 + (0.2 + 0.3) in f64: the order is fixed.
        assert_eq!(dot(&[0.1, 0.2, 0.3], &[1.0; 3]), (0.1 + 0.2) + 0.3);
        assert_eq!(
            max_abs_entry(&[[1.0, -7.0, 2.0], [0.0; 3], [3.0, 0.0, -6.5]]),
            7.0
        );
    }

    /// The characteristic polynomial det(λ − A) = λ³ − c2 λ² + c1 λ − c0, from the invariants.
    fn characteristic(a: &Matrix3, lambda: f64) -> f64 {
        let c2 = trace(a);
        let c1 = a[0][0] * a[1][1] - a[0][1] * a[1][0] + a[0][0] * a[2][2] - a[0][2] * a[2][0]
            + a[1][1] * a[2][2]
            - a[1][2] * a[2][1];
        let c0 = determinant(a);
        ((lambda - c2) * lambda + c1) * lambda - c0
    }

    /// Checks eigenvalues against invariants computed independently: the trace is their sum,
    /// the determinant their product, the sum of the principal 2×2 minors the sum of their
    /// pairwise products, and each is a root of the characteristic polynomial.
    fn assert_eigenvalues(a: &Matrix3, lambda: [f64; 3]) {
        let size = a.iter().flatten().fold(0.0_f64, |m, x| m.max(x.abs()));
        assert!(
            lambda[0] <= lambda[1] && lambda[1] <= lambda[2],
            "{lambda:?}"
        );
        let [l0, l1, l2] = lambda;
        let e = 1e-13 * size;
        assert!(
            (l0 + l1 + l2 - trace(a)).abs() <= e,
            "trace of {a:?}: {lambda:?}"
        );
        assert!(
            (l0 * l1 * l2 - determinant(a)).abs() <= e * size * size,
            "determinant of {a:?}: {lambda:?}"
        );
        let minors = a[0][0] * a[1][1] - a[0][1] * a[1][0] + a[0][0] * a[2][2] - a[0][2] * a[2][0]
            + a[1][1] * a[2][2]
            - a[1][2] * a[2][1];
        assert!(
            (l0 * l1 + l0 * l2 + l1 * l2 - minors).abs() <= e * size,
            "minors of {a:?}: {lambda:?}"
        );
        for l in lambda {
            // The residual, relative to the polynomial's scale at that point.
            let scale = (l.abs() + size).powi(3);
            assert!(
                characteristic(a, l).abs() <= 1e-13 * scale,
                "residual at {l} for {a:?}"
            );
        }
    }

    #[test]
    fn eigenvalues_of_a_diagonal_matrix_are_its_diagonal_exactly() {
        let a = [[0.3, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]];
        assert_eq!(symmetric_eigenvalues(&a), [0.1, 0.1, 0.3]);
        assert_eq!(symmetric_eigenvalues(&ZERO), [0.0; 3]);
        let a = [[-2.0, 0.0, 0.0], [0.0, 5e-300, 0.0], [0.0, 0.0, 1e300]];
        assert_eq!(symmetric_eigenvalues(&a), [-2.0, 5e-300, 1e300]);
    }

    #[test]
    fn eigenvalues_of_known_matrices() {
        // The products-of-inertia example of the UI catalog: −0.1, 0.1, 0.3.
        let a = [[0.1, 0.2, 0.0], [0.2, 0.1, 0.0], [0.0, 0.0, 0.1]];
        let lambda = symmetric_eigenvalues(&a);
        for (l, expected) in lambda.iter().zip([-0.1, 0.1, 0.3]) {
            assert!((l - expected).abs() < 1e-16, "{lambda:?}");
        }
        // [[2, 1, 0], [1, 2, 1], [0, 1, 2]]: 2 − √2, 2, 2 + √2.
        let a = [[2.0, 1.0, 0.0], [1.0, 2.0, 1.0], [0.0, 1.0, 2.0]];
        let lambda = symmetric_eigenvalues(&a);
        let sqrt2 = 2.0_f64.sqrt();
        for (l, expected) in lambda.iter().zip([2.0 - sqrt2, 2.0, 2.0 + sqrt2]) {
            assert!((l - expected).abs() < 4e-15, "{lambda:?}");
        }
        // All ones: 0, 0, 3 (a double eigenvalue, the case of r = −1).
        let lambda = symmetric_eigenvalues(&[[1.0; 3]; 3]);
        assert!((lambda[2] - 3.0).abs() < 1e-15, "{lambda:?}");
        assert!(
            lambda[0].abs() < 1e-15 && lambda[1].abs() < 1e-15,
            "{lambda:?}"
        );
        // A multiple of the identity is diagonal; a rotated one is not, but stays put.
        let r = rotation_from_rpy(0.3, -1.1, 2.0);
        let lambda = symmetric_eigenvalues(&rotate(&r, &scale(&IDENTITY, 2.5)));
        assert!(lambda.iter().all(|l| (l - 2.5).abs() < 1e-14), "{lambda:?}");
    }

    #[test]
    fn eigenvalues_of_rotated_diagonal_matrices_are_the_diagonal() {
        let mut random = Random(0xdead_beef);
        for case in 0..500 {
            let mut d = [random.next(), random.next(), random.next()];
            match case % 4 {
                1 => d[1] = d[0],          // a repeated eigenvalue
                2 => d = [0.0, 0.0, d[2]], // a repeated zero (rank one)
                3 => d[0] = d[2] * 1e-9,   // widely spread magnitudes
                _ => {}
            }
            let scale_factor = 10f64.powi((random.next() * 20.0) as i32);
            let d = d.map(|x| x * scale_factor);
            let r = rotation_from_rpy(random.next() * PI, random.next() * PI, random.next() * PI);
            let diagonal = [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]];
            let a = rotate(&r, &diagonal);
            let lambda = symmetric_eigenvalues(&a);
            let mut expected = d;
            expected.sort_by(f64::total_cmp);
            let size = d.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            // Every eigenvalue to a few ulps of the matrix, repeated ones too.
            for (l, e) in lambda.iter().zip(expected) {
                assert!(
                    (l - e).abs() <= 1e-14 * size,
                    "{a:?}: {lambda:?} vs {expected:?}"
                );
            }
            assert_eigenvalues(&a, lambda);
        }
    }

    #[test]
    fn eigenvalues_of_random_symmetric_matrices_satisfy_the_invariants() {
        let mut random = Random(42);
        for _ in 0..1000 {
            let (a00, a11, a22) = (random.next(), random.next(), random.next());
            let (a01, a02, a12) = (random.next(), random.next(), random.next());
            let a = [[a00, a01, a02], [a01, a11, a12], [a02, a12, a22]];
            assert_eigenvalues(&a, symmetric_eigenvalues(&a));
        }
    }
}
