//! Denavit–Hartenberg placements: a joint's `placement: dh(a, alpha, d, theta)` (standard)
//! or `placement: mdh(..)` (modified, Craig's) turned into what every other joint has (the
//! joint frame's pose in the parent body's frame, the axis z) plus, for the standard form,
//! the pose of the child body's declared frame in its model frame.
//!
//! Modified DH (Craig), on joint i the row (a_{i−1}, α_{i−1}, d_i, θ_i):
//! frame i = frame i−1 · Rx(α) Tx(a) Rz(θ + q) Tz(d) (revolute; d + q for prismatic). The
//! joint frame is placed by rotation Rx(α) Rz(θ) and translation [a, 0, 0] + Rx(α) [0, 0, d]
//! and the child's frame is Craig's frame i, the joint frame after the motion, as for any
//! joint: nothing else changes.
//!
//! Standard DH, on joint i the row (a_i, α_i, d_i, θ_i):
//! frame i = frame i−1 · Rz(θ + q) Tz(d) Tx(a) Rx(α), the joint's axis z of frame i−1. The
//! joint frame is placed by rotation Rz(θ) and translation [0, 0, d] in the parent's
//! declared frame (frame i−1); after the motion it is Craig's frame i, the child's model
//! frame (the frame the tree and every generated pose use). The child's declared frame, the
//! DH link frame i in which the user gives its mass centre, inertia, loads, frames,
//! constraint points and its children's placements, is that frame times the constant
//! C = Tx(a) Rx(α): x_model = R_C x_declared + t_C, with R_C = Rx(α), t_C = [a, 0, 0].
//!
//! C is applied in one place: the tree builder ([`super::tree`]) already places every
//! declared body in the frame of the tree body it moves with (a body welded through fixed
//! joints sits at its welds' composed placement), and everything declared "in a body's
//! frame" (joints whose parent it is, loads, operational frames, constraint points, bodies
//! welded to it) goes through that placement. A standard-DH body starts out placed at C in
//! its own tree body instead of at the identity, and its own mass centre and inertia are
//! carried by C as a welded part's are.
//!
//! Angles are constants (they are rotations); lengths may be parameters (they are
//! translations, affine in the parameters like `at`).

use super::value::{self, Value, Vec3};
use crate::syntax::DhConvention;

/// A rigid placement of an inner frame in an outer one: `x_outer = rotation x_inner +
/// translation`. The rotation is a constant (rows), the translation affine in the
/// parameters.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Pose {
    /// Rotation from the inner frame to the outer frame, by rows.
    pub rotation: [[f64; 3]; 3],
    /// The inner frame's origin in the outer frame.
    pub translation: Vec3,
}

impl Pose {
    /// A point of the inner frame in the outer frame.
    pub fn point(&self, p: &Vec3) -> Vec3 {
        value::add(&value::rotate(&self.rotation, p), &self.translation)
    }
}

/// A resolved row of a DH table: the angles constant, the lengths affine in the parameters.
pub(crate) struct Row {
    /// Link length a (m).
    pub a: Value,
    /// Link twist α (rad).
    pub alpha: f64,
    /// Link offset d (m) at q = 0.
    pub d: Value,
    /// Joint angle θ (rad) at q = 0.
    pub theta: f64,
}

/// A DH row as the tree sees it.
pub(crate) struct Placed {
    /// The joint frame in the parent body's declared frame; the joint moves about or along
    /// its z axis.
    pub joint: Pose,
    /// The child body's declared frame in its model frame (the joint frame after the
    /// motion): C = Tx(a) Rx(α) for standard DH, `None` (the same frame) for modified DH
    /// and for a standard row with a = 0 and α = 0.
    pub child: Option<Pose>,
}

