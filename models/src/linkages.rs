//! Statics and mechanism force analysis (the textbook's first and last sections): a supported
//! beam, a crank-rocker four-bar and a slider-crank, each a tree of joints closed by
//! declared constraints, with the driving joint marked `driven`; the four-bar with a load
//! on its coupler; and two rotors on a spatial bearing (`force_analysis: spatial;`), the
//! textbook's gyroscopic torque and an overhung, eccentric wobble plate.

use dynamics_runtime::mechanism;

mechanism! {
    /// The textbook's supported beam: a 1 m beam with a pin at A and a roller at B, loaded by
    /// 100 N and 200 N downward at 0.2 m and 0.8 m, its weight neglected (no gravity).
    /// Equilibrium gives A_x = 0, A_y = 120 N, B_y = 180 N.
    pub struct SupportedBeam;
    gravity: none;

    /// The beam along x (its mass plays no part at rest).
    body beam { mass: 4.0, com: [0.5, 0.0, 0.0], shape: rod(length: 1.0, axis: x) }

    /// The pin at A, at the world origin.
    joint A: revolute(ground -> beam) { axis: z }

    /// The roller at B: pushes along the ground's y.
    constraint B: roller(ground at [1.0, 0.0, 0.0], beam at [1.0, 0.0, 0.0]) { normal: y };

    /// 100 N at 0.2 m (inputs in the beam frame).
    load P1: force on beam at [0.2, 0.0, 0.0];
    /// 200 N at 0.8 m.
    load P2: force on beam at [0.8, 0.0, 0.0];
}

mechanism! {
    /// A crank-rocker four-bar (Grashof: 0.1 + 0.35 ≤ 0.3 + 0.3), driven at the crank. Ground
    /// pivots O2 = (0, 0) and O4 = (0.3, 0); crank a = 0.1 m, coupler b = 0.35 m, rocker
    /// c = 0.3 m; links are uniform rods along their x axes; gravity along −y. Coordinates:
    /// crank angle, coupler angle relative to the crank, rocker angle.
    pub struct FourBar;
    gravity: [0.0, -9.81, 0.0];

    /// The crank, O2 to A.
    body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    /// The coupler, A to B.
    body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
    /// The rocker, O4 to B.
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }

    /// The crank's ground pivot O2, driven by the input torque.
    joint O2: revolute(ground -> crank) { axis: z, driven: true }
    /// The crank–coupler pin A.
    joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
    /// The rocker's ground pivot O4.
    joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z }
    /// The coupler–rocker pin B closes the loop.
    constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
}

mechanism! {
    /// The same four-bar driven at the rocker (a treadle): when the crank and the coupler
    /// are collinear the rocker cannot turn the crank (a dead-centre position), and the
    /// force analysis is singular there.
    pub struct FourBarRockerDriven;
    gravity: [0.0, -9.81, 0.0];

    /// The crank, O2 to A.
    body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    /// The coupler, A to B.
    body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
    /// The rocker, O4 to B.
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }

    /// The crank's ground pivot O2.
    joint O2: revolute(ground -> crank) { axis: z }
    /// The crank–coupler pin A.
    joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
    /// The rocker's ground pivot O4, driven.
    joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z, driven: true }
    /// The coupler–rocker pin B closes the loop.
    constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);
}

