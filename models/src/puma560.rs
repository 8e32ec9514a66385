//! The Unimation PUMA 560 with the kinematic and inertial parameters of Armstrong, Khatib and
//! Burdick, "The Explicit Dynamic Model and Inertial Parameters of the PUMA 560 Arm" (ICRA
//! 1986), in modified Denavit–Hartenberg form (as tabulated in Corke's Robotics Toolbox,
//! `mdl_puma560akb`).
//!
//! Modified DH row i (α_{i−1}, a_{i−1}, d_i) places joint i in frame i−1 by
//! RotX(α_{i−1}) · TransX(a_{i−1}) · TransZ(d_i): rotation `rpy(α, 0, 0)` and translation
//! (a, −d sin α, d cos α); every joint turns about its z axis. Mass centres and inertias are
//! in the link frames. This is the model the published operation counts of customized
//! Newton–Euler refer to (Murray and Neuman's ARM: 224 multiplications, 174 additions).

use dynamics_runtime::mechanism;

mechanism! {
    /// The PUMA 560 arm (Armstrong, Khatib and Burdick 1986), gravity −z.
    pub struct Puma560;
    gravity: [0.0, 0.0, -9.81];
    // Link 1 is lumped as a pure moment of inertia about its axis (I_zz = 0.35 kg·m²,
    // I_xx = I_yy = 0), which no real body has.
    allow: [triangle_inequality];

    body link1 { mass: 0.0, inertia: diag([0.0, 0.0, 0.35]) }
    body link2 { mass: 17.4, com: [0.068, 0.006, -0.016], inertia: diag([0.13, 0.524, 0.539]) }
    body link3 { mass: 4.8, com: [0.0, -0.070, 0.014], inertia: diag([0.066, 0.0125, 0.066]) }
    body link4 { mass: 0.82, com: [0.0, 0.0, -0.019], inertia: diag([1.8e-3, 1.8e-3, 1.3e-3]) }
    body link5 { mass: 0.34, inertia: diag([0.3e-3, 0.3e-3, 0.4e-3]) }
    body link6 { mass: 0.09, com: [0.0, 0.0, 0.032], inertia: diag([0.15e-3, 0.15e-3, 0.04e-3]) }

    joint joint1: revolute(ground -> link1) { axis: z }
    joint joint2: revolute(link1 -> link2) { axis: z, at: [0.0, 0.2435, 0.0], rotation: rpy(-pi / 2.0, 0.0, 0.0) }
    joint joint3: revolute(link2 -> link3) { axis: z, at: [0.4318, 0.0, -0.0934] }
    joint joint4: revolute(link3 -> link4) { axis: z, at: [-0.0203, -0.4331, 0.0], rotation: rpy(pi / 2.0, 0.0, 0.0) }
    joint joint5: revolute(link4 -> link5) { axis: z, rotation: rpy(-pi / 2.0, 0.0, 0.0) }
    joint joint6: revolute(link5 -> link6) { axis: z, rotation: rpy(pi / 2.0, 0.0, 0.0) }
}
