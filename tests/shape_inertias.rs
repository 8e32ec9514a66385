//! The inertia forms of the language against textbook formulas written out here, not
//! against anything the code generator computes: every standard shape (slender rod, box,
//! solid cylinder, solid sphere, point mass), `principal(moments, rotation: R)` with R given
//! as `rpy(..)` and as `axis_angle(..)`, and a mass that is a scaled symbolic parameter.
//!
//! Each body sits on its own free joint with its mass centre at the body origin, so the
//! generated mass matrix (body-frame twist `[v; ω]`) is block diagonal with blocks
//! `m·1₃` and `I_G`: it shows the generated code's inertia directly, at any configuration.
//! The runtime `Model` that `mechanism!` emits (what the reference computes with) must carry
//! the same I_G. The point mass, which has no rotational inertia of its own, turns about z
//! at a distance d from the axis instead: M = m d².
//!
//! Expected values: slender rod of length L, across m L²/12, along 0; box of edges a, b, c,
//! (m/12)(b² + c²), (m/12)(a² + c²), (m/12)(a² + b²); solid cylinder of radius r and length
//! L, about its axis m r²/2, across (m/12)(3r² + L²); solid sphere 2/5 m r²; rotated
//! principal moments R diag(I₁, I₂, I₃) Rᵀ, with `rpy(r, p, y)` = Rz(y) Ry(p) Rx(r) (URDF's
//! fixed-axis convention) and `axis_angle(u, θ)` = 1 + sin θ [u]× + (1 − cos θ) [u]×²
//! (Rodrigues, u normalized). Tolerance 1e-14 · (1 + max |value|): the formulas and the
//! generated code round differently, nothing more.

use dynamics_runtime::{mechanism, Mechanism};
use dynamics_tests::assert_close;

mechanism! {
    /// One free body per inertia form, each with its mass centre at its origin.
    pub struct Shapes;
    gravity: [0.0, 0.0, -9.81];
    outputs: [mass_matrix];

    /// A box of edges 0.3 × 0.2 × 0.1, m = 1.5.
    body brick { mass: 1.5, shape: box(size: [0.3, 0.2, 0.1]) }
    /// A solid cylinder about z: m = 3, r = 0.2, L = 0.5.
    body drum_z { mass: 3.0, shape: cylinder(radius: 0.2, length: 0.5, axis: z) }
    /// A solid cylinder about x: m = 1.1, r = 0.05, L = 0.9.
    body drum_x { mass: 1.1, shape: cylinder(radius: 0.05, length: 0.9, axis: x) }
    /// A solid sphere: m = 2.5, r = 0.1.
    body ball { mass: 2.5, shape: sphere(radius: 0.1) }
    /// Principal moments (0.01, 0.02, 0.025) turned by rpy(0.3, −0.5, 1.1).
    body tilted { mass: 1.0, inertia: principal([0.01, 0.02, 0.025], rotation: rpy(0.3, -0.5, 1.1)) }
    /// Principal moments (0.04, 0.03, 0.05) turned by 0.7 rad about (1, 2, 2)/3.
    body turned { mass: 1.2, inertia: principal([0.04, 0.03, 0.05], rotation: axis_angle([1.0, 2.0, 2.0], 0.7)) }

    joint j_brick: free(ground -> brick);
    joint j_drum_z: free(ground -> drum_z);
    joint j_drum_x: free(ground -> drum_x);
    joint j_ball: free(ground -> ball);
    joint j_tilted: free(ground -> tilted);
    joint j_turned: free(ground -> turned);
}

mechanism! {
    /// Two slender rods, each turning about a diagonal axis through its centre (a rod has no
    /// inertia about its own axis, so a free rod would have a singular mass matrix).
    pub struct Rods;
    gravity: [0.0, 0.0, -9.81];
    outputs: [mass_matrix];

    /// A slender rod along x: m = 2, L = 0.6.
    body rod_x { mass: 2.0, shape: rod(length: 0.6, axis: x) }
    /// A slender rod along y: m = 0.7, L = 1.3.
    body rod_y { mass: 0.7, shape: rod(length: 1.3, axis: y) }

    joint j_rod_x: revolute(ground -> rod_x) { axis: [1.0, 1.0, 0.0] }
    joint j_rod_y: revolute(ground -> rod_y) { axis: [0.0, 1.0, 1.0] }
}

mechanism! {
    /// A point mass m = 2 at c = (0.3, 0.4, 0.7), turning about z through the origin.
    pub struct PointOnArm;
    gravity: [0.0, 0.0, -9.81];
    outputs: [mass_matrix];

    body bob { mass: 2.0, com: [0.3, 0.4, 0.7], shape: point }
    joint spin: revolute(ground -> bob) { axis: z }
}

mechanism! {
    /// A solid cylinder whose mass is half the parameter `m_tool`: its inertia scales with it.
    pub struct ScaledCylinder;
    outputs: [mass_matrix];
    parameters: [m_tool = 0.8];

    body tool { mass: 0.5 * m_tool, shape: cylinder(radius: 0.15, length: 0.4, axis: y) }
    joint flight: free(ground -> tool);
}

