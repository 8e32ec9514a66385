//! Force analysis and loop closure over DAG nodes (the model's [`Statics`]).
//!
//! **Force analysis.** Each moving body i balances, in its frame about its origin P_i,
//! Σ_c W_c,i(x) = W_i with W_i = [m a_P + U h; h × a_P + I_P α + ω × I_P ω] − loads (the
//! textbook's shifted-inertia equations, gravity as base acceleration; the same body equation
//! as [`super::rnea`]). An unknown of connection c with unit direction d in the first
//! body's frame a acts on the second body b, at its point x_b, and opposite on a, at x_a:
//!
//! ```text
//! force:  on b  [R_ba d;  x_b × R_ba d]     on a  [−d; −x_a × d]
//! couple: on b  [0;       R_ba d]           on a  [0;  −d]
//! ```
//!
//! with R_ba the rotation from a's frame to b's. The coefficient of each unknown in each
//! balance row is A(q); W is b(q, q̇, q̈); [`super::qr`] solves A x = b.
//!
//! **Loop closure.** With world poses (R_i, o_i) of the bodies, a declared constraint's
//! gap in the first body's frame is δ = R_aᵀ (o_b + R_b x_b − o_a) − x_a and its relative
//! rotation R_ab = R_aᵀ R_b. Each force component d gives φ = d · δ, each couple component
//! d gives φ = d · vee(R_ab) with vee(R) = ½ (R₃₂ − R₂₃, R₁₃ − R₃₁, R₂₁ − R₁₂) (zero for
//! the rotations the connection allows). Φ_q = ∂φ/∂q and γ = −(∂(Φ_q q̇)/∂q) q̇ (so that
//! Φ_q q̈ = γ keeps φ̈ = 0) are exact symbolic derivatives of φ.

use super::geometry::{BodyInertia, JointTransform};
use super::rnea::{self, SweepInputs};
use crate::model::statics::{Component, Statics};
use crate::model::Model;
use crate::sym::{Array, Graph, Mat3, Node, Vec3};

/// World pose of every body: rotation body → world and origin in the world frame.
pub fn world_poses(g: &Graph, model: &Model, transforms: &[JointTransform]) -> Vec<(Mat3, Vec3)> {
    let mut poses: Vec<(Mat3, Vec3)> = Vec::with_capacity(model.bodies.len());
    for (body, t) in model.bodies.iter().zip(transforms) {
        let pose = match body.parent {
            None => (t.rotation_to_parent, t.origin_in_parent),
            Some(p) => {
                let (r, o) = poses[p];
                (
                    r.mul(g, t.rotation_to_parent),
                    o.add(g, r.mul_vec(g, t.origin_in_parent)),
                )
            }
        };
        poses.push(pose);
    }
    poses
}

/// The rotation from the frame of `first` to the frame of `second` (`None`: ground).
fn rotation_between(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    poses: &[(Mat3, Vec3)],
    first: Option<usize>,
    second: usize,
) -> Mat3 {
    if model.bodies[second].parent == first {
        return transforms[second].rotation_to_parent.transpose();
    }
    let to_world_second = poses[second].0;
    match first {
        None => to_world_second.transpose(),
        Some(a) => to_world_second.transpose().mul(g, poses[a].0),
    }
}

/// A(q) x = b(q, q̇, q̈) of the force analysis: (A by rows, b).
pub fn balance_equations(
    g: &Graph,
    model: &Model,
    statics: &Statics,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    inputs: &SweepInputs,
) -> (Vec<Vec<Node>>, Vec<Node>) {
    // The wrench each body needs for its motion (the right-hand side).
    let motions = rnea::motions(g, model, transforms, inputs);
    let loads = rnea::load_wrenches(g, model, transforms, inputs.loads);
    let rows = statics.rows_per_body();
    let component = |(f, m): &(Vec3, Vec3), (kind, axis): (Component, usize)| match kind {
        Component::Force => f.get(axis),
        Component::Couple => m.get(axis),
    };
    let mut b = Vec::with_capacity(rows.len() * model.bodies.len());
    for ((motion, inertia), (load_f, load_m)) in motions.iter().zip(inertias).zip(&loads) {
        let (f, m) = rnea::body_wrench(g, motion, inertia);
        let wrench = (f.sub(g, *load_f), m.sub(g, *load_m));
        b.extend(rows.iter().map(|&row| component(&wrench, row)));
    }
    (balance_matrix(g, model, statics, transforms), b)
}