/// Rx(angle), by rows, with `snap` applied (entries within 1e-15 of 0 or ±1 made exact).
fn rotation_x(angle: f64, snap: fn(&[[f64; 3]; 3]) -> [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    snap(&[[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
}

/// Rz(angle), by rows, with `snap` applied.
fn rotation_z(angle: f64, snap: fn(&[[f64; 3]; 3]) -> [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let (s, c) = angle.sin_cos();
    snap(&[[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
}

fn zero() -> Value {
    Value::constant(0.0)
}

/// Places a joint by a DH row of either convention. `snap` is resolution's clean-up of
/// rotation entries (so that α = π/2 is exactly a quarter turn).
///
/// The modified placement is composed with the same arithmetic as the tree composes a
/// standard row's joint with its parent's C, so that a table declared both ways gives the
/// same numbers, bit for bit.
pub(crate) fn place(
    convention: DhConvention,
    row: Row,
    snap: fn(&[[f64; 3]; 3]) -> [[f64; 3]; 3],
) -> Placed {
    let rx = rotation_x(row.alpha, snap);
    let rz = rotation_z(row.theta, snap);
    let along_x: Vec3 = [row.a, zero(), zero()];
    let along_z: Vec3 = [zero(), zero(), row.d];
    match convention {
        DhConvention::Modified => {
            let twist = Pose {
                rotation: rx,
                translation: along_x,
            };
            Placed {
                joint: Pose {
                    rotation: value::rotation_product(&rx, &rz),
                    translation: twist.point(&along_z),
                },
                child: None,
            }
        }
        DhConvention::Standard => {
            let child = Pose {
                rotation: rx,
                translation: along_x,
            };
            let identity = child.rotation == super::linear::IDENTITY
                && child.translation.iter().all(|t| *t == zero());
            Placed {
                joint: Pose {
                    rotation: rz,
                    translation: along_z,
                },
                child: (!identity).then_some(child),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    type M4 = [[f64; 4]; 4];

    fn mul4(a: &M4, b: &M4) -> M4 {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
    }

    /// The elementary homogeneous transforms, written out.
    fn rx(t: f64) -> M4 {
        let (s, c) = t.sin_cos();
        [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, c, -s, 0.0],
            [0.0, s, c, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }
    fn rz(t: f64) -> M4 {
        let (s, c) = t.sin_cos();
        [
            [c, -s, 0.0, 0.0],
            [s, c, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }
    fn translation(x: f64, y: f64, z: f64) -> M4 {
        [
            [1.0, 0.0, 0.0, x],
            [0.0, 1.0, 0.0, y],
            [0.0, 0.0, 1.0, z],
            [0.0, 0.0, 0.0, 1.0],
        ]
    }

    fn homogeneous(pose: &Pose) -> M4 {
        let t = value::nominal3(&pose.translation, &[]);
        std::array::from_fn(|i| {
            std::array::from_fn(|j| match (i, j) {
                (3, 3) => 1.0,
                (3, _) => 0.0,
                (_, 3) => t[i],
                _ => pose.rotation[i][j],
            })
        })
    }

    fn identity4() -> M4 {
        translation(0.0, 0.0, 0.0)
    }

    /// The product of the transforms, left to right.
    fn product(transforms: &[M4]) -> M4 {
        transforms.iter().fold(identity4(), |acc, m| mul4(&acc, m))
    }

    fn assert_near(a: &M4, b: &M4, what: &str) {
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    (a[i][j] - b[i][j]).abs() < 1e-15,
                    "{what}: entry ({i}, {j}): {a:?} vs {b:?}"
                );
            }
        }
    }

    fn no_snap(m: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        *m
    }

    fn row(a: f64, alpha: f64, d: f64, theta: f64) -> Row {
        Row {
            a: Value::constant(a),
            alpha,
            d: Value::constant(d),
            theta,
        }
    }

    /// The joint's placement, the motion q about (or along) z, then the child's declared
    /// frame: the transform from the child's declared frame to the parent's declared frame.
    fn chained(placed: &Placed, motion: &M4) -> M4 {
        let child = placed.child.as_ref().map_or_else(identity4, homogeneous);
        mul4(&mul4(&homogeneous(&placed.joint), motion), &child)
    }

    /// A DH row against the 4×4 product of its elementary transforms, multiplied by hand
    /// (no snapping, angles off the quarter turns), for a revolute and a prismatic motion.
    #[test]
    fn rows_match_the_products_of_elementary_transforms() {
        let (a, alpha, d, theta) = (0.4318, -0.7, 0.15005, 0.3);
        let q = 1.1;
        // Standard: Rz(θ + q) Tz(d) Tx(a) Rx(α), and Rz(θ) Tz(d + q) Tx(a) Rx(α).
        let standard = place(DhConvention::Standard, row(a, alpha, d, theta), no_snap);
        let expected = product(&[
            rz(theta + q),
            translation(0.0, 0.0, d),
            translation(a, 0.0, 0.0),
            rx(alpha),
        ]);
        assert_near(&chained(&standard, &rz(q)), &expected, "standard, revolute");
        let expected = product(&[
            rz(theta),
            translation(0.0, 0.0, d + q),
            translation(a, 0.0, 0.0),
            rx(alpha),
        ]);
        assert_near(
            &chained(&standard, &translation(0.0, 0.0, q)),
            &expected,
            "standard, prismatic",
        );
        // Modified: Rx(α) Tx(a) Rz(θ + q) Tz(d), and Rx(α) Tx(a) Rz(θ) Tz(d + q).
        let modified = place(DhConvention::Modified, row(a, alpha, d, theta), no_snap);
        assert!(modified.child.is_none());
        let expected = product(&[
            rx(alpha),
            translation(a, 0.0, 0.0),
            rz(theta + q),
            translation(0.0, 0.0, d),
        ]);
        assert_near(&chained(&modified, &rz(q)), &expected, "modified, revolute");
        let expected = product(&[
            rx(alpha),
            translation(a, 0.0, 0.0),
            rz(theta),
            translation(0.0, 0.0, d + q),
        ]);
        assert_near(
            &chained(&modified, &translation(0.0, 0.0, q)),
            &expected,
            "modified, prismatic",
        );
    }

    /// A chain of standard rows, each child's C carried into the next joint's placement,
    /// is the chain of the same table in Craig's convention: Craig's row i takes a and α
    /// from standard row i − 1 (and d, θ from row i).
    #[test]
    fn a_standard_chain_is_the_shifted_modified_chain() {
        let table = [
            (0.0, 0.5, 0.2, 0.1),
            (0.3, -1.2, 0.0, -0.4),
            (0.25, 0.9, 0.1, 2.0),
        ];
        let q = [0.3, -0.8, 1.7];
        let mut standard = identity4();
        let mut modified = identity4();
        for (i, &(a, alpha, d, theta)) in table.iter().enumerate() {
            let s = place(DhConvention::Standard, row(a, alpha, d, theta), no_snap);
            // Standard: the parent's declared frame is frame i − 1, so the product so far
            // (ending in the parent's C) is that frame in the world.
            standard = mul4(&standard, &chained(&s, &rz(q[i])));
            let (a_prev, alpha_prev) = if i == 0 {
                (0.0, 0.0)
            } else {
                (table[i - 1].0, table[i - 1].1)
            };
            let m = place(
                DhConvention::Modified,
                row(a_prev, alpha_prev, d, theta),
                no_snap,
            );
            modified = mul4(&modified, &chained(&m, &rz(q[i])));
            // Craig's frame i is the standard frame i without its C = Tx(a_i) Rx(α_i).
            let craig_times_c = mul4(&mul4(&modified, &translation(a, 0.0, 0.0)), &rx(alpha));
            assert_near(&standard, &craig_times_c, "frame i");
        }
    }

    /// A standard row with a = 0 and α = 0 places the child's frame at the joint frame.
    #[test]
    fn a_row_without_length_and_twist_needs_no_child_frame() {
        let placed = place(DhConvention::Standard, row(0.0, 0.0, 0.3, 0.2), no_snap);
        assert!(placed.child.is_none());
        let placed = place(DhConvention::Standard, row(0.0, 1e-3, 0.3, 0.2), no_snap);
        assert!(placed.child.is_some());
    }
}
