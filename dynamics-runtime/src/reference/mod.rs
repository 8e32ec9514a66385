//! The independent numeric reference: the textbook algorithms on a runtime [`Model`].
//!
//! Everything here is written from the textbook chapter (Satici, *Kinematics and Machine
//! Dynamics*, ch. 10) and from Featherstone, *Rigid Body Dynamics Algorithms* (2008), and
//! shares no code with the symbolic expansion, whose mistakes it exists to catch.
//!
//! One file per algorithm:
//! - `spatial`: helpers for six-dimensional inertia, transforms and cross products,
//!   linear first (motion `[v_P; ω]`, force `[F; M_P]`);
//! - `kinematics`: placements, velocities and accelerations, the body poses in the world,
//!   the centre of mass;
//! - `frames`: operational frames: poses, Jacobians, velocities, classical accelerations;
//! - `loads`: the applied loads as generalized forces, Q = Σ J_Pᵀ F + J_ωᵀ M;
//! - `centroidal`: the centroidal momentum h_G and its rate ḣ_G;
//! - `rnea`: recursive Newton–Euler in the textbook's mass-centre form (inverse dynamics,
//!   gravity, bias, nonlinear effects, joint reactions);
//! - `crba`: composite-rigid-body algorithm, M(q);
//! - `aba`: articulated-body algorithm, forward dynamics;
//! - `coriolis`: a Christoffel-consistent C(q, v);
//! - `energy`: kinetic and potential energy.
//!
//! # Workspace
//! A [`Reference`] borrows the model, converts its `f64` constants to `T` once in
//! [`Reference::new`] and preallocates every scratch quantity, so no method allocates
//! afterwards. Each public method checks the lengths of its slices and returns a
//! [`SizeError`] instead of panicking.
//!
//! # Conventions
//! Body `i` is moved by joint `i` and `parent(i) < i`. Each body frame has its origin P at
//! the joint point; `rotation_in_parent` maps body coordinates to parent coordinates and
//! `origin_in_parent` is P in the parent frame. A free-floating joint has its parent on the
//! ground (the model guarantees it): its velocity `v = [v_P; ω]` and `a = dv/dt` are
//! expressed in the body frame, and its motion subspace S is the 6×6 identity. Armature adds
//! to M's diagonal; damping b adds `b·q̇` to the torque a joint needs.

mod aba;
mod centroidal;
mod coriolis;
mod crba;
mod energy;
#[cfg(test)]
mod frame_tests;
#[cfg(test)]
#[rustfmt::skip]
mod pinocchio_frames;
mod frames;
mod kinematics;
mod loads;
pub use frames::FrameError;
mod rnea;
mod spatial;

use crate::model::{JointKind, Model, SizeError};
use crate::scalar::Scalar;
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// An external wrench `[F; M_P]` acting ON a body, in that body's frame, with the moment
/// taken about the body frame's origin P (the joint point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrench<T: Scalar> {
    /// Resultant force F, in the body frame (N).
    pub force: Vector3<T>,
    /// Moment M_P about the body frame's origin P, in the body frame (N·m).
    pub moment: Vector3<T>,
}

impl<T: Scalar> Wrench<T> {
    /// The zero wrench.
    pub fn zero() -> Self {
        Wrench {
            force: Vector3::zeros(),
            moment: Vector3::zeros(),
        }
    }

    /// A wrench from its force and its moment about P.
    pub fn new(force: Vector3<T>, moment: Vector3<T>) -> Self {
        Wrench { force, moment }
    }

    /// The six-vector `[F; M_P]` (force first).
    pub fn to_vector6(&self) -> Vector6<T> {
        let f = &self.force;
        let m = &self.moment;
        Vector6::new(f[0], f[1], f[2], m[0], m[1], m[2])
    }

    /// The wrench of a six-vector `[F; M_P]`.
    pub fn from_vector6(f: &Vector6<T>) -> Self {
        Wrench {
            force: Vector3::new(f[0], f[1], f[2]),
            moment: Vector3::new(f[3], f[4], f[5]),
        }
    }
}

