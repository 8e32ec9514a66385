//! Inverse dynamics by the recursive Newton–Euler algorithm, in the textbook's shifted-inertia
//! form about each body's joint point P (all vectors in the body frame).
//!
//! Forward sweep (body i, parent λ, joint axis s, E = rotation body → parent, r = P_i in the
//! parent frame; the base has ω = α = 0 and a = −g, so gravity enters as an acceleration):
//!
//! ```text
//! revolute:   ω_i = Eᵀω_λ + s q̇        α_i = Eᵀα_λ + s q̈ + (Eᵀω_λ) × s q̇
//!             a_i = Eᵀ(a_λ + U_λ r)
//! prismatic:  ω_i = Eᵀω_λ   α_i = Eᵀα_λ
//!             a_i = Eᵀ(a_λ + U_λ r) + 2 ω_i × s q̇ + s q̈
//! free:       ω = v_ang, α = a_ang, a_P = a_lin + ω × v_lin + Eᵀ a_0
//! ```
//!
//! where U = α̂ + ω̂² is the matrix with U x = α × x + ω × (ω × x), the acceleration of a
//! body-fixed point at x relative to P. It is built once per body from the six products
//! ω_i ω_j and serves twice: to carry the acceleration to the children and in the body
//! equation. Body equation (the textbook's coupled six-dimensional equation, h = m c, c = PG,
//! I_P = I_G − m ĉ²):
//!
//! ```text
//! F   = m a_P − m ĉ α + m ω̂² c     = m a_P + U h
//! M_P = m ĉ a_P + I_P α + ω × I_P ω = h × a_P + I_P α + ω × (I_P ω)
//! ```
//!
//! with I_P α + ω × (I_P ω) from the Euler form of the textbook (ω × (I_P ω) has first
//! component (I_33 − I_22) ω_2 ω_3 + I_23 (ω_2² − ω_3²) + I_13 ω_1 ω_2 − I_12 ω_1 ω_3)
//! gathered by inertia entry ([`euler_moment`]: e.g. I_12 (α_2 − ω_1 ω_3), a sum U
//! already holds), whose constant differences fold at compile time. The applied loads on
//! the body are subtracted (those given `in world` first turned into the body's axes down
//! the tree, as gravity is). Backward sweep: the wrench the joint transmits,
//! f_i = (F, M_P)_i + Σ_children (E_c F_c, E_c M_c + r_c × E_c F_c), and τ_i = s_iᵀ f_i (the
//! moment for a revolute joint, the force for a prismatic one, the whole wrench for a free
//! joint), plus armature · q̈ and damping · q̇.
//!
//! The sweep takes the inertias it is given: the declared ones for the joint wrenches, or
//! base inertial parameters for τ alone ([`crate::passes::base_parameters`]).

use super::geometry::{self, BodyInertia, JointTransform};
use crate::model::{JointKind, LoadFrame, LoadKind, Model};
use crate::sym::{Array, Graph, Mat3, Node, Vec3};

/// The motion of a body: ω, α and the classical acceleration a_P of its origin, in its frame.
#[derive(Clone, Copy, Debug)]
pub struct BodyMotion {
    /// Angular velocity ω.
    pub omega: Vec3,
    /// Angular acceleration α.
    pub alpha: Vec3,
    /// Acceleration of the origin P (gravity included as −g at the base).
    pub accel: Vec3,
    /// U = α̂ + ω̂²: U x is the acceleration of the body point at x relative to P.
    pub relative_accel: Mat3,
    /// The products ω_i ω_j.
    pub omega_products: [[Node; 3]; 3],
}

