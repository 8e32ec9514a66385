//! The compact joint Jacobians in Pinocchio's WORLD convention, `joint_jacobians_world` (its
//! `data.J`) and `joint_jacobians_world_time_variation` (`data.J`, `data.dJ`):
//! - against Pinocchio's values for the five anchor robots
//!   (`tests/data/pinocchio_ext/<name>_kinematics.json`, 20 samples each), which store each
//!   joint's LOCAL_WORLD_ALIGNED Jacobian J_i and placement (R_i, p_i): every column c that
//!   moves body i is J_i's column taken to the world origin, [v + p_i × ω; ω]; and the
//!   spatial acceleration Σ_c J̇[:, c] v_c of body i at the origin, taken back to body i's
//!   origin as a classical acceleration (a_P = a_O + α × p_i + ω × v_P), is Pinocchio's
//!   J̇_i v — to 1e-12;
//! - on a free-floating branched tree with a prismatic joint: J̇ against central differences
//!   of J along the motion q ⊕ t v, and the tuple's J equal to `joint_jacobians_world`.

use dynamics_tests::free_tree;
use serde::Deserialize;

/// A URDF anchor with the world Jacobians (a `macro_rules!` around `mechanism!`: the URDF
/// path is a literal).
macro_rules! mechanism_with_world_jacobians {
    ($name:ident, $urdf:literal) => {
        dynamics_runtime::mechanism! {
            pub struct $name;
            urdf: $urdf;
            outputs: [joint_jacobians_world, joint_jacobians_world_time_variation];
        }
    };
}

mechanism_with_world_jacobians!(Pendulum, "../models/urdf/pendulum.urdf");
mechanism_with_world_jacobians!(DoublePendulum, "../models/urdf/double_pendulum.urdf");
mechanism_with_world_jacobians!(Ur5, "../models/urdf/ur5.urdf");
mechanism_with_world_jacobians!(Panda, "../models/urdf/panda.urdf");

dynamics_runtime::mechanism! {
    pub struct Planar3;
    urdf: "../models/urdf/planar3.urdf";
    outputs: [joint_jacobians_world, joint_jacobians_world_time_variation];
    allow: [triangle_inequality];
}

dynamics_runtime::mechanism! {
    /// The free tree of `generated_kinematics.rs`: a free base with two branches, one
    /// ending in a slider.
    pub struct FreeTree;
    outputs: [joint_jacobians_world, joint_jacobians_world_time_variation];
    body base { mass: 3.0, com: [0.01, 0.02, -0.03], inertia: [[0.1, 0.01, 0.0], [0.01, 0.12, 0.02], [0.0, 0.02, 0.09]] }
    body left { mass: 1.0, com: [0.1, 0.0, 0.0], shape: rod(length: 0.2, axis: x) }
    body right { mass: 0.7, com: [0.0, 0.05, 0.01], shape: box(size: [0.05, 0.1, 0.02]) }
    body slider { mass: 0.4, com: [0.02, 0.0, 0.01], shape: sphere(radius: 0.03) }
    joint float: free(ground -> base);
    joint hip_left: revolute(base -> left) { axis: [0.3, 0.2, 1.0], at: [0.1, 0.1, 0.0], rotation: rpy(0.1, 0.2, 0.3) }
    joint hip_right: revolute(base -> right) { axis: y, at: [0.1, -0.1, 0.0] }
    joint slide: prismatic(left -> slider) { axis: x, at: [0.2, 0.0, 0.0] }
}

#[derive(Deserialize)]
struct Placement {
    translation: [f64; 3],
}

#[derive(Deserialize)]
struct Sample {
    q: Vec<f64>,
    v: Vec<f64>,
    joint_placements: Vec<Placement>,
    joint_jacobians_world: Vec<Vec<Vec<f64>>>,
    joint_jacobian_time_derivative_times_v_world: Vec<[f64; 6]>,
}