/// A(q) of the force analysis, by rows: the coefficient of each unknown in each body's
/// balance equations (a function of q alone, built after b by [`balance_equations`]).
pub fn balance_matrix(
    g: &Graph,
    model: &Model,
    statics: &Statics,
    transforms: &[JointTransform],
) -> Vec<Vec<Node>> {
    let rows = statics.rows_per_body();
    let component = |(f, m): &(Vec3, Vec3), (kind, axis): (Component, usize)| match kind {
        Component::Force => f.get(axis),
        Component::Couple => m.get(axis),
    };
    let poses = world_poses(g, model, transforms);
    let n = statics.unknowns.len();
    let mut a = vec![vec![g.zero(); n]; rows.len() * model.bodies.len()];
    for (k, unknown) in statics.unknowns.iter().enumerate() {
        let c = &statics.connections[unknown.connection];
        let d = Vec3::constant(g, unknown.direction_in_first);
        let x_a = super::geometry::vector(g, &c.point_in_first);
        let x_b = super::geometry::vector(g, &c.point_in_second);
        let mut place = |body: usize, wrench: (Vec3, Vec3)| {
            for (r, &row) in rows.iter().enumerate() {
                let entry = &mut a[body * rows.len() + r][k];
                *entry = g.add(*entry, component(&wrench, row));
            }
        };
        let zero = Vec3::zero(g);
        if let Some(second) = c.second {
            let d_b = rotation_between(g, model, transforms, &poses, c.first, second).mul_vec(g, d);
            place(
                second,
                match unknown.component {
                    Component::Force => (d_b, x_b.cross(g, d_b)),
                    Component::Couple => (zero, d_b),
                },
            );
        }
        if let Some(first) = c.first {
            let minus = d.neg(g);
            place(
                first,
                match unknown.component {
                    Component::Force => (minus, x_a.cross(g, minus)),
                    Component::Couple => (zero, minus),
                },
            );
        }
    }
    a
}

/// φ(q) of the declared constraints, one entry per closure component.
pub fn closure_residual(
    g: &Graph,
    model: &Model,
    statics: &Statics,
    transforms: &[JointTransform],
) -> Vec<Node> {
    let poses = world_poses(g, model, transforms);
    let pose = |body: Option<usize>| body.map_or((Mat3::identity(g), Vec3::zero(g)), |i| poses[i]);
    statics
        .closure_components()
        .map(|u| {
            let c = &statics.connections[u.connection];
            let ((r_a, o_a), (r_b, o_b)) = (pose(c.first), pose(c.second));
            let d = Vec3::constant(g, u.direction_in_first);
            match u.component {
                Component::Force => {
                    let x_a = super::geometry::vector(g, &c.point_in_first);
                    let x_b = super::geometry::vector(g, &c.point_in_second);
                    let point_b = o_b.add(g, r_b.mul_vec(g, x_b));
                    let gap = r_a.transpose().mul_vec(g, point_b.sub(g, o_a)).sub(g, x_a);
                    d.dot(g, gap)
                }
                Component::Couple => {
                    let r = r_a.transpose().mul(g, r_b);
                    let half = g.constant(0.5);
                    let vee = Vec3::new(
                        g.mul(half, g.sub(r.get(2, 1), r.get(1, 2))),
                        g.mul(half, g.sub(r.get(0, 2), r.get(2, 0))),
                        g.mul(half, g.sub(r.get(1, 0), r.get(0, 1))),
                    );
                    d.dot(g, vee)
                }
            }
        })
        .collect()
}

/// Φ_q = ∂φ/∂q by rows (one column per coordinate; the closure needs nq = nv).
pub fn closure_jacobian(g: &Graph, model: &Model, phi: &[Node]) -> Vec<Vec<Node>> {
    let columns: Vec<Vec<Node>> = (0..model.nv)
        .map(|j| {
            g.derivative(phi, |r| {
                if r.array == Array::Q && r.index as usize == j {
                    g.one()
                } else {
                    g.zero()
                }
            })
        })
        .collect();
    (0..phi.len())
        .map(|i| columns.iter().map(|col| col[i]).collect())
        .collect()
}

/// φ̇ = Φ_q q̇ and γ = −(∂(Φ_q q̇)/∂q) q̇, from the velocity input.
pub fn closure_rates(g: &Graph, phi: &[Node]) -> (Vec<Node>, Vec<Node>) {
    let along_v = |r: crate::sym::InputRef| {
        if r.array == Array::Q {
            g.input(Array::V, r.index as usize)
        } else {
            g.zero()
        }
    };
    let rate = g.derivative(phi, along_v);
    let gamma = g
        .derivative(&rate, along_v)
        .into_iter()
        .map(|n| g.neg(n))
        .collect();
    (rate, gamma)
}
