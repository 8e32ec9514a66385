//! The bundled quadruped (`models::quadruped`) standing on its four feet: contact-constrained
//! forward dynamics from the generated M, h, foot Jacobians and J̇q̇, by a KKT solve.
//!
//! The feet are point contacts held in place (bilateral, no slipping), three rows each in
//! world axes, Jc (12 × 18) and J̇c q̇ from `frame_jacobians` / `frame_acceleration_biases`
//! of four foot frames. With S = [0; I₁₂] selecting the joint torques,
//!
//! ```text
//! [ M   Jcᵀ ] [ q̈  ]   [ S τ − h        ]
//! [ Jc  0   ] [ −λ ] = [ −J̇c q̇ − b(q, q̇) ],   b = 2ζω Jc q̇ + ω² (x_feet − x_feet,0)
//! ```
//!
//! solved by nalgebra's LU of the fixed 30 × 30 matrix (b = 0 without Baumgarte
//! stabilisation; with it ζ = 1, ω = 50 rad/s). λ are the forces of the ground on the feet.
//!
//! (a) Standing still: with q̈ = 0 the six base rows of M q̈ + h = S τ + Jcᵀ λ fix the net
//! contact wrench; the example takes the least-norm λ and the joint rows give τ, then checks
//! that the contact forces carry the weight and that the KKT solve with that τ keeps the
//! robot still.
//!
//! (b) A trot-like sway: the torso is commanded to sway sideways (±2 cm at 1 Hz), bob
//! (±1.5 cm at 2 Hz) and roll (±0.08 rad at 1 Hz). The controller is inverse dynamics with
//! the contacts: the torso's acceleration comes from a PD law on its pose (orientation error
//! log(R_d Rᵀ)), the legs' from the contact rows Jc q̈ = −J̇c q̇, then the least-norm λ and τ as
//! in (a). The plant is the KKT forward dynamics, integrated by semi-implicit Euler at 1 kHz
//! (q̇' = q̇ + q̈ dt, q' = q ⊕ q̇' dt, the quaternion kept unit by the generated `integrate`),
//! for 4 s, once without and once with Baumgarte stabilisation.
//!
//! The declaration below is a copy of `models::quadruped::Quadruped` without its foot loads
//! and with a frame on each foot; the example checks that its M and h equal the bundled
//! model's. Run with `cargo run --release -p models --example quadruped_standing`.

use dynamics_runtime::{mechanism, Dynamics, Mechanism};
use models::quadruped::Quadruped;
use nalgebra::{Quaternion, Rotation3, SMatrix, SVector, UnitQuaternion, Vector3, Vector6};
use std::f64::consts::PI;

