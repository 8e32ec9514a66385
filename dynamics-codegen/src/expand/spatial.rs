//! Spatial vectors and the operations the sweeps share. Six-dimensional quantities are
//! linear first: a motion [v_P; ω], a force [F; M_P], both about the frame's origin P.
//! Also the symmetric 3×3 helpers of the inertia sweeps and a joint's motion subspace.

use super::geometry::BodyInertia;
use crate::model::JointKind;
use crate::sym::{Graph, Mat3, Node, Vec3};

/// A spatial vector [linear; angular].
pub type Six = (Vec3, Vec3);

/// x + y.
pub fn add6(g: &Graph, x: Six, y: Six) -> Six {
    (x.0.add(g, y.0), x.1.add(g, y.1))
}

/// x − y.
pub fn sub6(g: &Graph, x: Six, y: Six) -> Six {
    (x.0.sub(g, y.0), x.1.sub(g, y.1))
}

/// The pairing of a motion and a force (or two spatial vectors componentwise).
pub fn dot6(g: &Graph, x: Six, y: Six) -> Node {
    g.add(x.0.dot(g, y.0), x.1.dot(g, y.1))
}

/// s x.
pub fn scale6(g: &Graph, x: Six, s: Node) -> Six {
    (x.0.scale(g, s), x.1.scale(g, s))
}

/// v × m for motions: [ω × m_l + v_l × m_a; ω × m_a].
pub fn motion_cross(g: &Graph, (v, w): Six, (ml, ma): Six) -> Six {
    (w.cross(g, ml).add(g, v.cross(g, ma)), w.cross(g, ma))
}

/// v ×* f for a force: [ω × f_l; ω × f_a + v_l × f_l].
pub fn force_cross(g: &Graph, (v, w): Six, (fl, fa): Six) -> Six {
    (w.cross(g, fl), w.cross(g, fa).add(g, v.cross(g, fl)))
}

/// The force I s of an inertia (m, h, I_P) along the motion s = [v; ω]:
/// [m v + ω × h; h × v + I_P ω].
pub fn inertia_times(g: &Graph, i: &BodyInertia, (v, w): Six) -> Six {
    (
        v.scale(g, i.mass).add(g, w.cross(g, i.first_moment)),
        i.first_moment
            .cross(g, v)
            .add(g, i.inertia_about_origin.mul_vec(g, w)),
    )
}

/// A symmetric matrix from its upper triangle: entry (i, j) for i ≤ j, mirrored.
pub fn symmetric(entry: impl Fn(usize, usize) -> Node) -> Mat3 {
    let upper: [[Option<Node>; 3]; 3] =
        std::array::from_fn(|i| std::array::from_fn(|j| (i <= j).then(|| entry(i, j))));
    Mat3(std::array::from_fn(|i| {
        std::array::from_fn(|j| upper[i.min(j)][i.max(j)].unwrap_or_else(|| entry(i, j)))
    }))
}

/// M S Mᵀ for symmetric S, computing each entry of the upper triangle once.
pub fn congruence(g: &Graph, m: Mat3, s: Mat3) -> Mat3 {
    let ms = m.mul(g, s);
    symmetric(|i, j| ms.row(i).dot(g, m.row(j)))
}

/// The motion subspace of a joint: one [v; ω] column per velocity coordinate.
pub fn motion_subspace(g: &Graph, kind: &JointKind) -> Vec<(Vec3, Vec3)> {
    match kind {
        JointKind::Revolute { axis_in_body } => {
            vec![(Vec3::zero(g), Vec3::constant(g, *axis_in_body))]
        }
        JointKind::Prismatic { axis_in_body } => {
            vec![(Vec3::constant(g, *axis_in_body), Vec3::zero(g))]
        }
        JointKind::Free => (0..6)
            .map(|k| {
                let unit = |j: usize| {
                    let mut e = [0.0; 3];
                    e[j] = 1.0;
                    Vec3::constant(g, e)
                };
                if k < 3 {
                    (unit(k), Vec3::zero(g))
                } else {
                    (Vec3::zero(g), unit(k - 3))
                }
            })
            .collect(),
    }
}
