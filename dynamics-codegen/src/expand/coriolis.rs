//! A Coriolis matrix C(q, q̇) with Ṁ − 2C skew-symmetric (the Christoffel-consistent one),
//! organized like the composite-rigid-body mass matrix.
//!
//! With world-frame Jacobians, C = Σ_i J_iᵀ (I_i J̇_i + B_i J_i), where
//! B(I, v) = ½ [(v×*) I + (I v)×̄ − I (v×)] and (f×̄) v = v ×* f (Echeandia & Wensing,
//! 2021); since B + Bᵀ = İ, C + Cᵀ = Ṁ. Joint k's column of J_i is its motion axis s_k,
//! with ṡ_k = v_k × s_k. Only bodies below both joints contribute, so with composite sums
//! over subtrees, I^C_j = Σ I_i and B^C_j = Σ B_i (each carried to body j's frame as
//! Xᵀ · X):
//!
//! ```text
//! C_ij = s_iᵀ (I^C_j ṡ_j + B^C_j s_j)              i = j or an ancestor of j
//! C_ji = (I^C_j s_j)ᵀ ṡ_i + (B^C_jᵀ s_j)ᵀ s_i      i a strict ancestor of j
//! ```
//!
//! Spatial inner products do not depend on the frame, so each column's forces are carried
//! up the tree like the mass matrix's. Six-dimensional quantities are linear first:
//! motion [v_P; ω], force [F; M_P].

use super::crba::{composite_inertias, motion_subspace};
use super::geometry::{self, BodyInertia, JointTransform};
use crate::model::Model;
use crate::sym::{Graph, Mat3, Node, Vec3};

/// A 6×6 matrix as 3×3 blocks [[top-left, top-right], [bottom-left, bottom-right]].
#[derive(Clone, Copy)]
struct Mat6([[Mat3; 2]; 2]);

/// A spatial vector [linear; angular].
type Six = (Vec3, Vec3);

impl Mat6 {
    fn add(self, g: &Graph, o: Mat6) -> Mat6 {
        let b = |i: usize, j: usize| self.0[i][j].add(g, o.0[i][j]);
        Mat6([[b(0, 0), b(0, 1)], [b(1, 0), b(1, 1)]])
    }

    fn scale(self, g: &Graph, s: Node) -> Mat6 {
        let b = |i: usize, j: usize| self.0[i][j].scale(g, s);
        Mat6([[b(0, 0), b(0, 1)], [b(1, 0), b(1, 1)]])
    }

    fn mul(self, g: &Graph, o: Mat6) -> Mat6 {
        let b = |i: usize, j: usize| {
            self.0[i][0]
                .mul(g, o.0[0][j])
                .add(g, self.0[i][1].mul(g, o.0[1][j]))
        };
        Mat6([[b(0, 0), b(0, 1)], [b(1, 0), b(1, 1)]])
    }

    fn transpose(self) -> Mat6 {
        let b = |i: usize, j: usize| self.0[j][i].transpose();
        Mat6([[b(0, 0), b(0, 1)], [b(1, 0), b(1, 1)]])
    }

    fn apply(self, g: &Graph, (l, a): Six) -> Six {
        let row = |i: usize| {
            self.0[i][0]
                .mul_vec(g, l)
                .add(g, self.0[i][1].mul_vec(g, a))
        };
        (row(0), row(1))
    }
}

/// The spatial inertia about P: [[m 1, −ĥ], [ĥ, I_P]].
fn inertia_matrix(g: &Graph, i: &BodyInertia) -> Mat6 {
    let h_hat = i.first_moment.cross_matrix(g);
    Mat6([
        [
            Mat3::identity(g).scale(g, i.mass),
            h_hat.scale(g, g.constant(-1.0)),
        ],
        [h_hat, i.inertia_about_origin],
    ])
}

/// v× for v = [v_l; ω]: [[ω̂, v̂_l], [0, ω̂]].
fn motion_cross((v, w): Six, g: &Graph) -> Mat6 {
    Mat6([
        [w.cross_matrix(g), v.cross_matrix(g)],
        [Mat3::zero(g), w.cross_matrix(g)],
    ])
}

/// v×* for v = [v_l; ω]: [[ω̂, 0], [v̂_l, ω̂]].
fn force_cross((v, w): Six, g: &Graph) -> Mat6 {
    Mat6([
        [w.cross_matrix(g), Mat3::zero(g)],
        [v.cross_matrix(g), w.cross_matrix(g)],
    ])
}

/// f×̄ for f = [F; M], defined by (f×̄) v = v ×* f: [[0, −F̂], [−F̂, −M̂]].
fn force_bar((f, m): Six, g: &Graph) -> Mat6 {
    let minus = g.constant(-1.0);
    let f_hat = f.cross_matrix(g).scale(g, minus);
    Mat6([
        [Mat3::zero(g), f_hat],
        [f_hat, m.cross_matrix(g).scale(g, minus)],
    ])
}

