//! The textbook's worked examples (Satici, *Kinematics and Machine Dynamics*, ch. 10,
//! "Formulation of Equations of Motion"), each through the runtime reference, with the
//! textbook's own numbers: exact ones to 1e-12, rounded ones to the textbook's last digit.

use dynamics_runtime::{BodySpec, Inertia, JointSpec, Model, ModelBuilder, Reference, Wrench};
use nalgebra::{DMatrix, Vector3};

/// Tolerance of numbers the textbook gives exactly.
const EXACT: f64 = 1e-12;
/// Tolerance of numbers the textbook rounds to three decimals.
const ROUNDED: f64 = 5e-4;

fn assert_near(what: &str, got: f64, expected: f64, tolerance: f64) {
    assert!(
        (got - expected).abs() <= tolerance,
        "{what}: got {got}, expected {expected} ± {tolerance}"
    );
}

fn build(builder: ModelBuilder) -> Model {
    builder
        .build()
        .expect("the textbook's mechanisms are valid")
}

/// The textbook's uniform rod, "Worked example: a falling rigid rod": m = 2 kg, L = 0.60 m,
/// pivoted at its end O about z, θ counterclockwise from the downward vertical, so the mass
/// centre is c = (0, −L/2, 0) in the body frame; a thin rod has I_G = diag(mL²/12, 0, mL²/12).
const ROD_MASS: f64 = 2.0;
const ROD_LENGTH: f64 = 0.60;
const G: f64 = 9.81;

fn rod(gravity: bool) -> Model {
    let i_g = ROD_MASS * ROD_LENGTH * ROD_LENGTH / 12.0;
    let g = if gravity { -G } else { 0.0 };
    build(
        ModelBuilder::new()
            .gravity([0.0, g, 0.0])
            .body(BodySpec::new(
                "rod",
                Inertia::new(
                    ROD_MASS,
                    [0.0, -ROD_LENGTH / 2.0, 0.0],
                    [[i_g, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, i_g]],
                ),
            ))
            .joint(JointSpec::revolute("pin", "ground", "rod", [0.0, 0.0, 1.0])),
    )
}

/// I_O = m L² / 3 = 0.24 kg·m² (seed).
fn rod_inertia_about_pivot() -> f64 {
    ROD_MASS * ROD_LENGTH * ROD_LENGTH / 3.0
}

/// Seed, "When inertia becomes significant": a mass centre at e = 1 mm from the spin axis,
/// m = 2 kg, needs F = m e ω² = 20 N at ω = 100 rad/s, and 80 N at twice the speed. The pin
/// reaction on the rotor points from G to the axis (centripetal), with no gravity.
#[test]
fn eccentric_rotor_pin_reaction() {
    let (mass, e) = (2.0, 1e-3);
    let model = build(
        ModelBuilder::new()
            .body(BodySpec::new(
                "rotor",
                Inertia::new(
                    mass,
                    [e, 0.0, 0.0],
                    [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.02]],
                ),
            ))
            .joint(JointSpec::revolute(
                "spin",
                "ground",
                "rotor",
                [0.0, 0.0, 1.0],
            )),
    );
    let mut reference = Reference::<f64>::new(&model);
    for (omega, expected) in [(100.0, 20.0), (200.0, 80.0)] {
        let mut reaction = [Wrench::zero()];
        reference
            .joint_reactions(&[0.3], &[omega], &[0.0], None, &mut reaction)
            .expect("sizes match");
        let force = reaction[0].force;
        assert_near("magnitude m e ω²", force.norm(), expected, EXACT * expected);
        // Towards the axis: along −c in the body frame.
        assert_near("F_x", force.x, -expected, EXACT * expected);
        assert_near("F_y", force.y, 0.0, EXACT * expected);
        assert_near("F_z", force.z, 0.0, EXACT * expected);
        // Spinning about a principal axis through P: no moment (c × F = 0, ω ∥ I_G ω).
        assert!(reaction[0].moment.norm() <= EXACT * expected);
    }
}

