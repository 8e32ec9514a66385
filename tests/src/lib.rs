//! Shared helpers of the integration tests: the Pinocchio anchor files, random mechanisms
//! and states for the property tests, and comparisons.

use dynamics_runtime::{
    BodySpec, DoubleDouble, Inertia, JointKind, JointSpec, Model, ModelBuilder, Pose, GROUND,
};
use nalgebra::{DMatrix, Matrix3, Rotation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use serde::Deserialize;

mod default_functions;
pub mod dual_derivatives;
pub mod into_twins;
mod split_mix;

pub use default_functions::DEFAULT_FUNCTIONS;

/// The 20 samples of Pinocchio's values in `tests/data/pinocchio_ext/<name>_<kind>.json`
/// (`kind`: `kinematics`, `frames`, `derivatives`), each read as an `S`. Panics with the
/// path on a missing or malformed file (a test's data, not user input).
pub fn pinocchio_ext_samples<S: serde::de::DeserializeOwned>(name: &str, kind: &str) -> Vec<S> {
    #[derive(Deserialize)]
    struct File<S> {
        samples: Vec<S>,
    }
    let path = format!(
        "{}/data/pinocchio_ext/{name}_{kind}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let file: File<S> = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
    assert_eq!(file.samples.len(), 20, "{path}");
    file.samples
}

/// Waits until the test harness's main thread has surely blocked, before a test counts
/// every allocation of the process (a global counting allocator). After spawning the test's
/// thread, libtest's main thread blocks on a channel, and a thread's first blocking wait on
/// std's channels allocates (its waiter context and queue entry, kept for the thread's
/// life): the likely source of the 4 allocations (900 bytes, none freed) a counted region
/// saw once in a loaded run of the whole workspace, and never when the test ran alone.
pub fn let_the_harness_settle() {
    std::thread::sleep(std::time::Duration::from_millis(200));
}

/// `1 + max |x|` over the values: the scale of the anchors' tolerance
/// `1e-11 · (1 + max |value|)`.
pub fn tolerance_scale<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    1.0 + values.into_iter().fold(0.0_f64, |m, x| m.max(x.abs()))
}

/// `max |a_k − b_k|` (infinite if the lengths differ).
pub fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Asserts `max |got − expected| ≤ tolerance · (1 + max |expected|)` (and equal lengths),
/// naming the quantity and showing both sides when it fails.
#[track_caller]
pub fn assert_close(what: &str, got: &[f64], expected: &[f64], tolerance: f64) {
    let error = max_abs_diff(got, expected);
    let allowed = tolerance * tolerance_scale(expected);
    assert!(
        error <= allowed,
        "{what}: error {error:e} > allowed {allowed:e} = {tolerance:e} · (1 + max |expected|)\n  \
         got      {got:?}\n  expected {expected:?}"
    );
}

/// Asserts that generated placements (each body's (rotation rows, origin) in the world,
/// `joint_placements`) are the reference's body poses, entry for entry within 1e-13.
#[track_caller]
pub fn assert_placements_are_the_poses(
    placements: &[([[f64; 3]; 3], [f64; 3])],
    poses: &[Pose<f64>],
) {
    assert_eq!(placements.len(), poses.len());
    for (b, ((rotation, origin), pose)) in placements.iter().zip(poses).enumerate() {
        for r in 0..3 {
            let e = pose.origin_in_world[r];
            assert!(
                (origin[r] - e).abs() <= 1e-13,
                "body {b} p[{r}] {}, {e}",
                origin[r]
            );
            for c in 0..3 {
                let (x, e) = (rotation[r][c], pose.rotation_in_world[(r, c)]);
                assert!((x - e).abs() <= 1e-13, "body {b} R[{r}][{c}] {x}, {e}");
            }
        }
    }
}

/// The 2-norm condition number `λ_max / λ_min` of a symmetric positive-definite matrix
/// (a mass matrix).
pub fn condition_number(m: &DMatrix<f64>) -> f64 {
    let eigen = m.clone().symmetric_eigenvalues();
    eigen.max() / eigen.min()
}

/// `max |got_k − exact_k|`, the differences taken in double-double (infinite if the lengths
/// differ).
pub fn max_abs_diff_dd(got: &[f64], exact: &[DoubleDouble]) -> f64 {
    if got.len() != exact.len() {
        return f64::INFINITY;
    }
    got.iter().zip(exact).fold(0.0_f64, |m, (g, e)| {
        m.max((DoubleDouble::new(*g) - *e).abs().to_f64())
    })
}

/// `max |x|` of double-double values, rounded to f64.
pub fn max_abs_dd(values: &[DoubleDouble]) -> f64 {
    values.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs()))
}

