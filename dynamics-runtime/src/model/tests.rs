//! One test per validation rule of the runtime model: the error and its message.

use super::*;

fn rod(name: &str) -> BodySpec {
    BodySpec::new(
        name,
        Inertia::new(
            1.0,
            [0.0, -0.5, 0.0],
            [[0.02, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.02]],
        ),
    )
}

fn pendulum() -> ModelBuilder {
    ModelBuilder::new()
        .gravity([0.0, -9.81, 0.0])
        .body(rod("rod"))
        .joint(JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0]))
}

/// The single error a builder reports, and its message.
fn only_error(builder: ModelBuilder) -> (ModelError, String) {
    let errors = builder.build().expect_err("ill-posed");
    assert_eq!(errors.0.len(), 1, "{errors}");
    let e = errors.0[0].clone();
    let message = e.to_string();
    (e, message)
}

fn with_body_inertia(mass: f64, com: [f64; 3], inertia: [[f64; 3]; 3]) -> ModelBuilder {
    ModelBuilder::new()
        .body(BodySpec::new("b", Inertia::new(mass, com, inertia)))
        .joint(JointSpec::revolute("j", GROUND, "b", [0.0, 0.0, 1.0]))
}

#[test]
fn a_valid_pendulum_builds() {
    let model = pendulum().build().expect("valid");
    assert_eq!((model.nq(), model.nv()), (1, 1));
    assert_eq!(model.bodies()[0].name, "rod");
}

#[test]
fn negative_mass() {
    let (e, m) = only_error(with_body_inertia(
        -2.0,
        [0.1, 0.0, 0.0],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ));
    assert_eq!(
        e,
        ModelError::NegativeMass {
            body: "b".into(),
            mass: -2.0
        }
    );
    assert!(m.contains("body `b`: mass is -2 kg"), "{m}");
}

#[test]
fn non_finite_values() {
    let (e, m) = only_error(with_body_inertia(
        f64::NAN,
        [0.1, 0.0, 0.0],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ));
    assert!(
        matches!(e, ModelError::NonFinite { field: "mass", .. }),
        "{e:?}"
    );
    assert!(m.contains("not a finite number"), "{m}");
    let (e, _) = only_error(pendulum().gravity([0.0, f64::INFINITY, 0.0]));
    assert!(
        matches!(e, ModelError::NonFinite { field: "y", .. }),
        "{e:?}"
    );
}

