//! Forward dynamics by the articulated-body algorithm (Featherstone, *Rigid Body Dynamics
//! Algorithms*, Table 7.1), in body frames, six-vectors linear first: motion [v_P; ω],
//! force [F; M_P]. Its code grows linearly with the number of joints.
//!
//! ```text
//! forward:  v_i = X_i v_λ + S_i q̇_i,   c_i = v_i × S_i q̇_i,
//!           I^A_i = I_i,   p^A_i = v_i ×* I_i v_i − f_ext,i
//! backward: U_i = I^A_i S_i,  D_i = S_iᵀ U_i + armature,  u_i = τ_i − b q̇_i − S_iᵀ p^A_i
//!           I^a = I^A_i − U_i D_i⁻¹ U_iᵀ,  p^a = p^A_i + I^a c_i + U_i D_i⁻¹ u_i
//!           I^A_λ += X_iᵀ I^a X_i,  p^A_λ += X_iᵀ p^a
//! forward:  a'_i = X_i a_λ + c_i,  q̈_i = D_i⁻¹ (u_i − U_iᵀ a'_i),  a_i = a'_i + S_i q̈_i
//! ```
//!
//! with a_0 = [−g; 0] (gravity as an acceleration of the base). A spatial inertia is the
//! textbook's symmetric matrix [[m 1, −m ĉ], [m ĉ, I_P]], kept as three 3×3 blocks
//! [[A, B], [Bᵀ, C]]; only one triangle of each symmetric block is computed, the other is
//! the same nodes. X_iᵀ I X_i with X_i = [[Eᵀ, −Eᵀ r̂], [0, Eᵀ]] is, with A' = E A Eᵀ,
//! B' = E B Eᵀ, C' = E C Eᵀ: [[A', B' − A' r̂], [Bᵀ' + r̂ A', C' + r̂ B' + (r̂ B')ᵀ − r̂ A' r̂]].

use super::geometry::{self, BodyInertia, JointTransform};
use super::ldlt;
use super::spatial::{
    add6, congruence, dot6, force_cross, motion_cross, motion_subspace, scale6, symmetric, Six,
};
use crate::model::Model;
use crate::sym::{Graph, Mat3, Node, Vec3};

/// A symmetric 6×6 matrix [[A, B], [Bᵀ, C]] with A and C symmetric.
#[derive(Clone, Copy)]
struct Symmetric6 {
    a: Mat3,
    b: Mat3,
    c: Mat3,
}

impl Symmetric6 {
    fn from_inertia(g: &Graph, i: &BodyInertia) -> Self {
        let m = i.mass;
        let zero = g.zero();
        let a = Mat3(std::array::from_fn(|r| {
            std::array::from_fn(|c| if r == c { m } else { zero })
        }));
        Symmetric6 {
            a,
            b: i.first_moment.cross_matrix(g).scale(g, g.constant(-1.0)),
            c: i.inertia_about_origin,
        }
    }

    fn apply(self, g: &Graph, (l, w): Six) -> Six {
        let top = self.a.mul_vec(g, l).add(g, self.b.mul_vec(g, w));
        let bottom = self
            .b
            .transpose()
            .mul_vec(g, l)
            .add(g, self.c.mul_vec(g, w));
        (top, bottom)
    }

    fn add(self, g: &Graph, o: Symmetric6) -> Self {
        Symmetric6 {
            a: self.a.add(g, o.a),
            b: self.b.add(g, o.b),
            c: self.c.add(g, o.c),
        }
    }

    /// self − x wᵀ for x = U and w = U D⁻¹ (so x wᵀ is symmetric): one triangle computed.
    fn minus_outer(self, g: &Graph, x: Six, w: Six) -> Self {
        let outer = |p: Vec3, q: Vec3| {
            Mat3(std::array::from_fn(|i| {
                std::array::from_fn(|j| g.mul(p.get(i), q.get(j)))
            }))
        };
        let a = symmetric(|i, j| g.sub(self.a.get(i, j), g.mul(x.0.get(i), w.0.get(j))));
        let c = symmetric(|i, j| g.sub(self.c.get(i, j), g.mul(x.1.get(i), w.1.get(j))));
        Symmetric6 {
            a,
            b: self.b.sub(g, outer(x.0, w.1)),
            c,
        }
    }