type Matrix<const NV: usize> = [[f64; NV]; 6];

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn column<const NV: usize>(m: &Matrix<NV>, c: usize) -> ([f64; 3], [f64; 3]) {
    ([m[0][c], m[1][c], m[2][c]], [m[3][c], m[4][c], m[5][c]])
}

#[track_caller]
fn assert_close(got: f64, expected: f64, tolerance: f64, what: &dyn Fn() -> String) {
    assert!(
        (got - expected).abs() <= tolerance,
        "{}: {got} against {expected}",
        what()
    );
}

/// The J of the two outputs agree (to rounding: each function's code is scheduled on its
/// own).
fn assert_same<const NV: usize>(a: &Matrix<NV>, b: &Matrix<NV>, what: &dyn Fn() -> String) {
    for r in 0..6 {
        for c in 0..NV {
            assert_close(a[r][c], b[r][c], 1e-15, &|| {
                format!("{} J[{r}][{c}]", what())
            });
        }
    }
}

/// One anchor robot's J and J̇ against Pinocchio's values (see the file's doc).
fn check_against_pinocchio<const NQ: usize, const NV: usize>(
    name: &str,
    world: fn(&[f64; NQ]) -> Matrix<NV>,
    time_variation: fn(&[f64; NQ], &[f64; NV]) -> (Matrix<NV>, Matrix<NV>),
) {
    let samples: Vec<Sample> = dynamics_tests::pinocchio_ext_samples(name, "kinematics");
    assert!(!samples.is_empty(), "{name}: no samples");
    for (k, sample) in samples.iter().enumerate() {
        let q: [f64; NQ] = sample.q.clone().try_into().expect("nq matches");
        let v: [f64; NV] = sample.v.clone().try_into().expect("nv matches");
        let j = world(&q);
        let (j_again, j_dot) = time_variation(&q, &v);
        assert_same(&j, &j_again, &|| format!("{name} sample {k}"));
        let mut checked = [false; NV];
        for (b, lwa) in sample.joint_jacobians_world.iter().enumerate() {
            let p = sample.joint_placements[b].translation;
            let moves = |c: usize| (0..6).any(|r| lwa[r][c] != 0.0);
            for c in (0..NV).filter(|&c| moves(c)) {
                checked[c] = true;
                let omega = [lwa[3][c], lwa[4][c], lwa[5][c]];
                let shift = cross(p, omega);
                for r in 0..3 {
                    let what = || format!("{name} sample {k} body {b} J[{r}][{c}]");
                    assert_close(j[r][c], lwa[r][c] + shift[r], 1e-12, &what);
                    let what = || format!("{name} sample {k} body {b} J[{}][{c}]", 3 + r);
                    assert_close(j[3 + r][c], omega[r], 1e-12, &what);
                }
            }
            // Body b's spatial acceleration at the origin (a = 0), then its classical
            // acceleration at p_b: a_P = a_O + α × p + ω × v_P, with [v_P; ω] = J_b v.
            let (mut a_origin, mut alpha) = ([0.0; 3], [0.0; 3]);
            let (mut v_point, mut omega) = ([0.0; 3], [0.0; 3]);
            for c in (0..NV).filter(|&c| moves(c)) {
                let (lin, ang) = column(&j_dot, c);
                for r in 0..3 {
                    a_origin[r] += lin[r] * v[c];
                    alpha[r] += ang[r] * v[c];
                    v_point[r] += lwa[r][c] * v[c];
                    omega[r] += lwa[3 + r][c] * v[c];
                }
            }
            let (turn, carry) = (cross(alpha, p), cross(omega, v_point));
            let expected = &sample.joint_jacobian_time_derivative_times_v_world[b];
            for r in 0..3 {
                let what = || format!("{name} sample {k} body {b} J̇v[{r}]");
                assert_close(a_origin[r] + turn[r] + carry[r], expected[r], 1e-12, &what);
                let what = || format!("{name} sample {k} body {b} J̇v[{}]", 3 + r);
                assert_close(alpha[r], expected[3 + r], 1e-12, &what);
            }
        }
        assert!(checked.iter().all(|&c| c), "{name}: a column moves no body");
    }
}