/// States of the free-floating test trees of `generated_kinematics`, `generated_frames` and
/// `generated_derivatives`: a free base (q: position, unit quaternion) and three joints of
/// one coordinate each (nq = 10, nv = 9).
pub mod free_tree {
    use dynamics_runtime::integrate_configuration;

    /// Configuration number `k`: position, a unit quaternion, three joint values.
    pub fn configuration(k: usize) -> [f64; 10] {
        let s = k as f64;
        let quaternion = [0.1 + 0.05 * s, -0.2, 0.3, 0.9 - 0.1 * s];
        let norm = quaternion.iter().map(|x| x * x).sum::<f64>().sqrt();
        [
            0.3 - 0.1 * s,
            0.2 * s,
            1.0,
            quaternion[0] / norm,
            quaternion[1] / norm,
            quaternion[2] / norm,
            quaternion[3] / norm,
            (0.7 + s).sin(),
            (0.3 * s).cos(),
            0.05 * s,
        ]
    }

    /// Velocity number `k` ([v; ω] of the base in its frame, then the joint rates).
    pub fn velocity(k: usize) -> [f64; 9] {
        let s = k as f64;
        [
            0.3,
            -0.2 + 0.1 * s,
            0.1,
            0.5 - 0.2 * s,
            0.4,
            -0.3,
            1.1,
            -0.7 + 0.3 * s,
            0.2,
        ]
    }

    /// Acceleration number `k`.
    pub fn acceleration(k: usize) -> [f64; 9] {
        let s = k as f64;
        [0.1, 0.4, -0.3, 0.2 * s, -0.5, 0.6, -1.0, 0.8, 0.3 - 0.1 * s]
    }

    /// e_col, the unit velocity of one coordinate.
    pub fn unit(col: usize) -> [f64; 9] {
        let mut v = [0.0; 9];
        v[col] = 1.0;
        v
    }

    /// q ⊕ t v: the free base moves on its manifold.
    pub fn moved(q: &[f64; 10], v: &[f64; 9], t: f64) -> [f64; 10] {
        let mut out = [0.0; 10];
        integrate_configuration(q, v, t, &[(0, 0)], &mut out);
        out
    }
}

/// The Pinocchio anchor files: models and sampled results (see
/// `tests/data/pinocchio/*.json` and their `conventions` field).
pub mod anchors {
    use super::*;

