//! The anchor models declared with `mechanism!` are the Pinocchio models: for every model of
//! `models::anchors` (the language) and of `models::urdf_anchors` (the URDF twins),
//! `<M as Mechanism>::model()` has the same nq, nv and gravity as `tests/data/pinocchio/<name>.json`
//! and, joint by joint, the same parent, axis and placement, and body by body the same mass,
//! mass centre and I_G (the file's conventions are the runtime's: the `conventions` block of
//! each file states them). The `Mechanism` constants agree with the file too. The textbook's mechanisms (`models::seed`) build with the numbers their docs state.
//!
//! Tolerance: 1e-12 absolute for both front ends. The language models carry the file's
//! numbers as literals. The URDF twins carry roll-pitch-yaw angles and recompute R from them
//! (UR5: `rpy="0.0 1.57079632679 0.0"`, so R has entries cos(1.57079632679) = 4.8966e-12),
//! but Pinocchio computed the file's R from the same strings with the same formula, so the
//! round trip costs nothing measurable: the largest deviation of any twin is ~6e-17 (Panda's
//! placements; see the printed deviations with `--nocapture`). Bodies merged through fixed
//! joints (Panda's hand and fingers) agree to ~1e-17.

use dynamics_runtime::{JointKind, Mechanism, Model};
use dynamics_tests::anchors::{self, AnchorFile};
use models::{anchors as lang, seed, urdf_anchors as urdf};
use nalgebra::{Matrix3, Vector3};

/// Absolute tolerance of every comparison (see the module docs).
const TOLERANCE: f64 = 1e-12;

/// Largest deviation found in each group of quantities of one model.
#[derive(Default, Debug)]
struct Deviation {
    placement: f64,
    axis: f64,
    inertia: f64,
    gravity: f64,
}

impl Deviation {
    fn max(&self) -> f64 {
        self.placement
            .max(self.axis)
            .max(self.inertia)
            .max(self.gravity)
    }
}

fn vec3(v: [f64; 3]) -> Vector3<f64> {
    Vector3::from(v)
}

fn mat3(rows: [[f64; 3]; 3]) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| rows[i][j])
}

/// Checks one deviation against the tolerance, naming the quantity; returns the deviation.
fn within(what: String, deviation: f64, tolerance: f64) -> f64 {
    assert!(
        deviation <= tolerance,
        "{what}: deviation {deviation:e} > {tolerance:e}"
    );
    deviation
}

/// `model` is the model of `file`, every number within `tolerance`; returns the largest
/// deviations.
fn compare(name: &str, model: &Model, file: &AnchorFile, tolerance: f64) -> Deviation {
    let expected = &file.model;
    let mut worst = Deviation::default();
    assert_eq!(model.nq(), expected.nq, "{name}: nq");
    assert_eq!(model.nv(), expected.nv, "{name}: nv");
    worst.gravity = within(
        format!("{name}: gravity"),
        (model.gravity_in_world() - vec3(expected.gravity)).amax(),
        tolerance,
    );
    assert_eq!(
        model.bodies().len(),
        expected.joints.len(),
        "{name}: one body per joint"
    );
    for (k, (body, joint)) in model.bodies().iter().zip(&expected.joints).enumerate() {
        let at = format!("{name}: joint {k} `{}`", joint.name);
        assert_eq!(body.joint.name, joint.name, "{at}: name");
        assert_eq!(
            body.parent,
            usize::try_from(joint.parent).ok(),
            "{at}: parent"
        );
        assert_eq!(body.joint.idx_q, joint.idx_q, "{at}: idx_q");
        assert_eq!(body.joint.idx_v, joint.idx_v, "{at}: idx_v");
        let axis = match (&body.joint.kind, joint.kind.as_str()) {
            (JointKind::Revolute { axis_in_joint }, "revolute")
            | (JointKind::Prismatic { axis_in_joint }, "prismatic") => axis_in_joint,
            (kind, expected) => panic!("{at}: kind {kind:?}, expected {expected}"),
        };
        worst.axis = worst.axis.max(within(
            format!("{at}: axis"),
            (axis - vec3(joint.axis)).amax(),
            tolerance,
        ));
        let placement = &body.joint.placement_in_parent;
        worst.placement = worst.placement.max(within(
            format!("{at}: placement rotation"),
            (placement.rotation - mat3(joint.placement.rotation)).amax(),
            tolerance,
        ));
        worst.placement = worst.placement.max(within(
            format!("{at}: placement translation"),
            (placement.translation - vec3(joint.placement.translation)).amax(),
            tolerance,
        ));
    }
    for expected_body in &expected.bodies {
        let k = expected_body.joint;
        let at = format!("{name}: body of joint {k}");
        let inertia = &model.bodies()[k].inertia;
        worst.inertia = worst.inertia.max(within(
            format!("{at}: mass"),
            (inertia.mass - expected_body.mass).abs(),
            tolerance,
        ));
        worst.inertia = worst.inertia.max(within(
            format!("{at}: com"),
            (inertia.com_in_body - vec3(expected_body.com)).amax(),
            tolerance,
        ));
        worst.inertia = worst.inertia.max(within(
            format!("{at}: inertia_com"),
            (inertia.inertia_com_in_body - mat3(expected_body.inertia_com)).amax(),
            tolerance,
        ));
    }
    worst
}

