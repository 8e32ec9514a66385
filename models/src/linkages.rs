//! Statics and mechanism force analysis (the seed's first and last sections): a supported
//! beam, a crank-rocker four-bar and a slider-crank, each a tree of joints closed by
//! declared constraints, with the driving joint marked `driven`.

use dynamics_runtime::mechanism;

mechanism! {
    /// The seed's supported beam: a 1 m beam with a pin at A and a roller at B, loaded by
    /// 100 N and 200 N downward at 0.2 m and 0.8 m, its weight neglected (no gravity).
    /// Equilibrium gives A_x = 0, A_y = 120 N, B_y = 180 N.
    pub struct SupportedBeam;

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