impl BodyMotion {
    /// Completes a motion from ω, α and a_P: the products ω_i ω_j and U = α̂ + ω̂².
    pub fn new(g: &Graph, omega: Vec3, alpha: Vec3, accel: Vec3) -> Self {
        let w = |i: usize| omega.get(i);
        let p: [[Node; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| g.mul(w(i), w(j))));
        let a = |i: usize| alpha.get(i);
        // ω̂² = ω ωᵀ − |ω|² 1; α̂ is skew.
        let diagonal = |i: usize| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            g.neg(g.add(p[j][j], p[k][k]))
        };
        let u = Mat3::from_rows([
            Vec3::new(diagonal(0), g.sub(p[0][1], a(2)), g.add(p[0][2], a(1))),
            Vec3::new(g.add(p[0][1], a(2)), diagonal(1), g.sub(p[1][2], a(0))),
            Vec3::new(g.sub(p[0][2], a(1)), g.add(p[1][2], a(0)), diagonal(2)),
        ]);
        BodyMotion {
            omega,
            alpha,
            accel,
            relative_accel: u,
            omega_products: p,
        }
    }
}

/// I α + ω × (I ω) for a symmetric I, linear in I's six entries: component i is
///
/// ```text
/// I_ii α_i + I_ij (α_j − ω_i ω_k) + I_ik (α_k + ω_i ω_j) + I_jk (ω_j² − ω_k²) + (I_kk − I_jj) ω_j ω_k
/// ```
///
/// for (i, j, k) a cyclic permutation of (x, y, z). The two sums α_j ∓ ω_i ω_k are the
/// off-diagonal entries of U = α̂ + ω̂² (up to sign), which the body builds anyway, and the
/// constant difference I_kk − I_jj folds: a full inertia costs 15 products where I α and the
/// Euler form ω × (I ω) apart cost 21, a diagonal one 6 as before.
pub fn euler_moment(g: &Graph, inertia: &Mat3, alpha: Vec3, p: &[[Node; 3]; 3]) -> Vec3 {
    let component = |i: usize| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let i_ = |r: usize, c: usize| inertia.get(r, c);
        let a = |r: usize| alpha.get(r);
        g.sum(&[
            g.mul(i_(i, i), a(i)),
            g.mul(i_(i, j), g.sub(a(j), p[i][k])),
            g.mul(i_(i, k), g.add(a(k), p[i][j])),
            g.mul(i_(j, k), g.sub(p[j][j], p[k][k])),
            g.mul(g.sub(i_(k, k), i_(j, j)), p[j][k]),
        ])
    };
    Vec3::new(component(0), component(1), component(2))
}

/// What a sweep computes: every body's motion, the loads on it, and the backward sweep
/// (the wrench each joint transmits and the joint forces τ).
pub(crate) struct Sweep {
    /// ω, α and a_P of every body.
    pub motions: Vec<BodyMotion>,
    /// The applied loads on every body, [F; M_P] in its frame ([`load_wrenches`]).
    pub loads: Vec<(Vec3, Vec3)>,
    /// The backward sweep over the sweep's inertias.
    pub backward: Backward,
}

impl Sweep {
    /// (F, M_P) transmitted by each body's joint, in the body frame about P.
    pub fn wrenches(&self) -> &[(Vec3, Vec3)] {
        &self.backward.joint
    }

    /// The wrench body `i` needs for its own motion with the inertia `inertia`, less the
    /// loads on it.
    pub fn own(&self, g: &Graph, i: usize, inertia: &BodyInertia) -> (Vec3, Vec3) {
        let (force, moment) = body_wrench(g, &self.motions[i], inertia);
        (
            force.sub(g, self.loads[i].0),
            moment.sub(g, self.loads[i].1),
        )
    }
}

/// The inputs of one sweep. Zero nodes fold away the terms they multiply, so the same code
/// yields inverse dynamics, bias (q̈ = 0) and gravity (q̇ = q̈ = 0).
pub struct SweepInputs<'a> {
    /// q̇, one node per velocity coordinate.
    pub velocity: &'a [Node],
    /// q̈, one node per velocity coordinate.
    pub acceleration: &'a [Node],
    /// Whether gravity acts.
    pub gravity: bool,
    /// Whether the declared loads act (read from the `loads` input).
    pub loads: bool,
}