/// The `Mechanism` constants of `M` agree with the file: sizes, joint names, body count.
fn constants<M: Mechanism>(file: &AnchorFile) {
    let name = M::NAME;
    assert_eq!(M::NQ, file.model.nq, "{name}: NQ");
    assert_eq!(M::NV, file.model.nv, "{name}: NV");
    let joints: Vec<&str> = file.model.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(M::JOINT_NAMES, joints.as_slice(), "{name}: JOINT_NAMES");
    assert_eq!(
        M::BODY_NAMES.len(),
        file.model.bodies.len(),
        "{name}: BODY_NAMES"
    );
    let model = M::model();
    let bodies: Vec<&str> = model.bodies().iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        M::BODY_NAMES,
        bodies.as_slice(),
        "{name}: BODY_NAMES vs model()"
    );
    assert!(M::PARAMETER_NAMES.is_empty() && M::NOMINAL_PARAMETERS.is_empty());
}

/// Checks mechanism `M` against anchor file `file_name`; returns the largest deviation.
fn check<M: Mechanism>(file_name: &str, tolerance: f64) -> f64 {
    let file = anchors::load(file_name).unwrap_or_else(|e| panic!("anchor file: {e}"));
    constants::<M>(&file);
    let worst = compare(M::NAME, &M::model(), &file, tolerance);
    println!(
        "{:<20} max deviation {:.3e} (placements {:.1e}, axes {:.1e}, inertias {:.1e}, gravity {:.1e})",
        M::NAME,
        worst.max(),
        worst.placement,
        worst.axis,
        worst.inertia,
        worst.gravity
    );
    worst.max()
}

#[test]
fn pendulum_is_the_anchor() {
    check::<lang::Pendulum>("pendulum", TOLERANCE);
    check::<urdf::PendulumUrdf>("pendulum", TOLERANCE);
}

#[test]
fn double_pendulum_is_the_anchor() {
    check::<lang::DoublePendulum>("double_pendulum", TOLERANCE);
    check::<urdf::DoublePendulumUrdf>("double_pendulum", TOLERANCE);
}

#[test]
fn planar3_is_the_anchor() {
    check::<lang::Planar3>("planar3", TOLERANCE);
    check::<urdf::Planar3Urdf>("planar3", TOLERANCE);
}

#[test]
fn ur5_is_the_anchor() {
    check::<lang::Ur5>("ur5", TOLERANCE);
    check::<urdf::Ur5Urdf>("ur5", TOLERANCE);
}

#[test]
fn panda_is_the_anchor() {
    check::<lang::Panda>("panda", TOLERANCE);
    check::<urdf::PandaUrdf>("panda", TOLERANCE);
}

/// The language model and its URDF twin agree with each other as closely as with Pinocchio.
#[test]
fn the_twins_agree_with_each_other() {
    fn pair<A: Mechanism, B: Mechanism>() {
        let (a, b) = (A::model(), B::model());
        assert_eq!(A::JOINT_NAMES, B::JOINT_NAMES, "{}", A::NAME);
        assert_eq!(A::BODY_NAMES, B::BODY_NAMES, "{}", A::NAME);
        for (x, y) in a.bodies().iter().zip(b.bodies()) {
            assert_eq!(x.parent, y.parent);
            assert_eq!(x.joint.kind, y.joint.kind, "{}", x.joint.name);
            let (p, q) = (&x.joint.placement_in_parent, &y.joint.placement_in_parent);
            assert!(
                (p.rotation - q.rotation).amax() <= TOLERANCE,
                "{}",
                x.joint.name
            );
            assert!(
                (p.translation - q.translation).amax() <= TOLERANCE,
                "{}",
                x.joint.name
            );
            let (i, j) = (&x.inertia, &y.inertia);
            assert!((i.mass - j.mass).abs() <= TOLERANCE, "{}", x.name);
            assert!(
                (i.com_in_body - j.com_in_body).amax() <= TOLERANCE,
                "{}",
                x.name
            );
            assert!(
                (i.inertia_com_in_body - j.inertia_com_in_body).amax() <= TOLERANCE,
                "{}",
                x.name
            );
        }
    }
    pair::<lang::Pendulum, urdf::PendulumUrdf>();
    pair::<lang::DoublePendulum, urdf::DoublePendulumUrdf>();
    pair::<lang::Planar3, urdf::Planar3Urdf>();
    pair::<lang::Ur5, urdf::Ur5Urdf>();
    pair::<lang::Panda, urdf::PandaUrdf>();
}

