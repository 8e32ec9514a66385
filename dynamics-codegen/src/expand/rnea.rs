//! Inverse dynamics by the recursive Newton–Euler algorithm, in the seed's shifted-inertia
//! form about each body's joint point P (all vectors in the body frame).
//!
//! Forward sweep (body i, parent λ, joint axis s, E = rotation body → parent, r = P_i in the
//! parent frame; the base has ω = α = 0 and a = −g, so gravity enters as an acceleration):
//!
//! ```text
//! revolute:   ω_i = Eᵀω_λ + s q̇        α_i = Eᵀα_λ + s q̈ + (Eᵀω_λ) × s q̇
//!             a_i = Eᵀ(a_λ + α_λ × r + ω_λ × (ω_λ × r))
//! prismatic:  ω_i = Eᵀω_λ   α_i = Eᵀα_λ
//!             a_i = Eᵀ(a_λ + α_λ × r + ω_λ × (ω_λ × r)) + 2 ω_i × s q̇ + s q̈
//! free:       ω = v_ang, α = a_ang, a_P = a_lin + ω × v_lin + Eᵀ a_0
//! ```
//!
//! Body equation (the seed's coupled six-dimensional equation, h = m c, c = PG,
//! I_P = I_G − m ĉ²):
//!
//! ```text
//! F   = m a_P − m ĉ α + m ω̂² c  = m a_P + α × h + ω × (ω × h)
//! M_P = m ĉ a_P + I_P α + ω × I_P ω = h × a_P + I_P α + ω × (I_P ω)
//! ```
//!
//! minus the applied loads on the body. Backward sweep: the wrench the joint transmits,
//! f_i = (F, M_P)_i + Σ_children (E_c F_c, E_c M_c + r_c × E_c F_c), and τ_i = s_iᵀ f_i
//! (the moment for a revolute joint, the force for a prismatic one, the whole wrench for a
//! free joint), plus armature · q̈ and damping · q̇.

use super::geometry::{self, BodyInertia, JointTransform};
use crate::model::{JointKind, LoadKind, Model};
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
}