/// Runs the Newton–Euler sweeps over `inertias`: the forward sweep of every body's
/// motion, each body's own wrench less its loads, and the backward sweep.
pub(crate) fn sweep(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    inputs: &SweepInputs,
) -> Sweep {
    let motions = motions(g, model, transforms, inputs);
    let loads = load_wrenches(g, model, transforms, inputs.loads);
    let mut sweep = Sweep {
        motions,
        loads,
        backward: Backward {
            own: Vec::new(),
            joint: Vec::new(),
            carried: Vec::new(),
            tau: Vec::new(),
        },
    };
    let own: Vec<(Vec3, Vec3)> = inertias
        .iter()
        .enumerate()
        .map(|(i, b)| sweep.own(g, i, b))
        .collect();
    sweep.backward = Backward::new(g, model, transforms, inputs, own);
    sweep
}

/// The backward sweep: each joint's wrench f_i is the body's own wrench plus its children's
/// joint wrenches carried to its frame (from the leaves to the root), and τ_i = s_iᵀ f_i.
/// Kept per body, so that a change of a few bodies' own wrenches redoes only their paths to
/// the root.
#[derive(Clone)]
pub(crate) struct Backward {
    /// Each body's own wrench [F; M_P] (loads subtracted).
    own: Vec<(Vec3, Vec3)>,
    /// f_i, the wrench each joint transmits to its body, in the body frame about P.
    joint: Vec<(Vec3, Vec3)>,
    /// f_i carried to the parent's frame, about the parent's origin.
    carried: Vec<(Vec3, Vec3)>,
    /// τ.
    pub tau: Vec<Node>,
}

impl Backward {
    /// The backward sweep over the bodies' own wrenches `own`.
    pub(crate) fn new(
        g: &Graph,
        model: &Model,
        transforms: &[JointTransform],
        inputs: &SweepInputs,
        own: Vec<(Vec3, Vec3)>,
    ) -> Self {
        let n = own.len();
        let mut sweep = Backward {
            joint: own.clone(),
            carried: own.clone(),
            own,
            tau: vec![g.zero(); model.nv],
        };
        sweep.redo(g, model, transforms, inputs, vec![true; n]);
        sweep
    }

    /// The sweep with the own wrenches of some bodies replaced.
    pub fn with(
        &self,
        g: &Graph,
        model: &Model,
        transforms: &[JointTransform],
        inputs: &SweepInputs,
        changes: &[(usize, (Vec3, Vec3))],
    ) -> Self {
        let mut sweep = self.clone();
        let mut dirty = vec![false; self.own.len()];
        for &(i, wrench) in changes {
            sweep.own[i] = wrench;
            let mut body = Some(i);
            while let Some(k) = body {
                dirty[k] = true;
                body = model.bodies[k].parent;
            }
        }
        sweep.redo(g, model, transforms, inputs, dirty);
        sweep
    }

    /// Each body's own wrench [F; M_P] (loads subtracted), as the sweep was given it.
    pub(crate) fn own_wrenches(&self) -> &[(Vec3, Vec3)] {
        &self.own
    }

    /// Recomputes f_i, its carried form and τ_i of the `dirty` bodies (closed under
    /// parents), children first; children are added in decreasing order.
    fn redo(
        &mut self,
        g: &Graph,
        model: &Model,
        transforms: &[JointTransform],
        inputs: &SweepInputs,
        dirty: Vec<bool>,
    ) {
        let children = children_in_decreasing_order(model);
        for i in (0..self.own.len()).rev().filter(|&i| dirty[i]) {
            let carried = children[i].iter().map(|&c| self.carried[c]);
            let total = joint_wrench(g, self.own[i], carried);
            self.joint[i] = total;
            self.carried[i] = geometry::wrench_to_parent(g, &transforms[i], total.0, total.1);
            joint_force(g, &model.bodies[i].joint, total, inputs, &mut self.tau);
        }
    }
}

/// f_i = the body's own wrench plus its children's, carried to its frame (in the order
/// given: the backward sweep's, children in decreasing order).
pub(crate) fn joint_wrench(
    g: &Graph,
    own: (Vec3, Vec3),
    carried: impl IntoIterator<Item = (Vec3, Vec3)>,
) -> (Vec3, Vec3) {
    carried.into_iter().fold(own, |(force, moment), (f, m)| {
        (force.add(g, f), moment.add(g, m))
    })
}

