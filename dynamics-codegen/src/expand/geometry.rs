//! Per-body symbolic data the sweeps share: the joint transform of each body and its
//! inertia about the body origin P.
//!
//! Body i's frame is the joint frame after the motion (turned about the joint's axis where
//! the tree chose to, see `model::Joint::joint_frame_in_body`). Its pose in the parent frame is
//! `E_i` (rotation, body → parent) and `r_i` (origin P_i in the parent frame):
//! revolute `E = R_pl · Rot(s, q)`, `r = p_pl`; prismatic `E = R_pl`, `r = p_pl + R_pl s q`;
//! free `E = R(quaternion)`, `r = (x, y, z)`.
//!
//! The inertia of a (composite) body about P, in the body frame, is kept as the textbook's
//! three quantities: m, the first moment h = m c (c = PG) and I_P = I_G − m ĉ², summed over
//! the parts merged into the body. Constant parts fold to numbers at compile time; only
//! declared parameters stay symbolic.

use crate::model::{self, JointKind, Model, Value};
use crate::sym::{Array, Graph, Mat3, Node, Vec3};

/// A body's rigid-body inertia about its origin P, in its own frame.
#[derive(Clone, Copy, Debug)]
pub struct BodyInertia {
    /// Mass m.
    pub mass: Node,
    /// First moment h = m c, with c = PG.
    pub first_moment: Vec3,
    /// Rotational inertia about P: I_P = I_G − m ĉ².
    pub inertia_about_origin: Mat3,
    /// The mass centre c and I_G about it, when the mass is a nonzero constant (so c needs
    /// no division at run time).
    pub mass_centre: Option<(Vec3, Mat3)>,
}

/// The pose of a body's frame in its parent's frame, as functions of q.
#[derive(Clone, Copy, Debug)]
pub struct JointTransform {
    /// E: rotation from body to parent coordinates.
    pub rotation_to_parent: Mat3,
    /// r: the body origin P in the parent frame.
    pub origin_in_parent: Vec3,
}

/// An affine model value as a node: constant + Σ coefficient · `p[k]`.
pub fn value(g: &Graph, v: &Value) -> Node {
    let terms: Vec<Node> = v
        .terms
        .iter()
        .map(|&(k, c)| g.mul(g.constant(c), g.input(Array::P, k)))
        .collect();
    let mut sum = g.constant(v.constant);
    for t in terms {
        sum = g.add(sum, t);
    }
    sum
}

/// A vector of affine model values as nodes.
pub fn vector(g: &Graph, v: &model::Vec3) -> Vec3 {
    Vec3::new(value(g, &v[0]), value(g, &v[1]), value(g, &v[2]))
}

/// A matrix of affine model values as nodes.
pub fn matrix(g: &Graph, m: &model::Mat3) -> Mat3 {
    Mat3::from_rows([vector(g, &m[0]), vector(g, &m[1]), vector(g, &m[2])])
}

/// m, h = m c and I_P = I_G − m ĉ² of a composite body: the sum over its parts; and, when
/// the mass is a nonzero constant, the composite mass centre c = h / m and I_G about it,
/// I_G = Σ_k (I_G,k − m_k (c_k − c)^²) (a single part keeps its declared c and I_G exactly).
pub fn body_inertia(g: &Graph, body: &model::Body) -> BodyInertia {
    let mut total = BodyInertia {
        mass: g.zero(),
        first_moment: Vec3::zero(g),
        inertia_about_origin: Mat3::zero(g),
        mass_centre: None,
    };
    for part in &body.parts {
        let m = value(g, &part.mass);
        let c = vector(g, &part.com_in_body);
        let c_hat = c.cross_matrix(g);
        let i_g = matrix(g, &part.inertia_com_in_body);
        let i_p = i_g.sub(g, c_hat.mul(g, c_hat).scale(g, m));
        total.mass = g.add(total.mass, m);
        total.first_moment = total.first_moment.add(g, c.scale(g, m));
        total.inertia_about_origin = total.inertia_about_origin.add(g, i_p);
    }
    total.mass_centre = match body.parts.as_slice() {
        [part] if part.mass.is_constant() && part.mass.constant > 0.0 => Some((
            vector(g, &part.com_in_body),
            matrix(g, &part.inertia_com_in_body),
        )),
        _ => match g.constant_value(total.mass) {
            Some(m) if m > 0.0 => {
                let c = total.first_moment.scale(g, g.constant(1.0 / m));
                let mut i_g = Mat3::zero(g);
                for part in &body.parts {
                    let d_hat = vector(g, &part.com_in_body).sub(g, c).cross_matrix(g);
                    let shift = d_hat.mul(g, d_hat).scale(g, value(g, &part.mass));
                    i_g = i_g.add(g, matrix(g, &part.inertia_com_in_body).sub(g, shift));
                }
                Some((c, i_g))
            }
            _ => None,
        },
    };
    total
}