/// Seed, "Worked example: a gyroscopic torque": I_G = diag(0.2, 0.3, 0.4) kg·m²,
/// ω = (1, 2, 3) rad/s, α = 0 need M_G = ω × I_G ω = (0.6, −0.6, 0.2) N·m. A free body with
/// G at its frame origin: inverse dynamics returns the body wrench [F; M_P], M_P = M_G.
#[test]
fn gyroscopic_torque() {
    let model = build(
        ModelBuilder::new()
            .body(BodySpec::new(
                "top",
                Inertia::new(
                    1.5,
                    [0.0; 3],
                    [[0.2, 0.0, 0.0], [0.0, 0.3, 0.0], [0.0, 0.0, 0.4]],
                ),
            ))
            .joint(JointSpec::free_flyer("float", "top")),
    );
    let mut reference = Reference::<f64>::new(&model);
    let q = model.neutral_configuration();
    let v = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0];
    let mut tau = [0.0; 6];
    reference
        .inverse_dynamics(&q, &v, &[0.0; 6], None, &mut tau)
        .expect("sizes match");
    let expected = [0.0, 0.0, 0.0, 0.6, -0.6, 0.2];
    for k in 0..6 {
        assert_near(&format!("wrench[{k}]"), tau[k], expected[k], EXACT);
    }
}

/// Seed, "Falling rod: angular acceleration": released at θ = 30° from rest,
/// θ̈ = −2 (9.81)(0.30) sin 30° / 0.24 = −12.2625 rad/s².
#[test]
fn falling_rod_angular_acceleration() {
    let model = rod(true);
    let mut reference = Reference::<f64>::new(&model);
    let mut qdd = [0.0];
    reference
        .forward_dynamics(&[30f64.to_radians()], &[0.0], &[0.0], None, &mut qdd)
        .expect("sizes match");
    assert_near("θ̈", qdd[0], -12.2625, EXACT);
    assert_near("I_O", rod_inertia_about_pivot(), 0.24, EXACT);
    let mut m = DMatrix::zeros(1, 1);
    reference
        .mass_matrix(&[30f64.to_radians()], &mut m)
        .expect("sizes match");
    assert_near("M = I_O", m[(0, 0)], 0.24, EXACT);
}

/// Seed, same example: "To hold the rod statically at this angle, the actuator would
/// instead supply +2.943 N·m" = m g l sin θ, the generalized gravity g(q).
#[test]
fn falling_rod_holding_torque() {
    let model = rod(true);
    let mut reference = Reference::<f64>::new(&model);
    let mut g = [0.0];
    reference
        .gravity(&[30f64.to_radians()], &mut g)
        .expect("sizes match");
    assert_near("g(q)", g[0], 2.943, EXACT);
}

/// Seed, "Falling rod: pin reactions": a_G = l θ̈ (cos θ, sin θ) ≈ (−3.186, −1.839) m/s²,
/// R_x = m a_G,x ≈ −6.372 N, R_y = m g + m a_G,y ≈ 15.941 N. a_G from the kinematics
/// (α × r_OG with ω = 0, r_OG the mass centre rotated to the world), R from the joint
/// reaction rotated to the world.
#[test]
fn falling_rod_pin_reactions() {
    let model = rod(true);
    let mut reference = Reference::<f64>::new(&model);
    let theta = 30f64.to_radians();
    let mut qdd = [0.0];
    reference
        .forward_dynamics(&[theta], &[0.0], &[0.0], None, &mut qdd)
        .expect("sizes match");
    let pose = reference.body_poses(&[theta]).expect("sizes match")[0];
    let com_in_world = pose.rotation_in_world * Vector3::new(0.0, -ROD_LENGTH / 2.0, 0.0);
    let accel_com = Vector3::new(0.0, 0.0, qdd[0]).cross(&com_in_world);
    assert_near("a_G,x", accel_com.x, -3.186, ROUNDED);
    assert_near("a_G,y", accel_com.y, -1.839, ROUNDED);
    let l_theta_dd = ROD_LENGTH / 2.0 * -12.2625;
    assert_near("a_G,x exact", accel_com.x, l_theta_dd * theta.cos(), EXACT);
    assert_near("a_G,y exact", accel_com.y, l_theta_dd * theta.sin(), EXACT);

    let mut reaction = [Wrench::zero()];
    reference
        .joint_reactions(&[theta], &[0.0], &qdd, None, &mut reaction)
        .expect("sizes match");
    let force_in_world = pose.rotation_in_world * reaction[0].force;
    assert_near("R_x", force_in_world.x, -6.372, ROUNDED);
    assert_near("R_y", force_in_world.y, 15.941, ROUNDED);
    assert_near(
        "R_x = m a_G,x",
        force_in_world.x,
        ROD_MASS * accel_com.x,
        EXACT,
    );
    assert_near(
        "R_y − m g = m a_G,y",
        force_in_world.y - ROD_MASS * G,
        ROD_MASS * accel_com.y,
        EXACT,
    );
    // An ideal pin transmits no couple about its axis: the rod falls freely.
    assert_near("M_z", reaction[0].moment.z, 0.0, EXACT);
}