/// The pose of a body frame (or of an operational frame) in the world:
/// `x_in_world = rotation_in_world · x_in_body + origin_in_world`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose<T: Scalar> {
    /// Rotation from body (or frame) coordinates to world coordinates.
    pub rotation_in_world: Matrix3<T>,
    /// The body frame's origin P (or the frame's origin), in the world frame (m).
    pub origin_in_world: Vector3<T>,
}

impl<T: Scalar> Pose<T> {
    fn identity() -> Self {
        Pose {
            rotation_in_world: Matrix3::identity(),
            origin_in_world: Vector3::zeros(),
        }
    }
}

/// How a joint moves its body, with its constants converted to `T`.
#[derive(Clone, Copy, Debug)]
enum Motion<T: Scalar> {
    /// Rotation by q about a unit axis (the same in the joint and the body frame).
    Revolute { axis: Vector3<T> },
    /// Translation by q along a unit axis (the same in the joint and the body frame).
    Prismatic { axis: Vector3<T> },
    /// Six degrees of freedom relative to the ground.
    FreeFlyer,
}

/// One body and its joint: the model's constants, converted to `T` once.
#[derive(Clone, Debug)]
struct BodyConstants<T: Scalar> {
    parent: Option<usize>,
    motion: Motion<T>,
    /// First coordinate of the joint in q, in v, and its number of velocity coordinates.
    idx_q: usize,
    idx_v: usize,
    nv: usize,
    /// Pose of the joint frame in the parent body frame at zero motion.
    rotation_joint_in_parent: Matrix3<T>,
    origin_joint_in_parent: Vector3<T>,
    mass: T,
    /// c = PG in the body frame.
    com_in_body: Vector3<T>,
    /// I_G in the body frame.
    inertia_com_in_body: Matrix3<T>,
    /// The textbook's coupled matrix about P, `[[m1, −m ĉ], [m ĉ, I_P]]`, in the body frame.
    spatial_inertia_in_body: Matrix6<T>,
    /// Motion subspace S in the body frame: its first `nv` columns are the joint's.
    motion_subspace_in_body: Matrix6<T>,
    armature: T,
    damping: T,
}

/// One frame of [`Model::frames`], with its placement converted to `T` once.
#[derive(Clone, Copy, Debug)]
struct FrameConstants<T: Scalar> {
    /// The tree body it moves with, `None` for the ground.
    body: Option<usize>,
    /// Rotation frame → body, and the frame's origin r = PF, in that body's frame (in the
    /// world for a frame on the ground).
    rotation_frame_in_body: Matrix3<T>,
    origin_frame_in_body: Vector3<T>,
}

/// Per-body scratch of the algorithms, each quantity in the frame its name says.
#[derive(Clone, Debug)]
struct BodyScratch<T: Scalar> {
    /// Pose of the body frame in the parent body frame at the current q.
    rotation_in_parent: Matrix3<T>,
    origin_in_parent: Vector3<T>,
    /// Motion transform from parent coordinates to body coordinates (Featherstone's X).
    x_from_parent: Matrix6<T>,
    /// ω and the velocity v_P of the origin, in the body frame.
    omega_in_body: Vector3<T>,
    velocity_origin_in_body: Vector3<T>,
    /// α and the classical acceleration a_P of the origin, in the body frame.
    alpha_in_body: Vector3<T>,
    accel_origin_in_body: Vector3<T>,
    /// Wrench the joint transmits from the parent to this body, `[F; M_P]` in the body frame.
    joint_wrench_in_body: Vector6<T>,
    /// Composite (CRBA) or articulated (ABA) inertia about P, in the body frame.
    inertia_6_in_body: Matrix6<T>,
    /// ABA: articulated bias force, velocity-product acceleration c, spatial acceleration.
    bias_force_in_body: Vector6<T>,
    bias_accel_in_body: Vector6<T>,
    spatial_accel_in_body: Vector6<T>,
    /// ABA, one-coordinate joints: U = I^A S, D = Sᵀ U + armature, u = τ − b q̇ − Sᵀ p^A.
    aba_u_vector: Vector6<T>,
    aba_d: T,
    aba_u: T,
}

