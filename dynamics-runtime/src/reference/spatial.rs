//! Six-dimensional (spatial) algebra, ordered linear first as in the textbook.
//!
//! A motion vector of a body, referred to a point P, is `m = [v_P; ω]` (v_P the velocity of
//! the body point at P); a force vector is `f = [F; M_P]`. The textbook's coupled
//! six-dimensional matrix is the spatial inertia about P (Satici ch. 10, "The coupled
//! six-dimensional equation"):
//!
//! ```text
//!     I = [ m 1    −m ĉ ]      I_P = I_G − m ĉ²,   c = PG,   ĉ x = c × x
//!         [ m ĉ     I_P ]
//! ```
//!
//! For a frame B whose pose in frame A is (R, p) (`x_A = R x_B + p`), Featherstone's
//! coordinate transforms (RBDA eq. 2.24 and 2.25, with the blocks reordered linear first) are
//!
//! ```text
//!     motion, A → B:  X = [ Rᵀ   −Rᵀ p̂ ]       force, B → A:  Xᵀ = [ R     0 ]
//!                         [ 0     Rᵀ   ]                            [ p̂ R   R ]
//! ```
//!
//! and the cross products (RBDA eq. 2.31 and 2.32, reordered) are
//! `v × m = [ω × m_lin + v_P × m_ang; ω × m_ang]` and
//! `v ×* f = [ω × F; ω × M_P + v_P × F]`, with `v ×* = −(v ×)ᵀ`.

use super::{Motion, Pose};
use crate::scalar::Scalar;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// ĉ, the matrix of the cross product: `skew(c) x = c × x`.
pub(crate) fn skew<T: Scalar>(c: &Vector3<T>) -> Matrix3<T> {
    let z = T::zero();
    Matrix3::new(z, -c[2], c[1], c[2], z, -c[0], -c[1], c[0], z)
}

/// Linear and angular parts of a six-vector.
pub(crate) fn split<T: Scalar>(m: &Vector6<T>) -> (Vector3<T>, Vector3<T>) {
    (
        Vector3::new(m[0], m[1], m[2]),
        Vector3::new(m[3], m[4], m[5]),
    )
}

/// The six-vector `[lin; ang]`.
pub(crate) fn join<T: Scalar>(lin: &Vector3<T>, ang: &Vector3<T>) -> Vector6<T> {
    Vector6::new(lin[0], lin[1], lin[2], ang[0], ang[1], ang[2])
}

/// Builds a 6×6 matrix from its four 3×3 blocks.
pub(crate) fn blocks<T: Scalar>(
    top_left: &Matrix3<T>,
    top_right: &Matrix3<T>,
    bottom_left: &Matrix3<T>,
    bottom_right: &Matrix3<T>,
) -> Matrix6<T> {
    let mut m = Matrix6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(top_left);
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(top_right);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(bottom_left);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(bottom_right);
    m
}

/// The spatial inertia about the frame origin P, `[[m1, −m ĉ], [m ĉ, I_G − m ĉ²]]`, from m,
/// c = PG and I_G, all in the same frame.
pub(crate) fn spatial_inertia<T: Scalar>(
    mass: T,
    com: &Vector3<T>,
    inertia_com: &Matrix3<T>,
) -> Matrix6<T> {
    let c_hat = skew(com);
    let m_c_hat = c_hat * mass;
    let inertia_origin = inertia_com - m_c_hat * c_hat;
    blocks(
        &(Matrix3::identity() * mass),
        &(-m_c_hat),
        &m_c_hat,
        &inertia_origin,
    )
}

/// Motion transform X from parent to body coordinates, for the body's pose (R, p) in the
/// parent: `X = [[Rᵀ, −Rᵀ p̂], [0, Rᵀ]]`.
pub(crate) fn motion_transform<T: Scalar>(
    rotation_in_parent: &Matrix3<T>,
    origin_in_parent: &Vector3<T>,
) -> Matrix6<T> {
    let rt = rotation_in_parent.transpose();
    blocks(
        &rt,
        &(-(rt * skew(origin_in_parent))),
        &Matrix3::zeros(),
        &rt,
    )
}

/// A motion vector of body coordinates expressed in world coordinates about the world
/// origin: `[R m_lin + p × R m_ang; R m_ang]`.
pub(crate) fn motion_to_world<T: Scalar>(pose: &Pose<T>, m: &Vector6<T>) -> Vector6<T> {
    let (lin, ang) = split(m);
    let ang_world = pose.rotation_in_world * ang;
    let lin_world = pose.rotation_in_world * lin + pose.origin_in_world.cross(&ang_world);
    join(&lin_world, &ang_world)
}