/// States (θ, θ̇, θ̈) of the driven pendulum examples.
const PENDULUM_STATES: [(f64, f64, f64); 4] = [
    (0.0, 0.0, 1.0),
    (0.5235987755982988, -1.5, 2.0),
    (2.0, 3.0, -4.0),
    (-2.7, 0.4, 0.25),
];

/// Seed, "A driven physical pendulum": I_O θ̈ + m g l sin θ = τ, inverse form τ(θ, θ̈) and
/// forward form θ̈(θ, θ̇, τ), at a few states (θ̇ does not enter: C = 0).
#[test]
fn driven_pendulum_inverse_and_forward() {
    let model = rod(true);
    let mut reference = Reference::<f64>::new(&model);
    let (i_o, mgl) = (rod_inertia_about_pivot(), ROD_MASS * G * ROD_LENGTH / 2.0);
    for (theta, theta_d, theta_dd) in PENDULUM_STATES {
        let expected_tau = i_o * theta_dd + mgl * theta.sin();
        let mut tau = [0.0];
        reference
            .inverse_dynamics(&[theta], &[theta_d], &[theta_dd], None, &mut tau)
            .expect("sizes match");
        assert_near("τ = I_O θ̈ + m g l sin θ", tau[0], expected_tau, EXACT);
        let mut qdd = [0.0];
        reference
            .forward_dynamics(&[theta], &[theta_d], &[expected_tau], None, &mut qdd)
            .expect("sizes match");
        assert_near("θ̈ = (τ − m g l sin θ) / I_O", qdd[0], theta_dd, EXACT);
    }
}

/// Seed, "An energy check on the pendulum equation": E = ½ I_O θ̇² + V and Ė = τ θ̇. The
/// reference's energies are T = ½ I_O θ̇² and V = −m g l cos θ (zero at the pivot, so V
/// differs from the textbook's m g l (1 − cos θ) by the constant m g l); dE/dt by a central
/// difference along a short trajectory θ(t) = θ₀ + θ̇₀ t + ½ θ̈₀ t², with τ from inverse
/// dynamics.
#[test]
fn pendulum_energy_balance() {
    let model = rod(true);
    let mut reference = Reference::<f64>::new(&model);
    let (i_o, mgl) = (rod_inertia_about_pivot(), ROD_MASS * G * ROD_LENGTH / 2.0);
    let h = 1e-4;
    for (theta0, theta_d0, theta_dd) in PENDULUM_STATES {
        let mut energy = |t: f64| {
            let theta = theta0 + theta_d0 * t + 0.5 * theta_dd * t * t;
            let theta_d = theta_d0 + theta_dd * t;
            let kinetic = reference
                .kinetic_energy(&[theta], &[theta_d])
                .expect("sizes match");
            let potential = reference.potential_energy(&[theta]).expect("sizes match");
            assert_near(
                "T = ½ I_O θ̇²",
                kinetic,
                0.5 * i_o * theta_d * theta_d,
                EXACT,
            );
            assert_near(
                "V = m g l (1 − cos θ) − m g l",
                potential,
                mgl * (1.0 - theta.cos()) - mgl,
                EXACT,
            );
            kinetic + potential
        };
        let energy_rate = (energy(h) - energy(-h)) / (2.0 * h);
        let mut tau = [0.0];
        reference
            .inverse_dynamics(&[theta0], &[theta_d0], &[theta_dd], None, &mut tau)
            .expect("sizes match");
        assert_near("Ė = τ θ̇", energy_rate, tau[0] * theta_d0, 1e-6);
    }
}