/// The children of every body, each list in decreasing order (the order in which the
/// backward sweep adds their wrenches).
pub(crate) fn children_in_decreasing_order(model: &Model) -> Vec<Vec<usize>> {
    let mut children = vec![Vec::new(); model.bodies.len()];
    for (c, body) in model.bodies.iter().enumerate().rev() {
        if let Some(p) = body.parent {
            children[p].push(c);
        }
    }
    children
}

/// τ of one joint from the wrench f it transmits: sᵀ f (the moment for a revolute joint,
/// the force for a prismatic one, the whole wrench for a free joint), plus armature · q̈ and
/// damping · q̇.
pub(crate) fn joint_force(
    g: &Graph,
    joint: &crate::model::Joint,
    (force, moment): (Vec3, Vec3),
    inputs: &SweepInputs,
    tau: &mut [Node],
) {
    let k = joint.idx_v;
    match joint.kind {
        JointKind::Revolute { axis_in_body } => {
            tau[k] = Vec3::constant(g, axis_in_body).dot(g, moment);
        }
        JointKind::Prismatic { axis_in_body } => {
            tau[k] = Vec3::constant(g, axis_in_body).dot(g, force);
        }
        JointKind::Free => {
            for j in 0..3 {
                tau[k + j] = force.get(j);
                tau[k + 3 + j] = moment.get(j);
            }
        }
    }
    let armature = geometry::value(g, &joint.armature);
    let damping = geometry::value(g, &joint.damping);
    for j in k..k + joint.kind.dofs() {
        let extra = g.add(
            g.mul(armature, inputs.acceleration[j]),
            g.mul(damping, inputs.velocity[j]),
        );
        tau[j] = g.add(tau[j], extra);
    }
}

/// The forward sweep: every body's ω, α and a_P, parents first, with gravity acting as an
/// upward acceleration −g of the base when `inputs.gravity` is set.
pub fn motions(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inputs: &SweepInputs,
) -> Vec<BodyMotion> {
    let base_accel = if inputs.gravity {
        Vec3::constant(g, model.gravity_in_world).neg(g)
    } else {
        Vec3::zero(g)
    };
    let base = BodyMotion::new(g, Vec3::zero(g), Vec3::zero(g), base_accel);
    let mut motions: Vec<BodyMotion> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let parent = body.parent.map_or(base, |p| motions[p]);
        motions.push(forward(g, &body.joint, &transforms[i], parent, inputs));
    }
    motions
}

/// One step of the forward sweep: the body's motion from its parent's.
pub(crate) fn forward(
    g: &Graph,
    joint: &crate::model::Joint,
    t: &JointTransform,
    parent: BodyMotion,
    inputs: &SweepInputs,
) -> BodyMotion {
    let k = joint.idx_v;
    let (qd, qdd) = (
        |j: usize| inputs.velocity[k + j],
        |j: usize| inputs.acceleration[k + j],
    );
    let r = t.origin_in_parent;
    let omega_in = geometry::to_body(g, t, parent.omega);
    let alpha_in = geometry::to_body(g, t, parent.alpha);
    let transported = parent.accel.add(g, parent.relative_accel.mul_vec(g, r));
    let accel_in = geometry::to_body(g, t, transported);
    match joint.kind {
        JointKind::Revolute { axis_in_body } => {
            let s = Vec3::constant(g, axis_in_body);
            let spin = s.scale(g, qd(0));
            let omega = omega_in.add(g, spin);
            let alpha = alpha_in
                .add(g, s.scale(g, qdd(0)))
                .add(g, omega_in.cross(g, spin));
            BodyMotion::new(g, omega, alpha, accel_in)
        }
        JointKind::Prismatic { axis_in_body } => {
            let s = Vec3::constant(g, axis_in_body);
            let slide = s.scale(g, qd(0));
            let two = g.constant(2.0);
            let accel = accel_in
                .add(g, omega_in.cross(g, slide).scale(g, two))
                .add(g, s.scale(g, qdd(0)));
            BodyMotion::new(g, omega_in, alpha_in, accel)
        }
        JointKind::Free => {
            let v_lin = Vec3::new(qd(0), qd(1), qd(2));
            let omega = omega_in.add(g, Vec3::new(qd(3), qd(4), qd(5)));
            let alpha = alpha_in.add(g, Vec3::new(qdd(3), qdd(4), qdd(5)));
            let accel = accel_in
                .add(g, Vec3::new(qdd(0), qdd(1), qdd(2)))
                .add(g, omega.cross(g, v_lin));
            BodyMotion::new(g, omega, alpha, accel)
        }
    }
}