    /// X_iᵀ self X_i: the articulated inertia carried to the parent frame.
    fn to_parent(self, g: &Graph, t: &JointTransform) -> Self {
        let e = t.rotation_to_parent;
        let r_hat = t.origin_in_parent.cross_matrix(g);
        let a = congruence(g, e, self.a);
        let b = e.mul(g, self.b).mul(g, e.transpose());
        let c = congruence(g, e, self.c);
        let r_b = r_hat.mul(g, b);
        let r_a = r_hat.mul(g, a);
        let r_a_r = symmetric(|i, j| r_a.row(i).dot(g, r_hat.col(j)));
        let shifted_c = symmetric(|i, j| {
            g.sub(
                g.add(c.get(i, j), g.add(r_b.get(i, j), r_b.get(j, i))),
                r_a_r.get(i, j),
            )
        });
        Symmetric6 {
            a,
            b: b.sub(g, a.mul(g, r_hat)),
            c: shifted_c,
        }
    }
}

/// X m: a parent-frame motion in the body frame.
fn motion_to_body(g: &Graph, t: &JointTransform, (l, w): Six) -> Six {
    let lin = l.add(g, w.cross(g, t.origin_in_parent));
    (geometry::to_body(g, t, lin), geometry::to_body(g, t, w))
}