#[test]
fn world_jacobians_and_their_rates_match_pinocchio() {
    check_against_pinocchio(
        "pendulum",
        Pendulum::joint_jacobians_world,
        Pendulum::joint_jacobians_world_time_variation,
    );
    check_against_pinocchio(
        "double_pendulum",
        DoublePendulum::joint_jacobians_world,
        DoublePendulum::joint_jacobians_world_time_variation,
    );
    check_against_pinocchio(
        "planar3",
        Planar3::joint_jacobians_world,
        Planar3::joint_jacobians_world_time_variation,
    );
    check_against_pinocchio(
        "ur5",
        Ur5::joint_jacobians_world,
        Ur5::joint_jacobians_world_time_variation,
    );
    check_against_pinocchio(
        "panda",
        Panda::joint_jacobians_world,
        Panda::joint_jacobians_world_time_variation,
    );
}

/// On the free tree J̇ is the derivative of J along the motion: J(q ⊕ h v) against
/// J(q ⊖ h v) by central differences.
#[test]
fn world_jacobian_rates_of_a_free_tree_are_the_derivatives() {
    let h = 1e-6;
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let v = free_tree::velocity(k);
        let (j, j_dot) = FreeTree::joint_jacobians_world_time_variation(&q, &v);
        assert_same(&j, &FreeTree::joint_jacobians_world(&q), &|| {
            format!("q {q:?}")
        });
        let plus = FreeTree::joint_jacobians_world(&free_tree::moved(&q, &v, h));
        let minus = FreeTree::joint_jacobians_world(&free_tree::moved(&q, &v, -h));
        for r in 0..6 {
            for c in 0..9 {
                let rate = (plus[r][c] - minus[r][c]) / (2.0 * h);
                let what = || format!("q {q:?} J̇[{r}][{c}]");
                assert_close(j_dot[r][c], rate, 1e-7, &what);
            }
        }
    }
}

/// J v of the free tree is the base's velocity at the world origin (columns 0..6: the
/// base's v = [v_P; ω] in its own frame, moved to the origin in world axes: R v_P + p × R ω),
/// checked from the base's own columns alone; and a joint's columns vanish from J's rate
/// only when nothing above it moves (the root's J̇ columns at v = 0 are zero).
#[test]
fn world_jacobian_of_the_free_base_is_its_twist_at_the_origin() {
    for k in 0..6 {
        let q = free_tree::configuration(k);
        let j = FreeTree::joint_jacobians_world(&q);
        let (_, j_dot) = FreeTree::joint_jacobians_world_time_variation(&q, &[0.0; 9]);
        assert!(j_dot.iter().flatten().all(|&x| x == 0.0), "J̇ at v = 0");
        let (x, y, z, w) = (q[3], q[4], q[5], q[6]);
        let rotation = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - z * w),
                2.0 * (x * z + y * w),
            ],
            [
                2.0 * (x * y + z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - x * w),
            ],
            [
                2.0 * (x * z - y * w),
                2.0 * (y * z + x * w),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        let p = [q[0], q[1], q[2]];
        for e in 0..3 {
            let axis = [rotation[0][e], rotation[1][e], rotation[2][e]];
            let (lin, ang) = column(&j, e);
            let (lin_spin, ang_spin) = column(&j, 3 + e);
            let moment = cross(p, axis);
            for r in 0..3 {
                let what = || format!("q {q:?} column {e} row {r}");
                assert_close(lin[r], axis[r], 1e-14, &what);
                assert_close(ang[r], 0.0, 0.0, &what);
                assert_close(lin_spin[r], moment[r], 1e-14, &what);
                assert_close(ang_spin[r], axis[r], 1e-14, &what);
            }
        }
    }
}