/// The textbook's body equation about P: the wrench that produces the body's motion.
///
/// F is always the shifted form F = m a_P + U h. The moment M_P = h × a_P + I_P α + ω × I_P ω
/// equals c × F + I_G α + ω × I_G ω (the textbook's M_P = M_G + c × F, from which the shifted
/// form is derived); when the body's inertia is constant, the grouping that costs fewer
/// operations is used (I_G is often diagonal where I_P is not).
pub fn body_wrench(g: &Graph, motion: &BodyMotion, inertia: &BodyInertia) -> (Vec3, Vec3) {
    let h = inertia.first_moment;
    let i_p: Mat3 = inertia.inertia_about_origin;
    let force = motion
        .accel
        .scale(g, inertia.mass)
        .add(g, motion.relative_accel.mul_vec(g, h));
    let about_centre = inertia
        .mass_centre
        .filter(|(c, i_g)| centre_grouping_is_cheaper(g, h, i_p, *c, *i_g));
    let moment = match about_centre {
        Some((c, i_g)) => c.cross(g, force).add(
            g,
            euler_moment(g, &i_g, motion.alpha, &motion.omega_products),
        ),
        None => h.cross(g, motion.accel).add(
            g,
            euler_moment(g, &i_p, motion.alpha, &motion.omega_products),
        ),
    };
    (force, moment)
}

/// Whether c × F + I_G α + ω × I_G ω costs fewer operations than h × a_P + I_P α +
/// ω × I_P ω for these constant inertias: both are built on a scratch graph whose inputs
/// stand for a_P, F, α and the products ω_i ω_j, and their op counts compared.
fn centre_grouping_is_cheaper(g: &Graph, h: Vec3, i_p: Mat3, c: Vec3, i_g: Mat3) -> bool {
    let constants = |v: Vec<Node>| {
        v.iter()
            .map(|&n| g.constant_value(n))
            .collect::<Option<Vec<f64>>>()
    };
    let (Some(h), Some(i_p), Some(c), Some(i_g)) = (
        constants(h.0.to_vec()),
        constants(i_p.0.iter().flatten().copied().collect()),
        constants(c.0.to_vec()),
        constants(i_g.0.iter().flatten().copied().collect()),
    ) else {
        return false;
    };
    let cost = |first: &[f64], linear: &[f64], use_force: bool| {
        let s = Graph::new();
        let input = |k: usize| s.input(Array::A, k);
        let vector = |v: &[f64]| Vec3::constant(&s, [v[0], v[1], v[2]]);
        let matrix = |m: &[f64]| {
            Mat3::constant(
                &s,
                [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]],
            )
        };
        let operand = if use_force {
            Vec3::new(input(0), input(1), input(2))
        } else {
            Vec3::new(input(3), input(4), input(5))
        };
        let alpha = Vec3::new(input(6), input(7), input(8));
        let p: [[Node; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| input(9 + 3 * i.min(j) + i.max(j))));
        let i_m = matrix(linear);
        let m = vector(first)
            .cross(&s, operand)
            .add(&s, euler_moment(&s, &i_m, alpha, &p));
        let ops = s.op_count(&m.0);
        ops.mul + ops.add
    };
    cost(&c, &i_g, true) < cost(&h, &i_p, false)
}