fn assert_near(what: &str, got: f64, expected: f64) {
    assert!(
        (got - expected).abs() <= TOLERANCE,
        "{what}: got {got}, expected {expected}"
    );
}

/// FallingRod: m = 2 kg, L = 0.6 m, c = (0, −L/2, 0), a thin rod along y:
/// I_G = diag(m L²/12, 0, m L²/12) = diag(0.06, 0, 0.06), and about the pivot
/// I_O = I_G,zz + m (L/2)² = m L²/3 = 0.24 kg·m²; gravity −9.81 y.
#[test]
fn falling_rod_has_the_seeds_numbers() {
    type M = seed::FallingRod;
    assert_eq!((M::NQ, M::NV), (1, 1));
    assert_eq!(M::JOINT_NAMES, ["pivot"]);
    assert_eq!(M::BODY_NAMES, ["rod"]);
    let model = M::model();
    assert_eq!(model.gravity_in_world(), Vector3::new(0.0, -9.81, 0.0));
    let body = &model.bodies()[0];
    assert_eq!(body.parent, None);
    assert_eq!(
        body.joint.kind,
        JointKind::Revolute {
            axis_in_joint: Vector3::z()
        }
    );
    let (m, l) = (2.0, 0.6);
    assert_near("m", body.inertia.mass, m);
    assert_near(
        "c",
        (body.inertia.com_in_body - Vector3::new(0.0, -l / 2.0, 0.0)).amax(),
        0.0,
    );
    let i_g = Matrix3::from_diagonal(&Vector3::new(m * l * l / 12.0, 0.0, m * l * l / 12.0));
    assert_near("I_G", (body.inertia.inertia_com_in_body - i_g).amax(), 0.0);
    let c = body.inertia.com_in_body;
    let i_o = body.inertia.inertia_com_in_body[(2, 2)] + m * (c.x * c.x + c.y * c.y);
    assert_near("I_O = m L²/3", i_o, m * l * l / 3.0);
    assert_near("I_O", i_o, 0.24);
    assert_near(
        "I_O from inertia_about_origin",
        body.inertia.inertia_about_origin()[(2, 2)],
        0.24,
    );
}

/// EccentricRotor: m = 2 kg, e = 1 mm, a solid disc r = 5 cm, 2 cm thick about z:
/// I_G = diag(m (3r² + l²)/12, m (3r² + l²)/12, m r²/2); no gravity; at ω = 100 rad/s the
/// bearing carries m e ω² = 20 N.
#[test]
fn eccentric_rotor_has_the_seeds_numbers() {
    type M = seed::EccentricRotor;
    assert_eq!((M::NQ, M::NV), (1, 1));
    assert_eq!(M::JOINT_NAMES, ["bearing"]);
    let model = M::model();
    assert_eq!(model.gravity_in_world(), Vector3::zeros());
    let body = &model.bodies()[0];
    let (m, e, r, l) = (2.0, 0.001, 0.05, 0.02);
    assert_near("m", body.inertia.mass, m);
    assert_near(
        "e",
        (body.inertia.com_in_body - Vector3::new(e, 0.0, 0.0)).amax(),
        0.0,
    );
    let across = m * (3.0 * r * r + l * l) / 12.0;
    let i_g = Matrix3::from_diagonal(&Vector3::new(across, across, m * r * r / 2.0));
    assert_near("I_G", (body.inertia.inertia_com_in_body - i_g).amax(), 0.0);
    let omega: f64 = 100.0;
    assert_near(
        "m e ω²",
        body.inertia.mass * body.inertia.com_in_body.norm() * omega.powi(2),
        20.0,
    );
}

/// GyroscopicBody: a free body, m = 1 kg, I_G = diag(0.2, 0.3, 0.4) kg·m², its frame at the
/// mass centre; at ω = (1, 2, 3) rad/s, ω × I_G ω = (0.6, −0.6, 0.2) N·m.
#[test]
fn gyroscopic_body_has_the_seeds_numbers() {
    type M = seed::GyroscopicBody;
    assert_eq!((M::NQ, M::NV), (7, 6));
    assert_eq!(M::JOINT_NAMES, ["flight"]);
    let model = M::model();
    let body = &model.bodies()[0];
    assert_eq!(body.joint.kind, JointKind::FreeFlyer);
    assert_eq!(body.parent, None);
    assert_near("m", body.inertia.mass, 1.0);
    assert_near("c", body.inertia.com_in_body.amax(), 0.0);
    let i_g = body.inertia.inertia_com_in_body;
    assert_near(
        "I_G",
        (i_g - Matrix3::from_diagonal(&Vector3::new(0.2, 0.3, 0.4))).amax(),
        0.0,
    );
    let omega = Vector3::new(1.0, 2.0, 3.0);
    let moment = omega.cross(&(i_g * omega));
    assert_near("M_G", (moment - Vector3::new(0.6, -0.6, 0.2)).amax(), 0.0);
}