mechanism! {
    /// `models::quadruped::Quadruped` without the foot loads, with a frame at each foot.
    pub struct StandingQuadruped;
    gravity: [0.0, 0.0, -9.81];
    outputs: [mass_matrix, bias, forward_dynamics, frame_placements, frame_jacobians,
              frame_acceleration_biases];

    /// The torso, its frame at the mass centre along its principal axes.
    body torso { mass: 3.575, inertia: diag([0.017528444, 0.129944698, 0.143418825]) }
    /// Floating base: position and orientation of the torso in the world.
    joint base: free(ground -> torso);

    body hip_fl { mass: 0.65, com: [0.05016, -0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_fl {
        mass: 0.863,
        com: [0.0, 0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, -0.000261229], [0.0, -0.000261229, 617.145e-6]],
    }
    body shin_fl { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_fl: revolute(torso -> hip_fl) { axis: x, at: [0.23, 0.0805, 0.0] }
    joint hip_fl: revolute(hip_fl -> thigh_fl) { axis: y, at: [0.053, 0.0575, 0.0] }
    joint knee_fl: revolute(thigh_fl -> shin_fl) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_fr { mass: 0.65, com: [0.05016, 0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_fr {
        mass: 0.863,
        com: [0.0, -0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, 0.000261229], [0.0, 0.000261229, 617.145e-6]],
    }
    body shin_fr { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_fr: revolute(torso -> hip_fr) { axis: x, at: [0.23, -0.0805, 0.0] }
    joint hip_fr: revolute(hip_fr -> thigh_fr) { axis: y, at: [0.053, -0.0575, 0.0] }
    joint knee_fr: revolute(thigh_fr -> shin_fr) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_hl { mass: 0.65, com: [-0.05016, -0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_hl {
        mass: 0.863,
        com: [0.0, 0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, -0.000261229], [0.0, -0.000261229, 617.145e-6]],
    }
    body shin_hl { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_hl: revolute(torso -> hip_hl) { axis: x, at: [-0.23, 0.0805, 0.0] }
    joint hip_hl: revolute(hip_hl -> thigh_hl) { axis: y, at: [-0.053, 0.0575, 0.0] }
    joint knee_hl: revolute(thigh_hl -> shin_hl) { axis: y, at: [0.0, 0.0, -0.2] }

    body hip_hr { mass: 0.65, com: [-0.05016, 0.013329, 0.0], inertia: diag([399.183e-6, 708.749e-6, 460.327e-6]) }
    body thigh_hr {
        mass: 0.863,
        com: [0.0, -0.029693, -0.013531],
        inertia: [[2082.653e-6, 0.0, 0.0], [0.0, 2271.664e-6, 0.000261229], [0.0, 0.000261229, 617.145e-6]],
    }
    body shin_hr { mass: 0.119, com: [0.0, 0.0, -0.093811], inertia: diag([827.276e-6, 834.282e-6, 15.950e-6]) }
    joint abduction_hr: revolute(torso -> hip_hr) { axis: x, at: [-0.23, -0.0805, 0.0] }
    joint hip_hr: revolute(hip_hr -> thigh_hr) { axis: y, at: [-0.053, -0.0575, 0.0] }
    joint knee_hr: revolute(thigh_hr -> shin_hr) { axis: y, at: [0.0, 0.0, -0.2] }

    /// Front-left foot, the end of the shin.
    frame foot_fl: on shin_fl at [0.0, 0.0, -0.2];
    /// Front-right foot.
    frame foot_fr: on shin_fr at [0.0, 0.0, -0.2];
    /// Hind-left foot.
    frame foot_hl: on shin_hl at [0.0, 0.0, -0.2];
    /// Hind-right foot.
    frame foot_hr: on shin_hr at [0.0, 0.0, -0.2];
}

type Robot = StandingQuadruped;
type Mass = SMatrix<f64, 18, 18>;
type Gen = SVector<f64, 18>;
type ContactJacobian = SMatrix<f64, 12, 18>;
type Contact = SVector<f64, 12>;

const FEET: [&str; 4] = ["front left", "front right", "hind left", "hind right"];
const GRAVITY: f64 = 9.81;
const DT: f64 = 1e-3;
const SECONDS: f64 = 4.0;
/// Baumgarte stabilisation: ζ = 1, ω = 50 rad/s (ω dt = 0.05).
const BAUMGARTE_OMEGA: f64 = 50.0;
/// Torso pose gains: ω_n = 20 rad/s, critically damped.
const KP: f64 = 400.0;
const KD: f64 = 40.0;
/// Bound on the feet's drift from their stance points with Baumgarte stabilisation (m):
/// about three times the 1e-5 m measured, a quarter of the drift without stabilisation
/// (1.3e-4 m), so a failure means the stabilisation (or the J̇c q̇ it corrects) is broken.
const DRIFT_BOUND: f64 = 3e-5;

/// Everything the contact dynamics needs at (q, q̇), from the generated code.
struct Terms {
    m: Mass,
    h: Gen,
    jc: ContactJacobian,
    jc_dot_v: Contact,
    feet: [Vector3<f64>; 4],
}

fn terms(q: &[f64; 19], v: &[f64; 18]) -> Terms {
    let m_rows = Robot::mass_matrix(q);
    let placements = Robot::frame_placements(q);
    let jacobians = Robot::frame_jacobians(q);
    let biases = Robot::frame_acceleration_biases(q, v);
    Terms {
        m: Mass::from_fn(|i, j| m_rows[i][j]),
        h: Gen::from(Robot::bias(q, v)),
        // The linear rows (0..3) of each foot's 6-row Jacobian and bias.
        jc: ContactJacobian::from_fn(|i, j| jacobians[i / 3][i % 3][j]),
        jc_dot_v: Contact::from_fn(|i, _| biases[i / 3][i % 3]),
        feet: std::array::from_fn(|f| Vector3::from(placements[f].1)),
    }
}

/// q̈ and λ from the KKT system, the contact rows optionally Baumgarte-stabilised towards
/// the stance points.
fn kkt(
    t: &Terms,
    v: &[f64; 18],
    tau: &SVector<f64, 12>,
    stance: Option<&[Vector3<f64>; 4]>,
) -> (Gen, Contact) {
    let mut a = SMatrix::<f64, 30, 30>::zeros();
    a.fixed_view_mut::<18, 18>(0, 0).copy_from(&t.m);
    a.fixed_view_mut::<18, 12>(0, 18)
        .copy_from(&t.jc.transpose());
    a.fixed_view_mut::<12, 18>(18, 0).copy_from(&t.jc);
    let mut rhs = SVector::<f64, 30>::zeros();
    let mut force = -t.h;
    let mut joints = force.fixed_rows_mut::<12>(6);
    joints += tau;
    rhs.fixed_rows_mut::<18>(0).copy_from(&force);
    let mut contact_rhs = -t.jc_dot_v;
    if let Some(stance) = stance {
        let feet_velocity = t.jc * Gen::from(*v);
        let w = BAUMGARTE_OMEGA;
        for f in 0..4 {
            let drift = t.feet[f] - stance[f];
            for k in 0..3 {
                contact_rhs[3 * f + k] -= 2.0 * w * feet_velocity[3 * f + k] + w * w * drift[k];
            }
        }
    }
    rhs.fixed_rows_mut::<12>(18).copy_from(&contact_rhs);
    let x = a
        .lu()
        .solve(&rhs)
        .expect("the KKT matrix is invertible: M > 0 and the feet's rows are independent");
    (x.fixed_rows::<18>(0).into(), -x.fixed_rows::<12>(18))
}

/// Inverse dynamics with the feet held: from the torso's acceleration (the free joint's
/// coordinates, body axes), the legs' accelerations by Jc q̈ = −J̇c q̇, the least-norm
/// contact forces that produce the torso's rows, and the joint torques.
fn contact_inverse_dynamics(
    t: &Terms,
    base_acceleration: &Vector6<f64>,
) -> (SVector<f64, 12>, Contact) {
    let jc_base = t.jc.fixed_view::<12, 6>(0, 0);
    let jc_legs = t.jc.fixed_view::<12, 12>(0, 6).into_owned();
    let legs = jc_legs
        .lu()
        .solve(&(-t.jc_dot_v - jc_base * base_acceleration))
        .expect("the legs are away from their singular (straight-knee) configurations");
    let mut qdd = Gen::zeros();
    qdd.fixed_rows_mut::<6>(0).copy_from(base_acceleration);
    qdd.fixed_rows_mut::<12>(6).copy_from(&legs);
    let required = t.m * qdd + t.h;
    // Jc_bᵀ λ = required[0..6], least norm: λ = Jc_b (Jc_bᵀ Jc_b)⁻¹ required[0..6].
    let gram = jc_base.transpose() * jc_base;
    let y = gram
        .cholesky()
        .expect("the feet span the torso's six motions")
        .solve(&required.fixed_rows::<6>(0).into_owned());
    let lambda = jc_base * y;
    let tau = (required - t.jc.transpose() * lambda)
        .fixed_rows::<12>(6)
        .into_owned();
    (tau, lambda)
}

/// The torso's orientation (q's quaternion is x, y, z, w). Orientation errors are taken
/// between unit quaternions: `Rotation3`'s log map (the acos of the trace) is NaN when
/// rounding puts a near-identity rotation's trace above 3.
fn torso_orientation(q: &[f64; 19]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[6], q[3], q[4], q[5]))
}

fn torso_rotation(q: &[f64; 19]) -> Rotation3<f64> {
    torso_orientation(q).to_rotation_matrix()
}

/// The commanded torso pose and its rates: position, velocity, acceleration (world), roll
/// angle and its two derivatives.
fn commanded(rest: &Vector3<f64>, t: f64) -> ([Vector3<f64>; 3], [f64; 3]) {
    let w = 2.0 * PI;
    let (sway, bob, roll) = (0.02, 0.015, 0.08);
    let (s1, c1) = (w * t).sin_cos();
    let (s2, c2) = (2.0 * w * t).sin_cos();
    let p = rest + Vector3::new(0.0, sway * s1, bob * s2);
    let v = Vector3::new(0.0, sway * w * c1, 2.0 * bob * w * c2);
    let a = Vector3::new(0.0, -sway * w * w * s1, -4.0 * bob * w * w * s2);
    ([p, v, a], [roll * s1, roll * w * c1, -roll * w * w * s1])
}

struct Run {
    drift: [f64; 4],
    position_rms: f64,
    position_max: f64,
    roll_max: f64,
    min_vertical_force: f64,
}

fn trot(q0: &[f64; 19], stabilised: bool) -> Run {
    let ticks = (SECONDS / DT).round() as usize;
    let settle = (1.0 / DT).round() as usize;
    let (mut q, mut v) = (*q0, [0.0; 18]);
    let rest = Vector3::new(q0[0], q0[1], q0[2]);
    let stance = terms(&q, &v).feet;
    let mut run = Run {
        drift: [0.0; 4],
        position_rms: 0.0,
        position_max: 0.0,
        roll_max: 0.0,
        min_vertical_force: f64::INFINITY,
    };
    let mut sum_sq = 0.0;
    for tick in 0..ticks {
        let t = tick as f64 * DT;
        let terms = terms(&q, &v);
        // Torso PD in world axes, then into the free joint's (body-axis) coordinates.
        let r = torso_rotation(&q);
        let v_body = Vector3::new(v[0], v[1], v[2]);
        let w_body = Vector3::new(v[3], v[4], v[5]);
        let ([p_d, v_d, a_d], [roll, roll_rate, roll_acc]) = commanded(&rest, t);
        let p = Vector3::new(q[0], q[1], q[2]);
        let r_d = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), roll);
        let linear = a_d + KD * (v_d - r * v_body) + KP * (p_d - p);
        let angular = roll_acc * Vector3::x()
            + KD * (roll_rate * Vector3::x() - r * w_body)
            + KP * (r_d * torso_orientation(&q).inverse()).scaled_axis();
        let mut base = Vector6::zeros();
        base.fixed_rows_mut::<3>(0)
            .copy_from(&(r.inverse() * linear - w_body.cross(&v_body)));
        base.fixed_rows_mut::<3>(3)
            .copy_from(&(r.inverse() * angular));
        let (tau, _) = contact_inverse_dynamics(&terms, &base);

        let (qdd, lambda) = kkt(&terms, &v, &tau, stabilised.then_some(&stance));
        for f in 0..4 {
            run.min_vertical_force = run.min_vertical_force.min(lambda[3 * f + 2]);
        }
        for k in 0..18 {
            v[k] += qdd[k] * DT;
        }
        q = <Robot as Dynamics<f64>>::integrate(&q, &v, DT);

        let feet = Robot::frame_placements(&q);
        for f in 0..4 {
            let moved = (Vector3::from(feet[f].1) - stance[f]).norm();
            run.drift[f] = run.drift[f].max(moved);
        }
        if tick + 1 >= settle {
            let ([p_d, _, _], [roll, _, _]) = commanded(&rest, t + DT);
            let error = (p_d - Vector3::new(q[0], q[1], q[2])).norm();
            sum_sq += error * error;
            run.position_max = run.position_max.max(error);
            let r_d = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), roll);
            let angle = r_d.angle_to(&torso_orientation(&q));
            run.roll_max = run.roll_max.max(angle);
        }
    }
    run.position_rms = (sum_sq / (ticks + 1 - settle) as f64).sqrt();
    run
}