/// The body-frame rotation matrices, written out.
fn rot_x(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
}

fn rot_y(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
}

fn rot_z(a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn product(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn transpose(a: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| a[j][i]))
}

fn diag(d: [f64; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| if i == j { d[i] } else { 0.0 }))
}

/// R diag(moments) Rᵀ.
fn rotated(r: &[[f64; 3]; 3], moments: [f64; 3]) -> [[f64; 3]; 3] {
    product(&product(r, &diag(moments)), &transpose(r))
}

/// Rodrigues' formula for a rotation by `angle` about the direction of `axis`.
fn axis_angle(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let norm = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
    let [x, y, z] = axis.map(|a| a / norm);
    let k = [[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]];
    let k2 = product(&k, &k);
    let (s, c) = angle.sin_cos();
    std::array::from_fn(|i| {
        std::array::from_fn(|j| f64::from(u8::from(i == j)) + s * k[i][j] + (1.0 - c) * k2[i][j])
    })
}

fn flat(m: &[[f64; 3]; 3]) -> Vec<f64> {
    m.iter().flatten().copied().collect()
}

/// A configuration away from the neutral one: every free body somewhere, turned.
fn configuration<const NQ: usize>() -> [f64; NQ] {
    let mut q = [0.0; NQ];
    for (k, x) in q.iter_mut().enumerate() {
        *x = 0.1 * k as f64 - 0.4;
    }
    for body in 0..NQ / 7 {
        let quat = &mut q[7 * body + 3..7 * body + 7];
        let norm = quat.iter().map(|x| x * x).sum::<f64>().sqrt();
        quat.iter_mut().for_each(|x| *x /= norm);
    }
    q
}

/// Mass and I_G of free body `k` read off a block-diagonal mass matrix.
fn free_body_block<const NV: usize>(m: &[[f64; NV]; NV], k: usize) -> (Vec<f64>, Vec<f64>) {
    let o = 6 * k;
    let linear = (0..3)
        .flat_map(|i| (0..3).map(move |j| m[o + i][o + j]))
        .collect();
    let angular = (0..3)
        .flat_map(|i| (0..3).map(move |j| m[o + 3 + i][o + 3 + j]))
        .collect();
    (linear, angular)
}

/// Slender rod of mass m and length L: m L²/12 across.
fn rod_across(m: f64, l: f64) -> f64 {
    m * l * l / 12.0
}

/// The expected mass and I_G of each body of [`Rods`], by hand.
fn expected_rods() -> Vec<(&'static str, f64, [[f64; 3]; 3])> {
    let (m, l) = (2.0, 0.6);
    let rod_x = diag([0.0, rod_across(m, l), rod_across(m, l)]);
    let (m, l) = (0.7, 1.3);
    let rod_y = diag([rod_across(m, l), 0.0, rod_across(m, l)]);
    vec![("rod_x", 2.0, rod_x), ("rod_y", 0.7, rod_y)]
}

/// The expected mass and I_G of each body of [`Shapes`], in declaration order, by hand.
fn expected_shapes() -> Vec<(&'static str, f64, [[f64; 3]; 3])> {
    let (m, a, b, c) = (1.5, 0.3, 0.2, 0.1);
    let brick = diag([
        m / 12.0 * (b * b + c * c),
        m / 12.0 * (a * a + c * c),
        m / 12.0 * (a * a + b * b),
    ]);
    let axial = |m: f64, r: f64| m * r * r / 2.0;
    let across = |m: f64, r: f64, l: f64| m / 12.0 * (3.0 * r * r + l * l);
    let (m, r, l) = (3.0, 0.2, 0.5);
    let drum_z = diag([across(m, r, l), across(m, r, l), axial(m, r)]);
    let (m, r, l) = (1.1, 0.05, 0.9);
    let drum_x = diag([axial(m, r), across(m, r, l), across(m, r, l)]);
    let (m, r) = (2.5, 0.1);
    let ball = diag([0.4 * m * r * r; 3]);
    let rpy = product(&product(&rot_z(1.1), &rot_y(-0.5)), &rot_x(0.3));
    let tilted = rotated(&rpy, [0.01, 0.02, 0.025]);
    let turned = rotated(&axis_angle([1.0, 2.0, 2.0], 0.7), [0.04, 0.03, 0.05]);
    vec![
        ("brick", 1.5, brick),
        ("drum_z", 3.0, drum_z),
        ("drum_x", 1.1, drum_x),
        ("ball", 2.5, ball),
        ("tilted", 1.0, tilted),
        ("turned", 1.2, turned),
    ]
}

const TOLERANCE: f64 = 1e-14;