/// The reference algorithms with their preallocated workspace, for one model.
///
/// Create once per model (and per thread) with [`Reference::new`]; afterwards no method
/// allocates. The methods take `&mut self` only to reuse the scratch.
#[derive(Clone, Debug)]
pub struct Reference<'m, T: Scalar> {
    model: &'m Model,
    gravity_in_world: Vector3<T>,
    bodies: Vec<BodyConstants<T>>,
    frames: Vec<FrameConstants<T>>,
    loads: Vec<loads::LoadConstants<T>>,
    scratch: Vec<BodyScratch<T>>,
    /// Pose of every body frame in the world.
    poses: Vec<Pose<T>>,
    /// Coriolis: world-frame Jacobian column S_k and its rate v_j × S_k, per velocity index.
    jacobian_column_in_world: Vec<Vector6<T>>,
    jacobian_rate_column_in_world: Vec<Vector6<T>>,
    /// Coriolis: the velocity indices supporting one body, and `B_i J_k + I_i J̇_k` for them.
    support: Vec<usize>,
    coriolis_work: Vec<Vector6<T>>,
    /// Frame Jacobians: the joint rates e_k, one column at a time (length nv).
    unit_rates: Vec<T>,
}

impl<'m, T: Scalar> Reference<'m, T> {
    /// The workspace for `model`: converts its constants to `T` and allocates all scratch.
    pub fn new(model: &'m Model) -> Self {
        let t = T::from_f64;
        let vec3 = |v: &Vector3<f64>| v.map(t);
        let mat3 = |m: &Matrix3<f64>| m.map(t);
        let bodies: Vec<BodyConstants<T>> = model
            .bodies()
            .iter()
            .map(|body| {
                let joint = &body.joint;
                let motion = match &joint.kind {
                    JointKind::Revolute { axis_in_joint } => Motion::Revolute {
                        axis: vec3(axis_in_joint),
                    },
                    JointKind::Prismatic { axis_in_joint } => Motion::Prismatic {
                        axis: vec3(axis_in_joint),
                    },
                    JointKind::FreeFlyer => Motion::FreeFlyer,
                };
                let mass = t(body.inertia.mass);
                let com_in_body = vec3(&body.inertia.com_in_body);
                let inertia_com_in_body = mat3(&body.inertia.inertia_com_in_body);
                BodyConstants {
                    parent: body.parent,
                    motion,
                    idx_q: joint.idx_q,
                    idx_v: joint.idx_v,
                    nv: joint.kind.nv(),
                    rotation_joint_in_parent: mat3(&joint.placement_in_parent.rotation),
                    origin_joint_in_parent: vec3(&joint.placement_in_parent.translation),
                    mass,
                    com_in_body,
                    inertia_com_in_body,
                    spatial_inertia_in_body: spatial::spatial_inertia(
                        mass,
                        &com_in_body,
                        &inertia_com_in_body,
                    ),
                    motion_subspace_in_body: spatial::motion_subspace(&motion),
                    armature: t(joint.armature),
                    damping: t(joint.damping),
                }
            })
            .collect();
        let zero6 = Vector6::zeros();
        let scratch = vec![
            BodyScratch {
                rotation_in_parent: Matrix3::identity(),
                origin_in_parent: Vector3::zeros(),
                x_from_parent: Matrix6::identity(),
                omega_in_body: Vector3::zeros(),
                velocity_origin_in_body: Vector3::zeros(),
                alpha_in_body: Vector3::zeros(),
                accel_origin_in_body: Vector3::zeros(),
                joint_wrench_in_body: zero6,
                inertia_6_in_body: Matrix6::zeros(),
                bias_force_in_body: zero6,
                bias_accel_in_body: zero6,
                spatial_accel_in_body: zero6,
                aba_u_vector: zero6,
                aba_d: T::zero(),
                aba_u: T::zero(),
            };
            bodies.len()
        ];
        let frames = model
            .frames()
            .iter()
            .map(|frame| FrameConstants {
                body: frame.body,
                rotation_frame_in_body: mat3(&frame.placement_in_body.rotation),
                origin_frame_in_body: vec3(&frame.placement_in_body.translation),
            })
            .collect();
        let loads = model
            .loads()
            .iter()
            .map(|load| loads::LoadConstants {
                body: load.body,
                kind: load.kind,
                frame: load.frame,
                rotation_declared_in_body: mat3(&load.placement_in_body.rotation),
                point_in_body: vec3(&load.placement_in_body.translation),
                input_offset: load.input_offset,
            })
            .collect();
        let nv = model.nv();
        Reference {
            model,
            gravity_in_world: vec3(&model.gravity_in_world()),
            poses: vec![Pose::identity(); bodies.len()],
            bodies,
            frames,
            loads,
            scratch,
            jacobian_column_in_world: vec![zero6; nv],
            jacobian_rate_column_in_world: vec![zero6; nv],
            support: Vec::with_capacity(nv),
            coriolis_work: vec![zero6; nv],
            unit_rates: vec![T::zero(); nv],
        }
    }