fn main() {
    // The copy has the bundled model's dynamics.
    let mut q_check = [0.0; 19];
    let mut v_check = [0.0; 18];
    for (k, x) in q_check.iter_mut().enumerate() {
        *x = 0.1 * (k as f64 + 1.0).sin();
    }
    let quaternion = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
    q_check[3..7].copy_from_slice(&[quaternion.i, quaternion.j, quaternion.k, quaternion.w]);
    for (k, x) in v_check.iter_mut().enumerate() {
        *x = 0.5 * (2.0 * k as f64 + 0.3).cos();
    }
    let (m_copy, m_bundled) = (
        Robot::mass_matrix(&q_check),
        Quadruped::mass_matrix(&q_check),
    );
    let (h_copy, h_bundled) = (
        Robot::bias(&q_check, &v_check),
        Quadruped::bias(&q_check, &v_check),
    );
    let differs = m_copy
        .iter()
        .flatten()
        .zip(m_bundled.iter().flatten())
        .chain(h_copy.iter().zip(&h_bundled))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        differs < 1e-12,
        "the copy's M or h differs from models::quadruped by {differs:.1e}"
    );

    // A standing posture: every leg at abduction 0, hip −0.8 rad, knee 1.6 rad; the torso
    // raised so that the feet touch z = 0.
    let mut q = [0.0; 19];
    q[6] = 1.0;
    for leg in 0..4 {
        q[7 + 3 * leg..10 + 3 * leg].copy_from_slice(&[0.0, -0.8, 1.6]);
    }
    let feet = Robot::frame_placements(&q);
    q[2] = -feet.iter().map(|(_, p)| p[2]).sum::<f64>() / 4.0;
    let v = [0.0; 18];

    // (a) Standing still.
    let standing = terms(&q, &v);
    let mass = standing.m[(0, 0)];
    let weight = mass * GRAVITY;
    let (tau, lambda) = contact_inverse_dynamics(&standing, &Vector6::zeros());
    let (qdd, lambda_kkt) = kkt(&standing, &v, &tau, None);
    let total = (0..4).fold(Vector3::zeros(), |sum: Vector3<f64>, f| {
        sum + Vector3::new(lambda[3 * f], lambda[3 * f + 1], lambda[3 * f + 2])
    });
    let weight_error = (total - Vector3::new(0.0, 0.0, weight)).norm();
    println!(
        "{} ({} dof, {mass:.3} kg) standing, torso at z = {:.4} m, feet at z = 0:",
        Robot::NAME,
        Robot::NV,
        q[2]
    );
    for (f, name) in FEET.iter().enumerate() {
        println!(
            "  {name:<12} vertical force {:>8.4} N  (horizontal {:+.4}, {:+.4} N)",
            lambda[3 * f + 2],
            lambda[3 * f],
            lambda[3 * f + 1]
        );
    }
    println!(
        "  sum of contact forces − m g: {weight_error:.1e} N (m g = {weight:.4} N); \
         joint torques up to {:.3} N·m",
        tau.amax()
    );
    println!(
        "  KKT forward dynamics with these torques: max |q̈| = {:.1e}, λ differs by {:.1e} N",
        qdd.amax(),
        (lambda_kkt - lambda).amax()
    );
    assert!(
        weight_error < 1e-9,
        "the contact forces do not carry the weight"
    );
    assert!(
        qdd.amax() < 1e-9,
        "the standing torques do not hold the robot still"
    );

    // (b) The sway, without and with Baumgarte stabilisation.
    println!(
        "Trot-like sway (±2 cm sideways and ±0.08 rad roll at 1 Hz, ±1.5 cm bob at 2 Hz), \
         {SECONDS} s, semi-implicit Euler at 1 kHz:"
    );
    let mut runs = Vec::new();
    for stabilised in [false, true] {
        let run = trot(&q, stabilised);
        println!(
            "  {:<22} feet drift (max distance from stance) {}",
            if stabilised {
                "Baumgarte (ζ 1, ω 50):"
            } else {
                "no stabilisation:"
            },
            run.drift
                .iter()
                .map(|d| format!("{d:.1e}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
        println!(
            "  {:<22} torso position error after 1 s: RMS {:.1e} m, max {:.1e} m; \
             orientation max {:.1e} rad; min vertical foot force {:.2} N",
            "", run.position_rms, run.position_max, run.roll_max, run.min_vertical_force
        );
        runs.push(run);
    }
    let stabilised_drift = runs[1].drift.iter().copied().fold(0.0, f64::max);
    assert!(
        stabilised_drift < DRIFT_BOUND,
        "with Baumgarte stabilisation the feet drift {stabilised_drift:.1e} m > {DRIFT_BOUND} m"
    );
    assert!(runs[1].min_vertical_force > 0.0, "a foot would lift off");
    println!("  ok: stabilised drift below {DRIFT_BOUND:.0e} m, every foot pressed on the ground");
}