    /// One anchor file.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorFile {
        /// Model name (`pendulum`, `ur5`, ...).
        pub name: String,
        /// The mechanism, in Pinocchio's order and conventions.
        pub model: AnchorModel,
        /// Random states and Pinocchio's results at them.
        pub samples: Vec<AnchorSample>,
    }

    /// The mechanism of an anchor file.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorModel {
        /// Configuration size.
        pub nq: usize,
        /// Velocity size.
        pub nv: usize,
        /// Gravity in the world frame.
        pub gravity: [f64; 3],
        /// Joints in tree order.
        pub joints: Vec<AnchorJoint>,
        /// Bodies, one per joint.
        pub bodies: Vec<AnchorBody>,
    }

    /// A joint of an anchor model.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorJoint {
        /// Joint name.
        pub name: String,
        /// Index of the parent joint, −1 for the world.
        pub parent: i64,
        /// `revolute`, `prismatic` or `free_flyer`.
        #[serde(rename = "type")]
        pub kind: String,
        /// Unit axis in the joint frame (absent for a free flyer).
        #[serde(default)]
        pub axis: [f64; 3],
        /// Pose of the joint frame in the parent joint frame at zero motion.
        pub placement: AnchorPlacement,
        /// First index in q.
        pub idx_q: usize,
        /// First index in v.
        pub idx_v: usize,
    }

    /// `x_parent = rotation · x_joint + translation`.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorPlacement {
        /// Translation.
        pub translation: [f64; 3],
        /// Rotation, by rows.
        pub rotation: [[f64; 3]; 3],
    }

    /// The body a joint moves.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorBody {
        /// The joint moving it.
        pub joint: usize,
        /// Mass.
        pub mass: f64,
        /// Mass centre in the body frame.
        pub com: [f64; 3],
        /// Inertia about the mass centre, in the body frame.
        pub inertia_com: [[f64; 3]; 3],
    }

    /// One sampled state and Pinocchio's results there.
    #[derive(Clone, Debug, Deserialize)]
    pub struct AnchorSample {
        /// Configuration.
        pub q: Vec<f64>,
        /// Velocity.
        pub v: Vec<f64>,
        /// Acceleration.
        pub a: Vec<f64>,
        /// A random torque (input of `aba`).
        pub tau: Vec<f64>,
        /// `M a + C v + g`.
        pub rnea: Vec<f64>,
        /// M(q), symmetric.
        pub crba: Vec<Vec<f64>>,
        /// `C v + g`.
        pub nle: Vec<f64>,
        /// g(q).
        pub gravity_torque: Vec<f64>,
        /// `M⁻¹ (tau − nle)`.
        pub aba: Vec<f64>,
        /// Pinocchio's Christoffel-consistent C(q, v).
        pub coriolis: Vec<Vec<f64>>,
        /// `½ vᵀ M v`.
        pub kinetic_energy: f64,
        /// `−Σ m_i g · c_i`.
        pub potential_energy: f64,
    }

    /// Path of an anchor file in this crate.
    pub fn path(name: &str) -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("data/pinocchio")
            .join(format!("{name}.json"))
    }

    /// Reads and parses an anchor file.
    pub fn load(name: &str) -> Result<AnchorFile, String> {
        let text = std::fs::read_to_string(path(name)).map_err(|e| format!("{name}: {e}"))?;
        serde_json::from_str(&text).map_err(|e| format!("{name}: {e}"))
    }

    /// Name given to the body moved by joint `index`.
    pub fn body_name(index: usize) -> String {
        format!("body{index}")
    }

    impl AnchorModel {
        /// The declaration of this mechanism for [`ModelBuilder`]: body k is the one joint
        /// k moves, named [`body_name`]`(k)`.
        pub fn builder(&self) -> ModelBuilder {
            let mut builder = ModelBuilder::new().gravity(self.gravity);
            for body in &self.bodies {
                builder = builder.body(BodySpec::new(
                    body_name(body.joint),
                    Inertia::new(body.mass, body.com, body.inertia_com),
                ));
            }
            for (k, joint) in self.joints.iter().enumerate() {
                let parent = match usize::try_from(joint.parent) {
                    Ok(p) => body_name(p),
                    Err(_) => GROUND.to_owned(),
                };
                let child = body_name(k);
                let spec = match joint.kind.as_str() {
                    "prismatic" => JointSpec::prismatic(&joint.name, &parent, &child, joint.axis),
                    "free_flyer" => JointSpec::free_flyer(&joint.name, &child),
                    _ => JointSpec::revolute(&joint.name, &parent, &child, joint.axis),
                };
                builder = builder
                    .joint(spec.placed(joint.placement.translation, joint.placement.rotation));
            }
            builder
        }
    }

    /// Row-major flattening of a matrix given by rows.
    pub fn flatten(rows: &[Vec<f64>]) -> Vec<f64> {
        rows.iter().flatten().copied().collect()
    }
}

/// Random mechanisms and states for the property tests.
pub mod random {
    use super::*;

    pub use crate::split_mix::SplitMix;