    /// The model this workspace was made for.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    fn check_q(&self, q: &[T]) -> Result<(), SizeError> {
        SizeError::check("q", self.model.nq(), q.len())
    }

    fn check_v(&self, what: &'static str, v: &[T]) -> Result<(), SizeError> {
        SizeError::check(what, self.model.nv(), v.len())
    }

    fn check_wrenches(
        &self,
        what: &'static str,
        wrenches: Option<&[Wrench<T>]>,
    ) -> Result<(), SizeError> {
        match wrenches {
            Some(w) => SizeError::check(what, self.bodies.len(), w.len()),
            None => Ok(()),
        }
    }

    /// Checks that an output matrix is nv × nv; `rows` and `cols` name its dimensions.
    fn check_square(
        &self,
        rows: &'static str,
        cols: &'static str,
        m: &nalgebra::DMatrix<T>,
    ) -> Result<(), SizeError> {
        SizeError::check(rows, self.model.nv(), m.nrows())?;
        SizeError::check(cols, self.model.nv(), m.ncols())
    }
}

#[cfg(test)]
mod tests {
    use super::spatial::{
        force_cross, force_cross_matrix, motion_cross, motion_cross_matrix, motion_transform,
        solve_spd6, spatial_inertia,
    };
    use super::*;
    use crate::model::{BodySpec, Inertia, JointSpec, LoadFrame, LoadSpec, LoadType, ModelBuilder};
    use nalgebra::DMatrix;

    /// A free-flyer base carrying a revolute and a prismatic joint.
    fn small_tree() -> Model {
        let body = |name: &str| {
            BodySpec::new(
                name,
                Inertia::new(
                    1.2,
                    [0.1, 0.05, -0.02],
                    [[0.03, 0.002, 0.0], [0.002, 0.02, 0.001], [0.0, 0.001, 0.04]],
                ),
            )
        };
        ModelBuilder::new()
            .gravity([0.0, 0.0, -9.81])
            .body(body("base"))
            .body(body("arm"))
            .body(body("slider"))
            .joint(JointSpec::free_flyer("float", "base"))
            .joint(
                JointSpec::revolute("hinge", "base", "arm", [0.0, 1.0, 0.0])
                    .at([0.2, 0.0, 0.1])
                    .with_armature(0.1),
            )
            .joint(
                JointSpec::prismatic("slide", "arm", "slider", [1.0, 0.0, 0.0])
                    .at([0.3, 0.0, 0.0])
                    .with_damping(0.5),
            )
            .build()
            .expect("valid model")
    }