mechanism! {
    /// An in-line slider-crank: crank r = 0.1 m driven at O, connecting rod l = 0.4 m, a
    /// 0.8 kg slider on the ground's x axis; gravity along −y. Coordinates: crank angle, rod
    /// angle relative to the crank, slider angle relative to the rod.
    pub struct SliderCrank;
    gravity: [0.0, -9.81, 0.0];

    /// The crank, O to A.
    body crank { mass: 0.6, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    /// The connecting rod, A to B.
    body rod { mass: 1.1, com: [0.2, 0.0, 0.0], shape: rod(length: 0.4, axis: x) }
    /// The slider (piston), its frame at the wrist pin B.
    body slider { mass: 0.8, inertia: diag([0.0004, 0.0004, 0.0004]) }

    /// The crank's pivot O, driven.
    joint O: revolute(ground -> crank) { axis: z, driven: true }
    /// The crank pin A.
    joint A: revolute(crank -> rod) { at: [0.1, 0.0, 0.0], axis: z }
    /// The wrist pin B.
    joint B: revolute(rod -> slider) { at: [0.4, 0.0, 0.0], axis: z }
    /// The guide: the slider moves along the ground's x axis without turning.
    constraint guide: prismatic(ground at [0.0, 0.0, 0.0], slider at [0.0, 0.0, 0.0]) { axis: x };
}

mechanism! {
    /// The crank-rocker four-bar of [`FourBar`] carrying a load on its coupler, for the
    /// forward dynamics of a closed loop with applied forces: a force given in the coupler's
    /// frame (a follower load, the run-time input `loads`) at (0.2, 0.05) m from A, off the
    /// line A–B. The tree's inverse dynamics is generated beside the constrained defaults:
    /// `inverse_dynamics(q, v, 0, loads)` = C q̇ + g − Q is the bias with the load's
    /// generalized force Q taken off, which `bias` (no loads input) cannot give.
    pub struct FourBarLoaded;
    gravity: [0.0, -9.81, 0.0];
    outputs: [force_analysis, constraints, mass_matrix, bias, energy, inverse_dynamics];

    /// The crank, O2 to A.
    body crank { mass: 0.5, com: [0.05, 0.0, 0.0], shape: rod(length: 0.1, axis: x) }
    /// The coupler, A to B.
    body coupler { mass: 1.2, com: [0.175, 0.0, 0.0], shape: rod(length: 0.35, axis: x) }
    /// The rocker, O4 to B.
    body rocker { mass: 1.0, com: [0.15, 0.0, 0.0], shape: rod(length: 0.3, axis: x) }

    /// The crank's ground pivot O2, driven by the input torque.
    joint O2: revolute(ground -> crank) { axis: z, driven: true }
    /// The crank–coupler pin A.
    joint A: revolute(crank -> coupler) { at: [0.1, 0.0, 0.0], axis: z }
    /// The rocker's ground pivot O4.
    joint O4: revolute(ground -> rocker) { at: [0.3, 0.0, 0.0], axis: z }
    /// The coupler–rocker pin B closes the loop.
    constraint B: pin(coupler at [0.35, 0.0, 0.0], rocker at [0.3, 0.0, 0.0]);

    /// A force on the coupler, components in the coupler's frame.
    load F: force on coupler at [0.2, 0.05, 0.0];
}

mechanism! {
    /// The textbook's gyroscopic torque, held by a bearing (spatial force analysis): a rotor of
    /// 2 kg with I_G = diag(0.2, 0.3, 0.4) kg·m², its mass centre on the bearing, turning on
    /// a fixed axis along (1, 2, 3) in its own frame, so that θ̇ = √14 rad/s is
    /// ω = (1, 2, 3) rad/s. At θ = 0, θ̇ = √14 rad/s, θ̈ = 0 the bearing supplies the couple
    /// ω × I_G ω = (0.6, −0.6, 0.2) N·m, normal to the axis n: its component along n, the
    /// driving torque, is zero (no power); across it, along n₁ = (0, 3, −2)/√13 and
    /// n₂ = n × n₁ = (−13, 2, 3)/√182, `spin.couple1` = −2.2/√13 = −0.61017 N·m and
    /// `spin.couple2` = −8.4/√182 = −0.62265 N·m; the bearing's force is the weight,
    /// 19.62 N up. Gravity along −z.
    pub struct GyroscopicRotor;
    gravity: [0.0, 0.0, -9.81];
    force_analysis: spatial;
    outputs: [force_analysis, inverse_dynamics];

    /// The rotor: principal axes along its frame, mass centre at the bearing.
    body rotor { mass: 2.0, inertia: diag([0.2, 0.3, 0.4]) }

    /// The bearing: a spatial hinge (three forces, two couples across the axis) at the
    /// world origin, driven (its torque is the sixth unknown).
    joint spin: revolute(ground -> rotor) { axis: [1.0, 2.0, 3.0] }
}

mechanism! {
    /// An overhung rotor on one long bearing (spatial force analysis): a shaft along x held
    /// at the origin by a spatial hinge (three forces and the two couples across the shaft)
    /// and driven there, carrying a 2 kg disc 0.3 m out whose mass centre is 1 mm off the
    /// axis (the textbook's eccentricity example, m e ω² = 20 N at 100 rad/s) and whose
    /// principal axes are turned 0.1 rad about z (a wobble plate: the spin axis is not
    /// principal, so spinning needs a gyroscopic couple), with a pull at the rim (the
    /// run-time input `loads`, in the disc's frame). Gravity along −z.
    ///
    /// At θ = 0, θ̇ = 100 rad/s, θ̈ = 0 and no pull the bearing supplies the force
    /// (0, −20, 19.62) N (the centripetal 20 N toward the axis, the weight) and the couple
    /// (0.01962, −5.886, −1.0333) N·m: about x the driving torque that holds the weight 1 mm
    /// off the axis, 0.001 × 19.62; about y the weight's arm, −0.3 × 19.62; about z the
    /// centripetal force's arm, −0.3 × 20 = −6, plus the wobble plate's ω × I_G ω =
    /// ω² I_xy = 10⁴ × 0.0025 sin 0.2 = 4.9667 N·m.
    pub struct OverhungRotor;
    gravity: [0.0, 0.0, -9.81];
    force_analysis: spatial;
    outputs: [force_analysis, inverse_dynamics];

    /// The shaft and disc, its principal moments (0.01, 0.005, 0.005) kg·m² turned 0.1 rad
    /// about z.
    body disc {
        mass: 2.0,
        com: [0.3, 0.001, 0.0],
        inertia: principal([0.01, 0.005, 0.005], rotation: rpy(0.0, 0.0, 0.1)),
    }

    /// The bearing at the origin, axis along the shaft.
    joint bearing: revolute(ground -> disc) { axis: x }

    /// A pull at the disc's rim, components in the disc's frame.
    load pull: force on disc at [0.3, 0.1, 0.0];
}