#[test]
fn inertia_not_symmetric() {
    let (e, m) = only_error(with_body_inertia(
        1.0,
        [0.1, 0.0, 0.0],
        [[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ));
    assert_eq!(
        e,
        ModelError::InertiaNotSymmetric {
            body: "b".into(),
            row: 0,
            col: 1,
            upper: 0.2,
            lower: 0.0
        }
    );
    assert!(m.contains("I[0][1] = 0.2 but I[1][0] = 0"), "{m}");
}

#[test]
fn inertia_not_positive() {
    let (e, m) = only_error(with_body_inertia(
        1.0,
        [0.1, 0.0, 0.0],
        [[-0.5, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ));
    assert!(
        matches!(e, ModelError::InertiaNotPositive { ref principal_moments, .. } if principal_moments[0] == -0.5),
        "{e:?}"
    );
    assert!(m.contains("not positive semi-definite"), "{m}");
}

/// A placeholder `base` (alone, 1e-6 + 1e-6 < 1e-5) welded to `trunk` with `inertia`, on a
/// free joint, and a leg on a revolute joint.
fn placeholder_base(trunk: [[f64; 3]; 3]) -> ModelBuilder {
    let diagonal = |d: [f64; 3]| [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]];
    ModelBuilder::new()
        .body(BodySpec::new(
            "base",
            Inertia::new(0.001, [0.0; 3], diagonal([1e-6, 1e-6, 1e-5])),
        ))
        .body(BodySpec::new(
            "trunk",
            Inertia::new(6.0, [0.01, 0.0, 0.02], trunk),
        ))
        .body(rod("leg"))
        .joint(JointSpec::free_flyer("root", "base"))
        .joint(JointSpec::fixed("weld", "base", "trunk").at([0.02, 0.0, 0.01]))
        .joint(JointSpec::revolute("hip", "trunk", "leg", [0.0, 1.0, 0.0]))
}

#[test]
fn inertia_rules_judge_bodies_merged_through_fixed_joints() {
    let model = placeholder_base([[0.05, 0.0, 0.0], [0.0, 0.12, 0.0], [0.0, 0.0, 0.14]])
        .build()
        .expect("the merged body is physical");
    assert_eq!(model.bodies()[0].inertia.mass, 6.001);
    let (e, m) = only_error(placeholder_base([
        [0.1, 0.0, 0.0],
        [0.0, 0.1, 0.0],
        [0.0, 0.0, 0.3],
    ]));
    assert!(
        matches!(e, ModelError::TriangleInequality { ref body, ref welded, .. }
            if body == "base" && welded == &["trunk"]),
        "{e:?}"
    );
    assert!(
        m.starts_with("body `base` merged with `trunk` (welded through fixed joints): principal"),
        "{m}"
    );
    // Welded to the ground, the bodies are merged too.
    let ground = |kind: JointType| {
        let mut weld = JointSpec::revolute("bolt", GROUND, "trunk", [0.0, 0.0, 1.0]);
        weld.kind = kind;
        ModelBuilder::new()
            .body(BodySpec::new(
                "stand",
                Inertia::new(
                    0.001,
                    [0.0; 3],
                    [[1e-6, 0.0, 0.0], [0.0, 1e-6, 0.0], [0.0, 0.0, 1e-5]],
                ),
            ))
            .body(BodySpec::new(
                "trunk",
                Inertia::new(
                    2.0,
                    [0.0, 0.0, 0.1],
                    [[0.05, 0.0, 0.0], [0.0, 0.05, 0.0], [0.0, 0.0, 0.05]],
                ),
            ))
            .body(rod("leg"))
            .joint(JointSpec::fixed("stand_weld", GROUND, "stand"))
            .joint(weld)
            .joint(JointSpec::revolute("hip", "trunk", "leg", [0.0, 1.0, 0.0]))
    };
    ground(JointType::Fixed).build().expect("merged, physical");
    let (e, _) = only_error(ground(JointType::Revolute));
    assert!(
        matches!(e, ModelError::TriangleInequality { ref body, ref welded, .. }
            if body == "stand" && welded.is_empty()),
        "{e:?}"
    );
}

#[test]
fn triangle_inequality() {
    let (e, m) = only_error(with_body_inertia(
        1.0,
        [0.1, 0.0, 0.0],
        [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.3]],
    ));
    assert!(matches!(e, ModelError::TriangleInequality { .. }), "{e:?}");
    assert!(m.contains("I1 + I2 ≥ I3"), "{m}");
    // The waiver accepts it.
    with_body_inertia(
        1.0,
        [0.1, 0.0, 0.0],
        [[0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.3]],
    )
    .skip_triangle_inequality()
    .build()
    .expect("waived");
}

#[test]
fn zero_axis() {
    let builder = ModelBuilder::new()
        .body(rod("rod"))
        .joint(JointSpec::revolute("pivot", GROUND, "rod", [0.0; 3]));
    let (e, m) = only_error(builder);
    assert_eq!(
        e,
        ModelError::ZeroAxis {
            joint: "pivot".into(),
            axis: [0.0; 3]
        }
    );
    assert!(
        m.contains("joint `pivot`: axis [0, 0, 0] has zero length"),
        "{m}"
    );
}

#[test]
fn non_finite_axis() {
    let builder = ModelBuilder::new()
        .body(rod("rod"))
        .joint(JointSpec::revolute(
            "pivot",
            GROUND,
            "rod",
            [0.0, f64::NAN, 1.0],
        ));
    let (e, _) = only_error(builder);
    assert!(
        matches!(e, ModelError::NonFinite { field: "axis", .. }),
        "{e:?}"
    );
}

#[test]
fn rotation_not_orthonormal() {
    let joint = JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0]).placed(
        [0.0; 3],
        [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    );
    let (e, m) = only_error(ModelBuilder::new().body(rod("rod")).joint(joint));
    assert!(
        matches!(e, ModelError::RotationNotOrthonormal { .. }),
        "{e:?}"
    );
    assert!(m.contains("not orthonormal"), "{m}");
}

#[test]
fn rotation_improper() {
    let joint = JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0]).placed(
        [0.0; 3],
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]],
    );
    let (e, m) = only_error(ModelBuilder::new().body(rod("rod")).joint(joint));
    assert_eq!(
        e,
        ModelError::RotationImproper {
            joint: "pivot".into(),
            determinant: -1.0
        }
    );
    assert!(m.contains("determinant -1"), "{m}");
}