    fn state() -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let q = vec![
            0.1,
            -0.2,
            0.3,
            0.2,
            -0.1,
            0.3,
            0.9273618495495703,
            0.7,
            -0.2,
        ];
        let v = vec![0.5, -1.0, 0.2, 1.5, -0.3, 0.8, 2.0, -1.0];
        let a = vec![1.0, 0.3, -0.5, 0.2, 0.9, -1.1, 0.4, 2.0];
        (q, v, a)
    }

    #[test]
    fn every_method_reports_wrong_lengths() {
        let model = small_tree();
        let mut r = Reference::<f64>::new(&model);
        let (q, v, a) = state();
        let (short_q, short_v) = (&q[1..], &v[1..]);
        let mut out = vec![0.0; 8];
        let mut short_out = vec![0.0; 7];
        let mut m = DMatrix::zeros(8, 8);
        let mut m_bad = DMatrix::zeros(8, 7);
        let w = vec![Wrench::zero(); 3];
        let mut w_out = vec![Wrench::zero(); 3];
        let mut w_short = vec![Wrench::zero(); 2];
        let err = |what, expected, got| SizeError {
            what,
            expected,
            got,
        };
        let id = |r: &mut Reference<f64>, q: &[f64], v: &[f64], a: &[f64], f, o: &mut [f64]| {
            r.inverse_dynamics(q, v, a, f, o)
        };
        assert_eq!(
            id(&mut r, short_q, &v, &a, None, &mut out),
            Err(err("q", 9, 8))
        );
        assert_eq!(
            id(&mut r, &q, short_v, &a, None, &mut out),
            Err(err("v", 8, 7))
        );
        assert_eq!(
            id(&mut r, &q, &v, short_v, None, &mut out),
            Err(err("a", 8, 7))
        );
        assert_eq!(
            id(&mut r, &q, &v, &a, Some(&w[1..]), &mut out),
            Err(err("external wrenches", 3, 2))
        );
        assert_eq!(
            id(&mut r, &q, &v, &a, None, &mut short_out),
            Err(err("tau", 8, 7))
        );
        assert!(r.gravity(short_q, &mut out).is_err());
        assert!(r.gravity(&q, &mut short_out).is_err());
        assert!(r.bias(&q, short_v, &mut out).is_err());
        assert!(r.bias(&q, &v, &mut short_out).is_err());
        assert!(r.nonlinear_effects(short_q, &v, &mut out).is_err());
        assert!(r.nonlinear_effects(&q, &v, &mut short_out).is_err());
        assert_eq!(
            r.coriolis_matrix(&q, &v, &mut m_bad),
            Err(err("coriolis matrix columns", 8, 7))
        );
        assert!(r.coriolis_matrix(&q, short_v, &mut m).is_err());
        assert_eq!(
            r.mass_matrix(&q, &mut m_bad),
            Err(err("mass matrix columns", 8, 7))
        );
        assert!(r.mass_matrix(short_q, &mut m).is_err());
        assert!(r.forward_dynamics(&q, &v, short_v, None, &mut out).is_err());
        assert!(r
            .forward_dynamics(&q, &v, &a, Some(&w[1..]), &mut out)
            .is_err());
        assert!(r
            .forward_dynamics(&q, &v, &a, None, &mut short_out)
            .is_err());
        assert!(r.kinetic_energy(&q, short_v).is_err());
        assert!(r.potential_energy(short_q).is_err());
        assert!(r.joint_reactions(&q, &v, &a, None, &mut w_short).is_err());
        assert!(r
            .joint_reactions(&q, &v, short_v, Some(&w), &mut w_out)
            .is_err());
        assert!(r.body_poses(short_q).is_err());
        // And the right lengths work.
        assert!(r.joint_reactions(&q, &v, &a, Some(&w), &mut w_out).is_ok());
    }

    /// [`small_tree`] with a tool welded to the arm (turned and offset) and three loads: a
    /// force on the tool in its own axes, a wrench on the slider in world axes, a couple on
    /// the base in world axes.
    fn loaded_tree() -> Model {
        let inertia = Inertia::new(
            1.2,
            [0.1, 0.05, -0.02],
            [[0.03, 0.002, 0.0], [0.002, 0.02, 0.001], [0.0, 0.001, 0.04]],
        );
        let turned = *nalgebra::Rotation3::from_euler_angles(0.3, -0.4, 0.9).matrix();
        let rows = |m: Matrix3<f64>| std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]));
        ModelBuilder::new()
            .gravity([0.0, 0.0, -9.81])
            .body(BodySpec::new("base", inertia.clone()))
            .body(BodySpec::new("arm", inertia.clone()))
            .body(BodySpec::new("slider", inertia.clone()))
            .body(BodySpec::new("tool", inertia))
            .joint(JointSpec::free_flyer("float", "base"))
            .joint(JointSpec::revolute("hinge", "base", "arm", [0.0, 1.0, 0.0]).at([0.2, 0.0, 0.1]))
            .joint(
                JointSpec::prismatic("slide", "arm", "slider", [1.0, 0.0, 0.0]).at([0.3, 0.0, 0.0]),
            )
            .joint(JointSpec::fixed("weld", "arm", "tool").placed([0.1, 0.2, 0.0], rows(turned)))
            .load(LoadSpec::force("push", "tool").at([0.05, -0.1, 0.2]))
            .load(
                LoadSpec::wrench("wind", "slider")
                    .at([0.0, 0.1, 0.0])
                    .in_world(),
            )
            .load(LoadSpec::couple("spin", "base").in_world())
            .build()
            .expect("valid model")
    }

    /// The loads' generalized force Q = Σ J_Pᵀ F + J_ωᵀ M is exactly what the same loads,
    /// turned by hand into each body's axes and moved to its origin, subtract from τ in
    /// the Newton–Euler sweep: two ways that share nothing but the body poses.
    #[test]
    fn loads_do_the_work_of_the_equivalent_wrenches() {
        let model = loaded_tree();
        assert_eq!(model.num_load_inputs(), 12);
        let offsets: Vec<usize> = model.loads().iter().map(|l| l.input_offset).collect();
        assert_eq!(offsets, [0, 3, 9]);
        let mut r = Reference::<f64>::new(&model);
        let (q, v, a) = state();
        let loads: Vec<f64> = (0..12).map(|k| (1.7 * k as f64).sin() * 3.0).collect();
        let mut q_loads = vec![0.0; 8];
        r.generalized_load_forces(&q, &loads, &mut q_loads)
            .expect("sizes match");
        // The same loads as wrenches [F; M_P] in each tree body's frame.
        let poses = r.body_poses(&q).expect("sizes match").to_vec();
        let mut wrenches = vec![Wrench::zero(); model.bodies().len()];
        let three = |k: usize| Vector3::new(loads[k], loads[k + 1], loads[k + 2]);
        for load in model.loads() {
            let b = load.body.expect("moving body");
            let to_body = |given: Vector3<f64>| match load.frame {
                LoadFrame::Body => load.placement_in_body.rotation * given,
                LoadFrame::World => poses[b].rotation_in_world.transpose() * given,
            };
            let o = load.input_offset;
            let (force, couple) = match load.kind {
                LoadType::Force => (to_body(three(o)), Vector3::zeros()),
                LoadType::Couple => (Vector3::zeros(), to_body(three(o))),
                LoadType::Wrench => (to_body(three(o)), to_body(three(o + 3))),
            };
            wrenches[b].force += force;
            wrenches[b].moment += load.placement_in_body.translation.cross(&force) + couple;
        }
        let (mut with, mut without) = (vec![0.0; 8], vec![0.0; 8]);
        r.inverse_dynamics(&q, &v, &a, Some(&wrenches), &mut with)
            .expect("sizes match");
        r.inverse_dynamics(&q, &v, &a, None, &mut without)
            .expect("sizes match");
        for k in 0..8 {
            let expected = without[k] - q_loads[k];
            assert!(
                (with[k] - expected).abs() < 1e-12 * (1.0 + expected.abs()),
                "τ[{k}]: {} with the wrenches, {expected} by virtual power",
                with[k]
            );
        }
        // Wrong lengths are errors, not panics.
        assert!(r
            .generalized_load_forces(&q, &loads[1..], &mut q_loads)
            .is_err());
        assert!(r
            .generalized_load_forces(&q[1..], &loads, &mut q_loads)
            .is_err());
        assert!(r
            .generalized_load_forces(&q, &loads, &mut q_loads[1..])
            .is_err());
    }

    #[test]
    fn single_precision_follows_double() {
        let model = small_tree();
        let (q, v, a) = state();
        let to32 = |x: &[f64]| x.iter().map(|&y| y as f32).collect::<Vec<f32>>();
        let mut r64 = Reference::<f64>::new(&model);
        let mut r32 = Reference::<f32>::new(&model);
        let mut tau64 = vec![0.0; 8];
        let mut tau32 = vec![0.0f32; 8];
        r64.inverse_dynamics(&q, &v, &a, None, &mut tau64)
            .expect("sizes match");
        r32.inverse_dynamics(&to32(&q), &to32(&v), &to32(&a), None, &mut tau32)
            .expect("sizes match");
        let mut qdd32 = vec![0.0f32; 8];
        r32.forward_dynamics(&to32(&q), &to32(&v), &tau32, None, &mut qdd32)
            .expect("sizes match");
        for k in 0..8 {
            assert!((tau64[k] - f64::from(tau32[k])).abs() < 1e-4 * (1.0 + tau64[k].abs()));
            assert!((a[k] - f64::from(qdd32[k])).abs() < 1e-3 * (1.0 + a[k].abs()));
        }
    }

    #[test]
    fn spatial_algebra_identities() {
        let v: Vector6<f64> = Vector6::new(0.3, -1.2, 0.5, 0.7, 0.1, -0.4);
        let m: Vector6<f64> = Vector6::new(-0.2, 0.4, 1.1, -0.6, 0.9, 0.2);
        let f: Vector6<f64> = Vector6::new(1.5, 0.2, -0.7, 0.3, -0.8, 0.6);
        // v ×* = −(v ×)ᵀ, so (v × m) · f = −m · (v ×* f).
        assert!((motion_cross(&v, &m).dot(&f) + m.dot(&force_cross(&v, &f))).abs() < 1e-15);
        assert!((force_cross_matrix(&v) + motion_cross_matrix(&v).transpose()).amax() < 1e-15);
        assert!((motion_cross_matrix(&v) * m - motion_cross(&v, &m)).amax() < 1e-15);
        // The textbook's coupled matrix is symmetric, and its motion transform preserves power:
        // (X m) · (X⁻ᵀ f) = m · f with X⁻ᵀ = the force transform child → parent inverted.
        let inertia = spatial_inertia(
            2.0,
            &Vector3::new(0.1, -0.2, 0.3),
            &Matrix3::new(0.1, 0.01, 0.0, 0.01, 0.2, 0.02, 0.0, 0.02, 0.15),
        );
        assert_eq!(inertia, inertia.transpose());
        let rotation = *nalgebra::Rotation3::from_euler_angles(0.3, -0.5, 1.1).matrix();
        let x = motion_transform(&rotation, &Vector3::new(0.4, -0.1, 0.2));
        let x_inv = x.try_inverse().expect("X is invertible");
        assert!(((x * m).dot(&(x_inv.transpose() * f)) - m.dot(&f)).abs() < 1e-14);
        // LDLᵀ solve of a symmetric positive-definite system.
        let b = Vector6::new(1.0, 2.0, 3.0, -1.0, 0.5, 0.25);
        assert!((inertia * solve_spd6(&inertia, &b) - b).amax() < 1e-12);
    }
}
