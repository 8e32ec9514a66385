//! The textbook chapter's mechanisms (Satici, *Kinematics and Machine Dynamics*, ch. 10).

use dynamics_runtime::mechanism;

mechanism! {
    /// The textbook's falling rod and driven physical pendulum: a uniform rod, m = 2 kg,
    /// L = 0.6 m, pivoted at one end; θ is measured counterclockwise from the downward
    /// vertical, so the mass centre is at c = PG = (0, −L/2, 0) in the rod frame.
    /// I_O = m L²/3 = 0.24 kg·m²; I_O θ̈ + m g l sin θ = τ.
    pub struct FallingRod;
    gravity: [0.0, -9.81, 0.0];
    force_analysis: planar;

    /// The rod, lying along −y of its frame.
    body rod { mass: 2.0, com: [0.0, -0.3, 0.0], shape: rod(length: 0.6, axis: y) }

    /// The frictionless pivot O, fixed in the ground.
    joint pivot: revolute(ground -> rod) { axis: z }
}

mechanism! {
    /// The textbook's eccentric rotor: a 2 kg rotor whose mass centre sits e = 1 mm off its
    /// spin axis. At ω = 100 rad/s the bearing carries the inertia force m e ω² = 20 N.
    pub struct EccentricRotor;
    gravity: none;
    outputs: [inverse_dynamics, reactions, mass_matrix, energy];

    /// The rotor: a solid disc (radius 5 cm, 2 cm thick) about its spin axis z.
    body rotor { mass: 2.0, com: [0.001, 0.0, 0.0], shape: cylinder(radius: 0.05, length: 0.02, axis: z) }

    /// The bearing.
    joint bearing: revolute(ground -> rotor) { axis: z }
}

mechanism! {
    /// The textbook's gyroscopic example: a free rigid body with I_G = diag(0.2, 0.3, 0.4)
    /// kg·m². Spinning at ω = (1, 2, 3) rad/s with α = 0 it needs M_G = ω × I_G ω =
    /// (0.6, −0.6, 0.2) N·m.
    pub struct GyroscopicBody;
    gravity: none;
    outputs: [inverse_dynamics, mass_matrix, forward_dynamics, energy];

    /// The body, its frame at the mass centre along the principal axes.
    body body { mass: 1.0, inertia: diag([0.2, 0.3, 0.4]) }

    /// Free flight.
    joint flight: free(ground -> body);
}