/// q̈ = FD(q, q̇, τ) by the articulated-body algorithm.
pub fn forward_dynamics(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    velocity: &[Node],
    tau: &[Node],
    loads: &[(Vec3, Vec3)],
) -> Vec<Node> {
    let n = model.bodies.len();
    let subspaces: Vec<Vec<Six>> = model
        .bodies
        .iter()
        .map(|b| motion_subspace(g, &b.joint.kind))
        .collect();
    // Pass 1: velocities, velocity-product accelerations, bias forces.
    let mut twists: Vec<Six> = Vec::with_capacity(n);
    let mut bias_accel: Vec<Six> = Vec::with_capacity(n);
    let mut inertia_a: Vec<Symmetric6> = Vec::with_capacity(n);
    let mut force_a: Vec<Six> = Vec::with_capacity(n);
    for (i, body) in model.bodies.iter().enumerate() {
        let k = body.joint.idx_v;
        let joint_velocity = subspaces[i]
            .iter()
            .enumerate()
            .fold((Vec3::zero(g), Vec3::zero(g)), |acc, (col, s)| {
                add6(g, acc, scale6(g, *s, velocity[k + col]))
            });
        let inherited = body
            .parent
            .map(|p| motion_to_body(g, &transforms[i], twists[p]));
        let v = inherited.map_or(joint_velocity, |vp| add6(g, vp, joint_velocity));
        // c = v × v_J; on the ground v = v_J, so c = 0.
        let c = match inherited {
            Some(_) => motion_cross(g, v, joint_velocity),
            None => (Vec3::zero(g), Vec3::zero(g)),
        };
        let inertia = Symmetric6::from_inertia(g, &inertias[i]);
        let momentum = inertia.apply(g, v);
        let mut p = force_cross(g, v, momentum);
        p = (p.0.sub(g, loads[i].0), p.1.sub(g, loads[i].1));
        twists.push(v);
        bias_accel.push(c);
        inertia_a.push(inertia);
        force_a.push(p);
    }
    // Pass 2: articulated inertias and bias forces, leaves to root.
    let mut u_vectors: Vec<Vec<Six>> = vec![Vec::new(); n];
    let mut inverse_d: Vec<Vec<Vec<Node>>> = vec![Vec::new(); n];
    let mut u_scalars: Vec<Vec<Node>> = vec![Vec::new(); n];
    for i in (0..n).rev() {
        let body = &model.bodies[i];
        let k = body.joint.idx_v;
        let dofs = body.joint.kind.dofs();
        let ia = inertia_a[i];
        let u: Vec<Six> = subspaces[i].iter().map(|s| ia.apply(g, *s)).collect();
        let armature = geometry::value(g, &body.joint.armature);
        let damping = geometry::value(g, &body.joint.damping);
        // D = Sᵀ I^A S is symmetric: entry (r, c) for r ≤ c, mirrored.
        let d: Vec<Vec<Node>> = (0..dofs)
            .map(|r| {
                (0..dofs)
                    .map(|c| {
                        let entry = dot6(g, subspaces[i][r.min(c)], u[r.max(c)]);
                        if r == c {
                            g.add(entry, armature)
                        } else {
                            entry
                        }
                    })
                    .collect()
            })
            .collect();
        let small_u: Vec<Node> = (0..dofs)
            .map(|r| {
                g.sub(
                    g.sub(tau[k + r], g.mul(damping, velocity[k + r])),
                    dot6(g, subspaces[i][r], force_a[i]),
                )
            })
            .collect();
        if let Some(parent) = body.parent {
            // D⁻¹ applied to each column of Uᵀ (one dof: a reciprocal; more: a solve).
            let d_inv_ut: Vec<Six> = if dofs == 1 {
                let inv = g.div(g.one(), d[0][0]);
                vec![scale6(g, u[0], inv)]
            } else {
                solve_columns(g, &d, &u)
            };
            let mut ia_small = ia;
            for col in 0..dofs {
                ia_small = ia_small.minus_outer(g, u[col], d_inv_ut[col]);
            }
            let mut pa = add6(g, force_a[i], ia_small.apply(g, bias_accel[i]));
            for col in 0..dofs {
                pa = add6(g, pa, scale6(g, d_inv_ut[col], small_u[col]));
            }
            let moved = ia_small.to_parent(g, &transforms[i]);
            inertia_a[parent] = inertia_a[parent].add(g, moved);
            let (fl, fa) = geometry::wrench_to_parent(g, &transforms[i], pa.0, pa.1);
            force_a[parent] = add6(g, force_a[parent], (fl, fa));
        }
        u_vectors[i] = u;
        inverse_d[i] = d;
        u_scalars[i] = small_u;
    }
    // Pass 3: accelerations, root to leaves.
    let gravity = Vec3::constant(g, model.gravity_in_world).neg(g);
    let base: Six = (gravity, Vec3::zero(g));
    let mut accel: Vec<Six> = Vec::with_capacity(n);
    let mut qdd = vec![g.zero(); model.nv];
    for (i, body) in model.bodies.iter().enumerate() {
        let k = body.joint.idx_v;
        let parent_accel = body.parent.map_or(base, |p| accel[p]);
        let a_prime = add6(
            g,
            motion_to_body(g, &transforms[i], parent_accel),
            bias_accel[i],
        );
        let rhs: Vec<Node> = u_vectors[i]
            .iter()
            .zip(&u_scalars[i])
            .map(|(u, &small)| g.sub(small, dot6(g, *u, a_prime)))
            .collect();
        let solution = if rhs.len() == 1 {
            vec![g.div(rhs[0], inverse_d[i][0][0])]
        } else {
            ldlt::solve_dense(g, inverse_d[i].clone(), rhs)
        };
        let mut a = a_prime;
        for (col, &x) in solution.iter().enumerate() {
            qdd[k + col] = x;
            a = add6(g, a, scale6(g, subspaces[i][col], x));
        }
        accel.push(a);
    }
    qdd
}

/// D⁻¹ Uᵀ for a multi-dof joint, column by column: for each column of Uᵀ (a row of the
/// 6-vector stack), solve with D. Returns the columns U D⁻¹ as six-vectors.
fn solve_columns(g: &Graph, d: &[Vec<Node>], u: &[Six]) -> Vec<Six> {
    let dofs = d.len();
    // Each of the 6 spatial components: the dofs-vector of U entries, solved with D.
    let component = |x: Six, k: usize| if k < 3 { x.0.get(k) } else { x.1.get(k - 3) };
    let solved: Vec<Vec<Node>> = (0..6)
        .map(|k| {
            ldlt::solve_dense(
                g,
                d.to_vec(),
                (0..dofs).map(|c| component(u[c], k)).collect(),
            )
        })
        .collect();
    (0..dofs)
        .map(|c| {
            (
                Vec3::new(solved[0][c], solved[1][c], solved[2][c]),
                Vec3::new(solved[3][c], solved[4][c], solved[5][c]),
            )
        })
        .collect()
}