    /// One random joint and the body it moves.
    #[derive(Clone, Debug)]
    pub struct RandomJoint {
        /// In [0, 1): picks the parent among the bodies before this one (and the ground).
        pub parent_choice: f64,
        /// Prismatic instead of revolute.
        pub prismatic: bool,
        /// Axis direction (normalized by the builder; replaced by z if nearly zero).
        pub axis: [f64; 3],
        /// Joint placement: translation and rotation vector (axis · angle).
        pub translation: [f64; 3],
        /// Rotation vector of the placement.
        pub rotation: [f64; 3],
        /// Body mass.
        pub mass: f64,
        /// ∫x² dm, ∫y² dm, ∫z² dm in principal axes (so the triangle inequality holds).
        pub second_moments: [f64; 3],
        /// Rotation vector of the principal axes in the body frame.
        pub principal_axes: [f64; 3],
        /// Mass centre in the body frame.
        pub com: [f64; 3],
        /// Armature and damping, used when the tree asks for joint friction.
        pub armature: f64,
        /// Viscous damping coefficient.
        pub damping: f64,
    }

    /// A random tree of bodies.
    #[derive(Clone, Debug)]
    pub struct RandomTree {
        /// The joints, in order; body k is moved by joint k.
        pub joints: Vec<RandomJoint>,
        /// Body 0 is a free flyer and every other body hangs below it.
        pub free_flyer_root: bool,
        /// Armature and damping are nonzero.
        pub joint_friction: bool,
        /// Gravity in the world frame.
        pub gravity: [f64; 3],
    }

    fn rotation(v: &[f64; 3]) -> Matrix3<f64> {
        *Rotation3::from_scaled_axis(Vector3::from(*v)).matrix()
    }

    fn rows(m: &Matrix3<f64>) -> [[f64; 3]; 3] {
        [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ]
    }

    impl RandomJoint {
        /// I_G in the body frame: principal moments `(d2 + d3, d1 + d3, d1 + d2)` rotated by
        /// the principal axes.
        pub fn inertia_com(&self) -> [[f64; 3]; 3] {
            let [d1, d2, d3] = self.second_moments;
            let principal = Matrix3::from_diagonal(&Vector3::new(d2 + d3, d1 + d3, d1 + d2));
            let axes = rotation(&self.principal_axes);
            let i_g = axes * principal * axes.transpose();
            rows(&((i_g + i_g.transpose()) * 0.5))
        }
    }

    impl RandomTree {
        /// The declaration; `damping` false drops the damping even with joint friction.
        pub fn builder(&self, damping: bool) -> ModelBuilder {
            let mut builder = ModelBuilder::new().gravity(self.gravity);
            for (k, joint) in self.joints.iter().enumerate() {
                let name = format!("b{k}");
                builder = builder.body(BodySpec::new(
                    &name,
                    Inertia::new(joint.mass, joint.com, joint.inertia_com()),
                ));
                let parent = if self.free_flyer_root {
                    // k ≥ 1: one of the bodies 0..k.
                    let p = (joint.parent_choice * k as f64) as usize;
                    format!("b{}", p.min(k.saturating_sub(1)))
                } else {
                    // One of the ground and the bodies 0..k.
                    match (joint.parent_choice * (k + 1) as f64) as usize {
                        0 => GROUND.to_owned(),
                        p => format!("b{}", p.min(k) - 1),
                    }
                };
                let norm = joint.axis.iter().map(|a| a * a).sum::<f64>().sqrt();
                let axis = if norm < 0.1 {
                    [0.0, 0.0, 1.0]
                } else {
                    joint.axis
                };
                let jname = format!("j{k}");
                let spec = if k == 0 && self.free_flyer_root {
                    JointSpec::free_flyer(&jname, &name)
                } else if joint.prismatic {
                    JointSpec::prismatic(&jname, &parent, &name, axis)
                } else {
                    JointSpec::revolute(&jname, &parent, &name, axis)
                };
                let mut spec = spec.placed(joint.translation, rows(&rotation(&joint.rotation)));
                if self.joint_friction {
                    spec = spec.with_armature(joint.armature);
                    if damping {
                        spec = spec.with_damping(joint.damping);
                    }
                }
                builder = builder.joint(spec);
            }
            builder
        }

        /// The validated model (damping included if the tree has joint friction).
        pub fn model(&self) -> Model {
            self.model_with_damping(true)
        }

        /// The validated model, with or without damping.
        pub fn model_with_damping(&self, damping: bool) -> Model {
            match self.builder(damping).build() {
                Ok(model) => model,
                Err(e) => panic!("a random tree must be valid: {e}"),
            }
        }
    }