/// What a sweep computes: the joint forces and the wrench each joint transmits.
pub struct Sweep {
    /// τ, one per velocity coordinate.
    pub tau: Vec<Node>,
    /// (F, M_P) transmitted by each body's joint, in the body frame about P.
    pub wrenches: Vec<(Vec3, Vec3)>,
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

/// Runs the Newton–Euler sweeps.
pub fn sweep(
    g: &Graph,
    model: &Model,
    transforms: &[JointTransform],
    inertias: &[BodyInertia],
    inputs: &SweepInputs,
) -> Sweep {
    let base_accel = if inputs.gravity {
        Vec3::constant(g, model.gravity_in_world).neg(g)
    } else {
        Vec3::zero(g)
    };
    let base = BodyMotion {
        omega: Vec3::zero(g),
        alpha: Vec3::zero(g),
        accel: base_accel,
    };
    let mut motions: Vec<BodyMotion> = Vec::with_capacity(model.bodies.len());
    for (i, body) in model.bodies.iter().enumerate() {
        let parent = body.parent.map_or(base, |p| motions[p]);
        motions.push(forward(g, &body.joint, &transforms[i], parent, inputs));
    }
    let mut wrenches: Vec<(Vec3, Vec3)> = motions
        .iter()
        .zip(inertias)
        .map(|(motion, inertia)| body_wrench(g, motion, inertia))
        .collect();
    if inputs.loads {
        subtract_loads(g, model, &mut wrenches);
    }
    for i in (0..model.bodies.len()).rev() {
        if let Some(p) = model.bodies[i].parent {
            let (f, m) =
                geometry::wrench_to_parent(g, &transforms[i], wrenches[i].0, wrenches[i].1);
            wrenches[p] = (wrenches[p].0.add(g, f), wrenches[p].1.add(g, m));
        }
    }
    let mut tau = vec![g.zero(); model.nv];
    for (body, (force, moment)) in model.bodies.iter().zip(&wrenches) {
        let joint = &body.joint;
        let k = joint.idx_v;
        match joint.kind {
            JointKind::Revolute { axis_in_joint } => {
                tau[k] = Vec3::constant(g, axis_in_joint).dot(g, *moment)
            }
            JointKind::Prismatic { axis_in_joint } => {
                tau[k] = Vec3::constant(g, axis_in_joint).dot(g, *force)
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
        for j in k..k + joint_dofs(&joint.kind) {
            let extra = g.add(
                g.mul(armature, inputs.acceleration[j]),
                g.mul(damping, inputs.velocity[j]),
            );
            tau[j] = g.add(tau[j], extra);
        }
    }
    Sweep { tau, wrenches }
}

/// Number of velocity coordinates of a joint.
pub fn joint_dofs(kind: &JointKind) -> usize {
    match kind {
        JointKind::Free => 6,
        _ => 1,
    }
}

/// One step of the forward sweep: the body's motion from its parent's.
fn forward(
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
    let transported = parent
        .accel
        .add(g, parent.alpha.cross(g, r))
        .add(g, parent.omega.cross(g, parent.omega.cross(g, r)));
    let accel_in = geometry::to_body(g, t, transported);
    match joint.kind {
        JointKind::Revolute { axis_in_joint } => {
            let s = Vec3::constant(g, axis_in_joint);
            let spin = s.scale(g, qd(0));
            BodyMotion {
                omega: omega_in.add(g, spin),
                alpha: alpha_in
                    .add(g, s.scale(g, qdd(0)))
                    .add(g, omega_in.cross(g, spin)),
                accel: accel_in,
            }
        }
        JointKind::Prismatic { axis_in_joint } => {
            let s = Vec3::constant(g, axis_in_joint);
            let slide = s.scale(g, qd(0));
            let two = g.constant(2.0);
            BodyMotion {
                omega: omega_in,
                alpha: alpha_in,
                accel: accel_in
                    .add(g, omega_in.cross(g, slide).scale(g, two))
                    .add(g, s.scale(g, qdd(0))),
            }
        }
        JointKind::Free => {
            let v_lin = Vec3::new(qd(0), qd(1), qd(2));
            let omega = omega_in.add(g, Vec3::new(qd(3), qd(4), qd(5)));
            BodyMotion {
                omega,
                alpha: alpha_in.add(g, Vec3::new(qdd(3), qdd(4), qdd(5))),
                accel: accel_in
                    .add(g, Vec3::new(qdd(0), qdd(1), qdd(2)))
                    .add(g, omega.cross(g, v_lin)),
            }
        }
    }
}

/// The seed's body equation about P: the wrench that produces the body's motion.
pub fn body_wrench(g: &Graph, motion: &BodyMotion, inertia: &BodyInertia) -> (Vec3, Vec3) {
    let BodyMotion {
        omega,
        alpha,
        accel,
    } = *motion;
    let h = inertia.first_moment;
    let i_p: Mat3 = inertia.inertia_about_origin;
    let force = accel
        .scale(g, inertia.mass)
        .add(g, alpha.cross(g, h))
        .add(g, omega.cross(g, omega.cross(g, h)));
    let moment = h
        .cross(g, accel)
        .add(g, i_p.mul_vec(g, alpha))
        .add(g, omega.cross(g, i_p.mul_vec(g, omega)));
    (force, moment)
}

/// Subtracts each declared load (force f through point r_l, couple n, both given in the
/// loaded body's declared frame) from its body's wrench: F −= f, M_P −= r_l × f + n.
fn subtract_loads(g: &Graph, model: &Model, wrenches: &mut [(Vec3, Vec3)]) {
    for load in &model.loads {
        let input = |k: usize| {
            let raw = Vec3::new(
                g.input(Array::Loads, load.input_offset + k),
                g.input(Array::Loads, load.input_offset + k + 1),
                g.input(Array::Loads, load.input_offset + k + 2),
            );
            Mat3::constant(g, load.rotation_in_body).mul_vec(g, raw)
        };
        let (force, couple) = match load.kind {
            LoadKind::Force => (input(0), Vec3::zero(g)),
            LoadKind::Couple => (Vec3::zero(g), input(0)),
            LoadKind::Wrench => (input(0), input(3)),
        };
        let point = geometry::vector(g, &load.point_in_body);
        let moment = point.cross(g, force).add(g, couple);
        let (f, m) = &mut wrenches[load.body];
        *f = f.sub(g, force);
        *m = m.sub(g, moment);
    }
}