#[test]
fn generated_mass_matrix_carries_the_textbook_shape_inertias() {
    const NV: usize = <Shapes as Mechanism>::NV;
    let q = configuration::<{ <Shapes as Mechanism>::NQ }>();
    let m: [[f64; NV]; NV] = Shapes::mass_matrix(&q);
    let expected = expected_shapes();
    assert_eq!(expected.len() * 6, NV, "one free body per expected inertia");
    for (k, (name, mass, inertia)) in expected.iter().enumerate() {
        let (linear, angular) = free_body_block(&m, k);
        assert_close(
            &format!("{name}: m·1"),
            &linear,
            &flat(&diag([*mass; 3])),
            TOLERANCE,
        );
        assert_close(&format!("{name}: I_G"), &angular, &flat(inertia), TOLERANCE);
    }
    // Nothing couples two free bodies.
    for i in 0..NV {
        for j in 0..NV {
            if i / 6 != j / 6 {
                assert_eq!(m[i][j], 0.0, "M[{i}][{j}] couples two free bodies");
            }
        }
    }
}

#[test]
fn generated_mass_matrix_carries_the_textbook_rod_inertia() {
    // About the unit axis n = (1, 1, 0)/√2 through the centre, nᵀ I_G n = (0 + m L²/12)/2
    // for the rod along x; n = (0, 1, 1)/√2 gives the same for the rod along y. The zero
    // moment along the rod enters with weight ½: a nonzero one would show.
    for angles in [[0.0, 0.0], [0.7, -2.1]] {
        let m = Rods::mass_matrix(&angles);
        let expected = [
            rod_across(2.0, 0.6) / 2.0,
            0.0,
            0.0,
            rod_across(0.7, 1.3) / 2.0,
        ];
        assert_close("rods: M", m.as_flattened(), &expected, TOLERANCE);
    }
}

fn check_model_inertias(
    model: &dynamics_runtime::Model,
    expected: Vec<(&'static str, f64, [[f64; 3]; 3])>,
) {
    for (name, mass, inertia) in expected {
        let k = model
            .body_index(name)
            .unwrap_or_else(|| panic!("the model has body `{name}`"));
        let body = &model.bodies()[k].inertia;
        assert_close(&format!("{name}: mass"), &[body.mass], &[mass], TOLERANCE);
        assert_close(
            &format!("{name}: com"),
            body.com_in_body.as_slice(),
            &[0.0; 3],
            0.0,
        );
        let rows: Vec<f64> = (0..3)
            .flat_map(|i| (0..3).map(move |j| body.inertia_com_in_body[(i, j)]))
            .collect();
        assert_close(&format!("{name}: I_G"), &rows, &flat(&inertia), TOLERANCE);
    }
}

#[test]
fn runtime_model_carries_the_textbook_shape_inertias() {
    check_model_inertias(&<Shapes as Mechanism>::model(), expected_shapes());
    check_model_inertias(&<Rods as Mechanism>::model(), expected_rods());
}

#[test]
fn point_mass_has_only_its_transfer_inertia() {
    // M = m d², d² = 0.3² + 0.4² the squared distance from the z axis; the height 0.7 does
    // not count.
    for angle in [0.0, 1.3, -2.9] {
        let m = PointOnArm::mass_matrix(&[angle]);
        assert_close(
            "point mass: M",
            &[m[0][0]],
            &[2.0 * (0.09 + 0.16)],
            TOLERANCE,
        );
    }
    let model = <PointOnArm as Mechanism>::model();
    let inertia = &model.bodies()[0].inertia.inertia_com_in_body;
    assert_eq!(
        inertia.amax(),
        0.0,
        "a point has no inertia about its centre"
    );
}

#[test]
fn shape_inertia_scales_with_a_parameter_mass() {
    // m = 0.5 m_tool; solid cylinder about y: I_yy = m r²/2, I_xx = I_zz = (m/12)(3r² + L²).
    let (r, l) = (0.15_f64, 0.4_f64);
    let q = configuration::<7>();
    for m_tool in [0.8, 3.7, 0.05] {
        let m = 0.5 * m_tool;
        let across = m / 12.0 * (3.0 * r * r + l * l);
        let expected = diag([across, m * r * r / 2.0, across]);
        let matrix = ScaledCylinder::mass_matrix(&q, &[m_tool]);
        let (linear, angular) = free_body_block(&matrix, 0);
        let at = format!("m_tool = {m_tool}");
        assert_close(
            &format!("{at}: m·1"),
            &linear,
            &flat(&diag([m; 3])),
            TOLERANCE,
        );
        assert_close(&format!("{at}: I_G"), &angular, &flat(&expected), TOLERANCE);

        let model = <ScaledCylinder as Mechanism>::model_with_parameters(&[m_tool])
            .unwrap_or_else(|e| panic!("{at}: {e}"));
        let body = &model.bodies()[0].inertia;
        assert_close(&format!("{at}: model mass"), &[body.mass], &[m], TOLERANCE);
        let rows: Vec<f64> = (0..3)
            .flat_map(|i| (0..3).map(move |j| body.inertia_com_in_body[(i, j)]))
            .collect();
        assert_close(
            &format!("{at}: model I_G"),
            &rows,
            &flat(&expected),
            TOLERANCE,
        );
    }
}