#[test]
fn negative_armature_and_damping() {
    let builder = ModelBuilder::new().body(rod("rod")).joint(
        JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0])
            .with_armature(-0.1)
            .with_damping(-2.0),
    );
    let errors = builder.build().expect_err("ill-posed").0;
    assert_eq!(
        errors,
        [
            ModelError::NegativeJointCoefficient {
                joint: "pivot".into(),
                field: "armature",
                value: -0.1
            },
            ModelError::NegativeJointCoefficient {
                joint: "pivot".into(),
                field: "damping",
                value: -2.0
            },
        ]
    );
}

#[test]
fn unknown_parent_and_child() {
    let builder = ModelBuilder::new()
        .body(rod("rod"))
        .joint(JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0]))
        .joint(JointSpec::revolute("elbow", "arm", "hand", [0.0, 0.0, 1.0]));
    let errors = builder.build().expect_err("ill-posed").0;
    assert!(
        errors.contains(&ModelError::UnknownBody {
            joint: "elbow".into(),
            role: "parent",
            name: "arm".into()
        }),
        "{errors:?}"
    );
    assert!(
        errors.contains(&ModelError::UnknownBody {
            joint: "elbow".into(),
            role: "child",
            name: "hand".into()
        }),
        "{errors:?}"
    );
    assert!(errors[0]
        .to_string()
        .contains("joint `elbow`: parent `arm` is not a declared body"));
}

#[test]
fn duplicate_names() {
    let errors = pendulum()
        .body(rod("rod"))
        .build()
        .expect_err("ill-posed")
        .0;
    assert_eq!(
        errors[0],
        ModelError::DuplicateName {
            kind: "body",
            name: "rod".into()
        }
    );
    let errors = pendulum()
        .body(rod("tip"))
        .joint(JointSpec::fixed("pivot", "rod", "tip"))
        .build()
        .expect_err("ill-posed")
        .0;
    assert_eq!(
        errors[0],
        ModelError::DuplicateName {
            kind: "joint",
            name: "pivot".into()
        }
    );
    assert!(errors[0]
        .to_string()
        .contains("two joints are named `pivot`"));
    // The ground's name is taken.
    let (e, _) = only_error(ModelBuilder::new().body(rod(GROUND)));
    assert_eq!(
        e,
        ModelError::DuplicateName {
            kind: "body",
            name: GROUND.into()
        }
    );
}

#[test]
fn two_parents() {
    let builder = pendulum().joint(JointSpec::revolute(
        "second",
        GROUND,
        "rod",
        [0.0, 0.0, 1.0],
    ));
    let (e, m) = only_error(builder);
    assert_eq!(
        e,
        ModelError::TwoParents {
            body: "rod".into(),
            first_joint: "pivot".into(),
            second_joint: "second".into()
        }
    );
    assert!(m.contains("moved by two joints"), "{m}");
}

#[test]
fn cycle() {
    let builder = ModelBuilder::new()
        .body(rod("a"))
        .body(rod("b"))
        .joint(JointSpec::revolute("ab", "a", "b", [0.0, 0.0, 1.0]))
        .joint(JointSpec::revolute("ba", "b", "a", [0.0, 0.0, 1.0]));
    let (e, m) = only_error(builder);
    assert_eq!(
        e,
        ModelError::Cycle {
            bodies: vec!["a".into(), "b".into()]
        }
    );
    assert!(m.contains("cycle through bodies `a`, `b`"), "{m}");
}