/// Motion cross product `v × m = [ω × m_lin + v_P × m_ang; ω × m_ang]`.
pub(crate) fn motion_cross<T: Scalar>(v: &Vector6<T>, m: &Vector6<T>) -> Vector6<T> {
    let (v_lin, omega) = split(v);
    let (m_lin, m_ang) = split(m);
    join(
        &(omega.cross(&m_lin) + v_lin.cross(&m_ang)),
        &omega.cross(&m_ang),
    )
}

/// Force cross product `v ×* f = [ω × F; ω × M_P + v_P × F]`.
pub(crate) fn force_cross<T: Scalar>(v: &Vector6<T>, f: &Vector6<T>) -> Vector6<T> {
    let (v_lin, omega) = split(v);
    let (force, moment) = split(f);
    join(
        &omega.cross(&force),
        &(omega.cross(&moment) + v_lin.cross(&force)),
    )
}

/// The matrix of `m ↦ v × m`: `[[ω̂, v̂_P], [0, ω̂]]`.
pub(crate) fn motion_cross_matrix<T: Scalar>(v: &Vector6<T>) -> Matrix6<T> {
    let (v_lin, omega) = split(v);
    let omega_hat = skew(&omega);
    blocks(&omega_hat, &skew(&v_lin), &Matrix3::zeros(), &omega_hat)
}

/// The matrix of `f ↦ v ×* f`: `[[ω̂, 0], [v̂_P, ω̂]] = −(v ×)ᵀ`.
pub(crate) fn force_cross_matrix<T: Scalar>(v: &Vector6<T>) -> Matrix6<T> {
    let (v_lin, omega) = split(v);
    let omega_hat = skew(&omega);
    blocks(&omega_hat, &Matrix3::zeros(), &skew(&v_lin), &omega_hat)
}

/// The matrix `f ×̄` defined by `(f ×̄) v = v ×* f` (Echeandia & Wensing 2021):
/// `[[0, −F̂], [−F̂, −M̂_P]]`, which is skew-symmetric.
pub(crate) fn force_bar_matrix<T: Scalar>(f: &Vector6<T>) -> Matrix6<T> {
    let (force, moment) = split(f);
    let minus_f_hat = -skew(&force);
    blocks(
        &Matrix3::zeros(),
        &minus_f_hat,
        &minus_f_hat,
        &(-skew(&moment)),
    )
}

/// The motion subspace S of a joint in the body frame, in the first `nv` columns:
/// revolute `[0; s]`, prismatic `[s; 0]`, free-flyer the 6×6 identity.
pub(crate) fn motion_subspace<T: Scalar>(motion: &Motion<T>) -> Matrix6<T> {
    let zero = Vector3::zeros();
    match motion {
        Motion::Revolute { axis } => {
            let mut s = Matrix6::zeros();
            s.set_column(0, &join(&zero, axis));
            s
        }
        Motion::Prismatic { axis } => {
            let mut s = Matrix6::zeros();
            s.set_column(0, &join(axis, &zero));
            s
        }
        Motion::FreeFlyer => Matrix6::identity(),
    }
}

/// Solves `A x = b` for a symmetric positive-definite 6×6 `A` by LDLᵀ without pivoting
/// (no comparisons, so it works for every [`Scalar`]). The result is meaningless (NaN or
/// infinite) if A is not positive definite.
pub(crate) fn solve_spd6<T: Scalar>(a: &Matrix6<T>, b: &Vector6<T>) -> Vector6<T> {
    let mut l = Matrix6::<T>::identity();
    let mut d = Vector6::<T>::zeros();
    for j in 0..6 {
        let mut d_j = a[(j, j)];
        for k in 0..j {
            d_j -= l[(j, k)] * l[(j, k)] * d[k];
        }
        d[j] = d_j;
        for i in (j + 1)..6 {
            let mut l_ij = a[(i, j)];
            for k in 0..j {
                l_ij -= l[(i, k)] * l[(j, k)] * d[k];
            }
            l[(i, j)] = l_ij / d_j;
        }
    }
    // L y = b, then D z = y, then Lᵀ x = z (in place).
    let mut x = *b;
    for i in 0..6 {
        for k in 0..i {
            let lx = l[(i, k)] * x[k];
            x[i] -= lx;
        }
    }
    for i in 0..6 {
        x[i] /= d[i];
    }
    for i in (0..6).rev() {
        for k in (i + 1)..6 {
            let lx = l[(k, i)] * x[k];
            x[i] -= lx;
        }
    }
    x
}