/// The rotation by angle θ (given by its sine and cosine) about a unit axis. Coordinate
/// axes get the explicit matrix, so that their zeros and ones cost nothing; other axes use
/// Rodrigues' formula R = 1 + sin θ ŝ + (1 − cos θ) ŝ².
pub fn axis_rotation(g: &Graph, axis: [f64; 3], sin: Node, cos: Node) -> Mat3 {
    let coordinate = axis.iter().filter(|a| **a != 0.0).count() == 1;
    if coordinate {
        let k = axis.iter().position(|a| *a != 0.0).unwrap_or(2);
        let s = if axis[k] < 0.0 { g.neg(sin) } else { sin };
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let mut m = Mat3::identity(g).0;
        m[i][i] = cos;
        m[j][j] = cos;
        m[i][j] = g.neg(s);
        m[j][i] = s;
        return Mat3(m);
    }
    let s_hat = Vec3::constant(g, axis).cross_matrix(g);
    let one_minus_cos = g.sub(g.one(), cos);
    Mat3::identity(g)
        .add(g, s_hat.scale(g, sin))
        .add(g, s_hat.mul(g, s_hat).scale(g, one_minus_cos))
}

/// The rotation of a unit quaternion (x, y, z, w), body → parent.
pub fn quaternion_rotation(g: &Graph, x: Node, y: Node, z: Node, w: Node) -> Mat3 {
    let two = g.constant(2.0);
    let t = |a: Node, b: Node| g.mul(two, g.mul(a, b));
    let (xx, yy, zz) = (t(x, x), t(y, y), t(z, z));
    let (xy, xz, yz) = (t(x, y), t(x, z), t(y, z));
    let (xw, yw, zw) = (t(x, w), t(y, w), t(z, w));
    let one = g.one();
    Mat3::from_rows([
        Vec3::new(g.sub(one, g.add(yy, zz)), g.sub(xy, zw), g.add(xz, yw)),
        Vec3::new(g.add(xy, zw), g.sub(one, g.add(xx, zz)), g.sub(yz, xw)),
        Vec3::new(g.sub(xz, yw), g.add(yz, xw), g.sub(one, g.add(xx, yy))),
    ])
}

/// The joint transform of every body at the configuration input `q`.
pub fn joint_transforms(g: &Graph, model: &Model) -> Vec<JointTransform> {
    model
        .bodies
        .iter()
        .map(|body| {
            let joint = &body.joint;
            let placement = Mat3::constant(g, joint.rotation_in_parent);
            let offset = vector(g, &joint.translation_in_parent);
            let q = |k: usize| g.input(Array::Q, joint.idx_q + k);
            match joint.kind {
                JointKind::Revolute { axis_in_body } => {
                    let angle = q(0);
                    let motion = axis_rotation(g, axis_in_body, g.sin(angle), g.cos(angle));
                    JointTransform {
                        rotation_to_parent: placement.mul(g, motion),
                        origin_in_parent: offset,
                    }
                }
                JointKind::Prismatic { axis_in_body } => {
                    let slide = Vec3::constant(g, axis_in_body).scale(g, q(0));
                    JointTransform {
                        rotation_to_parent: placement,
                        origin_in_parent: offset.add(g, placement.mul_vec(g, slide)),
                    }
                }
                JointKind::Free => {
                    let rotation = quaternion_rotation(g, q(3), q(4), q(5), q(6));
                    let position = Vec3::new(q(0), q(1), q(2));
                    JointTransform {
                        rotation_to_parent: placement.mul(g, rotation),
                        origin_in_parent: offset.add(g, placement.mul_vec(g, position)),
                    }
                }
            }
        })
        .collect()
}

/// Expresses a parent-frame vector in the body frame: Eᵀ w.
pub fn to_body(g: &Graph, t: &JointTransform, w: Vec3) -> Vec3 {
    t.rotation_to_parent.transpose().mul_vec(g, w)
}

/// Carries a wrench [F; M_P] from the body frame (about P_i) to the parent frame (about
/// the parent's origin): F' = E F, M' = E M + r × F'.
pub fn wrench_to_parent(g: &Graph, t: &JointTransform, force: Vec3, moment: Vec3) -> (Vec3, Vec3) {
    let f = t.rotation_to_parent.mul_vec(g, force);
    let m = t
        .rotation_to_parent
        .mul_vec(g, moment)
        .add(g, t.origin_in_parent.cross(g, f));
    (f, m)
}

/// Whether m, h and I_P of a body are all numbers (no declared parameter).
pub fn is_constant_inertia(g: &Graph, b: &BodyInertia) -> bool {
    let constant = |n: &Node| g.constant_value(*n).is_some();
    constant(&b.mass)
        && b.first_moment.0.iter().all(constant)
        && b.inertia_about_origin.0.iter().flatten().all(constant)
}

/// A body's inertia (m, h, I_P) with its mass centre and I_G recomputed when m is a
/// positive number.
pub fn inertia_from(g: &Graph, mass: Node, first_moment: Vec3, about_origin: Mat3) -> BodyInertia {
    let mass_centre = match g.constant_value(mass) {
        Some(m) if m > 0.0 => {
            let c = first_moment.scale(g, g.constant(1.0 / m));
            let c_hat = c.cross_matrix(g);
            // I_P = I_G − m ĉ², so I_G = I_P + m ĉ².
            Some((c, about_origin.add(g, c_hat.mul(g, c_hat).scale(g, mass))))
        }
        _ => None,
    };
    BodyInertia {
        mass,
        first_moment,
        inertia_about_origin: about_origin,
        mass_centre,
    }
}