#[test]
fn not_connected() {
    let (e, m) = only_error(pendulum().body(rod("loose")));
    assert_eq!(
        e,
        ModelError::NotConnected {
            body: "loose".into()
        }
    );
    assert!(
        m.contains("body `loose` is not connected to the ground"),
        "{m}"
    );
}

#[test]
fn self_joint_and_ground_as_child() {
    let (e, _) =
        only_error(pendulum().joint(JointSpec::revolute("spin", "rod", "rod", [0.0, 0.0, 1.0])));
    assert_eq!(
        e,
        ModelError::SelfJoint {
            joint: "spin".into()
        }
    );
    let (e, _) = only_error(pendulum().joint(JointSpec::fixed("weld", "rod", GROUND)));
    assert_eq!(
        e,
        ModelError::GroundAsChild {
            joint: "weld".into()
        }
    );
}

#[test]
fn free_flyer_must_be_on_the_ground() {
    let (e, m) = only_error(pendulum().body(rod("drone")).joint(JointSpec {
        parent: "rod".into(),
        ..JointSpec::free_flyer("float", "drone")
    }));
    assert_eq!(
        e,
        ModelError::FreeFlyerNotOnGround {
            joint: "float".into(),
            parent: "rod".into()
        }
    );
    assert!(m.contains("must attach its body to the ground"), "{m}");
}

#[test]
fn massless_subtree() {
    let builder = ModelBuilder::new()
        .body(BodySpec::new("frame", Inertia::zero()))
        .joint(JointSpec::revolute(
            "spin",
            GROUND,
            "frame",
            [0.0, 0.0, 1.0],
        ));
    let (e, m) = only_error(builder);
    assert_eq!(
        e,
        ModelError::MasslessSubtree {
            body: "frame".into(),
            joint: "spin".into()
        }
    );
    assert!(m.contains("zero mass and zero inertia"), "{m}");
}

/// A mechanism used for its kinematics only may have massless coordinates.
#[test]
fn massless_subtree_allowed_for_kinematics() {
    let model = ModelBuilder::new()
        .body(BodySpec::new("frame", Inertia::zero()))
        .joint(JointSpec::revolute(
            "spin",
            GROUND,
            "frame",
            [0.0, 0.0, 1.0],
        ))
        .allow_coordinates_without_inertia()
        .build()
        .expect("allowed");
    assert_eq!(model.nv(), 1);
}