/// The motion transform from parent to body coordinates, X = [[Eᵀ, −Eᵀ r̂], [0, Eᵀ]].
fn motion_transform(g: &Graph, t: &JointTransform) -> Mat6 {
    let et = t.rotation_to_parent.transpose();
    let minus = g.constant(-1.0);
    Mat6([
        [
            et,
            et.mul(g, t.origin_in_parent.cross_matrix(g))
                .scale(g, minus),
        ],
        [Mat3::zero(g), et],
    ])
}

/// Spatial velocities of every body, in its own frame.
fn velocities(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    velocity: &[Node],
) -> Vec<Six> {
    let mut out: Vec<Six> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let (v_p, w_p) = body
            .parent
            .map_or((Vec3::zero(g), Vec3::zero(g)), |p| out[p]);
        let t = &transforms[i];
        let mut w = geometry::to_body(g, t, w_p);
        let mut v = geometry::to_body(g, t, v_p.add(g, w_p.cross(g, t.origin_in_parent)));
        let k = body.joint.idx_v;
        for (col, (sv, sw)) in motion_subspace(g, &body.joint.kind).into_iter().enumerate() {
            v = v.add(g, sv.scale(g, velocity[k + col]));
            w = w.add(g, sw.scale(g, velocity[k + col]));
        }
        out.push((v, w));
    }
    out
}

fn dot(g: &Graph, a: Six, b: Six) -> Node {
    g.add(a.0.dot(g, b.0), a.1.dot(g, b.1))
}

fn motion_cross_vector(g: &Graph, (v, w): Six, (mv, mw): Six) -> Six {
    (w.cross(g, mv).add(g, v.cross(g, mw)), w.cross(g, mw))
}

/// C(q, q̇), an `nv × nv` matrix of nodes.
pub fn coriolis_matrix(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
) -> Vec<Vec<Node>> {
    let n = model.bodies.len();
    let twists = velocities(g, model, transforms, velocity);
    let half = g.constant(0.5);
    let mut b_composite: Vec<Mat6> = (0..n)
        .map(|i| {
            let inertia = inertia_matrix(g, &inertias[i]);
            let momentum = inertia.apply(g, twists[i]);
            force_cross(twists[i], g)
                .mul(g, inertia)
                .add(g, force_bar(momentum, g))
                .add(
                    g,
                    inertia
                        .mul(g, motion_cross(twists[i], g))
                        .scale(g, g.constant(-1.0)),
                )
                .scale(g, half)
        })
        .collect();
    for i in (0..n).rev() {
        if let Some(p) = model.bodies[i].parent {
            let x = motion_transform(g, &transforms[i]);
            let moved = x.transpose().mul(g, b_composite[i].mul(g, x));
            b_composite[p] = b_composite[p].add(g, moved);
        }
    }
    let i_composite: Vec<Mat6> = composite_inertias(g, model, transforms, inertias)
        .iter()
        .map(|c| inertia_matrix(g, c))
        .collect();
    let subspaces: Vec<Vec<Six>> = model
        .bodies
        .iter()
        .map(|b| motion_subspace(g, &b.joint.kind))
        .collect();
    let axis_rates: Vec<Vec<Six>> = subspaces
        .iter()
        .zip(&twists)
        .map(|(s, &twist)| {
            s.iter()
                .map(|&col| motion_cross_vector(g, twist, col))
                .collect()
        })
        .collect();
    let mut c = vec![vec![g.zero(); model.nv]; model.nv];
    for (j, body) in model.bodies.iter().enumerate() {
        for (col, &s_j) in subspaces[j].iter().enumerate() {
            let column = body.joint.idx_v + col;
            let f1 = i_composite[j].apply(g, axis_rates[j][col]);
            let mut f1 = add6(g, f1, b_composite[j].apply(g, s_j));
            let mut f2 = i_composite[j].apply(g, s_j);
            let mut f3 = b_composite[j].transpose().apply(g, s_j);
            for (row_in_joint, &s_row) in subspaces[j].iter().enumerate() {
                c[body.joint.idx_v + row_in_joint][column] = dot(g, s_row, f1);
            }
            let mut i = j;
            while let Some(p) = model.bodies[i].parent {
                let t = &transforms[i];
                f1 = geometry::wrench_to_parent(g, t, f1.0, f1.1);
                f2 = geometry::wrench_to_parent(g, t, f2.0, f2.1);
                f3 = geometry::wrench_to_parent(g, t, f3.0, f3.1);
                i = p;
                let ancestor = &model.bodies[i].joint;
                for (row_in_joint, &s_i) in subspaces[i].iter().enumerate() {
                    let row = ancestor.idx_v + row_in_joint;
                    c[row][column] = dot(g, s_i, f1);
                    c[column][row] =
                        g.add(dot(g, f2, axis_rates[i][row_in_joint]), dot(g, f3, s_i));
                }
            }
        }
    }
    c
}

fn add6(g: &Graph, a: Six, b: Six) -> Six {
    (a.0.add(g, b.0), a.1.add(g, b.1))
}