/// The applied loads as a wrench on each body, [F; M_P] in the body frame: a force f
/// through point r_l and a couple n give F = f, M_P = r_l × f + n, with f and n in the body
/// frame: the inputs turned from the loaded body's declared frame by a constant rotation
/// (the body's place in the composite body it was merged into), or, for a load given
/// `in world`, from the world's axes down the tree, f_in_body = E_iᵀ ⋯ E_1ᵀ f_in_world
/// ([`world_to_body`]). Bodies without loads get zero.
pub fn load_wrenches(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    with_loads: bool,
) -> Vec<(Vec3, Vec3)> {
    let mut wrenches = vec![(Vec3::zero(g), Vec3::zero(g)); model.bodies.len()];
    if !with_loads {
        return wrenches;
    }
    for load in &model.loads {
        let input = |k: usize| {
            let raw = Vec3::new(
                g.input(Array::Loads, load.input_offset + k),
                g.input(Array::Loads, load.input_offset + k + 1),
                g.input(Array::Loads, load.input_offset + k + 2),
            );
            match load.frame {
                LoadFrame::Body => Mat3::constant(g, load.rotation_in_body).mul_vec(g, raw),
                LoadFrame::World => world_to_body(g, model, transforms, load.body, raw),
            }
        };
        let (force, couple) = match load.kind {
            LoadKind::Force => (input(0), Vec3::zero(g)),
            LoadKind::Couple => (Vec3::zero(g), input(0)),
            LoadKind::Wrench => (input(0), input(3)),
        };
        let point = geometry::vector(g, &load.point_in_body);
        let moment = point.cross(g, force).add(g, couple);
        let (f, m) = &mut wrenches[load.body];
        *f = f.add(g, force);
        *m = m.add(g, moment);
    }
    wrenches
}

/// A vector given in world axes, in the axes of body `body`: turned into each body's frame
/// on the path from the root down, w_i = E_iᵀ w_λ (as gravity enters the forward sweep),
/// which is R_bodyᵀ w_in_world with R_body = E_1 ⋯ E_i.
fn world_to_body(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    body: usize,
    in_world: Vec3,
) -> Vec3 {
    let mut path = vec![body];
    while let Some(parent) = path.last().and_then(|&b| model.bodies[b].parent) {
        path.push(parent);
    }
    path.iter()
        .rev()
        .fold(in_world, |w, &b| geometry::to_body(g, &transforms[b], w))
}

#[cfg(test)]
mod tests {
    use super::euler_moment;
    use crate::sym::{Array, Graph, Mat3, Node, Vec3};

    /// I α + ω × (I ω) gathered by inertia entry equals the textbook form, and a full
    /// numeric inertia costs 15 products (21 for I α and the Euler form apart).
    #[test]
    fn euler_moment_is_i_alpha_plus_gyroscopic_for_fewer_products() {
        let inertia = [[0.7, -0.02, 0.03], [-0.02, 0.5, 0.011], [0.03, 0.011, 0.3]];
        let (omega, alpha) = ([0.3, -1.7, 2.2], [-0.4, 0.9, 1.3]);
        let g = Graph::new();
        let w = Vec3::new(
            g.input(Array::V, 0),
            g.input(Array::V, 1),
            g.input(Array::V, 2),
        );
        let a = Vec3::new(
            g.input(Array::A, 0),
            g.input(Array::A, 1),
            g.input(Array::A, 2),
        );
        let p: [[Node; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|j| g.mul(w.get(i), w.get(j))));
        let m = euler_moment(&g, &Mat3::constant(&g, inertia), a, &p);
        let value = |r: crate::sym::InputRef| match r.array {
            Array::V => omega[r.index as usize],
            _ => alpha[r.index as usize],
        };
        let got = g.eval(value, &m.0);
        let times = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|i| (0..3).map(|j| inertia[i][j] * v[j]).sum())
        };
        let (i_alpha, i_omega) = (times(alpha), times(omega));
        for k in 0..3 {
            let (j, l) = ((k + 1) % 3, (k + 2) % 3);
            let expected = i_alpha[k] + omega[j] * i_omega[l] - omega[l] * i_omega[j];
            assert!(
                (got[k] - expected).abs() < 1e-14,
                "component {k}: {} vs {expected}",
                got[k]
            );
        }
        let products = g.op_count(&m.0).mul - 6; // less the six ω_i ω_j, which U shares
        assert_eq!(products, 15);
    }
}