#[test]
fn errors_are_collected() {
    let errors = ModelBuilder::new()
        .body(BodySpec::new(
            "a",
            Inertia::new(
                -1.0,
                [0.0; 3],
                [[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            ),
        ))
        .joint(JointSpec::revolute("j", GROUND, "a", [0.0; 3]))
        .build()
        .expect_err("ill-posed");
    assert_eq!(errors.0.len(), 3, "{errors}");
    assert_eq!(errors.to_string().lines().count(), 3);
}

#[test]
fn fixed_joints_merge_into_composite_bodies() {
    // Two 1 kg point masses, one merged through a fixed joint 1 m along x: the composite
    // body has 2 kg at x = 0.5 and I_zz about its centre = 2 · 1 · 0.5² = 0.5.
    let point = |name: &str| BodySpec::new(name, Inertia::new(1.0, [0.0; 3], [[0.0; 3]; 3]));
    let model = ModelBuilder::new()
        .body(point("a"))
        .body(point("b"))
        .joint(JointSpec::revolute("j", GROUND, "a", [0.0, 0.0, 1.0]).at([0.0, 0.0, 1.0]))
        .joint(JointSpec::fixed("weld", "a", "b").at([1.0, 0.0, 0.0]))
        .build()
        .expect("valid");
    assert_eq!(model.bodies().len(), 1);
    let inertia = &model.bodies()[0].inertia;
    assert_eq!(inertia.mass, 2.0);
    assert_eq!(inertia.com_in_body.x, 0.5);
    assert!((inertia.inertia_com_in_body[(2, 2)] - 0.5).abs() < 1e-15);
    let frame = model.frame("b").expect("kept as a frame");
    assert_eq!(
        (frame.body, frame.placement_in_body.translation.x),
        (Some(0), 1.0)
    );
}

#[test]
fn model_with_wrong_parameter_count_is_an_error() {
    let e = ModelError::ParameterCount {
        expected: 2,
        got: 1,
    };
    assert_eq!(
        e.to_string(),
        "the mechanism declares 2 parameters but 1 values were given"
    );
}

/// Issue item 8: an axis component above 1.4e154 overflowed |a|² and the axis became zero;
/// it is normalized by its largest component first.
#[test]
fn a_huge_axis_is_a_unit_axis() {
    let model = ModelBuilder::new()
        .body(rod("rod"))
        .joint(JointSpec::revolute(
            "pivot",
            GROUND,
            "rod",
            [0.0, 0.0, 1e300],
        ))
        .build()
        .expect("valid");
    match model.bodies()[0].joint.kind {
        JointKind::Revolute { axis_in_joint } => {
            assert_eq!(axis_in_joint, Vector3::new(0.0, 0.0, 1.0))
        }
        ref other => panic!("{other:?}"),
    }
}

/// Issue item 9: armature is inertia of the coordinate, M = [armature] for a massless slider.
#[test]
fn armature_gives_a_massless_subtree_inertia() {
    ModelBuilder::new()
        .body(BodySpec::new(
            "carriage",
            Inertia::new(0.0, [0.0; 3], [[0.0; 3]; 3]),
        ))
        .joint(
            JointSpec::prismatic("slide", GROUND, "carriage", [1.0, 0.0, 0.0]).with_armature(0.5),
        )
        .build()
        .expect("M = [0.5] is not singular");
}

/// A revolute link `arm` carrying, through a fixed joint, a `hand` placed and turned.
fn arm_with_hand() -> ModelBuilder {
    let quarter_turn_z = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    pendulum()
        .body(rod("arm"))
        .body(rod("hand"))
        .joint(JointSpec::revolute("shoulder", "rod", "arm", [0.0, 0.0, 1.0]).at([0.0, -1.0, 0.0]))
        .joint(JointSpec::fixed("wrist", "arm", "hand").placed([0.5, 0.0, 0.0], quarter_turn_z))
}

#[test]
fn declared_frames_follow_the_body_frames() {
    let half_turn_x = [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]];
    let model = arm_with_hand()
        .frame(FrameSpec::new("tool", "hand").placed([0.1, 0.2, 0.0], half_turn_x))
        .frame(FrameSpec::new("marker", GROUND).at([1.0, 2.0, 3.0]))
        .frame(FrameSpec::new("elbow", "arm").at([0.0, 0.0, 0.3]))
        .build()
        .expect("valid");
    let names: Vec<&str> = model.frames().iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["rod", "arm", "hand", "tool", "marker", "elbow"]);
    assert_eq!(model.frame_index("tool"), Some(3));
    assert_eq!(model.frame_index("nowhere"), None);
    // `tool` is on `hand`, merged into `arm` (tree body 1): hand's placement in arm, then
    // the tool's in hand.
    let hand = model.frame("hand").expect("hand");
    let tool = model.frame("tool").expect("tool");
    assert_eq!((hand.body, tool.body), (Some(1), Some(1)));
    let expected = hand
        .placement_in_body
        .compose(&Placement::new([0.1, 0.2, 0.0], half_turn_x));
    assert_eq!(tool.placement_in_body, expected);
    // By hand: hand at (0.5, 0, 0) turned +90° about z, so the tool's origin is at
    // (0.5 − 0.2, 0.1, 0) and its x axis along the arm's y.
    assert_eq!(
        tool.placement_in_body.translation,
        Vector3::new(0.3, 0.1, 0.0)
    );
    assert_eq!(
        tool.placement_in_body.rotation.column(0),
        Vector3::new(0.0, 1.0, 0.0)
    );
    let marker = model.frame("marker").expect("marker");
    assert_eq!(marker.body, None);
    assert_eq!(
        marker.placement_in_body,
        Placement::translation([1.0, 2.0, 3.0])
    );
    let elbow = model.frame("elbow").expect("elbow");
    assert_eq!(elbow.body, Some(1));
    assert_eq!(
        elbow.placement_in_body,
        Placement::translation([0.0, 0.0, 0.3])
    );
}

