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
use super::slots::Slots;
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

    /// Lane k of every entry (`None`: the matrix itself).
    fn lane(self, g: &Graph, k: Option<usize>) -> Self {
        let lane = |m: Mat3| k.map_or(m, |k| m.lane(g, k));
        Symmetric6 {
            a: lane(self.a),
            b: lane(self.b),
            c: lane(self.c),
        }
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

/// q̈ = FD(q, q̇, τ) by the articulated-body algorithm over [`Slots`]: isomorphic limbs
/// side by side, their twists, articulated inertias and bias forces, U, D⁻¹ and
/// accelerations in the lanes of packed values; each lane's articulated inertia and bias
/// force added into a scalar parent's in turn, lane for lane into a packed one, and q̈ read
/// lane by lane. Without isomorphic limbs every body is a slot of its own and every value
/// scalar: the algorithm one body at a time.
pub fn forward_dynamics(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    (velocity, tau): (&[Node], &[Node]),
    loads: &[(Vec3, Vec3)],
) -> Vec<Node> {
    let slots = Slots::of(model);
    by_slots(
        g,
        model,
        &slots,
        (transforms, inertias),
        (velocity, tau),
        loads,
    )
}

/// The articulated-body algorithm over `slots`, from every body's transform, inertia and
/// load (zipped into the slots').
fn by_slots(
    g: &Graph,
    model: &Model,
    slots: &Slots,
    (transforms, inertias): (&[JointTransform], &[BodyInertia]),
    (velocity, tau): (&[Node], &[Node]),
    loads: &[(Vec3, Vec3)],
) -> Vec<Node> {
    let n = slots.slots.len();
    let transforms = slots.transforms(g, transforms);
    let inertias = slots.inertias(g, inertias);
    let joint = |s: usize| &model.bodies[slots.slots[s].lanes[0]].joint;
    let subspaces: Vec<Vec<Six>> = (0..n).map(|s| motion_subspace(g, &joint(s).kind)).collect();
    // The lanes' values of a per-coordinate input (`of`, at `row` of the joint's
    // coordinates) or of a per-body one.
    let coordinate = |s: usize, of: &[Node], row: usize| {
        slots.zip_lanes(g, s, |b| of[model.bodies[b].joint.idx_v + row])
    };
    let per_body = |s: usize, value: &dyn Fn(usize) -> Node| slots.zip_lanes(g, s, value);
    // Pass 1: velocities, velocity-product accelerations, bias forces.
    let mut twists: Vec<Six> = Vec::with_capacity(n);
    let mut bias_accel: Vec<Six> = Vec::with_capacity(n);
    let mut inertia_a: Vec<Symmetric6> = Vec::with_capacity(n);
    let mut force_a: Vec<Six> = Vec::with_capacity(n);
    for s in 0..n {
        let joint_velocity = subspaces[s]
            .iter()
            .enumerate()
            .fold((Vec3::zero(g), Vec3::zero(g)), |acc, (col, axis)| {
                add6(g, acc, scale6(g, *axis, coordinate(s, velocity, col)))
            });
        let inherited = slots
            .parent_slot(s)
            .map(|p| motion_to_body(g, &transforms[s], twists[p]));
        let v = inherited.map_or(joint_velocity, |vp| add6(g, vp, joint_velocity));
        // c = v × v_J; on the ground v = v_J, so c = 0.
        let c = match inherited {
            Some(_) => motion_cross(g, v, joint_velocity),
            None => (Vec3::zero(g), Vec3::zero(g)),
        };
        let inertia = Symmetric6::from_inertia(g, &inertias[s]);
        let momentum = inertia.apply(g, v);
        let load = |part: fn(&(Vec3, Vec3)) -> Vec3| {
            Vec3(std::array::from_fn(|i| {
                per_body(s, &|b| part(&loads[b]).get(i))
            }))
        };
        let p = force_cross(g, v, momentum);
        let p = (p.0.sub(g, load(|l| l.0)), p.1.sub(g, load(|l| l.1)));
        twists.push(v);
        bias_accel.push(c);
        inertia_a.push(inertia);
        force_a.push(p);
    }
    // Pass 2: articulated inertias and bias forces, leaves to root.
    let mut u_vectors: Vec<Vec<Six>> = vec![Vec::new(); n];
    let mut inverse_d: Vec<Vec<Vec<Node>>> = vec![Vec::new(); n];
    let mut u_scalars: Vec<Vec<Node>> = vec![Vec::new(); n];
    for s in (0..n).rev() {
        let dofs = joint(s).kind.dofs();
        let ia = inertia_a[s];
        let u: Vec<Six> = subspaces[s].iter().map(|axis| ia.apply(g, *axis)).collect();
        let armature = per_body(s, &|b| geometry::value(g, &model.bodies[b].joint.armature));
        let damping = per_body(s, &|b| geometry::value(g, &model.bodies[b].joint.damping));
        // D = Sᵀ I^A S is symmetric: entry (r, c) for r ≤ c, mirrored.
        let d: Vec<Vec<Node>> = (0..dofs)
            .map(|r| {
                (0..dofs)
                    .map(|c| {
                        let entry = dot6(g, subspaces[s][r.min(c)], u[r.max(c)]);
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
                let rate = coordinate(s, velocity, r);
                g.sub(
                    g.sub(coordinate(s, tau, r), g.mul(damping, rate)),
                    dot6(g, subspaces[s][r], force_a[s]),
                )
            })
            .collect();
        if let Some(parent) = slots.parent_slot(s) {
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
            let mut pa = add6(g, force_a[s], ia_small.apply(g, bias_accel[s]));
            for col in 0..dofs {
                pa = add6(g, pa, scale6(g, d_inv_ut[col], small_u[col]));
            }
            let moved = ia_small.to_parent(g, &transforms[s]);
            let (fl, fa) = geometry::wrench_to_parent(g, &transforms[s], pa.0, pa.1);
            for k in slots.lanes_into_parent(s) {
                let lane = |x: Vec3| k.map_or(x, |k| x.lane(g, k));
                inertia_a[parent] = inertia_a[parent].add(g, moved.lane(g, k));
                force_a[parent] = add6(g, force_a[parent], (lane(fl), lane(fa)));
            }
        }
        u_vectors[s] = u;
        inverse_d[s] = d;
        u_scalars[s] = small_u;
    }
    // Pass 3: accelerations, root to leaves.
    let gravity = Vec3::constant(g, model.gravity_in_world).neg(g);
    let base: Six = (gravity, Vec3::zero(g));
    let mut accel: Vec<Six> = Vec::with_capacity(n);
    let mut qdd = vec![g.zero(); model.nv];
    for s in 0..n {
        let parent_accel = slots.parent_slot(s).map_or(base, |p| accel[p]);
        let a_prime = add6(
            g,
            motion_to_body(g, &transforms[s], parent_accel),
            bias_accel[s],
        );
        let rhs: Vec<Node> = u_vectors[s]
            .iter()
            .zip(&u_scalars[s])
            .map(|(u, &small)| g.sub(small, dot6(g, *u, a_prime)))
            .collect();
        let solution = if rhs.len() == 1 {
            vec![g.div(rhs[0], inverse_d[s][0][0])]
        } else {
            ldlt::solve_dense(g, inverse_d[s].clone(), rhs)
        };
        let mut a = a_prime;
        for (col, &x) in solution.iter().enumerate() {
            for (k, &b) in slots.slots[s].lanes.iter().enumerate() {
                qdd[model.bodies[b].joint.idx_v + col] = g.lane(x, k);
            }
            a = add6(g, a, scale6(g, subspaces[s][col], x));
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

#[cfg(test)]
mod tests {
    use super::{by_slots, forward_dynamics};
    use crate::expand::{
        fresh_graph, inputs,
        slots::Slots,
        tests::{humanoid, state},
    };
    use crate::sym::{Array, Vec3};

    /// The algorithm over the humanoid's slots (legs and arms in pairs of lanes) gives the
    /// one-body-a-slot algorithm's q̈, with a third of its operations packed (the free base's 6 × 6
    /// solve and the waist are scalar) and fewer in all.
    #[test]
    fn the_packed_algorithm_is_the_scalar_one() {
        let model = humanoid();
        let (g, t, i) = fresh_graph(&model);
        let v = inputs(&g, Array::V, model.nv);
        let tau = inputs(&g, Array::Tau, model.nv);
        let none = vec![(Vec3::zero(&g), Vec3::zero(&g)); model.bodies.len()];
        let each_body = Slots::each_body(&model);
        let scalar = by_slots(&g, &model, &each_body, (&t, &i), (&v, &tau), &none);
        let packed = forward_dynamics(&g, &model, &t, &i, (&v, &tau), &none);
        let count = g.op_count(&packed);
        assert!(3 * count.packed > count.total(), "{count}");
        assert!(count.total() < g.op_count(&scalar).total(), "{count}");
        let at = state(&model);
        let (want, got) = (g.eval(&at, &scalar), g.eval(&at, &packed));
        for (k, (w, x)) in want.iter().zip(&got).enumerate() {
            assert!(
                (w - x).abs() <= 1e-12 * (1.0 + w.abs()),
                "q̈[{k}]: {x} packed, {w} not"
            );
        }
        assert!(want.iter().filter(|w| w.abs() > 1e-3).count() > model.nv / 2);
    }
}