    fn unit_interval_array() -> impl Strategy<Value = [f64; 3]> {
        prop::array::uniform3(-1.0..1.0f64)
    }

    prop_compose! {
        /// A random joint and body.
        pub fn random_joint()(
            parent_choice in 0.0..1.0f64,
            prismatic in prop::bool::weighted(0.25),
            axis in unit_interval_array(),
            translation in prop::array::uniform3(-0.5..0.5f64),
            rotation in prop::array::uniform3(-3.0..3.0f64),
            mass in 0.1..5.0f64,
            second_moments in prop::array::uniform3(0.0005..0.05f64),
            principal_axes in prop::array::uniform3(-3.0..3.0f64),
            com in prop::array::uniform3(-0.3..0.3f64),
            armature in 0.0..0.2f64,
            damping in 0.0..0.5f64,
        ) -> RandomJoint {
            RandomJoint {
                parent_choice, prismatic, axis, translation, rotation, mass, second_moments,
                principal_axes, com, armature, damping,
            }
        }
    }

    prop_compose! {
        /// A random tree of 1 to `max_joints` joints; sometimes a free-flyer root, sometimes
        /// armature and damping.
        pub fn random_tree(max_joints: usize)(
            joints in prop::collection::vec(random_joint(), 1..=max_joints),
            free_flyer_root in prop::bool::weighted(0.3),
            joint_friction in prop::bool::weighted(0.5),
            gravity in prop::array::uniform3(-10.0..10.0f64),
        ) -> RandomTree {
            RandomTree { joints, free_flyer_root, joint_friction, gravity }
        }
    }

    /// A random state: q (angles in ±π, prismatic ±0.5 m, unit quaternions), v in ±2,
    /// a in ±3.
    pub fn random_state(model: &Model, rng: &mut SplitMix) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let mut q = vec![0.0; model.nq()];
        for body in model.bodies() {
            let j = body.joint.idx_q;
            match body.joint.kind {
                JointKind::Revolute { .. } => {
                    q[j] = rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
                }
                JointKind::Prismatic { .. } => q[j] = rng.uniform(-0.5, 0.5),
                JointKind::FreeFlyer => {
                    for k in 0..3 {
                        q[j + k] = rng.uniform(-1.0, 1.0);
                    }
                    let rotation = Vector3::new(
                        rng.uniform(-3.0, 3.0),
                        rng.uniform(-3.0, 3.0),
                        rng.uniform(-3.0, 3.0),
                    );
                    let quat = UnitQuaternion::from_scaled_axis(rotation);
                    q[j + 3..j + 7].copy_from_slice(quat.coords.as_slice());
                }
            }
        }
        let v = (0..model.nv()).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let a = (0..model.nv()).map(|_| rng.uniform(-3.0, 3.0)).collect();
        (q, v, a)
    }

    /// The configuration reached from q by moving with velocity v for time `dt` along a
    /// curve whose tangent at `dt = 0` is v: joint coordinates `q + v dt`; a free flyer's
    /// position `p + R v_lin dt` and orientation `quat ⊗ exp(ω dt / 2)` (body-frame ω).
    pub fn integrate(model: &Model, q: &[f64], v: &[f64], dt: f64) -> Vec<f64> {
        let mut out = q.to_vec();
        for body in model.bodies() {
            let (iq, iv) = (body.joint.idx_q, body.joint.idx_v);
            match body.joint.kind {
                JointKind::FreeFlyer => {
                    let quat = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                        q[iq + 6],
                        q[iq + 3],
                        q[iq + 4],
                        q[iq + 5],
                    ));
                    let v_lin = Vector3::new(v[iv], v[iv + 1], v[iv + 2]);
                    let omega = Vector3::new(v[iv + 3], v[iv + 4], v[iv + 5]);
                    let position = Vector3::new(q[iq], q[iq + 1], q[iq + 2]) + quat * v_lin * dt;
                    let moved = quat * UnitQuaternion::from_scaled_axis(omega * dt);
                    out[iq..iq + 3].copy_from_slice(position.as_slice());
                    out[iq + 3..iq + 7].copy_from_slice(moved.coords.as_slice());
                }
                _ => out[iq] = q[iq] + v[iv] * dt,
            }
        }
        out
    }
}