#[test]
fn frame_on_an_unknown_body() {
    let (e, m) = only_error(pendulum().frame(FrameSpec::new("tool", "claw")));
    assert_eq!(
        e,
        ModelError::UnknownFrameBody {
            frame: "tool".into(),
            body: "claw".into()
        }
    );
    assert!(
        m.contains("frame `tool`: body `claw` is not a declared body"),
        "{m}"
    );
}

#[test]
fn frame_names_are_unique_among_all_frames() {
    let (e, m) = only_error(pendulum().frame(FrameSpec::new("rod", "rod")));
    assert!(
        matches!(e, ModelError::DuplicateFrameName { ref frame, taken_by } if frame == "rod" && taken_by.starts_with("a body")),
        "{e:?}"
    );
    assert!(
        m.contains("frame `rod`: the name is already taken by a body"),
        "{m}"
    );
    let (e, _) = only_error(pendulum().frame(FrameSpec::new(GROUND, "rod")));
    assert_eq!(
        e,
        ModelError::DuplicateFrameName {
            frame: GROUND.into(),
            taken_by: "the ground"
        }
    );
    let (e, m) = only_error(
        pendulum()
            .frame(FrameSpec::new("tip", "rod"))
            .frame(FrameSpec::new("tip", GROUND)),
    );
    assert_eq!(
        e,
        ModelError::DuplicateFrameName {
            frame: "tip".into(),
            taken_by: "another frame"
        }
    );
    assert!(m.contains("already taken by another frame"), "{m}");
}

#[test]
fn frame_numbers_must_be_finite() {
    let errors = pendulum()
        .frame(FrameSpec::new("tool", "rod").placed(
            [0.0, f64::NAN, 0.0],
            [[1.0, 0.0, 0.0], [0.0, f64::INFINITY, 0.0], [0.0, 0.0, 1.0]],
        ))
        .build()
        .expect_err("ill-posed")
        .0;
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(
        matches!(&errors[0], ModelError::NonFinite { item, field: "translation", value } if item == "frame `tool`" && value.is_nan()),
        "{errors:?}"
    );
    assert!(
        matches!(&errors[1], ModelError::NonFinite { field: "rotation", value, .. } if *value == f64::INFINITY),
        "{errors:?}"
    );
}

#[test]
fn frame_rotation_must_be_proper() {
    let sheared = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let (e, m) =
        only_error(pendulum().frame(FrameSpec::new("tool", "rod").placed([0.0; 3], sheared)));
    assert!(
        matches!(e, ModelError::FrameRotationNotOrthonormal { ref frame, deviation } if frame == "tool" && (deviation - 0.1).abs() < 1e-12),
        "{e:?}"
    );
    assert!(
        m.contains("frame `tool`: placement rotation is not orthonormal"),
        "{m}"
    );
    let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    let (e, m) =
        only_error(pendulum().frame(FrameSpec::new("tool", "rod").placed([0.0; 3], mirror)));
    assert_eq!(
        e,
        ModelError::FrameRotationImproper {
            frame: "tool".into(),
            determinant: -1.0
        }
    );
    assert!(m.contains("determinant -1, a reflection"), "{m}");
}

#[test]
fn frame_errors_are_collected_with_the_tree_errors() {
    let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    let errors = pendulum()
        .body(rod("loose"))
        .frame(FrameSpec::new("a", "claw"))
        .frame(FrameSpec::new("loose", "rod").placed([0.0; 3], mirror))
        .frame(FrameSpec::new("on_loose", "loose"))
        .build()
        .expect_err("ill-posed");
    assert_eq!(
        errors.0,
        [
            ModelError::FrameRotationImproper {
                frame: "loose".into(),
                determinant: -1.0
            },
            ModelError::NotConnected {
                body: "loose".into()
            },
            ModelError::UnknownFrameBody {
                frame: "a".into(),
                body: "claw".into()
            },
            ModelError::DuplicateFrameName {
                frame: "loose".into(),
                taken_by: "a body (every declared body is a frame)"
            },
        ]
    );
    assert_eq!(errors.to_string().lines().count(), 4);
}

#[test]
fn loads_are_placed_on_the_tree_body_and_numbered() {
    // A force on a body welded 1 m along x and turned a quarter turn about z: its point and
    // the declared body's axes are carried into the moving body's frame.
    let quarter = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
    let model = pendulum()
        .body(rod("tip"))
        .joint(JointSpec::fixed("weld", "rod", "tip").placed([1.0, 0.0, 0.0], quarter))
        .load(LoadSpec::force("push", "tip").at([0.5, 0.0, 0.0]))
        .load(LoadSpec::wrench("wind", "rod").in_world())
        .load(LoadSpec::couple("twist", "rod").in_frame(LoadFrame::Body))
        .build()
        .expect("valid");
    let loads = model.loads();
    assert_eq!(model.num_load_inputs(), 12);
    assert_eq!(
        loads
            .iter()
            .map(|l| (l.name.as_str(), l.kind, l.frame, l.body, l.input_offset))
            .collect::<Vec<_>>(),
        [
            ("push", LoadType::Force, LoadFrame::Body, Some(0), 0),
            ("wind", LoadType::Wrench, LoadFrame::World, Some(0), 3),
            ("twist", LoadType::Couple, LoadFrame::Body, Some(0), 9),
        ]
    );
    let push = &loads[0].placement_in_body;
    assert!((push.translation - nalgebra::Vector3::new(1.0, 0.5, 0.0)).amax() < 1e-15);
    assert_eq!(push.rotation, matrix_from_rows(quarter));
}

#[test]
fn a_load_names_a_declared_body_and_a_name_of_its_own() {
    let (e, message) = only_error(pendulum().load(LoadSpec::force("push", "rdo")));
    assert_eq!(
        e,
        ModelError::UnknownLoadBody {
            load: "push".into(),
            body: "rdo".into()
        }
    );
    assert!(message.contains("load `push`: body `rdo` is not a declared body"));
    let (e, _) = only_error(pendulum().load(LoadSpec::force("push", GROUND)));
    assert!(matches!(e, ModelError::UnknownLoadBody { .. }));
    let (e, message) = only_error(
        pendulum()
            .load(LoadSpec::force("push", "rod"))
            .load(LoadSpec::couple("push", "rod")),
    );
    assert_eq!(
        e,
        ModelError::DuplicateName {
            kind: "load",
            name: "push".into()
        }
    );
    assert!(message.contains("two loads are named `push`"));
    let (e, _) = only_error(pendulum().load(LoadSpec::force("push", "rod").at([f64::NAN; 3])));
    assert!(matches!(e, ModelError::NonFinite { field: "point", .. }));
}

/// A joint's child frame (a standard DH row's Tx(a) Rx(α)) places the child's declared
/// frame in its tree body: the body's inertia, its frame, a frame and a load declared on it,
/// a child joint and a body welded to it are all carried by it, exactly as if they had
/// been declared in the tree body's frame; and a child frame given on a fixed joint composes
/// after the weld's placement.
#[test]
fn a_child_frame_carries_what_is_declared_on_the_child() {
    let quarter_x = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
    let c = Placement::new([0.3, 0.0, 0.0], quarter_x);
    let inertia = Inertia::new(
        2.0,
        [0.1, 0.2, -0.05],
        [[0.03, 0.001, 0.0], [0.001, 0.02, 0.002], [0.0, 0.002, 0.04]],
    );
    let tip = Inertia::new(
        0.5,
        [0.0, 0.0, 0.1],
        [[1e-3, 0.0, 0.0], [0.0, 1e-3, 0.0], [0.0, 0.0, 2e-3]],
    );
    let declared = ModelBuilder::new()
        .body(BodySpec::new("link", inertia.clone()))
        .body(BodySpec::new("tip", tip.clone()))
        .body(BodySpec::new("weight", tip.clone()))
        .joint(
            JointSpec::revolute("j1", GROUND, "link", [0.0, 0.0, 1.0])
                .placed(
                    [0.0, 0.0, 0.4],
                    [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
                )
                .with_child_frame([0.3, 0.0, 0.0], quarter_x),
        )
        .joint(JointSpec::revolute("j2", "link", "tip", [0.0, 0.0, 1.0]).at([0.0, 0.0, 0.2]))
        .joint(JointSpec::fixed("bolt", "link", "weight").at([0.05, 0.0, 0.0]))
        .frame(FrameSpec::new("tool", "link").at([0.0, 0.1, 0.0]))
        .load(LoadSpec::force("push", "link").at([0.0, 0.0, 0.1]))
        .build()
        .expect("valid");
    let by_hand = ModelBuilder::new()
        .body(BodySpec::new("link", inertia.transformed(&c)))
        .body(BodySpec::new("tip", tip.clone()))
        .joint(
            JointSpec::revolute("j1", GROUND, "link", [0.0, 0.0, 1.0]).placed(
                [0.0, 0.0, 0.4],
                [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
            ),
        )
        .joint({
            let p = c.compose(&Placement::translation([0.0, 0.0, 0.2]));
            let rows = std::array::from_fn(|i| std::array::from_fn(|j| p.rotation[(i, j)]));
            JointSpec::revolute("j2", "link", "tip", [0.0, 0.0, 1.0])
                .placed(p.translation.into(), rows)
        })
        .build()
        .expect("valid");
    for (a, b) in declared.bodies().iter().zip(by_hand.bodies()) {
        assert!(
            (a.joint.placement_in_parent.rotation - b.joint.placement_in_parent.rotation).norm()
                < 1e-15
        );
        assert!(
            (a.joint.placement_in_parent.translation - b.joint.placement_in_parent.translation)
                .norm()
                < 1e-15
        );
    }
    // The link's own inertia with the weight's, welded at c · (0.05, 0, 0).
    let weight = tip.transformed(&c.compose(&Placement::translation([0.05, 0.0, 0.0])));
    let link = &declared.bodies()[0].inertia;
    let expected = inertia.transformed(&c).combined(&weight);
    assert!((link.mass - expected.mass).abs() < 1e-15);
    assert!((link.com_in_body - expected.com_in_body).norm() < 1e-15);
    assert!((link.inertia_com_in_body - expected.inertia_com_in_body).norm() < 1e-15);
    // The body's own frame is its declared frame, C in the tree body.
    let frame = declared.frame("link").expect("link");
    assert_eq!((frame.body, &frame.placement_in_body), (Some(0), &c));
    let tool = declared.frame("tool").expect("tool");
    assert_eq!(
        tool.placement_in_body,
        c.compose(&Placement::translation([0.0, 0.1, 0.0]))
    );
    let push = &declared.loads()[0];
    assert_eq!(
        push.placement_in_body,
        c.compose(&Placement::translation([0.0, 0.0, 0.1]))
    );
    // On a fixed joint, the child's frame is composed after the weld's placement.
    let welded = ModelBuilder::new()
        .body(BodySpec::new("link", inertia.clone()))
        .body(BodySpec::new("weight", tip.clone()))
        .joint(JointSpec::revolute("j1", GROUND, "link", [0.0, 0.0, 1.0]))
        .joint(
            JointSpec::fixed("bolt", "link", "weight")
                .at([0.05, 0.0, 0.0])
                .with_child_frame([0.3, 0.0, 0.0], quarter_x),
        )
        .build()
        .expect("valid");
    let weight = welded.frame("weight").expect("weight");
    assert_eq!(
        weight.placement_in_body,
        Placement::translation([0.05, 0.0, 0.0]).compose(&c)
    );
}

/// A child frame's rotation is checked as the joint's own.
#[test]
fn a_child_frame_rotation_is_proper() {
    let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    let (e, _) = only_error(
        ModelBuilder::new().body(rod("rod")).joint(
            JointSpec::revolute("pivot", GROUND, "rod", [0.0, 0.0, 1.0])
                .with_child_frame([0.0; 3], mirror),
        ),
    );
    assert_eq!(
        e,
        ModelError::RotationImproper {
            joint: "pivot".into(),
            determinant: -1.0
        }
    );
}
